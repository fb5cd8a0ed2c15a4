"""SME against the public SME v4 regression suite, plus properties that must hold for any input."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.analogy import sme
from aileen.terms import Term, fn, parse

# The older preset the SME v4 regression file scores with.
OLD = sme.Params(same_functor=0.005, same_function=0.002, trickle_down=16.0)
FUNCTIONS = frozenset({"pressure", "diameter", "temperature", "mass", "charge"})

# sme/dgroup/swater.dgr and sheat.dgr ("Simple heat/water analogy"), '-' written as '_'.
SWATER = [
    "flow(beaker,vial,water,pipe)",
    "greater(pressure(beaker),pressure(vial))",
    "greater(diameter(beaker),diameter(vial))",
    "clear(beaker)",
    "flat_top(water)",
    "liquid(water)",
    "cause(greater(pressure(beaker),pressure(vial)),flow(beaker,vial,water,pipe))",
]
SHEAT = [
    "flow(coffee,ice_cube,heat,bar)",
    "greater(temperature(coffee),temperature(ice_cube))",
    "flat_top(coffee)",
    "liquid(coffee)",
]
# sme/dgroup/solar.dgr and ruther.dgr ("Rutherford analogy").
SOLAR = [
    "greater(mass(sun),mass(planet))",
    "attracts(sun,planet)",
    "revolve_around(planet,sun)",
    "cause(and(greater(mass(sun),mass(planet)),attracts(sun,planet)),revolve_around(planet,sun))",
    "greater(temperature(sun),temperature(planet))",
    "cause(gravity(mass(sun),mass(planet)),attracts(sun,planet))",
]
RUTHER = [
    "greater(mass(nucleus),mass(electron))",
    "attracts(nucleus,electron)",
    "revolve_around(electron,nucleus)",
    "cause(opposite_sign(charge(nucleus),charge(electron)),attracts(nucleus,electron))",
]


def strs(terms: list[Term]) -> set[str]:
    return {str(t) for t in terms}


def test_simple_water_heat_regression() -> None:
    r = sme.analyze(SWATER, SHEAT, functions=FUNCTIONS, params=OLD)
    assert (r.mh_count, r.kernel_count, len(r.mappings)) == (20, 5, 2)
    m1, m2 = r.mappings
    ents = {"pipe": "bar", "water": "heat", "beaker": "coffee", "vial": "ice_cube"}
    for m in (m1, m2):
        assert m.score == pytest.approx(3.1179998, abs=1e-3)
        assert m.mh_count == 11
        assert m.entities == ents
    assert strs([b for b, _ in m1.root_pairs]) == {
        "flow(beaker,vial,water,pipe)", "greater(pressure(beaker),pressure(vial))"}
    assert strs([b for b, _ in m2.root_pairs]) == {
        "flow(beaker,vial,water,pipe)", "greater(diameter(beaker),diameter(vial))"}
    assert strs(m1.inferences) == {
        "cause(greater(temperature(coffee),temperature(ice_cube)),flow(coffee,ice_cube,heat,bar))",
        "liquid(heat)", "flat_top(heat)", "clear(coffee)",
        "greater(diameter(coffee),diameter(ice_cube))",
    }
    assert strs(m2.inferences) == {
        "clear(coffee)", "liquid(heat)", "flat_top(heat)",
        "cause(greater(pressure(coffee),pressure(ice_cube)),flow(coffee,ice_cube,heat,bar))",
    }
    # Reverse: the coffee's attributes, about the beaker.
    assert strs(m1.reverse_inferences) == {"flat_top(beaker)", "liquid(beaker)"}


def test_rutherford_regression() -> None:
    r = sme.analyze(SOLAR, RUTHER, functions=FUNCTIONS, params=OLD)
    assert (r.mh_count, r.kernel_count, len(r.mappings)) == (22, 6, 2)
    m1, m2 = r.mappings
    assert m1.score == pytest.approx(3.2250004, abs=1e-3)
    assert m2.score == pytest.approx(3.1230001, abs=1e-3)
    assert m1.mh_count == m2.mh_count == 11
    for m in (m1, m2):
        assert m.entities == {"sun": "nucleus", "planet": "electron"}
    assert strs(m1.inferences) == {
        "cause(and(greater(mass(nucleus),mass(electron)),attracts(nucleus,electron)),"
        "revolve_around(electron,nucleus))",
        "greater(temperature(nucleus),temperature(electron))",
        "cause(gravity(mass(nucleus),mass(electron)),attracts(nucleus,electron))",
    }
    assert strs(m2.inferences) == {
        "cause(and(greater(mass(nucleus),mass(electron)),attracts(nucleus,electron)),"
        "revolve_around(electron,nucleus))",
        "cause(gravity(mass(nucleus),mass(electron)),attracts(nucleus,electron))",
    }
    assert strs([b for b, _ in m2.root_pairs]) >= {"greater(temperature(sun),temperature(planet))"}


def test_functions_only_align_when_declared() -> None:
    # Without declaring them functions, pressure and temperature are relations: no alignment.
    r = sme.analyze(SWATER, SHEAT, params=OLD)
    assert all("greater" not in str(b) for m in r.mappings for b, _ in m.root_pairs)


def test_default_preset_keeps_ratios() -> None:
    # Halving both local scores halves the scores (trickle-down is linear).
    new = sme.match(SOLAR, RUTHER, functions=FUNCTIONS, params=sme.Params(same_functor=0.0025, same_function=0.001, trickle_down=16.0))
    old = sme.match(SOLAR, RUTHER, functions=FUNCTIONS, params=OLD)
    assert new[0].score == pytest.approx(old[0].score / 2)
    assert new[0].similarity == pytest.approx(old[0].similarity)


def test_isa_class_only_aligns_with_identical_class() -> None:
    ms = sme.match(["isa(g,cv_red)", "isa(g,r_red)"], ["isa(o4,cv_blue)", "isa(o5,cv_red)"])
    assert len(ms) == 1
    assert ms[0].entities == {"g": "o5"}
    assert strs(ms[0].inferences) == {"isa(o5,r_red)"}
    # o4 shares nothing with the base: no inference about it either way.
    assert ms[0].reverse_inferences == []


def test_generalized_entities_and_skolems_are_entities() -> None:
    g0, g1 = fn("gen_ent", 0, "r_left_of"), fn("gen_ent", 1, "r_left_of")
    base = [fn("w", g0, g1), fn("r_left_of", g0, g1), fn("isa", g0, "cv_red"), fn("near", g0, fn("skolem", "x"))]
    ms = sme.match(base, ["w(o1,o2)", "isa(o1,cv_red)"])
    assert ms[0].entities == {str(g0): "o1", str(g1): "o2"}
    assert strs(ms[0].inferences) == {"r_left_of(o1,o2)", "near(o1,skolem(skolem(x)))"}


def test_higher_order_trace_facts() -> None:
    base = ["isa(t0,start)", "h(t0,dc(a,b))", "after(t1,t0)", "h(t1,held(a))"]
    ms = sme.match(base, ["isa(t0,start)", "h(t0,dc(o5,o6))", "h(t0,e(o5,o6))"])
    m = ms[0]
    assert m.entities == {"t0": "t0", "a": "o5", "b": "o6"}
    assert strs(m.inferences) == {"after(skolem(t1),t0)", "h(skolem(t1),held(o5))"}
    assert strs(m.reverse_inferences) == {"h(t0,e(a,b))"}


def test_no_overlap_gives_no_mapping() -> None:
    assert sme.match(["p(a)"], ["q(b)"]) == []
    assert sme.match([], ["q(b)"]) == []


def test_max_mappings_and_cutoff() -> None:
    base = ["r(a,b)"]
    target = ["r(c,d)", "r(e,f)", "r(g,h)", "r(i,j)"]
    assert len(sme.match(base, target)) == 3
    assert len(sme.match(base, target, params=sme.Params(max_mappings=1))) == 1
    # A much weaker second interpretation is cut off.
    ms = sme.match(["r(a,b)", "p(a)", "q(b)"], ["r(c,d)", "p(c)", "q(d)", "p(x)"])
    assert len(ms) == 1 and ms[0].entities == {"a": "c", "b": "d"}


# ----------------------------------------------------------------------------- properties

ENTS = ["a", "b", "c", "d"]
atoms = st.sampled_from(ENTS).map(Term)
unary = st.builds(lambda p, x: fn(p, x), st.sampled_from(["p", "q"]), atoms)
binary = st.builds(lambda p, x, y: fn(p, x, y), st.sampled_from(["r", "s"]), atoms, atoms)
isa = st.builds(lambda x, c: fn("isa", x, c), atoms, st.sampled_from(["cv_red", "cv_box", "r_red"]))
first_order = st.one_of(unary, binary, isa)
higher = st.builds(lambda a, b: fn("cause", a, b), first_order, first_order)
descriptions = st.lists(st.one_of(first_order, higher), min_size=1, max_size=8)


@settings(max_examples=60, deadline=None)
@given(descriptions)
def test_self_match_is_identity_with_similarity_one(facts: list[Term]) -> None:
    ms = sme.match(facts, facts)
    assert ms
    assert ms[0].similarity == pytest.approx(1.0)
    assert all(b == t for b, t in ms[0].entities.items())
    assert ms[0].inferences == [] and ms[0].reverse_inferences == []


@settings(max_examples=60, deadline=None)
@given(descriptions, descriptions)
def test_mappings_are_one_to_one_and_similarity_bounded(base: list[Term], target: list[Term]) -> None:
    ms = sme.match(base, target)
    for m in ms:
        assert 0.0 <= m.similarity <= 1.0
        targets = list(m.pairs.values())
        assert len(targets) == len(set(targets))
        # Parallel connectivity: a mapped expression's arguments are mapped to the target's.
        conv = {sme._to_sme(b): sme._to_sme(t) for b, t in m.pairs.items()}
        for b, t in conv.items():
            if not sme.is_entity(b):
                assert len(b.args) == len(t.args)
                for ba, ta in zip(b.args, t.args):
                    assert conv.get(ba) is ta, (b, t)
    scores = [m.score for m in ms]
    assert scores == sorted(scores, reverse=True)
    if ms:
        assert all(s >= 0.8 * scores[0] - 1e-12 for s in scores)


def test_self_score_matches_identity_match_score() -> None:
    for facts in (SWATER, SOLAR, ["isa(o1,cv_red)", "w(o1,o2)"]):
        ms = sme.match(facts, facts, functions=FUNCTIONS)
        assert ms[0].score == pytest.approx(sme.self_score(facts, functions=FUNCTIONS))


def test_strings_and_terms_are_interchangeable() -> None:
    a = sme.match([parse(s) for s in SOLAR], RUTHER, functions=FUNCTIONS, params=OLD)
    b = sme.match(SOLAR, [parse(s) for s in RUTHER], functions=FUNCTIONS, params=OLD)
    assert [m.score for m in a] == [m.score for m in b]


def test_benchmark_script_smoke() -> None:
    import importlib.util
    import pathlib
    import random

    path = pathlib.Path(__file__).resolve().parents[1] / "benchmarks" / "sme.py"
    spec = importlib.util.spec_from_file_location("bench_sme", path)
    mod = importlib.util.module_from_spec(spec)
    assert spec.loader is not None
    spec.loader.exec_module(mod)
    facts = mod.scene(5, random.Random(0))
    assert len(facts) == 5 * 2 + 5 * 4 * 2
    ms = sme.match(mod.GENERALIZATION, facts)
    assert ms and all(0.0 <= m.similarity <= 1.0 for m in ms)
    assert mod.time_match(facts, 1) > 0.0
