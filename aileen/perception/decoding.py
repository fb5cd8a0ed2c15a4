"""The detector's output maps read as detections: the heatmaps' peaks, one per object.

Why its own module: the network's output format (per level C shape heatmaps, the centre's
offset and the box size, at stride `STRIDE`) is read the same way at run time
(`detector.Detector.detect`) and when training validates (`train`), and the rules that turn
peaks into objects (a split peak is one object; an object in both layers' maps is one object;
a box under a stronger one of its own level is a second reading of it) are the part of
perception that changed most with stacks. `peaks.find_peaks` finds the peaks; this module
decides which of them are objects. Pure numpy.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from aileen.perception.peaks import find_peaks
from aileen.perception.pixels import overlap_share
from aileen.world.catalog import SHAPES

__all__ = ["STRIDE", "N_CLASSES", "DEFAULT_THRESHOLD", "decode", "peak_box", "carrier_peak"]

STRIDE = 8
N_CLASSES = len(SHAPES)
DEFAULT_THRESHOLD = 0.3
# Peaks of the two layers closer than this share of the smaller box side are one object.
SAME_OBJECT = 0.1
SAME_SHAPE = 0.2
SAME_SIZE = 0.1
# Per layer, the most that one detection's box may overlap a stronger one's (of the smaller
# box) before it counts as a second reading of that object (`_apart`).
LAYER_OVERLAP = (1.0, 0.1)


def decode(out: np.ndarray, *, threshold: float = DEFAULT_THRESHOLD, stride: int = STRIDE,
           split_levels: bool = True, contested: list | None = None, n_classes: int = N_CLASSES,
           ) -> list[tuple[int, float, float, float, float, float, np.ndarray, float]]:
    """Network output (C + 4, C + 5 or 2 (C + 4), h, w) for C = `n_classes` shape classes (the
    model's, by its metadata: a model trained before a shape joined the catalog has fewer)
    -> [(class, score, cu, cv, w, h, class_scores, level)] in pixels; `level` is the level
    score at the peak (0 for a model without one).

    Peaks are per-class 3x3 local maxima of the heatmap whose block score exceeds
    `threshold` (`peaks.find_peaks`); each peak cell reads its own offset and size. A peak
    within half the smaller side of a stronger one is the same object (a split peak, or the
    classes disagreeing) and is dropped, so one object never yields two detections, unless the two
    disagree on the level score (one above 0.5, one not): an object resting on another, off
    its centre by a cell or two, is a second object.

    A layered model (16 maps: the 8 maps once for objects on the table, once for objects
    resting on another) is decoded layer by layer, its level score 0 or 1 by layer: the
    lower object of a stack and the one on it are peaks in different maps, so neither can
    hide the other, even of one shape and a cell apart.

    Where a peak of the upper layer reads the same object as a stronger one of the lower
    layer, the lower layer wins; with a list as `contested`, such upper-layer peaks are
    appended to it with the peak they lost to, (upper, lower), for the image to decide
    (`Detector.detect`): the lower layer at times reads a stack's upper object as standing on
    the table, and then only the pixels of the object under it tell the two apart."""
    maps = n_classes + 4
    if out.shape[0] == 2 * maps:
        # both layers' heatmaps filtered at once (each map on its own, so as one by one)
        heat = out.reshape(2, maps, *out.shape[1:])[:, :n_classes].reshape(2 * n_classes, *out.shape[1:])
        block, (cls, ys, xs) = find_peaks(heat, threshold)
        both = []
        for k in range(2):
            at = slice(k * n_classes, (k + 1) * n_classes)
            mine = (cls >= k * n_classes) & (cls < (k + 1) * n_classes)
            layer = _decode_maps(out[k * maps : (k + 1) * maps], threshold, stride, split_levels, float(k), n_classes,
                                 (heat[at], block[at], (cls[mine] - k * n_classes, ys[mine], xs[mine])))
            both += _apart(layer, LAYER_OVERLAP[k])
        both.sort(key=lambda d: -d[1])
        kept: list[tuple[int, float, float, float, float, float, np.ndarray, float]] = []
        for d in both:
            # One object seen in both layers: the layer where it is stronger says its level.
            rival = next((k for k in kept if k[7] != d[7] and _same_object(d, k)), None)
            if rival is None:
                kept.append(d)
            elif contested is not None and d[7] == 1.0:
                contested.append((d, rival))
        return kept
    return _decode_maps(out, threshold, stride, split_levels, None, n_classes)


def carrier_peak(out: np.ndarray, upper: tuple, carriers: Sequence[int], floor: float, reach: float, *,
                 stride: int = STRIDE, n_classes: int = N_CLASSES,
                 ) -> tuple[int, float, float, float, float, float, np.ndarray, float] | None:
    """The lower-layer peak of a layered model's output that could carry `upper` (a decoded
    upper-layer peak), read at a lower bar than `decode`'s: the strongest peak of a class in
    `carriers` (the shapes with a flat top) with block score above `floor`, its centre
    within `reach` pixels of the upper one's and its box (read at its own cell) holding the
    upper one's centre; None when there is none (or the model has one layer).

    Why: an object resting on another of its shape and size, off its centre by less than a
    fifth of its side, is one object to `decode` (`_same_object`), and a lower peak next to
    the upper object's own lower-layer reading is a split peak of it; the lower object is
    then lost though a third of it shows. The caller decides by the pixels around the upper
    object (`Detector.detect`)."""
    maps = n_classes + 4
    if out.shape[0] != 2 * maps or not carriers:
        return None
    low = out[:maps]
    block, (cls, ys, xs) = find_peaks(low[:n_classes], floor)
    best = None
    for c, y, x in zip(cls.tolist(), ys.tolist(), xs.tolist()):
        if c not in carriers:
            continue
        score = float(block[c, y, x])
        if best is not None and score <= best[1]:
            continue
        cu, cv_ = (x + float(low[n_classes, y, x])) * stride, (y + float(low[n_classes + 1, y, x])) * stride
        bw, bh = max(float(low[n_classes + 2, y, x]), 0.1) * stride, max(float(low[n_classes + 3, y, x]), 0.1) * stride
        if (cu - upper[2]) ** 2 + (cv_ - upper[3]) ** 2 > reach**2:
            continue
        if not (cu - bw / 2 - 2 <= upper[2] <= cu + bw / 2 + 2 and cv_ - bh / 2 - 2 <= upper[3] <= cv_ + bh / 2 + 2):
            continue
        best = (c, score, cu, cv_, bw, bh, np.ascontiguousarray(block[:, y, x]), 0.0)
    return best


def _same_object(a: tuple, b: tuple) -> bool:
    """Whether two peaks of different layers read one object: centres closer than
    `SAME_OBJECT` of the smaller side, or, of one shape and box size (within
    `SAME_SIZE`), closer than `SAME_SHAPE` of it. An object on another is at least 15 % of
    the lower one's side off its centre, and one on an object of its own shape and size
    hides nearly all of it when less."""
    d2 = (a[2] - b[2]) ** 2 + (a[3] - b[3]) ** 2
    # the smaller object's length: its box side for the squares and discs, the longer side of
    # an elongated one's (a capsule's box is half as wide as long lying square to the table)
    side = min(max(a[4], a[5]), max(b[4], b[5]))
    if d2 < (SAME_OBJECT * side) ** 2:
        return True
    alike = a[0] == b[0] and abs(a[4] - b[4]) <= SAME_SIZE * side and abs(a[5] - b[5]) <= SAME_SIZE * side
    return alike and d2 < (SAME_SHAPE * side) ** 2


def peak_box(d: tuple) -> tuple[float, float, float, float]:
    return (d[2] - d[4] / 2, d[3] - d[5] / 2, d[2] + d[4] / 2, d[3] + d[5] / 2)


def _apart(dets: list, limit: float) -> list:
    """The detections of one layer (strongest first) without those whose box overlaps a
    stronger one's by more than `limit` of the smaller box: objects of one level never
    overlap (the world keeps them apart; turned neighbours' boxes clip each other by less)."""
    kept: list = []
    for d in dets:
        if all(overlap_share(peak_box(d), peak_box(k)) <= limit for k in kept):
            kept.append(d)
    return kept


def _decode_maps(out: np.ndarray, threshold: float, stride: int, split_levels: bool,
                 layer: float | None, n_classes: int = N_CLASSES,
                 filtered: tuple[np.ndarray, np.ndarray, tuple[np.ndarray, np.ndarray, np.ndarray]] | None = None,
                 ) -> list[tuple[int, float, float, float, float, float, np.ndarray, float]]:
    """`decode` for one set of maps (C + 4 or C + 5); `layer`, when given, is every peak's
    level; `filtered`, when given, is the maps' (heat, block scores, peaks) computed already
    (`peaks.find_peaks`)."""
    if filtered is None:
        heat = out[:n_classes]
        block, (cls, ys, xs) = find_peaks(heat, threshold)
    else:
        heat, block, (cls, ys, xs) = filtered
    if len(cls) == 0:
        return []
    scores = block[cls, ys, xs]
    order = np.lexsort((-heat[cls, ys, xs], -scores))
    kept: list[tuple[int, float, float, float, float, float, np.ndarray, float]] = []
    has_level = out.shape[0] > n_classes + 4
    # every peak's readings at once, as Python floats (the values `float(out[...])` gives)
    off_u, off_v, size_w, size_h, *lvl = out[n_classes : n_classes + (5 if has_level else 4), ys, xs].tolist()
    class_scores = np.ascontiguousarray(block[:, ys, xs].T)  # a row per peak, its own
    cls_, ys_, xs_, scores_ = cls.tolist(), ys.tolist(), xs.tolist(), scores.tolist()
    for i in order.tolist():
        c, y, x = cls_[i], ys_[i], xs_[i]
        cu = (x + off_u[i]) * stride
        cv_ = (y + off_v[i]) * stride
        bw = max(size_w[i], 0.1) * stride
        bh = max(size_h[i], 0.1) * stride
        if layer is not None:
            level = layer
        else:
            level = lvl[0][i] if has_level else 0.0
        dup = False
        for _, _, ku, kv, kw, kh, _, kl in kept:
            # One object read twice agrees with itself on its level; an object on top of
            # another, a cell or two from its centre, does not.
            # (a layered model's lower object peaks twice at times, once with a box of the
            # part that shows: half the larger of the two boxes' sides there)
            radius = 0.5 * (max(min(bw, bh), min(kw, kh)) if layer is not None else min(bw, bh, kw, kh))
            if (ku - cu) ** 2 + (kv - cv_) ** 2 < radius**2 and (
                not split_levels or (kl > 0.5) == (level > 0.5)
            ):
                dup = True
                break
        if not dup:
            kept.append((c, scores_[i], cu, cv_, bw, bh, class_scores[i], level))
    return kept
