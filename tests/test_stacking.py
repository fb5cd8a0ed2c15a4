"""Which of two overlapping detections is on top: levels from the detector's level score."""

from __future__ import annotations

import pytest

from aileen.perception.detector import RawDetection
from aileen.perception.stacking import resolve_levels


def det(box: tuple[float, float, float, float], level_score: float, score: float = 0.9) -> RawDetection:
    cu, cv = (box[0] + box[2]) / 2, (box[1] + box[3]) / 2
    return RawDetection(box, box, (cu, cv), (cu / 256, 1 - cv / 256), "box", score, {}, level_score)


def test_the_higher_scoring_of_two_overlapping_objects_is_on_top() -> None:
    lower, upper = det((100, 100, 126, 126), 0.02), det((110, 108, 128, 126), 0.97)
    out = resolve_levels([lower, upper])
    assert [d.level for d in out] == [0, 1]
    assert out[0].occluders == (upper.box_px,) and out[1].occluders == ()


def test_a_high_score_without_anything_under_it_is_on_the_table() -> None:
    alone = det((10, 10, 36, 36), 0.9)
    apart = det((100, 100, 126, 126), 0.1)
    assert [d.level for d in resolve_levels([alone, apart])] == [0, 0]


def test_touching_neighbours_are_not_a_stack() -> None:
    # boxes that clip by a pixel share far less than MIN_OVERLAP of their area
    a, b = det((100, 100, 126, 126), 0.2), det((125, 100, 151, 126), 0.8)
    assert [d.level for d in resolve_levels([a, b])] == [0, 0]


def test_a_stack_is_at_most_two_high() -> None:
    # two overlapping objects that both score high: only the higher one is on top
    a, b = det((100, 100, 126, 126), 0.7), det((108, 100, 134, 126), 0.9)
    out = resolve_levels([a, b])
    assert [d.level for d in out] == [0, 1]


def test_one_object_carries_at_most_one() -> None:
    low = det((100, 100, 140, 140), 0.0)
    u1, u2 = det((98, 98, 118, 118), 0.9), det((122, 122, 142, 142), 0.8)
    out = resolve_levels([low, u1, u2])
    assert [d.level for d in out] == [0, 1, 0]
    assert out[0].occluders == (u1.box_px,)


def test_colours_of_the_overlap_tell_which_is_on_top() -> None:
    from aileen.perception.stacking import on_top_by_colour
    from aileen.world.render import render
    from aileen.world.sim import World

    w = World()
    low = w.add("box", "red", 0.5, 0.5, size="large")
    up = w.add("sphere", "blue", 0.2, 0.2)
    w.pick_up(up)
    w.place(up, 0.53, 0.52, onto=low)
    frame = render(w, seed=2, noise=2.0)
    box = {t.id: t.box_px for t in frame.truth}
    assert on_top_by_colour(frame.image, box[up], box[low]) == 0
    assert on_top_by_colour(frame.image, box[low], box[up]) == 1
    same = World()
    a = same.add("box", "red", 0.5, 0.5, size="large")
    b = same.add("box", "red", 0.2, 0.2)
    same.pick_up(b)
    same.place(b, 0.53, 0.52, onto=a)
    f2 = render(same, seed=2)
    box2 = {t.id: t.box_px for t in f2.truth}
    assert on_top_by_colour(f2.image, box2[b], box2[a]) is None  # one colour: the detector's score decides


def test_with_the_image_colours_override_a_wrong_score() -> None:
    from aileen.world.render import render
    from aileen.world.sim import World

    w = World()
    low = w.add("cylinder", "green", 0.5, 0.5, size="large")
    up = w.add("box", "yellow", 0.2, 0.2, size="small")
    w.pick_up(up)
    w.place(up, 0.47, 0.5, onto=low)
    frame = render(w)
    t = {x.id: x for x in frame.truth}
    # the scores say the lower one is on top; the overlap is yellow
    dets = [det(t[low].box_px, 0.9), det(t[up].box_px, 0.6)]
    out = resolve_levels(dets, frame.image)
    assert [d.level for d in out] == [0, 1]
    assert out[0].occluders == (t[up].box_px,)


