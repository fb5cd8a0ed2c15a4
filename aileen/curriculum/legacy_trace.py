"""Does an original-format lesson's `trace-actions` show its action? Played once, at load.

Why: the original's instructor demonstrated whatever trace a script wrote, so a "move ... left
of ..." whose trace only points at the object, or places it right of the other, taught "left
of" from a table that shows no such thing. The trainer lays the lesson out, plays the trace as
it would demonstrate it and grades the end state with the goal a react is graded by
(`grading.goal_holds`). A trace that does not reach the goal is no lesson to learn from: it is
skipped with the reason (`Lesson.skip`), as a lesson the trainer cannot lay out is. A lesson
the trainer cannot lay out here is left to the run, which says why.
"""

from __future__ import annotations

import dataclasses

from aileen.curriculum import grading, placeholders, trainer
from aileen.curriculum.demonstration import demonstrate, execute
from aileen.curriculum.lesson import Lesson
from aileen.curriculum.stage import LayoutError

__all__ = ["shortfall"]


def shortfall(lesson: Lesson, *, seed: int) -> str | None:
    """Why the lesson's demonstration does not reach its action's goal, or None (it does, the
    lesson has no demonstration or action, or the trainer cannot lay it out at `seed`: the run
    says why). A trace that cannot be played at all ("place" before "pick-up") stays the
    located `UserError` the run would raise."""
    if lesson.demonstration is None or lesson.action is None:
        return None
    lesson = placeholders.name(lesson, seed=seed)
    try:
        setup = trainer.layout(dataclasses.replace(lesson, distractors=0), seed=seed)
        steps = demonstrate(lesson, setup, seed=seed)
    except LayoutError:
        return None
    world = setup.world.copy()
    for step in steps:
        execute(world, step)
    if grading.goal_holds(lesson, world, setup.ids, setup.start):
        return None
    shown = ", ".join(str(s) for s in lesson.demonstration)
    return (f"its trace-actions ({shown}) do not show '{lesson.action.name}': after them the goal does not "
            "hold, so there is nothing to learn the word from")
