"""Region sampling: sampled positions satisfy the requested QSRs, stay free and on the table;
impossible requests raise RegionEmpty naming the constraints."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.errors import UserError
from aileen.world.geometry import CARDINALS, cardinal, gap, rcc8
from aileen.perception.regions import RegionEmpty, sample_region
from aileen.terms import fn, parse
from aileen.world.camera import Table

TABLE = Table()


def sq(x: float, y: float, s: float = 0.1) -> tuple[float, float, float, float]:
    return (x - s / 2, y - s / 2, x + s / 2, y + s / 2)


@pytest.mark.parametrize("direction", CARDINALS)
def test_each_sector_with_dc(direction: str) -> None:
    boxes = {"o2": sq(0.5, 0.5), "o3": sq(0.2, 0.8)}
    rng = np.random.default_rng(0)
    for _ in range(20):
        x, y = sample_region(0.1, [fn(direction, "o1", "o2"), fn("dc", "o1", "o2")], boxes, TABLE, rng)
        me = sq(x, y)
        assert cardinal(me, boxes["o2"]) == direction
        assert rcc8(me, boxes["o2"]) == "dc"
        assert gap(me, boxes["o3"]) > 0.01
        assert 0.05 <= x <= 0.95 and 0.05 <= y <= 0.95


def test_ec_touches_without_overlap() -> None:
    boxes = {"o2": sq(0.5, 0.5)}
    rng = np.random.default_rng(1)
    for _ in range(20):
        x, y = sample_region(0.1, [parse("e(o1,o2)"), parse("ec(o1,o2)")], boxes, TABLE, rng)
        me = sq(x, y)
        assert rcc8(me, boxes["o2"]) == "ec"
        assert cardinal(me, boxes["o2"]) == "e"
        assert gap(me, boxes["o2"]) > 0  # no physical overlap


def test_subject_second_argument_is_inverted() -> None:
    boxes = {"o2": sq(0.5, 0.5)}
    x, y = sample_region(0.1, [parse("e(o2,o1)")], boxes, TABLE, np.random.default_rng(2))
    assert cardinal(sq(x, y), boxes["o2"]) == "w"


def test_own_box_is_ignored() -> None:
    # the held object's old box (o1) may still be listed; it is not an obstacle
    boxes = {"o1": sq(0.2, 0.5), "o2": sq(0.5, 0.5)}
    x, y = sample_region(0.1, [parse("w(o1,o2)"), parse("dc(o1,o2)")], boxes, TABLE, np.random.default_rng(3))
    assert cardinal(sq(x, y), boxes["o2"]) == "w"


def test_empty_sector_off_table() -> None:
    boxes = {"o2": sq(0.06, 0.5)}
    with pytest.raises(RegionEmpty, match=r"w\(o1,o2\)"):
        sample_region(0.1, [parse("w(o1,o2)"), parse("dc(o1,o2)")], boxes, TABLE, np.random.default_rng(0))


def test_conflicting_sectors() -> None:
    boxes = {"o2": sq(0.5, 0.5), "o3": sq(0.3, 0.5)}
    with pytest.raises(RegionEmpty):
        sample_region(0.1, [parse("w(o1,o2)"), parse("e(o1,o3)")], boxes, TABLE, np.random.default_rng(0))


def test_blocked_by_other_objects() -> None:
    # o2 in the west middle; the west sector is filled by a wall of obstacles
    boxes = {"o2": sq(0.3, 0.5)} | {f"b{i}": sq(0.1, 0.05 + 0.1 * i, 0.1) for i in range(10)}
    with pytest.raises(RegionEmpty, match="no room"):
        sample_region(0.1, [parse("w(o1,o2)"), parse("dc(o1,o2)")], boxes, TABLE, np.random.default_rng(0), tries=500)


def test_overlap_relations_are_empty() -> None:
    with pytest.raises(RegionEmpty, match="overlap"):
        sample_region(0.1, [parse("po(o1,o2)")], {"o2": sq(0.5, 0.5)}, TABLE, np.random.default_rng(0))


def test_bad_constraints() -> None:
    rng = np.random.default_rng(0)
    with pytest.raises(UserError, match="not on the table"):
        sample_region(0.1, [parse("w(o1,o9)")], {"o2": sq(0.5, 0.5)}, TABLE, rng)
    with pytest.raises(UserError, match="binary QSR"):
        sample_region(0.1, [parse("left(o1,o2)")], {"o2": sq(0.5, 0.5)}, TABLE, rng)
    assert not issubclass(UserError, RegionEmpty)


def test_deterministic_from_seed() -> None:
    boxes = {"o2": sq(0.5, 0.5)}
    rel = [parse("n(o1,o2)"), parse("dc(o1,o2)")]
    a = sample_region(0.1, rel, boxes, TABLE, np.random.default_rng(7))
    b = sample_region(0.1, rel, boxes, TABLE, np.random.default_rng(7))
    assert a == b


@settings(max_examples=60, deadline=None)
@given(
    st.sampled_from(CARDINALS),
    st.sampled_from(["dc", "ec"]),
    st.floats(0.2, 0.8),
    st.floats(0.2, 0.8),
    st.integers(0, 2**31),
)
def test_sample_satisfies_or_reports_empty(direction: str, rel: str, x2: float, y2: float, seed: int) -> None:
    boxes = {"o2": sq(x2, y2)}
    try:
        x, y = sample_region(0.1, [fn(direction, "o1", "o2"), fn(rel, "o1", "o2")], boxes, TABLE, np.random.default_rng(seed))
    except RegionEmpty:
        # only legitimate when the sector is really short of room: confirm by brute force
        xs, ys = np.meshgrid(np.linspace(0.06, 0.94, 89), np.linspace(0.06, 0.94, 89))
        ok = [
            (cardinal(sq(a, b), boxes["o2"]) == direction and rcc8(sq(a, b), boxes["o2"]) == rel and gap(sq(a, b), boxes["o2"]) > 0.003)
            for a, b in zip(xs.ravel(), ys.ravel())
        ]
        assert sum(ok) < 5
        return
    me = sq(x, y)
    assert cardinal(me, boxes["o2"]) == direction
    assert rcc8(me, boxes["o2"]) == rel


# ------------------------------------------------------------------ distance targets (issue 22)


class _Placed:
    """A square footprint as the trainer judges it (`relations.holds`)."""

    def __init__(self, x: float, y: float, side: float) -> None:
        self.x, self.y, self.side, self.size = x, y, side, "medium"

    def box_m(self) -> tuple[float, float, float, float]:
        return sq(self.x, self.y, self.side)


@settings(max_examples=40, deadline=None)
@given(st.sampled_from([("qd_close", "near"), ("qd_far", "far from")]), st.sampled_from([0.07, 0.10, 0.13]),
       st.sampled_from([0.07, 0.10, 0.13]), st.floats(0.15, 0.85), st.floats(0.15, 0.85), st.integers(0, 2**31))
def test_a_distance_target_is_what_the_trainer_calls_the_word(pred_word: tuple[str, str], mine: float, ref: float,
                                                              x2: float, y2: float, seed: int) -> None:
    """The agent places at a distance relation it perceives (qd_close, qd_far); the point is
    taken where the relation survives mismeasurement, which is also where a person says the
    word ("near" is stricter than the calculus's edge): the goal holds after the object is
    seen again and after the trainer looks."""
    from aileen.domain import relations
    from aileen.perception.regions import DEFAULT_SLACK, robustness

    pred, word = pred_word
    boxes = {"o2": sq(x2, y2, ref), "o3": sq(0.9, 0.9, 0.1)}
    try:
        x, y = sample_region(mine, [fn(pred, "o1", "o2"), fn("dc", "o1", "o2")], boxes, TABLE,
                             np.random.default_rng(seed))
    except RegionEmpty:
        assert pred == "qd_far"  # "near" always has room around a reference inside the table
        return
    cons = [(pred, "o2"), ("dc", "o2")]
    assert robustness(x, y, mine, cons, {"o2": boxes["o2"], "o3": boxes["o3"]}, TABLE) >= 1
    assert relations.holds(word, _Placed(x, y, mine), _Placed(x2, y2, ref))
    # a pixel of box noise either way does not undo it
    for dx in (-DEFAULT_SLACK, DEFAULT_SLACK):
        assert rcc8(sq(x + dx, y, mine), boxes["o2"]) == "dc"


def test_the_most_robust_candidate_is_taken() -> None:
    """Near a 10 cm box, "close" spans gaps of 1.5 to 4 cm; the target sits well inside."""
    from aileen.world.geometry import gap as box_gap

    boxes = {"o2": sq(0.5, 0.5)}
    gaps = [box_gap(sq(*sample_region(0.1, [parse("qd_close(o1,o2)"), parse("dc(o1,o2)")], boxes, TABLE,
                                       np.random.default_rng(s))), boxes["o2"]) for s in range(12)]
    assert all(0.015 < g <= 0.033 for g in gaps), gaps


@settings(max_examples=40, deadline=None)
@given(w=st.floats(0.04, 0.2), h=st.floats(0.04, 0.2), seed=st.integers(0, 2**16),
       side=st.sampled_from(["e", "w", "n", "s"]))
def test_a_box_wider_than_deep_is_put_against_the_other_on_any_side(w: float, h: float, seed: int, side: str) -> None:
    """A capsule lying across the table has a box wider one way than the other: "touching"
    puts that box, not a square of its longer side, against the reference's (a square left
    the capsule's box a gap away on its shorter side: the agent then saw it apart)."""
    boxes = {"o2": sq(0.5, 0.5)}
    x, y = sample_region((w, h), [fn(side, "o1", "o2"), fn("ec", "o1", "o2")], boxes, TABLE,
                         np.random.default_rng(seed))
    me = (x - w / 2, y - h / 2, x + w / 2, y + h / 2)
    assert rcc8(me, boxes["o2"]) == "ec" and 0 < gap(me, boxes["o2"])


@settings(max_examples=30, deadline=None)
@given(s=st.floats(0.04, 0.2), seed=st.integers(0, 2**16),
       rel=st.sampled_from(["e(o1,o2)", "ec(o1,o2)", "dc(o1,o2)", "n(o1,o2)"]))
def test_a_square_footprint_given_as_a_box_places_the_same(s: float, seed: int, rel: str) -> None:
    boxes = {"o2": sq(0.5, 0.5), "o3": sq(0.2, 0.8)}
    got = [sample_region(fp, [parse(rel)], boxes, TABLE, np.random.default_rng(seed)) for fp in (s, (s, s))]
    assert got[0] == got[1]
