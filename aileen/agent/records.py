"""The agent's records: its answer to a lesson, and its parameters."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

from aileen.analogy.sage import SageParams
from aileen.domain import calculi
from aileen.errors import UserError

PAPER_ASSIMILATION = 0.01  # SAGE's threshold (the paper's Table 2)
#: `Answer.result` of a sentence the agent could not read: neither "success" nor "failure".
NOT_UNDERSTOOD = "not understood"
# How an answer begins to say that no action was done where one was asked about or taught
# (the console reads it to say how a verb of one's own is shown)
NOTHING_DONE = "nothing was done"


@dataclass
class Answer:
    """What the agent says back to the trainer for one lesson."""

    signal: str
    content: str
    result: str  # "success" | "failure" | NOT_UNDERSTOOD
    reason: str | None = None
    referents: dict[str, list[str]] = field(default_factory=dict)
    created: list[str] = field(default_factory=list)
    stored: list[str] = field(default_factory=list)
    steps: list[str] = field(default_factory=list)
    projections: int = 0
    goal_holds: bool | None = None
    said: str | None = None  # generate: the sentence the agent said
    # Per recognised fact about the referents (`isa(o1,r_red)`): how typical an instance it is,
    # in [0, 1] (memory/quality.py).
    typicality: dict[str, float] = field(default_factory=dict)
    # False when the agent could not read the sentence (`result` is NOT_UNDERSTOOD, `reason`
    # says what it could not read and what it expected): never an answer "no", never graded,
    # and nothing is learned from it.
    understood: bool = True
    # What the agent asks back instead of answering ("did you mean 'box'?"): a word it does not
    # know one edit from one it does, and the word said (`asked_about`: "bx", "nleft of"). The
    # trainer may answer "no, as said" (`Agent.take_as_said`); a lesson file's trainer does for
    # a word its lessons say more than once, else it skips the lesson.
    question: str | None = None
    asked_about: str | None = None
    # The sentence's words the agent does not know (its concepts' symbols): a "no" for that
    # reason is not an answer that the sentence is false (a lesson file's run grades it wrong,
    # `LessonResult.correct`: an untaught word's "no" was graded right).
    unknown_words: list[str] = field(default_factory=list)

    @property
    def commands(self) -> int:
        """create + store commands sent to the concept memory (the paper's bar chart)."""
        return len(self.created) + len(self.stored)

    @property
    def ok(self) -> bool:
        return self.result == "success"

    def add_reason(self, why: str) -> None:
        """Say `why` beside what the answer says already (once)."""
        if why not in (self.reason or "").split("; "):
            self.reason = f"{self.reason}; {why}" if self.reason else why


def not_understood(signal: str, content: str, why: str, *, question: str | None = None,
                   asked_about: str | None = None) -> Answer:
    """The answer to a sentence the agent cannot read (or asks about): what it could not read,
    in the teacher's words; no "yes", no "no", nothing learned."""
    return Answer(signal, content, NOT_UNDERSTOOD, why, understood=False, question=question, asked_about=asked_about)


@dataclass(frozen=True)
class AgentParams:
    mutual_exclusivity: bool = True  # leave out of an example what known words already explain
    # Learn which perceptual channel (shape, colour) each position in a noun phrase names
    # (head noun, modifier) from the words already pinned down, and read new words by it.
    syntactic_bootstrapping: bool = True
    # A relation concept may hold several generalizations (a query succeeds when any of them
    # matches): SAGE keeps an example apart when merging it would leave the concept with no
    # meaning (agent/disjunction.py). Off: the paper's merge of anything that shares a fact.
    disjunctive_concepts: bool = True
    # One action concept per verb (`r_move`) whose outcome is a slot the sentence's relation
    # fills, and whose traces say who moved (agent/verbs.py). Off: the paper's one concept
    # per verb and relation (`r_move_left_of`), with the relation checked at the end.
    one_verb: bool = True
    # With one verb: where a demonstration's mover started relative to the reference (the
    # relations the move changed) is recorded as "not yet the relation named" (agent/verbs.py),
    # so it is no part of the verb. Off: the start state as seen.
    start_contrast: bool = True
    # The agent's sense of direction (`calculi.DIRECTIONS`): "cones" (four 90-degree cones around
    # the axes), "sectors" (the paper's 8 CDC sectors) or "all" (every grain at once, the word's
    # grain learned from its examples by the size principle: memory/extent.py).
    senses_of_direction: str = calculi.AGENT_DIRECTIONS
    # With several grains: a relation word's direction is the region its examples support,
    # smaller regions preferred as examples accumulate (memory/extent.py). Off: every grain's
    # facts go to SME and SAGE as they are.
    size_principle: bool = True
    # With the size principle: a teacher's near miss lies near the word's edge (pedagogical
    # sampling, memory/extent.py), so it says where the edge is. Off: a near miss only rules
    # out the regions that hold it.
    near_miss_edges: bool = True
    # With every grain of direction: distance perceived in bands too (`calculi.FINER`), a
    # word's distance learned as a region where distance is what it says (memory/reach.py).
    # Off: the coarse grain of distance alone (close, far), as before.
    distance_bands: bool = True
    # With the bands: distance measured two ways, qdist's gap and the gap of discs
    # (`calculi.DGAP`: the same on every side), a word's examples picking the measure
    # (memory/reach.py). Off: qdist's measure alone, as before.
    disc_gap: bool = True
    # In a lesson whose answer the trainer grades (`feedback = "wrong"`), a "no" to a relation
    # sentence the trainer lets stand is a near miss of the relation word (agent/feedback.py).
    answers_let_stand: bool = True
    # Active learning also stores when comprehension succeeds only weakly: a recognised fact
    # whose match similarity lies within this margin of the match threshold (0: never).
    weak_margin: float = 0.05
    # The switch for that store (`--without weak-comprehension`): off, only what failed is
    # learned from, as the paper's learner does.
    weak_comprehension: bool = True
    # Object permanence: an object another one hides (put on it, or seen resting on it) stays
    # in the agent's state under it while the upper one stays where it was (agent/state.py,
    # `Tracker`). Off: the agent knows only what it sees in each frame.
    object_permanence: bool = True
    max_react_projections: int = 6
    plan_depth: int = 6
    seed: int = 0  # region sampling

    @property
    def directions(self) -> str:
        """The agent's direction sense, a key of `calculi.DIRECTIONS`."""
        return self.senses_of_direction

    @property
    def extents(self) -> bool:
        """Are relation words' directions learned as regions (several grains, size principle)?"""
        return self.size_principle and len(calculi.DIRECTIONS[self.senses_of_direction]) > 1

    def senses(self) -> tuple[calculi.Calculus, ...]:
        """The calculi this agent perceives."""
        out = calculi.senses(self.directions, finer=self.distance_bands)
        return out if self.disc_gap else tuple(c for c in out if c is not calculi.DGAP)

    def sage(self) -> SageParams:
        """The concept memory's parameters for a fresh memory of this agent."""
        return SageParams(assimilation=PAPER_ASSIMILATION)


# The mechanisms `--without` can switch off (ablations, in `aileen run`, `aileen teach` and
# `aileen experiment`): name -> `AgentParams` field.
ABLATIONS: dict[str, str] = {
    "mutual-exclusivity": "mutual_exclusivity",
    "syntactic-bootstrapping": "syntactic_bootstrapping",
    "disjunctive-concepts": "disjunctive_concepts",
    "one-verb": "one_verb",
    "start-contrast": "start_contrast",
    "size-principle": "size_principle",
    "near-miss-edges": "near_miss_edges",
    "distance-bands": "distance_bands",
    "disc-gap": "disc_gap",
    "answers-let-stand": "answers_let_stand",
    # the paper's 8 sectors instead of the default sense (kept for `--without cones` scripts;
    # `--senses sectors` says the same)
    "cones": "senses_of_direction",
    "weak-comprehension": "weak_comprehension",
    "object-permanence": "object_permanence",
}
SENSES: tuple[str, ...] = tuple(calculi.DIRECTIONS)


def ablation_params(without: Sequence[str], senses: str | None = None) -> dict[str, object]:
    """`AgentParams` fields for the mechanisms `--without` switches off (a UserError names an
    unknown one) and the sense of direction `--senses` chooses."""
    unknown = [w for w in without if w not in ABLATIONS]
    if unknown:
        raise UserError(f"unknown mechanism {unknown[0]!r} for --without; expected one of {', '.join(ABLATIONS)}")
    if senses is not None and senses not in SENSES:
        raise UserError(f"unknown sense {senses!r} for --senses; expected one of {', '.join(SENSES)}")
    out: dict[str, object] = {ABLATIONS[w]: False for w in without if w != "cones"}
    if "cones" in without:
        out["senses_of_direction"] = "sectors"
    if senses is not None:
        out["senses_of_direction"] = senses
    return out


def ablated(without: Sequence[str] = (), senses: str | None = None, *, seed: int = 0) -> "AgentParams":
    """The agent's parameters with `--without`'s mechanisms off and `--senses`'s sense of
    direction (`ablation_params`), and its seed: the one place a run, a learning curve and the
    react benchmark make them."""
    return AgentParams(seed=seed, **ablation_params(without, senses))  # type: ignore[arg-type]
