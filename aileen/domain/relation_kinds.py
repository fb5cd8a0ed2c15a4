"""The kinds of relation the trainer lays out: what each is, and how it is built and laid out.

Split from `relations.py`, which keeps the registry of declared relations and the queries over
it, so that a kind can be read or added without the registry's bookkeeping. This module never
imports the registry; the kinds made of relations declared there by name (`disjunctive`,
`conjunction`) are built in `relations.py`, from the dataclasses and geometry here.

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

A `Direction` names its axis, its opposite and its `Grain` (how wide its family's words are),
and is laid out plain, wide and touching (`Direction.layouts`); a `Distance` is a distance
word's region.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from aileen.domain.table_geometry import OnTable, angle_from, extent, gap, on_table, resting_on, ring, touch_length
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
    # The word that says it from the other side, b <converse> a whenever a r b, where it is no
    # direction (a direction's is its `opposite`) and not symmetric: "smaller than" for "larger than".
    converse: str | None = None

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


# ------------------------------------------------------------------ factories


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
        ok = angle_from(judge, a, b) < accept_half_angle and gap(a, b) > 0.0 and on_table(a) and on_table(b)
        return ok and (not touching or gap(a, b) <= TOUCH_GAP)

    def clear(a: OnTable, b: OnTable) -> bool:
        g = gap(a, b)
        if angle_from(heading, a, b) >= clear_half_angle or not accepts(a, b):
            return False
        return g <= TOUCH_GAP if touching else g > CLEAR_GAP - 0.005

    def offset(rng: np.random.Generator, fa: float, fb: float) -> tuple[float, float]:
        if touching:
            theta = heading + math.radians(rng.uniform(-lay_half_angle / 2, lay_half_angle / 2))
            length = touch_length(theta, fa, fb, LAY_TOUCH_GAP)
            return length * math.cos(theta), length * math.sin(theta)
        dx, dy = ring(rng, heading, lay_half_angle, max(fa, fb) * rng.uniform(*PLACE_DISTANCE))
        return apart(dx, dy, fa, fb)  # (only wide layouts of small objects need it)

    def apart(dx: float, dy: float, fa: float, fb: float) -> tuple[float, float]:
        # Far off the axis a short draw leaves the squares barely apart along their wider
        # axis; keep the clear standard's gap.
        theta = math.atan2(dy, dx)
        least = touch_length(theta, fa, fb, CLEAR_GAP)
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
        return ring(rng, judge + turn, spread, max(fa, fb) * rng.uniform(*PLACE_DISTANCE))

    return TrainerRelation(name, said.word, accepts, clear, offset, near_miss, aliases=aliases, direction=said)


def next_to() -> TrainerRelation:
    """In contact, on any side."""

    def accepts(a: OnTable, b: OnTable) -> bool:
        return 0.0 < gap(a, b) <= TOUCH_GAP and on_table(a) and on_table(b)

    def offset(rng: np.random.Generator, fa: float, fb: float) -> tuple[float, float]:
        theta = math.radians(90.0 * int(rng.integers(4)) + rng.uniform(-PLACE_HALF_ANGLE, PLACE_HALF_ANGLE))
        length = touch_length(theta, fa, fb, LAY_TOUCH_GAP)
        return length * math.cos(theta), length * math.sin(theta)

    def near_miss(rng: np.random.Generator, fa: float, fb: float) -> tuple[float, float]:
        theta = math.radians(90.0 * int(rng.integers(4)) + rng.uniform(-PLACE_HALF_ANGLE, PLACE_HALF_ANGLE))
        length = touch_length(theta, fa, fb, max(fa, fb) * rng.uniform(0.6, 1.2))
        return length * math.cos(theta), length * math.sin(theta)

    return TrainerRelation("next to", "next to", accepts, accepts, offset, near_miss,
                           aliases=("beside", "touching", "nextto"), symmetric=True)


def distance(name: str, lo: float, hi: float, lay: tuple[float, float], miss: tuple[float, float],
             aliases: tuple[str, ...] = ()) -> TrainerRelation:
    """The gap between the footprints, in units of the larger one, lies in (lo, hi] (its
    `Distance` region, which a `conjunction` reads)."""
    region = Distance(lo, hi, lay, miss)

    def ratio(a: OnTable, b: OnTable) -> float:
        return gap(a, b) / max(extent(a), extent(b), 1e-6)

    def accepts(a: OnTable, b: OnTable) -> bool:
        return lo < ratio(a, b) <= hi and on_table(a) and on_table(b)

    def clear(a: OnTable, b: OnTable) -> bool:
        r = ratio(a, b)
        return accepts(a, b) and lay[0] * 0.8 <= r <= lay[1] * 1.2 and gap(a, b) > 0.02 * (lo > 0 or lay[0] > 0.2)

    def _at(rng: np.random.Generator, fa: float, fb: float, span: tuple[float, float],
            least: float = 0.0) -> tuple[float, float]:
        theta = rng.uniform(0.0, 2 * math.pi)
        # square boxes: the gap along the bigger axis component
        g = max(max(fa, fb) * rng.uniform(*span), least)
        length = touch_length(theta, fa, fb, g)
        return length * math.cos(theta), length * math.sin(theta)

    return TrainerRelation(name, name, accepts, clear, lambda r, fa, fb: _at(r, fa, fb, lay, APART_MIN),
                           lambda r, fa, fb: _at(r, fa, fb, miss), aliases=aliases, distance=region,
                           symmetric=True)


def comparative(name: str, larger: bool, aliases: tuple[str, ...] = (), converse: str | None = None) -> TrainerRelation:
    """a is larger (or smaller) than b: by catalogued size, wherever they stand; `converse`,
    the comparative that says it the other way round."""
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
        return ring(rng, rng.uniform(0.0, 2 * math.pi), 0.0, max(fa, fb) * rng.uniform(*PLACE_DISTANCE))

    return TrainerRelation(name, name, accepts, accepts, side_by_side, side_by_side, sizes=sizes,
                           near_miss_sizes=same, positional=False, aliases=aliases, converse=converse)


def on() -> TrainerRelation:
    """a rests on b."""

    def offset(rng: np.random.Generator, fa: float, fb: float) -> tuple[float, float]:
        return ring(rng, rng.uniform(0.0, 2 * math.pi), 0.0, 0.5 * fb * rng.uniform(*ON_TOP_OFFSET))

    def near_miss(rng: np.random.Generator, fa: float, fb: float) -> tuple[float, float]:
        theta = math.radians(90.0 * int(rng.integers(4)))
        length = touch_length(theta, fa, fb, LAY_TOUCH_GAP)
        return length * math.cos(theta), length * math.sin(theta)

    return TrainerRelation("on", "on", resting_on, resting_on, offset, near_miss, stacked=True,
                           aliases=("on top of", "onto", "upon"))
