"""Qualitative spatial relations at their edges (issue 27): cones, the tolerance of `cdc_eq`,
containment exactly at the margin, edges shared with a box that is not a square, and the
margins passed through `relations` and `qsr_facts`. Numbers are chosen exact in binary so that
a boundary is the boundary, not a rounding of it."""

from __future__ import annotations

import pytest

from aileen.world.geometry import CONE_EQ, cardinal, cone, heading, qsr_facts, rcc8, relations, sector_index

Q = 0.25  # a margin exact in binary
B = (1.0, 2.0, 5.0, 4.0)  # x from 1 to 5, y from 2 to 4: no two edges alike
INSIDE = (2.0, 2.5, 3.0, 3.5)


def box_at(x: float, y: float, half: float = 0.5) -> tuple[float, float, float, float]:
    return (x - half, y - half, x + half, y + half)


# ---------------------------------------------------------------- cones
@pytest.mark.parametrize("dx, dy, expected", [
    (0.0, 2.0, "cone_n"), (2.0, 0.0, "cone_e"), (0.0, -2.0, "cone_s"), (-2.0, 0.0, "cone_w"),
    (1.0, 2.0, "cone_n"), (2.0, -1.0, "cone_e"), (-1.0, -2.0, "cone_s"), (-2.0, 1.0, "cone_w"),
])
def test_a_box_lies_in_the_cone_around_the_axis_nearest_its_bearing(dx: float, dy: float, expected: str) -> None:
    assert cone(box_at(5.0 + dx, 5.0 + dy), box_at(5.0, 5.0)) == expected


def test_a_bearing_on_a_cones_edge_goes_to_the_next_cone_clockwise() -> None:
    assert cone(box_at(7.0, 7.0), box_at(5.0, 5.0)) == "cone_e"  # 45 degrees: n's edge with e
    assert cone(box_at(3.0, 3.0), box_at(5.0, 5.0)) == "cone_w"  # 225 degrees: s's edge with w


def test_boxes_with_the_same_centre_have_no_cone() -> None:
    assert cone(box_at(5.0, 5.0, 0.25), box_at(5.0, 5.0)) == CONE_EQ


def test_the_cone_tolerance_is_the_one_given() -> None:
    a, b = box_at(5.5, 5.0), box_at(5.0, 5.0)
    assert cone(a, b) == "cone_e"
    assert cone(a, b, tol=0.5) == CONE_EQ


# ---------------------------------------------------------------- the tolerance of cdc_eq
def test_centres_exactly_the_tolerance_apart_along_x_have_no_direction() -> None:
    a, b = box_at(5.5, 5.0), box_at(5.0, 5.0)
    assert cardinal(a, b, tol=0.5) == "cdc_eq"
    assert cardinal(a, b, tol=0.25) == "e"


def test_centres_exactly_the_tolerance_apart_along_y_have_no_direction() -> None:
    a, b = box_at(5.0, 4.5), box_at(5.0, 5.0)
    assert cardinal(a, b, tol=0.5) == "cdc_eq"
    assert cardinal(a, b, tol=0.25) == "s"


# ---------------------------------------------------------------- containment at the margin
@pytest.mark.parametrize("edge", range(4))
def test_a_box_sharing_an_edge_of_a_larger_box_is_its_tangential_proper_part(edge: int) -> None:
    a = list(INSIDE)
    a[edge] = B[edge]
    assert rcc8(tuple(a), B, q=Q) == "tpp"
    assert rcc8(B, tuple(a), q=Q) == "tppi"


@pytest.mark.parametrize("edge", range(4))
def test_a_box_sticking_out_by_exactly_the_margin_is_still_inside(edge: int) -> None:
    a = list(INSIDE)
    a[edge] = B[edge] - Q if edge < 2 else B[edge] + Q
    assert rcc8(tuple(a), B, q=Q) == "tpp"
    assert rcc8(B, tuple(a), q=Q) == "tppi"


