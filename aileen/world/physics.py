"""The table top's physics: pymunk parts built from an object's kind, and the step loop.

This is the only module that imports pymunk; `aileen.world.sim` (the World and its actions)
builds and steps its space through these functions. The view is top-down, so there is no
gravity in the simulation; friction with the table is modelled the way pymunk's top-down
examples do it (tank.py): every object is tied to the static body by a pivot joint and a
gear joint whose `max_bias` is 0 and whose `max_force` is the Coulomb friction force
(mu * m * g) and torque. Such a joint only removes velocity, at a bounded rate, so a pushed
object slides and comes to a stop in finite time, exactly at rest. Objects collide with each
other (boxes are square polygons, the round shapes circles) and with a low rim around the
table, so a push can never drop an object off the table.

Layers: an object collides only with objects of its own level (a shape filter per layer),
and with the pushing hand when it is the one pushed. An object resting on another is tied
to it by a rigid pivot and gear joint instead of the table friction.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import pymunk

from aileen.world.camera import Table
from aileen.world import catalog
from aileen.world.footprints import capsule_parts

__all__ = ["PhysicsConfig", "Body", "Shape", "Constraint", "Space", "new_space", "rigid_body", "collision_shape",
           "friction_joints", "rest_joints", "layer_filter", "pushing_hand", "step_until_rest"]

Body = pymunk.Body
Shape = pymunk.Shape
Constraint = pymunk.Constraint
Space = pymunk.Space

HAND_BIT = 1 << 8  # collision category of the pushing hand
PUSHED_BIT = 1 << 9  # ... and of the one object it touches


@dataclass(frozen=True)
class PhysicsConfig:
    """The physical constants. Defaults are tuned so a push ends within a few hundred steps."""

    dt: float = 1.0 / 120.0  # s per step
    mu_table: float = 0.6  # table friction coefficient (objects on wood)
    mu_objects: float = 0.4  # object-object friction
    g: float = 9.81  # m/s^2, only to turn mu into a friction force
    density: float = 60.0  # kg per m^2 of footprint (a 0.10 m box weighs 0.6 kg)
    collision_slop: float = 0.0005  # m of overlap pymunk tolerates
    collision_bias: float = 0.7**60  # overlap left after 1 s of correction (pymunk default 0.9^60)
    rest_speed: float = 1e-3  # m/s: slower than this counts as resting
    rest_spin: float = 1e-2  # rad/s
    rest_step: float = 2e-6  # m (or rad x footprint) moved in one step: less counts as resting
    rest_steps: int = 2  # consecutive resting steps needed
    rim: float = 0.01  # m, thickness of the rim around the table


def layer_filter(level: int, *, pushed: bool = False) -> pymunk.ShapeFilter:
    """Objects collide only within their layer, and with the hand when it pushes them."""
    bit = 1 << level
    if pushed:
        return pymunk.ShapeFilter(categories=bit | PUSHED_BIT, mask=bit | HAND_BIT)
    return pymunk.ShapeFilter(categories=bit, mask=bit | HAND_BIT)


def new_space(table: Table, ph: PhysicsConfig) -> pymunk.Space:
    """An empty space: no gravity (top-down view), our collision tolerances, and the rim."""
    space = pymunk.Space()
    space.gravity = (0.0, 0.0)
    space.iterations = 10
    space.collision_slop = ph.collision_slop
    space.collision_bias = ph.collision_bias
    _add_rim(space, table, ph)
    return space


def _add_rim(space: pymunk.Space, table: Table, ph: PhysicsConfig) -> None:
    """Four static segments just outside the table edges, so pushes stay on the table."""
    w, d, r = table.width, table.depth, ph.rim
    # pymunk lets shapes sink `collision_slop` into each other: move the rim's inner face
    # in by that much, so that resting objects end inside the table, not a hair beyond.
    o = r - ph.collision_slop
    corners = [(-o, -o), (w + o, -o), (w + o, d + o), (-o, d + o)]
    for a, b in zip(corners, corners[1:] + corners[:1]):
        seg = pymunk.Segment(space.static_body, a, b, r)
        seg.friction = ph.mu_objects
        seg.elasticity = 0.0
        space.add(seg)


def _capsule(shape: str, side: float) -> tuple[float, float] | None:
    """(half the axis, end radius) of a lying capsule of length `side`; None for other shapes."""
    w = catalog.ELONGATED_FOOTPRINTS.get(shape)
    if w is None:
        return None
    r, a = capsule_parts(side, w)
    return a, r


def rigid_body(
    ph: PhysicsConfig,
    shape: str,
    side: float,
    position: tuple[float, float],
    angle: float,
    velocity: tuple[float, float],
    spin: float,
) -> pymunk.Body:
    """A body with the mass and moment of a uniform slab of the object's footprint."""
    capsule = _capsule(shape, side)
    if capsule is not None:
        a, r = capsule
        mass = ph.density * (math.pi * r * r + 4.0 * a * r)
        moment = pymunk.moment_for_segment(mass, (-a, 0.0), (a, 0.0), r)
    elif shape in catalog.SQUARE_FOOTPRINTS:
        mass = ph.density * side * side
        moment = pymunk.moment_for_box(mass, (side, side))
    else:
        mass = ph.density * math.pi * side * side / 4.0
        moment = pymunk.moment_for_circle(mass, 0.0, side / 2.0)
    body = pymunk.Body(mass, moment)
    body.position = (float(position[0]), float(position[1]))
    body.angle = float(angle)
    body.velocity = (float(velocity[0]), float(velocity[1]))
    body.angular_velocity = float(spin)
    return body


