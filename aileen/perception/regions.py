"""Region sampling: a concrete table position that satisfies qualitative constraints.

The planner decides `place(o1, region)` qualitatively, e.g. `w(o1,o2)` and `dc(o1,o2)`;
this module turns such a conjunction into a point (x, y) for the centre of o1, the object
to be placed. The constraint set is a convex region for the sectors (two half-planes each,
clipped to the table), a ring around the reference box for `ec`, and the outside of the
reference box widened for `dc`; every other object is an obstacle the placed object must
clear by `margin`, so the world can execute the placement without pushing anything.

Sampling draws from the tightest proposal (the `ec` ring, else the polygon of all sector
constraints, and for a distance relation also rings around its reference), rejects what
fails, and *verifies* every accepted point by recomputing the QSRs of the would-be box with
`geometry.relations` (with a little slack, so a point is not accepted on a sector boundary where
a pixel of detector noise would flip it: every relation must hold for the centre moved by the
slack, and a distance or size relation also for both footprints measured that much smaller
or larger). When no point exists -- provably (empty polygon, a relation that needs overlap)
or after the sample budget -- `RegionEmpty` names the constraints.

Of the points that pass, the most robust is taken: the one whose relations still hold under
the largest slack (up to `ROBUST_LEVELS` times the default). A place target on the edge of a
relation comes true in the plan and false once the object is seen again, and an edge the
calculus draws ("close": under 0.4 widths apart) is not where a person draws it; the middle
of the region is where both agree (issue 22: "near" placed at 0.39 widths was judged not near).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping, Sequence

import numpy as np

from aileen.domain import calculi
from aileen.errors import UserError
from aileen.world.geometry import DEFAULT_Q, RCC8, Box, gap, rcc8
from aileen.terms import Term
from aileen.world.camera import Table
from aileen.world.stacks import ON_TOP_OFFSET

__all__ = ["RegionEmpty", "sample_region", "region_ok", "robustness", "DEFAULT_MARGIN", "DEFAULT_SLACK"]

# Clearance from every object that is not meant to touch (metres): more than the RCC8 margin
# q, so a `dc` placement is still `dc` after re-perception, and enough to keep physics quiet.
DEFAULT_MARGIN = 0.02
# A sampled centre must keep its sector when moved by this much in x and y (about a pixel).
DEFAULT_SLACK = 0.005
# An `ec` placement leaves this fraction of q between the boxes: no physical contact (the
# world would push), and room for a pixel of box noise on both boxes before it reads `dc`.
EC_GAP = 0.3
# Robustness: how many multiples of the slack a chosen point is checked against, and how many
# passing points are compared before the most robust is taken.
ROBUST_LEVELS = 4
CANDIDATES = 24
# Distance relations (`qdist`): half the draws come from rings around the reference, with the
# gap between the footprints uniform up to this (metres), so a narrow band of gaps is found.
RING_REACH = 0.6
_OVERLAP = frozenset({"po", "eq", "tpp", "ntpp", "tppi", "ntppi"})
# The distance relations (how far apart, relative to the objects' size).
_DISTANCES = frozenset(calculi.QDIST.relations) | frozenset(r for c in calculi.FINER for r in c.relations)


class RegionEmpty(UserError):
    """No free table position satisfies the constraints."""


def _normalise(relations: Sequence[Term], boxes: Mapping[str, Box], subject: str | None) -> tuple[str, list[tuple[str, str]]]:
    """Find the placed object and rewrite every constraint as (predicate, reference id) with
    the placed object first."""
    rels = list(relations)
    for t in rels:
        if not isinstance(t, Term) or t.arity != 2 or t.name not in _inverse():
            raise UserError(
                f"bad placement constraint {t}: expected a binary QSR, one of {' '.join(sorted(_inverse()))}"
            )
    if subject is None:
        if not rels:
            raise UserError("sample_region needs a subject when there are no constraints")
        common = set(str(a) for a in rels[0].args)
        for t in rels[1:]:
            common &= {str(a) for a in t.args}
        not_seen = [c for c in common if c not in boxes]
        subject = not_seen[0] if len(not_seen) == 1 else str(rels[0].args[0])
    out: list[tuple[str, str]] = []
    for t in rels:
        a, b = str(t.args[0]), str(t.args[1])
        if a == subject and b != subject:
            pred, ref = str(t.name), b
        elif b == subject and a != subject:
            pred, ref = _inverse()[str(t.name)], a
        else:
            raise UserError(f"placement constraint {t} does not relate {subject} to another object")
        if ref not in boxes:
            raise UserError(f"placement constraint {t} names {ref}, which is not on the table")
        out.append((pred, ref))
    return subject, out


def _describe(cons: Sequence[tuple[str, str]], subject: str) -> str:
    return " and ".join(f"{p}({subject},{r})" for p, r in cons) or "(no constraints)"


def _clip(poly: list[tuple[float, float]], nx: float, ny: float, c: float) -> list[tuple[float, float]]:
    """Sutherland-Hodgman: keep the part of a convex polygon where nx*x + ny*y <= c."""
    out: list[tuple[float, float]] = []
    n = len(poly)
    for i in range(n):
        p, q = poly[i], poly[(i + 1) % n]
        fp = nx * p[0] + ny * p[1] - c
        fq = nx * q[0] + ny * q[1] - c
        if fp <= 0:
            out.append(p)
        if (fp < 0 < fq) or (fq < 0 < fp):
            t = fp / (fp - fq)
            out.append((p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])))
    return out


@functools.lru_cache(maxsize=4)
def _tables(version: int) -> tuple[dict[str, str], dict[str, tuple[calculi.Calculus, float, float]], tuple[str, ...]]:
    """Read from the declared calculi once per `calculi.version()` (a calculus declared after
    this module was imported is in them): the converse of each predicate (for constraints
    written with the placed object second); the direction predicates of every grain, each with
    its calculus and its wedge (centre and width in degrees, counter-clockwise from east:
    `Calculus.regions`); and those that have none (`*_eq`)."""
    inverse = {r: c.converse_of(r) for c in calculi.CALCULI for r in c.relations}
    wedges = {r: (c, centre, width) for c in calculi.CALCULI for r, (centre, width) in c.regions.items()}
    none = tuple(r for c in calculi.CALCULI if c.is_direction for r in c.relations if r not in c.regions)
    return inverse, wedges, none


def _inverse() -> dict[str, str]:
    return _tables(calculi.version())[0]


def _wedges() -> dict[str, tuple[calculi.Calculus, float, float]]:
    return _tables(calculi.version())[1]


def _no_direction() -> tuple[str, ...]:
    return _tables(calculi.version())[2]


def _sector_halfplanes(pred: str, ref_centre: tuple[float, float]) -> list[tuple[float, float, float]]:
    """Half-planes nx*x + ny*y <= c whose intersection is the wedge of directions `pred` names
    around ref_centre (at most 90 degrees wide, so convex)."""
    _calc, centre, width = _wedges()[pred]
    cx, cy = ref_centre
    mid = math.radians(centre)
    mx, my = math.cos(mid), math.sin(mid)  # the wedge's bisector, from ref toward p
    planes = []
    for a in (math.radians(centre - width / 2), math.radians(centre + width / 2)):
        ux, uy = math.cos(a), math.sin(a)  # a boundary ray from ref
        nx, ny = uy, -ux  # a normal of that ray ...
        if nx * mx + ny * my > 0:  # ... turned to point away from the bisector (outside)
            nx, ny = -nx, -ny
        planes.append((nx, ny, nx * cx + ny * cy))
    return planes


def _polygon_sampler(poly: list[tuple[float, float]]):
    """Uniform sampler over a convex polygon (fan triangulation)."""
    tris = [(poly[0], poly[i], poly[i + 1]) for i in range(1, len(poly) - 1)]
    areas = np.array([abs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])) / 2 for a, b, c in tris])
    total = float(areas.sum())
    if total <= 1e-12:
        return None, 0.0
    cum = np.cumsum(areas) / total

    def draw(rng: np.random.Generator) -> tuple[float, float]:
        i = int(np.searchsorted(cum, rng.random(), side="right"))
        a, b, c = tris[min(i, len(tris) - 1)]
        r1, r2 = rng.random(), rng.random()
        if r1 + r2 > 1:
            r1, r2 = 1 - r1, 1 - r2
        return (a[0] + r1 * (b[0] - a[0]) + r2 * (c[0] - a[0]), a[1] + r1 * (b[1] - a[1]) + r2 * (c[1] - a[1]))

    return draw, total


def _ring_point(box: Box, half: tuple[float, float], g: float, rng: np.random.Generator) -> tuple[float, float]:
    """A centre whose rectangle of half-sides `half` (x, y) has gap exactly g to `box`: a point
    on the boundary of the box widened by half + g, uniform by length."""
    hx, hy = half
    x0, y0, x1, y1 = box[0] - hx - g, box[1] - hy - g, box[2] + hx + g, box[3] + hy + g
    w, h = x1 - x0, y1 - y0
    s = rng.random() * 2 * (w + h)
    if s < w:
        return x0 + s, y0
    s -= w
    if s < h:
        return x1, y0 + s
    s -= h
    if s < w:
        return x1 - s, y1
    s -= w
    return x0, y1 - s


#: The room an object to be placed takes: a square's side (m), or its box's (width, depth).
Footprint = float | tuple[float, float]


def _halves(footprint: Footprint) -> tuple[float, float]:
    """Half the width and half the depth of a footprint: a box lying across the table (a
    capsule on a diagonal is wider one way than the other) keeps both, so that "touching"
    puts its box against the other's on either side (a square of its longer side left a gap)."""
    if isinstance(footprint, tuple):
        return footprint[0] / 2, footprint[1] / 2
    return footprint / 2, footprint / 2


