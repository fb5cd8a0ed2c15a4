"""SAGE's store with its content filter gives the exhaustive store's answers (issue 25, item 2).

The filter (`retrieval.StoreFilter`) runs SME only on descriptions whose similarity bound can
still reach the best similarity found; these tests store the same random examples into two
memories, one filtered and one exhaustive, and hold every store's result and the final
generalizations and examples equal. They also check that the filter does skip SME runs
(otherwise equality would hold trivially) and that ties still go to the earlier description.
"""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.analogy import sage, sme
from aileen.analogy.sage import GeneralizationContext, SageParams
from aileen.memory import retrieval
from aileen.memory.concept import ConceptMemory
from aileen.terms import Term, parse

OBJECTS = ["o1", "o2", "o3"]
CLASSES = ["cv_red", "cv_blue", "cv_box", "cv_cone", "cv_big"]
RELATIONS = ["w", "e", "dc", "ec"]


def _percept() -> st.SearchStrategy[Term]:
    return st.builds(lambda o, c: parse(f"isa({o},{c})"), st.sampled_from(OBJECTS), st.sampled_from(CLASSES))


def _relation() -> st.SearchStrategy[Term]:
    return st.builds(lambda r, x, y: parse(f"{r}({x},{y})"), st.sampled_from(RELATIONS),
                     st.sampled_from(OBJECTS), st.sampled_from(OBJECTS))


def _nested() -> st.SearchStrategy[Term]:  # an action trace's shape: h(T, relation)
    return st.builds(lambda t, r, x, y: parse(f"h({t},{r}({x},{y}))"), st.sampled_from(["t0", "t1"]),
                     st.sampled_from(RELATIONS[:2]), st.sampled_from(OBJECTS), st.sampled_from(OBJECTS))


_fact = st.one_of(_percept(), _relation(), _nested())
# An example: some facts plus the membership fact of the concept (`isa(o1,r_w)` or `r_w(o1,o2)`).
_example = st.tuples(st.lists(_fact, min_size=1, max_size=6), st.booleans())
_params = st.builds(lambda a, p: SageParams(assimilation=a, probability=p),
                    st.sampled_from([0.01, 0.3, 0.5, 0.7, 0.9]), st.sampled_from([0.4, 0.6, 1.0]))


def _with_member(ex: tuple[list[Term], bool]) -> list[Term]:
    facts, binary = ex
    return facts + [parse("r_w(o1,o2)") if binary else parse("isa(o1,r_w)")]


def _state(m: ConceptMemory) -> tuple:
    return m.generalizations("r_w"), m.examples("r_w")


@settings(max_examples=150, deadline=None)
@given(st.lists(_example, min_size=1, max_size=25), _params, st.integers(0, 3))
def test_filtered_store_equals_exhaustive_store(examples, params, refuse_every) -> None:
    filtered, exhaustive = ConceptMemory(params), ConceptMemory(params)
    for m in (filtered, exhaustive):
        m.create("r_w", "spatial")

    def accept(merged: sage.Generalization) -> bool:  # refuses some merges, deterministically
        return refuse_every == 0 or merged.size % (refuse_every + 1) != 0

    for ex in examples:
        facts = _with_member(ex)
        a = filtered.store(facts, "r_w", accept=accept)
        b = exhaustive.store(facts, "r_w", accept=accept, exhaustive=True)
        assert a == b
        assert _state(filtered) == _state(exhaustive)


def _dissimilar(i: int) -> list[Term]:
    """Examples that share only the membership fact with each other (they stay kept at 0.9)."""
    return [parse(f"isa(o1,cv_a{i})"), parse(f"isa(o1,cv_b{i})"), parse("isa(o1,r_w)")]


def test_the_filter_skips_sme_runs_and_keeps_the_answer(monkeypatch) -> None:
    params = SageParams(assimilation=0.9)
    filtered, exhaustive = ConceptMemory(params), ConceptMemory(params)
    for m in (filtered, exhaustive):
        m.create("r_w", "visual")
        for i in range(30):
            m.store(_dissimilar(i), "r_w", exhaustive=m is exhaustive)
    runs = {"n": 0}
    real = sme.match

    def counting(*a, **k):  # noqa: ANN002, ANN003, ANN202
        runs["n"] += 1
        return real(*a, **k)

    monkeypatch.setattr(sme, "match", counting)
    # Shares cv_a7 and r_w with example 7 and only r_w with the 29 others.
    probe = [parse("isa(o5,cv_a7)"), parse("isa(o5,cv_zz)"), parse("isa(o5,r_w)")]
    a = filtered.store(probe, "r_w")
    filtered_runs, runs["n"] = runs["n"], 0
    b = exhaustive.store(probe, "r_w", exhaustive=True)
    assert a == b and a.action == "kept" and a.similarity > 0
    assert runs["n"] == 30  # the exhaustive store matches every description
    assert filtered_runs == 1  # the filtered one only example 7: no other can reach its similarity
    assert _state(filtered) == _state(exhaustive)


def test_ties_go_to_the_earlier_description_as_in_the_exhaustive_store() -> None:
    params = SageParams(assimilation=0.3)
    twins = [[parse(f"isa(o{k},cv_red)"), parse(f"isa(o{k},r_w)"), parse(f"isa(o{k},cv_q{k})")] for k in (1, 2)]
    contexts = []
    for use_filter in (True, False):
        ctx = GeneralizationContext("r_w")
        ctx.examples.extend(twins)  # two kept examples equally similar to the probe
        f = retrieval.StoreFilter().bounds("r_w", ctx, params) if use_filter else None
        r = ctx.add([parse("isa(o9,cv_red)"), parse("isa(o9,r_w)")], params, bounds=f)
        contexts.append((r, [sorted(map(str, g.counts)) for g in ctx.generalizations], ctx.examples))
    assert contexts[0] == contexts[1]
    r, gens, kept = contexts[0]
    assert r.action == "new_generalization"
    assert kept == [twins[1]]  # the first example was merged, the second is still kept
    assert any("cv_q1" in f for f in gens[0])


def test_no_filter_with_function_predicates() -> None:
    params = SageParams(functions=frozenset({"f"}))
    assert retrieval.StoreFilter().bounds("r_w", GeneralizationContext("r_w"), params) is None
