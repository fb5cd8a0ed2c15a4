"""The simulated table top: a pymunk world seen from above, and the primitive actions.

This module is the `World`: its building, reading and actions. The records it keeps of each
object (`WorldObject`, `SettleReport`, the internal `Entry` and `State`, the footprint
arithmetic) are `aileen.world.records`, split off so each file holds one job; they are
re-exported here, their home before the split, so `from aileen.world.sim import WorldObject`
keeps working.

The table is a plane in metres (origin at the south-west corner, +x east, +y north; see
`aileen.world.camera`). The pymunk parts and the step loop are `aileen.world.physics` (the
only module that imports pymunk): top-down, friction with the table as velocity-only joints,
a low rim so nothing leaves the table.

Placing an object into others overlaps their footprints; pymunk's penetration correction
pushes them apart over a few steps. That correction moves positions without adding velocity,
so "at rest" is detected by polling both velocities and the movement in the last step.

Stacks: every object lives in a layer, its level (0 on the table, 1 resting on another
object), and collides only with objects of its own layer (a pymunk shape filter per layer).
An object on another is tied to it by a rigid pivot and gear joint instead of the table
friction, so it rides along when the lower one slides, and the lower one's table friction
counts both masses. The rules (what may carry what, where a push ends) are in
`aileen.world.stacks`.

Push: `push_away` drives a kinematic hand, which touches only the pushed object, north at a
walking pace for about one footprint; the object shoves whatever it runs into, and after the
hand lets go everything slides to rest under friction.

Determinism: there is no hidden randomness. The same seed and the same calls replay the same
floating-point operations, so positions agree exactly (the tests require 1e-9).
"""

from __future__ import annotations

import copy as _copy
import math
from collections.abc import Mapping

import numpy as np

from aileen.errors import UserError, said_number
from aileen.world import catalog, stacks
from aileen.world import physics as engine
from aileen.world.appearance import Appearance, complete
from aileen.world.camera import Table
from aileen.world.physics import PhysicsConfig
from aileen.world.records import (  # re-exported: their home before the split
    Entry,
    SettleReport,
    State,
    WorldObject,
    build,
    footprint_half_extent,
    footprint_half_extents,
    snapshot,
)

__all__ = ["Table", "WorldObject", "SettleReport", "World", "PhysicsConfig", "footprint_half_extents",
           "footprint_half_extent"]

MOVED_EPS = 1e-4  # m: a settle reports an object as moved when it moved further than this
PUSH_SPEED = 0.25  # m/s: the hand's pace (slow, so what it shoves does not fly off)


