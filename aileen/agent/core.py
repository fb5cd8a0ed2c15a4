"""The agent: perceive, comprehend, learn, act.

One `Agent` holds the state that persists across lessons (semantic, episodic and concept
memories, the lexicon, the scene now seen) and its parts (agent/part.py), each with its own
records and caches: reading (reading.py), grounding (grounding.py), referents (referents.py), demonstrations
(demonstration.py), composite words (composite.py), learning (learning.py), acting
(acting.py), generation (generation.py) and the trainer's feedback (feedback.py). It answers
the paper's signals by handing them to its parts: `inform` (learning), `verify` (grounding),
`react` (acting) and `generate` (generation). Everything the agent knows about the table
comes through `perceive(image)` and its own actions; the simulator's ground truth never
reaches it. Other code talks to it through its methods, never its fields.
"""

from __future__ import annotations

import copy
from typing import TYPE_CHECKING

import numpy as np

from aileen.agent.acting import Acting
from aileen.agent.composite import Composites
from aileen.agent.demonstration import Demonstrations
from aileen.agent.directions import Directions
from aileen.agent.feedback import Feedback
from aileen.agent.generation import Generation, Phrase
from aileen.agent.grounding import Grounding
from aileen.agent.learning import Learning
from aileen.agent.lexicon import Lexicon
from aileen.agent.reading import Reading
from aileen.agent.referents import Referents
from aileen.agent.records import AgentParams, Answer
from aileen.agent.state import State, Tracker, id_order
from aileen.domain import actions, calculi
from aileen.memory.concept import ConceptMemory
from aileen.memory.episodic import EpisodicMemory
from aileen.memory.semantic import SemanticMemory
from aileen.perception.facts import scene_facts, static_facts
from aileen.perception.perceiver import Detection, Perceiver
from aileen.reasoning import comprehension, language
from aileen.terms import Term, fn
from aileen.world.camera import DEFAULT_CAMERA, Camera

