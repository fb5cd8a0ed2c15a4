"""The linear exclusivity pass gives exactly what the pairwise pass gives (its specification)."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.memory.claims import exclusive


def pairwise(meanings):
    """The agent's original pass: every concept against every other, to a fixpoint; a concept
    whose given meaning another concept has too gives up nothing."""
    m = dict(meanings)
    given = list(meanings.values())
    changed = True
    while changed:
        changed = False
        for c, mine in m.items():
            if given.count(meanings[c]) > 1:
                continue
            claimed = set()
            for other, theirs in m.items():
                if other != c and theirs and theirs < mine:
                    claimed |= theirs
            rest = mine - claimed
            if rest and rest != mine:
                m[c] = frozenset(rest)
                changed = True
    return m


PERCEPTS = ["red", "blue", "box", "cone", "green"]
meaning = st.frozensets(st.sampled_from(PERCEPTS), max_size=4)


@settings(max_examples=300, deadline=None)
@given(st.lists(meaning, max_size=14))
def test_same_as_the_pairwise_pass(ms) -> None:
    meanings = {f"w{i}": s for i, s in enumerate(ms)}
    assert exclusive(meanings) == pairwise(meanings)


def test_order_matters_as_in_the_pairwise_pass() -> None:
    ms = {"a": frozenset({"red", "box"}), "b": frozenset({"red", "box", "large"}), "c": frozenset({"red"})}
    assert exclusive(ms) == pairwise(ms) == {"a": frozenset({"box"}), "b": frozenset({"large"}),
                                             "c": frozenset({"red"})}
    assert exclusive(ms, frozenset({"large"})) == {"a": frozenset({"box"}), "b": frozenset({"red", "box", "large"}),
                                                   "c": frozenset({"red"})}


def test_two_words_shown_on_the_same_things_give_up_nothing() -> None:
    """"red" and "box", each shown once on a red box, and "crimson" shown on red things: the
    order of the pass no longer decides that "red" means box (it did: "red" came first)."""
    ms = {"red": frozenset({"cv_red", "cv_box"}), "box": frozenset({"cv_red", "cv_box"}),
          "crimson": frozenset({"cv_red"})}
    assert exclusive(ms) == pairwise(ms) == ms
    flipped = {"box": ms["box"], "red": ms["red"], "crimson": ms["crimson"]}
    assert exclusive(flipped) == flipped


def test_a_pinned_word_frees_the_words_taught_with_it() -> None:
    ms = {"green": frozenset({"cv_green", "cv_cone"}), "cone": frozenset({"cv_cone"}),
          "red": frozenset({"cv_red", "cv_cone"})}
    assert exclusive(ms) == {"green": frozenset({"cv_green"}), "cone": frozenset({"cv_cone"}),
                             "red": frozenset({"cv_red"})}


# ---------------------------------------------------------------- kept up to date (issue 25)
from hypothesis import HealthCheck  # noqa: E402

from aileen.memory.claims import Exclusivity  # noqa: E402

_KEYS = [f"w{i}" for i in range(10)]
_MANY = [f"p{i}" for i in range(10)]  # meanings of more than 6 percepts go through the postings


def _steps(percepts: list[str], most: int):  # noqa: ANN202
    step = st.tuples(st.sampled_from(_KEYS), st.one_of(st.none(), st.frozensets(st.sampled_from(percepts),
                                                                                   max_size=most)))
    flat = st.one_of(st.none(), st.frozensets(st.sampled_from(percepts), max_size=2))
    return st.lists(st.tuples(st.lists(step, min_size=1, max_size=4), flat), max_size=14)


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.one_of(_steps(PERCEPTS, 4), _steps(_MANY, 9)), st.sampled_from(["replay", "plain pass", "bulk", "mixed"]))
def test_kept_up_to_date_it_gives_what_the_pass_from_scratch_gives(steps, way) -> None:
    """After every batch of changes (set, add, remove meanings; change the uninformative
    percepts), the incremental meanings are `exclusive` over the meanings now held, in the
    same order, and the keys it says changed are exactly those whose meaning changed: when
    the replay runs to its end, when it gives way to the plain pass over its part at once,
    when every update is one plain pass over everything, and mixed as in use."""
    import aileen.memory.claims as claims

    kept = (claims._REPLAY_BUDGET, claims._REPLAY_SLACK, claims._BULK_SHARE)
    if way != "mixed":
        claims._BULK_SHARE = 10**9 if way == "bulk" else 0
    if way == "plain pass":
        claims._REPLAY_BUDGET, claims._REPLAY_SLACK = 0, 0
    try:
        _check_updates(steps)
    finally:
        claims._REPLAY_BUDGET, claims._REPLAY_SLACK, claims._BULK_SHARE = kept


def _check_updates(steps) -> None:  # noqa: ANN001
    inc: Exclusivity = Exclusivity()
    held: dict[str, frozenset] = {}
    flat: frozenset = frozenset()
    before: dict[str, frozenset] = {}
    for batch, new_flat in steps:
        changes = dict(batch)
        for k, m in changes.items():
            if m is None:
                held.pop(k, None)
            else:
                held[k] = m
        if new_flat is not None:
            flat = new_flat
        said = inc.update(changes, new_flat)
        want = exclusive(held, flat)
        assert dict(inc.meanings()) == want
        assert list(inc.meanings()) == list(want)
        assert said == {k: before.get(k) for k in {*before, *want} if before.get(k) != want.get(k)}
        before = want


def test_kept_up_to_date_a_store_that_pins_a_word_frees_the_words_taught_with_it() -> None:
    inc: Exclusivity = Exclusivity()
    inc.update({"green": frozenset({"cv_green", "cv_cone"}), "red": frozenset({"cv_red", "cv_cone"})})
    assert inc.meanings()["green"] == {"cv_green", "cv_cone"}
    changed = inc.update({"cone": frozenset({"cv_cone"})})
    assert changed == {"green": {"cv_green", "cv_cone"}, "red": {"cv_red", "cv_cone"}, "cone": None}
    assert dict(inc.meanings()) == {"green": frozenset({"cv_green"}), "red": frozenset({"cv_red"}),
                                    "cone": frozenset({"cv_cone"})}
    assert inc.acting() == {"green", "red"}


def test_kept_up_to_date_a_store_elsewhere_visits_no_concept_that_gives_nothing_up() -> None:
    """Concepts none of whose strict subsets is held are not even looked at."""
    inc: Exclusivity = Exclusivity()
    inc.update({f"w{i}": frozenset({f"a{i}", f"b{i}"}) for i in range(1000)})
    assert inc.acting() == frozenset()
    inc.update({"red": frozenset({"cv_red"}), "grox": frozenset({"cv_red", "cv_box"})})
    assert inc.acting() == {"grox"}
    assert inc.meanings()["grox"] == {"cv_box"}


def test_kept_up_to_date_it_copies_and_pickles_with_the_agent() -> None:
    import copy
    import pickle

    inc: Exclusivity = Exclusivity()
    inc.update({"red": frozenset({"cv_red"}), "grox": frozenset({"cv_red", "cv_box"})})
    for twin in (copy.deepcopy(inc), pickle.loads(pickle.dumps(inc))):
        twin.update({"box": frozenset({"cv_box"})})
        assert dict(twin.meanings()) == exclusive({"red": frozenset({"cv_red"}), "grox": frozenset({"cv_red", "cv_box"}),
                                                   "box": frozenset({"cv_box"})})
    assert dict(inc.meanings()) == {"red": {"cv_red"}, "grox": {"cv_box"}}
