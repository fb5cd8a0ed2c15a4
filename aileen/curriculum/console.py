"""The trainer's console behind `aileen teach`: build a scene by hand, then talk to the agent.

Commands (one per line; `help` lists them):

    place red box [at 0.3 0.6]     put an object on the table (a free spot unless given; says what settling moved)
    scene red box left of blue cone [with 2 distractors]
                                   lay out a fresh scene as a lesson would
    clear                          empty the table
    inform <sentence>              teach (with "move X <rel> Y" the trainer demonstrates first)
    verify <sentence>              ask whether the sentence holds (an action is demonstrated)
    react <sentence>               ask the agent to do it
    describe                       ask the agent to say what it sees, in its words (generate)
    no                             the agent asked "did you mean 'box'?": no, the word is meant as
                                   said ("rox"), a word of its own (the sentence is given again)
    wrong                          the last verify answer was wrong: the agent learns from it
                                   (a "yes" becomes a near miss, a "no" an example)
    right                          the last verify answer was right: a "no" to a relation it
                                   knows becomes a near miss of it (as a lesson file's verdict)
    confirm                        the last react reached its goal: its trace becomes an example
    undo [N]                       take back the last lesson or verdict, or the last N (up to 10):
                                   what the agent learned from them and the table as it was
    show                           what the agent sees and which words it knows
    memory [concept]               what the concept memory holds
    save [PATH]                    save the memory (to --memory's file, or PATH)
    help                           this list
    quit                           leave (the memory is saved to --memory's file, if given)

A new word is learned from a table where exactly one object can be what the sentence
names: `place red box` then `inform red box` teaches "red" and "box"; on a table with two
candidates the agent cannot tell which object the trainer means, and learns nothing. A new
word said alone of a table of several objects ("dax" over a sphere and a box) names them
together, as laid out: a word for the group, as "wall" is for three boxes in a row.
"""

from __future__ import annotations

import math
import re
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from aileen.agent import Agent
from aileen.agent.body import WorldBody
from aileen.agent.protocol import give_verdict
from aileen.agent.records import NOTHING_DONE
from aileen.curriculum import grading, settled, trainer
from aileen.curriculum.interpreter import Interpreter, LessonResult
from aileen.curriculum.lesson import Lesson, ObjectSpec, Source
from aileen.curriculum.plain import already, plain
from aileen.curriculum.report import transcript
from aileen.curriculum.sentences import action_from_content, parse_object, read_content
from aileen.curriculum.stage import off_table, scene_lesson
from aileen.domain import actions
from aileen.errors import UserError
from aileen.memory.store import MemoryFile
from aileen.reasoning.language import property_said
from aileen.world.camera import DEFAULT_CAMERA
from aileen.world.render import Frame
from aileen.world.scenes import sample_free_position
from aileen.world.records import WorldObject
from aileen.world.sim import World

HELP = __doc__.split("Commands (one per line; `help` lists them):", 1)[1].rstrip()
#: Every command, as `help` lists them (quit is handled by the caller's loop).
COMMANDS = ("place", "scene", "clear", "inform", "verify", "react", "describe", "no", "wrong", "right", "confirm",
            "undo", "show", "memory", "save", "help", "quit")
#: The commands that may change what the agent knows (or, for react, the table): each can be
#: taken back by `undo`, and one that fails half-way is taken back at once (all or nothing).
LESSONS = ("inform", "verify", "react", "describe", "no", "wrong", "right", "confirm")
#: The commands after which the memory may differ: `aileen teach` saves after each of them
#: (`--autosave`), so a killed session loses at most the command under way.
CHANGES_MEMORY = (*LESSONS, "undo")
#: The commands that take nothing after them: "clear the table please" is refused, not read as "clear".
BARE = ("clear", "no", "wrong", "right", "confirm", "show", "help", "quit", "describe")
#: How many of them `undo` can take back, newest first.
UNDO_STEPS = 10


@dataclass(frozen=True)
class _Step:
    """What `undo` puts back: the command, the agent before it, the table, the agent's
    question ("did you mean ...?") and the table as the agent had last looked at it."""

    what: str
    agent: object
    world: World
    asked: tuple[str, str, str, bool] | None
    looked: tuple[WorldObject, ...] | None


# How far (m) settling may move a placed object before the console says so.
MOVED_NOTE_M = 0.005
# Two centres closer than this (m) are one spot: the new object is put this far to the side.
SAME_SPOT_M = 1e-4


