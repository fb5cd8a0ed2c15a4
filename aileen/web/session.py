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

import os
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from aileen.agent import Agent, Answer
from aileen.agent.body import WorldBody
from aileen.curriculum import lessonfile, rehearsal, trainer
from aileen.curriculum.interpreter import CAMERA_NOISE, Interpreter
from aileen.curriculum.lesson import Lesson, Source
from aileen.curriculum.sentences import action_from_content, read_content
from aileen.domain import channels, relations
from aileen.errors import UserError
from aileen.web import overlay, state, transcript
from aileen.web.table import Placed, TableEdit
from aileen.world.camera import DEFAULT_CAMERA, Camera
from aileen.world.render import Frame

SIGNALS = ("inform", "verify", "react", "generate")
# Signals other work adds to the agent; the console offers them when the agent has the method.
VERDICTS = ("wrong", "confirm")  # the trainer's verdict on the last verify / react
NO = "no"  # the trainer's answer to the agent's "did you mean 'box'?": the word is meant as said
SAME = {"describe": "generate"}  # the console's word for a signal
MAX_CONTENT = 200
# Scene edits and the fields each takes.
EDITS: dict[str, set[str]] = {"add": {"object", "at", "px", "relation", "of"}, "move": {"index", "at", "px"},
                              "remove": {"index"}, "clear": set(), "shuffle": {"distractors"},
                              "layout": {"content", "distractors"}, "undo": set()}  # characters in one sentence
UNDO_LESSONS = 10  # lessons (and verdicts, forgets) that can be taken back, newest first


class Stale(Exception):
    """An edit made on a table the page no longer shows (another tab changed it): HTTP 409."""

    def __init__(self, given: object, now: int) -> None:
        super().__init__(f"the table changed since this page last saw it (version {given!r}, now {now}); "
                         "it is shown as it is now, and nothing was done")
        self.message = str(self)
        self.version = now


@dataclass
class _Step:
    """A lesson, verdict or forget that undo can take back: everything as it was before it."""

    what: str  # the record's signal, or "forget"
    agent: object  # Agent.snapshot()
    table: list[Placed]
    blocks: list[str]
    records: int
    undone: dict | None = None  # what undo reports for a step that has no record (a forget)


