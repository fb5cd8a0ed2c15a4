"""The relations the trainer can lay out, examine and grade: the teacher's meaning of its words.

The agent never reads this module. It learns "left of" from examples laid out with it and is
graded against it, so these definitions are the trainer's intent, not the learner's concept.

Frame (docs/architecture.md): metres, +x east (the trainer's right), +y north (away from the
trainer, who stands at the south edge).

A `TrainerRelation` is one way of laying a relation out, under the word the trainer says for
it. Several layouts may share a word: `behind1`, `behind2`, `behind3` (straight behind, behind
and to the left, behind and to the right, as in the original AILEEN's scripts) and
`behind disjunctive` (any of them) are all said "behind"; `left of ec` is "left of" with the
objects touching. Each relation gives:

* `accepts(a, b)`: what a person accepts as the word (grading exams and the outcome of an
  action; lenient: "left of" is anything more left than in front or behind, up to 45 degrees).
* `clear(a, b)`: what the trainer insists on for its own scenes, checked again after physics
  settles (well inside the camera's 22.5-degree sector, so perception agrees).
* `offset(rng, fa, fb)`: where to put a (footprint fa) relative to b (footprint fb) so that it
  clearly holds; `near_miss(rng, fa, fb)` a position close to it where the word does not hold.
* `sizes(rng)`: for the comparatives, the sizes (a, b) to give objects whose size the lesson
  leaves open; `stacked`: a rests on b.

Direction words come in families. A `Direction` is declared with its axis, the word opposite
it and its `Grain` (how wide its family's words are: the four cardinal words are each a quarter
of the circle); `declare_directions` lays each out three ways, plain (`left of`), wide (`left of
wide`) and touching (`left of ec`). What is "a direction word", "the opposite of left of", "the
wide layout of behind" is read from these declarations (`directions`, `direction`), never from
a layout's geometry. A distance word (`distance`) declares its region as a `Distance`, and a
word that is both ("far left of") is their `conjunction`: laid out, accepted and near-missed
through the two declarations.

To add a relation: one `TrainerRelation` in `RELATIONS` (the factories below cover direction,
contact, distance, size and stacking; `declare_directions` a family of direction words,
`conjunction` a direction at a distance); nothing else lists relations.
"""

from __future__ import annotations

import contextlib
import math
import re
from collections.abc import Callable, Iterator
from contextvars import ContextVar
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from aileen.errors import UserError
from aileen.world import catalog
from aileen.world.stacks import ON_TOP_OFFSET

HOLDS_HALF_ANGLE = 45.0
CLEAR_HALF_ANGLE = 15.0
PLACE_HALF_ANGLE = 10.0
# The wide layouts (`aileen experiment --protocol wide`): drawn over the whole region a person
# accepts, uniform in angle up to this far off the axis, and checked after settling within
# WIDE_CLEAR_HALF_ANGLE (still inside HOLDS_HALF_ANGLE, so a person says the word).
# A grain's wide layouts reach this far inside its edge (`Grain.wide_lay`, `Grain.wide_clear`).
WIDE_LAY_MARGIN = 5.0
WIDE_CLEAR_MARGIN = 3.0
WIDE_HALF_ANGLE = HOLDS_HALF_ANGLE - WIDE_LAY_MARGIN  # 40 degrees for the cardinal words
WIDE_CLEAR_HALF_ANGLE = HOLDS_HALF_ANGLE - WIDE_CLEAR_MARGIN  # 42
WIDE_SUFFIX = " wide"
TOUCHING_SUFFIX = " ec"  # a direction's touching layout: `left of ec`
# Centre-to-centre distance when the trainer places an object in a directional relation, in
# units of the larger footprint of the two objects.
PLACE_DISTANCE = (1.5, 4.0)
# Touching: the gap a person still calls "touching" (the camera's RCC8 margin is 1 cm), and
# the gap the trainer leaves when it lays objects side by side (no physical contact: the
# world would push).
TOUCH_GAP = 0.01
# A clear directional layout leaves at least this gap (metres) between the footprints; the
# trainer lays them out with this much, and judges a settled scene clear above 2 cm.
CLEAR_GAP = 0.025
LAY_TOUCH_GAP = 0.003
# Distance words, in units of the larger footprint: the gap between footprints. Kept apart from
# the directional layouts (gaps of 0.48 to 3 widths), so a "left of" scene is never also
# "near" or "far from" by the trainer's judgement.
NEAR_GAP = 0.35  # "near": at most about a third of an object's width apart
NEAR_LAY = (0.08, 0.25)
# A distance layout leaves at least this gap (metres): clear of perception's contact
# tolerance (`geometry.DEFAULT_Q`, 1 cm) plus a pixel of box noise on each edge, so a "near"
# example meant apart is not read as touching on one scene and apart on the next.
APART_MIN = 0.018
FAR_GAP = 3.6  # "far from": more than three and a half widths apart
FAR_LAY = (4.2, 6.0)


