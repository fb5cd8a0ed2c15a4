"""Exam scenes recorded once per trial and replayed to the agent after every lesson.

Why: a trial gives the same 10 exam items after each of its 20-24 lessons, and the items never
change (their layout seeds are fixed per trial): only the learner does. Laying each item out,
rendering it and running vision on it again after every lesson was most of a trial's time.
`record` does the trainer's and the camera's part once (layout, demonstration, images, and what
the visual module reports for each image); `ExamTape.replay` gives the agent exactly the inputs
it would have had (the same images, the same detections, the same pointing) and asks it the
same question. `Replayer` is the perceiver that serves the recorded detections: the agent's own
code is unchanged, and its vision ran on these very images when they were recorded.

A demonstration the trainer cannot carry out is an error here, never a free "failure" answer
that a specificity exam would count as right.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from aileen.agent import Agent, Answer
from aileen.agent.body import WorldBody
from aileen.perception.perceiver import Detection, Perceiver
from aileen.curriculum import demonstration, grading, trainer
from aileen.curriculum.lesson import Lesson
from aileen.errors import UserError
from aileen.reasoning.asp import RulesTimeout
from aileen.reasoning.planner import NoPlan
from aileen.world.camera import DEFAULT_CAMERA, Camera
from aileen.world.render import Frame


@dataclass(frozen=True)
class Look:
    """One image the agent gets, what its vision reports for it, and the trainer's hand
    before it (None for the first look of a scene, (action, u, v) for a demonstration step;
    u and v are None for a `place`)."""

    image: np.ndarray
    detections: tuple[Detection, ...]
    step: tuple[str, float | None, float | None] | None = None


@dataclass(frozen=True)
class ExamTape:
    """One verify lesson as the agent experiences it, and what a correct learner answers."""

    lesson: Lesson
    looks: tuple[Look, ...]
    expected: str
    sector: str | None = None  # ground truth, for the evaluation's sector ceiling (experiments/ceiling.py)
    # ground truth, for the ideal observer (experiments/ideal.py): the direction, in degrees, of
    # the object said first seen from the one said second
    direction: float | None = None

    @property
    def demonstrated(self) -> bool:
        return len(self.looks) > 1

    def replay(self, agent: Agent, replayer: "Replayer") -> Answer:
        """The agent's answer to the recorded lesson (as `Interpreter.run` would give it)."""
        first, rest = self.looks[0], self.looks[1:]
        agent.new_scene()
        replayer.serve(first)
        agent.perceive(first.image)
        demo_start = None
        if self.demonstrated:
            demo_start = agent.episode_now()
            for look in rest:
                assert look.step is not None
                action, u, v = look.step
                replayer.serve(look)
                agent.watch(action, u, v, look.image)
        try:
            return agent.verify(self.lesson.content, demo_start=demo_start)
        except (UserError, NoPlan) as exc:
            if isinstance(exc, RulesTimeout):
                raise
            reason = exc.message if isinstance(exc, UserError) else str(exc)
            return Answer("verify", self.lesson.content, "failure", reason)


class Replayer:
    """A perceiver: the recorded detections of the image being replayed, else the live one."""

    def __init__(self, live: Perceiver) -> None:
        self.live = live
        self._next: Look | None = None

    def serve(self, look: Look) -> None:
        self._next = look

    def __call__(self, image: np.ndarray) -> list[Detection]:
        look, self._next = self._next, None
        if look is None:
            return self.live(image)
        if look.image is not image:
            raise RuntimeError("the replayed image is not the one recorded")
        return list(look.detections)


def record(lesson: Lesson, seed: int, perceiver: Perceiver, *, camera: Camera = DEFAULT_CAMERA,
           noise: float = 0.0, on_frame: Callable[[Frame], None] | None = None) -> ExamTape:
    """Lay out (and demonstrate) a verify lesson once, as `Interpreter.run` would, keeping
    every image the agent would get and what `perceiver` reports for it."""
    if lesson.signal != "verify":
        raise ValueError(f"only verify lessons are exam items, not {lesson.signal!r}")
    setup = trainer.layout(lesson, seed=seed, table=camera.table)
    body = WorldBody(setup.world, camera, seed=seed, noise=noise, on_frame=on_frame)

    def look(step: tuple[str, float | None, float | None] | None = None) -> Look:
        image = body.look()
        return Look(image, tuple(perceiver(image)), step)

    looks = [look()]
    if lesson.action is not None or lesson.demonstration is not None:
        world = setup.world
        for step in demonstration.demonstrate(lesson, setup, seed=seed):
            hand = demonstration.pointing(world, step, camera)  # as a lesson's demonstration shows it
            u, v = hand if hand is not None else (None, None)
            demonstration.execute(world, step)
            looks.append(look((step.action, u, v)))
    expected = grading.expected(lesson, setup)
    if expected is None:
        raise RuntimeError(f"the trainer cannot grade exam item {lesson.content!r}")
    from aileen.experiments.ceiling import sector_of
    from aileen.experiments.ideal import said_direction

    return ExamTape(lesson, tuple(looks), expected, sector_of(lesson, setup), said_direction(lesson, setup))


def record_all(lessons: Sequence[Lesson], seeds: Sequence[int], perceiver: Perceiver, **kw) -> list[ExamTape]:  # noqa: ANN003
    return [record(lesson, s, perceiver, **kw) for lesson, s in zip(lessons, seeds, strict=True)]
