"""Where the pixels correct the detector: square or disc by the outline, and the boxes of
touching objects."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.perception.detector import RawDetection
from aileen.perception.pixels import outline_fill
from aileen.world.geometry import rcc8
from aileen.perception.refine import SQUARE_FILL, by_pixels
from aileen.world import catalog
from aileen.world.camera import DEFAULT_CAMERA
from aileen.world.render import render
from aileen.world.sim import World


def _detection(t, shape: str, scores: dict[str, float], occluders=()) -> RawDetection:
    cam = DEFAULT_CAMERA
    return RawDetection(t.box_px, t.box_m, cam.to_pixels(*t.centre_m), t.centre_m, shape, scores[shape], scores,
                     occluders=occluders)


SQUARE_OR_DISC = tuple(s for s in catalog.SHAPES if s not in catalog.ELONGATED_FOOTPRINTS)


@settings(max_examples=60, deadline=None)
@given(st.sampled_from(SQUARE_OR_DISC), st.sampled_from(catalog.COLOURS), st.sampled_from(tuple(catalog.SIZES)),
       st.floats(0.12, 0.88), st.floats(0.12, 0.88), st.floats(0.0, 1.5), st.one_of(st.none(), st.integers(0, 2**30)))
def test_an_outline_is_square_exactly_for_square_footprints(shape, colour, size, x, y, angle, seed) -> None:
    w = World()
    w.add(shape, colour, x, y, size=size, angle=angle if shape in catalog.SQUARE_FOOTPRINTS else 0.0)
    frame = render(w, seed=seed, noise=0.0 if seed is None else 2.0)
    fill = outline_fill(frame.image, frame.truth[0].box_px)
    assert fill is not None and (fill > SQUARE_FILL) == (shape in catalog.SQUARE_FOOTPRINTS)


def test_a_wrong_square_or_disc_call_is_corrected_and_a_hidden_object_is_left_alone() -> None:
    w = World()
    w.add("box", "red", 0.3, 0.3, size="small")
    w.add("cylinder", "blue", 0.7, 0.7)
    frame = render(w, seed=None)
    box_t, cyl_t = frame.truth
    scores = {"box": 0.2, "cone": 0.1, "sphere": 0.05, "cylinder": 0.7}
    dets = [_detection(box_t, "cylinder", scores), _detection(cyl_t, "box", {**scores, "box": 0.8, "cylinder": 0.4})]
    out = by_pixels(dets, frame.image, DEFAULT_CAMERA)
    assert [d.shape for d in out] == ["box", "cylinder"] and out[0].score == 0.2
    # what is partly hidden keeps the detector's call (its outline is not its footprint's)
    hidden = [_detection(box_t, "cylinder", scores, occluders=((0.0, 0.0, 1.0, 1.0),))]
    assert by_pixels(hidden, frame.image, DEFAULT_CAMERA)[0].shape == "cylinder"


@settings(max_examples=20, deadline=None)
@given(st.sampled_from(tuple(catalog.SIZES)), st.floats(0.0, 3.2), st.one_of(st.none(), st.integers(0, 2**30)))
def test_a_capsule_is_neither_called_square_nor_disc_nor_made_one(size, angle, seed) -> None:
    # its stadium fills 0.89-0.94 of its rectangle: between a disc's and a square's
    w = World()
    w.add("capsule", "green", 0.5, 0.5, size=size, angle=angle)
    box = World()
    box.add("box", "red", 0.5, 0.5, size=size)
    frame, box_frame = render(w, seed=seed, noise=2.0), render(box, seed=seed, noise=2.0)
    caps = {s: 0.01 for s in catalog.SHAPES}
    said_capsule = _detection(frame.truth[0], "capsule", {**caps, "capsule": 0.9, "box": 0.2})
    assert by_pixels([said_capsule], frame.image, DEFAULT_CAMERA)[0].shape == "capsule"
    # a square read as a disc shape is corrected to the box, never to the capsule
    said_disc = _detection(box_frame.truth[0], "sphere", {**caps, "sphere": 0.8, "capsule": 0.7, "box": 0.1})
    assert by_pixels([said_disc], box_frame.image, DEFAULT_CAMERA)[0].shape == "box"


@settings(max_examples=20, deadline=None)
@given(st.sampled_from(("sphere", "cone", "cylinder")), st.floats(0.0, 3.2), st.one_of(st.none(), st.integers(0, 2**30)))
def test_a_long_outline_is_a_capsule_and_a_round_one_is_not(disc, angle, seed) -> None:
    w = World()
    w.add("capsule", "blue", 0.3, 0.5, angle=angle)
    w.add(disc, "yellow", 0.7, 0.5)
    frame = render(w, seed=seed, noise=0.0 if seed is None else 2.0)
    caps, round_ = frame.truth
    scores = {s: 0.05 for s in catalog.SHAPES}
    said_round = _detection(caps, disc, {**scores, disc: 0.8, "capsule": 0.4})
    said_capsule = _detection(round_, "capsule", {**scores, "capsule": 0.9, disc: 0.6})
    out = by_pixels([said_round, said_capsule], frame.image, DEFAULT_CAMERA)
    assert [d.shape for d in out] == ["capsule", disc]


def test_touching_boxes_that_the_detector_overlaps_take_their_pixels_edges() -> None:
    w = World()
    w.add("box", "yellow", 0.37, 0.40)
    w.add("box", "purple", 0.37, 0.50)  # edge to edge
    frame = render(w, seed=9)
    a, b = frame.truth
    scores = {s: (1.0 if s == "box" else 0.0) for s in catalog.SHAPES}
    da, db = _detection(a, "box", scores), _detection(b, "box", scores)
    # the detector's box of the one behind reaches 4 pixels too far south: the pair reads po
    u0, v0, u1, v1 = db.box_px
    grown = (u0, v0, u1, v1 + 4.0)
    db = RawDetection(grown, DEFAULT_CAMERA.box_to_metres(grown), db.centre_px, db.centre_m, "box", 1.0, scores)
    assert rcc8(da.box_m, db.box_m) == "po"
    out = by_pixels([da, db], frame.image, DEFAULT_CAMERA)
    assert abs(out[1].box_px[3] - b.box_px[3]) <= 1.0 and rcc8(out[0].box_m, out[1].box_m) == "ec"
    # apart, nothing changes
    far = [_detection(a, "box", scores)]
    assert by_pixels(far, frame.image, DEFAULT_CAMERA)[0].box_px == a.box_px
