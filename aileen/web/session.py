"""One teaching session: an agent, the trainer's table, the lessons given, what the agent saw.

Framework-free: the HTTP app (`aileen.web.app`) calls it, and so can tests and scripts. Every
lesson goes through the same path as `aileen run`: the session writes the lesson as lesson-file
text (objects at their exact positions, the seed), parses it with the lesson-file reader and
runs it with the lesson interpreter. The downloadable transcript is that text, so `aileen run`
replays the session to the same answers (from the same starting memory).

This module holds the session's state and gives its lessons, verdicts and forgets; the other
jobs it once did are modules of their own, so each stays small and readable alone:
`edits` (the page's table requests), `view` (the preview and the marks the page draws),
`history` (undo), `transcript` (the session as a lesson file), `concepts` (the memory panel),
`state` (the table and transcript kept beside the memory file). Their names that were
importable from here still are.
"""

from __future__ import annotations

import threading

from aileen.agent import Agent, Answer
from aileen.agent.protocol import VERDICTS as JUDGES, give_verdict
from aileen.curriculum import grading, lessonfile, rehearsal
from aileen.curriculum.grading import CONFIRM_REFUSED
from aileen.curriculum.interpreter import Interpreter
from aileen.curriculum.plain import plain
from aileen.curriculum.sentences import action_from_content, read_content
from aileen.errors import UserError
from aileen.memory.store import SaveRefused
from aileen.web import concepts, edits, history, overlay, state, transcript
from aileen.web.history import Step
from aileen.web.table import Placed, TableEdit
from aileen.web.view import View, after_lesson, objects_json, preview
from aileen.world.camera import DEFAULT_CAMERA, Camera
from aileen.world.render import Frame

# Names that lived here before the split, re-exported for callers that import them from here.
from aileen.web.edits import EDITS  # noqa: F401
from aileen.web.edits import number as _number, opt_text as _opt_text, text as _text  # noqa: F401
from aileen.web.history import UNDO_LESSONS, Step as _Step  # noqa: F401
from aileen.web.view import arrows, marks_of as _marks, seen_at as _seen_at  # noqa: F401

SIGNALS = ("inform", "verify", "react", "generate")
# Signals other work adds to the agent; the console offers them when the agent has the method.
VERDICTS = tuple(JUDGES)  # the trainer's verdict on the last verify / react
NO = "no"  # the trainer's answer to the agent's "did you mean 'box'?": the word is meant as said
OPPOSITE = {"success": "failure", "failure": "success"}  # what a "wrong" says the answer should have been
SAME = {"describe": "generate"}  # the console's word for a signal
MAX_CONTENT = 200  # characters in one sentence


class Stale(Exception):
    """An edit made on a table the page no longer shows (another tab changed it): HTTP 409."""

    def __init__(self, given: object, now: int) -> None:
        super().__init__(f"the table changed since this page last saw it (version {given!r}, now {now}); "
                         "it is shown as it is now, and nothing was done")
        self.message = str(self)
        self.version = now


