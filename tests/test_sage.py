"""SAGE: assimilation, probabilities, generalized entities, thresholds."""

from __future__ import annotations

import pytest

from aileen.analogy.sage import (
    Generalization,
    GeneralizationContext,
    SageParams,
    entities_of,
    gen_ent,
)
from aileen.terms import Term, fn, parse, parse_many

A = parse_many("isa(o2,cv_red) isa(o2,cv_cylinder) isa(o2,r_red)")
B = parse_many("isa(o3,cv_red) isa(o3,cv_cube) isa(o3,r_red)")


def probs(g: Generalization) -> dict[str, float]:
    return {str(f): p for f, p in g.probabilities().items()}


def test_defaults_are_the_papers_table_2() -> None:
    p = SageParams()
    assert (p.assimilation, p.probability, p.match) == (0.01, 0.6, 0.75)


def test_bad_params_are_rejected() -> None:
    with pytest.raises(ValueError):
        SageParams(normalisation="nope")
    with pytest.raises(ValueError):
        SageParams(match=1.5)


def test_paper_rred_generalization() -> None:
    ctx = GeneralizationContext("r_red")
    r1 = ctx.add(A, SageParams())
    assert r1.action == "kept" and len(ctx.examples) == 1
    r2 = ctx.add(B, SageParams())
    assert r2.action == "new_generalization"
    assert ctx.examples == [] and len(ctx.generalizations) == 1
    g = ctx.generalizations[0]
    assert g.size == 2
    assert probs(g) == {
        "isa(gen_ent(0,r_red),r_red)": 1.0,
        "isa(gen_ent(0,r_red),cv_red)": 1.0,
        "isa(gen_ent(0,r_red),cv_cube)": 0.5,
        "isa(gen_ent(0,r_red),cv_cylinder)": 0.5,
    }
    assert {str(f) for f in g.significant(0.6)} == {"isa(gen_ent(0,r_red),r_red)", "isa(gen_ent(0,r_red),cv_red)"}


def test_third_example_updates_counts() -> None:
    ctx = GeneralizationContext("r_red")
    for ex in (A, B, parse_many("isa(o9,cv_red) isa(o9,cv_cube) isa(o9,r_red)")):
        ctx.add(ex, SageParams())
    g = ctx.generalizations[0]
    assert g.size == 3
    p = probs(g)
    assert p["isa(gen_ent(0,r_red),cv_cube)"] == pytest.approx(2 / 3)
    assert p["isa(gen_ent(0,r_red),cv_cylinder)"] == pytest.approx(1 / 3)
    assert p["isa(gen_ent(0,r_red),r_red)"] == 1.0


def test_assimilation_threshold_keeps_dissimilar_examples_apart() -> None:
    ctx = GeneralizationContext("r_x")
    strict = SageParams(assimilation=0.99)
    ctx.add(A, strict)
    r = ctx.add(B, strict)
    assert r.action == "kept" and len(ctx.examples) == 2 and ctx.generalizations == []
    # Nothing in common at all: kept even with the paper's tiny threshold.
    ctx2 = GeneralizationContext("r_x")
    ctx2.add(A, SageParams())
    assert ctx2.add(parse_many("isa(o7,cv_blue)"), SageParams()).action == "kept"


def test_identical_entities_are_kept_and_others_generalized() -> None:
    ctx = GeneralizationContext("r_move")
    ctx.add(parse_many("isa(t0,start) h(t0,dc(o1,o2)) after(t1,t0) h(t1,held(o1))"), SageParams())
    ctx.add(parse_many("isa(t0,start) h(t0,dc(o3,o1)) after(t1,t0) h(t1,held(o3))"), SageParams())
    g = ctx.generalizations[0]
    ents = set(entities_of(g.counts))
    assert Term("t0") in ents and Term("t1") in ents
    assert {gen_ent(0, "r_move"), gen_ent(1, "r_move")} <= ents
    assert not {Term("o1"), Term("o2"), Term("o3")} & ents
    assert all(p == 1.0 for p in g.probabilities().values())


def test_unaligned_entities_get_fresh_names_no_collision() -> None:
    ctx = GeneralizationContext("c")
    ctx.add(parse_many("p(o1) r(o1,o2)"), SageParams())
    ctx.add(parse_many("p(o2) r(o2,o1) q(o5)"), SageParams())
    g = ctx.generalizations[0]
    assert probs(g)["p(gen_ent(0,c))"] == 1.0
    # o5 was in no correspondence: a generalized entity of its own, probability 1/2.
    [q] = [f for f in g.counts if f.name == "q"]
    assert q.args[0].name == "gen_ent" and q.args[0] not in (gen_ent(0, "c"), gen_ent(1, "c"))
    assert g.probability(q) == 0.5


def test_low_probability_facts_do_not_count_when_matching() -> None:
    ctx = GeneralizationContext("r_red")
    ctx.add(A, SageParams())
    ctx.add(B, SageParams())
    [cand] = ctx.match(parse_many("isa(o8,cv_cube)"), SageParams()) or [None]
    assert cand is None  # cv_cube holds in half the examples only
    loose = SageParams(probability=0.5)
    [cand] = ctx.match(parse_many("isa(o8,cv_cube)"), loose)
    assert cand.mappings[0].entities == {"gen_ent(0,r_red)": "o8"}


def test_generalization_from_pair_direct() -> None:
    g = Generalization.from_pair("k", [parse("p(a)")], [parse("p(b)")], {Term("b"): Term("a")})
    assert probs(g) == {"p(gen_ent(0,k))": 1.0}
    assert g.size == 2


from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

_objs = st.sampled_from(["o1", "o2", "o3"])
_fact = st.one_of(
    st.builds(lambda o, c: fn("isa", o, c), _objs, st.sampled_from(["cv_red", "cv_blue", "cv_box", "cv_cone"])),
    st.builds(lambda r, a, b: fn(r, a, b), st.sampled_from(["w", "e", "dc"]), _objs, _objs),
)
_example = st.lists(_fact, min_size=1, max_size=6)


@settings(max_examples=40, deadline=None)
@given(st.lists(_example, min_size=1, max_size=6), st.sampled_from([0.01, 0.3, 0.9]))
def test_contexts_account_for_every_example(examples: list[list[Term]], assimilation: float) -> None:
    ctx = GeneralizationContext("r_k")
    params = SageParams(assimilation=assimilation)
    for ex in examples:
        ctx.add(ex, params)
    assert sum(g.size for g in ctx.generalizations) + len(ctx.examples) == len(examples)
    for g in ctx.generalizations:
        assert g.size >= 2
        assert all(1 <= c <= g.size for c in g.counts.values())
        assert all(0.0 < p <= 1.0 for p in g.probabilities().values())
        # A concrete name survives only if the examples that had the entity all called it
        # that: so it appears in at least as many examples as its most frequent fact counts.
        for e in entities_of(g.counts):
            if e.name != "gen_ent":
                seen = max(c for f, c in g.counts.items() if e in set(f))
                assert sum(any(e in set(f) for f in ex) for ex in examples) >= seen, e
