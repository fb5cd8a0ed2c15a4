"""One teaching session: an agent, the trainer's table, the lessons given, what the agent saw.

Framework-free: the HTTP app (`aileen.web.app`) calls it, and so can tests and scripts. Every
lesson goes through the same path as `aileen run`: the session writes the lesson as lesson-file
text (objects at their exact positions, the seed), parses it with the lesson-file reader and
runs it with the lesson interpreter. The downloadable transcript is that text, so `aileen run`
replays the session to the same answers (from the same starting memory).

Between lessons the page shows a preview: the table laid out and photographed exactly as the
next lesson will, perceived by a second, memory-less agent (`eyes`), so the trainer's agent
never perceives anything outside a lesson and its episodic memory matches a replay.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from aileen.agent import Agent, Answer
from aileen.agent.body import WorldBody
from aileen.curriculum import demonstration, lessonfile, trainer
from aileen.curriculum.interpreter import CAMERA_NOISE, Interpreter
from aileen.curriculum.lesson import Lesson, Source
from aileen.curriculum.sentences import action_from_content, read_content
from aileen.errors import UserError
from aileen.web import overlay, transcript
from aileen.web.table import Placed, TableEdit
from aileen.world.camera import DEFAULT_CAMERA, Camera
from aileen.world.render import Frame

SIGNALS = ("inform", "verify", "react", "generate")
# Signals other work adds to the agent; the console offers them when the agent has the method.
VERDICTS = ("wrong", "confirm")  # the trainer's verdict on the last verify / react
SAME = {"describe": "generate"}  # the console's word for a signal
MAX_CONTENT = 200
# Scene edits and the fields each takes.
EDITS: dict[str, set[str]] = {"add": {"object", "at", "px", "relation", "of"}, "move": {"index", "at", "px"},
                              "remove": {"index"}, "clear": set(), "shuffle": {"distractors"},
                              "layout": {"content", "distractors"}, "undo": set()}  # characters in one sentence


@dataclass
class View:
    """What the page shows: a camera image and the agent's perception of it."""

    image: np.ndarray
    marks: list[overlay.Mark]
    highlight: list[str] = field(default_factory=list)
    frames: list[np.ndarray] = field(default_factory=list)  # a lesson's frames, for playback
    pngs: dict[bool, bytes] = field(default_factory=dict)  # encoded once, by overlay on/off