class OnTable(Protocol):
    """Anything with a centre, a footprint box in table metres and a size (a `WorldObject`)."""

    x: float
    y: float
    size: str

    def box_m(self) -> tuple[float, float, float, float]: ...


Offset = Callable[[np.random.Generator, float, float], tuple[float, float]]


@dataclass(frozen=True)
class TrainerRelation:
    name: str  # the layout's canonical name: "left of", "behind2", "left of ec"
    word: str  # what the trainer says: "left of", "behind"
    accepts: Callable[[OnTable, OnTable], bool]
    clear: Callable[[OnTable, OnTable], bool]
    offset: Offset | None = None  # None: any position (e.g. the comparatives)
    near_miss: Offset | None = None
    sizes: Callable[[np.random.Generator], tuple[str, str]] | None = None
    near_miss_sizes: Callable[[np.random.Generator], tuple[str, str]] | None = None
    stacked: bool = False
    positional: bool = True  # where the objects stand decides it (not so for the comparatives)
    aliases: tuple[str, ...] = ()
    # The direction the layout says (the word's axis, its opposite, its grain): a direction
    # word's layouts and a conjunction's; None for a word where the objects stand in no
    # particular direction (near, next to, larger than, on).
    direction: Direction | None = None
    distance: Distance | None = None  # the distance region it says (near, far from, far left of)
    symmetric: bool = False  # a r b whenever b r a (near, far from, next to): no role-swapped near miss

    @property
    def symbol(self) -> str:
        """ASP-safe spelling of the word: `left of` -> `left_of` (the agent's concept `r_left_of`)."""
        return self.word.replace(" ", "_")


@dataclass(frozen=True)
class Grain:
    """How wide the words of one family of directions are, as the trainer means them: how far
    off its axis a person still says a word of the family (`half_angle`), and how far off it
    the trainer lays out and judges clear its plain layouts (`lay`, `clear`: well inside the
    word, so that perception agrees) and its wide ones (`wide_lay`, `wide_clear`: the whole
    region a person accepts, `WIDE_LAY_MARGIN` inside its edge). The words of one grain do not
    overlap (`declare_directions` holds them so), so at most one of them holds of a pair."""

    name: str
    half_angle: float  # degrees
    lay: float = PLACE_HALF_ANGLE
    clear: float = CLEAR_HALF_ANGLE

    def __post_init__(self) -> None:
        if not 0.0 < self.lay < self.clear < self.half_angle <= 90.0 or self.wide_lay <= self.clear:
            raise ValueError(f"grain {self.name!r}: expected 0 < lay < clear < half_angle <= 90 degrees and "
                             f"room for wide layouts beyond clear, got lay {self.lay}, clear {self.clear}, "
                             f"half_angle {self.half_angle}")

    @property
    def wide_lay(self) -> float:
        return self.half_angle - WIDE_LAY_MARGIN

    @property
    def wide_clear(self) -> float:
        return self.half_angle - WIDE_CLEAR_MARGIN


# The four cardinal words (left of, right of, in front of, behind): a person's 45 degrees
# either side, each a quarter of the circle (the grain of the cone calculus).
CARDINAL = Grain("cardinal", HOLDS_HALF_ANGLE)


