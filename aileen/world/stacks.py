"""Stacking and pushing rules of the table top, apart from the physics that carries them out.

The simulator (`aileen.world.sim`, the only pymunk module) asks these functions whether a
stack may be built, where the upper object goes, and how far a push goes; they decide from
plain numbers, so the rules are testable and readable without the physics. Each refusal is
a `UserError` whose one line says why, since a trainer or an agent that asks for an
impossible stack or push must learn what was wrong, and nothing in the world changes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from aileen.errors import NoRoom, UserError
from aileen.world import catalog

# A flat top carries an object; a sphere or a cone does not.
FLAT_TOPS: tuple[str, ...] = ("box", "cylinder")
# A stack is at most this many objects high (level 0 on the table, level 1 on top).
MAX_HEIGHT = 2
# Where a placed object's centre goes over the object it is put on, in units of that one's half
# width: off-centre, so the camera still sees part of the lower object (centred, an upper object
# as large as the lower one hides it). The agent's placements onto an object
# (`aileen.perception.regions.on_top_of`) and the trainer's "on" layouts
# (`aileen.domain.relation_kinds.on`) both draw from it.
ON_TOP_OFFSET = (0.7, 0.95)


@dataclass(frozen=True)
class Support:
    """What the rules need to know of the object asked to carry another."""

    id: str
    shape: str
    x: float
    y: float
    angle: float
    footprint: float  # side or diameter, metres
    level: int  # 0 on the table
    carries: str | None  # the id of what already rests on it
    held: bool


def check_stack(upper: str, support: Support) -> None:
    """Refuse a stack that cannot hold: onto itself, a held object, a round top, a loaded
    object or one that is already up on another."""
    what = f"cannot place {upper} on {support.id}"
    if support.id == upper:
        raise UserError(f"{what}: an object cannot rest on itself")
    if support.held:
        raise UserError(f"{what}: {support.id} is held, not on the table")
    if support.shape not in FLAT_TOPS:
        raise UserError(f"{what}: a {support.shape} has no flat top (only a {' or a '.join(FLAT_TOPS)} can carry an object)")
    if support.carries is not None:
        raise UserError(f"{what}: {support.carries} already rests on it")
    if support.level + 1 >= MAX_HEIGHT:
        raise UserError(f"{what}: it rests on another object, and a stack is at most {MAX_HEIGHT} objects high")


def is_over(support: Support, x: float, y: float) -> bool:
    """Whether the point (x, y) lies over the support's footprint (a turned square for a
    box, a disk for a cylinder): an object whose centre is there rests on it."""
    dx, dy = x - support.x, y - support.y
    r = support.footprint / 2.0
    if support.shape in catalog.SQUARE_FOOTPRINTS:
        c, s = math.cos(support.angle), math.sin(support.angle)
        return abs(dx * c + dy * s) <= r and abs(-dx * s + dy * c) <= r
    return dx * dx + dy * dy <= r * r


def stack_position(support: Support, x: float | None, y: float | None) -> tuple[float, float]:
    """Where the upper object's centre goes: (x, y) when it lies over the support, else the
    support's centre (a hand that misses the top a little still sets the object on it)."""
    if x is not None and y is not None and is_over(support, float(x), float(y)):
        return float(x), float(y)
    return support.x, support.y


def check_pick_up(obj_id: str, carries: str | None) -> None:
    """The lower object of a stack cannot be lifted from under what rests on it."""
    if carries is not None:
        raise UserError(f"cannot pick up {obj_id}: {carries} rests on it; pick up {carries} first")


def check_push(obj_id: str, *, carries: str | None, on: str | None) -> None:
    """A push moves one object on the table: not a loaded one, not one up on a stack."""
    if carries is not None:
        raise UserError(f"cannot push {obj_id}: {carries} rests on it and would fall off; pick up {carries} first")
    if on is not None:
        raise UserError(f"cannot push {obj_id}: it rests on {on}, not on the table")


def push_target(obj_id: str, y: float, half_extent: float, footprint: float, depth: float) -> float:
    """The y the object's centre is pushed to (one footprint north), or a UserError when
    that would carry it over the table's far edge."""
    target = y + footprint
    if target + half_extent > depth + 1e-9:
        room = max(0.0, depth - half_extent - y)
        raise NoRoom(
            f"cannot push {obj_id}: one footprint ({footprint:.2f} m) north would push it off the table's far edge "
            f"(only {room:.3f} m of room)"
        )
    return target
