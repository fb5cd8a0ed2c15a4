"""Which perceived object is which true one: the pairing `aileen perception eval` grades on.

A perceived object can only be a true one whose centre lies within `MATCH_FRACTION` of that
object's footprint. Apart from stacks that leaves at most one candidate: two objects on the
table stand a footprint apart. In a stack it does not. An object resting near the middle
of another has its centre within a centimetre or two of the lower one's, and the detector
boxes the lower one's whole footprint from the sliver that shows, so both detections lie
within reach of both true objects, a few millimetres apart. Pairing them nearest first
(`greedy`, the rule until stop 37) then decides by those millimetres: in 1,000 stacked
scenes it paired a perceived green cone on a red cylinder, both read right, the other way
round, and graded two level, two colour and two shape errors where perception had made
none.

The rule (`AGREE`): nearest first says which objects pair (which true ones are missed,
which perceived ones spurious), as before. Then, where the same objects can be paired
another way whose total distance lies within `TIE_M` of that one (positions cannot tell
the two apart: the centroid error's 99th percentile on stacked scenes is about 1 cm), the
pairing whose pairs agree on the most attributes (shape, colour, size, level) says which is
which. Positions still decide wherever they can: a perceived object more than `TIE_M`
nearer one true object keeps it, whatever its attributes. Tried and not taken: letting the
attributes also choose which objects pair (a stack read as one object then missed the
whole upper object rather than the sliver of the lower one, which moved misses from partly
hidden objects to whole ones), and the assignment of least total distance instead of
nearest first (it moved shape errors between objects, not fewer). `GREEDY` is nearest first
alone, the rule until stop 37, for comparison.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

__all__ = ["AGREE", "GREEDY", "MATCHINGS", "MATCH_FRACTION", "TIE_M", "match"]

# A perceived object pairs with a true one only within this share of its footprint.
MATCH_FRACTION = 0.4
# Pairings whose total centre distance differs by less than this (metres) are a tie for
# positions (about the 99th percentile of the centroid error on stacked scenes).
TIE_M = 0.01
AGREE, GREEDY = "agree", "greedy"
MATCHINGS = (AGREE, GREEDY)
# A group of candidates this large is paired greedily (every pairing of a group is tried;
# scenes of a few objects make groups of two to four).
MAX_GROUP_PAIRS = 16

Pair = tuple[int, int, float]  # (perceived index, true index, distance in metres)


def match(pred: Sequence[tuple[float, float]], truth: Sequence[tuple[float, float, float]],
          agree: Callable[[int, int], int] | None = None, *, rule: str = AGREE) -> list[Pair]:
    """One-to-one pairs (perceived index, true index, distance) of perceived centres (x, y)
    and true ones (x, y, footprint), each within `MATCH_FRACTION` of the footprint, by
    `rule` (see the module doc). `agree(i, j)`: how many attributes perceived object i and
    true object j share (without it, nearest first alone)."""
    if rule not in MATCHINGS:
        raise ValueError(f"unknown matching {rule!r}: expected one of {', '.join(MATCHINGS)}")
    cands: list[Pair] = []
    for i, (px, py) in enumerate(pred):
        for j, (tx, ty, f) in enumerate(truth):
            d = math.hypot(px - tx, py - ty)
            if d < MATCH_FRACTION * f:
                cands.append((i, j, d))
    pairs = _greedy(cands)
    if rule == GREEDY or agree is None:
        return pairs
    out: list[Pair] = []
    for group in _groups(cands):
        chosen = [p for p in pairs if p in group]
        out += chosen if len(group) > MAX_GROUP_PAIRS or len(chosen) < 2 else _swapped(group, chosen, agree)
    return sorted(out, key=lambda p: (p[2], p[0], p[1]))


def _greedy(cands: Sequence[Pair]) -> list[Pair]:
    """Nearest first, each object once."""
    used_p: set[int] = set()
    used_t: set[int] = set()
    out = []
    for i, j, d in sorted(cands, key=lambda p: (p[2], p[0], p[1])):
        if i in used_p or j in used_t:
            continue
        used_p.add(i)
        used_t.add(j)
        out.append((i, j, d))
    return out


def _groups(cands: Sequence[Pair]) -> list[list[Pair]]:
    """The candidates in groups that share no object with another group (connected parts of
    the graph of candidate pairs), in the order of their first candidate."""
    parent: dict[tuple[str, int], tuple[str, int]] = {}

    def root(x: tuple[str, int]) -> tuple[str, int]:
        while parent.setdefault(x, x) != x:
            x = parent[x]
        return x

    for i, j, _ in cands:
        parent[root(("p", i))] = root(("t", j))
    groups: dict[tuple[str, int], list[Pair]] = {}
    for c in cands:
        groups.setdefault(root(("p", c[0])), []).append(c)
    return list(groups.values())


def _swapped(group: Sequence[Pair], chosen: Sequence[Pair], agree: Callable[[int, int], int]) -> list[Pair]:
    """The pairing of the same objects as `chosen` (nearest first) within `TIE_M` of its
    total distance whose pairs agree on the most attributes (every pairing of the group
    tried), `chosen` where none agrees on more."""
    objs = ({i for i, _, _ in chosen}, {j for _, j, _ in chosen})
    inside = [c for c in group if c[0] in objs[0] and c[1] in objs[1]]
    limit = sum(d for _, _, d in chosen) + TIE_M
    best, best_agree = list(chosen), sum(agree(i, j) for i, j, _ in chosen)

    def extend(k: int, picked: tuple[Pair, ...], used_p: frozenset[int], used_t: frozenset[int]) -> None:
        nonlocal best, best_agree
        if len(picked) == len(chosen):
            score = sum(agree(i, j) for i, j, _ in picked)
            if score > best_agree and sum(d for _, _, d in picked) <= limit:
                best, best_agree = list(picked), score
            return
        if k == len(inside):
            return
        extend(k + 1, picked, used_p, used_t)
        i, j, _ = inside[k]
        if i not in used_p and j not in used_t:
            extend(k + 1, picked + (inside[k],), used_p | {i}, used_t | {j})

    extend(0, (), frozenset(), frozenset())
    return best