@dataclass(frozen=True)
class Direction:
    """A direction word as the trainer means it: a lies along `axis` (degrees,
    counter-clockwise from east) from b, within its grain's half-angle.

    Declared in a family (`declare_directions`) it names its `opposite` (the word whose axis
    is turned half a circle, declared with it) and its `grain`, and is laid out three ways:
    plain (named like the word), wide (`wide`) and touching (`touching`). A direction built
    for one layout alone (`directional` without a declared direction: a lesson's own "above
    right of", a teacher's sense for one trial) has neither, and is in no family."""

    word: str
    axis: float
    opposite: str | None = None
    grain: Grain | None = None
    aliases: tuple[str, ...] = ()

    @property
    def radians(self) -> float:
        return math.radians(self.axis)

    @property
    def vector(self) -> tuple[float, float]:
        """Unit vector along the axis, in table metres (+x east, +y north)."""
        return math.cos(self.radians), math.sin(self.radians)

    @property
    def wide(self) -> str:
        """Name of the wide layout: anywhere a person still says the word."""
        return self.word + WIDE_SUFFIX

    @property
    def touching(self) -> str:
        """Name of the touching layout: that direction with the objects in contact."""
        return self.word + TOUCHING_SUFFIX

    def region(self) -> tuple[float, float]:
        """(centre, width) in degrees, as a direction calculus declares its regions."""
        if self.grain is None:
            raise ValueError(f"direction {self.word!r} belongs to no grain")
        return self.axis, 2.0 * self.grain.half_angle

    def layouts(self) -> tuple[TrainerRelation, TrainerRelation, TrainerRelation]:
        """The plain, wide and touching layouts of a direction declared in a family."""
        g = self.grain
        if g is None:
            raise ValueError(f"direction {self.word!r} belongs to no grain")
        plain = directional(self.word, self.axis, aliases=self.aliases, direction=self, lay_half_angle=g.lay,
                            clear_half_angle=g.clear, accept_half_angle=g.half_angle)
        wide = directional(self.wide, self.axis, direction=self, lay_half_angle=g.wide_lay,
                           clear_half_angle=g.wide_clear, accept_half_angle=g.half_angle)
        touching = directional(self.touching, self.axis, direction=self, touching=True,
                               aliases=tuple(a + TOUCHING_SUFFIX for a in self.aliases), lay_half_angle=g.lay,
                               clear_half_angle=g.clear, accept_half_angle=g.half_angle)
        return plain, wide, touching


@dataclass(frozen=True)
class Distance:
    """A distance word's region: the gap between the footprints, in units of the larger one,
    lies in (lo, hi]. The trainer lays it out with a gap in `lay` and its near misses in `miss`
    (units of the larger footprint too)."""

    lo: float
    hi: float
    lay: tuple[float, float]
    miss: tuple[float, float]


# ------------------------------------------------------------------ geometry


def gap(a: OnTable, b: OnTable) -> float:
    """Clearance between the two footprint boxes in metres; <= 0 when they touch or overlap."""
    ax0, ay0, ax1, ay1 = a.box_m()
    bx0, by0, bx1, by1 = b.box_m()
    return max(bx0 - ax1, ax0 - bx1, by0 - ay1, ay0 - by1)


def _extent(p: OnTable) -> float:
    x0, y0, x1, y1 = p.box_m()
    return max(x1 - x0, y1 - y0)


def _angle_from(heading: float, a: OnTable, b: OnTable) -> float:
    dx, dy = a.x - b.x, a.y - b.y
    if math.hypot(dx, dy) < 1e-9:
        return 180.0
    diff = math.atan2(dy, dx) - heading
    diff = (diff + math.pi) % (2 * math.pi) - math.pi
    return abs(math.degrees(diff))


def _resting_on(a: OnTable, b: OnTable) -> bool:
    return getattr(a, "on", None) == getattr(b, "id", object())


def _on_table(p: OnTable) -> bool:
    return getattr(p, "on", None) is None and not getattr(p, "held", False)


# ------------------------------------------------------------------ factories


def _ring(rng: np.random.Generator, heading: float, half_angle: float, length: float) -> tuple[float, float]:
    theta = heading + math.radians(rng.uniform(-half_angle, half_angle))
    return length * math.cos(theta), length * math.sin(theta)


def _touch_length(heading: float, fa: float, fb: float, g: float) -> float:
    """Centre distance along `heading` at which two axis-aligned squares have gap g."""
    c, s = abs(math.cos(heading)), abs(math.sin(heading))
    return (0.5 * (fa + fb) + g) / max(c, s)