if TYPE_CHECKING:
    from aileen.agent.body import WorldBody


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
        self.memory = memory if memory is not None else ConceptMemory(params.sage())
        self.semantic = semantic if semantic is not None else SemanticMemory()
        self.episodic = EpisodicMemory()
        self.params = params
        self.camera = camera
        self.rules = rules
        self.tracker = Tracker(params.object_permanence)
        self._perceiver = perceiver if perceiver is not None else vision(camera)
        self.state: State | None = None
        self.held: str | None = None
        self._senses = params.senses()  # the calculi it perceives (its direction sense)
        # where relation words hold, as regions of directions (derived from the memory as it is)
        self.directions = Directions(self._current_memory, params.mutual_exclusivity, params.near_miss_edges)
        # the visual words' meanings, kept up to date from the memory's change log
        self.lexicon = Lexicon(self._required_percepts, self.semantic.word, self._visual_concepts,
                               bootstrapping=params.syntactic_bootstrapping, changes=self._memory_changes)
        self.lexicon.load_annotation(self.memory.annotations.get("lexicon"))
        # the parts (agent/part.py): each keeps its own records and caches, and asks the
        # others by name (`self.agent.grounding`)
        self.reading = Reading(self)
        self.grounding = Grounding(self)
        self.referents = Referents(self)
        self.demonstrations = Demonstrations(self)
        self.composites = Composites(self)
        self.learning = Learning(self)
        self.acting = Acting(self)
        self.generation = Generation(self)
        self.feedback = Feedback(self)

    # ------------------------------------------------------------------ the parts' signals
    def inform(self, content: str, *, demo_start: int | None = None) -> Answer:
        """Comprehend; learn only from what failed. `demo_start` is the episode index where
        a demonstration began (for action lessons: the trace runs from there to now).
        (`Learning.inform`.)"""
        return self.learning.inform(content, demo_start=demo_start)

    def verify(self, content: str, *, demo_start: int | None = None) -> Answer:
        """Does what the content says hold in the scene (or the demonstration just seen)?
        (`Grounding.verify`; the feedback part keeps the answer for the trainer's verdict.)"""
        answer = self.grounding.verify(content, demo_start=demo_start)
        self.feedback.answered("verify", content, demo_start, answer)
        return answer

    def react(self, content: str, body: "WorldBody") -> Answer:
        """Carry out an action sentence in the world (`Acting.react`; the feedback part keeps
        the answer, with where the agent first looked, for the trainer's confirmation)."""
        start = self.episodic.now + 1  # react looks first
        answer = self.acting.react(content, body)
        self.feedback.answered("react", content, start, answer)
        return answer

    def comprehend(self, content: str, *, demo_start: int | None = None) -> comprehension.Comprehension:
        """Indexical comprehension of `content` in the current scene (and demonstration)
        (`Grounding.comprehend`)."""
        return self.grounding.comprehend(content, demo_start=demo_start)

    def meaning(self, concept: str) -> frozenset[Term]:
        """The percept symbols a visual concept requires (its generalization's significant
        `isa` facts), for mutual exclusivity; the lexicon keeps them, read again only when
        the concept is stored into."""
        return self.lexicon.meaning(concept)

    def take_as_said(self, word: str) -> None:
        """The teacher's "no" to the agent's "did you mean ...?" about `word` ("rox" beside
        "box", "nleft of" beside "left of"): the word is meant as said, a word of its own, and
        is learned like any new word (`Reading.take_as_said`)."""
        self.reading.take_as_said(word)

    def told_wrong(self, answer: Answer) -> None:
        """The trainer says the last verify answer was wrong (`Feedback.told_wrong`)."""
        self.feedback.told_wrong(answer)

    def told_right(self, answer: Answer) -> None:
        """The trainer lets the last verify answer stand (`Feedback.told_right`)."""
        self.feedback.told_right(answer)

    def confirmed(self, answer: Answer) -> None:
        """The trainer confirms the last react reached its goal (`Feedback.confirmed`)."""
        self.feedback.confirmed(answer)

    def generate(self, content: str = "") -> Answer:
        """Describe the table in learned words (`Generation.generate`)."""
        return self.generation.generate(content)

    def phrase(self, obj: str, state: State) -> Phrase:
        """The learned words for one object (`Generation.phrase`)."""
        return self.generation.phrase(obj, state)

    def location(self, obj: str, state: State) -> str | None:
        """Where `obj` is, in learned words (`Generation.location`)."""
        return self.generation.location(obj, state)

    @property
    def positions(self) -> dict[str, set[str]]:
        """Where each taught word has stood in noun phrases (the lexicon's, read-only use)."""
        return self.lexicon.positions

    # ------------------------------------------------------------------ persistence
    def save(self, path: str) -> None:
        """Save what was learned: the concept memory, with the lexicon (word positions) in
        its annotations; the semantic memory is rebuilt from it."""
        self._sync_lexicon()
        self.memory.save(path)

    def _required_percepts(self, concept: str) -> frozenset[Term]:
        """A visual concept's meaning (`meaning`), read from the memory now, for the lexicon."""
        return self.memory.required_classes(concept)

    def _visual_concepts(self) -> list[str]:
        """The visual concepts of the memory now, for the lexicon."""
        return [c.symbol for c in self.memory.concepts() if c.kind == "visual"]

    def _current_memory(self) -> ConceptMemory:
        """The concept memory as it is now (a bound method, so a restored copy reads its own)."""
        return self.memory

    def _memory_changes(self, mark: int | None) -> tuple[int, dict[str, str] | None]:
        """The concepts stored into since `mark` (`ConceptMemory.changes_since`), for the lexicon."""
        return self.memory.changes_since(mark)

    def snapshot(self) -> "Agent":
        """A copy of everything this agent has learned and perceived (its eyes are shared, not
        copied): `restore` takes it back to this moment (the console's undo of a lesson)."""
        return copy.deepcopy(self, {id(self._perceiver): self._perceiver})

    def restore(self, snapshot: "Agent") -> None:
        """Become the agent `snapshot` was, in place (whoever holds this agent keeps it). The
        snapshot is copied, so it can be restored again."""
        eyes = snapshot._perceiver  # shared, not copied: ground-truth eyes see the frames rendered for them
        state = copy.deepcopy(snapshot.__dict__, {id(snapshot): self, id(eyes): eyes})  # bound methods bind to self
        self.__dict__.clear()
        self.__dict__.update(state)

    def forget(self, concept: str) -> str | None:
        """Forget a concept: its generalizations, examples and near misses, its word, and where
        the word stood in phrases. What was perceived (episodes, the scene now seen) stays.
        Returns the concept's word. Other concepts' stored facts are left as they were."""
        from aileen.errors import UserError

        if concept not in self.memory:
            raise UserError(f"no concept {concept!r} to forget")
        word = self.semantic.word(concept)
        self._sync_lexicon()
        data = copy.deepcopy(self.memory.to_dict())  # its annotations are the live memory's own
        data["concepts"] = [c for c in data["concepts"] if c["symbol"] != concept]
        lex = data.get("annotations", {}).get("lexicon")
        if word is not None and isinstance(lex, dict):
            for part in ("positions", "distance"):
                lex.get(part, {}).pop(word, None)
            lex.get("seen", {}).get("taught", {}).pop(word, None)
        memory = ConceptMemory.from_dict(data)
        semantic = SemanticMemory.from_dict({w: e for w, e in self.semantic.to_dict().items()
                                             if e["concept"] != concept})
        fresh = type(self)(memory, semantic, params=self.params, camera=self.camera, rules=self.rules,
                           perceiver=self._perceiver)
        for kept in ("episodic", "tracker", "state", "held"):
            setattr(fresh, kept, getattr(self, kept))
        fresh.acting.rng = self.acting.rng
        self.restore(fresh)
        return word

    def _sync_lexicon(self) -> None:
        """Keep the lexicon in the concept memory's annotations, so an agent built on the
        same memory (a copy, a worker process, a saved file) reads words the same way."""
        self.memory.annotations["lexicon"] = self.lexicon.to_annotation()

    def note_seen(self) -> None:
        """Count the objects on the table of a lesson taught from (`seen.py`), kept in the
        lexicon and the memory's annotations."""
        if self.state is not None:
            self.lexicon.note_seen(o.percepts for _i, o in sorted(self.state.objects.items()))
            self._sync_lexicon()

    def note_positions(self, parse: language.Parse) -> None:
        """Where the trainer put each word of a lesson's sentence (the learning part, as part
        of the lesson), kept in the lexicon and the memory's annotations."""
        self.lexicon.note_positions(parse)
        self._sync_lexicon()

    # ------------------------------------------------------------------ perceiving
    def new_scene(self) -> None:
        """The trainer set up a new scene: forget object identities from the last one."""
        self.tracker.reset()
        self.held = None
        self.state = None

    def perceive(self, image: np.ndarray, action: Term | None = None, released: str | None = None) -> State:
        """Look at an image, keep object ids stable, derive facts, record the episode.
        `action`: what the hand has just done (its declared marks hold of its object in this
        frame); `released`: the object the hand has just put down (`Tracker.assign`)."""
        ids = self.tracker.assign(self._perceiver(image), released, self.held)
        objects = {i: self.tracker.known[i] for i in ids}
        facts = scene_facts([objects[i] for i in sorted(objects, key=id_order)], self._senses, remember=True)
        facts.extend(fn(calculi.MOVED, i) for i in sorted(self.tracker.moved, key=id_order))
        if action is not None and action.args and str(action.args[0]) in objects:
            # the marks of what the hand was seen to do (or did): pushed(o1) after push(o1)
            facts.extend(fn(m, action.args[0]) for m in actions.marks_of(str(action.name)))
        if self.held in objects:
            self.held = None  # back on the table
        if self.held is not None:
            facts.append(fn("held", self.held))
            if self.held in self.tracker.known:
                # what it still knows of the object in the hand: how it looked, and the static
                # relations (sizes) to what is in view ("lift the red box", demonstrated, ends
                # with the box held: the sentence names it, and the blue cone in view was taken
                # for it and taught as a red box)
                seen = self.tracker.known[self.held]
                visible = [objects[i] for i in sorted(objects, key=id_order)]
                facts.extend(scene_facts([seen], self._senses))
                facts.extend(static_facts(seen, visible))
        self.state = State(objects, self.held, facts)
        self.episodic.record(facts, action)
        return self.state

    def describe_scene(self) -> list[str]:
        """What the agent sees now, one line per object: `o1 cv_red cv_box at (0.42, 0.55)`
        (percepts in noun-phrase order: modifiers first, the shape last)."""
        if self.state is None:
            return []
        out = []
        for oid in sorted(self.state.objects, key=id_order):
            s = self.state.objects[oid]
            x, y = s.centre
            out.append(f"{oid} {' '.join(reversed(s.percepts))} at ({x:.2f}, {y:.2f}){s.note}")
        return out

    def locate(self, u: float, v: float) -> str:
        """The agent id of the object seen at pixel (u, v) (where the trainer points); the
        upper one where two are stacked."""
        assert self.state is not None
        best, best_key = None, (float("inf"), 0.0)
        for s in self.state.objects.values():
            u0, v0, u1, v1 = s.box_px
            if u0 - 1 <= u <= u1 + 1 and v0 - 1 <= v <= v1 + 1:
                d = ((u0 + u1) / 2 - u) ** 2 + ((v0 + v1) / 2 - v) ** 2
                key = (-s.level, d)
                if key < best_key:
                    best, best_key = s.id, key
        if best is None:
            raise LookupError(f"no object seen at pixel ({u:.0f}, {v:.0f})")
        return best

    def watch(self, action: str, u: float | None, v: float | None, image: np.ndarray) -> None:
        """The trainer did one primitive action while the agent watched: it saw where the
        hand went (pixel (u, v) of the object touched, or None for `place`, which releases
        what is held) and then the table afterwards (`image`)."""
        hand = actions.action(action).hand
        released = None
        if u is not None and v is not None:
            seen_id = self.locate(u, v)
            if hand == actions.GRASP:
                self.held = seen_id
            act = fn(action, seen_id)
        else:
            act = fn(action, self.held or "nothing")
            if hand == actions.RELEASE:
                released, self.held = self.held, None
        self.perceive(image, action=act, released=released)

    def episode_now(self) -> int:
        """The episodic memory's current index (where a demonstration starts)."""
        return self.episodic.now


def vision(camera: Camera) -> Perceiver:
    """The shipped visual module: detector, one measure per channel, boxes (loaded on first use)."""

    def see(image: np.ndarray) -> list[Detection]:
        from aileen.perception import perceive

        scene = perceive(image, camera=camera)
        return [Detection(o.percepts, o.box_m, o.box_px, o.level, o.footprint) for o in scene.objects]

    return see