class Session:
    """The state behind the console. Not thread-safe: the app serialises requests."""

    def __init__(self, agent: Agent, *, seed: int = 0, memory_path: str | None = None, memory_file=None,
                 camera: Camera = DEFAULT_CAMERA, eyes: Agent | None = None) -> None:
        self.agent = agent
        self.seed = seed
        self.memory_path = memory_path
        self.memory_file = memory_file  # aileen.memory.store.MemoryFile: locked, saves with recovery
        self.camera = camera
        self.eyes = eyes if eyes is not None else Agent(camera=camera)
        self.table = TableEdit(camera.table, seed=seed)
        self.blocks: list[str] = []  # the transcript, one lesson-file block per lesson
        self.records: list[dict] = []  # each lesson's `aileen run --json` record
        self.version = 0  # bumped on every change the page must redraw
        self._frames: list[Frame] = []
        self.interp = Interpreter(agent, camera=camera, on_frame=self._frames.append)
        self._view: View | None = None

    # ------------------------------------------------------------------ seeds
    def lesson_seed(self, n: int | None = None) -> int:
        """The seed of lesson n (0-based; default: the next one), as `aileen run` derives it."""
        n = len(self.blocks) if n is None else n
        return self.seed * 1000 + n

    # ------------------------------------------------------------------ the table
    def edit(self, op: str, **kw) -> dict:
        """One edit of the table: add, move, remove, clear, shuffle, layout, undo."""
        t = self.table
        if op not in EDITS:
            raise UserError(f"unknown scene op {op!r}; expected one of: {', '.join(EDITS)}")
        extra = sorted(set(kw) - EDITS[op])
        if extra:
            raise UserError(f"unexpected field(s) for {op!r}: {', '.join(extra)}")
        if op == "add":
            t.add(_text(kw.pop("object", None), "object"), at=_xy(self, kw), relation=_opt_text(kw.pop("relation", None)),
                  of=_opt_text(kw.pop("of", None)))
        elif op == "move":
            at = _xy(self, kw)
            if at is None:
                raise UserError("move needs 'at': [x, y] metres, or 'px': [u, v] camera pixels")
            t.move(kw.pop("index", None), at)
        elif op == "remove":
            t.remove(kw.pop("index", None))
        elif op == "clear":
            t.clear()
        elif op == "shuffle":
            t.shuffle_distractors(kw.pop("distractors", 2))
        elif op == "layout":
            d = kw.pop("distractors", 0)
            if not isinstance(d, int) or isinstance(d, bool) or not 0 <= d <= 8:
                raise UserError("distractors must be a whole number from 0 to 8")
            t.lay_out(_text(kw.pop("content", None), "content"), distractors=d)
        else:
            t.undo()
        self._view = None
        self.version += 1
        return self.scene()

    def scene(self) -> dict:
        """The table (trainer's truth, for editing) and what the agent will see of it."""
        view = self.view()
        cam = self.camera
        objs = []
        for i, o in enumerate(self.table.objects):
            u, v = cam.to_pixels(o.x, o.y)
            objs.append({"index": i, "shape": o.shape, "colour": o.colour, "size": o.size, "x": o.x, "y": o.y,
                         "px": [round(u, 1), round(v, 1)], "half_px": round(o.half * cam.width / cam.table.width, 1),
                         "distractor": o.distractor, "name": o.describe()})
        return {"version": self.version, "objects": objs, "seen": [m.to_json() for m in view.marks],
                "highlight": view.highlight, "frames": len(view.frames), "scale": overlay.SCALE,
                "camera": {"width": cam.width, "height": cam.height}, "lessons": len(self.blocks),
                "next_seed": self.lesson_seed()}

    def view(self) -> View:
        if self._view is None:
            self._view = self._preview()
        return self._view

    def _preview(self) -> View:
        """The next lesson's camera image of the table, as the memory-less eyes perceive it."""
        seed = self.lesson_seed()
        lesson = Lesson("inform", "", [o.spec() for o in self.table.objects], source=Source("<console>"))
        if lesson.objects:
            world = trainer.layout(lesson, seed=seed, table=self.camera.table).world
        else:
            from aileen.world.sim import World

            world = World(self.camera.table, seed=seed)
        image = WorldBody(world, self.camera, seed=seed, noise=CAMERA_NOISE).look()
        self.eyes.new_scene()
        state = self.eyes.perceive(image)
        return View(image, _marks(state))

    def image(self, *, overlay_on: bool, frame: int | None = None) -> bytes:
        view = self.view()
        if frame is None:
            if overlay_on not in view.pngs:
                view.pngs[overlay_on] = overlay.png(overlay.draw(view.image, view.marks, view.highlight,
                                                                 overlay=overlay_on))
            return view.pngs[overlay_on]
        if not isinstance(frame, int) or not 0 <= frame < len(view.frames):
            raise UserError(f"no frame {frame!r}; the last lesson has {len(view.frames)}")
        return overlay.png(overlay.draw(view.frames[frame], overlay=False))

    # ------------------------------------------------------------------ lessons
    def lesson(self, signal: object, content: object) -> dict:
        """Give one lesson; returns the `aileen run --json` record."""
        if not isinstance(signal, str):
            raise UserError("'signal' must be a string: inform, verify or react")
        signal = SAME.get(signal, signal)
        if signal in VERDICTS:
            return self._verdict(signal)
        if signal not in SIGNALS:
            raise UserError(f"unknown signal {signal!r}; expected one of: {', '.join(SIGNALS + tuple(SAME) + VERDICTS)}")
        content = "" if signal == "generate" and content in (None, "") else _text(content, "content")
        if len(content) > MAX_CONTENT:
            raise UserError(f"'content' is longer than {MAX_CONTENT} characters")
        objects = self._ordered(content)
        action = action_from_content(content)
        n = len(self.blocks)
        seed = self.lesson_seed(n)
        block = transcript.lesson_block(signal, content, [o.spec() for o in objects], seed=seed,
                                        demonstrate=action is not None and signal != "react",
                                        note=f"console lesson {n + 1}")
        lesson = lessonfile.loads(block, path="<console>").lessons[0]
        demonstration.check_curriculum([lesson], [seed], table=self.camera.table)
        self._frames.clear()
        result = self.interp.run(lesson, index=n + 1, seed=seed)
        record = result.to_json()
        self.blocks.append(block)
        self.records.append(record)
        frames = list(self._frames)
        self._after(objects, frames[-1] if frames else None)
        state = self.agent.state
        marks = _marks(state) if state is not None else []
        lit = sorted({i for ids in result.answer.referents.values() for i in ids})
        image = frames[-1].image if frames else self.view().image
        self._view = View(image, marks, lit, [f.image for f in frames])
        self.image(overlay_on=True)  # drawn before the answer goes out, so the page shows it at once
        self.version += 1
        return record

    def _ordered(self, content: str) -> list[Placed]:
        """The table's objects, those an action sentence names first (mover, then reference):
        the trainer demonstrates and judges with objects 1 and 2, as in a lesson file."""
        objects = list(self.table.objects)
        if action_from_content(content) is None:
            return objects
        phrases = read_content(content).phrases
        if len(phrases) != 2:
            raise UserError("an action sentence names two objects: 'move <object> <relation> <object>'")
        picked = []
        for p in phrases:
            hits = [i for i, o in enumerate(objects) if p.matches(o.shape, o.colour)]
            if len(hits) != 1:
                raise UserError(f"to demonstrate or judge, the table needs exactly one {p.describe()} (it has {len(hits)})")
            picked.append(hits[0])
        if picked[0] == picked[1]:
            raise UserError("the sentence names the same object twice")
        return [objects[i] for i in picked] + [o for i, o in enumerate(objects) if i not in picked]

    def _after(self, objects: list[Placed], frame: Frame | None) -> None:
        """The table as the lesson left it (a demonstration or the agent's hand moves objects).
        World ids follow the lesson's object order (obj1 = first object)."""
        if frame is None:
            return
        where = {t.id: t.centre_m for t in frame.truth}
        moved = []
        for k, o in enumerate(objects):
            xy = where.get(f"obj{k + 1}")
            moved.append(o if xy is None else Placed(o.shape, o.colour, o.size, float(xy[0]), float(xy[1]),
                                                     o.distractor))
        if moved != list(self.table.objects):
            self.table.set_all(moved)

    def _verdict(self, what: str) -> dict:
        """The trainer's verdict on the last lesson: `wrong` after a verify (the agent learns
        from the near miss, or from what it failed to understand), `confirm` after a react that
        reached its goal (its trace becomes an example). The lesson file gets `feedback`, so a
        replay learns the same."""
        asks = {"wrong": "verify", "confirm": "react"}[what]
        if not self.records or self.records[-1]["signal"] != asks:
            raise UserError(f"'{what}' is a verdict on the last {asks} lesson; give one first")
        answer = Answer(what, "", "success")
        try:
            self.agent.told_wrong(answer) if what == "wrong" else self.agent.confirmed(answer)
        except ValueError as exc:
            raise UserError(str(exc)) from None
        self.blocks[-1] += f'feedback = "{what}"\n'
        record = {"index": len(self.records) + 1, "signal": what, "content": "", "result": answer.result,
                  "reason": None, "commands": answer.commands, "created": answer.created,
                  "stored": answer.stored, "referents": {}, "seen": [], "expected": None, "correct": None,
                  "seconds": 0.0}
        self.records.append(record)
        self.version += 1
        return record

    # ------------------------------------------------------------------ transcript and memory
    def lesson_file(self) -> str:
        if not self.blocks:
            raise UserError("no lessons given yet")
        return transcript.document(
            self.blocks, title="aileen serve session", seed=self.seed,
            description=("Lessons given in the teaching console. Replay with `aileen run` from the memory the "
                         "session started with" + (f" ({Path(self.memory_path).name})" if self.memory_path else
                                                   " (an empty one)") + "."))

    def memory(self) -> dict:
        from aileen.memory.commands import render_json, render_text

        mem = self.agent.memory
        out = render_json(mem)
        words = self.agent.semantic.words()
        by_concept = {c: w for w, c in words.items()}
        for sym, entry in out.items():
            entry["word"] = by_concept.get(sym)
            entry["text"] = render_text(mem, sym).split("\n", 1)[1].strip()
            entry["quality"] = self._quality(by_concept.get(sym))
        p = mem.params
        return {"concepts": out, "thresholds": {"assimilation": p.assimilation, "probability": p.probability,
                                                 "match": p.match}, "path": bool(self.memory_path)}

    def _quality(self, word: str | None) -> dict | None:
        """How the word fared in this session's graded verify lessons that used it."""
        if not word:
            return None
        graded = [r for r in self.records if r["signal"] == "verify" and r["correct"] is not None
                  and word.replace("_", " ") in r["content"]]
        if not graded:
            return None
        return {"verify_right": sum(bool(r["correct"]) for r in graded), "verify_graded": len(graded)}

    def save(self) -> str:
        if not self.memory_path:
            raise UserError("the console was started without --memory, so there is nowhere to save")
        if self.memory_file is not None:
            self.memory_file.save(self.agent)
        else:
            self.agent.save(self.memory_path)
        return f"saved {len(self.agent.memory)} concepts to {self.memory_path}"