class Session:
    """The state behind the console. Not thread-safe: the app serialises requests."""

    def __init__(self, agent: Agent, *, seed: int = 0, memory_path: str | None = None, memory_file=None,
                 camera: Camera = DEFAULT_CAMERA, eyes: Agent | None = None, replay: tuple[str, ...] = (),
                 autosave: bool = False) -> None:
        """`replay`: the options `aileen run` needs to replay the session (`commands.replay_options`).
        `autosave`: save the memory, table and transcript after every lesson, verdict, undo and
        forget (`aileen serve --autosave`), so a killed server loses at most the request under way."""
        self.agent = agent
        self.autosave = autosave
        self.replay = replay
        # the copy of the memory the transcript started from (`state.keep_start`), and whether
        # it is known: a transcript restored from before the console kept one has none
        self.start_memory: str | None = None
        self.start_known = memory_path is None
        self.seed = seed
        self.memory_path = memory_path
        self.memory_file = memory_file  # aileen.memory.store.MemoryFile: locked, saves with recovery
        self.camera = camera
        self.eyes = eyes if eyes is not None else Agent(camera=camera)
        self.table = TableEdit(camera.table, seed=seed)
        self.blocks: list[str] = []  # the transcript, one lesson-file block per lesson
        self.records: list[dict] = []  # each lesson's `aileen run --json` record
        self.version = 0  # bumped on every change the page must redraw; edits may carry it (409 if stale)
        self._history = history.History()  # for undo
        self._frames: list[Frame] = []
        self.interp = Interpreter(agent, camera=camera, on_frame=self._frames.append)
        self._view: View | None = None
        # held while a request's work runs (in a worker thread): a stop that gives up waiting
        # for the request still saves only once its lesson is done, never a memory mid-lesson
        self.busy = threading.Lock()

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

    # ------------------------------------------------------------------ the table (`edits`)
    def set_table(self, objects: object, relation: object = None, distractors: object = 0) -> dict:
        """The whole table in one call (`edits.set_table`); returns the scene."""
        edits.set_table(self.table, self.camera, objects, relation, distractors)
        return self._changed()

    def edit(self, op: str, **kw) -> dict:
        """One edit of the table: add, move, remove, clear, shuffle, layout, undo (`edits.edit`)."""
        edits.edit(self.table, self.camera, op, kw)
        return self._changed()

    def _changed(self) -> dict:
        self._view = None
        self.version += 1
        return self.scene()

    words = staticmethod(edits.words)

    # ------------------------------------------------------------------ what the page shows (`view`)
    def scene(self) -> dict:
        """The table (trainer's truth, for editing) and what the agent will see of it."""
        view = self.view()
        cam = self.camera
        step = self._history.last
        return {"version": self.version, "objects": objects_json(self.table.objects, cam, view.marks),
                "seen": [m.to_json() for m in view.marks],
                "highlight": view.highlight, "frames": len(view.frames), "scale": overlay.SCALE,
                "camera": {"width": cam.width, "height": cam.height}, "lessons": len(self.blocks),
                "next_seed": self.lesson_seed(),
                "relations": [{"from": a.src, "to": a.dst, "word": a.word} for a in view.arrows],
                "undo": None if step is None else {"what": step.what, "record": len(self.records)}}

    def view(self) -> View:
        if self._view is None:
            self._view = preview(self.table.objects, self.camera, self.eyes, self.lesson_seed())
        return self._view

    def image(self, *, overlay_on: bool, frame: int | None = None) -> bytes:
        return self.view().png(overlay_on=overlay_on, frame=frame)

    # ------------------------------------------------------------------ lessons
    def lesson(self, signal: object, content: object, *, as_said: tuple[str, ...] = (),
               again: bool = False) -> dict:
        """Give one lesson; returns the `aileen run --json` record. `as_said`: words the trainer
        means as said (`no`); `again`: the lesson is the last one given again (`no`), one
        lesson of the file, not two."""
        if not isinstance(signal, str):
            raise UserError("'signal' must be a string: inform, verify or react")
        signal = SAME.get(signal, signal)
        # describe and the verdicts take no sentence; one sent with them is not read (the page
        # sent its text box with every signal, and describe demonstrated "move the red box
        # ..." and wrote it into the lesson file)
        if signal in VERDICTS:
            return self._verdict(signal)
        if signal == NO:
            return self._no()
        if signal not in SIGNALS:
            raise UserError(f"unknown signal {signal!r}; expected one of: "
                            f"{', '.join(SIGNALS + tuple(SAME) + VERDICTS + (NO,))}")
        content = "" if signal == "generate" else edits.text(content, "content")
        if len(content) > MAX_CONTENT:
            raise UserError(f"'content' is longer than {MAX_CONTENT} characters")
        if not self.table.objects and signal in ("generate", "react"):
            raise UserError("the table is empty: put an object on it first (type it, then click the table)")
        if signal == "react" and action_from_content(content) is None:
            raise UserError("react needs something to do, e.g. 'move the red box left of the blue cone' "
                            "or 'push the red box'")
        objects = self._ordered(content)
        action = action_from_content(content)
        n = len(self.blocks) - 1 if again else len(self.blocks)
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
        del self.blocks[n:]
        self.blocks.append(block)
        self.records.append(record)
        frames = list(self._frames)
        self._after(objects, frames[-1] if frames else None)
        seen = self.agent.state  # what the agent saw, taken before any preview
        image = frames[-1].image if frames else self.view().image
        said = record.get("said") if signal == "generate" else content
        self._view = after_lesson(seen, result.answer.referents, image, frames, said,
                                  denied=signal == "verify" and result.answer.result == "failure")
        self.image(overlay_on=True)  # drawn before the answer goes out, so the page shows it at once
        self.version += 1
        return self._kept(record)

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
        the word is meant as said; the lesson is given again with it (`Lesson.as_said`), and
        the lesson file holds it once, with `as_said`, as a run gives it: the agent asks, the
        trainer says no. (Written twice, a replay took the word as said from the first copy on,
        the trainer saying it in two lessons, and learned what the console had not.)"""
        last = self.records[-1] if self.records else None
        if last is None or not last.get("asked_about"):
            raise UserError("'no' answers the agent's \"did you mean ...?\" about the last lesson; it asked nothing")
        return self.lesson(last["signal"], last["content"], as_said=(last["asked_about"],), again=True)

    def _verdict(self, what: str) -> dict:
        """The trainer's verdict on the last lesson: `wrong` after a verify (the agent learns
        from the near miss, or from what it failed to understand), `right` after a verify (a
        "no" to a relation it knows becomes a near miss of it), `confirm` after a react that
        reached its goal (its trace becomes an example). The lesson file gets `feedback`, so a
        replay learns the same."""
        asks = JUDGES[what]
        if not self.records or self.records[-1]["signal"] != asks:
            raise UserError(f"'{what}' is a verdict on the last {asks} lesson; give one first")
        last = self.records[-1]
        if what == "confirm" and not grading.confirmable(last.get("goal_holds"), last["result"] == "success"):
            # as a lesson file's run (`Interpreter._feedback`): a replay of the downloaded file
            # ignored it, and the agent had stored a "move" in which nothing moved
            raise UserError(CONFIRM_REFUSED)
        answer = Answer(what, "", "success")
        step = self._step(what)
        try:
            give_verdict(self.agent, what, answer)
        except ValueError as exc:
            self._back(step)
            raise UserError(str(exc)) from None
        except BaseException:
            self._back(step)
            raise
        self._push(step)
        last = self.records[-1]
        # a lesson file's `feedback = "wrong"` is the trainer's verdict as it grades: `right`
        # is written as that verdict with the person's answer as what is expected
        self.blocks[-1] += f'feedback = "{"wrong" if what == "right" else what}"\n'
        if what == "right" and last.get("expected") != last["result"] and last["result"] in OPPOSITE:
            self.blocks[-1] += f'expect = "{last["result"]}"\n'
        if what == "wrong" and last.get("expected") is not None and last["expected"] == last["result"]:
            # The person at the console says wrong where the trainer's own grading found the
            # answer right (their word is not the trainer's): the file says what they expect,
            # or its replay takes the verdict as the trainer's and lets the answer stand.
            self.blocks[-1] += f'expect = "{OPPOSITE[last["result"]]}"\n'
        # a verdict's record carries the number of the lesson it judges
        record = {"index": last["index"], "signal": what, "content": "", "result": answer.result,
                  "reason": None, "commands": answer.commands, "created": answer.created,
                  "stored": answer.stored, "referents": {}, "seen": [], "expected": None, "correct": None,
                  "seconds": 0.0}
        self.records.append(record)
        self.version += 1
        return self._kept(record)

    # ------------------------------------------------------------------ undo and forget (`history`)
    def _step(self, what: str) -> Step | None:
        return history.before(what, self.agent, self.table, self.blocks, self.records)

    def _push(self, step: Step | None) -> None:
        self._history.push(step)

    def _back(self, step: Step | None) -> None:
        history.back(step, self.agent, self.table, self.blocks, self.records)

    def undo_lesson(self) -> dict:
        """Take back the last lesson, verdict or forget: the memory, the table, the transcript
        as they were before it. Returns {"undone": its record (or the forget), "scene": ...}."""
        step = self._history.pop()
        undone = step.undone if step.undone is not None else self.records[step.records]
        self._back(step)
        self._view = None
        self.version += 1
        return self._kept({"undone": undone, "scene": self.scene()})

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
        return self._kept({"forgot": symbol, "word": word, "concepts": len(self.agent.memory)})

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
        return transcript.session_file(self.blocks, seed=self.seed, start=self.start_memory,
                                       known=self.start_known, options=self.replay)

    def memory(self) -> dict:
        return concepts.memory_json(self.agent, self.records, saved_to_file=bool(self.memory_path))

    def save(self) -> str:
        """Save the memory, then the table and transcript beside it (`state`), marked with the
        memory file they go with. A save that went to a recovery file (`SaveRefused`) keeps them
        beside that file instead, and says so: stamped beside the memory file, they claimed a
        file another program wrote, and the next start restored lessons that never taught it."""
        if not self.memory_path:
            raise UserError("the console was started without --memory, so there is nowhere to save")
        if self.memory_file is not None:
            try:
                self.memory_file.save(self.agent)
            except SaveRefused as exc:
                raise self._beside_recovery(exc) from None
        else:
            self.agent.save(self.memory_path)
        self.save_state()
        return f"saved {len(self.agent.memory)} concepts to {self.memory_path}"

    def keep(self) -> str:
        """For the way out: save, and say in one line where the memory went and, separately,
        what became of the table and transcript; never raises a `UserError`. (A failed state
        save said only "saved the memory, but not the table ...", though the memory had gone
        to a recovery file it never named.)"""
        assert self.memory_file is not None, "keep is for a session on a held memory file"
        try:
            self.memory_file.save(self.agent)
        except SaveRefused as exc:
            return self._beside_recovery(exc).format()
        note = self.memory_file.saved_note()
        try:
            self.save_state()
        except UserError as exc:
            return f"{note}; {exc.format()}"
        return note

    def _beside_recovery(self, exc: SaveRefused) -> SaveRefused:
        """`exc`, after keeping the table and transcript beside the recovery file that holds
        the memory (`m.recovered-PID.console.json`, stamped with that file), saying where."""
        if exc.recovered is None:
            return exc.adding("the table and transcript were not kept (no memory file to go with)")
        try:
            state.keep(exc.recovered, self.version, self.table.objects, self.blocks, self.records)
        except UserError as err:
            return exc.adding(err.format())
        return exc.adding(f"the table and transcript are beside it in {state.path_for(exc.recovered)}")

    def _kept(self, answer: dict) -> dict:
        """`answer`, after saving what changed when autosaving. A save that fails (the disk full,
        the file changed by another program) does not take back the lesson: the answer carries
        the one-line reason (`autosave_error`: where the memory went instead), as `save` says it."""
        if self.autosave and self.memory_path:
            try:
                self.save()
            except UserError as exc:
                return {**answer, "autosave_error": exc.format()}
        return answer

    def save_state(self) -> None:
        """The table and transcript beside the memory file (`state.keep`), after the memory was saved."""
        if not self.memory_path:
            return
        state.keep(self.memory_path, self.version, self.table.objects, self.blocks, self.records)

    def resume(self) -> str | None:
        """At start: the table and transcript saved beside the memory file, when they go with
        the memory file as it is now. Returns a line to print, or None when there was nothing."""
        if not self.memory_path:
            return None
        saved, line = state.recall(self.memory_path, self.camera.table)
        start = state.start_path_for(self.memory_path)
        if saved is None:  # a new transcript: it starts from the memory as it is now
            self.start_memory, self.start_known = str(state.keep_start(self.memory_path, self.agent)), True
        elif start.is_file():
            self.start_memory, self.start_known = str(start), True
        if saved is not None:
            self.table.restore(saved.objects)
            self.blocks = list(saved.blocks)
            self.records = list(saved.records)
            self.version = saved.version + 1  # a page open before the restart reloads
            self._view = None
        return line


def _plain(exc: UserError, objects: list[Placed]) -> UserError:
    """A lesson's error as the person at the console reads it (`curriculum.plain`): without
    the lesson file's place (`<console>:3: lesson 1: ...`) and step numbers, and with the
    objects named as on the table, not `obj1`."""
    return UserError(plain(exc.message, [o.describe() for o in objects]))


def _xy(session: Session, kw: dict) -> tuple[float, float] | None:
    """Kept from before the split for callers that import it from here: `edits.spot`."""
    return edits.spot(session.camera, kw)
