"""The sizes of a lesson's objects: as the lesson says, else what its relation needs.

A comparative ("larger than") is laid out with a larger and a smaller object, fitting a size
the lesson gives for one of them; a lesson whose given sizes cannot show it is said so before
any layout is tried (issue 22: the original's comparative scripts). Split from the trainer,
which asks these before it places anything.
"""

from __future__ import annotations

import numpy as np

from aileen.curriculum.lesson import Lesson
from aileen.domain import relations
from aileen.world import catalog

__all__ = ["ruled_out", "sizes"]


class _Sized:
    """A catalogued size, for asking a comparative about two sizes alone."""

    def __init__(self, size: str) -> None:
        self.size = size


def ruled_out(lesson: Lesson) -> str | None:
    """Why the sizes the lesson gives rule its comparative out (no sizes for the objects it
    leaves open would fit), or None: "blue cone (large) cannot be larger than green sphere
    (large)". A near miss is ruled out by sizes that make the relation hold."""
    rel = relations.get(lesson.relation) if lesson.relation else None
    if rel is None or rel.sizes is None or len(lesson.objects) < 2:
        return None
    a, b = lesson.objects[0], lesson.objects[1]
    for sa in catalog.SIZES:
        for sb in catalog.SIZES:
            if a.size in (None, sa) and b.size in (None, sb) and rel.accepts(_Sized(sa), _Sized(sb)) != lesson.near_miss:
                return None
    if lesson.near_miss:
        return f"the sizes given rule out the near miss: {a.describe()} is always {lesson.relation} {b.describe()}"
    return f"the sizes given rule it out: {a.describe()} cannot be {lesson.relation} {b.describe()}"


def sizes(lesson: Lesson, rng: np.random.Generator) -> list[str]:
    """Each described object's size: as said, else what the lesson's relation needs (a
    comparative draws a larger and a smaller one, fitting a size the lesson gives for one of
    them), else the default."""
    sizes = [spec.size for spec in lesson.objects]
    rel = relations.get(lesson.relation) if lesson.relation else None
    draw = rel.near_miss_sizes if (rel is not None and lesson.near_miss) else (rel.sizes if rel else None)
    if draw is not None and len(sizes) >= 2:
        for _ in range(50):
            sa, sb = draw(rng)
            if sizes[0] in (None, sa) and sizes[1] in (None, sb):
                sizes[0], sizes[1] = sa, sb
                break
    return [s or catalog.DEFAULT_SIZE for s in sizes]