def _marks(state) -> list[overlay.Mark]:
    return [overlay.Mark(s.id, s.percepts, s.box_px) for _, s in sorted(state.objects.items())]


def _text(value: object, name: str) -> str:
    if not isinstance(value, str) or not value.strip():
        raise UserError(f"'{name}' must be a non-empty string")
    if "\n" in value or "\r" in value:
        raise UserError(f"'{name}' must be one line")
    return " ".join(value.split())  # as the lesson-file reader reads it


def _opt_text(value: object) -> str | None:
    return None if value is None else _text(value, "relation/of")


def _number(v: object) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v):
        raise UserError("a position must be two finite numbers")
    return float(v)


def _xy(session: Session, kw: dict) -> tuple[float, float] | None:
    """A spot from 'at' (metres) or 'px' (camera pixels, as clicked on the page)."""
    at, px = kw.pop("at", None), kw.pop("px", None)
    if at is not None and px is not None:
        raise UserError("give 'at' or 'px', not both")
    pair = at if at is not None else px
    if pair is None:
        return None
    if not isinstance(pair, list) or len(pair) != 2:
        raise UserError("a position is a list of two numbers")
    a, b = _number(pair[0]), _number(pair[1])
    return (a, b) if at is not None else session.camera.to_metres(a, b)
