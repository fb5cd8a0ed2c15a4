"""The perception helpers sped up in issue 25 give, to the bit, what their plain numpy
definitions give (the code before the speed-up, kept here as the reference): on rendered
crops and on random ones."""

from __future__ import annotations

import cv2
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from aileen.perception import color, ownpixels, pixels
from aileen.perception.dataset import SceneSpec, generate


def _own_pixels_reference(crop: np.ndarray, hidden: np.ndarray | None = None, close: int = 0) -> np.ndarray:
    hsv = cv2.cvtColor(np.ascontiguousarray(crop), cv2.COLOR_RGB2HSV)
    sat = hsv[..., 1] >= pixels.MIN_SATURATION
    if hidden is not None:
        sat &= ~hidden
    rgb = crop.astype(np.float32)
    chroma = rgb / np.maximum(rgb.sum(axis=2, keepdims=True), 1.0)
    h, w = sat.shape
    ref = sat
    if hidden is None:
        centre = np.zeros_like(sat)
        centre[h // 4 : h - h // 4, w // 4 : w - w // 4] = True
        if (sat & centre).sum() >= 6:
            ref = sat & centre
    if ref.sum() < 6:
        return sat
    own = np.median(chroma[ref], axis=0)
    mask = sat & (np.linalg.norm(chroma - own, axis=2) < pixels.CHROMA_TOL)
    if close > 0:
        k, p = np.ones((close + 1, close + 1), np.uint8), close + 1
        padded = cv2.copyMakeBorder(mask.astype(np.uint8), p, p, p, p, cv2.BORDER_CONSTANT, value=0)
        mask = cv2.morphologyEx(padded, cv2.MORPH_CLOSE, k)[p:-p, p:-p] > 0
        if hidden is not None:
            mask &= ~hidden
    return _one_object_reference(mask, hidden)


def _one_object_reference(mask: np.ndarray, hidden: np.ndarray | None) -> np.ndarray:
    n, labels, stats, _ = cv2.connectedComponentsWithStats(mask.astype(np.uint8), connectivity=8)
    if n <= 2:
        return mask
    keep = np.zeros(n, dtype=bool)
    keep[1 + int(np.argmax(stats[1:, cv2.CC_STAT_AREA]))] = True
    if hidden is not None and hidden.any():
        near = cv2.dilate(hidden.astype(np.uint8), np.ones((5, 5), np.uint8)) > 0
        keep[np.unique(labels[near & mask])] = True
        keep[0] = False
    return keep[labels]


def _score_reference(labels, pos, width, height, k):  # noqa: ANN001, ANN202
    n = len(labels)
    centre = np.array([width / 2.0, height / 2.0], dtype=np.float32)
    feats = np.zeros((k, 2), dtype=np.float64)
    for s in range(k):
        m = labels == s
        c = int(m.sum())
        if c == 0:
            feats[s] = (0.0, 1.0)
            continue
        feats[s, 0] = c / n
        feats[s, 1] = float(np.linalg.norm(pos[m].mean(axis=0) - centre)) / max(width, 1.0)
    return feats


def _means_reference(labels, pix, k):  # noqa: ANN001, ANN202
    means = np.zeros((k, 3), dtype=np.float32)
    for s in range(k):
        m = labels == s
        if m.any():
            means[s] = pix[m].mean(axis=0)
    return means


def _candidates_reference(means, feats, min_saturation):  # noqa: ANN001, ANN202
    nonempty = feats[:, 0] > 0
    chroma = nonempty & np.array([color.saturation(m) >= min_saturation
                                  and _nearest_reference(m)[1] <= color.MAX_CHROMA_DISTANCE for m in means])
    return chroma if chroma.any() else nonempty


def _nearest_reference(rgb):  # noqa: ANN001, ANN202
    from aileen.world.catalog import PRESETS

    names = list(PRESETS)
    table = np.asarray([PRESETS[n] for n in names], dtype=np.float32)
    x = np.asarray(rgb, dtype=np.float32)[None, :]
    table, x = color._chroma(table), color._chroma(x)
    d = np.linalg.norm(table - x, axis=1)
    i = int(np.argmin(d))
    return names[i], float(d[i])


def _crops() -> list[np.ndarray]:
    out = []
    for s in generate(25, 91, SceneSpec(1, 4, 0.5)):
        for o in s.objects:
            for grow in (0, 3, 9):
                u0, v0, u1, v1 = pixels.crop_window(s.image, (o.box_px[0] - grow, o.box_px[1] - grow,
                                                              o.box_px[2] + grow, o.box_px[3] + grow))
                if u1 - u0 >= 2 and v1 - v0 >= 2:
                    out.append(s.image[v0:v1, u0:u1])
    return out


CROPS = _crops()


def test_own_pixels_on_rendered_crops_is_its_definition() -> None:
    assert len(CROPS) > 150
    for crop in CROPS:
        assert np.array_equal(pixels.own_pixels(crop), _own_pixels_reference(crop))
        hidden = np.zeros(crop.shape[:2], dtype=bool)
        hidden[: crop.shape[0] // 3] = True
        assert np.array_equal(pixels.own_pixels(crop, hidden), _own_pixels_reference(crop, hidden))
        for close in (1, 3):
            assert np.array_equal(pixels.own_pixels(crop, close=close), _own_pixels_reference(crop, close=close))
            assert np.array_equal(pixels.own_pixels(crop, hidden, close=close),
                                  _own_pixels_reference(crop, hidden, close=close))


@settings(max_examples=150, deadline=None)
@given(arrays(np.uint8, st.tuples(st.integers(2, 40), st.integers(2, 40), st.just(3))))
def test_own_pixels_on_any_crop_is_its_definition(crop: np.ndarray) -> None:
    assert np.array_equal(pixels.own_pixels(crop), _own_pixels_reference(crop))


def test_own_pixels_of_many_windows_are_each_windows() -> None:
    """`own_pixels_of` finds many windows' own pixels at once (the crops stacked): each
    mask is `own_pixels` of its crop alone, for boxes, grown boxes, windows on the wood
    alone and tiny ones, in any order, a window asked twice included."""
    rng = np.random.default_rng(3)
    asked = 0
    for s in generate(40, 23, SceneSpec(stack_share=0.5, row_share=0.3, max_objects=8)):
        windows = []
        for o in s.objects:
            for grow in (0, 3, 9):
                windows.append(pixels.crop_window(s.image, (o.box_px[0] - grow, o.box_px[1] - grow,
                                                            o.box_px[2] + grow, o.box_px[3] + grow)))
        for _ in range(4):
            u, v = (int(x) for x in rng.integers(0, 250, 2))
            w, h = (int(x) for x in rng.integers(2, 30, 2))
            windows.append(pixels.crop_window(s.image, (u, v, u + w, v + h)))
        windows = [w for w in windows if w[2] - w[0] >= 2 and w[3] - w[1] >= 2]
        windows.append(windows[0])
        rng.shuffle(windows)
        for (u0, v0, u1, v1), mask in zip(windows, ownpixels.own_pixels_of(s.image, windows)):
            assert np.array_equal(mask, pixels.own_pixels(s.image[v0:v1, u0:u1]))
            asked += 1
        own = ownpixels.OwnPixels(s.image)
        own.find(windows[: len(windows) // 2])
        for u0, v0, u1, v1 in windows:
            assert np.array_equal(own((u0, v0, u1, v1)), pixels.own_pixels(s.image[v0:v1, u0:u1]))
    assert asked > 500


@settings(max_examples=150, deadline=None)
@given(arrays(np.uint8, st.tuples(st.integers(0, 50), st.integers(0, 50), st.just(3))), st.booleans())
def test_saturated_pixels_laid_flat_are_the_crops(crop: np.ndarray, strided: bool) -> None:
    """`saturated` converts the pixels as one row; the mask is the HSV conversion's of the
    crop as it is (a view into an image included)."""
    if strided:
        crop = crop[::2, ::-1]
    want = cv2.cvtColor(np.ascontiguousarray(crop), cv2.COLOR_RGB2HSV)[..., 1] >= pixels.MIN_SATURATION \
        if crop.size else np.zeros(crop.shape[:2], dtype=bool)
    got = ownpixels.saturated(crop)
    assert got.shape == crop.shape[:2] and got.dtype == bool
    assert np.array_equal(got, want)


@settings(max_examples=150, deadline=None)
@given(arrays(np.float32, st.tuples(st.just(3), st.integers(1, 60)), elements=st.floats(0, 1, width=32)))
def test_row_medians_are_numpys(a: np.ndarray) -> None:
    assert np.array_equal(ownpixels._row_medians(a), np.median(a.T, axis=0))


def test_colour_scoring_on_rendered_crops_is_its_definition() -> None:
    for crop in CROPS:
        labels, pos, pix = color._clusters(crop, color.DEFAULT_K, 0)
        k = int(labels.max()) + 1
        feats = color.score_clusters(labels, pos, crop.shape[1], crop.shape[0], k)
        assert np.array_equal(feats, _score_reference(labels, pos, crop.shape[1], crop.shape[0], k))
        means = color._cluster_means(labels, pix, k)
        assert np.array_equal(means, _means_reference(labels, pix, k))
        assert np.array_equal(color._candidates(means, feats, color.MIN_SATURATION),
                              _candidates_reference(means, feats, color.MIN_SATURATION))


def _colour_of_reference(image, box_px, exclude=()):  # noqa: ANN001, ANN202
    crop = color._crop(image, box_px)
    hidden = pixels.hidden_mask(image, color._window(image, box_px), exclude) if exclude else None
    keep = None if hidden is None else ~hidden
    if keep is not None and keep.sum() < color.MIN_VISIBLE_PIXELS:
        keep = None
    labels, pos, pix = color._clusters(crop, color.DEFAULT_K, 0, keep)
    k = int(labels.max()) + 1
    if keep is None:
        feats = _score_reference(labels, pos, crop.shape[1], crop.shape[0], k)
    else:
        lo, hi = pos.min(axis=0), pos.max(axis=0)
        feats = _score_reference(labels, pos - lo, float(hi[0] - lo[0] + 1), float(hi[1] - lo[1] + 1), k)
    means = _means_reference(labels, pix, k)
    w1 = color.DEFAULT_W1
    scores = np.where(_candidates_reference(means, feats, color.MIN_SATURATION),
                      w1 * feats[:, 0] + (1.0 - w1) * (1.0 - feats[:, 1]), -np.inf)
    best = int(np.argmax(scores))
    name, dist = _nearest_reference(means[best])
    return color.ColourPercept(name, tuple(float(v) for v in means[best]), dist, float(feats[best, 0]))


def test_colours_of_a_scene_are_each_boxs_colour_by_its_definition() -> None:
    """`colours_of` scores the clusters of all of a scene's boxes at once: each percept is
    the one of its box alone, by the plain definition, lower objects of stacks included."""
    from aileen.perception.detector import load_detector
    from aileen.perception.stacking import resolve_levels

    detector = load_detector()
    hidden = 0
    for s in generate(30, 17, SceneSpec(stack_share=0.6, max_objects=6)):
        dets = resolve_levels(detector.detect(s.image), s.image, scored=detector.scores_levels,
                              layered=detector.layered)
        excludes = [d.occluders for d in dets]
        hidden += sum(bool(e) for e in excludes)
        together = color.colours_of(s.image, [d.box_px for d in dets], excludes=excludes)
        assert together == [_colour_of_reference(s.image, d.box_px, d.occluders) for d in dets]
        assert together == [color.colour_of(s.image, d.box_px, exclude=d.occluders) for d in dets]
    assert hidden > 5


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 255), st.integers(0, 255), st.integers(0, 255)), min_size=1, max_size=40))
def test_nearest_preset_of_many_is_of_each(rgbs: list[tuple[int, int, int]]) -> None:
    means = np.asarray(rgbs, dtype=np.float32) * np.float32(0.97)  # off the integers
    names, d = color._preset_distances(means)
    for row, m in zip(d, means):
        assert color.nearest_preset(m) == _nearest_reference(m)
        assert (names[int(np.argmin(row))], float(row.min())) == _nearest_reference(m)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.floats(0.05, 0.9), st.floats(0.05, 0.9), st.sampled_from([0.04, 0.06, 0.08]),
                          st.integers(0, 1)), min_size=1, max_size=4))
