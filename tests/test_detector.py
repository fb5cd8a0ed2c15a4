"""The shipped ONNX detector (run by cv2.dnn) and the heatmap decoder."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.errors import UserError
from aileen.perception.detector import (
    CARRIER_PIXELS,
    DEFAULT_MODEL,
    N_CLASSES,
    check_image,
    decode,
    load_detector,
)
from aileen.perception.pixels import unexplained_around
from aileen.world import catalog
from aileen.world.render import render
from aileen.world.sim import World

KNOWN = (("box", "red", 0.25, 0.3), ("cone", "blue", 0.7, 0.6), ("sphere", "green", 0.4, 0.75),
         ("cylinder", "yellow", 0.8, 0.2), ("box", "purple", 0.52, 0.3))  # fmt: skip


def known_world() -> World:
    w = World()
    for shape, colour, x, y in KNOWN:
        w.add(shape, colour, x, y)
    # two touching neighbours
    w.add("sphere", "red", 0.15, 0.85)
    w.add("cone", "green", 0.2505, 0.85)
    return w


def test_shipped_model_exists_and_is_small() -> None:
    assert DEFAULT_MODEL.is_file()
    assert DEFAULT_MODEL.stat().st_size < 4 * 1024 * 1024
    meta = load_detector().meta
    # catalogued shapes in the catalog's order, every shape random draws take among them (a
    # shape the model cannot see stays out of the draws: catalog.UNDRAWN_SHAPES)
    assert meta["classes"] == [s for s in catalog.SHAPES if s in meta["classes"]]
    assert set(catalog.drawn_shapes()) <= set(meta["classes"])
    assert meta["input_size"] == [256, 256]


@pytest.mark.parametrize("seed", [None, 5])
def test_detects_known_scene(seed) -> None:
    frame = render(known_world(), seed=seed, noise=0.0 if seed is None else 2.0)
    dets = load_detector().detect(frame.image)
    assert len(dets) == len(frame.truth)
    for t in frame.truth:
        d = min(dets, key=lambda d: math.dist(d.centre_m, t.centre_m))
        assert math.dist(d.centre_m, t.centre_m) < 0.01
        assert d.shape == t.shape
        # box in metres agrees with the pixel box through the camera
        assert abs((d.box_m[2] - d.box_m[0]) - (d.box_px[2] - d.box_px[0]) / 256) < 1e-9
        assert abs((t.box_px[2] - t.box_px[0]) - (d.box_px[2] - d.box_px[0])) < 3.0


def test_empty_table_has_no_detections() -> None:
    assert load_detector().detect(render(World(), seed=1, noise=2.0).image) == []


def _maps(h: int = 8, w: int = 8) -> np.ndarray:
    out = np.zeros((N_CLASSES + 4, h, w), np.float32)
    out[N_CLASSES + 2 :] = 3.0  # 24 px boxes
    return out


def test_decode_peaks_offsets_and_sizes() -> None:
    out = _maps()
    out[0, 2, 3] = 0.9  # a box at cell (x=3, y=2)
    out[N_CLASSES : N_CLASSES + 2, 2, 3] = (0.25, 0.75)
    out[2, 6, 6] = 0.8  # a sphere
    out[2, 6, 5] = 0.5  # its shoulder: not a peak
    dets = decode(out, threshold=0.3)
    # scores are 2x2 block sums capped at 1: the sphere's shoulder counts toward it
    assert [(c, round(s, 2)) for c, s, *_ in dets] == [(2, 1.0), (0, 0.9)]
    c, s, cu, cv, bw, bh, scores, level = dets[1]
    assert level == 0.0  # an 8-map model has no level score
    assert (cu, cv, bw, bh) == (26.0, 22.0, 24.0, 24.0)
    assert scores.shape == (N_CLASSES,)


def test_decode_split_peak_on_a_cell_corner() -> None:
    # a centre exactly on a cell corner spreads its heat over four cells, none above threshold
    out = _maps()
    out[3, 3:5, 3:5] = 0.26
    out[N_CLASSES, 3:5, 3:5] = [[1.0, 0.0], [1.0, 0.0]]
    out[N_CLASSES + 1, 3:5, 3:5] = [[1.0, 1.0], [0.0, 0.0]]
    dets = decode(out, threshold=0.3)
    assert len(dets) == 1
    c, s, cu, cv, *_ = dets[0]
    assert c == 3 and s > 0.9 and (cu, cv) == (32.0, 32.0)


def test_decode_merges_class_disagreement() -> None:
    out = _maps()
    out[1, 4, 4] = 0.7  # cone
    out[3, 4, 5] = 0.6  # cylinder, one cell away: the same object, classes disagreeing
    dets = decode(out)
    assert len(dets) == 1 and dets[0][0] == 1


def test_decode_threshold() -> None:
    out = _maps()
    out[0, 1, 1] = 0.2
    assert decode(out, threshold=0.3) == []


def test_bad_images() -> None:
    with pytest.raises(UserError, match="numpy array"):
        check_image([[1, 2, 3]])
    with pytest.raises(UserError, match="uint8"):
        check_image(np.zeros((256, 256, 3), np.float32))
    with pytest.raises(UserError, match=r"\(H, W, 3\)"):
        check_image(np.zeros((256, 256), np.uint8))
    with pytest.raises(UserError, match="256x256"):
        check_image(np.zeros((100, 256, 3), np.uint8))


def test_missing_and_corrupt_models(tmp_path) -> None:
    missing = tmp_path / "nope.onnx"
    with pytest.raises(UserError, match="nope.onnx.*not found.*aileen perception train"):
        load_detector(missing)
    empty = tmp_path / "empty.onnx"
    empty.write_bytes(b"")
    with pytest.raises(UserError, match="empty.onnx.*empty.*aileen perception train"):
        load_detector(empty)
    bad = tmp_path / "bad.onnx"
    bad.write_bytes(b"this is not a protobuf" * 50)
    with pytest.raises(UserError, match="bad.onnx.*not a valid ONNX.*aileen perception train"):
        load_detector(bad)


def test_decode_keeps_an_object_on_top_of_another() -> None:
    # a cone resting on a cylinder, its centre one cell off: the level scores disagree
    out = np.zeros((N_CLASSES + 5, 8, 8), np.float32)
    out[N_CLASSES + 2 : N_CLASSES + 4] = 3.0
    out[3, 4, 4] = 0.8  # cylinder, on the table
    out[1, 4, 5] = 0.7  # cone, one cell east
    out[N_CLASSES + 4, 4, 5] = 0.95
    dets = decode(out)
    assert sorted((d[0], d[7] > 0.5) for d in dets) == [(1, True), (3, False)]
    out[N_CLASSES + 4, 4, 5] = 0.1  # the same levels: one object, the classes disagreeing
    assert len(decode(out)) == 1


def test_layered_decode_keeps_a_stack_of_one_shape_apart() -> None:
    # a box resting on a box, its centre a cell off: each in its own layer's box map
    out = np.zeros((2 * (N_CLASSES + 4), 8, 8), np.float32)
    out[N_CLASSES + 2 : N_CLASSES + 4] = 3.0
    out[2 * N_CLASSES + 6 :] = 3.0
    out[0, 4, 4] = 0.8  # box on the table
    out[N_CLASSES + 4, 4, 5] = 0.9  # box on another
    dets = decode(out)
    assert sorted((d[0], d[7]) for d in dets) == [(0, 0.0), (0, 1.0)]
    assert {round(d[2]) for d in dets} == {32, 40}
    # one object that fires in both layers at one spot is one object, at the stronger layer's level
    out[N_CLASSES + 4, 4, 5] = 0.0
    out[N_CLASSES + 4, 4, 4] = 0.5
    dets = decode(out)
    assert [(d[0], d[7]) for d in dets] == [(0, 0.0)]
    out[N_CLASSES + 4, 4, 4] = 0.95
    assert [(d[0], d[7]) for d in decode(out)] == [(0, 1.0)]


def test_layered_decode_hands_a_contested_upper_peak_to_the_image() -> None:
    # the lower layer reads an object at one spot more strongly than the upper layer: one
    # object, unless the image shows something under it; decode says which peak lost to which
    out = np.zeros((2 * (N_CLASSES + 4), 8, 8), np.float32)
    out[N_CLASSES + 2 : N_CLASSES + 4] = 3.0
    out[2 * N_CLASSES + 6 :] = 3.0
    out[0, 4, 4] = 0.9  # box on the table
    out[N_CLASSES + 4, 4, 4] = 0.6  # box on another, at the same spot
    contested: list = []
    dets = decode(out, contested=contested)
    assert [(d[0], d[7]) for d in dets] == [(0, 0.0)]
    assert len(contested) == 1 and contested[0][0][7] == 1.0 and contested[0][1] is dets[0]
    out[N_CLASSES + 4, 4, 4] = 0.0
    contested.clear()
    decode(out, contested=contested)
    assert contested == []


@settings(max_examples=60, deadline=None)
@given(st.sampled_from(catalog.SHAPES), st.sampled_from(catalog.COLOURS), st.sampled_from(tuple(catalog.SIZES)),
       st.floats(0.1, 0.9), st.floats(0.1, 0.9), st.integers(0, 2**31 - 1))
def test_an_object_alone_leaves_nothing_unexplained_around_it(shape, colour, size, x, y, seed) -> None:
    """Every catalogued shape, the capsule read by its hue (its highlight runs its whole
    length: by chromaticity, 19 of 300 lone capsules left 6-280 px unexplained)."""
    w = World()
    w.add(shape, colour, x, y, size=size)
    frame = render(w, seed=seed, noise=2.0)
    lying = shape in catalog.ELONGATED_FOOTPRINTS
    assert unexplained_around(frame.image, frame.truth[0].box_px, [], elongated=lying) < CARRIER_PIXELS


def test_the_box_under_a_diagonal_capsule_shows_inside_the_capsules_box() -> None:
    """A large capsule lying diagonally across a medium box of another colour: the box's
    corners that show lie inside the capsule's axis-aligned box, and only the capsule's own
    pixels (not its whole box) leave them unexplained."""
    w = World()
    low = w.add("box", "blue", 0.5, 0.5, size="medium")
    up = w.add("capsule", "red", 0.3, 0.3, size="large")
    w.pick_up(up)
    w.place(up, 0.5, 0.5, angle=math.pi / 4, onto=low)
    frame = render(w, seed=5, noise=2.0)
    boxes = {t.id: t.box_px for t in frame.truth}
    assert unexplained_around(frame.image, boxes[up], [], elongated=True) >= CARRIER_PIXELS


def test_lone_capsules_leave_nothing_unexplained_read_by_hue() -> None:
    """60 lone capsules of every colour, size and turn: read by chromaticity, some leave
    their own streak-split halves unexplained (`elongated=False` below fails); by hue, none."""
    rng = np.random.default_rng(11)
    left = []
    for _ in range(60):
        w = World()
        w.add("capsule", catalog.COLOURS[int(rng.integers(len(catalog.COLOURS)))], float(rng.uniform(0.1, 0.9)),
              float(rng.uniform(0.1, 0.9)), size=tuple(catalog.SIZES)[int(rng.integers(3))])
        frame = render(w, seed=int(rng.integers(2**31)), noise=float(rng.uniform(0, 3)))
        left.append(unexplained_around(frame.image, frame.truth[0].box_px, [], elongated=True))
    assert max(left) < CARRIER_PIXELS


@pytest.mark.parametrize("carrier_colour", ["blue", "red"])
def test_what_shows_of_the_box_under_a_capsule_is_unexplained(carrier_colour: str) -> None:
    """Reading a capsule's own pixels by hue keeps what shows of its carrier outside it,
    of another colour or of its own (the part in the capsule's box then passes for the
    capsule's, the rest does not)."""
    w = World()
    low = w.add("box", carrier_colour, 0.5, 0.5, size="large")
    up = w.add("capsule", "red", 0.3, 0.3, size="small")
    w.pick_up(up)
    w.place(up, 0.5, 0.5, onto=low)
    frame = render(w, seed=5, noise=2.0)
    boxes = {t.id: t.box_px for t in frame.truth}
    assert unexplained_around(frame.image, boxes[up], [], elongated=True) >= CARRIER_PIXELS
    assert unexplained_around(frame.image, boxes[up], [boxes[low]], elongated=True) < CARRIER_PIXELS


def test_what_shows_of_an_object_underneath_is_unexplained_and_a_detected_neighbour_is_not() -> None:
    w = World()
    low = w.add("box", "blue", 0.5, 0.5, size="medium")
    up = w.add("cylinder", "red", 0.52, 0.5, size="medium")
    w.pick_up(up)
    w.place(up, 0.53, 0.5, onto=low)
    w.add("box", "green", 0.35, 0.5)  # a neighbour, detected
    frame = render(w, seed=3)
    boxes = {t.id: t.box_px for t in frame.truth}
    assert unexplained_around(frame.image, boxes[up], [boxes["obj3"]]) >= CARRIER_PIXELS
    # with the lower one detected too, nothing is left
    assert unexplained_around(frame.image, boxes[up], [boxes["obj3"], boxes[low]]) < CARRIER_PIXELS
    # the neighbour, once detected, is explained: only the lower one's pixels counted
    assert unexplained_around(frame.image, boxes["obj3"], [boxes[up], boxes[low]]) < CARRIER_PIXELS


def test_an_upper_reading_nothing_could_carry_over_a_round_object_is_that_object_read_twice() -> None:
    from aileen.perception.detector import _supported
    from aileen.world.catalog import SHAPES

    cls = SHAPES.index
    scores = np.zeros(len(SHAPES), np.float32)
    capsule = (cls("capsule"), 1.0, 100.0, 100.0, 27.0, 27.0, scores, 0.0)
    twice = (cls("capsule"), 0.5, 95.0, 96.0, 19.0, 25.0, scores, 1.0)  # a cell or two off, boxed otherwise
    assert _supported([capsule, twice], SHAPES) == [capsule]
    # on a box (a flat top under its centre) it is an object on another, kept
    box = (cls("box"), 1.0, 100.0, 100.0, 34.0, 34.0, scores, 0.0)
    on_box = (cls("sphere"), 0.9, 95.0, 96.0, 19.0, 19.0, scores, 1.0)
    assert _supported([box, on_box], SHAPES) == [box, on_box]
    # beside a sphere, reaching a little over it, it stays too (it rests on something unseen)
    sphere = (cls("sphere"), 1.0, 100.0, 100.0, 26.0, 26.0, scores, 0.0)
    beside = (cls("cone"), 0.9, 118.0, 100.0, 26.0, 26.0, scores, 1.0)
    assert _supported([sphere, beside], SHAPES) == [sphere, beside]


# an object on another off its centre: one of its shape and size by a fifth of its side (one
# object to decoding's rule 3), and a cone on a cylinder (its lower peak read as a split peak
# of the cone's own lower-layer reading); a third of the lower object shows in each
@pytest.mark.parametrize(("lower", "upper"), [
    (("cylinder", "purple", "medium", 0.134, 0.319), ("cylinder", "green", "medium", 0.118, 0.332)),
    (("cylinder", "green", "small", 0.187, 0.690), ("cone", "blue", "small", 0.159, 0.700)),
])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_carrier_that_shows_around_the_object_on_it_is_found(lower: tuple, upper: tuple, seed: int) -> None:
    from aileen.perception.scene import perceive
    from aileen.world.render import render
    from aileen.world.sim import World

    w = World()
    low = w.add(lower[0], lower[1], lower[3], lower[4], size=lower[2])
    up = w.add(upper[0], upper[1], upper[3], upper[4], size=upper[2])
    w.pick_up(up)
    w.place(up, upper[3], upper[4], onto=low)
    seen = perceive(render(w, seed=seed, noise=2.0).image)
    assert sorted((o.values["colour"], o.values["shape"], o.level) for o in seen.objects) == sorted(
        [(lower[1], lower[0], 0), (upper[1], upper[0], 1)])


def test_only_pixels_of_another_hue_count_as_unlike_the_object() -> None:
    # a capsule the model does not know, read as a small sphere, leaves the rest of itself
    # around the sphere's box: of the sphere's own hue, which is no carrier's sliver
    image = np.full((256, 256, 3), (196, 178, 150), np.uint8)  # wood
    image[100:126, 100:126] = (35, 70, 205)  # a blue object
    image[104:122, 126:131] = (25, 50, 150)  # more of it, darker, beside its box
    box = (100.0, 100.0, 126.0, 126.0)
    assert unexplained_around(image, box, []) >= CARRIER_PIXELS
    assert unexplained_around(image, box, [], unlike=True) == 0
    image[104:122, 126:131] = (200, 30, 30)  # a red sliver: an object under it
    assert unexplained_around(image, box, [], unlike=True) >= CARRIER_PIXELS