def test_a_layered_detector_pairs_an_upper_only_with_an_object_on_the_table() -> None:
    import numpy as np

    # a layered model scores 1 (on another) or 0 (on the table); two layer-1 readings that
    # overlap are not a stack, and the colours where they overlap do not overrule the layers
    lower, upper = det((100, 100, 126, 126), 0.0), det((110, 108, 128, 126), 1.0, 0.6)
    other = det((104, 90, 122, 110), 1.0, 0.6)
    image = np.zeros((256, 256, 3), np.uint8)
    image[100:126, 100:126] = (200, 30, 30)  # the lower one's red drawn over everything
    out = resolve_levels([lower, upper, other], image, scored=True, layered=True)
    assert [d.level for d in out] == [0, 1, 0]
    assert out[0].occluders[0] == upper.box_px
    # without the lower one detected, neither carries the other (the red that shows around
    # them is what carries them: `_carried_unseen`)
    assert [d.occluders for d in resolve_levels([upper, other], image, scored=True, layered=True)] == [(), ()]


def test_an_object_rests_on_another_only_with_its_centre_over_it() -> None:
    # boxes that overlap by a third, but the upper one's centre is off the other's box
    lower, beside = det((100, 100, 126, 126), 0.0), det((118, 100, 144, 126), 0.9, 0.6)
    assert [d.level for d in resolve_levels([lower, beside])] == [0, 0]
    over = det((112, 100, 138, 126), 0.9, 0.6)  # its centre (125) over the other's box
    assert [d.level for d in resolve_levels([lower, over])] == [0, 1]


def test_an_upper_reading_whose_carrier_was_missed_keeps_its_level_when_a_sliver_shows() -> None:
    import numpy as np

    image = np.full((256, 256, 3), (196, 178, 150), np.uint8)  # wood
    image[100:126, 100:126] = (35, 70, 205)  # a blue object, alone on the wood
    weak, sure = det((100, 100, 126, 126), 1.0, 0.6), det((100, 100, 126, 126), 1.0, 1.0)
    layered = {"scored": True, "layered": True}
    # only wood around it: on the table, however sure the detector is
    assert [d.level for d in resolve_levels([weak], image, **layered)] == [0]
    assert [d.level for d in resolve_levels([sure], image, **layered)] == [0]
    # a sliver of a red object under it shows beside it: what carries it
    image[104:122, 126:131] = (200, 30, 30)
    assert [d.level for d in resolve_levels([weak], image, **layered)] == [1]
    # a model that is not layered is not read this way
    assert [d.level for d in resolve_levels([weak], image, scored=True)] == [0]


@pytest.mark.parametrize("seed", [0, 1])
def test_a_size_the_examples_of_on_showed_is_no_goal_of_move_on(tmp_path, capsys, seed: int) -> None:
    """After the size words, "on" shown with a small box on a large one kept which of the two was larger in its
    goal (`sz_smaller`): no move changes that, so "move the green cylinder on the yellow box"
    (both medium) found no plan at every depth. Which is larger describes, never a goal."""
    from pathlib import Path

    from aileen.cli import main

    path = tmp_path / "on_sizes.toml"
    path.write_text(
        '[[lesson]]\nsignal = "inform"\ncontent = "red box on blue box"\nobjects = ["small red box", "large blue box"]\n'
        'relation = "on"\n'
        '[[lesson]]\nsignal = "inform"\ncontent = "move the red box on the blue box"\n'
        'objects = ["red box", "blue box"]\ndemonstration = "auto"\n'
        '[[lesson]]\nsignal = "react"\ncontent = "move the green cylinder on the yellow box"\n'
        'objects = ["green cylinder", "yellow box"]\n')
    lessons = Path(__file__).resolve().parents[1] / "lessons"
    main(["run", str(lessons / "visual.toml"), str(lessons / "sizes.toml"), str(path), "--perception", "truth",
          "--seed", str(seed)])
    out = capsys.readouterr().out
    assert "react 1/1 reached the goal" in out
    assert "sz_smaller" not in out