def directional(name: str, heading_deg: float, *, word: str | None = None, aliases: tuple[str, ...] = (),
                accept_from: float | None = None, lay_half_angle: float = PLACE_HALF_ANGLE,
                touching: bool = False, clear_half_angle: float = CLEAR_HALF_ANGLE,
                accept_half_angle: float = HOLDS_HALF_ANGLE,
                near_miss_band: tuple[float, float] | None = None,
                direction: Direction | None = None) -> TrainerRelation:
    """a lies in direction `heading_deg` (degrees, counter-clockwise from east) from b.

    `accept_from` is the heading a person judges by (the word's own direction: a `behind2`
    laid out behind and to the left is still judged as "behind"); `touching` lays the objects
    side by side in contact and requires it. `clear_half_angle` is how far off the heading
    the trainer still calls its own layout clear (the wide layouts reach 40 degrees).
    `accept_half_angle` is how far off the heading the word is still accepted (a person's
    45 degrees; a stricter teacher's 20, a narrow word's 5: `experiments/teacher.py`).

    Near misses: by default within `PLACE_HALF_ANGLE` of the opposite or a perpendicular
    heading, whatever the layout's spread, so a near miss is never one a person would hesitate
    over. With `near_miss_band` (lo, hi) instead just outside the edge: between lo and hi
    degrees beyond `accept_half_angle`, on either side, apart as a clear layout is.

    `direction` is the declared direction the layout says (its word and the axis it is judged
    by: `behind2`, laid out at 120 degrees, says "behind"); without one, the layout says a
    direction of its own, `word` along `accept_from` (default `heading_deg`), in no family."""
    said = direction or Direction(word or name, accept_from if accept_from is not None else heading_deg)
    heading = math.radians(heading_deg)
    judge = said.radians

    def accepts(a: OnTable, b: OnTable) -> bool:
        ok = _angle_from(judge, a, b) < accept_half_angle and gap(a, b) > 0.0 and _on_table(a) and _on_table(b)
        return ok and (not touching or gap(a, b) <= TOUCH_GAP)

    def clear(a: OnTable, b: OnTable) -> bool:
        g = gap(a, b)
        if _angle_from(heading, a, b) >= clear_half_angle or not accepts(a, b):
            return False
        return g <= TOUCH_GAP if touching else g > CLEAR_GAP - 0.005

    def offset(rng: np.random.Generator, fa: float, fb: float) -> tuple[float, float]:
        if touching:
            theta = heading + math.radians(rng.uniform(-lay_half_angle / 2, lay_half_angle / 2))
            length = _touch_length(theta, fa, fb, LAY_TOUCH_GAP)
            return length * math.cos(theta), length * math.sin(theta)
        dx, dy = _ring(rng, heading, lay_half_angle, max(fa, fb) * rng.uniform(*PLACE_DISTANCE))
        return apart(dx, dy, fa, fb)  # (only wide layouts of small objects need it)

    def apart(dx: float, dy: float, fa: float, fb: float) -> tuple[float, float]:
        # Far off the axis a short draw leaves the squares barely apart along their wider
        # axis; keep the clear standard's gap.
        theta = math.atan2(dy, dx)
        least = _touch_length(theta, fa, fb, CLEAR_GAP)
        length = math.hypot(dx, dy)
        if length < least:
            dx, dy = dx * least / length, dy * least / length
        return dx, dy

    def near_miss(rng: np.random.Generator, fa: float, fb: float) -> tuple[float, float]:
        if near_miss_band is not None:  # just outside the edge, on either side
            length = max(fa, fb) * rng.uniform(*PLACE_DISTANCE)
            off = accept_half_angle + rng.uniform(*near_miss_band)
            theta = judge + math.radians(off if rng.random() < 0.5 else -off)
            return apart(length * math.cos(theta), length * math.sin(theta), fa, fb)
        # the opposite or a perpendicular direction, at the same distances
        turn = math.radians(float(rng.choice([90.0, 180.0, 270.0])))
        spread = min(lay_half_angle, PLACE_HALF_ANGLE)
        return _ring(rng, judge + turn, spread, max(fa, fb) * rng.uniform(*PLACE_DISTANCE))

    return TrainerRelation(name, said.word, accepts, clear, offset, near_miss, aliases=aliases, direction=said)


def next_to() -> TrainerRelation:
    """In contact, on any side."""

    def accepts(a: OnTable, b: OnTable) -> bool:
        return 0.0 < gap(a, b) <= TOUCH_GAP and _on_table(a) and _on_table(b)

    def offset(rng: np.random.Generator, fa: float, fb: float) -> tuple[float, float]:
        theta = math.radians(90.0 * int(rng.integers(4)) + rng.uniform(-PLACE_HALF_ANGLE, PLACE_HALF_ANGLE))
        length = _touch_length(theta, fa, fb, LAY_TOUCH_GAP)
        return length * math.cos(theta), length * math.sin(theta)

    def near_miss(rng: np.random.Generator, fa: float, fb: float) -> tuple[float, float]:
        theta = math.radians(90.0 * int(rng.integers(4)) + rng.uniform(-PLACE_HALF_ANGLE, PLACE_HALF_ANGLE))
        length = _touch_length(theta, fa, fb, max(fa, fb) * rng.uniform(0.6, 1.2))
        return length * math.cos(theta), length * math.sin(theta)

    return TrainerRelation("next to", "next to", accepts, accepts, offset, near_miss,
                           aliases=("beside", "touching", "nextto"), symmetric=True)


