"""The agent: perceive, comprehend, learn, act.

One `Agent` holds the state that persists across lessons (semantic, episodic and concept
memories) and answers the three signals of the paper's curriculum of guided participation:

- `inform`: comprehend with what is known; learn only on failure (active learning): create a
  concept for each unknown word and store an example built from the scene (a visual word:
  the referent's facts; a relation: both objects and the relations between them; an action:
  the demonstration trace).
- `verify`: success or failure, with the grounded referents or the reason.
- `react`: project the next desired state from the action concept, plan it, act, perceive,
  and repeat until the projection says the action is complete.

Everything the agent knows about the table comes through `look()` (an image) and its own
actions; the simulator's ground truth never reaches it.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from aileen.errors import UserError
from aileen.memory.claims import exclusive
from aileen.memory.concept import ConceptMemory
from aileen.memory.episodic import EpisodicMemory
from aileen.memory.semantic import SemanticMemory
from aileen.perception.factindex import FactIndex
from aileen.perception.qsr import qsr_facts
from aileen.perception.regions import sample_region
from aileen.reasoning import comprehension, language, planner
from aileen.terms import Term, fn
from aileen.world.camera import DEFAULT_CAMERA, Camera

if TYPE_CHECKING:
    from aileen.body import WorldBody

Box = tuple[float, float, float, float]
Detection = tuple[str, str, Box, Box]  # shape percept, colour percept, box in metres, box in pixels
Perceiver = Callable[[np.ndarray], list[Detection]]


# --------------------------------------------------------------------------- records

@dataclass(frozen=True)
class Seen:
    """An object as the agent knows it: its own id, percepts and where it was last seen."""

    id: str
    shape: str  # percept symbol, e.g. cv_box
    colour: str  # percept symbol, e.g. cv_red
    box_m: Box
    box_px: Box

    @property
    def centre(self) -> tuple[float, float]:
        x0, y0, x1, y1 = self.box_m
        return (x0 + x1) / 2, (y0 + y1) / 2

    @property
    def footprint(self) -> float:
        x0, y0, x1, y1 = self.box_m
        return max(x1 - x0, y1 - y0)


@dataclass
class State:
    """The perceived state: visible objects by agent id, and its facts (percepts, QSRs, held)."""

    objects: dict[str, Seen]
    held: str | None
    facts: list[Term]
    _index: FactIndex | None = field(default=None, init=False, repr=False, compare=False)

    def _facts_index(self) -> FactIndex:
        """The facts by object and pair, built once per state (rebuilt if facts were added)."""
        if self._index is None or self._index.size != len(self.facts):
            self._index = FactIndex(self.facts)
        return self._index

    def percepts(self, obj: str) -> list[Term]:
        return self._facts_index().percepts(obj)

    def relations(self, a: str, b: str) -> list[Term]:
        """QSR facts between a and b, both directions."""
        return self._facts_index().relations(a, b)


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
    max_react_projections: int = 6
    plan_depth: int = 6
    seed: int = 0  # region sampling


@dataclass
class _Grounding:
    """Comprehension plus the concept-memory evidence that fed it."""

    parse: language.Parse
    result: comprehension.Comprehension
    unknown: list[str]


# --------------------------------------------------------------------------- tracker

class Tracker:
    """Keeps agent ids stable across frames: a detection takes the id of the nearest
    previously seen object with the same percepts (objects do not change colour or shape),
    so an object keeps its id while it is held out of view and after it is placed."""

    def __init__(self) -> None:
        self.known: dict[str, Seen] = {}
        self._next = 1

    def reset(self) -> None:
        self.known.clear()
        self._next = 1

    def assign(self, detections: Sequence[tuple[str, str, Box, Box]]) -> list[str]:
        pairs = []
        for i, (shape, colour, box_m, _) in enumerate(detections):
            cx, cy = (box_m[0] + box_m[2]) / 2, (box_m[1] + box_m[3]) / 2
            for oid, s in self.known.items():
                if s.shape == shape and s.colour == colour:
                    sx, sy = s.centre
                    pairs.append((math.hypot(cx - sx, cy - sy), i, oid))
        pairs.sort()
        ids: list[str | None] = [None] * len(detections)
        used: set[str] = set()
        for _, i, oid in pairs:
            if ids[i] is None and oid not in used:
                ids[i] = oid
                used.add(oid)
        for i in range(len(detections)):
            if ids[i] is None:
                while f"o{self._next}" in self.known:
                    self._next += 1
                ids[i] = f"o{self._next}"
                self._next += 1
        for i, (shape, colour, box_m, box_px) in enumerate(detections):
            self.known[ids[i]] = Seen(ids[i], shape, colour, box_m, box_px)  # type: ignore[index]
        return ids  # type: ignore[return-value]


# --------------------------------------------------------------------------- agent

class Agent:
    def __init__(
        self,
        memory: ConceptMemory | None = None,
        semantic: SemanticMemory | None = None,
        *,
        params: AgentParams = AgentParams(),
        camera: Camera = DEFAULT_CAMERA,
        rules: str | None = None,
        perceiver: Perceiver | None = None,
    ) -> None:
        self.memory = memory if memory is not None else ConceptMemory()
        self.semantic = semantic if semantic is not None else SemanticMemory()
        self.episodic = EpisodicMemory()
        self.params = params
        self.camera = camera
        self.rules = rules
        self.tracker = Tracker()
        self._perceiver = perceiver if perceiver is not None else _vision(camera)
        self.state: State | None = None
        self.held: str | None = None
        self._rng = np.random.default_rng(params.seed)
        # Which channel of the visual module each percept symbol belongs to: the agent knows
        # its own senses (the detector's classes, the colour module's presets).
        self.channels: dict[Term, str] = sense_channels()
        # Where each taught word has stood in multi-word noun phrases (learned).
        self.positions: dict[str, set[str]] = {}
        self._load_lexicon()
        # Caches of meaning() (and "<effective>": the effective meanings); cleared on store.
        self._meanings: dict[str, frozenset[Term]] = {}

    # ------------------------------------------------------------------ persistence
    def save(self, path: str) -> None:
        """Save what was learned: the concept memory, with the lexicon (word positions,
        percept channels) in its annotations; the semantic memory is rebuilt from it."""
        self._sync_lexicon()
        self.memory.save(path)

    def _sync_lexicon(self) -> None:
        """Keep the lexicon in the concept memory's annotations, so an agent built on the
        same memory (a copy, a worker process, a saved file) reads words the same way."""
        self.memory.annotations["lexicon"] = {
            "positions": {w: sorted(p) for w, p in sorted(self.positions.items())},
        }

    def _load_lexicon(self) -> None:
        lex = self.memory.annotations.get("lexicon")
        if not isinstance(lex, dict):
            return
        for w, ps in dict(lex.get("positions", {})).items():
            self.positions[str(w)] = {str(p) for p in ps if p in ("head", "modifier")}

    # ------------------------------------------------------------------ perceiving
    def new_scene(self) -> None:
        """The trainer set up a new scene: forget object identities from the last one."""
        self.tracker.reset()
        self.held = None
        self.state = None

    def perceive(self, image: np.ndarray, action: Term | None = None) -> State:
        """Look at an image, keep object ids stable, derive facts, record the episode."""
        ids = self.tracker.assign(self._perceiver(image))
        objects = {i: self.tracker.known[i] for i in ids}
        facts: list[Term] = []
        for i in sorted(objects, key=_id_order):
            facts.append(fn("isa", i, objects[i].shape))
            facts.append(fn("isa", i, objects[i].colour))
        facts.extend(qsr_facts({i: objects[i].box_m for i in objects}))
        if self.held in objects:
            self.held = None  # back on the table
        if self.held is not None:
            facts.append(fn("held", self.held))
        self.state = State(objects, self.held, facts)
        self.episodic.record(facts, action)
        return self.state

    def describe_scene(self) -> list[str]:
        """What the agent sees now, one line per object: `o1 cv_red cv_box at (0.42, 0.55)`."""
        if self.state is None:
            return []
        out = []
        for oid in sorted(self.state.objects, key=_id_order):
            s = self.state.objects[oid]
            x, y = s.centre
            out.append(f"{oid} {s.colour} {s.shape} at ({x:.2f}, {y:.2f})")
        return out

    def locate(self, u: float, v: float) -> str:
        """The agent id of the object seen at pixel (u, v) (where the trainer points)."""
        assert self.state is not None
        best, best_d = None, float("inf")
        for s in self.state.objects.values():
            u0, v0, u1, v1 = s.box_px
            if u0 - 1 <= u <= u1 + 1 and v0 - 1 <= v <= v1 + 1:
                d = ((u0 + u1) / 2 - u) ** 2 + ((v0 + v1) / 2 - v) ** 2
                if d < best_d:
                    best, best_d = s.id, d
        if best is None:
            raise LookupError(f"no object seen at pixel ({u:.0f}, {v:.0f})")
        return best

    # ------------------------------------------------------------------ comprehension
    def _concept_facts(self, p: language.Parse, state: State, demo_start: int | None) -> list[Term]:
        """Ask the concept memory which known concepts of the sentence hold in the scene.

        Each candidate object (or ordered pair) is queried alone with its own facts, so other
        objects on the table neither dilute the match nor lend it spurious support."""
        inferred: list[Term] = []
        objs = sorted(state.objects, key=_id_order)
        unary: dict[str, list[str]] = {}
        for ref in p.objects:
            cands = objs
            for word in ref.words:
                c = self.semantic.concept(word)
                if c is None or self.semantic.kind(c) != "visual":
                    continue
                holds = [o for o in cands if self._holds_unary(c, o, state)]
                inferred.extend(fn("isa", o, c) for o in holds)
                cands = holds
            unary[ref.id] = cands
        if p.relation is not None:
            c = self.semantic.concept(p.relation.word)
            if c is not None:
                r1, r2 = unary.get(p.relation.arg1, objs), unary.get(p.relation.arg2, objs)
                for a in r1:
                    for b in r2:
                        if a != b and self._holds_binary(c, a, b, state):
                            inferred.append(fn(c, a, b))
        if p.action is not None and demo_start is not None:
            inferred += self._action_facts(p, unary, demo_start)
        return inferred

    def _holds_unary(self, concept: str, obj: str, state: State) -> bool:
        facts = state.percepts(obj)
        ignore = self._claimed_by_others(concept) if self.params.mutual_exclusivity else ()
        return bool(self.memory.query(facts, fn("isa", obj, concept), ignore=ignore))

    def _claimed_by_others(self, concept: str) -> frozenset[Term]:
        """Mutual exclusivity at query time: percepts that other visual words already stand
        for. After "green cone" (both words new) and then "red cone", `cone` means `cv_cone`
        alone, so `green` stops requiring `cv_cone`: it was the cone's."""
        return self.meaning(concept) - self._effective_meanings().get(concept, frozenset())

    def _effective_meanings(self) -> dict[str, frozenset[Term]]:
        """Each visual concept's meaning once the percepts that other words stand for are
        taken out, repeated until nothing changes so that a word pinned down frees the words
        it was taught with (cylinder pinned -> purple; then purple pinned -> ...). A word
        only gives up percepts that a strictly smaller meaning claims, and never all of them."""
        eff = self._meanings.get("<effective>")
        if eff is not None:
            return eff  # type: ignore[return-value]
        m = _exclusive({c: self.meaning(c) for c in self._visual_concepts()})
        if self.params.syntactic_bootstrapping:
            by_position = self._position_channels(m)
            if by_position:
                narrowed = {}
                for c, mine in m.items():
                    word = self.semantic.word(c)
                    chans = {by_position.get(p) for p in self.positions.get(word or "", ())}
                    keep = frozenset(t for t in mine if self.channels.get(t) in chans)
                    narrowed[c] = keep if keep and None not in chans else mine
                m = _exclusive(narrowed)
        self._meanings["<effective>"] = m  # type: ignore[assignment]
        return m

    def _position_channels(self, meanings: dict[str, frozenset[Term]]) -> dict[str, str]:
        """Syntactic bootstrapping: which channel each noun-phrase position names, learned
        from the words already pinned to one percept (a word seen as a modifier that means
        `cv_red` is evidence that modifiers name colours). A position whose evidence
        disagrees names no channel."""
        evidence: dict[str, set[str]] = {}
        for c, mine in meanings.items():
            word = self.semantic.word(c)
            if len(mine) != 1 or word is None:
                continue
            (only,) = mine
            chan = self.channels.get(only)
            if chan is None:
                continue
            for pos in self.positions.get(word, ()):
                evidence.setdefault(pos, set()).add(chan)
        return {pos: next(iter(ch)) for pos, ch in evidence.items() if len(ch) == 1}

    def _note_positions(self, p: language.Parse) -> None:
        """Remember where each word stood: the last word of a noun phrase is its head."""
        for ref in p.objects:
            if len(ref.words) < 2:
                continue
            for i, w in enumerate(ref.words):
                pos = "head" if i == len(ref.words) - 1 else "modifier"
                seen = self.positions.setdefault(w, set())
                if pos not in seen:
                    seen.add(pos)
                    self._meanings.pop("<effective>", None)
                    self._sync_lexicon()

    def _visual_concepts(self) -> list[str]:
        return [c.symbol for c in self.memory.concepts() if c.kind == "visual"]

    def _holds_binary(self, concept: str, a: str, b: str, state: State) -> bool:
        facts = state.percepts(a) + state.percepts(b) + state.relations(a, b)
        return bool(self.memory.query(facts, fn(concept, a, b)))

    # ------------------------------------------------------------------ referents for learning
    def _candidates(self, g: _Grounding, inferred: Iterable[Term]) -> dict[str, list[str]]:
        """Which objects each reference may mean, by the words already known (unknown words
        do not constrain), then by mutual exclusivity: two references of one sentence do not
        mean the same object, so a reference pinned to one object frees it from the others."""
        assert self.state is not None
        holds: dict[str, set[str]] = {}
        for f in inferred:
            if f.name == "isa":
                holds.setdefault(str(f.args[1]), set()).add(str(f.args[0]))
        objs = sorted(self.state.objects, key=_id_order)
        cands: dict[str, list[str]] = {}
        for ref in g.parse.objects:
            cs = objs
            for w in ref.words:
                c = self.semantic.concept(w)
                if c is not None and self.semantic.kind(c) == "visual":
                    cs = [o for o in cs if o in holds.get(c, set())] or cs
            cands[ref.id] = list(cs)
        changed = True
        while changed:
            changed = False
            for rid, cs in cands.items():
                if len(cs) == 1:
                    for other, ocs in cands.items():
                        if other != rid and cs[0] in ocs and len(ocs) > 1:
                            ocs.remove(cs[0])
                            changed = True
        return cands

    def meaning(self, concept: str) -> frozenset[Term]:
        """The percept symbols a visual concept requires (its generalization's significant
        `isa` facts), for mutual exclusivity."""
        m = self._meanings.get(concept)
        if m is None:
            m = self._meanings[concept] = frozenset(
                f.args[1]
                for f in self.memory.significant_facts(concept)
                if f.name == "isa" and len(f.args) == 2 and str(f.args[1]) != concept
            )
        return m

    def _explained(self, obj: str, words: Iterable[str], inferred: set[Term]) -> set[Term]:
        """Percept facts of `obj` that the (already known, holding) `words` account for."""
        out: set[Term] = set()
        for w in words:
            c = self.semantic.concept(w)
            if c is None or fn("isa", obj, c) not in inferred:
                continue
            out |= {fn("isa", obj, p) for p in self.meaning(c)}
        return out

    # ------------------------------------------------------------------ signals
    def inform(self, content: str, *, demo_start: int | None = None) -> Answer:
        """Comprehend; learn only from what failed. `demo_start` is the episode index where
        a demonstration began (for action lessons: the trace runs from there to now)."""
        assert self.state is not None, "perceive before a lesson"
        g, inferred = self._understand(content, demo_start)
        answer = self._answer("inform", content, g, inferred, demo_start)
        self._note_positions(g.parse)  # part of the lesson: where the trainer put each word
        if answer.ok:
            return answer
        state = self.state
        inferred_set = set(inferred)
        known_before = {w for w in g.parse.words if self.semantic.concept(w) is not None}
        cands = self._candidates(g, inferred)
        referent: dict[str, str] = {}
        for ref in g.parse.objects:
            cs = cands[ref.id]
            if len(cs) != 1:
                why = f"cannot tell which object is '{ref.text}'"
                answer.reason = f"{answer.reason}; {why}" if answer.reason else why
                continue
            obj = referent[ref.id] = cs[0]
            for w in ref.words:
                c = self.semantic.concept(w)
                if c is not None and fn("isa", obj, c) in inferred_set:
                    continue  # known and it holds: nothing to learn
                others = [x for x in ref.words if x != w and x in known_before]
                drop = self._explained(obj, others, inferred_set) if self.params.mutual_exclusivity else set()
                percepts = [f for f in state.percepts(obj) if f not in drop] or state.percepts(obj)
                self._learn(answer, w, "visual", percepts, lambda c, o=obj: fn("isa", o, c))
        rel, act = g.parse.relation, g.parse.action
        if rel is not None and rel.arg1 in referent and rel.arg2 in referent:
            a, b = referent[rel.arg1], referent[rel.arg2]
            c = self.semantic.concept(rel.word)
            if c is None or fn(c, a, b) not in inferred_set:
                facts = self._objects_facts([(a, rel.arg1), (b, rel.arg2)], g, known_before, inferred_set)
                facts += state.relations(a, b)
                self._learn(answer, rel.word, "spatial", facts, lambda c, a=a, b=b: fn(c, a, b))
        if act is not None and act.arg1 in referent and act.arg2 in referent and demo_start is not None:
            a, b = referent[act.arg1], referent[act.arg2]
            c = self.semantic.concept(act.word)
            if c is None or fn(c, a, b) not in inferred_set:
                facts = self.episodic.trace(demo_start, [Term(a), Term(b)])
                facts += self._objects_facts([(a, act.arg1), (b, act.arg2)], g, known_before, inferred_set)
                self._learn(answer, act.word, "action", facts, lambda c, a=a, b=b: fn(c, a, b))
        return answer

    def _objects_facts(self, objs: list[tuple[str, str]], g: _Grounding, known: set[str],
                       inferred: set[Term]) -> list[Term]:
        """Percepts of the objects a relation or action is about, leaving out (mutual
        exclusivity) what the known words naming those objects already account for."""
        assert self.state is not None
        out: list[Term] = []
        for obj, ref_id in objs:
            words = [w for w in g.parse.object(ref_id).words if w in known]
            drop = self._explained(obj, words, inferred) if self.params.mutual_exclusivity else set()
            out += [f for f in self.state.percepts(obj) if f not in drop]
        return out

    def _learn(self, answer: Answer, word: str, kind: str, facts: list[Term],
               member: Callable[[str], Term]) -> None:
        """`create` the word's concept if it is new, then `store` the example: `facts` plus
        the membership fact `member(concept)` (`isa(o1,r_red)`, `r_left_of(o1,o2)`)."""
        concept = self.semantic.concept(word) or self.semantic.add(word, kind)
        if not self.memory.has(concept):
            self.memory.create(concept, kind)
            answer.created.append(concept)
        self.memory.store(facts + [member(concept)], concept)
        # Only this concept's meaning changed; the exclusivity pass is redone from the others'.
        self._meanings.pop(concept, None)
        self._meanings.pop("<effective>", None)
        answer.stored.append(concept)

    def verify(self, content: str, *, demo_start: int | None = None) -> Answer:
        """Does what the content says hold in the scene (or the demonstration just seen)?"""
        assert self.state is not None, "perceive before a lesson"
        g, inferred = self._understand(content, demo_start)
        return self._answer("verify", content, g, inferred, demo_start)

    # ------------------------------------------------------------------ shared helpers
    def comprehend(self, content: str, *, demo_start: int | None = None) -> comprehension.Comprehension:
        """Indexical comprehension of `content` in the current scene (and demonstration)."""
        return self._understand(content, demo_start)[0].result

    def _understand(self, content: str, demo_start: int | None) -> tuple[_Grounding, list[Term]]:
        assert self.state is not None, "perceive before comprehending"
        p = language.parse(content)
        inferred = self._concept_facts(p, self.state, demo_start)
        words = self.semantic.words()
        result = comprehension.comprehend(p, words=words, facts=self.state.facts, inferred=inferred, rules=self.rules)
        unknown = [w for w in p.words if w not in words]
        return _Grounding(p, result, unknown), inferred

    def _action_facts(self, p: language.Parse, unary: dict[str, list[str]], demo_start: int) -> list[Term]:
        """Which (mover, reference) pairs the demonstration since `demo_start` shows the action
        for. The action concept must match the trace, and, since the sentence also says
        where the mover ends up ("move X right of Y" ends with X right of Y), the relation's
        own concept must hold at the end when it is known: meaning composes."""
        assert self.state is not None and p.action is not None
        c = self.semantic.concept(p.action.word)
        if c is None:
            return []
        rel_c = self.semantic.concept(p.action.relation)
        objs = sorted(self.state.objects, key=_id_order)
        out = []
        for a in unary.get(p.action.arg1, objs):
            for b in unary.get(p.action.arg2, objs):
                if a == b:
                    continue
                trace = self.episodic.trace(demo_start, [Term(a), Term(b)])
                if not self.memory.query(trace, fn(c, a, b)):
                    continue
                if rel_c is not None and not self._holds_binary(rel_c, a, b, self.state):
                    continue
                out.append(fn(c, a, b))
        return out

    def _answer(self, signal: str, content: str, g: _Grounding, inferred: list[Term],
                demo_start: int | None) -> Answer:
        r = g.result
        referents = {g.parse.object(k).text: [str(o) for o in v] for k, v in r.referents.items()}
        # Two red boxes on the table do not make "red box" false: only acting on one needs
        # it to be unique.
        failures = [f for f in r.failures if f.reason != "ambiguous" or signal == "react"]
        reasons = [_reason_text(f.reason, f.subject, g.parse) for f in failures]
        if g.parse.action is not None and not failures and demo_start is not None:
            if not any(f.name == self.semantic.concept(g.parse.action.word) for f in inferred):
                reasons.append(f"the demonstration is not '{g.parse.action.word.replace('_', ' ')}'")
        result = "failure" if reasons else "success"
        return Answer(signal, content, result, "; ".join(reasons) or None, referents)

    # ------------------------------------------------------------------ acting
    def react(self, content: str, body: "WorldBody") -> Answer:
        """Carry out an action sentence in the world: project the next desired state from the
        action concept, plan it, act, look again; until the projection says it is complete."""
        self.perceive(body.look())
        g, inferred = self._understand(content, None)
        answer = self._answer("react", content, g, inferred, None)
        goal = g.result.goal
        if not answer.ok:
            return answer
        if goal is None:
            answer.result, answer.reason = "failure", "the sentence asks for no action"
            return answer
        a, b, concept = str(goal.arg1), str(goal.arg2), str(goal.concept)
        start = self.episodic.now
        final: list[Term] = []
        try:
            for _ in range(self.params.max_react_projections):
                # The trace names the action's arguments (`r_move_right_of(o1,o2)`), so the
                # mapping cannot swap mover and reference when their start state is symmetric.
                trace = self.episodic.trace(start, [Term(a), Term(b)], extra=[fn(concept, a, b)])
                proj = self.memory.project(trace, concept)
                answer.projections += 1
                if not proj.facts:
                    raise UserError(f"the concept memory projects no next state for '{content}'")
                final = list(proj.facts)
                assert self.state is not None
                plan = planner.plan(self.state.facts, final, max_depth=self.params.plan_depth, rules=self.rules)
                for step in plan.steps:
                    self._execute(step, body)
                    answer.steps.append(_step_text(step))
                if proj.complete:
                    break
            else:
                raise UserError(f"the action was not complete after {self.params.max_react_projections} projections")
        except UserError as exc:
            answer.result, answer.reason = "failure", exc.message
            return answer
        assert self.state is not None
        have = set(self.state.facts)
        answer.goal_holds = all(f in have for f in final)
        if not answer.goal_holds:
            missing = ", ".join(str(f) for f in final if f not in have)
            answer.result, answer.reason = "failure", f"after acting, the goal does not hold: {missing}"
        return answer

    def _execute(self, step: "planner.PlanStep", body: "WorldBody") -> None:
        """One primitive action through the body, then look again (and record both)."""
        assert self.state is not None
        action = step.action
        obj = str(action.args[0])
        if action.name in ("point", "pick_up"):
            seen = self.state.objects[obj]
            u0, v0, u1, v1 = seen.box_px
            u, v = (u0 + u1) / 2, (v0 + v1) / 2
            if action.name == "point":
                body.point(u, v)
            else:
                body.pick_up(u, v)
                self.held = obj
        elif action.name == "place":
            seen = self.tracker.known[obj]
            others = {i: s.box_m for i, s in self.state.objects.items() if i != obj}
            x, y = sample_region(
                seen.footprint, list(step.relations), others, self.camera.table, self._rng, subject=obj
            )
            body.place(x, y)
            self.held = None
        else:
            raise ValueError(f"the body cannot do {action}")
        self.perceive(body.look(), action=action)


