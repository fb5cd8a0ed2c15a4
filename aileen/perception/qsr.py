"""Qualitative spatial relations between boxes on the table: cardinal direction and RCC8.

The definitions are QSRlib's (QSRlib itself does not run on Python 3), restated in
`../shared/DESIGN.md` section 7, always in *table* coordinates (metres, +x east, +y north):
image boxes must be converted with the camera first, since image v grows southwards.

One predicate per relation, `d(a,b)` reads "a lies to the d of b" (see docs/architecture.md):
cardinal `n ne e se s sw w nw`, `cdc_eq` when the centres coincide; RCC8 `dc ec po eq tpp
ntpp tppi ntppi`, where `tpp(a,b)` means a is a tangential proper part of b.

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
    "rcc8",
    "relations",
    "qsr_facts",
]

Box = tuple[float, float, float, float]  # (x0, y0, x1, y1), metres, x0 <= x1, y0 <= y1

# Sector order of QSRlib's cardinal direction calculus, indexed by floor((angle + 22.5) / 45).
CARDINALS: tuple[str, ...] = ("s", "sw", "w", "nw", "n", "ne", "e", "se")
CDC_EQ = "cdc_eq"
RCC8: tuple[str, ...] = ("dc", "ec", "po", "eq", "tpp", "ntpp", "tppi", "ntppi")
QSR_PREDICATES: frozenset[str] = frozenset(CARDINALS) | {CDC_EQ} | frozenset(RCC8)

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


def cardinal(a: Box, b: Box, *, tol: float = DEFAULT_EQ_TOL) -> str:
    """Cardinal direction of `a` relative to `b` from box centres: the predicate name
    (`w` means a lies west of b), or `cdc_eq` when the centres are within `tol`."""
    ax, ay = centre(a)
    bx, by = centre(b)
    dx = bx - ax
    dy = by - ay
    if abs(dx) <= tol and abs(dy) <= tol:
        return CDC_EQ
    angle = math.degrees(math.atan2(dx, dy)) + 22.5
    if angle < 0:
        angle += 360.0
    return CARDINALS[int(angle // 45.0) % 8]


def _inside(a: Box, b: Box, q: float) -> bool:
    """a lies inside b, allowing each edge to stick out by up to q."""
    return a[0] >= b[0] - q and a[1] >= b[1] - q and a[2] <= b[2] + q and a[3] <= b[3] + q


def _touches_edge(a: Box, b: Box, q: float) -> bool:
    """Some edge of a is within q of the corresponding edge of b (containment is tangential)."""
    return any(abs(a[i] - b[i]) <= q for i in range(4))


def rcc8(a: Box, b: Box, *, q: float = DEFAULT_Q) -> str:
    """RCC8 relation of box `a` to box `b` with quantisation margin `q` (metres).

    eq: every edge pair within q. dc: the boxes are more than q apart on some axis. Containment
    (with q slack) is tpp / tppi when an edge pair is within q, else ntpp / ntppi. ec: the gap
    or overlap is within q. po otherwise.
    """
    if all(abs(a[i] - b[i]) <= q for i in range(4)):
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
