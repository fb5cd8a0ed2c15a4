"""Terms: interning, ASP-syntax round trip, parse errors, unify and substitute."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.terms import Term, TermSyntaxError, fn, parse, parse_many, substitute, unify

names = st.from_regex(r"[a-z][a-zA-Z0-9_]{0,6}", fullmatch=True)
variables = st.from_regex(r"[A-Z][a-zA-Z0-9_]{0,4}", fullmatch=True)
numbers = st.integers(min_value=-10**6, max_value=10**6)
strings = st.from_regex(r'"[a-z ]{0,5}"', fullmatch=True)
leaves = st.one_of(names, variables, numbers, strings).map(Term)
terms = st.recursive(
    leaves,
    lambda inner: st.builds(lambda n, args: Term(n, tuple(args)), names, st.lists(inner, min_size=1, max_size=4)),
    max_leaves=20,
)


@settings(max_examples=100, deadline=None)
@given(terms)
def test_round_trip(t: Term) -> None:
    assert parse(str(t)) is t
    assert parse(str(t) + ".") is t


@settings(max_examples=50, deadline=None)
@given(st.lists(terms, max_size=5))
def test_parse_many_round_trip(ts: list[Term]) -> None:
    assert parse_many(". ".join(str(t) for t in ts) + ("." if ts else "")) == ts


def test_paper_fact_round_trip() -> None:
    text = "cause(greater(pressure(beaker),pressure(vial)),flow(beaker,vial,water,pipe))"
    t = parse(text)
    assert str(t) == text
    assert t.name == "cause" and t.args[1] is fn("flow", "beaker", "vial", "water", "pipe")
    assert parse("  isa( o1 , cv_red ) ") is fn("isa", "o1", "cv_red")


@pytest.mark.parametrize("text", ["", "isa(o1,", "isa(o1 cv)", "f()", "(a)", "a b", "f(a))", "é"])
def test_parse_errors(text: str) -> None:
    with pytest.raises(TermSyntaxError):
        parse(text)


def test_unify_and_substitute() -> None:
    b = unify(parse("isa(O,r_red)"), parse("isa(o4,r_red)"))
    assert b == {Term("O"): Term("o4")}
    assert unify(parse("isa(O,r_red)"), parse("isa(o4,r_blue)")) is None
    assert unify(parse("r(X,X)"), parse("r(a,b)")) is None
    assert unify(parse("r(X,_)"), parse("r(a,b)")) == {Term("X"): Term("a")}
    assert substitute(parse("h(t0,w(o1,o2))"), {Term("o1"): Term("o9")}) is parse("h(t0,w(o9,o2))")


def test_interning_and_immutability() -> None:
    assert fn("w", "o1", "o2") is parse("w(o1,o2)")
    with pytest.raises(AttributeError):
        fn("w", "o1", "o2").name = "e"  # type: ignore[misc]


def test_a_term_nested_past_the_limit_is_a_syntax_error_not_a_recursion_error() -> None:
    # a memory file with a fact nested 300 deep loaded, and its save ended in a RecursionError
    # (a traceback, the run's learning lost); 5,000 deep failed the load the same way
    from aileen.terms import MAX_DEPTH

    ok = "f(" * MAX_DEPTH + "a" + ")" * MAX_DEPTH
    assert str(parse(ok)) == ok
    for depth in (MAX_DEPTH + 1, 300, 5000):
        text = "f(" * depth + "a" + ")" * depth
        with pytest.raises(TermSyntaxError, match=f"a term nested more than {MAX_DEPTH} deep") as info:
            parse(text)
        assert len(str(info.value)) < 200  # the text is shortened: one readable line


def test_a_memory_file_with_a_deeply_nested_fact_is_one_line_and_exit_2(tmp_path, capsys) -> None:
    import json

    from aileen.cli import main

    lessons = tmp_path / "one.toml"
    lessons.write_text('[[lesson]]\nsignal = "inform"\ncontent = "red box"\nobjects = ["red box"]\n')
    memory = tmp_path / "m.json"
    assert main(["run", str(lessons), "--memory", str(memory), "--perception", "truth"]) == 0
    data = json.loads(memory.read_text())
    data["concepts"][0]["examples"][0].append("f(" * 300 + "a" + ")" * 300)
    memory.write_text(json.dumps(data))
    before = memory.read_bytes()
    capsys.readouterr()
    assert main(["run", str(lessons), "--memory", str(memory), "--perception", "truth"]) == 2
    err = capsys.readouterr().err.strip()
    assert "a term nested more than" in err and len(err.splitlines()) == 1 and "Traceback" not in err
    assert memory.read_bytes() == before
