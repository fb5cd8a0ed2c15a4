"""Which of two overlapping objects is on top, from the detector's level score.

The detector scores, at each object's centre, whether that object rests on another (it sees
the whole of the upper object drawn over part of the lower one, and the upper one's soft
shadow on it). A score alone is not a stack: an object is read as on top only when its box
overlaps another detection's box that scores lower, since something must carry it; and a
stack is at most two high, so of two overlapping objects that both score high only the
higher one is on top.

The lower object of a stack, and any neighbour an upper object reaches over, learns which
boxes cover it (`Detection.occluders`): its colour
and size are then measured on the part of it that shows (see `aileen.perception.color` and
`aileen.perception.size`), not on the pixels of what rests on it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

from aileen.perception.detector import Detection

__all__ = ["resolve_levels", "LEVEL_THRESHOLD", "MIN_OVERLAP"]

LEVEL_THRESHOLD = 0.5
# Boxes must share at least this share of the smaller box's area to count as one on the
# other: neighbours that touch (or turned boxes whose axis-aligned boxes clip) share less.
MIN_OVERLAP = 0.1

Box = tuple[float, float, float, float]


def _overlap(a: Box, b: Box) -> float:
    """Intersection area of two boxes over the smaller box's area."""
    w = min(a[2], b[2]) - max(a[0], b[0])
    h = min(a[3], b[3]) - max(a[1], b[1])
    if w <= 0 or h <= 0:
        return 0.0
    small = min((a[2] - a[0]) * (a[3] - a[1]), (b[2] - b[0]) * (b[3] - b[1]))
    return w * h / max(small, 1e-9)


def resolve_levels(dets: Sequence[Detection], *, threshold: float = LEVEL_THRESHOLD) -> list[Detection]:
    """The detections (same order) with `level` set (1 for an object on another) and, for
    each object on the table, `occluders`: the pixel boxes of what rests on it and of any
    upper object that reaches over it."""
    level = [0] * len(dets)
    lower_of: dict[int, int] = {}
    carries: dict[int, int] = {}
    order = sorted(range(len(dets)), key=lambda i: -dets[i].level_score)
    for i in order:
        d = dets[i]
        if d.level_score <= threshold or i in carries:
            continue
        best, best_overlap = None, MIN_OVERLAP
        for j, e in enumerate(dets):
            if j == i or level[j] or j in carries or e.level_score >= d.level_score:
                continue
            ov = _overlap(d.box_px, e.box_px)
            if ov >= best_overlap:
                best, best_overlap = j, ov
        if best is not None:
            level[i] = 1
            lower_of[i] = best
            carries[best] = i
    out = []
    for i, d in enumerate(dets):
        # What rests on it, and any other object up on a stack that reaches over it.
        occ = tuple(dets[u].box_px for u, low in lower_of.items() if low == i)
        if not level[i]:
            occ += tuple(dets[u].box_px for u, low in lower_of.items() if low != i and _overlap(d.box_px, dets[u].box_px) > 0)
        out.append(replace(d, level=level[i], occluders=occ))
    return out
