"""The relation <-> rel/3 conversion shared by comprehension and planning."""

from hypothesis import given
from hypothesis import strategies as st

from aileen.reasoning.reify import is_relation, reify, unreify
from aileen.terms import fn, parse

names = st.from_regex(r"[a-z][a-z0-9_]{0,6}", fullmatch=True)


@given(names, names, names)
def test_relations_round_trip(p: str, a: str, b: str) -> None:
    f = fn(p, a, b)
    if p in ("isa", "obj", "rel", "word_concept"):
        assert reify(f) is f
    else:
        r = reify(f)
        assert r.name == "rel" and str(r.args[0]) == p
        assert unreify(r) is f


def test_what_is_not_a_relation_passes_unchanged() -> None:
    for text in ("isa(o1,cv_red)", "held(o1)", "h(t0,w(o1,o2))", "w(o1,f(x))", "obj(o1)"):
        f = parse(text)
        assert not is_relation(f)
        assert reify(f) is f and unreify(f) is f
    assert is_relation(parse("r_left_of(o1,o2)"))