def collision_shape(ph: PhysicsConfig, body: pymunk.Body, shape: str, side: float, level: int = 0) -> pymunk.Shape:
    """The footprint as pymunk sees it: a square polygon for a box, a rounded segment for a
    lying capsule, else a circle, in its layer."""
    poly: pymunk.Shape
    capsule = _capsule(shape, side)
    if capsule is not None:
        poly = pymunk.Segment(body, (-capsule[0], 0.0), (capsule[0], 0.0), capsule[1])
    elif shape in catalog.SQUARE_FOOTPRINTS:
        poly = pymunk.Poly.create_box(body, (side, side))
    else:
        poly = pymunk.Circle(body, side / 2.0)
    poly.friction = ph.mu_objects
    poly.elasticity = 0.0
    poly.filter = layer_filter(level)
    return poly


def friction_joints(ph: PhysicsConfig, space: pymunk.Space, body: pymunk.Body, side: float,
                    mass: float | None = None) -> tuple[pymunk.Constraint, ...]:
    """Table friction as two velocity-only joints to the static body (pymunk's tank.py idea).

    `mass` is what presses on the table: the body's own, plus what rests on it."""
    m = body.mass if mass is None else mass
    static = space.static_body
    pivot = pymunk.PivotJoint(static, body, (0.0, 0.0), (0.0, 0.0))
    pivot.max_bias = 0.0
    pivot.max_force = ph.mu_table * m * ph.g
    gear = pymunk.GearJoint(static, body, 0.0, 1.0)
    gear.max_bias = 0.0
    # Friction torque of a uniform disk of radius r sliding on a plane: (2/3) mu m g r.
    gear.max_force = (2.0 / 3.0) * ph.mu_table * m * ph.g * (side / 2.0)
    return (pivot, gear)


def rest_joints(lower: pymunk.Body, upper: pymunk.Body) -> tuple[pymunk.Constraint, ...]:
    """An object resting on another rides along with it: a rigid pivot and gear joint."""
    pivot = pymunk.PivotJoint(lower, upper, tuple(upper.position))
    gear = pymunk.GearJoint(lower, upper, upper.angle - lower.angle, 1.0)
    return (pivot, gear)


def pushing_hand(ph: PhysicsConfig, x: float, y: float, width: float) -> tuple[pymunk.Body, pymunk.Shape]:
    """The hand that pushes: a kinematic bar `width` wide whose north face lies just south of
    (x, y), that touches only the object filtered as pushed (`layer_filter(..., pushed=True)`)."""
    hand = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
    thick = 0.01
    hand.position = (float(x), float(y) - thick / 2.0 - 1e-4)
    bar = pymunk.Poly.create_box(hand, (width, thick))
    bar.friction = ph.mu_objects
    bar.filter = pymunk.ShapeFilter(categories=HAND_BIT, mask=PUSHED_BIT)
    return hand, bar


def step_until_rest(space: pymunk.Space, bodies: Sequence[pymunk.Body], ph: PhysicsConfig,
                    max_steps: int) -> tuple[int, bool]:
    """Step until every body rests (or `max_steps`); returns (steps, settled).

    A body rests when its speed, spin and its movement during the last step are all below
    the thresholds in `PhysicsConfig`, for `rest_steps` steps in a row; settled bodies are
    then set exactly at rest, so the next settle starts clean."""
    prev = [(b.position.x, b.position.y, b.angle) for b in bodies]
    rest_run = 0
    steps = 0
    settled = False
    v2 = ph.rest_speed * ph.rest_speed
    while steps < max_steps:
        space.step(ph.dt)
        steps += 1
        resting = True
        for i, b in enumerate(bodies):
            p = b.position
            a = b.angle
            px, py, pa = prev[i]
            prev[i] = (p.x, p.y, a)
            if not resting:
                continue
            v = b.velocity
            if (
                v.x * v.x + v.y * v.y > v2
                or abs(b.angular_velocity) > ph.rest_spin
                or abs(p.x - px) > ph.rest_step
                or abs(p.y - py) > ph.rest_step
                or abs(a - pa) * 0.05 > ph.rest_step
            ):
                resting = False
        rest_run = rest_run + 1 if resting else 0
        if rest_run >= ph.rest_steps:
            settled = True
            break
    if settled:
        for b in bodies:
            b.velocity = (0.0, 0.0)
            b.angular_velocity = 0.0
    return steps, settled
