"""Where a relation word holds, as `aileen memory show` says it: its learned regions in words.

Why: a relation word's direction and distance are not facts of its generalizations (those
hold every grain a few examples happened to fall in) but regions the size principle reads
from its examples and near misses (`extent`, `reach`). A researcher checking the grain a word
was learned at needs the region itself: "holds 135-225 degrees, surely 146-214", not 64
sector facts with probability 1.

What is shown is the word's own reading, from its own evidence: the agent's mutual
exclusivity (a word with more than a direction may leave its side to the direction words:
`agent.directions`) weighs other words too, and can only narrow what is said here to "no side".
A word that says a side and nothing beyond it (`extent.marked`: no description holds close,
far, touching, ...) has no distance region of its own, as the agent reads it
(`Directions.reach`: how far apart its examples lay is the distance words' business); it was
shown one ("zup of" shown four times 0.2 m apart: "distance holds 0.75-1; any distance: 0 %",
where the agent took it at every distance). A word whose every description holds more keeps
its distance: mutual exclusivity may leave its side to the direction words, and its distance
is then read.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from aileen.domain import calculi
from aileen.memory import extent, reach

__all__ = ["Regions", "read", "text_lines"]

#: How angles are given (`calculi`'s convention): of the word's first object seen from its second.
ANGLES = "the first object seen from the second: 0 east (right of), 90 behind, 180 west, 270 in front"


@dataclass(frozen=True)
class Regions:
    """A relation word's learned regions: direction arcs in degrees (start, end; counter-
    clockwise) where it holds (belief >= `extent.ACCEPT`) and surely (>= `extent.SURE`), and
    how likely it holds on every side; distance ranges (gap over the larger footprint) in the
    measure holding most of the posterior, and how likely it holds at any distance. None
    where its examples show no direction or no distance, and distance None too where the
    word says a side (`says_side`: its distance is no region of its own)."""

    examples: int
    near_misses: int
    holds: tuple[tuple[float, float], ...] | None
    surely: tuple[tuple[float, float], ...] | None
    sideless: float | None
    measure: str | None
    within: tuple[tuple[float, float | None], ...] | None
    unbounded: float | None
    says_side: bool = False

    def to_json(self) -> dict[str, Any]:
        return {"examples": self.examples, "near_misses": self.near_misses,
                "direction": None if self.holds is None else
                {"holds": [list(a) for a in self.holds], "surely": [list(a) for a in self.surely or ()],
                 "every_side": round(self.sideless or 0.0, 4)},
                "distance": None if self.within is None else
                {"measure": self.measure, "holds": [list(r) for r in self.within],
                 "any_distance": round(self.unbounded or 0.0, 4)},
                "says_side": self.says_side}


def _arcs(belief: np.ndarray, at_least: float) -> tuple[tuple[float, float], ...]:
    """The runs of fine sectors whose belief is at least `at_least`, as arcs in degrees (a run
    over 0 degrees is one arc: (337.5, 22.5))."""
    fine = calculi.FINEST
    names = list(extent.fine_sectors())
    inside = belief >= at_least
    n = len(names)
    if inside.all():
        return ((0.0, 360.0),)
    if not inside.any():
        return ()
    start = next(k for k in range(n) if not inside[k - 1] and inside[k])  # a run's first sector
    out = []
    k = start
    for _ in range(n):
        if inside[k] and not inside[k - 1]:
            first = k
        if inside[k] and not inside[(k + 1) % n]:
            lo = fine.regions[names[first]][0] - fine.regions[names[first]][1] / 2
            hi = fine.regions[names[k]][0] + fine.regions[names[k]][1] / 2
            out.append((round(lo % 360.0, 2), round(hi if 0.0 < hi <= 360.0 else hi % 360.0, 2)))
        k = (k + 1) % n
    return tuple(sorted(out))


def _ranges(within: np.ndarray, at_least: float) -> tuple[tuple[float, float | None], ...]:
    """The runs of distance bands whose belief is at least `at_least`, as (from, to) gaps over
    the larger footprint (`calculi.BAND_EDGES`; None: no end)."""
    edges = list(calculi.BAND_EDGES)
    return tuple((edges[k], edges[j + 1] if j + 1 < len(edges) else None) for k, j in reach.runs(within >= at_least))


def read(concept: Any, params: Any = None) -> Regions | None:
    """The regions of a relation concept (`Concept` of the memory), None for one of no kind
    of region (a visual word, or a relation whose examples show neither). `params` (the
    memory's `SageParams`): its descriptions are read as queries match them (significant
    facts); without it, every fact of each generalization."""
    if concept.kind != "spatial":
        return None
    ctx = concept.context
    descriptions: list = [g.counts for g in ctx.generalizations] + list(ctx.examples)
    pos, neg = extent.evidence(concept.symbol, descriptions, concept.near_misses)
    rpos, rneg = reach.evidence(concept.symbol, descriptions, concept.near_misses)
    if not any(pos) and not any(rpos):
        return None
    holds = surely = sideless = None
    if any(pos):
        belief = extent.predictive(pos, neg)
        holds, surely = _arcs(belief, extent.ACCEPT), _arcs(belief, extent.SURE)
        sideless = extent.sideless(pos, neg)
    described = ([facts for _kind, _i, facts in ctx.descriptions(params)] if params is not None
                 else descriptions)
    says_side = (sideless is not None and sideless < extent.SIDELESS
                 and not all(extent.marked(d, concept.symbol) for d in described))
    measure = within = unbounded = None
    if any(rpos) and not says_side:
        r = reach.read(rpos, rneg)
        measure, within, unbounded = r.measure.name, _ranges(r.within, extent.ACCEPT), r.unbounded
    shown = max(sum(pos), reach.seen(rpos) if any(rpos) else 0)
    return Regions(shown, len(concept.near_misses), holds, surely, sideless, measure, within, unbounded, says_side)


def _arcs_text(arcs: Sequence[tuple[float, float]]) -> str:
    if not arcs:
        return "nowhere"
    if arcs == ((0.0, 360.0),):
        return "every side"
    return ", ".join(f"{a:g}-{b:g}" for a, b in arcs)


def text_lines(concept: Any, params: Any = None) -> list[str]:
    """`memory show`'s lines for a relation concept's regions (none for other concepts)."""
    r = read(concept, params)
    if r is None:
        return []
    out = [f"  learned regions (the size principle over {r.examples} examples and {r.near_misses} near misses):"]
    if r.holds is not None:
        out.append(f"    direction, degrees ({ANGLES}):")
        out.append(f"      holds {_arcs_text(r.holds)}; surely {_arcs_text(r.surely or ())}; "
                   f"every side: {100 * (r.sideless or 0.0):.0f} %")
    if r.within is not None:
        spans = ", ".join(f"{a:g}-{b:g}" if b is not None else f"from {a:g}" for a, b in r.within) or "nowhere"
        out.append(f"    distance, gap over the larger object's width ({r.measure}): holds {spans}; "
                   f"any distance: {100 * (r.unbounded or 0.0):.0f} %")
    elif r.says_side:
        out.append("    distance: no region of its own (it says a side and nothing more: how far apart its "
                   "examples lay is for distance words to say)")
    return out