def distance(name: str, lo: float, hi: float, lay: tuple[float, float], miss: tuple[float, float],
             aliases: tuple[str, ...] = ()) -> TrainerRelation:
    """The gap between the footprints, in units of the larger one, lies in (lo, hi] (its
    `Distance` region, which a `conjunction` reads)."""
    region = Distance(lo, hi, lay, miss)

    def ratio(a: OnTable, b: OnTable) -> float:
        return gap(a, b) / max(_extent(a), _extent(b), 1e-6)

    def accepts(a: OnTable, b: OnTable) -> bool:
        return lo < ratio(a, b) <= hi and _on_table(a) and _on_table(b)

    def clear(a: OnTable, b: OnTable) -> bool:
        r = ratio(a, b)
        return accepts(a, b) and lay[0] * 0.8 <= r <= lay[1] * 1.2 and gap(a, b) > 0.02 * (lo > 0 or lay[0] > 0.2)

    def _at(rng: np.random.Generator, fa: float, fb: float, span: tuple[float, float],
            least: float = 0.0) -> tuple[float, float]:
        theta = rng.uniform(0.0, 2 * math.pi)
        # square boxes: the gap along the bigger axis component
        g = max(max(fa, fb) * rng.uniform(*span), least)
        length = _touch_length(theta, fa, fb, g)
        return length * math.cos(theta), length * math.sin(theta)

    return TrainerRelation(name, name, accepts, clear, lambda r, fa, fb: _at(r, fa, fb, lay, APART_MIN),
                           lambda r, fa, fb: _at(r, fa, fb, miss), aliases=aliases, distance=region,
                           symmetric=True)


def comparative(name: str, larger: bool, aliases: tuple[str, ...] = ()) -> TrainerRelation:
    """a is larger (or smaller) than b: by catalogued size, wherever they stand."""
    order = list(catalog.SIZES)

    def accepts(a: OnTable, b: OnTable) -> bool:
        ka, kb = order.index(a.size), order.index(b.size)
        return ka > kb if larger else ka < kb

    def sizes(rng: np.random.Generator) -> tuple[str, str]:
        lo = int(rng.integers(len(order) - 1))
        hi = int(rng.integers(lo + 1, len(order)))
        return (order[hi], order[lo]) if larger else (order[lo], order[hi])

    def same(rng: np.random.Generator) -> tuple[str, str]:
        k = order[int(rng.integers(len(order)))]
        return k, k

    def side_by_side(rng: np.random.Generator, fa: float, fb: float) -> tuple[float, float]:
        # shown side by side at an ordinary distance, so that nothing but the sizes stands out
        return _ring(rng, rng.uniform(0.0, 2 * math.pi), 0.0, max(fa, fb) * rng.uniform(*PLACE_DISTANCE))

    return TrainerRelation(name, name, accepts, accepts, side_by_side, side_by_side, sizes=sizes,
                           near_miss_sizes=same, positional=False, aliases=aliases)


def on() -> TrainerRelation:
    """a rests on b."""

    def offset(rng: np.random.Generator, fa: float, fb: float) -> tuple[float, float]:
        return _ring(rng, rng.uniform(0.0, 2 * math.pi), 0.0, 0.5 * fb * rng.uniform(*ON_TOP_OFFSET))

    def near_miss(rng: np.random.Generator, fa: float, fb: float) -> tuple[float, float]:
        theta = math.radians(90.0 * int(rng.integers(4)))
        length = _touch_length(theta, fa, fb, LAY_TOUCH_GAP)
        return length * math.cos(theta), length * math.sin(theta)

    return TrainerRelation("on", "on", _resting_on, _resting_on, offset, near_miss, stacked=True,
                           aliases=("on top of", "onto", "upon"))


def disjunctive(name: str, word: str, variants: tuple[str, ...]) -> TrainerRelation:
    """Any of several layouts of one word, drawn at random for each scene."""
    parts = [RELATIONS[v] for v in variants]

    def offset(rng: np.random.Generator, fa: float, fb: float) -> tuple[float, float]:
        return parts[int(rng.integers(len(parts)))].offset(rng, fa, fb)  # type: ignore[misc]

    first = parts[0]
    return TrainerRelation(name, word, first.accepts, lambda a, b: any(p.clear(a, b) for p in parts), offset,
                           first.near_miss, direction=first.direction)


