"""The exact footprint of an object on the table, and the clearance between two footprints.

Why: the QSRs and the trainer's relations read the axis-aligned box around each footprint
(QSRlib's definitions, `geometry.py`), which is the footprint itself only for a box square to
the table. Two spheres 0.135 m apart on a diagonal leave 3.5 cm between them, but their boxes
meet; a check that asks whether two objects overlap on the table (the trainer's, after
physics settles a hand-placed lesson) must read the footprints as the physics does
(`physics.collision_shape`: a circle, a turned square, a rounded segment for a lying capsule).

A footprint is a convex core (a point, a segment or a square's corners) grown by a radius, so
the clearance of two is the distance between their cores less both radii. Pure arithmetic in
table metres; no pymunk (its `shapes_collide` asserts on shapes whose boxes meet but whose
outlines do not). The detector's training data lay objects out with polygons of their own
(`perception/dataset.py`: round shapes as circumscribed 24-gons, a little larger than these),
kept so that a data set made again with a recipe's seed is the same.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from aileen.world import catalog

__all__ = ["Footprint", "capsule_parts", "clearance", "footprint"]

Point = tuple[float, float]


@dataclass(frozen=True)
class Footprint:
    """A convex core (1, 2 or 4 points, in order round it) grown by `radius` metres."""

    core: tuple[Point, ...]
    radius: float


def footprint(shape: str, side: float, angle: float, x: float, y: float) -> Footprint:
    """The footprint of an object of `shape` whose footprint measures `side` (a box's side, a
    round object's diameter, a capsule's length), turned by `angle` radians, centred at (x, y)."""
    c, s = math.cos(angle), math.sin(angle)

    def at(u: float, v: float) -> Point:
        return x + c * u - s * v, y + s * u + c * v

    if shape in catalog.SQUARE_FOOTPRINTS:
        h = side / 2.0
        return Footprint((at(-h, -h), at(h, -h), at(h, h), at(-h, h)), 0.0)
    w = catalog.ELONGATED_FOOTPRINTS.get(shape)
    if w is not None:
        r, a = capsule_parts(side, w)
        return Footprint((at(-a, 0.0), at(a, 0.0)), r)
    return Footprint(((x, y),), side / 2.0)


def capsule_parts(length: float, width_ratio: float) -> tuple[float, float]:
    """A lying capsule of `length` whose width is `width_ratio` of it (a stadium): the radius
    of its round ends and half the length of its axis."""
    return 0.5 * length * width_ratio, 0.5 * length * (1.0 - width_ratio)


def clearance(a: Footprint, b: Footprint) -> float:
    """The distance between two footprints, metres; 0 or less when they touch or overlap
    (then less the deeper, for round ones exactly)."""
    return _core_distance(a.core, b.core) - a.radius - b.radius


def _core_distance(p: Sequence[Point], q: Sequence[Point]) -> float:
    if _intersect(p, q):
        return 0.0
    return min(min(_to_segment(v, e0, e1) for v in p for e0, e1 in _edges(q)),
               min(_to_segment(v, e0, e1) for v in q for e0, e1 in _edges(p)))


def _edges(poly: Sequence[Point]) -> list[tuple[Point, Point]]:
    if len(poly) == 1:
        return [(poly[0], poly[0])]
    if len(poly) == 2:
        return [(poly[0], poly[1])]
    return [(poly[k], poly[(k + 1) % len(poly)]) for k in range(len(poly))]


def _to_segment(v: Point, a: Point, b: Point) -> float:
    dx, dy = b[0] - a[0], b[1] - a[1]
    n = dx * dx + dy * dy
    t = 0.0 if n == 0.0 else max(0.0, min(1.0, ((v[0] - a[0]) * dx + (v[1] - a[1]) * dy) / n))
    return math.hypot(v[0] - a[0] - t * dx, v[1] - a[1] - t * dy)


def _intersect(p: Sequence[Point], q: Sequence[Point]) -> bool:
    """Do two convex cores share a point? Separating axes: every edge's normal of either
    (a segment's too), and for two points their own line."""
    if len(p) == 1 and len(q) == 1:
        return p[0] == q[0]
    axes = [(e0[1] - e1[1], e1[0] - e0[0]) for poly in (p, q) for e0, e1 in _edges(poly) if e0 != e1]
    if len(p) <= 2 and len(q) <= 2:  # segments (or a point and a segment): their directions too
        axes += [(e1[0] - e0[0], e1[1] - e0[1]) for poly in (p, q) for e0, e1 in _edges(poly) if e0 != e1]
    for ax, ay in axes:
        lo_p, hi_p = _span(p, ax, ay)
        lo_q, hi_q = _span(q, ax, ay)
        if hi_p < lo_q or hi_q < lo_p:
            return False
    return True


def _span(poly: Sequence[Point], ax: float, ay: float) -> tuple[float, float]:
    d = [x * ax + y * ay for x, y in poly]
    return min(d), max(d)
