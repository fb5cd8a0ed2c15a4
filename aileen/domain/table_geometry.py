"""The table geometry the trainer's relation kinds read (`relation_kinds.py`): the clearance
between two footprints, a footprint's extent, the bearing of one object from another, whether
an object rests on another or stands on the table, and the two placements every layout is
made of (a point on a ring about a heading; the centre distance at which two squares touch).

Split from `relation_kinds.py` so that a kind of relation reads as what it accepts and how it
is laid out, not as trigonometry. Frame: metres, +x east, +y north (docs/architecture.md).
"""

from __future__ import annotations

import math
from typing import Protocol

import numpy as np

__all__ = ["OnTable", "angle_from", "extent", "gap", "on_table", "resting_on", "ring", "touch_length"]


class OnTable(Protocol):
    """Anything with a centre, a footprint box in table metres and a size (a `WorldObject`)."""

    x: float
    y: float
    size: str

    def box_m(self) -> tuple[float, float, float, float]: ...


def gap(a: OnTable, b: OnTable) -> float:
    """Clearance between the two footprint boxes in metres; <= 0 when they touch or overlap."""
    ax0, ay0, ax1, ay1 = a.box_m()
    bx0, by0, bx1, by1 = b.box_m()
    return max(bx0 - ax1, ax0 - bx1, by0 - ay1, ay0 - by1)


def extent(p: OnTable) -> float:
    """The longer side of a footprint box, metres."""
    x0, y0, x1, y1 = p.box_m()
    return max(x1 - x0, y1 - y0)


def angle_from(heading: float, a: OnTable, b: OnTable) -> float:
    """Degrees between `heading` (radians) and the bearing of a from b; 180 when they coincide."""
    dx, dy = a.x - b.x, a.y - b.y
    if math.hypot(dx, dy) < 1e-9:
        return 180.0
    diff = math.atan2(dy, dx) - heading
    diff = (diff + math.pi) % (2 * math.pi) - math.pi
    return abs(math.degrees(diff))


def resting_on(a: OnTable, b: OnTable) -> bool:
    """Does a rest on b (a stack)?"""
    return getattr(a, "on", None) == getattr(b, "id", object())


def on_table(p: OnTable) -> bool:
    """Does p stand on the table itself (not on another object, not held)?"""
    return getattr(p, "on", None) is None and not getattr(p, "held", False)


def ring(rng: np.random.Generator, heading: float, half_angle: float, length: float) -> tuple[float, float]:
    """An offset `length` from the origin, within `half_angle` degrees of `heading` (radians)."""
    theta = heading + math.radians(rng.uniform(-half_angle, half_angle))
    return length * math.cos(theta), length * math.sin(theta)


def touch_length(heading: float, fa: float, fb: float, g: float) -> float:
    """Centre distance along `heading` at which two axis-aligned squares have gap g."""
    c, s = abs(math.cos(heading)), abs(math.sin(heading))
    return (0.5 * (fa + fb) + g) / max(c, s)