def conjunction(name: str, direction: str, distance: str, *, aliases: tuple[str, ...] = ()) -> TrainerRelation:
    """a lies in the declared `direction` from b and at the declared `distance` from it ("far
    left of": left of, and far from), as a person judges both words.

    Read from the two declarations: the direction word's axis and grain, the distance word's
    region. Laid out along the axis (within the grain's plain spread) with a gap in the
    distance's layout band; clear when the direction is clear of its edge and the distance
    clearly holds. A near miss is one without the other: along the axis at the distance's
    near-miss gap, or at the distance in the opposite or a perpendicular direction."""
    way, apart_by = get(direction), get(distance)
    if way.direction is None or apart_by.distance is None:
        raise UserError(f"a conjunction joins a direction and a distance; got {direction!r} and {distance!r}")
    d, region = way.direction, apart_by.distance
    spread = d.grain.lay if d.grain is not None else PLACE_HALF_ANGLE
    clear_half = d.grain.clear if d.grain is not None else CLEAR_HALF_ANGLE

    def accepts(a: OnTable, b: OnTable) -> bool:
        return way.accepts(a, b) and apart_by.accepts(a, b)

    def clear(a: OnTable, b: OnTable) -> bool:
        return accepts(a, b) and _angle_from(d.radians, a, b) < clear_half and apart_by.clear(a, b)

    def at(rng: np.random.Generator, fa: float, fb: float, axis: float,
           span: tuple[float, float]) -> tuple[float, float]:
        theta = axis + math.radians(rng.uniform(-spread, spread))
        length = _touch_length(theta, fa, fb, max(max(fa, fb) * rng.uniform(*span), APART_MIN))
        return length * math.cos(theta), length * math.sin(theta)

    def offset(rng: np.random.Generator, fa: float, fb: float) -> tuple[float, float]:
        return at(rng, fa, fb, d.radians, region.lay)

    def near_miss(rng: np.random.Generator, fa: float, fb: float) -> tuple[float, float]:
        if rng.random() < 0.5:  # the direction, not at the distance
            return at(rng, fa, fb, d.radians, region.miss)
        turn = math.radians(float(rng.choice([90.0, 180.0, 270.0])))  # the distance, another way
        return at(rng, fa, fb, d.radians + turn, region.lay)

    return TrainerRelation(name, name, accepts, clear, offset, near_miss, aliases=aliases, direction=d,
                           distance=region)


RELATIONS: dict[str, TrainerRelation] = {}
_ALIASES: dict[str, str] = {}
# The declared direction words, by word (`declare_directions`): what "a direction word", "its
# opposite" and "its wide layout" mean everywhere.
DIRECTIONS: dict[str, Direction] = {}
# `spellings()`, made again after a declaration (keyed by `version()`)
_SPELLINGS: dict[tuple[int, int, int], dict[str, str]] = {}
_DECLARED = [0]  # declarations so far


def declare(*rels: TrainerRelation) -> None:
    """Add relations the trainer can lay out, examine and grade (with their spellings)."""
    _DECLARED[0] += 1
    for r in rels:
        RELATIONS[r.name] = r
        _ALIASES[_normalise(r.name)] = r.name
        _ALIASES[r.name.replace(" ", "_")] = r.name
        for alias in r.aliases:
            _ALIASES[_normalise(alias)] = r.name


def declare_directions(*dirs: Direction) -> None:
    """Declare direction words, each with its opposite (declared with it or before), its grain
    and spellings, and their layouts: every plain one, then every wide one, then every
    touching one. A `ValueError` when an opposite is missing or does not name the word back,
    lies elsewhere than half a circle away or in another grain, or when two words of one grain
    overlap (a word of a grain must be the only one of its grain that holds)."""
    family = {**DIRECTIONS, **{d.word: d for d in dirs}}
    for d in dirs:
        if d.grain is None or d.opposite is None:
            raise ValueError(f"direction {d.word!r}: a declared direction names its opposite and its grain")
        o = family.get(d.opposite)
        if o is None or o.opposite != d.word:
            raise ValueError(f"direction {d.word!r}: its opposite {d.opposite!r} is not declared with "
                             f"{d.word!r} as its own opposite")
        if abs(math.remainder(o.axis - d.axis - 180.0, 360.0)) > 1e-9 or o.grain != d.grain:
            raise ValueError(f"direction {d.word!r}: its opposite {o.word!r} must lie half a circle away "
                             f"({o.axis} against {d.axis} degrees) in the same grain")
        for other in family.values():
            apart = abs(math.remainder(other.axis - d.axis, 360.0))
            if other is not d and other.grain == d.grain and apart < 2 * d.grain.half_angle - 1e-9:
                raise ValueError(f"directions {d.word!r} and {other.word!r} of grain {d.grain.name!r} overlap: "
                                 f"{apart:g} degrees apart, each {2 * d.grain.half_angle:g} wide")
    layouts = [d.layouts() for d in dirs]
    DIRECTIONS.update((d.word, d) for d in dirs)
    declare(*(lay[k] for k in range(3) for lay in layouts))


