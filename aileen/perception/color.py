"""The colour module: the paper's k-means method, on a detected box.

A detector box holds the object and, around it, table and sometimes a neighbour's pixels.
Following the paper, the crop's pixels are clustered with k-means (`cv2.kmeans`) and each
cluster s is scored `w1 * R_s + w2 * (1 - C_s)`, with `R_s` its share of the crop's pixels
and `C_s` the distance of its pixels' spatial centroid from the crop centre, normalised by
the crop width (w2 = 1 - w1). The best cluster's mean RGB is matched to the nearest preset
colour (`catalog.PRESETS`). The weight w1 is grid-searched on rendered crops by
`aileen perception tune-color` (see `tune_weights`); the chosen value is `DEFAULT_W1`.

Two refinements, both measured (docs/perception.md): the paper's score alone picks the table
in the crop of a rotated box (half the crop is table, and it surrounds the centre
symmetrically), and plain RGB distance calls a shaded yellow green. So (1) only *chromatic*
clusters (saturation (max-min)/max >= MIN_SATURATION) compete, unless none is: the table,
dark outlines and white highlights are grey-ish, every catalog colour is saturated; and
(2) the match is by chromaticity (rgb / (r+g+b)), so a colour under dimmer or brighter light
still matches its preset -- the renderer changes intensity, never hue. `match="rgb"` gives
the paper's plain Euclidean RGB match.

Images are RGB uint8 arrays (H, W, 3) everywhere in aileen; OpenCV's BGR never leaks here.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache

import cv2
import numpy as np

from aileen.perception.pixels import hidden_mask, own_pixels
from aileen.world.catalog import COLOURS, PRESETS

__all__ = ["ColourPercept", "colour_of", "colours_of", "score_clusters", "nearest_preset", "tune_weights", "saturation",
           "TuneResult", "DEFAULT_W1", "DEFAULT_K", "MIN_SATURATION", "MAX_CHROMA_DISTANCE"]

# Chosen by `aileen perception tune-color` (see docs/perception.md for the grid and accuracy).
DEFAULT_W1 = 0.5
DEFAULT_K = 4
MIN_SATURATION = 0.45
# ... and whose chromaticity lies within this of a preset's (every catalog shade is within
# 0.13 of its preset; the table is 0.25 away, a cluster of table-object edge pixels ~0.2).
MAX_CHROMA_DISTANCE = 0.18
# k-means on at most this many pixels: a 33 px box has ~1100; a regular subsample keeps the
# shares and the spatial centroids unbiased and the cost flat.
_MAX_PIXELS = 400
_CRITERIA = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 12, 0.5)


@dataclass(frozen=True)
class ColourPercept:
    name: str  # catalog colour name, e.g. "red"
    rgb: tuple[float, float, float]  # mean RGB of the chosen cluster
    distance: float  # Euclidean RGB distance to the matched preset
    share: float  # R_s of the chosen cluster


def _chroma(rgb: np.ndarray) -> np.ndarray:
    return rgb / np.maximum(rgb.sum(axis=-1, keepdims=True), 1e-6)


def saturation(rgb: Sequence[float]) -> float:
    """HSV saturation (max - min) / max of an RGB triple, 0 for black."""
    hi, lo = max(rgb), min(rgb)
    return float((hi - lo) / hi) if hi > 0 else 0.0


def nearest_preset(
    rgb: Sequence[float], presets: Mapping[str, tuple[int, int, int]] = PRESETS, *, match: str = "chroma"
) -> tuple[str, float]:
    """The preset colour nearest to `rgb` and its distance: Euclidean in chromaticity
    (`match="chroma"`, intensity-invariant) or in plain RGB (`match="rgb"`, the paper's)."""
    names, d = _preset_distances(np.asarray(rgb, dtype=np.float32)[None, :], presets, match)
    i = int(np.argmin(d[0]))
    return names[i], float(d[0, i])


def _preset_distances(rgb: np.ndarray, presets: Mapping[str, tuple[int, int, int]] = PRESETS,
                      match: str = "chroma") -> tuple[list[str], np.ndarray]:
    """The preset names and, for each row of an (n, 3) float32 array, its distance to each
    preset, (n, presets): `nearest_preset` for n colours at once, the same float32
    arithmetic row by row."""
    if presets is PRESETS:
        names, key = _DEFAULT_NAMES, _DEFAULT_PRESETS
    else:
        names = list(presets)
        key = tuple((n, tuple(presets[n])) for n in names)
    table = _preset_table(key, match)
    x = _chroma(rgb) if match == "chroma" else rgb
    # `np.linalg.norm(..., axis=2)` without its checks: for real float32 it is this sum of
    # squares over the last axis and its square root (the colour module runs per object)
    diff = table[None, :, :] - x[:, None, :]
    return list(names), np.sqrt(np.add.reduce(diff * diff, axis=2))


_DEFAULT_PRESETS = tuple((n, tuple(PRESETS[n])) for n in PRESETS)
_DEFAULT_NAMES = tuple(PRESETS)


@lru_cache(maxsize=8)
def _preset_table(presets: tuple[tuple[str, tuple[int, int, int]], ...], match: str) -> np.ndarray:
    """The presets as a float32 table in the space of the match (computed once per set)."""
    if match not in ("chroma", "rgb"):
        raise ValueError(f"match must be 'chroma' or 'rgb', got {match!r}")
    table = np.asarray([rgb for _, rgb in presets], dtype=np.float32)
    table = _chroma(table) if match == "chroma" else table
    table.setflags(write=False)
    return table


def _window(image: np.ndarray, box_px: Sequence[float]) -> tuple[int, int, int, int]:
    h, w = image.shape[:2]
    u0 = min(max(math.floor(box_px[0]), 0), w - 1)
    v0 = min(max(math.floor(box_px[1]), 0), h - 1)
    u1 = min(max(math.ceil(box_px[2]), u0 + 1), w)
    v1 = min(max(math.ceil(box_px[3]), v0 + 1), h)
    return u0, v0, u1, v1


def _crop(image: np.ndarray, box_px: Sequence[float]) -> np.ndarray:
    u0, v0, u1, v1 = _window(image, box_px)
    return image[v0:v1, u0:u1]


def _clusters(crop: np.ndarray, k: int, seed: int, keep: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """k-means over the crop's pixels (only those where `keep` is True, if given): (labels,
    pixel (u, v) positions, rgb values) of the (subsampled) pixels."""
    h, w = crop.shape[:2]
    n = h * w if keep is None else int(np.count_nonzero(keep))
    step = max(1, math.ceil(math.sqrt(n / _MAX_PIXELS)))
    pix = crop[step // 2 :: step, step // 2 :: step].astype(np.float32).reshape(-1, 3)
    pos = _grid(h, w, step)
    if keep is not None:
        m = keep[step // 2 :: step, step // 2 :: step].ravel()
        pix, pos = np.ascontiguousarray(pix[m]), np.ascontiguousarray(pos[m])
    k = max(1, min(k, len(pix)))
    cv2.setRNGSeed(seed)
    _, labels, _ = cv2.kmeans(pix, k, None, _CRITERIA, 1, cv2.KMEANS_PP_CENTERS)
    return labels.ravel(), pos, pix


@lru_cache(maxsize=1024)
def _grid(h: int, w: int, step: int) -> np.ndarray:
    """The (u, v) pixel centres of a crop of h x w sampled every `step` pixels, row by row,
    float32 (n, 2); read-only, as it is shared between calls."""
    vv, uu = np.mgrid[step // 2 : h : step, step // 2 : w : step]
    pos = np.stack([uu.ravel() + 0.5, vv.ravel() + 0.5], axis=1).astype(np.float32)
    pos.setflags(write=False)
    return pos


def score_clusters(labels: np.ndarray, pos: np.ndarray, width: float, height: float, k: int) -> np.ndarray:
    """Per-cluster features (R_s, C_s), shape (k, 2): pixel share and normalised distance of
    the cluster's spatial centroid from the crop centre."""
    counts = np.bincount(labels, minlength=k)[:k]
    return _features(counts, _label_means(labels, pos, counts), len(labels), width, height)


def _features(counts: np.ndarray, cents: np.ndarray, n: int | np.ndarray, width: float | np.ndarray,
              height: float | np.ndarray) -> np.ndarray:
    """`score_clusters` from the clusters' pixel counts and float32 spatial centroids (k, 2);
    an empty cluster is as far as can be (C_s = 1). The crop's pixel count and size are
    numbers, or arrays of one per cluster (the clusters of several crops at once)."""
    feats = np.empty((len(counts), 2), dtype=np.float64)
    feats[:, 0] = counts / n
    # the centroids' distances from the centre, all at once: float32 squares summed in
    # float32 as `np.linalg.norm` does for one centroid, then its square root
    d = cents - np.stack((np.divide(width, 2.0), np.divide(height, 2.0)), axis=-1).astype(np.float32)
    dist = np.sqrt(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1]).astype(np.float64) / np.maximum(width, 1.0)
    feats[:, 1] = np.where(counts > 0, dist, 1.0)
    return feats


def _label_means(labels: np.ndarray, values: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """Per label, the float32 mean of its rows of `values` (0 for an empty label): what
    `values[labels == s].mean(axis=0)` gives, to the bit, because the values here (pixel
    levels 0-255, pixel centres at half pixels) sum exactly in float64 and float32 alike,
    and float32(float64 sum / count) is the correctly rounded quotient numpy's mean gives."""
    k, m = len(counts), values.shape[1]
    # one bincount over (label, column) bins: each bin sums its rows in the same order as a
    # bincount per column would, so every sum is the same
    bins = (labels[:, None] * m + np.arange(m)).ravel()
    sums = np.bincount(bins, weights=values.ravel(), minlength=k * m)[: k * m].reshape(k, m)
    return (sums / np.maximum(counts, 1)[:, None]).astype(np.float32)


def colour_of(
    image: np.ndarray,
    box_px: Sequence[float],
    *,
    w1: float = DEFAULT_W1,
    k: int = DEFAULT_K,
    seed: int = 0,
    presets: Mapping[str, tuple[int, int, int]] = PRESETS,
    match: str = "chroma",
    min_saturation: float = MIN_SATURATION,
    exclude: Sequence[Sequence[float]] = (),
    upper: bool = False,
) -> ColourPercept:
    """The colour percept of the object in `box_px` (u0, v0, u1, v1) of an RGB image.

    `exclude` lists pixel boxes of objects resting on this one: their own pixels
    (`aileen.perception.pixels.hidden_mask`) are left out, and the centre the clusters are
    scored against is that of the part that shows. `upper`: the object rests on another,
    and its box holds part of that one (a lying capsule across a box, a small sphere on a
    large one: the lower colour can be the larger cluster), so only its own pixels
    (`aileen.perception.pixels.own_pixels`) are clustered.
    `min_saturation=0` and `match="rgb"` give the paper's method unchanged."""
    return colours_of(image, [box_px], w1=w1, k=k, seed=seed, presets=presets, match=match,
                      min_saturation=min_saturation, excludes=[exclude], upper=[upper])[0]


def colours_of(
    image: np.ndarray,
    boxes: Sequence[Sequence[float]],
    *,
    w1: float = DEFAULT_W1,
    k: int = DEFAULT_K,
    seed: int = 0,
    presets: Mapping[str, tuple[int, int, int]] = PRESETS,
    match: str = "chroma",
    min_saturation: float = MIN_SATURATION,
    excludes: Sequence[Sequence[Sequence[float]]] | None = None,
    upper: Sequence[bool] | None = None,
) -> list[ColourPercept]:
    """`colour_of` for each of several boxes of one image (`excludes`: each box's
    `exclude`; `upper`: each box's `upper`). Each box is clustered on its own
    (`_Clustered`); the clusters of all of them are then scored in one set of array
    operations, which on a handful of clusters cost about as much as for one box's (issue
    25: perceive() asks for every object of a scene). Row by row the arithmetic is that of
    one box alone, so each percept is the one `colour_of` gives."""
    if not boxes:
        return []
    groups = [_clustered(image, b, k, seed, e, up)
              for b, e, up in zip(boxes, excludes or [()] * len(boxes), upper or [False] * len(boxes))]
    sizes = [g.k for g in groups]
    labels = np.concatenate([g.labels + first for g, first in zip(groups, np.cumsum([0] + sizes[:-1]).tolist())])
    values = np.concatenate((np.concatenate([g.pos for g in groups]), np.concatenate([g.pix for g in groups])), axis=1)
    counts = np.bincount(labels, minlength=sum(sizes))
    both = _label_means(labels, values, counts)
    feats = _features(counts, both[:, :2], np.repeat([len(g.labels) for g in groups], sizes),
                      np.repeat([g.width for g in groups], sizes), np.repeat([g.height for g in groups], sizes))
    means = np.ascontiguousarray(both[:, 2:])
    chroma, names, dists = _chromatic_rows(means, feats, min_saturation)
    rows, nonempty, rgbs = feats.tolist(), (feats[:, 0] > 0).tolist(), means.tolist()
    chroma_ = chroma.tolist() if chroma is not None else None
    dists_ = dists.tolist() if dists is not None else None
    out, first = [], 0
    for size in sizes:
        at = slice(first, first + size)
        allowed = nonempty[at] if chroma_ is None or not any(chroma_[at]) else chroma_[at]
        best = first + _best(rows[at], allowed, w1)
        if dists_ is not None and presets is PRESETS and match == "chroma":
            row = dists_[best]  # what nearest_preset(rgb) gives, computed already
            i = min(range(len(row)), key=row.__getitem__)
            name, dist = names[i], row[i]
        else:
            name, dist = nearest_preset(means[best], presets, match=match)
        out.append(ColourPercept(name, tuple(rgbs[best]), dist, rows[best][0]))
        first += size
    return out


@dataclass(frozen=True)
class _Clustered:
    """One box's sampled pixels, clustered: what scoring its clusters reads."""

    labels: np.ndarray  # (n,) each pixel's cluster
    pos: np.ndarray  # (n, 2) float32 pixel centres, in the visible part's spread when part is hidden
    pix: np.ndarray  # (n, 3) float32 RGB
    k: int  # clusters: the largest label + 1
    width: float  # of the crop (or of the visible part's spread)
    height: float


def _clustered(image: np.ndarray, box_px: Sequence[float], k: int, seed: int,
               exclude: Sequence[Sequence[float]], upper: bool = False) -> _Clustered:
    """k-means over the box's crop (`_clusters`), without the pixels of what rests on it, or,
    for an object on another (`upper`), on its own pixels alone."""
    crop = _crop(image, box_px)
    hidden = hidden_mask(image, _window(image, box_px), exclude) if exclude else None
    keep = None if hidden is None else ~hidden
    if upper:
        keep = own_pixels(crop) if keep is None else keep & own_pixels(crop)
    if keep is not None and keep.sum() < MIN_VISIBLE_PIXELS:
        keep = None  # too little shows: the whole box is the best there is
    labels, pos, pix = _clusters(crop, k, seed, keep)
    width, height = float(crop.shape[1]), float(crop.shape[0])
    if keep is not None:  # score against the centre of the visible part, in a crop of its spread
        lo, hi = pos.min(axis=0), pos.max(axis=0)
        pos, width, height = pos - lo, float(hi[0] - lo[0] + 1), float(hi[1] - lo[1] + 1)
    return _Clustered(labels, pos, pix, int(labels.max()) + 1, width, height)


def _best(rows: Sequence[Sequence[float]], allowed: Sequence[bool], w1: float) -> int:
    """The allowed cluster (rows of (R_s, C_s)) of the highest score
    `w1 * R_s + (1 - w1) * (1 - C_s)`, the first of equals (`np.argmax`'s choice): in Python
    floats, the same float64 arithmetic as over arrays, at a fraction of the cost for a
    few clusters."""
    scores = [w1 * r + (1.0 - w1) * (1.0 - c) if ok else -math.inf for (r, c), ok in zip(rows, allowed)]
    return max(range(len(scores)), key=scores.__getitem__)


MIN_VISIBLE_PIXELS = 12


def _cluster_means(labels: np.ndarray, pix: np.ndarray, k: int) -> np.ndarray:
    return _label_means(labels, pix, np.bincount(labels, minlength=k)[:k])


def _candidates(means: np.ndarray, feats: np.ndarray, min_saturation: float) -> np.ndarray:
    """Clusters allowed to win: non-empty and chromatic (saturated, and near some preset's
    chromaticity); all non-empty ones if none is. `min_saturation <= 0` allows all."""
    chroma, _names, _d = _chromatic_rows(means, feats, min_saturation)
    return chroma if chroma is not None and chroma.any() else feats[:, 0] > 0


def _chromatic_rows(means: np.ndarray, feats: np.ndarray, min_saturation: float
                    ) -> tuple[np.ndarray | None, list[str], np.ndarray | None]:
    """Per cluster, whether it is non-empty and chromatic (None when `min_saturation <= 0`
    asks for none), the preset names and each mean's chromaticity distance to each preset."""
    if min_saturation <= 0:
        return None, [], None
    hi, lo = np.maximum.reduce(means, axis=1), np.minimum.reduce(means, axis=1)
    sat = np.zeros_like(hi)
    np.divide(hi - lo, hi, out=sat, where=hi > 0)  # `saturation`, row by row, float32 alike
    names, d = _preset_distances(means)
    near = np.minimum.reduce(d, axis=1).astype(np.float64) <= MAX_CHROMA_DISTANCE
    return (feats[:, 0] > 0) & (sat.astype(np.float64) >= min_saturation) & near, names, d


@dataclass(frozen=True)
class TuneResult:
    w1: float
    accuracy: float
    grid: list[tuple[float, float]]  # (w1, accuracy) for every grid point
    n: int


def tune_weights(
    samples: Sequence[tuple[np.ndarray, Sequence[float], str]],
    *,
    grid: Sequence[float] = tuple(np.round(np.linspace(0.0, 1.0, 21), 2)),
    k: int = DEFAULT_K,
    match: str = "chroma",
    min_saturation: float = MIN_SATURATION,
) -> TuneResult:
    """Grid-search w1 (w2 = 1 - w1) on (image, box_px, true colour) samples.

    Clustering does not depend on the weights, so each crop is clustered once and every grid
    point only re-scores the clusters. Ties go to the w1 closest to 0.5 (the least extreme)."""
    if not samples:
        raise ValueError("tune_weights needs samples")
    pre = []
    for image, box, truth in samples:
        crop = _crop(image, box)
        labels, pos, pix = _clusters(crop, k, 0)
        kk = int(labels.max()) + 1
        feats = score_clusters(labels, pos, crop.shape[1], crop.shape[0], kk)
        means = _cluster_means(labels, pix, kk)
        names = [nearest_preset(m, match=match)[0] for m in means]
        pre.append((feats, names, truth, _candidates(means, feats, min_saturation)))
    results: list[tuple[float, float]] = []
    for w1 in grid:
        ok = 0
        for feats, names, truth, cand in pre:
            s = np.where(cand, w1 * feats[:, 0] + (1 - w1) * (1 - feats[:, 1]), -np.inf)
            ok += names[int(np.argmax(s))] == truth
        results.append((float(w1), ok / len(pre)))
    best_w1, best_acc = max(results, key=lambda r: (r[1], -abs(r[0] - 0.5)))
    return TuneResult(best_w1, best_acc, results, len(pre))


assert set(COLOURS) == set(PRESETS)


def measure_colour(image: np.ndarray, detection, camera=None) -> tuple[str, float]:
    """The colour channel's measure (see `aileen.domain.channels`): k-means over the
    detection box, nearest preset."""
    c = colour_of(image, detection.box_px, exclude=getattr(detection, "occluders", ()))
    return c.name, c.distance


def measure_colours(image: np.ndarray, detections: Sequence, camera=None) -> list[tuple[str, float]]:
    """`measure_colour` of each detection of one image, scored together (`colours_of`)."""
    found = colours_of(image, [d.box_px for d in detections],
                       excludes=[getattr(d, "occluders", ()) for d in detections],
                       upper=[getattr(d, "level", 0) > 0 for d in detections])
    return [(c.name, c.distance) for c in found]
