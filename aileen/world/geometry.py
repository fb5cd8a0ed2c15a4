"""The table's box geometry and the qualitative spatial relations (QSRs) defined on it:
centres, gaps, bearings and sectors; directions (8 sectors or 4 cones) and RCC8.

Pure arithmetic on boxes in table metres, so it stands below both its readers: the domain's
calculi (`aileen.domain.calculi`) compute their relations with it, and perception (region
sampling, `aileen.perception.regions`) checks a sampled spot with it.

The definitions are QSRlib's (QSRlib itself does not run on Python 3), restated in
`../shared/DESIGN.md` section 7, always in *table* coordinates (metres, +x east, +y north):
image boxes must be converted with the camera first, since image v grows southwards.

One predicate per relation, `d(a,b)` reads "a lies to the d of b" (see docs/architecture.md):
cardinal `n ne e se s sw w nw`, `cdc_eq` when the centres coincide; the four cones `cone_n
cone_e cone_s cone_w` (`cone_eq`); RCC8 `dc ec po eq tpp ntpp tppi ntppi`, where `tpp(a,b)`
means a is a tangential proper part of b.

The direction grains (`aileen.domain.calculi.DIRECTIONS`): QSRlib's cardinal directions cut
the circle into 8 sectors of 45 degrees; the cone-based cardinal directions (Frank 1991,
"Qualitative spatial reasoning about cardinal directions") into 4 cones of 90 degrees around
the axes; `heading` and `sector_index` give any finer grain (16 and 64 sectors). Which grain a
word means is learned from its examples (aileen/memory/extent.py).

The RCC8 quantisation margin `q` absorbs perception noise: boxes whose gap (or overlap) is
within `q` are externally connected, so two objects that touch on the table read `ec`
even when the detector's boxes are a pixel apart or overlap by a pixel.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

from aileen.terms import Term, fn

__all__ = [
    "Box",
    "CARDINALS",
    "RCC8",
    "QSR_PREDICATES",
    "DEFAULT_Q",
    "DEFAULT_EQ_TOL",
    "centre",
    "gap",
    "cardinal",
    "cone",
    "heading",
    "sector_index",
    "CONES",
    "CONE_EQ",
    "rcc8",
    "relations",
    "qsr_facts",
]

Box = tuple[float, float, float, float]  # (x0, y0, x1, y1), metres, x0 <= x1, y0 <= y1

# Sector order of QSRlib's cardinal direction calculus, indexed by floor((angle + 22.5) / 45).
CARDINALS: tuple[str, ...] = ("s", "sw", "w", "nw", "n", "ne", "e", "se")
CDC_EQ = "cdc_eq"
# Cone order of the cone-based directions, indexed by floor((angle + 45) / 90), angle as above.
CONES: tuple[str, ...] = ("cone_s", "cone_w", "cone_n", "cone_e")
CONE_EQ = "cone_eq"
RCC8: tuple[str, ...] = ("dc", "ec", "po", "eq", "tpp", "ntpp", "tppi", "ntppi")
QSR_PREDICATES: frozenset[str] = frozenset(CARDINALS) | {CDC_EQ} | frozenset(CONES) | {CONE_EQ} | frozenset(RCC8)

# One image pixel is 1/256 m = 3.9 mm on the default camera; detector boxes are good to about
# a pixel per edge, so 1 cm covers the noise of both boxes without calling a 2 cm gap `ec`.
DEFAULT_Q = 0.01
# Centres closer than this (metres) have no direction: `cdc_eq`.
DEFAULT_EQ_TOL = 1e-3


def centre(box: Box) -> tuple[float, float]:
    """Centre of a box."""
    x0, y0, x1, y1 = box
    return (x0 + x1) / 2.0, (y0 + y1) / 2.0


def gap(a: Box, b: Box) -> float:
    """Signed separation of two boxes: > 0 the width of the widest empty band between them
    along an axis, <= 0 they overlap (minus the smaller of the two axis overlaps)."""
    gx = max(b[0] - a[2], a[0] - b[2])
    gy = max(b[1] - a[3], a[1] - b[3])
    return max(gx, gy)


def _bearing(a: Box, b: Box, tol: float) -> float | None:
    """Compass angle (degrees, [0, 360)) of b - a between the centres; None when they coincide."""
    ax, ay = centre(a)
    bx, by = centre(b)
    dx = bx - ax
    dy = by - ay
    if abs(dx) <= tol and abs(dy) <= tol:
        return None
    return math.degrees(math.atan2(dx, dy)) % 360.0


def _sector(angle: float, names: tuple[str, ...]) -> str:
    """The name of the sector (one of len(names), the first centred on angle 0) holding angle."""
    width = 360.0 / len(names)
    return names[int(((angle + width / 2) % 360.0) // width) % len(names)]


def cardinal(a: Box, b: Box, *, tol: float = DEFAULT_EQ_TOL) -> str:
    """Cardinal direction of `a` relative to `b` from box centres: the predicate name
    (`w` means a lies west of b), or `cdc_eq` when the centres are within `tol`."""
    angle = _bearing(a, b, tol)
    return CDC_EQ if angle is None else _sector(angle, CARDINALS)


def cone(a: Box, b: Box, *, tol: float = DEFAULT_EQ_TOL) -> str:
    """Cone-based direction of `a` relative to `b` (four 90-degree cones around the axes):
    `cone_w` when a lies within 45 degrees of due west of b, or `cone_eq` when the centres
    are within `tol`. A bearing exactly on a cone's edge goes to the next cone clockwise."""
    angle = _bearing(a, b, tol)
    return CONE_EQ if angle is None else _sector(angle, CONES)