def sense_channels() -> dict[Term, str]:
    """The percept symbols of each channel of the visual module: shapes from the detector,
    colours from the colour module's presets."""
    from aileen.world.catalog import COLOURS, SHAPES, percept

    return {Term(percept(s)): "shape" for s in SHAPES} | {Term(percept(c)): "colour" for c in COLOURS}


def _exclusive(meanings: dict[str, frozenset[Term]]) -> dict[str, frozenset[Term]]:
    """Mutual exclusivity to a fixpoint: a meaning gives up the percepts of any strictly
    smaller meaning, repeated so that a word pinned down frees the words taught with it, and
    never down to nothing (`claims.exclusive`: linear in the number of concepts)."""
    return exclusive(meanings)


def _vision(camera: Camera) -> Perceiver:
    """The shipped visual module: detector, colour, boxes (loaded on first use)."""

    def see(image: np.ndarray) -> list[Detection]:
        from aileen.perception import perceive
        from aileen.world.catalog import percept

        scene = perceive(image, camera=camera)
        return [(percept(o.shape), percept(o.colour), o.box_m, o.box_px) for o in scene.objects]

    return see


def _id_order(obj_id: str) -> tuple[int, str]:
    digits = obj_id.lstrip("o")
    return (int(digits), obj_id) if digits.isdigit() else (1 << 30, obj_id)


def _step_text(step: "planner.PlanStep") -> str:
    if step.action.name == "place" and step.relations:
        return f"place({step.action.args[0]}) where {', '.join(str(r) for r in step.relations)}"
    return str(step.action)


def _reason_text(reason: str, subject: Term, parse: language.Parse) -> str:
    """A failure as a person would say it."""
    s = str(subject)
    if reason == "unknown_word":
        return f"I do not know the word '{s.replace('_', ' ')}'"
    if reason in ("no_referent", "ambiguous"):
        try:
            text = parse.object(s).text
        except KeyError:
            text = s
        return f"I see no '{text}'" if reason == "no_referent" else f"I see more than one '{text}'"
    if reason == "relation_false":
        rel = parse.relation
        return f"'{rel.word.replace('_', ' ')}' does not hold" if rel is not None else "the relation does not hold"
    return f"{reason}: {s}"
