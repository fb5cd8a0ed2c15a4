"""The evaluation's pairing of perceived with true objects (aileen/perception/matching.py)."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.perception.matching import AGREE, GREEDY, TIE_M, match

# A green cone (true 0, level 1) resting near the middle of a small red cylinder (true 1,
# 21 % of it in sight), both perceived right: perceived 0 is the cone, perceived 1 the
# cylinder, but each perceived centre lies a few millimetres nearer the other's true one
# (as in seed 2024, scene 849 of `aileen perception eval`).
CONE, CYLINDER = ("cone", "green", 1), ("cylinder", "red", 0)
TRUE = [(0.500, 0.500, 0.07), (0.503, 0.500, 0.07)]
SEEN_AT = [(0.504, 0.500), (0.5005, 0.500)]
SEEN = [CONE, CYLINDER]
TRUTH = [CONE, CYLINDER]


def _agree(seen, truth):
    return lambda i, j: sum(a == b for a, b in zip(seen[i], truth[j]))


def test_nearest_first_pairs_a_near_centred_stack_the_wrong_way_round() -> None:
    pairs = match(SEEN_AT, TRUE, _agree(SEEN, TRUTH), rule=GREEDY)
    assert {(i, j) for i, j, _ in pairs} == {(1, 0), (0, 1)}


def test_the_attributes_decide_which_is_which_when_positions_cannot() -> None:
    pairs = match(SEEN_AT, TRUE, _agree(SEEN, TRUTH), rule=AGREE)
    assert {(i, j) for i, j, _ in pairs} == {(0, 0), (1, 1)}


def test_positions_decide_where_they_can() -> None:
    # the same two objects 3 cm apart, perceived each at the other's place: a real error
    true = [(0.50, 0.50, 0.07), (0.52, 0.50, 0.07)]
    seen_at = [(0.52, 0.50), (0.50, 0.50)]
    pairs = match(seen_at, true, _agree(SEEN, TRUTH), rule=AGREE)
    assert {(i, j) for i, j, _ in pairs} == {(0, 1), (1, 0)}


def test_a_stack_read_as_one_object_misses_the_same_object_either_way() -> None:
    # one perception (a cylinder at level 0) nearest the cone's centre: the cylinder is missed
    # under both rules, though the attributes agree with it
    seen = [CYLINDER]
    seen_at = [(0.5005, 0.5)]
    for rule in (GREEDY, AGREE):
        pairs = match(seen_at, TRUE, _agree(seen, TRUTH), rule=rule)
        assert [(i, j) for i, j, _ in pairs] == [(0, 0)]


_coord = st.floats(min_value=0.0, max_value=0.1, allow_nan=False)
_attrs = st.tuples(st.sampled_from("abc"), st.sampled_from("xy"), st.integers(0, 1))


@settings(max_examples=300, deadline=None)
@given(st.lists(st.tuples(_coord, _coord, _attrs), min_size=0, max_size=5),
       st.lists(st.tuples(_coord, _coord, st.floats(0.04, 0.13), _attrs), min_size=0, max_size=5))
def test_the_attributes_never_change_which_objects_pair_only_which_is_which(seen, true) -> None:
    seen_at = [(x, y) for x, y, _ in seen]
    true_at = [(x, y, f) for x, y, f, _ in true]
    agree = _agree([a for *_, a in seen], [a for *_, a in true])
    greedy = match(seen_at, true_at, agree, rule=GREEDY)
    pairs = match(seen_at, true_at, agree, rule=AGREE)
    assert sorted(i for i, _, _ in pairs) == sorted(i for i, _, _ in greedy)  # the same perceived objects pair
    assert sorted(j for _, j, _ in pairs) == sorted(j for _, j, _ in greedy)  # with the same true ones
    assert sum(d for *_, d in pairs) <= sum(d for *_, d in greedy) + TIE_M + 1e-12
    assert sum(agree(i, j) for i, j, _ in pairs) >= sum(agree(i, j) for i, j, _ in greedy)
    for i, j, d in pairs:
        x, y, f = true_at[j]
        assert d < 0.4 * f
