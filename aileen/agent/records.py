"""The agent's records: its answer to a lesson, and its parameters."""

from __future__ import annotations

from dataclasses import dataclass, field

from aileen.analogy.sage import SageParams

# SAGE's assimilation threshold for the agent's relation concepts: an example joins a
# generalization only when SME's similarity to it reaches this; otherwise it stays apart (a
# disjunct). Measured (benchmarks/assimilation.py, 3 wide spatial trials, ground-truth vision):
# two examples of a relation word in different CDC sectors score 0.48-0.60 (they share `dc`
# alone), in the same sector 0.80-1.0; 0.7 lies between. (Without mutual exclusivity the two
# overlap, 0.44-0.69 against 0.66-0.87: the objects' percepts swamp the direction.) Visual words
# cannot share a threshold with relations: "cone" taught as "green cone" and then "large blue
# cone" gives two examples at 0.50 that must merge (lessons/visual.toml). Visual and action
# concepts keep the paper's 0.01 (merge anything that shares a fact).
DISJUNCTIVE_ASSIMILATION = 0.7
PAPER_ASSIMILATION = 0.01

@dataclass
class Answer:
    """What the agent says back to the trainer for one lesson."""

    signal: str
    content: str
    result: str  # "success" | "failure"
    reason: str | None = None
    referents: dict[str, list[str]] = field(default_factory=dict)
    created: list[str] = field(default_factory=list)
    stored: list[str] = field(default_factory=list)
    steps: list[str] = field(default_factory=list)
    projections: int = 0
    goal_holds: bool | None = None
    # Per recognised fact about the referents (`isa(o1,r_red)`): how typical an instance it is,
    # in [0, 1] (memory/quality.py).
    typicality: dict[str, float] = field(default_factory=dict)

    @property
    def commands(self) -> int:
        """create + store commands sent to the concept memory (the paper's bar chart)."""
        return len(self.created) + len(self.stored)

    @property
    def ok(self) -> bool:
        return self.result == "success"


@dataclass(frozen=True)
class AgentParams:
    mutual_exclusivity: bool = True  # leave out of an example what known words already explain
    # Learn which perceptual channel (shape, colour) each position in a noun phrase names
    # (head noun, modifier) from the words already pinned down, and read new words by it.
    syntactic_bootstrapping: bool = True
    # Keep examples that are too unlike every generalization apart (a concept may hold several
    # generalizations, and a query succeeds when any of them matches): SAGE's disjunctions.
    disjunctive_concepts: bool = True
    # One action concept per verb (`r_move`) whose outcome is a slot the sentence's relation
    # fills, and whose traces say who moved (agent/verbs.py). Off: the paper's one concept
    # per verb and relation (`r_move_left_of`), with the relation checked at the end.
    one_verb: bool = True
    # Active learning also stores when comprehension succeeds only weakly: a recognised fact
    # whose match similarity lies within this margin of the match threshold (0: never).
    weak_margin: float = 0.05
    max_react_projections: int = 6
    plan_depth: int = 6
    seed: int = 0  # region sampling


    def sage(self) -> SageParams:
        """The concept memory's parameters for a fresh memory of this agent."""
        if not self.disjunctive_concepts:
            return SageParams(assimilation=PAPER_ASSIMILATION)
        return SageParams(assimilation=PAPER_ASSIMILATION, assimilation_by_kind=(("spatial", DISJUNCTIVE_ASSIMILATION),))