def test_remembered_scene_facts_are_the_facts(placed: list[tuple[float, float, float, int]]) -> None:
    from aileen.agent.state import Seen
    from aileen.domain.calculi import senses
    from aileen.perception.facts import scene_facts

    objs = [Seen(f"o{i + 1}", ("cv_box", "cv_red", "cv_medium"), (x, y, x + s, y + s), (0.0, 0.0, 1.0, 1.0),
                 level=lvl, footprint=s) for i, (x, y, s, lvl) in enumerate(placed)]
    calcs = senses("all")
    plain = scene_facts(objs, calcs)
    first = scene_facts(objs, calcs, remember=True)
    assert first == plain
    first.append(first[0])  # a caller's list is its own
    assert scene_facts(objs, calcs, remember=True) == plain
    moved = [Seen(o.id, o.percepts, (o.box_m[0] + 0.2, o.box_m[1], o.box_m[2] + 0.2, o.box_m[3]), o.box_px,
                  level=o.level, footprint=o.footprint) for o in objs]
    assert scene_facts(moved, calcs, remember=True) == scene_facts(moved, calcs)


def _block_score_reference(heat: np.ndarray) -> np.ndarray:
    c, h, w = heat.shape
    p = np.zeros((c, h + 2, w + 2), dtype=heat.dtype)
    p[:, 1:-1, 1:-1] = heat
    s2 = p[:, :-1, :-1] + p[:, 1:, :-1] + p[:, :-1, 1:] + p[:, 1:, 1:]
    best = np.maximum(np.maximum(s2[:, :-1, :-1], s2[:, 1:, :-1]), np.maximum(s2[:, :-1, 1:], s2[:, 1:, 1:]))
    return np.minimum(best, 1.0)