@pytest.mark.parametrize("edge", range(4))
def test_an_edge_exactly_the_margin_inside_still_touches(edge: int) -> None:
    a = list(INSIDE)
    a[edge] = B[edge] + Q if edge < 2 else B[edge] - Q
    assert rcc8(tuple(a), B, q=Q) == "tpp"


def test_a_box_well_inside_touches_nothing() -> None:
    assert rcc8(INSIDE, B, q=Q) == "ntpp" and rcc8(B, INSIDE, q=Q) == "ntppi"


def test_boxes_whose_edges_differ_by_the_margin_up_to_rounding_are_equal_both_ways() -> None:
    # 0.3 - 0.29 is a hair over 0.01 in floating point; each box is inside the other within q.
    a, b = (0.3, 0.3, 0.5, 0.5), (0.29, 0.29, 0.49, 0.49)
    assert abs(a[0] - b[0]) > 0.01
    assert rcc8(a, b, q=0.01) == rcc8(b, a, q=0.01) == "eq"


# ---------------------------------------------------------------- margins passed through
def test_relations_use_the_margin_and_tolerance_given() -> None:
    a, b = (0.0, 0.0, 1.0, 1.0), (1.5, 0.0, 2.5, 1.0)  # half a metre apart, centres 1.5 apart
    assert relations(a, b) == ("w", "dc")
    assert relations(a, b, q=0.5) == ("w", "ec")
    assert relations(a, b, tol=1.5) == ("cdc_eq", "dc")


def test_qsr_facts_read_pairs_as_well_as_a_mapping_and_pass_the_margins_on() -> None:
    boxes = [("o1", (0.0, 0.0, 1.0, 1.0)), ("o2", (1.5, 0.0, 2.5, 1.0))]
    assert [str(f) for f in qsr_facts(boxes)] == ["w(o1,o2)", "dc(o1,o2)", "e(o2,o1)", "dc(o2,o1)"]
    assert [str(f) for f in qsr_facts(dict(boxes), q=0.5, tol=1.5)] == [
        "cdc_eq(o1,o2)", "ec(o1,o2)", "cdc_eq(o2,o1)", "ec(o2,o1)"]


# ---------------------------------------------------------------- headings and sectors
@pytest.mark.parametrize("dx, dy, expected", [
    (2.0, 0.0, 0.0), (0.0, 2.0, 90.0), (-2.0, 0.0, 180.0), (0.0, -2.0, 270.0), (2.0, 2.0, 45.0), (2.0, -2.0, 315.0),
])
def test_heading_is_counter_clockwise_from_east_of_the_second_box(dx: float, dy: float, expected: float) -> None:
    assert heading(box_at(5.0 + dx, 5.0 + dy), box_at(5.0, 5.0)) == pytest.approx(expected)


def test_a_heading_within_the_tolerance_along_both_axes_is_none() -> None:
    b = box_at(5.0, 5.0)
    assert heading(box_at(5.5, 5.5), b, tol=0.5) is None
    assert heading(box_at(5.5, 5.0), b, tol=0.25) == pytest.approx(0.0)
    assert heading(box_at(5.0, 5.5), b, tol=0.25) == pytest.approx(90.0)
    assert heading(box_at(5.5, 5.0), b, tol=0.5) is None and heading(box_at(5.0, 5.5), b, tol=0.5) is None


@pytest.mark.parametrize("angle, n, expected", [
    (0.0, 4, 0), (44.0, 4, 0), (45.0, 4, 1), (90.0, 4, 1), (314.0, 4, 3), (315.0, 4, 0), (359.0, 4, 0),
    (22.5, 8, 1), (22.0, 8, 0), (337.5, 8, 0), (180.0, 8, 4),
])
def test_sector_index_centres_sector_0_on_east_and_sends_an_edge_counter_clockwise(
        angle: float, n: int, expected: int) -> None:
    assert sector_index(angle, n) == expected