@dataclass
class View:
    """What the page shows: a camera image and the agent's perception of it."""

    image: np.ndarray
    marks: list[overlay.Mark]
    highlight: list[str] = field(default_factory=list)
    frames: list[np.ndarray] = field(default_factory=list)  # a lesson's frames, for playback
    arrows: list[overlay.Arrow] = field(default_factory=list)  # relations between grounded objects
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
        self.version = 0  # bumped on every change the page must redraw; edits may carry it (409 if stale)
        self._steps: list[_Step] = []  # for undo, newest last
        self._frames: list[Frame] = []
        self.interp = Interpreter(agent, camera=camera, on_frame=self._frames.append)
        self._view: View | None = None

    # ------------------------------------------------------------------ seeds
    def lesson_seed(self, n: int | None = None) -> int:
        """The seed of lesson n (0-based; default: the next one), as `aileen run` derives it."""
        n = len(self.blocks) if n is None else n
        return self.seed * 1000 + n

    def check_version(self, given: object) -> None:
        """An edit that carries the version of the table it was made on must be made on this
        one: a stale tab must not remove or move the wrong object (`Stale`, HTTP 409)."""
        if given is None:
            return
        if not isinstance(given, int) or isinstance(given, bool):
            raise UserError("'version' must be the whole number the last scene answer gave")
        if given != self.version:
            raise Stale(given, self.version)

    # ------------------------------------------------------------------ the table
    def set_table(self, objects: object, relation: object = None, distractors: object = 0) -> dict:
        """The whole table in one call: `objects` a list of descriptions ('large red box') or
        of {"object": description, "at": [x, y] | "px": [u, v]}; `relation` lays out two."""
        if not isinstance(objects, list) or not objects:
            raise UserError("'objects' must be a non-empty list of object descriptions")
        items = []
        for o in objects:
            if isinstance(o, str):
                items.append((_text(o, "object"), None))
            elif isinstance(o, dict):
                extra = sorted(set(o) - {"object", "at", "px"})
                if extra:
                    raise UserError(f"unexpected field(s) in an object: {', '.join(map(str, extra))}; "
                                    "expected object and at or px")
                kw = dict(o)
                items.append((_text(kw.pop("object", None), "object"), _xy(self, kw)))
            else:
                raise UserError("each of 'objects' is a description or {\"object\": ..., \"at\": [x, y]}")
        if not isinstance(distractors, int) or isinstance(distractors, bool):
            raise UserError("distractors must be a whole number from 0 to 8")
        self.table.set_table(items, relation=_opt_text(relation), distractors=distractors)
        self._view = None
        self.version += 1
        return self.scene()

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

    @staticmethod
    def words() -> dict:
        """The words the page offers, read from the declarations: each channel with its values
        and default (what an object description may say), and the relation words the table
        can lay an object out in (a place beside another object; not stacking, not a size)."""
        placing = [w for w in relations.words()
                   if (r := relations.of_word(w)).offset is not None and not r.stacked and r.sizes is None]
        return {"channels": [{"name": c.name, "values": list(c.values), "default": c.default}
                             for c in channels.CHANNELS],
                "relations": placing}

    def scene(self) -> dict:
        """The table (trainer's truth, for editing) and what the agent will see of it."""
        view = self.view()
        cam = self.camera
        objs = []
        for i, o in enumerate(self.table.objects):
            u, v = cam.to_pixels(o.x, o.y)
            objs.append({"index": i, **o.appearance, "x": o.x, "y": o.y,
                         "px": [round(u, 1), round(v, 1)], "half_px": round(o.half * cam.width / cam.table.width, 1),
                         "distractor": o.distractor, "name": o.describe(), "seen_id": _seen_at(view.marks, u, v)})
        step = self._steps[-1] if self._steps else None
        return {"version": self.version, "objects": objs, "seen": [m.to_json() for m in view.marks],
                "highlight": view.highlight, "frames": len(view.frames), "scale": overlay.SCALE,
                "camera": {"width": cam.width, "height": cam.height}, "lessons": len(self.blocks),
                "next_seed": self.lesson_seed(),
                "relations": [{"from": a.src, "to": a.dst, "word": a.word} for a in view.arrows],
                "undo": None if step is None else {"what": step.what, "record": len(self.records)}}

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
                                                                 overlay=overlay_on, arrows=view.arrows))
            return view.pngs[overlay_on]
        if not isinstance(frame, int) or not 0 <= frame < len(view.frames):
            raise UserError(f"no frame {frame!r}; the last lesson has {len(view.frames)}")
        return overlay.png(overlay.draw(view.frames[frame], overlay=False))

    # ------------------------------------------------------------------ lessons
    def lesson(self, signal: object, content: object, *, as_said: tuple[str, ...] = ()) -> dict:
        """Give one lesson; returns the `aileen run --json` record. `as_said`: words the trainer
        means as said (`no`)."""
        if not isinstance(signal, str):
            raise UserError("'signal' must be a string: inform, verify or react")
        signal = SAME.get(signal, signal)
        if signal in VERDICTS:
            return self._verdict(signal)
        if signal == NO:
            return self._no()
        if signal not in SIGNALS:
            raise UserError(f"unknown signal {signal!r}; expected one of: "
                            f"{', '.join(SIGNALS + tuple(SAME) + VERDICTS + (NO,))}")
        content = "" if signal == "generate" and content in (None, "") else _text(content, "content")
        if len(content) > MAX_CONTENT:
            raise UserError(f"'content' is longer than {MAX_CONTENT} characters")
        if not self.table.objects and signal in ("generate", "react"):
            raise UserError("the table is empty: put an object on it first (type it, then click the table)")
        if signal == "react" and action_from_content(content) is None:
            raise UserError("react needs something to do, e.g. 'move the red box left of the blue cone' "
                            "or 'push the red box'")
        objects = self._ordered(content)
        action = action_from_content(content)
        n = len(self.blocks)
        seed = self.lesson_seed(n)
        block = transcript.lesson_block(signal, content, [o.spec() for o in objects], seed=seed,
                                        demonstrate=action is not None and signal != "react",
                                        note=f"console lesson {n + 1}", as_said=as_said)
        try:
            lesson = lessonfile.loads(block, path="<console>").lessons[0]
            rehearsal.check_curriculum([lesson], [seed], table=self.camera.table)
        except UserError as exc:
            raise _plain(exc, objects) from None
        step = self._step(signal)
        self._frames.clear()
        try:
            result = self.interp.run(lesson, index=n + 1, seed=seed)
        except UserError as exc:
            self._back(step)  # the agent may have learned part of it: all or nothing
            raise _plain(exc, objects) from None
        except BaseException:
            self._back(step)
            raise
        self._push(step)
        record = result.to_json()
        self.blocks.append(block)
        self.records.append(record)
        frames = list(self._frames)
        self._after(objects, frames[-1] if frames else None)
        seen = self.agent.state
        marks = _marks(seen) if seen is not None else []
        lit = sorted({i for ids in result.answer.referents.values() for i in ids})
        image = frames[-1].image if frames else self.view().image
        said = record.get("said") if signal == "generate" else content
        drawn = arrows(said or "", result.answer.referents, {m.id for m in marks},
                       denied=signal == "verify" and result.answer.result == "failure")
        self._view = View(image, marks, lit, [f.image for f in frames], arrows=drawn)
        self.image(overlay_on=True)  # drawn before the answer goes out, so the page shows it at once
        self.version += 1
        return record

    def _ordered(self, content: str) -> list[Placed]:
        """The table's objects, those an action sentence names first (mover, then reference):
        the trainer demonstrates and judges with objects 1 and 2, as in a lesson file."""
        objects = list(self.table.objects)
        action = action_from_content(content)
        if action is None:
            return objects
        phrases = read_content(content).phrases
        if len(phrases) != action.n_objects:
            example = "'move the red box left of the blue cone'" if action.relation else "'push the red box'"
            raise UserError(f"'{action.verb}' {'with a relation ' if action.relation else ''}names "
                            f"{'two objects' if action.n_objects == 2 else 'one object'}, e.g. {example}")
        picked = []
        for p in phrases:
            hits = [i for i, o in enumerate(objects) if p.fits(o.appearance.replace(size=None))]
            if len(hits) != 1:
                raise UserError(f"to demonstrate or judge, the table needs exactly one {p.describe()} (it has {len(hits)})")
            picked.append(hits[0])
        if len(set(picked)) != len(picked):
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
            moved.append(o if xy is None else Placed(o.appearance, float(xy[0]), float(xy[1]), o.distractor))
        if moved != list(self.table.objects):
            self.table.set_all(moved)

    def _no(self) -> dict:
        """The trainer's "no" to the agent's "did you mean 'box'?" about the last lesson's word:
        the word is meant as said; the lesson is given again with it (`Lesson.as_said`, written
        into the lesson file, so a replay learns the same)."""
        last = self.records[-1] if self.records else None
        if last is None or not last.get("asked_about"):
            raise UserError("'no' answers the agent's \"did you mean ...?\" about the last lesson; it asked nothing")
        return self.lesson(last["signal"], last["content"], as_said=(last["asked_about"],))

    def _verdict(self, what: str) -> dict:
        """The trainer's verdict on the last lesson: `wrong` after a verify (the agent learns
        from the near miss, or from what it failed to understand), `confirm` after a react that
        reached its goal (its trace becomes an example). The lesson file gets `feedback`, so a
        replay learns the same."""
        asks = {"wrong": "verify", "confirm": "react"}[what]
        if not self.records or self.records[-1]["signal"] != asks:
            raise UserError(f"'{what}' is a verdict on the last {asks} lesson; give one first")
        answer = Answer(what, "", "success")
        step = self._step(what)
        try:
            self.agent.told_wrong(answer) if what == "wrong" else self.agent.confirmed(answer)
        except ValueError as exc:
            self._back(step)
            raise UserError(str(exc)) from None
        except BaseException:
            self._back(step)
            raise
        self._push(step)
        self.blocks[-1] += f'feedback = "{what}"\n'
        record = {"index": len(self.records) + 1, "signal": what, "content": "", "result": answer.result,
                  "reason": None, "commands": answer.commands, "created": answer.created,
                  "stored": answer.stored, "referents": {}, "seen": [], "expected": None, "correct": None,
                  "seconds": 0.0}
        self.records.append(record)
        self.version += 1
        return record

    # ------------------------------------------------------------------ undo and forget
    def _step(self, what: str) -> _Step | None:
        """What undo needs to take back the step about to be made (None: this agent cannot
        be snapshotted, so the step cannot be undone)."""
        snap = getattr(self.agent, "snapshot", None)
        if snap is None:
            return None
        return _Step(what, snap(), list(self.table.objects), list(self.blocks), len(self.records))

    def _push(self, step: _Step | None) -> None:
        if step is None:
            self._steps.clear()  # an older step cannot be undone past one that cannot
            return
        self._steps.append(step)
        del self._steps[:-UNDO_LESSONS]

    def _back(self, step: _Step | None) -> None:
        """Everything as it was before `step` (a failed step, or an undone one)."""
        if step is None:
            return
        self.agent.restore(step.agent)
        self.table.restore(step.table)
        self.blocks[:] = step.blocks
        del self.records[step.records:]

    def undo_lesson(self) -> dict:
        """Take back the last lesson, verdict or forget: the memory, the table, the transcript
        as they were before it. Returns {"undone": its record (or the forget), "scene": ...}."""
        if not self._steps:
            raise UserError("no lesson to undo (undo reaches back over the lessons given since the server "
                            f"started, at most {UNDO_LESSONS})")
        step = self._steps.pop()
        undone = step.undone if step.undone is not None else self.records[step.records]
        self._back(step)
        self._view = None
        self.version += 1
        return {"undone": undone, "scene": self.scene()}

    def forget(self, name: object) -> dict:
        """Forget a concept (by symbol, `r_red`, or word, `red`): undo takes it back. Not a
        lesson: the downloaded lesson file does not forget."""
        if not isinstance(name, str) or not name.strip():
            raise UserError("'concept' must be a concept's symbol (r_red) or its word (red)")
        symbol = self._concept(name.strip())
        step = self._step("forget")
        if step is None:
            raise UserError("this agent cannot forget")
        word = self.agent.forget(symbol)
        step.undone = {"signal": "forget", "content": symbol, "word": word}
        self._push(step)
        self._view = None
        self.version += 1
        return {"forgot": symbol, "word": word, "concepts": len(self.agent.memory)}

    def _concept(self, name: str) -> str:
        mem = self.agent.memory
        if name in mem:
            return name
        for word in (name, name.replace(" ", "_"), name.replace("_", " ")):
            symbol = self.agent.semantic.concept(word)
            if symbol is not None and symbol in mem:
                return symbol
        known = ", ".join(c.symbol for c in mem.concepts()) or "none yet"
        raise UserError(f"no concept {name!r} in the memory (known: {known})")

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
            entry["concept_quality"] = entry["quality"]  # the memory's own figures (memory/quality.py)
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
        """Save the memory, then the table and transcript beside it (`state`), marked with the
        memory file they go with."""
        if not self.memory_path:
            raise UserError("the console was started without --memory, so there is nowhere to save")
        if self.memory_file is not None:
            self.memory_file.save(self.agent)
        else:
            self.agent.save(self.memory_path)
        self.save_state()
        return f"saved {len(self.agent.memory)} concepts to {self.memory_path}"

    def save_state(self) -> None:
        """The table and transcript beside the memory file, marked with the memory file as it
        is now (after the memory was saved)."""
        if not self.memory_path:
            return
        where = state.path_for(self.memory_path)
        try:
            state.write(where, state.Saved(self.version, list(self.table.objects), list(self.blocks),
                                           list(self.records), state.digest(self.memory_path)))
        except OSError as exc:
            raise UserError(f"saved the memory, but not the table and transcript: {exc.strerror or exc}",
                            path=str(where)) from None

    def resume(self) -> str | None:
        """At start: the table and transcript saved beside the memory file, when they go with
        the memory file as it is now. Returns a line to print, or None when there was nothing."""
        if not self.memory_path:
            return None
        where = state.path_for(self.memory_path)
        if not where.exists():
            return None
        saved = state.read(where)
        if saved.memory_sha256 != state.digest(self.memory_path):
            aside = state.aside_path(where)
            os.replace(where, aside)
            return (f"warning: {where} was saved with another version of {self.memory_path} (another run "
                    f"changed it); moved it to {aside} and started with an empty table")
        self.table.restore(saved.objects)
        self.blocks = list(saved.blocks)
        self.records = list(saved.records)
        self.version = saved.version + 1  # a page open before the restart reloads
        self._view = None
        return (f"restored the table ({len(saved.objects)} objects) and {len(saved.blocks)} lessons "
                f"from {where}")


