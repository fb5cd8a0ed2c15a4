"""The linear exclusivity pass gives exactly what the pairwise pass gives (its specification)."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.memory.claims import exclusive


def pairwise(meanings):
    """The agent's original pass: every concept against every other, to a fixpoint."""
    m = dict(meanings)
    changed = True
    while changed:
        changed = False
        for c, mine in m.items():
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
    ms = {"a": frozenset({"red", "box"}), "b": frozenset({"red", "box"}), "c": frozenset({"red"})}
    assert exclusive(ms) == pairwise(ms) == {"a": frozenset({"box"}), "b": frozenset({"red", "box"}),
                                             "c": frozenset({"red"})}


def test_a_pinned_word_frees_the_words_taught_with_it() -> None:
    ms = {"green": frozenset({"cv_green", "cv_cone"}), "cone": frozenset({"cv_cone"}),
          "red": frozenset({"cv_red", "cv_cone"})}
    assert exclusive(ms) == {"green": frozenset({"cv_green"}), "cone": frozenset({"cv_cone"}),
                             "red": frozenset({"cv_red"})}