def heading(a: Box, b: Box, *, tol: float = DEFAULT_EQ_TOL) -> float | None:
    """Direction of `a`'s centre from `b`'s, in degrees counter-clockwise from east, [0, 360);
    None when the centres are within `tol` (no direction)."""
    ax, ay = centre(a)
    bx, by = centre(b)
    dx, dy = ax - bx, ay - by
    if abs(dx) <= tol and abs(dy) <= tol:
        return None
    return math.degrees(math.atan2(dy, dx)) % 360.0


def sector_index(angle: float, n: int) -> int:
    """Which of `n` equal sectors holds `angle` (degrees counter-clockwise from east), sector 0
    centred on east; an angle exactly on an edge goes to the next sector counter-clockwise."""
    width = 360.0 / n
    return int(((angle + width / 2) % 360.0) // width) % n


def _inside(a: Box, b: Box, q: float) -> bool:
    """a lies inside b, allowing each edge to stick out by up to q."""
    return a[0] >= b[0] - q and a[1] >= b[1] - q and a[2] <= b[2] + q and a[3] <= b[3] + q


def _touches_edge(a: Box, b: Box, q: float) -> bool:
    """Some edge of a is within q of the corresponding edge of b (containment is tangential)."""
    return abs(a[0] - b[0]) <= q or abs(a[1] - b[1]) <= q or abs(a[2] - b[2]) <= q or abs(a[3] - b[3]) <= q


def rcc8(a: Box, b: Box, *, q: float = DEFAULT_Q) -> str:
    """RCC8 relation of box `a` to box `b` with quantisation margin `q` (metres).

    eq: every edge pair within q. dc: the boxes are more than q apart on some axis. Containment
    (with q slack) is tpp / tppi when an edge pair is within q, else ntpp / ntppi. ec: the gap
    or overlap is within q. po otherwise.
    """
    # (spelled out: perception asks it of every ordered pair, twice, every frame)
    if abs(a[0] - b[0]) <= q and abs(a[1] - b[1]) <= q and abs(a[2] - b[2]) <= q and abs(a[3] - b[3]) <= q:
        return "eq"
    g = gap(a, b)
    if g > q:
        return "dc"
    a_in_b, b_in_a = _inside(a, b, q), _inside(b, a, q)
    if a_in_b and b_in_a:
        # Each inside the other within the margin: equal up to q (an edge pair differs by q
        # plus rounding), and the converse must stay eq.
        return "eq"
    if a_in_b:
        return "tpp" if _touches_edge(a, b, q) else "ntpp"
    if b_in_a:
        return "tppi" if _touches_edge(a, b, q) else "ntppi"
    if g >= -q:
        return "ec"
    return "po"


def relations(a: Box, b: Box, *, q: float = DEFAULT_Q, tol: float = DEFAULT_EQ_TOL) -> tuple[str, str]:
    """(cardinal, rcc8) predicate names of a relative to b."""
    return cardinal(a, b, tol=tol), rcc8(a, b, q=q)


def qsr_facts(
    boxes: Mapping[str, Box] | Sequence[tuple[str, Box]],
    *,
    q: float = DEFAULT_Q,
    tol: float = DEFAULT_EQ_TOL,
) -> list[Term]:
    """Facts `d(a,b)` and `r(a,b)` for every ordered pair of distinct objects, in the order
    the objects are given (a major, b minor; cardinal before RCC8 for each pair)."""
    items = list(boxes.items()) if isinstance(boxes, Mapping) else list(boxes)
    facts: list[Term] = []
    for ida, ba in items:
        for idb, bb in items:
            if ida == idb:
                continue
            d, r = relations(ba, bb, q=q, tol=tol)
            facts.append(fn(d, ida, idb))
            facts.append(fn(r, ida, idb))
    return facts
