"""The perception overlay: labels readable and on the image, relations drawn as arrows."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.web import overlay
from aileen.web.view import arrows
from aileen.world import catalog

W = H = 256 * overlay.SCALE


def _rects(marks, highlight=()):
    """The label rectangles `draw` places, in its order (arrows none)."""
    taken = []
    objects = [tuple(int(round(c * overlay.SCALE)) for c in m.box_px) for m in marks]
    for m, box in zip(marks, objects):
        others = [b for b in objects if b != box]
        taken.append(overlay.place_label(overlay._text_size(m.label), box, W, H, taken, others))
    return taken


box = st.tuples(st.floats(0, 236), st.floats(0, 236), st.floats(8, 20)).map(lambda t: (t[0], t[1], t[0] + t[2], t[1] + t[2]))


@settings(max_examples=80, deadline=None)
@given(st.lists(box, min_size=1, max_size=8))
def test_labels_stay_on_the_image(boxes) -> None:
    marks = [overlay.Mark(f"o{i + 1}", ("cv_cylinder", "cv_purple", "cv_large"), b) for i, b in enumerate(boxes)]
    for x0, y0, x1, y1 in _rects(marks):
        assert 0 <= x0 < x1 <= W and 0 <= y0 < y1 <= H
    img = overlay.draw(np.zeros((256, 256, 3), np.uint8), marks, ["o1"])
    assert img.shape == (H, W, 3)


def test_labels_at_the_right_edge_and_side_by_side_do_not_overlap() -> None:
    """The issue's cases: objects at the right edge (labels were cut off) and close together."""
    marks = [overlay.Mark("o1", ("cv_cylinder", "cv_green", "cv_large"), (228, 20, 250, 42)),
             overlay.Mark("o2", ("cv_sphere", "cv_yellow", "cv_medium"), (226, 50, 248, 72)),
             overlay.Mark("o3", ("cv_box", "cv_red", "cv_medium"), (120, 120, 140, 140)),
             overlay.Mark("o4", ("cv_cone", "cv_blue", "cv_medium"), (146, 122, 166, 142))]
    rects = _rects(marks)
    for i, a in enumerate(rects):
        assert a[2] <= W and a[3] <= H
        for b in rects[i + 1:]:
            assert overlay._overlap(a, b) == 0, (a, b)


def test_the_highlight_is_no_object_colour_and_labels_are_large() -> None:
    hi = np.array(overlay.HIGHLIGHT)
    for colour, shades in catalog.SHADES.items():
        for rgb in shades:
            assert np.abs(hi - np.array(rgb)).sum() > 150, colour  # cyan is not yellow, nor blue
    w, h, _ = overlay._text_size("o1 medium red box")
    assert h >= 10  # pixels of text height on the 512 px image (it was 0.4 scale, unplated)


def test_a_relation_is_drawn_between_the_grounded_objects() -> None:
    refs = {"red box": ["o1"], "blue cone": ["o2"]}
    assert arrows("red box left of blue cone", refs, {"o1", "o2"}) == [overlay.Arrow("o1", "o2", "left of")]
    assert arrows("the blue cone right of the red box", refs, {"o1", "o2"}) == [overlay.Arrow("o2", "o1", "right of")]
    assert arrows("red box left of blue cone", refs, {"o1", "o2"}, denied=True)[0].word == "not left of"
    assert arrows("red box", refs, {"o1", "o2"}) == []
    assert arrows("red box left of blue cone", {"red box": ["o1"], "blue cone": []}, {"o1"}) == []
    marks = [overlay.Mark("o1", ("cv_box", "cv_red", "cv_medium"), (40, 120, 60, 140)),
             overlay.Mark("o2", ("cv_cone", "cv_blue", "cv_medium"), (180, 120, 200, 140))]
    table = np.full((256, 256, 3), catalog.TABLE_RGB, np.uint8)
    plain = overlay.draw(table, marks)
    drawn = overlay.draw(table, marks, arrows=[overlay.Arrow("o1", "o2", "left of")])
    between = (slice(255, 285), slice(130, 350))  # the row of pixels between the two boxes
    assert (plain[between] != drawn[between]).any(axis=-1).sum() > 200
    assert (np.abs(drawn[between].astype(int) - overlay.HIGHLIGHT).sum(axis=-1) < 60).sum() > 100