@contextlib.contextmanager
def kept() -> Iterator[None]:
    """Within the block, declare freely; on leaving, the registry is as it was (a test that
    declares a relation or a family for itself alone)."""
    saved = dict(RELATIONS), dict(_ALIASES), dict(DIRECTIONS)
    try:
        yield
    finally:
        for live, old in zip((RELATIONS, _ALIASES, DIRECTIONS), saved):
            live.clear()
            live.update(old)  # type: ignore[arg-type]
        _DECLARED[0] += 1  # what was read from the registry inside is stale (`version`)


def _normalise(name: str) -> str:
    return re.sub(r"\s+", " ", re.sub(r"[-_]", " ", name.strip().lower())).strip()


# A trial's own relations (experiments/teacher.py draws a teacher per trial): known to the
# trainer inside `scope(...)` only, where they stand before the registry's (the teacher's
# "left of" is the word "left of" there). The registry itself, which the published protocols
# read, is never changed by them. A ContextVar: per thread, so concurrent runs do not mix.
_SCOPE: ContextVar[tuple[dict[str, TrainerRelation], dict[str, str]]] = ContextVar("relations_scope",
                                                                                  default=({}, {}))


@contextlib.contextmanager
def scope(*rels: TrainerRelation) -> Iterator[None]:
    """Within the block, `rels` are known by their names and aliases (before the registry's)."""
    own, aliases = dict(_SCOPE.get()[0]), dict(_SCOPE.get()[1])
    for r in rels:
        own[r.name] = r
        for spelling in (r.name, *r.aliases):
            aliases[_normalise(spelling)] = r.name
    token = _SCOPE.set((own, aliases))
    try:
        yield
    finally:
        _SCOPE.reset(token)


def _lookup(name: str) -> TrainerRelation:
    """The relation of a canonical name: the scope's, else the registry's."""
    own = _SCOPE.get()[0].get(name)
    return own if own is not None else RELATIONS[name]


# The four cardinal words, each laid out plain (within 10 degrees of its axis), wide (anywhere
# a person still says it: up to 40 degrees off the axis) and touching (in contact).
declare_directions(
    Direction("left of", 180.0, "right of", CARDINAL, aliases=("left", "to the left of", "leftof")),
    Direction("right of", 0.0, "left of", CARDINAL, aliases=("right", "to the right of", "rightof")),
    Direction("in front of", 270.0, "behind", CARDINAL, aliases=("front of", "in front", "infrontof", "frontof")),
    Direction("behind", 90.0, "in front of", CARDINAL, aliases=("behind of", "in back of", "back of")),
)
declare(
    # numbered layouts of one word (the original's behind1/2/3): straight, to the left, to the right
    directional("behind1", 90.0, direction=DIRECTIONS["behind"]),
    directional("behind2", 120.0, direction=DIRECTIONS["behind"], lay_half_angle=5.0),
    directional("behind3", 60.0, direction=DIRECTIONS["behind"], lay_half_angle=5.0),
    next_to(),
    distance("near", 0.0, NEAR_GAP, NEAR_LAY, (1.2, 2.0), aliases=("close to", "near to")),
    distance("far from", FAR_GAP, math.inf, FAR_LAY, (1.2, 2.0), aliases=("distant", "far away from", "far")),
    comparative("larger than", True, aliases=("bigger than", "larger")),
    comparative("smaller than", False, aliases=("smaller",)),
    on(),
)
declare(disjunctive("behind disjunctive", "behind", ("behind1", "behind2", "behind3")))


# ------------------------------------------------------------------ names


def known() -> tuple[str, ...]:
    """Canonical names of the layouts the trainer can lay out and demonstrate."""
    return tuple(RELATIONS)


def words() -> tuple[str, ...]:
    """The relation words the trainer says (one per meaning; layouts share them)."""
    return tuple(dict.fromkeys(r.word for r in RELATIONS.values()))


def directions(grain: str | None = None) -> tuple[str, ...]:
    """The declared direction words (`declare_directions`), or those of one grain
    (`directions("cardinal")`: left of, right of, in front of, behind), in declaration order.
    Words of one grain never both hold of a pair; words of different grains may."""
    return tuple(w for w, d in DIRECTIONS.items() if grain is None or (d.grain is not None and d.grain.name == grain))


def direction(word: str) -> Direction:
    """The declared direction of a direction word (any spelling): its axis, opposite, grain and
    layouts; a `UserError` for a word that is not a declared direction."""
    found = find(word)
    if found is None or found not in DIRECTIONS:
        raise UserError(f"{word!r} is not a declared direction; expected one of: {', '.join(DIRECTIONS)}")
    return DIRECTIONS[found]


def protocol_words() -> tuple[str, ...]:
    """The relation words the wide protocol teaches and examines: every word whose plain
    layout puts two objects side by side on the table (all but stacking)."""
    return tuple(w for w in words() if not of_word(w).stacked)


