"""The lesson interpreter: the trainer's side of guided participation.

For each lesson it lays out the scene (the trainer knows what the words mean), lets the
agent look, demonstrates the action if there is one (the agent watches every step), gives
the signal, and grades the answer against the trainer's own ground truth. Only images and
the trainer's pointing reach the agent.
"""

from __future__ import annotations

import os
import re
import time
from collections import Counter
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from pathlib import Path

from aileen.agent import Answer, Learner
from aileen.agent.body import WorldBody
from aileen.agent.records import not_understood
from aileen.curriculum import demonstration, falsehood, grading, placeholders, trainer
from aileen.curriculum.lesson import Curriculum, Lesson, Step
from aileen.errors import UserError
from aileen.reasoning.asp import RulesError
from aileen.reasoning.language import NotUnderstood
from aileen.reasoning.planner import NoPlan
from aileen.world.camera import DEFAULT_CAMERA, Camera
from aileen.world.render import Frame


@dataclass
class LessonResult:
    index: int  # 1-based within its curriculum
    lesson: Lesson
    answer: Answer
    seen: list[str]  # what the agent perceived, one line per object
    expected: str | None  # what a correct learner answers (None: the trainer cannot tell)
    goal_holds: bool | None = None  # react: does the trainer see the goal reached?
    seconds: float = 0.0
    image: str | None = None
    table: list[str] = field(default_factory=list)  # the trainer's ground-truth layout
    # The trainer's table after the lesson (ground truth, for the evaluation only; never shown
    # to the agent, never serialised).
    setup: "trainer.Setup | None" = field(default=None, repr=False, compare=False)
    said_true: bool | None = None  # generate: is what the agent said true of the table?
    # Why the trainer could not lay the lesson out (the agent got nothing); None when it ran.
    skipped: str | None = None
    notes: list[str] = field(default_factory=list)  # what the trainer changed to lay it out
    # Why a verify is left ungraded although it has an expected answer: its file contradicts
    # itself (`grading.contradiction`); None otherwise.
    ungraded: str | None = None

    @property
    def correct(self) -> bool | None:
        if self.skipped is not None or not self.answer.understood:
            return None  # a sentence the agent could not read is no answer: not graded
        if self.lesson.signal == "react":
            return self.goal_holds
        if self.lesson.signal == "generate" or self.answer.said is not None:
            return self.said_true  # "where is X?" too: is what it said true of the table?
        if self.expected is None:
            return None
        if self.answer.unknown_words and self.answer.result == "failure":
            return False  # "I do not know the word" says nothing of the table: no right "no"
        return self.answer.result == self.expected

    def to_json(self) -> dict:
        a = self.answer
        out = {
            "index": self.index,
            "signal": a.signal,
            "content": a.content,
            "result": a.result,
            "reason": a.reason,
            "commands": a.commands,
            "created": a.created,
            "stored": a.stored,
            "referents": a.referents,
            "typicality": a.typicality,
            "seen": self.seen,
            "expected": self.expected,
            "correct": self.correct,
            "understood": a.understood,
            "seconds": round(self.seconds, 4),
        }
        if a.signal == "react":
            out.update(steps=a.steps, projections=a.projections, goal_holds=self.goal_holds)
        if a.signal == "generate" or a.said is not None:
            out["said"] = a.said
        if self.image:
            out["image"] = self.image
        if self.notes:
            out["layout_notes"] = self.notes
        if self.skipped is not None:
            out["skipped"] = self.skipped
        if self.ungraded is not None:
            out["ungraded"] = self.ungraded
        if a.question is not None:
            out["question"] = a.question
            out["asked_about"] = a.asked_about
        return out


def close_agent(agent: object) -> None:
    """Shut down what an agent holds (the Soar agent's kernel), on every exit path."""
    close = getattr(agent, "close", None)
    if close is not None:
        close()


# Standard deviation of the camera's sensor noise (0-255 scale): a real camera is never clean;
# this is inside the range the detector was trained and evaluated on (0-3).
CAMERA_NOISE = 2.0