def _square(x: float, y: float, half: float | tuple[float, float]) -> Box:
    hx, hy = half if isinstance(half, tuple) else (half, half)
    return (x - hx, y - hy, x + hx, y + hy)


def region_ok(
    x: float,
    y: float,
    obj_footprint: Footprint,
    constraints: Sequence[tuple[str, str]],
    boxes: Mapping[str, Box],
    table: Table,
    *,
    margin: float = DEFAULT_MARGIN,
    q: float = DEFAULT_Q,
    slack: float = DEFAULT_SLACK,
    allow_overlap: bool = False,
) -> bool:
    """Whether a centre (x, y) for a square of side obj_footprint (or a box of its (width,
    depth)) satisfies every (predicate, reference) constraint robustly and clears the table
    edge and every object."""
    half = _halves(obj_footprint)
    side = 2 * max(half)  # what the calculi read as its size, as for a reference's box
    if not (half[0] + margin / 2 <= x <= table.width - half[0] - margin / 2
            and half[1] + margin / 2 <= y <= table.depth - half[1] - margin / 2):
        return False
    me = _square(x, y, half)
    touching = {r for p, r in constraints if p == "ec" or (allow_overlap and p in _OVERLAP)}
    # what the placed object must be at a distance from is cleared only as far as `dc` needs,
    # robustly (q and the slack), so "close" keeps room between `dc` and its far edge
    spaced = {r for p, r in constraints if p in _DISTANCES}
    for oid, b in boxes.items():
        if oid in touching:
            continue
        if gap(me, b) <= (q + DEFAULT_SLACK if oid in spaced else max(margin, q)):
            return False
    for pred, ref in constraints:
        b = boxes[ref]
        if pred in RCC8:
            if pred == "ec":
                g = gap(me, b)
                # no physical overlap, and within q with room for detector noise
                if not (0.0 < g <= q - slack / 2):
                    return False
            elif rcc8(me, b, q=q) != pred:
                return False
        elif pred in _wedges() or pred in _no_direction():
            # the sector must hold for the centre moved by +-slack on both axes
            calc = calculi.calculus_of(pred)
            assert calc is not None
            ref = _Body(b, max(b[2] - b[0], b[3] - b[1]))
            for sx in (-slack, slack):
                for sy in (-slack, slack):
                    if calc.compute(_Body(_square(x + sx, y + sy, half), side), ref) != pred:
                        return False
        elif calculi.is_finer(pred):
            # a distance band is a few millimetres wide near the object: the goal is the band
            # at the centre drawn, its neighbours being where the word holds too (the goal is
            # the middle of the bands it surely holds of: `reach.surest`)
            calc = calculi.calculus_of(pred)
            assert calc is not None
            if calc.compute(_Body(me, side), _Body(b, max(b[2] - b[0], b[3] - b[1]))) != pred:
                return False
        else:
            calc = calculi.calculus_of(pred)
            if calc is None:
                return False
            # the centre moved by the slack, both footprints measured that much off
            ref_fp = max(b[2] - b[0], b[3] - b[1])
            for sx in (-slack, slack):
                for sy in (-slack, slack):
                    moved = _square(x + sx, y + sy, half)
                    for d in (-slack, slack):
                        if calc.compute(_Body(moved, side + d), _Body(b, ref_fp + d)) != pred:
                            return False
    return True