def wide(word: str) -> str:
    """The wide layout of a directional word (`left of` -> `left of wide`): the whole region
    a person accepts; the word itself when it has none."""
    return DIRECTIONS[word].wide if word in DIRECTIONS else word


def placeable() -> tuple[str, ...]:
    """Layouts that say where an object stands (what `move X <r> Y` can bring about)."""
    return tuple(n for n, r in RELATIONS.items() if r.offset is not None and r.positional)


def find(name: str) -> str | None:
    """Canonical name for a spelling (`left-of`, `Left_Of`, `to the left of`), or None."""
    key = _normalise(name)
    return _SCOPE.get()[1].get(key) or _ALIASES.get(key)


def canonical(name: str) -> str:
    """Like `find`, but an unknown name is a `UserError` that lists the known relations."""
    found = find(name)
    if found is None:
        raise UserError(f"unknown relation {name!r}; expected one of: {', '.join(known())}")
    return found


def get(name: str) -> TrainerRelation:
    return _lookup(canonical(name))


def of_word(word: str) -> TrainerRelation:
    """The plain layout of a relation word (the one named like it)."""
    return _lookup(word)


def phrases() -> list[tuple[str, str]]:
    """(spelling, word) pairs with spaces, longest first: for finding relation words in the
    trainer's own sentences (only spellings of words, not of layout variants; a `scope`'s
    words too)."""
    global _PHRASES
    scope, ver = _SCOPE.get(), version()
    last = _PHRASES
    if last is not None and last[0] == ver and last[1] is scope:
        return list(last[2])  # the trainer reads every sentence through this: kept per registry and scope
    own, own_aliases = scope
    found = {k: _lookup(v).word for k, v in _ALIASES.items()
             if "_" not in k and _lookup(v).name == _lookup(v).word}
    found.update({k: own[v].word for k, v in own_aliases.items() if own[v].name == own[v].word})
    out = sorted(found.items(), key=lambda kv: -len(kv[0]))
    _PHRASES = (ver, scope, out)
    return list(out)


# `phrases`' last answer: (registry version, the scope it was for, the pairs)
_PHRASES: tuple | None = None


def version() -> tuple[int, int, int]:
    """Which registry this is: changes with every declaration, and when the registry is put
    back by hand (tests do), so what is read from it can be cached by it."""
    return (_DECLARED[0], len(RELATIONS), len(_ALIASES))


def spellings() -> dict[str, str]:
    """Every declared spelling of a relation word in the registry -> the word it spells
    (`"to the left of"`, `"left"`, `"leftof"` -> `"left of"`; as `phrases`, the spellings of
    words, not of layout variants such as `"left of ec"`), words separated by one space. The teacher's grammar reads the
    words of its sentences with it (`aileen/reasoning/grammar.py`); the registry only, so what a
    sentence says does not depend on a trial's teacher (`scope`)."""
    key = version()
    if _SPELLINGS.get(key) is None:
        _SPELLINGS.clear()
        _SPELLINGS[key] = {k.replace("_", " "): RELATIONS[v].word for k, v in _ALIASES.items()
                           if RELATIONS[v].name == RELATIONS[v].word}
    return _SPELLINGS[key]


def angle_off(relation: str, a: OnTable, b: OnTable) -> float:
    """Degrees between the axis of the direction a relation says (`TrainerRelation.direction`:
    "behind" for `behind2` too) and the direction from b's centre to a's (180 when the centres
    coincide)."""
    rel = get(relation)
    if rel.direction is None:
        raise UserError(f"relation {relation!r} has no direction")
    return _angle_from(rel.direction.radians, a, b)


def holds(relation: str, a: OnTable, b: OnTable) -> bool:
    """Ground truth as a person judges it: does `a <relation> b` hold?"""
    return get(relation).accepts(a, b)


def clearly_holds(relation: str, a: OnTable, b: OnTable) -> bool:
    """The trainer's standard for its own scenes."""
    return get(relation).clear(a, b)


def which(a: OnTable, b: OnTable) -> list[str]:
    """Every relation word that holds of `a` to `b`, as a person judges it."""
    return [w for w in words() if of_word(w).accepts(a, b)]


def sample_offset(relation: str, fa: float, fb: float | None, rng: np.random.Generator) -> tuple[float, float]:
    """A displacement (dx, dy) that puts an object (footprint fa) clearly in `relation` to one
    (footprint fb) at the origin."""
    rel = get(relation)
    if rel.offset is None:
        raise UserError(f"relation {relation!r} does not depend on where the objects stand")
    return rel.offset(rng, fa, fa if fb is None else fb)
