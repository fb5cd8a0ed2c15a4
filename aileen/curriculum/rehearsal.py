"""A rehearsal of a curriculum: every lesson laid out (and its action shown) once, before the
run, so a bad lesson file fails before anything is learned or saved.

It does what `Interpreter.run` will do with the same seed (name the open objects, make up a
false sentence, lay out, demonstrate), and hands the tables it drew to the run.
"""

from __future__ import annotations

from collections.abc import Iterable

from aileen.curriculum import falsehood, placeholders, trainer
from aileen.curriculum.demonstration import demonstrate
from aileen.curriculum.lesson import Lesson
from aileen.curriculum.stage import DEFAULT_MARGIN, LayoutError, Setup, Skip
from aileen.world.camera import Table

__all__ = ["check_curriculum"]


#: A file of at least this many lessons shows a bar while they are laid out (`progress`).
PROGRESS_FROM = 200


def check_curriculum(lessons: Iterable[Lesson], seeds: Iterable[int], *, table: Table = Table(),
                     margin: float = DEFAULT_MARGIN, skip: bool = False,
                     progress: str | None = None) -> "list[Setup | Skip | None]":
    """Lay out (and demonstrate) every lesson once, so a bad lesson fails before anything runs.

    Raises the first lesson's located `UserError`, e.g. a hand position off the table. Cheap
    (a few ms per lesson): run it before loading or changing a memory file, so an invalid
    lesson file leaves the memory untouched. Returns the laid-out tables (a demonstration is
    checked on a copy, so they are as `layout` made them; None for a `say_false` lesson):
    `Interpreter.run(..., setup=)` runs the lesson on its table instead of laying it out again.
    A lesson the trainer cannot lay out (`trainer.LayoutError`) is no mistake in the file: with
    `skip` it gets a `Skip` with the reason (the run skips it), else the error is raised.
    `progress` (the file's name) shows a bar on standard error for a long file.
    """
    out: list[Setup | Skip | None] = []
    lessons = list(lessons)
    pairs: Iterable = zip(lessons, seeds, strict=True)
    if progress is not None and len(lessons) >= PROGRESS_FROM:  # a long file: seconds before the first lesson
        from tqdm import tqdm

        pairs = tqdm(pairs, total=len(lessons), desc=f"laying out {progress}", unit="lesson", leave=False)
    for lesson, seed in pairs:
        if lesson.skip is not None:
            out.append(Skip(lesson.skip))
            continue
        lesson = placeholders.name(lesson, seed=seed)  # as `Interpreter.run` will, with the same seed
        reuse = not lesson.say_false  # a false sentence is made up again with the table it is run on
        try:
            if lesson.say_false:
                lesson, setup = falsehood.prepare(lesson, seed=seed, table=table)
            else:
                setup = trainer.layout(lesson, seed=seed, table=table, margin=margin)
            if lesson.demonstration is not None:
                demonstrate(lesson, setup, seed=seed, margin=margin)
        except LayoutError as exc:
            if not skip:
                raise
            out.append(Skip(exc.reason))
            continue
        out.append(setup if reuse else None)
    return out