class World:
    """A pymunk table top with primitive actions `point`, `pick_up`, `place` and `settle`.

    Every action checks its arguments first and raises `UserError` before it changes
    anything, so a failed action leaves the world exactly as it was.
    """

    def __init__(self, table: Table = Table(), *, seed: int = 0, physics: PhysicsConfig = PhysicsConfig()) -> None:
        self.table = table
        self.seed = seed
        self.physics = physics
        # Randomness that belongs to the world (scene generators may draw from it); seeded.
        self.rng = np.random.default_rng(seed)
        self._s = State(space=engine.new_space(self.table, self.physics))

    # ----------------------------------------------------------------- building

    def _check_on_table(self, shape: str, size: str, x: float, y: float, angle: float, what: str) -> None:
        if not (math.isfinite(x) and math.isfinite(y) and math.isfinite(angle)):
            raise UserError(f"{what}: position ({x}, {y}) and angle {angle} must be finite numbers")
        hx, hy = footprint_half_extents(shape, catalog.SIZES[size], angle)
        tol = 1e-5  # m: resting objects may sit a few micrometres into the rim
        if not (
            hx - tol <= x <= self.table.width - hx + tol and hy - tol <= y <= self.table.depth - hy + tol
        ):
            raise UserError(
                f"{what}: ({said_number(x)}, {said_number(y)}) is off the table; a {size} {shape} needs its centre within "
                f"x in [{hx:.3f}, {self.table.width - hx:.3f}], y in [{hy:.3f}, {self.table.depth - hy:.3f}] m"
            )

    def add(
        self,
        shape: str,
        colour: str,
        x: float,
        y: float,
        *,
        size: str = catalog.DEFAULT_SIZE,
        shade: int = 0,
        angle: float = 0.0,
        **looks: str,
    ) -> str:
        """Put a new object on the table at (x, y) and return its id (`obj1`, `obj2`, ...).

        A channel declared beyond shape, colour and size is given by its name
        (`texture="striped"`); one not given shows its default. It does not settle: a scene
        is built first and settled (if at all) once.
        """
        return self.put(Appearance(shape=shape, colour=colour, size=size, **looks), x, y, shade=shade, angle=angle)

    def put(self, appearance: Mapping[str, str], x: float, y: float, *, shade: int = 0, angle: float = 0.0) -> str:
        """`add` for an object described by its appearance (a size left out is the default)."""
        shape, colour = appearance.get("shape"), appearance.get("colour")
        size = appearance.get("size", catalog.DEFAULT_SIZE)
        catalog.check_shape(shape)
        catalog.check_colour(colour)
        catalog.check_size(size)
        looks = complete({**appearance, "size": size})
        n_shades = len(catalog.SHADES[colour])
        if not (isinstance(shade, (int, np.integer)) and 0 <= shade < n_shades):
            raise UserError(f"shade {shade!r} for {colour}: expected an integer in 0..{n_shades - 1}")
        x, y, angle = float(x), float(y), float(angle)
        self._check_on_table(shape, size, x, y, angle, f"cannot add a {colour} {shape}")
        side = catalog.SIZES[size]
        body = engine.rigid_body(self.physics, shape, side, (x, y), angle, (0.0, 0.0), 0.0)
        poly = engine.collision_shape(self.physics, body, shape, side)
        joints = engine.friction_joints(self.physics, self._s.space, body, side)
        obj_id = f"obj{self._s.next_id}"
        self._s.next_id += 1
        entry = Entry(obj_id, looks, int(shade), body, poly, joints)
        self._s.space.add(body, poly, *joints)
        self._s.entries[obj_id] = entry
        return obj_id

    def remove(self, obj_id: str) -> None:
        """Take an object out of the world for good (held or not)."""
        entry = self._entry(obj_id)
        if not entry.held:
            self._s.space.remove(entry.body, entry.poly, *entry.joints)
        else:
            self._s.held = None
        for other in self._s.entries.values():
            if other.on == obj_id:  # what rested on it drops to the table where it is
                other.on, other.level = None, 0
                other.poly.filter = engine.layer_filter(0)
        del self._s.entries[obj_id]
        if self._s.last_pointed == obj_id:
            self._s.last_pointed = None

    # ----------------------------------------------------------------- reading

    def _entry(self, obj_id: str) -> Entry:
        try:
            return self._s.entries[obj_id]
        except (KeyError, TypeError):
            known = ", ".join(self._s.entries) or "none"
            raise UserError(f"no object {obj_id!r} in the world; objects: {known}") from None

    def _carried_by(self, obj_id: str) -> str | None:
        """The id of the object resting on `obj_id`, if any."""
        for e in self._s.entries.values():
            if e.on == obj_id:
                return e.id
        return None

    def carries(self, obj_id: str) -> str | None:
        """The id of the object resting on `obj_id`, or None."""
        self._entry(obj_id)
        return self._carried_by(obj_id)

    def objects(self) -> list[WorldObject]:
        """All objects in insertion order, held ones included (`held=True`)."""
        return [snapshot(e) for e in self._s.entries.values()]

    def get(self, obj_id: str) -> WorldObject:
        return snapshot(self._entry(obj_id))

    def __contains__(self, obj_id: object) -> bool:
        return obj_id in self._s.entries

    def __len__(self) -> int:
        return len(self._s.entries)

    @property
    def held(self) -> str | None:
        """The id of the held object, or None when the hand is empty."""
        return self._s.held

    @property
    def last_pointed(self) -> str | None:
        """The object most recently pointed at (None if none, or if it was removed)."""
        return self._s.last_pointed

    # ----------------------------------------------------------------- actions

    def point(self, obj_id: str) -> None:
        """Point at an object: no physical effect; remembered as `last_pointed`."""
        self._entry(obj_id)
        self._s.last_pointed = obj_id

    def pick_up(self, obj_id: str) -> None:
        """Lift an object off the table; it is then held (at most one at a time)."""
        entry = self._entry(obj_id)
        if entry.held:
            raise UserError(f"cannot pick up {obj_id}: it is already held")
        if self._s.held is not None:
            raise UserError(f"cannot pick up {obj_id}: already holding {self._s.held}; place it first")
        stacks.check_pick_up(obj_id, self._carried_by(obj_id))
        self._s.space.remove(entry.body, entry.poly, *entry.joints)
        entry.body.velocity = (0.0, 0.0)
        entry.body.angular_velocity = 0.0
        entry.held = True
        entry.on, entry.level = None, 0  # the lower object, if any, is free again
        self._s.held = obj_id

    def _support(self, obj_id: str) -> stacks.Support:
        e = self._entry(obj_id)
        p = e.body.position
        return stacks.Support(e.id, e.shape, float(p.x), float(p.y), float(e.body.angle), catalog.SIZES[e.size],
                              e.level, self._carried_by(obj_id), e.held)

    def place(
        self, obj_id: str, x: float, y: float, *, angle: float | None = None, onto: str | None = None
    ) -> SettleReport:
        """Put the held object down at (x, y), then settle; returns the settle report.

        Placing into other objects pushes them (and the placed one) apart, as on a real table.
        With `onto`, the object goes on top of that one instead: at (x, y) if that lies over
        its footprint, else centred on it (see `aileen.world.stacks` for what is refused).
        """
        entry = self._entry(obj_id)
        if self._s.held is None:
            raise UserError(f"cannot place {obj_id}: nothing is held")
        if self._s.held != obj_id:
            raise UserError(f"cannot place {obj_id}: the held object is {self._s.held}")
        new_angle = float(entry.body.angle if angle is None else angle)
        level = 0
        if onto is not None:
            support = self._support(onto)
            stacks.check_stack(obj_id, support)
            x, y = stacks.stack_position(support, x, y)
            level = support.level + 1
        x, y = float(x), float(y)
        self._check_on_table(entry.shape, entry.size, x, y, new_angle, f"cannot place {obj_id}")
        # Exactly coincident centres give pymunk no direction to push in (two equal squares
        # then stay stacked): nudge by a micrometre, deterministically, toward the table centre.
        for other in self._s.entries.values():
            if other is not entry and not other.held and other.level == level and onto is None:
                op = other.body.position
                if abs(op.x - x) < 1e-9 and abs(op.y - y) < 1e-9:
                    x += 1e-6 if x < self.table.width / 2 else -1e-6
                    y += 1e-6 if y < self.table.depth / 2 else -1e-6
                    break
        entry.body.position = (x, y)
        entry.body.angle = new_angle
        entry.body.velocity = (0.0, 0.0)
        entry.body.angular_velocity = 0.0
        entry.level, entry.on = level, onto
        if onto is not None:
            lb = self._entry(onto).body
            c, s_ = math.cos(lb.angle), math.sin(lb.angle)
            dx, dy = x - lb.position.x, y - lb.position.y
            entry.rest = (dx * c + dy * s_, -dx * s_ + dy * c, new_angle - lb.angle)
        entry.poly.filter = engine.layer_filter(level)
        # Its joints (to the table, or to what it rests on) come with settle's rebuild.
        entry.joints = ()
        self._s.space.add(entry.body, entry.poly)
        self._s.space.reindex_shapes_for_body(entry.body)
        entry.held = False
        self._s.held = None
        return self.settle()

    def push(self, obj_id: str, vx: float, vy: float) -> None:
        """Give an object on the table a velocity (m/s); `settle()` lets it slide to rest."""
        entry = self._entry(obj_id)
        if entry.held:
            raise UserError(f"cannot push {obj_id}: it is held")
        stacks.check_push(obj_id, carries=self._carried_by(obj_id), on=entry.on)
        entry.body.velocity = (float(vx), float(vy))

    def push_away(self, obj_id: str) -> SettleReport:
        """The hand slides the object north (away from the trainer) by about one footprint,
        through the physics: a kinematic hand drives it at `PUSH_SPEED`, it shoves what it
        runs into, and after the hand lets go everything slides to rest. Returns who moved
        how far, from before the push to rest.

        Refused (nothing changes) for a held object, one carrying another or resting on
        another, and when one footprint north would take it over the table's far edge."""
        entry = self._entry(obj_id)
        if entry.held:
            raise UserError(f"cannot push {obj_id}: it is held")
        stacks.check_push(obj_id, carries=self._carried_by(obj_id), on=entry.on)
        ph = self.physics
        side = catalog.SIZES[entry.size]
        p = entry.body.position
        half = footprint_half_extent(entry.shape, side, float(entry.body.angle))
        stacks.push_target(obj_id, float(p.y), half, side, self.table.depth)
        entries = [e for e in self._s.entries.values() if not e.held]
        self._canonicalize(entries)
        start = {e.id: (e.body.position.x, e.body.position.y) for e in entries}
        # The hand: a thin bar as wide as the object, just south of it, that touches only it.
        hand, bar = engine.pushing_hand(ph, float(p.x), float(p.y) - half, 2.0 * half)
        entry.poly.filter = engine.layer_filter(entry.level, pushed=True)
        space = self._s.space
        space.add(hand, bar)
        # After the hand stops, the object slides v^2 / (2 mu g) further: the hand's travel
        # leaves room for that, so the whole push comes to about one footprint.
        slide = PUSH_SPEED * PUSH_SPEED / (2.0 * ph.mu_table * ph.g)
        steps = max(1, math.ceil((side - slide + 1e-4) / (PUSH_SPEED * ph.dt)))
        hand.velocity = (0.0, PUSH_SPEED)
        for _ in range(steps):
            space.step(ph.dt)
        space.remove(hand, bar)
        entry.poly.filter = engine.layer_filter(entry.level)
        rest = self.settle()
        moved: dict[str, float] = {}
        for e in entries:
            sx, sy = start[e.id]
            d = math.hypot(e.body.position.x - sx, e.body.position.y - sy)
            if d > MOVED_EPS:
                moved[e.id] = d
        return SettleReport(moved, steps + rest.steps, rest.settled)

    def settle(self, max_steps: int = 2400) -> SettleReport:
        """Step the physics until every object rests (or `max_steps`), and report who moved.

        An object rests when its speed, spin and its movement during the last step are all
        below the thresholds in `PhysicsConfig`, for `rest_steps` steps in a row. A scene
        without contacts or motion therefore ends after `rest_steps` steps.
        """
        if max_steps < 1:
            raise UserError(f"max_steps must be >= 1, got {max_steps}")
        entries = [e for e in self._s.entries.values() if not e.held]
        if not entries:
            return SettleReport({}, 0, True)
        self._canonicalize(entries)
        bodies = [e.body for e in entries]
        start = [(b.position.x, b.position.y) for b in bodies]
        steps, settled = engine.step_until_rest(self._s.space, bodies, self.physics, max_steps)
        self._snap_stacks(entries)
        moved: dict[str, float] = {}
        for e, b, (sx, sy) in zip(entries, bodies, start):
            dist = math.hypot(b.position.x - sx, b.position.y - sy)
            if dist > MOVED_EPS:
                moved[e.id] = dist
        return SettleReport(moved, steps, settled)

    def _snap_stacks(self, entries: list[Entry]) -> None:
        """Put every upper object exactly where it rests on its support: the joints carry
        it along while stepping, but a soft joint lags by a fraction of a millimetre."""
        by_id = {e.id: e for e in entries}
        for e in entries:
            lower = by_id.get(e.on) if e.on is not None else None
            if lower is None:
                continue
            lb = lower.body
            c, s_ = math.cos(lb.angle), math.sin(lb.angle)
            ox, oy, oa = e.rest
            e.body.position = (lb.position.x + ox * c - oy * s_, lb.position.y + ox * s_ + oy * c)
            e.body.angle = lb.angle + oa
            e.body.velocity = lb.velocity
            e.body.angular_velocity = lb.angular_velocity

    def _canonicalize(self, entries: list[Entry]) -> None:
        """Rebuild the pymunk space from the objects' states, in insertion order.

        pymunk (Chipmunk) carries history that is not part of the objects' states: contact
        caches, joints' accumulated impulses, and the shape ids that order its collision
        pairs. A settle that starts from a fresh space depends only on the objects, so a
        `copy()` and its original replay exactly the same steps (to the last bit).
        """
        self._s.space = engine.new_space(self.table, self.physics)
        build(self._s.space, self.physics, entries)

    # ----------------------------------------------------------------- copies

    def copy(self) -> World:
        """An independent deep copy, for planning and what-if.

        Built from the objects' states rather than by copying pymunk's space (about ten
        times faster): `settle()` rebuilds the space from those states anyway, so the copy
        and the original replay the same calls identically.
        """
        new = World.__new__(World)
        new.table = self.table
        new.seed = self.seed
        new.physics = self.physics
        new.rng = _copy.deepcopy(self.rng)
        s = self._s
        new._s = State(space=engine.new_space(new.table, new.physics), held=s.held, next_id=s.next_id, last_pointed=s.last_pointed)
        for e in s.entries.values():
            b = e.body
            side = catalog.SIZES[e.size]
            body = engine.rigid_body(new.physics, e.shape, side, b.position, b.angle, b.velocity, b.angular_velocity)
            poly = engine.collision_shape(new.physics, body, e.shape, side, e.level)
            new._s.entries[e.id] = Entry(e.id, e.appearance, e.shade, body, poly, (), e.held, e.level, e.on,
                                          e.rest)
        build(new._s.space, new.physics, [e for e in new._s.entries.values() if not e.held])
        return new

    def __repr__(self) -> str:
        parts = [f"{o.id}:{o.colour} {o.shape}@({o.x:.3f},{o.y:.3f}){'[held]' if o.held else ''}"
                 f"{f'[on {o.on}]' if o.on else ''}" for o in self.objects()]
        return f"World({', '.join(parts)})"
