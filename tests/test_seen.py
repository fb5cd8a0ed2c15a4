"""The counts of what the objects taught on are like (`agent/seen.py`): which percepts are
common, from how many objects on, and what a memory file may hold of them."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from aileen.agent.seen import COMMON, MIN_OBJECTS, SeenPercepts
from aileen.memory.persist import check_annotations
from aileen.terms import Term


def _seen(objects: list[tuple[str, ...]]) -> SeenPercepts:
    s = SeenPercepts()
    s.note(objects)
    return s


def test_a_percept_most_objects_have_is_common_and_a_rarer_one_is_not() -> None:
    objects = [("cv_medium", "cv_red")] * 4 + [("cv_medium", "cv_blue")] * 4 + [("cv_small", "cv_blue")] * 2
    assert _seen(objects).common() == {Term("cv_medium")}  # 0.8 >= COMMON; blue 0.6, red 0.4
    objects = [("cv_medium",)] * 7 + [("cv_small",)] * 3
    assert _seen(objects).common() == frozenset()  # 0.7 < COMMON


def test_nothing_is_common_before_enough_objects() -> None:
    few = _seen([("cv_medium",)] * (MIN_OBJECTS - 1))
    assert few.common() == frozenset()
    assert few.note([("cv_medium",)]) is True and few.common() == {Term("cv_medium")}
    assert few.note([("cv_medium",)]) is False  # what is common did not change


@given(st.lists(st.frozensets(st.sampled_from(["cv_a", "cv_b", "cv_c"])), min_size=MIN_OBJECTS, max_size=40))
def test_common_is_exactly_the_share_rule(objects: list[frozenset[str]]) -> None:
    s = _seen([tuple(o) for o in objects])
    for p in ("cv_a", "cv_b", "cv_c"):
        share = sum(p in o for o in objects) / len(objects)
        assert (Term(p) in s.common()) == (share >= COMMON)


def test_the_counts_round_trip_and_a_file_checks_them() -> None:
    s = _seen([("cv_medium", "cv_red"), ("cv_medium", "cv_box")])
    saved = s.to_annotation()
    s.note_taught("red")
    saved = s.to_annotation()
    assert saved == {"objects": 2, "percepts": {"cv_box": 1, "cv_medium": 2, "cv_red": 1},
                     "runs": {"cv_medium": 2}, "unbroken": ["cv_medium"], "taught": {"red": 2}, "said": {"red": 1}}
    again = SeenPercepts()
    again.load_annotation(saved)
    assert again.objects == 2 and again.counts == s.counts
    assert again.unmarked("red") == s.unmarked("red") == {Term("cv_medium")}
    assert check_annotations({"lexicon": {"seen": saved}}) is None


def test_what_every_object_had_until_a_word_was_taught_is_unmarked_for_it() -> None:
    """"green", taught on a medium sphere while every object shown was medium, does not name
    medium when later objects are large or small; a word taught after the first large one may."""
    s = _seen([("cv_medium", "cv_red"), ("cv_medium", "cv_blue"), ("cv_medium", "cv_green")])
    s.note_taught("green")
    s.note([("cv_large", "cv_red")])
    s.note_taught("large")
    assert s.unmarked("green") == {Term("cv_medium")}
    assert s.unmarked("large") == frozenset() and s.unmarked("never taught") == frozenset()
    first = _seen([("cv_medium", "cv_red")])
    first.note_taught("red")  # the first object: nothing to contrast with yet ...
    assert first.unmarked("red") == frozenset()
    first.note([("cv_medium", "cv_blue")])  # ... the second shows what was not a contrast
    assert first.unmarked("red") == {Term("cv_medium")}
    both = _seen([("cv_medium", "cv_cylinder")])
    both.note_taught("cylinder")
    both.note([("cv_medium", "cv_cylinder")])
    both.note_taught("cylinder")  # taught on every object so far: it may name what they share
    assert both.unmarked("cylinder") == frozenset()


@pytest.mark.parametrize("seen", [
    [], {"objects": -1, "percepts": {}}, {"objects": 2}, {"objects": True, "percepts": {}},
    {"objects": 2, "percepts": {"cv_red": 3}}, {"objects": 2, "percepts": {"cv_red": 1.5}},
    {"objects": 2, "percepts": {}, "extra": 1}, {"objects": 2, "percepts": {}, "runs": {"cv_red": 3}, "unbroken": []},
    {"objects": 2, "percepts": {}, "taught": {"red": -1}}, {"objects": 2, "percepts": {}, "unbroken": "cv_red"},
])
def test_a_malformed_count_is_refused_in_one_line_and_loads_nothing(seen: object) -> None:
    msg = check_annotations({"lexicon": {"seen": seen}})
    assert msg is not None and "\n" not in msg and '"seen"' in msg
    s = SeenPercepts()
    s.load_annotation(seen)
    assert s.objects == 0 or s.counts == {}  # never a count past the objects counted
    assert all(n <= s.objects for n in s.counts.values())


def test_an_experiment_gives_its_exams_again_only_when_what_is_common_changes() -> None:
    """The counts change with every inform; the agent's answers only through `common()`. The
    experiment's digest (whether the last exam's answers still hold) follows that, and reading
    it leaves the memory's annotations as they were."""
    import copy

    from aileen.agent import Agent, AgentParams
    from aileen.experiments.trial import _memory_digest

    agent = Agent(None, params=AgentParams(seed=0))
    agent.lexicon.note_seen([("cv_medium", "cv_red")] * 4 + [("cv_medium", "cv_green")] * 4
                            + [("cv_small", "cv_blue")] * 2)
    agent._sync_lexicon()
    assert agent.lexicon.seen.common() == {Term("cv_medium")}
    before = _memory_digest(agent)
    kept = copy.deepcopy(agent.memory.annotations)
    agent.lexicon.note_seen([("cv_medium", "cv_yellow")])  # counts move, medium stays common
    agent._sync_lexicon()
    assert _memory_digest(agent) == before
    agent.lexicon.note_seen([("cv_small", "cv_blue")] * 5)  # medium is no longer common
    agent._sync_lexicon()
    assert _memory_digest(agent) != before
    assert agent.memory.annotations["lexicon"]["seen"]["objects"] == 16 and "seen" in kept["lexicon"]
