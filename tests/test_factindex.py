"""The state's fact index answers exactly what a scan of the facts answers, in the same order."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.perception.factindex import FactIndex
from aileen.terms import Term

OBJS = ["o1", "o2", "o3", "o4"]
fact = st.one_of(
    st.builds(lambda o, c: Term("isa", (Term(o), Term(c))), st.sampled_from(OBJS), st.sampled_from(["cv_red", "cv_box"])),
    st.builds(lambda r, a, b: Term(r, (Term(a), Term(b))), st.sampled_from(["w", "e", "dc", "ec"]),
              st.sampled_from(OBJS), st.sampled_from(OBJS)),
    st.builds(lambda o: Term("held", (Term(o),)), st.sampled_from(OBJS)),
)


def scan_percepts(facts, obj):  # the definition the index replaces (State.percepts)
    o = Term(obj)
    return [f for f in facts if f.name == "isa" and f.args[0] is o]


def scan_relations(facts, a, b):  # (State.relations)
    ta, tb = Term(a), Term(b)
    return [f for f in facts if f.name != "isa" and len(f.args) == 2 and {f.args[0], f.args[1]} == {ta, tb}]


@settings(max_examples=150, deadline=None)
@given(st.lists(fact, max_size=40))
def test_index_answers_what_the_scan_answers(facts) -> None:
    idx = FactIndex(facts)
    for a in OBJS + ["o9"]:
        assert idx.percepts(a) == scan_percepts(facts, a)
        for b in OBJS:
            assert idx.relations(a, b) == scan_relations(facts, a, b)
    assert idx.size == len(facts)


def test_answers_are_copies() -> None:
    idx = FactIndex([Term("isa", (Term("o1"), Term("cv_red")))])
    idx.percepts("o1").append(Term("x"))
    assert idx.percepts("o1") == [Term("isa", (Term("o1"), Term("cv_red")))]
