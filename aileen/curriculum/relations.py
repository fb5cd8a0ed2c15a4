"""The trainer's own meaning of the spatial words: ground truth in table metres.

The agent never reads this module. It learns "left of" from examples laid out with it and is
graded against it, so these definitions are the teacher's intent, not the learner's concept.

Frame (docs/architecture.md): metres, +x east (the trainer's right), +y north (away from the
trainer, who stands at the south edge). For a person standing there:

| relation      | direction of a from b |
|---------------|-----------------------|
| `left of`     | west  (-x)            |
| `right of`    | east  (+x)            |
| `in front of` | south (-y, towards the trainer) |
| `behind`      | north (+y)            |

`a` stands in a relation to `b` when the direction from `b`'s centre to `a`'s centre lies
within `half_angle` degrees of the relation's direction and the two footprints do not touch
(the agent's `dc`). Three angles matter and are kept apart on purpose:

* `HOLDS_HALF_ANGLE` (45 degrees): what a person accepts as "left of": more left than in front
  or behind. Used to grade the outcome of an action (lenient: the learner may put the object
  anywhere a person would call "left of").
* `CLEAR_HALF_ANGLE` (15 degrees): what the trainer insists on for its own scenes, checked
  again after physics has settled; well inside the camera's cardinal-direction sector
  (22.5 degrees), so what the agent perceives agrees with what the trainer meant even when
  the detector's box centres are off by a pixel or two (7.5 degrees at the closest distance
  of 0.15 m is 2 cm, 5 pixels).
* `PLACE_HALF_ANGLE` (10 degrees): where the trainer samples positions, leaving room for
  physics to nudge objects without leaving the clear zone.

Relations live in one table (`RELATIONS`); add a `Relation` there to teach a new direction.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from aileen.errors import UserError

HOLDS_HALF_ANGLE = 45.0
CLEAR_HALF_ANGLE = 15.0
PLACE_HALF_ANGLE = 10.0
# Centre-to-centre distance when the trainer places an object in a relation, in units of the
# larger footprint of the two objects: close enough to read as a relation between the two,
# far enough that the footprints stay clearly apart.
PLACE_DISTANCE = (1.5, 4.0)


class Placed(Protocol):
    """Anything with a centre and a footprint box in table metres (e.g. `WorldObject`)."""

    x: float
    y: float

    def box_m(self) -> tuple[float, float, float, float]: ...


@dataclass(frozen=True)
class Relation:
    """A directional relation, `a <name> b`: a lies in `direction` (unit vector) from b."""

    name: str
    direction: tuple[float, float]
    aliases: tuple[str, ...] = ()

    @property
    def symbol(self) -> str:
        """ASP-safe spelling: `left of` -> `left_of` (the agent's concept is `r_left_of`)."""
        return self.name.replace(" ", "_")

    @property
    def heading(self) -> float:
        """Direction as an angle in radians, counter-clockwise from east."""
        return math.atan2(self.direction[1], self.direction[0])


RELATIONS: dict[str, Relation] = {
    r.name: r
    for r in (
        Relation("left of", (-1.0, 0.0), ("left", "to the left of", "leftof")),
        Relation("right of", (1.0, 0.0), ("right", "to the right of", "rightof")),
        Relation("in front of", (0.0, -1.0), ("front of", "in front", "infrontof", "frontof")),
        Relation("behind", (0.0, 1.0), ("behind of", "in back of", "back of")),
    )
}


def _normalise(name: str) -> str:
    return re.sub(r"\s+", " ", re.sub(r"[-_]", " ", name.strip().lower())).strip()


_ALIASES: dict[str, str] = {}
for _rel in RELATIONS.values():
    _ALIASES[_rel.name] = _rel.name
    _ALIASES[_rel.symbol] = _rel.name
    for _alias in _rel.aliases:
        _ALIASES[_normalise(_alias)] = _rel.name


def known() -> tuple[str, ...]:
    """Canonical names of the relations the trainer can lay out and demonstrate."""
    return tuple(RELATIONS)


def find(name: str) -> str | None:
    """Canonical name for a spelling (`left-of`, `Left_Of`, `to the left of`), or None."""
    return _ALIASES.get(_normalise(name))


def canonical(name: str) -> str:
    """Like `find`, but an unknown name is a `UserError` that lists the known relations."""
    found = find(name)
    if found is None:
        raise UserError(f"unknown relation {name!r}; expected one of: {', '.join(known())}")
    return found


def get(name: str) -> Relation:
    return RELATIONS[canonical(name)]


def phrases() -> list[tuple[str, str]]:
    """(spelling, canonical) pairs with spaces, longest first: for finding relations in text."""
    pairs = [(k, v) for k, v in _ALIASES.items() if "_" not in k]
    return sorted(pairs, key=lambda kv: -len(kv[0]))


def gap(a: Placed, b: Placed) -> float:
    """Clearance between the two footprint boxes in metres; <= 0 when they touch or overlap."""
    ax0, ay0, ax1, ay1 = a.box_m()
    bx0, by0, bx1, by1 = b.box_m()
    return max(bx0 - ax1, ax0 - bx1, by0 - ay1, ay0 - by1)


def angle_off(relation: str, a: Placed, b: Placed) -> float:
    """Degrees between the relation's direction and the direction from b's centre to a's.

    180 when the centres coincide (no direction at all, so no relation holds).
    """
    rel = get(relation)
    dx, dy = a.x - b.x, a.y - b.y
    if math.hypot(dx, dy) < 1e-9:
        return 180.0
    diff = math.atan2(dy, dx) - rel.heading
    diff = (diff + math.pi) % (2 * math.pi) - math.pi
    return abs(math.degrees(diff))


def holds(
    relation: str,
    a: Placed,
    b: Placed,
    *,
    half_angle: float = HOLDS_HALF_ANGLE,
    min_gap: float = 0.0,
) -> bool:
    """Ground truth: does `a <relation> b` hold (direction within `half_angle`, footprints apart)?

    The default is the lenient, person's reading (see the module docstring); the trainer's own
    scenes are checked with `clearly_holds`.
    """
    return angle_off(relation, a, b) < half_angle and gap(a, b) > min_gap


def clearly_holds(relation: str, a: Placed, b: Placed, *, min_gap: float = 0.02) -> bool:
    """The trainer's standard for its own scenes: well inside the sector and well apart."""
    return holds(relation, a, b, half_angle=CLEAR_HALF_ANGLE, min_gap=min_gap)


def which(a: Placed, b: Placed, *, half_angle: float = HOLDS_HALF_ANGLE) -> list[str]:
    """Every known relation that holds of `a` to `b` (at most one with the default angle)."""
    return [name for name in RELATIONS if holds(name, a, b, half_angle=half_angle)]


def sample_offset(
    relation: str,
    size: float,
    rng: np.random.Generator,
    *,
    half_angle: float = PLACE_HALF_ANGLE,
    distance: tuple[float, float] = PLACE_DISTANCE,
) -> tuple[float, float]:
    """A displacement (dx, dy) that puts an object clearly in `relation` to one at the origin.

    The angle is uniform within `half_angle` of the relation's direction, the length uniform
    in `distance` times `size` (the larger footprint of the two objects).
    """
    rel = get(relation)
    theta = rel.heading + math.radians(rng.uniform(-half_angle, half_angle))
    length = size * rng.uniform(*distance)
    return length * math.cos(theta), length * math.sin(theta)
