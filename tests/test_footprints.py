"""The exact footprints and their clearance (aileen/world/footprints.py), and the trainer's
overlap check that reads them."""

from __future__ import annotations

import math
from pathlib import Path

from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.curriculum import lessonfile
from aileen.curriculum.trainer import layout
from aileen.world import catalog
from aileen.world.footprints import clearance, footprint
from aileen.world.records import footprint_half_extents

SHAPES = st.sampled_from(catalog.SHAPES)
SIDES = st.sampled_from(sorted(catalog.SIZES.values()))
ANGLES = st.floats(0.0, math.pi)
XY = st.floats(0.0, 1.0)


def _box_gap(shape: str, side: float, angle: float, x: float, y: float,
             shape2: str, side2: float, angle2: float, x2: float, y2: float) -> float:
    hx, hy = footprint_half_extents(shape, side, angle)
    gx, gy = footprint_half_extents(shape2, side2, angle2)
    return max(abs(x - x2) - hx - gx, abs(y - y2) - hy - gy)


@settings(max_examples=300, deadline=None)
@given(st.tuples(SHAPES, SIDES, ANGLES, XY, XY), st.tuples(SHAPES, SIDES, ANGLES, XY, XY))
def test_clearance_is_symmetric_and_never_below_the_boxes_gap(one: tuple, two: tuple) -> None:
    args = (*one, *two)
    a, b = footprint(*one), footprint(*two)
    assert math.isclose(clearance(a, b), clearance(b, a), abs_tol=1e-9)
    # a footprint lies inside the box around it: boxes apart, footprints at least as far apart
    if _box_gap(*args) > 0.0:
        assert clearance(a, b) >= _box_gap(*args) - 1e-9


@settings(max_examples=200, deadline=None)
@given(SIDES, SIDES, st.floats(0.0, 2 * math.pi), st.floats(0.0, 0.5))
def test_two_round_objects_are_as_far_apart_as_their_centres_less_both_radii(s1: float, s2: float,
                                                                               bearing: float, d: float) -> None:
    a = footprint("sphere", s1, 0.0, 0.5, 0.5)
    b = footprint("cylinder", s2, 1.0, 0.5 + d * math.cos(bearing), 0.5 + d * math.sin(bearing))
    assert math.isclose(clearance(a, b), max(d, 0.0) - (s1 + s2) / 2, abs_tol=1e-9)


@settings(max_examples=100, deadline=None)
@given(SIDES, SIDES, st.floats(0.001, 0.3), st.floats(-0.02, 0.02))
def test_boxes_square_to_the_table_side_by_side_are_their_gap_apart(s1: float, s2: float, g: float,
                                                                      dy: float) -> None:
    a = footprint("box", s1, 0.0, 0.2, 0.5)
    b = footprint("box", s2, 0.0, 0.2 + (s1 + s2) / 2 + g, 0.5 + dy)
    assert math.isclose(clearance(a, b), g, abs_tol=1e-9)


def test_a_turned_box_and_a_sphere_off_its_corner() -> None:
    box = footprint("box", 0.1, math.pi / 4, 0.5, 0.5)  # a diamond: its corner 0.0707 m east
    assert math.isclose(clearance(box, footprint("sphere", 0.1, 0.0, 0.5 + 0.0707 + 0.05 + 0.02, 0.5)),
                        0.02, abs_tol=1e-3)
    assert clearance(box, footprint("sphere", 0.1, 0.0, 0.55, 0.55)) < 0.0  # its centre on the box


def test_a_lying_capsule_is_a_rounded_segment() -> None:
    cap = footprint("capsule", 0.12, 0.0, 0.5, 0.5)  # 6 cm long, ends of radius 3 cm
    assert math.isclose(clearance(cap, footprint("sphere", 0.1, 0.0, 0.5, 0.5 + 0.03 + 0.05 + 0.01)), 0.01,
                        abs_tol=1e-9)
    assert math.isclose(clearance(cap, footprint("sphere", 0.1, 0.0, 0.5 + 0.06 + 0.05 + 0.01, 0.5)), 0.01,
                        abs_tol=1e-9)


def test_round_objects_near_each_other_on_a_diagonal_are_laid_out(tmp_path: Path) -> None:
    # 0.135 m apart on a diagonal, 3.5 cm between them: their boxes meet, they do not (the
    # distance probe's file at seed 3 was refused: "after settling, obj1 and obj2 overlap")
    f = tmp_path / "diagonal.toml"
    f.write_text('[[lesson]]\nsignal = "verify"\ncontent = "red cylinder toma of blue sphere"\n'
                 'objects = [{ shape = "cylinder", colour = "red", size = "medium", position = [0.850, 0.436] }, '
                 '{ shape = "sphere", colour = "blue", size = "medium", position = [0.758, 0.336] }]\n'
                 'expect = "failure"\n')
    setup = layout(lessonfile.load(f).lessons[0], seed=3)
    a, b = setup.world.objects()
    assert math.hypot(a.x - b.x, a.y - b.y) > 0.13