def robustness(x: float, y: float, obj_footprint: Footprint, constraints: Sequence[tuple[str, str]],
               boxes: Mapping[str, Box], table: Table, *, slack: float = DEFAULT_SLACK,
               levels: int = ROBUST_LEVELS, **kw: object) -> int:
    """How many multiples of `slack` (up to `levels`) the point's relations survive: 0 when it
    fails `region_ok` at `slack` itself."""
    k = 0
    while k < levels and region_ok(x, y, obj_footprint, constraints, boxes, table, slack=(k + 1) * slack, **kw):
        k += 1
    return k


class _Body:
    """A would-be placement (or a reference box) as the calculi see it: on the table."""

    level = 0

    def __init__(self, box: Box, footprint: float) -> None:
        self.box_m = box
        self.footprint = footprint


def sample_region(
    obj_footprint: Footprint,
    relations: Sequence[Term],
    boxes: Mapping[str, Box],
    table: Table,
    rng: np.random.Generator,
    *,
    margin: float = DEFAULT_MARGIN,
    q: float = DEFAULT_Q,
    slack: float = DEFAULT_SLACK,
    subject: str | None = None,
    allow_overlap: bool = False,
    tries: int = 4000,
) -> tuple[float, float]:
    """A centre (x, y) in table metres for the object to be placed (a square of side
    `obj_footprint`, or a box of its (width, depth)) such that every relation in `relations` holds against `boxes`, the
    object stays on the table and clears every other box by `margin`.

    `relations` are terms such as `w(o1,o2)`, `dc(o1,o2)` (o1 the object to be placed; it
    may also appear second, `e(o2,o1)`, which is read as `w(o1,o2)`). The placed object is
    `subject`, or else the one argument shared by all relations that is not in `boxes`, or
    else the first argument of the first relation. Its own box, if present, is ignored.
    Raises `RegionEmpty` naming the constraints when no such position exists (or none was
    found in `tries` samples), `UserError` for malformed constraints.
    """
    if not all(v > 0 for v in (obj_footprint if isinstance(obj_footprint, tuple) else (obj_footprint,))):
        raise UserError(f"footprint must be positive, got {obj_footprint}")
    subject, cons = _normalise(relations, boxes, subject)
    others = {k: tuple(map(float, v)) for k, v in boxes.items() if k != subject}
    desc = _describe(cons, subject)
    half = _halves(obj_footprint)
    side = 2 * max(half)
    for pred, ref in cons:
        if pred in _no_direction():
            raise RegionEmpty(f"no free position for {desc}: {pred}({subject},{ref}) puts the centre on {ref}'s centre")
        if pred in _OVERLAP and not allow_overlap:
            raise RegionEmpty(f"no free position for {desc}: {pred}({subject},{ref}) needs {subject} to overlap {ref}")
    # Feasible centres: the table shrunk by the half side, cut by every sector's half-planes.
    lx, ly = half[0] + margin / 2, half[1] + margin / 2
    poly = [(lx, ly), (table.width - lx, ly), (table.width - lx, table.depth - ly), (lx, table.depth - ly)]
    if table.width - lx <= lx or table.depth - ly <= ly:
        raise RegionEmpty(f"no free position for {desc}: an object of {side:.2f} m does not fit on the table")
    for pred, ref in cons:
        if pred in _wedges():
            for nx, ny, c in _sector_halfplanes(pred, _centre(others[ref])):
                poly = _clip(poly, nx, ny, c)
                if len(poly) < 3:
                    raise RegionEmpty(f"no free position for {desc}: the {pred} sector of {ref} misses the table")
    draw_poly, area = _polygon_sampler(poly)
    if draw_poly is None:
        raise RegionEmpty(f"no free position for {desc}: the sectors do not intersect on the table")
    ec_refs = [r for p, r in cons if p == "ec"]
    spaced = [r for p, r in cons if p in _DISTANCES]
    kw = dict(margin=margin, q=q, allow_overlap=allow_overlap)
    found: list[tuple[float, float]] = []
    for k in range(tries):
        if ec_refs:
            x, y = _ring_point(others[ec_refs[0]], half, EC_GAP * q, rng)
        elif spaced and k % 2:
            x, y = _ring_point(others[spaced[0]], half, rng.uniform(0.0, RING_REACH), rng)
        else:
            x, y = draw_poly(rng)
        if region_ok(x, y, obj_footprint, cons, others, table, slack=slack, **kw):
            found.append((float(x), float(y)))
            if len(found) >= CANDIDATES:
                break
    if found:
        # the first of the most robust (an `ec` ring point is as robust as it gets already)
        scores = [0 if ec_refs else robustness(x, y, obj_footprint, cons, others, table, slack=slack, **kw)
                  for x, y in found]
        return found[scores.index(max(scores))]
    raise RegionEmpty(
        f"no free position for {desc}: the table has no room for an object of {side:.2f} m there "
        f"(clearance {margin:.2f} m; {tries} samples)"
    )


ON_TOP_TRIES = 32  # draws of a spot on top that lies `within` before the centre is pulled in


def on_top_of(box: Box, rng: np.random.Generator, within: Box | None = None) -> tuple[float, float]:
    """A centre (x, y) over the object in `box` for an object put on top of it. `within`: the
    box (x0, y0, x1, y1) that centre must lie in (the table, less the mover's own half
    extent: a carrier near the edge leaves only its inner side); a draw outside it is drawn
    again, and when none lands inside, the carrier's centre is pulled into it."""
    cx, cy = _centre(box)
    half = 0.5 * min(box[2] - box[0], box[3] - box[1])
    for _ in range(ON_TOP_TRIES):
        theta = rng.uniform(0.0, 2 * math.pi)
        r = half * rng.uniform(*ON_TOP_OFFSET)
        x, y = cx + r * math.cos(theta), cy + r * math.sin(theta)
        if within is None or (within[0] <= x <= within[2] and within[1] <= y <= within[3]):
            return x, y
    assert within is not None
    return min(max(cx, within[0]), within[2]), min(max(cy, within[1]), within[3])


def _centre(b: Box) -> tuple[float, float]:
    return (b[0] + b[2]) / 2, (b[1] + b[3]) / 2