def _local_max_reference(heat: np.ndarray) -> np.ndarray:
    c, h, w = heat.shape
    p = np.full((c, h + 2, w + 2), -np.inf, dtype=heat.dtype)
    p[:, 1:-1, 1:-1] = heat
    m = heat.copy()
    for dy in (0, 1, 2):
        for dx in (0, 1, 2):
            np.maximum(m, p[:, dy : dy + h, dx : dx + w], out=m)
    return m


@settings(max_examples=150, deadline=None)
@given(arrays(np.float32, st.tuples(st.integers(1, 9), st.integers(1, 34), st.integers(1, 34)),
              elements=st.sampled_from([0.0, 0.04, 0.06, 0.1, 0.15, 0.25, 0.3, 0.5, 0.9, 1.0])
              | st.floats(0, 1, width=32)),
       st.floats(0.05, 0.95))
def test_heatmap_peaks_are_their_definition(heat: np.ndarray, threshold: float) -> None:
    """`peaks.find_peaks` (all maps flat at once) gives the block scores and the peaks of the
    maps filtered one by one: 3x3 maxima with -inf past the edge, 2x2 block sums with zeros."""
    from aileen.perception.peaks import find_peaks

    block, cells = find_peaks(heat, threshold)
    ref = _block_score_reference(heat)
    assert np.array_equal(block, ref)
    peaks = (heat >= _local_max_reference(heat)) & (ref > threshold) & (heat > 0.05)
    for got, want in zip(cells, np.nonzero(peaks)):
        assert np.array_equal(got, want)
