"""The world's object records: what the simulator keeps of each object, and what it hands out.

Split from `aileen.world.sim` so that module holds one job, the `World` and its actions; this
one holds the records those actions work on. `WorldObject` is the frozen snapshot every reader
gets (the trainer, the camera, grading); `Entry` is the simulator's own mutable state of one
object, with its pymunk parts; `State` is everything a World holds, in one object so a copy is
one step. `build` makes fresh pymunk parts for records from their states alone, which is what
lets a settle start from a canonical space and a copy replay its original exactly.

The footprint arithmetic (`footprint_half_extents`) lives here, beside `WorldObject.box_m`,
because the scenes' layouts and the camera's patches measure footprints the same way.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from aileen.world import catalog
from aileen.world.footprints import Footprint, capsule_parts, footprint
from aileen.world import physics as engine
from aileen.world.appearance import Appearance, BodyChannels
from aileen.world.physics import PhysicsConfig

__all__ = ["WorldObject", "SettleReport", "Entry", "State", "footprint_half_extents", "footprint_half_extent",
           "snapshot", "build"]


@dataclass(frozen=True)
class WorldObject(BodyChannels):
    """A snapshot of one object: simulator ground truth. The agent never reads it.

    A held object keeps the position it had when it was picked up (`held=True`); it is not
    on the table and the camera does not draw it.
    """

    id: str
    appearance: Appearance  # every channel's value: shape, colour, size, then any declared look
    shade: int
    x: float
    y: float
    angle: float
    held: bool
    level: int = 0  # 0 on the table, 1 resting on another object
    on: str | None = None  # the id of the object it rests on

    @property
    def footprint(self) -> float:
        """Side (box), diameter (round shapes) or length (capsule) of the footprint, in metres."""
        return catalog.SIZES[self.size]

    def outline(self) -> Footprint:
        """The exact footprint where the object stands (`footprints.footprint`)."""
        return footprint(self.shape, self.footprint, self.angle, self.x, self.y)

    def box_m(self) -> tuple[float, float, float, float]:
        """Axis-aligned box (x0, y0, x1, y1) around the footprint, the rotation included."""
        hx, hy = footprint_half_extents(self.shape, self.footprint, self.angle)
        return self.x - hx, self.y - hy, self.x + hx, self.y + hy


def footprint_half_extents(shape: str, footprint: float, angle: float) -> tuple[float, float]:
    """Half the width and half the depth of the axis-aligned box around an object's footprint.

    A box rotated by `angle` covers `side * (|cos| + |sin|)` both ways; a round shape is the
    same in every direction; a lying capsule (a stadium of length `footprint`, width `w` x
    that) covers its axis's projection plus its round ends.
    """
    if shape in catalog.SQUARE_FOOTPRINTS:
        h = 0.5 * footprint * (abs(math.cos(angle)) + abs(math.sin(angle)))
        return h, h
    w = catalog.ELONGATED_FOOTPRINTS.get(shape)
    if w is not None:
        r, a = capsule_parts(footprint, w)
        return a * abs(math.cos(angle)) + r, a * abs(math.sin(angle)) + r
    return 0.5 * footprint, 0.5 * footprint


def footprint_half_extent(shape: str, footprint: float, angle: float) -> float:
    """Half the side of the axis-aligned square that covers an object's footprint (the
    larger of `footprint_half_extents`)."""
    return max(footprint_half_extents(shape, footprint, angle))


@dataclass(frozen=True)
class SettleReport:
    """What a `settle()` did: who moved how far (m), how many steps, whether all came to rest."""

    moved: dict[str, float]
    steps: int
    settled: bool


@dataclass
class Entry(BodyChannels):
    """One object's simulator state: its catalog kind and its pymunk parts."""

    id: str
    appearance: Appearance
    shade: int
    body: engine.Body
    poly: engine.Shape
    joints: tuple[engine.Constraint, ...]
    held: bool = False
    level: int = 0
    on: str | None = None
    rest: tuple[float, float, float] = (0.0, 0.0, 0.0)  # offset (x, y, angle) in the frame of what it rests on


@dataclass
class State:
    """Everything a World holds, kept in one object so `copy()` is one deepcopy."""

    space: engine.Space
    entries: dict[str, Entry] = field(default_factory=dict)
    held: str | None = None
    next_id: int = 1
    last_pointed: str | None = None


def snapshot(e: Entry) -> WorldObject:
    """The frozen snapshot of one record, as readers of the world see it."""
    px, py = e.body.position
    return WorldObject(e.id, e.appearance, e.shade, float(px), float(py), float(e.body.angle), e.held,
                       e.level, e.on)


def build(space: engine.Space, physics: PhysicsConfig, entries: list[Entry]) -> None:
    """Fresh pymunk parts for `entries` (objects on the table) from their states, added to
    `space`: bodies and shapes first, then each object's joints (to the table, or to the
    object it rests on)."""
    for e in entries:
        side = catalog.SIZES[e.size]
        b = e.body
        e.body = engine.rigid_body(physics, e.shape, side, b.position, b.angle, b.velocity, b.angular_velocity)
        e.poly = engine.collision_shape(physics, e.body, e.shape, side, e.level)
        space.add(e.body, e.poly)
    by_id = {e.id: e for e in entries}
    for e in entries:
        lower = by_id.get(e.on) if e.on is not None else None
        if lower is not None:
            e.joints = engine.rest_joints(lower.body, e.body)
        else:
            load = sum(o.body.mass for o in entries if o.on == e.id)
            e.joints = engine.friction_joints(physics, space, e.body, catalog.SIZES[e.size], e.body.mass + load)
        space.add(*e.joints)