# Where a note about a shape the detector was not trained on sends the reader (`aileen run`
# and `aileen teach` give one).
UNTRAINED_SEE = '(docs/perception.md, "The capsule"; --perception truth sees it)'


def _command_of(line: str) -> tuple[str, str]:
    """A console line's command word and the rest: split at the first run of any whitespace
    (a tab after "verify" was the command 'verify\tthe', unknown)."""
    word, *rest = line.split(None, 1) or [""]
    return word, rest[0].strip() if rest else ""


class Console:
    """`unseen`: shapes the agent's perception was not trained on (`Detector.untrained`):
    `place` and `scene` say so when they put one down, since the agent sees another shape
    there."""

    def __init__(self, agent: Agent, *, seed: int = 0, on_frame: Callable[[Frame], None] | None = None,
                 memory_file: "MemoryFile | None" = None, unseen: frozenset[str] = frozenset()) -> None:
        self.agent = agent
        self.unseen = unseen
        self.seed = seed
        self.memory_file = memory_file
        self.interp = Interpreter(agent, on_frame=on_frame)
        self.world = World(DEFAULT_CAMERA.table, seed=seed)
        self.on_frame = on_frame
        self._rng = np.random.default_rng(seed)
        self._n = 0  # looks at the table (each a camera's noise)
        self._drawn = 0  # the trainer's draws (scenes, demonstrations): looking does not move them
        self._goal: bool | None = None  # may the last lesson, a react, be confirmed (`grading.confirmable`)?
        # the last lesson's question about a word: (signal, sentence, the word, demonstrated)
        self._asked: tuple[str, str, str, bool] | None = None
        # the table as the agent last looked at it (a `show` on the same table looks no more:
        # looking again is a new scene, and a verdict is about the scene its answer was on)
        self._looked: tuple[WorldObject, ...] | None = None
        self._undo: list[_Step] = []  # what `undo` puts back, the newest last

    def _body(self) -> WorldBody:
        self._n += 1
        return WorldBody(self.world, DEFAULT_CAMERA, seed=self.seed * 7919 + self._n, on_frame=self.on_frame)

    def do(self, line: str) -> str:
        word, rest = _command_of(line)
        handler = getattr(self, f"_cmd_{word.lower()}", None)
        if handler is None:
            raise UserError(f"unknown command {word!r}; expected one of: {', '.join(COMMANDS)}")
        if rest and word.lower() in BARE:
            raise UserError(f"'{word.lower()}' takes nothing after it (got {rest!r}); type 'help' for the commands")
        snap = getattr(self.agent, "snapshot", None)
        if word.lower() not in LESSONS or snap is None:  # (an agent without snapshots: no undo)
            return handler(rest)
        step = _Step(f"{word.lower()} {rest}".strip(), snap(), self.world.copy(), self._asked, self._looked)
        try:
            out = handler(rest)
        except BaseException:
            self._back(step)  # all or nothing: a lesson that failed half-way teaches nothing
            raise
        self._undo = [*self._undo, step][-UNDO_STEPS:]
        return out

    @staticmethod
    def changes_memory(line: str) -> bool:
        """Whether the command `line` may have changed what the agent knows (`CHANGES_MEMORY`)."""
        return _command_of(line)[0].lower() in CHANGES_MEMORY

    def _back(self, step: _Step) -> None:
        self.agent.restore(step.agent)
        self.world, self._asked, self._looked = step.world, step.asked, step.looked

    def _cmd_undo(self, rest: str) -> str:
        """`undo` or `undo N`: the last N lessons and verdicts, newest first."""
        if not rest:
            n = 1
        elif rest.isdigit() and int(rest) >= 1:
            n = int(rest)
        else:
            raise UserError(f"expected 'undo' or 'undo N' (N a whole number >= 1), got 'undo {rest}'")
        if not self._undo:
            raise UserError(f"nothing to undo: the last {UNDO_STEPS} lessons and verdicts can be taken back")
        if n > len(self._undo):
            raise UserError(f"only {len(self._undo)} lesson(s) or verdict(s) can be taken back now, not {n}")
        steps = [self._undo.pop() for _ in range(n)]
        self._back(steps[-1])  # the agent and the table as they were before the oldest of them
        return "\n".join(f"undone: {step.what}" for step in steps) + " (the agent and the table as they were before it)"

    def _cmd_quit(self, rest: str) -> str:
        # the session's loop ends at a bare 'quit'; with words after it, `do` refuses it first
        raise UserError("type 'quit' alone to leave")

    # ------------------------------------------------------------------ the table
    def _cmd_help(self, rest: str) -> str:
        return HELP

    def _cmd_clear(self, rest: str) -> str:
        self.world = World(DEFAULT_CAMERA.table, seed=self.seed)
        return "the table is empty"

    def _cmd_place(self, rest: str) -> str:
        m = re.fullmatch(r"(.+?)(?:\s+at\s+(\S+)\s+(\S+))?", rest)
        if not rest or m is None:
            raise UserError("expected 'place <colour> <shape> [at X Y]'")
        if m.group(2) is None and re.search(r"\bat\b", m.group(1)):
            raise UserError("expected 'at X Y': two numbers in metres, x then y, e.g. 'place red box at 0.3 0.6'")
        spec = parse_object(m.group(1))
        if spec.shape is None or spec.colour is None:
            raise UserError("say both colour and shape, e.g. 'place red box'")
        from aileen.world.catalog import DEFAULT_SIZE, SIZES

        size_name = spec.size or DEFAULT_SIZE
        size = SIZES[size_name]
        asked = m.group(2) is not None
        if asked:
            try:
                x, y = float(m.group(2)), float(m.group(3))
            except ValueError:
                raise UserError("expected 'at X Y' in metres, e.g. 'at 0.3 0.6'") from None
            if not (math.isfinite(x) and math.isfinite(y)):  # (it named an angle nobody gave)
                raise UserError(f"expected 'at X Y' with finite numbers in metres, got ({x}, {y})")
            why = off_table(x, y, size_name, self.world.table)
            if why is not None:
                raise UserError(f"({x}, {y}) is off the table: {why}")
        else:
            x, y = sample_free_position(self.world, size, self._rng)
        before = {o.id: (o.x, o.y) for o in self.world.objects()}
        if any(math.dist((x, y), xy) < SAME_SPOT_M for xy in before.values()):
            # Put exactly where another stands, the physics cannot tell which way to push the
            # two apart, and they stayed one inside the other (the agent saw one object); a
            # hair to the side, settling pushes the new one clear and the note says so.
            x += SAME_SPOT_M
        obj = self.world.put(spec.appearance.replace(size=size_name), x, y)
        self.world.settle()
        o = self.world.get(obj)
        moved = self._moved_note(o, (x, y) if asked else None, before)
        return f"placed a {spec.describe()} at ({o.x:.2f}, {o.y:.2f})" + moved + self._unseen_note({o.shape})

    def _moved_note(self, placed: WorldObject, asked: tuple[float, float] | None,
                    before: dict[str, tuple[float, float]]) -> str:
        """What settling did that the teacher did not ask for: the object put down on another
        one, or pushed clear of it, and any object it pushed (a teacher who sets angles by hand
        was told nothing and got other angles)."""
        said = {w.id: f"the {ObjectSpec(appearance=w.appearance).describe()}" for w in self.world.objects()}
        notes = []
        if placed.on is not None:
            notes.append(f"it rests on {said.get(placed.on, 'another object')}")
        elif asked is not None and math.dist(asked, (placed.x, placed.y)) > MOVED_NOTE_M:
            notes.append(f"not at ({asked[0]:.2f}, {asked[1]:.2f}): it was pushed clear of what was there")
        alike = Counter(said.values())
        for w in self.world.objects():
            if w.id in before and math.dist(before[w.id], (w.x, w.y)) > MOVED_NOTE_M:
                # which of two alike: where it stood ("the medium red box was pushed" twice)
                was = f" at ({before[w.id][0]:.2f}, {before[w.id][1]:.2f})" if alike[said[w.id]] > 1 else ""
                notes.append(f"{said[w.id]}{was} was pushed to ({w.x:.2f}, {w.y:.2f})")
        return f" ({'; '.join(notes)})" if notes else ""

    def _cmd_scene(self, rest: str) -> str:
        bad = re.search(r"\bwith\s+(\S+)\s+distractors?$", rest)
        if bad and not bad.group(1).isdigit():  # ("-1" was "cannot lay out 'red box with -1 distractors'")
            raise UserError(f"expected 'with N distractors', N a whole number >= 0 (got {bad.group(1)!r})")
        m = re.fullmatch(r"(.+?)(?:\s+with\s+(\d+)\s+distractors?)?", rest)
        if not rest or m is None:
            raise UserError("expected 'scene <objects> [with N distractors]', e.g. 'scene red box left of blue cone'")
        lesson = scene_lesson(m.group(1), distractors=int(m.group(2) or 0), source=Source("<teach>"))
        self._drawn += 1
        try:
            setup = trainer.layout(lesson, seed=self.seed * 7919 + self._drawn, table=DEFAULT_CAMERA.table)
        except UserError as exc:  # (the console's words: not "<teach>: ... objects[1]")
            raise UserError(plain(exc.message, [p.describe() for p in lesson.objects])) from None
        self.world = setup.world
        notes = "".join(f"\nnote: {n}" for n in setup.notes)  # "laid out with 30 of 99 distractors: ..."
        return "\n".join(setup.describe()) + notes + self._unseen_note({o.shape for o in self.world.objects()})

    def _unseen_note(self, put: set[str]) -> str:
        """A line for each shape just put on the table that the agent's perception was not
        trained on."""
        shapes = sorted(put & self.unseen)
        return "".join(f"\nnote: the detector was not trained on the {s}: the agent sees another shape there "
                       f"{UNTRAINED_SEE}" for s in shapes)

    # ------------------------------------------------------------------ lessons
    def _lesson(self, signal: str, content: str) -> str:
        if not content and signal != "generate":
            raise UserError(f"expected '{signal} <sentence>'")
        agent = self.agent
        body = self._body()
        if self.world.held is None:
            agent.new_scene()
        # (else the scene goes on: with an object in the hand, a new scene forgot it, and "lift
        # the blue cone" after "lift the red box" was "already holding the red box")
        agent.perceive(body.look())
        seen = agent.describe_scene()  # the table before any action: what the transcript shows
        action = action_from_content(content)
        goal_holds = None
        if signal == "react":
            judged = self._judged(content)
            answer = agent.react(content, body)
            if judged is not None:  # graded as a lesson file's react is: the goal, in the world
                lesson, ids, start = judged
                goal_holds = grading.goal_holds(lesson, self.world, ids, start)
        elif signal == "generate":
            if not self.world.objects():
                raise UserError("the table is empty: put something on it to describe ('place red box')")
            answer = agent.generate(content)
        else:
            demo_start = None
            if action is not None:
                ids = self._find(content)
                lesson = _action_lesson(signal, content)
                names = [p.describe() for p in read_content(content).phrases]
                self._drawn += 1
                setup = trainer.Setup(self.world, ids)
                if not settled.goal_false_at_start(lesson, setup):
                    # as a lesson file's would be refused: the demonstration would show no change
                    raise UserError(already(names, action.relation))
                try:
                    demo_start = self.interp.demonstrate(lesson, setup, body, seed=self.seed * 7919 + self._drawn)
                except UserError as exc:
                    raise UserError(plain(exc.message, names)) from None
            answer = agent.inform(content, demo_start=demo_start) if signal == "inform" else agent.verify(content, demo_start=demo_start)
        self._asked = None
        self._looked = tuple(self.world.objects())
        self._goal = grading.confirmable(goal_holds, answer.ok) if signal == "react" else None  # what `confirm` may confirm
        if answer.question is not None and answer.asked_about is not None:
            self._asked = (signal, content, answer.asked_about, action is not None and signal != "react")
        result = LessonResult(0, Lesson(signal, content), answer, seen, None, goal_holds)
        if answer.said and answer.understood:  # graded as a person would, as a lesson file's run grades it
            result.said_true = grading.content_true(answer.said, self.world.objects())
        if signal in ("inform", "verify") and action is None and NOTHING_DONE in (answer.reason or ""):
            # a verb the trainer cannot demonstrate ("put the red box on the blue box"): the
            # agent's "learned from a demonstration" left the teacher with no way to give one
            verbs = ", ".join(sorted({v.name for v in actions.VERBS.values()}))
            result.notes.append(f"the console demonstrates the trainer's verbs ({verbs}) with the relations it "
                                "knows; a verb of your own is shown in a lesson file: demonstration = [...] "
                                "(docs/lessons.md)")
        return transcript(result)

    def _cmd_no(self, rest: str) -> str:
        """The trainer's "no" to the agent's "did you mean ...?": the word is meant as said;
        the sentence is given again (a demonstration is not: the objects have moved)."""
        if self._asked is None:
            raise UserError("the agent asked nothing to say 'no' to: 'no' answers its \"did you mean ...?\"")
        signal, content, word, demonstrated = self._asked
        self._asked = None
        self.agent.take_as_said(word)
        if demonstrated:
            return f"noted: '{word}' is a word of its own; show the lesson again to teach it"
        return f"noted: '{word}' is a word of its own\n" + self._lesson(signal, content)

    def _judged(self, content: str) -> tuple[Lesson, list[str], dict[str, tuple[float, float]]] | None:
        """What the trainer grades a react by: the lesson, its objects and where they stand
        now; None when it cannot tell which objects the sentence means (it then says nothing
        of the goal, as for a sentence it cannot read)."""
        if action_from_content(content) is None:
            return None
        try:
            ids = self._find(content)
        except UserError:
            return None
        return _action_lesson("react", content), ids, {o.id: (o.x, o.y) for o in self.world.objects()}

    def _find(self, content: str) -> list[str]:
        """The trainer finds the objects its sentence is about (it knows what it said)."""
        ids = []
        for p in read_content(content).phrases:
            hits = [o.id for o in self.world.objects() if not o.held and p.fits(o.appearance)]
            if len(hits) != 1:
                raise UserError(f"to demonstrate, the table needs exactly one {p.describe()} (it has {len(hits)})")
            ids.append(hits[0])
        action = action_from_content(content)
        if action is None or len(ids) != action.n_objects:
            raise UserError("to demonstrate, say '<verb> <object> [<relation> <object>]', e.g. 'move red box "
                            "left of blue cone' or 'push red box'")
        return ids

    def _cmd_inform(self, rest: str) -> str:
        return self._lesson("inform", rest)

    def _cmd_verify(self, rest: str) -> str:
        return self._lesson("verify", rest)

    def _cmd_react(self, rest: str) -> str:
        return self._lesson("react", rest)

    def _cmd_describe(self, rest: str) -> str:
        return self._lesson("generate", rest)

    def _verdict(self, what: str) -> str:
        from aileen.agent import Answer

        answer = Answer(what, what, "success")
        try:
            give_verdict(self.agent, what, answer)
        except ValueError as exc:
            raise UserError(str(exc)) from None
        if not answer.commands:
            return "noted; nothing to learn from it" + (f" ({answer.reason})" if answer.reason else "")
        return "learned: " + ", ".join([f"created {c}" for c in answer.created]
                                       + [f"stored {c}" for c in answer.stored]) + (
            f" ({answer.reason})" if answer.reason else "")

    def _cmd_wrong(self, rest: str) -> str:
        return self._verdict("wrong")

    def _cmd_right(self, rest: str) -> str:
        return self._verdict("right")

    def _cmd_confirm(self, rest: str) -> str:
        if self._goal is not True:
            raise UserError(grading.CONFIRM_REFUSED)
        return self._verdict("confirm")

    # ------------------------------------------------------------------ inspection
    def _cmd_show(self, rest: str) -> str:
        agent = self.agent
        table = tuple(self.world.objects())
        if agent.state is None or table != self._looked:
            agent.new_scene()
            agent.perceive(self._body().look())
            self._looked = table
        words = agent.semantic.words()
        lines = ["sees:  " + ("; ".join(agent.describe_scene()) or "nothing")]
        kinds = {w: agent.semantic.kind(c) for w, c in words.items()}
        lines.append("knows: " + (", ".join(f"{property_said(w) if k == 'visual' else w.replace('_', ' ')} ({k})"
                                            for w, k in sorted(kinds.items())) or "no words yet"))
        return "\n".join(lines)

    def _cmd_memory(self, rest: str) -> str:
        from aileen.memory.commands import render_text, resolve_concept

        return render_text(self.agent.memory, resolve_concept(self.agent.memory, rest) if rest else None)

    def _cmd_save(self, rest: str) -> str:
        """Save through the locked memory file, or lock PATH for the moment of the save; a
        failure is an error line and the session (with its memory) goes on."""
        held = self.memory_file
        if not rest and held is None:
            raise UserError("expected 'save PATH' (or start with --memory PATH)")
        if held is not None and (not rest or held.same_file(rest)):
            held.save(self.agent)
            path = held.path
        else:
            with MemoryFile.open(rest, instead="save to another file") as mf:
                mf.save(self.agent)
            path = Path(rest)
        return f"saved {len(self.agent.memory)} concepts to {path}"


def _action_lesson(signal: str, content: str) -> Lesson:
    """The lesson the trainer demonstrates or grades a console's action sentence by (its
    objects are the table's, found by `Console._find`)."""
    action = action_from_content(content)
    assert action is not None
    return Lesson(signal, content, [ObjectSpec()] * action.n_objects, action=action, source=Source("<teach>"))