def _marks(seen_state) -> list[overlay.Mark]:
    return [overlay.Mark(s.id, s.percepts, s.box_px, s.under) for _, s in sorted(seen_state.objects.items())]


def _seen_at(marks: list[overlay.Mark], u: float, v: float) -> str | None:
    """The agent's id for the object whose centre is at camera pixel (u, v): the perceived box
    around that pixel, the nearest centre first; None when the agent saw nothing there."""
    best, best_d = None, float("inf")
    for m in marks:
        if m.under is not None:
            continue  # kept in mind, not seen: the pixel shows what lies over it
        u0, v0, u1, v1 = m.box_px
        if u0 - 2 <= u <= u1 + 2 and v0 - 2 <= v <= v1 + 2:
            d = ((u0 + u1) / 2 - u) ** 2 + ((v0 + v1) / 2 - v) ** 2
            if d < best_d:
                best, best_d = m.id, d
    return best


def arrows(sentence: str, referents: dict[str, list[str]], seen: set[str], *,
           denied: bool = False) -> list[overlay.Arrow]:
    """The relation a sentence states, between the objects its phrases grounded to: an arrow
    from the first phrase's object to the second's, with the relation's words as said ("not
    left of" when the agent `denied` it). The trainer's reading of its own sentence finds the
    relation words (`relations.phrases`)."""
    text = " " + " ".join(sentence.lower().split()) + " "
    for spelling, _word in relations.phrases():
        at = text.find(f" {spelling} ")
        if at >= 0:
            break
    else:
        return []
    before = [k for k in referents if 0 <= text.find(k.lower()) < at]
    after = [k for k in referents if text.find(k.lower(), at + len(spelling) + 1) > at]
    if len(before) != 1 or len(after) != 1:
        return []
    pairs = [(a, b) for a in referents[before[0]] for b in referents[after[0]] if a != b and a in seen and b in seen]
    return [overlay.Arrow(a, b, f"not {spelling}" if denied else spelling) for a, b in pairs[:4]]


def _plain(exc: UserError, objects: list[Placed]) -> UserError:
    """A lesson's error as the person at the console reads it: without the lesson file's
    place (`<console>:3: lesson 1: ...`) and step numbers, which are the console's own
    bookkeeping, and with the objects named as on the table, not `obj1`."""
    text = re.sub(r"^lesson \d+: ", "", exc.message)
    text = re.sub(r"^demonstration step \d+ \(.*?\): ", "", text)
    if "not clearly false at the start" in text and len(objects) >= 2:
        text = (f"the {objects[0].describe()} is already there: move it elsewhere first, so that the "
                "demonstration shows the change")
    elif "not clearly false at the start" in text:
        text = "that is already so on the table: change the table first, so that the demonstration shows the change"

    def name(m: re.Match) -> str:
        k = int(m.group(1)) - 1
        return f"the {objects[k].describe()}" if 0 <= k < len(objects) else m.group(0)

    return UserError(re.sub(r"\bobj(\d+)\b", name, text))


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