class Interpreter:
    """Runs lessons for one learner (any `Learner`: the ASP agent, the Soar agent, a baseline).
    `seed` fixes layouts, demonstrations and camera noise."""

    def __init__(
        self,
        agent: Learner,
        *,
        camera: Camera = DEFAULT_CAMERA,
        save_images: str | os.PathLike[str] | None = None,
        noise: float = CAMERA_NOISE,
        on_frame: "Callable[[Frame], None] | None" = None,
    ) -> None:
        self.agent = agent
        self.on_frame = on_frame
        self.camera = camera
        self.save_images = Path(save_images) if save_images is not None else None
        self.noise = noise
        # Words the trainer means as said: when the agent asks "did you mean 'box'?" about
        # one of them ("rox"), the trainer answers "no" and asks again (`meant_as_said`).
        self.as_said: frozenset[str] = frozenset()
        # A lesson file's verify whose expected answer contradicts its own table is left
        # ungraded (`grading.contradiction`); off for the experiments, which draw their own.
        self.files_contradict = False

    def mean_as_said(self, lessons: "Iterable[Lesson]") -> None:
        """Take as meant the words a run's lessons say in more than one lesson: a trainer who
        says "rox" in six lessons (the original's conjunctive words: "rox", "kone", "nleft
        of") means a word of its own, where a slip ("the red bx" once) is a slip; the agent's
        question about a slip skips its lesson."""
        self.as_said = words_said_often(lessons)

    def run(self, lesson: Lesson, *, index: int, seed: int,
            setup: "trainer.Setup | trainer.Skip | None" = None) -> LessonResult:
        """Lay the lesson out (or take `setup`, laid out by `rehearsal.check_curriculum` with the
        same seed and not used since), show it, ask, grade. A `trainer.Skip` (a lesson
        `check_curriculum` could not lay out) is skipped: the result says why, and the agent sees
        nothing of it. Laying out here, a `trainer.LayoutError` is raised (experiments draw
        lessons that fit; a lesson left out silently would change their curves)."""
        t0 = time.perf_counter()
        if lesson.skip is not None:
            return self._skipped(lesson, index, lesson.skip, t0)
        lesson = placeholders.name(lesson, seed=seed)  # objects left open are drawn and named
        if isinstance(setup, trainer.Skip):
            return self._skipped(lesson, index, setup.reason, t0)
        if setup is None or lesson.say_false:
            # a negative original lesson gets its false sentence here, from the laid-out table
            lesson, setup = falsehood.prepare(lesson, seed=seed, table=self.camera.table)
        body = WorldBody(setup.world, self.camera, seed=seed, noise=self.noise, on_frame=self.on_frame)
        agent = self.agent
        agent.new_scene()
        image = body.look()
        agent.perceive(image)
        seen = agent.describe_scene()
        image_path = self._save(image, index, "scene")
        goal_holds = None
        try:
            answer, asked = self._ask(lesson, setup, body, seed)
        except (UserError, NoPlan) as exc:
            if isinstance(exc, RulesError):  # the rules, not this lesson: the run stops (and saves) with exit 2
                raise type(exc)(f"{exc.message} (lesson {index}: {lesson.signal} {lesson.content!r})",
                                   path=exc.path, line=exc.line) from None
            # A lesson the agent cannot carry out is that lesson's failure, with its reason;
            # the run goes on, and what was learned so far is kept. A sentence it cannot read
            # (an agent that does not say so itself) is not understood, never a failure.
            reason = exc.message if isinstance(exc, UserError) else str(exc)
            answer = (not_understood(lesson.signal, lesson.content, reason) if isinstance(exc, NotUnderstood)
                      else Answer(lesson.signal, lesson.content, "failure", reason))
            asked = []
        if lesson.signal == "react":
            if lesson.action is not None:
                goal_holds = grading.goal_holds(lesson, setup.world, setup.ids, setup.start)
            self._save(body.look(), index, "after")
        # Inform lessons are not graded (learning from them is the point); verify lessons are
        # graded against the trainer's ground truth, react lessons by the goal in the world.
        expected = grading.expected(lesson, setup) if lesson.signal == "verify" else None
        ungraded = grading.contradiction(lesson, setup) if self.files_contradict else None
        # a lesson whose file says both answers is not graded, but its verdict is the teacher's
        # word, given as the file says it (a console's session file writes a person's `wrong`
        # with their `expect`, where their "right of" is not the trainer's: its replay had
        # dropped the verdict, and answered the next question otherwise)
        self._feedback(lesson, answer, lesson.expect if ungraded else expected, goal_holds)
        if ungraded is not None:
            expected = None
        result = LessonResult(index, lesson, answer, seen, expected, goal_holds, time.perf_counter() - t0,
                              image_path, setup.describe(), setup=setup, notes=[*setup.notes, *asked],
                              ungraded=ungraded)
        if answer.question is not None:
            # a word one edit from a known one ("bx") that the lessons do not say again: the
            # agent asks, the trainer takes it for a slip and cannot say what was meant, so the
            # lesson is reported and skipped (nothing was learned from it)
            result.skipped = f"the agent asks: {answer.reason}"
        if answer.said and answer.understood:
            # graded as a person would: is what it said true of the table?
            result.said_true = grading.content_true(answer.said, setup.world.objects())  # None: not graded
        return result

    @staticmethod
    def _skipped(lesson: Lesson, index: int, reason: str, t0: float) -> LessonResult:
        answer = Answer(lesson.signal, lesson.content, "skipped", reason)
        return LessonResult(index, lesson, answer, [], None, seconds=time.perf_counter() - t0, skipped=reason)

    def _ask(self, lesson: Lesson, setup: trainer.Setup, body: WorldBody, seed: int) -> tuple[Answer, list[str]]:
        """Give the lesson's signal (after the demonstration, if any); the agent's answer, and
        the trainer's answers to the agent's questions about words (`as_said`): each "no"
        gives the signal again, the demonstration already seen."""
        demo_start = None
        if lesson.signal != "react" and (lesson.action is not None or lesson.demonstration is not None):
            demo_start = self.demonstrate(lesson, setup, body, seed=seed)
        answer = self._signal(lesson, body, demo_start)
        told: list[str] = []
        take = getattr(self.agent, "take_as_said", None)
        while (answer.question is not None and answer.asked_about is not None and take is not None
               and len(told) < MAX_WORD_QUESTIONS
               and (meant_as_said(answer.asked_about, self.as_said) or _said_as(answer.asked_about, lesson.as_said))):
            told.append(f"the agent asked: {answer.reason}; the trainer: no, '{answer.asked_about}' as said")
            take(answer.asked_about)
            answer = self._signal(lesson, body, demo_start)
        return answer, told

    def _signal(self, lesson: Lesson, body: WorldBody, demo_start: int | None) -> Answer:
        agent = self.agent
        if lesson.signal == "react":
            return agent.react(lesson.content, body)
        if lesson.signal == "inform":
            return agent.inform(lesson.content, demo_start=demo_start)
        if lesson.signal == "generate":
            return agent.generate(lesson.content)
        return agent.verify(lesson.content, demo_start=demo_start)

    def _feedback(self, lesson: Lesson, answer: Answer, expected: str | None, goal_holds: bool | None) -> None:
        """The trainer's verdict, when the lesson asks for it: "wrong" after a verify answer
        that is wrong (always, when the trainer cannot judge), the answer let stand after one
        that is right (`told_right`), "confirm" after a react whose
        goal the trainer sees reached (or cannot grade: `grading.confirmable`). The agent's stores go on the lesson's answer."""
        if lesson.feedback == "wrong" and lesson.signal == "verify" and answer.result != expected:
            self.agent.told_wrong(answer)
        elif lesson.feedback == "wrong" and lesson.signal == "verify" and expected is not None:
            self.agent.told_right(answer)
        elif lesson.feedback == "confirm" and lesson.signal == "react" and grading.confirmable(goal_holds, answer.ok):
            self.agent.confirmed(answer)

    def run_all(self, lessons: Curriculum | Iterable[Lesson], *, seed: int = 0) -> Iterator[LessonResult]:
        for i, lesson in enumerate(lessons):
            own = lesson.seed
            yield self.run(lesson, index=i + 1, seed=own if own is not None else seed * 1000 + i)

    def demonstrate(self, lesson: Lesson, setup: trainer.Setup, body: WorldBody, *, seed: int) -> int:
        """The trainer demonstrates the lesson's action while the agent watches; returns the
        episode index where the demonstration started (for the agent's trace)."""
        start = self.agent.episode_now()
        for step in demonstration.demonstrate(lesson, setup, seed=seed):
            self._show(step, setup, body)
        return start

    def _show(self, step: Step, setup: trainer.Setup, body: WorldBody) -> None:
        """The trainer does one step while the agent watches: it sees where the hand goes
        (the pixel of the object touched), then the table afterwards."""
        world = setup.world
        hand = demonstration.pointing(world, step, self.camera)
        u, v = hand if hand is not None else (None, None)
        demonstration.execute(world, step)
        self.agent.watch(step.action, u, v, body.look())

    def _save(self, image, index: int, what: str) -> str | None:
        if self.save_images is None:
            return None
        from aileen.world.render import save_png

        path = self.save_images / f"lesson{index:03d}-{what}.png"
        try:
            self.save_images.mkdir(parents=True, exist_ok=True)
            save_png(image, str(path))
        except OSError as exc:
            raise UserError(f"cannot save the camera image: {exc.strerror or exc}", path=str(path)) from None
        return str(path)


#: The most questions about words the trainer answers in one lesson (one per word said).
MAX_WORD_QUESTIONS = 4


def _words(content: str) -> list[str]:
    return re.findall(r"[a-z0-9]+", content.lower())


def words_said_often(lessons: "Iterable[Lesson]") -> frozenset[str]:
    """The words that more than one of the lessons says (each lesson counted once)."""
    seen: Counter[str] = Counter()
    for lesson in lessons:
        seen.update(set(_words(lesson.content or "")))
    return frozenset(w for w, n in seen.items() if n > 1)


def _said_as(word: str, as_said: "tuple[str, ...]") -> bool:
    """Is `word` one the lesson itself says is meant as said (`Lesson.as_said`)?"""
    return _words(word) in [_words(w) for w in as_said]


def meant_as_said(word: str, often: frozenset[str]) -> bool:
    """Is the word the agent asked about ("rox", "nleft of") one the trainer means as said:
    every one of its words said in more than one lesson?"""
    ws = _words(word)
    return bool(ws) and all(w in often for w in ws)

