"""SME's behaviours one by one (issue 27): required correspondences, what aligns with what,
parallel connectivity, candidate inferences, the greedy merge and what a match reports.
Each test names the behaviour it holds (tools/mutation.py checks it against SME's mutants)."""

from __future__ import annotations

from aileen.analogy import sme
from aileen.terms import Term, parse, parse_many

T = Term


def ents(mappings: list[sme.Mapping]) -> list[dict[str, str]]:
    return [m.entities for m in mappings]


# ---------------------------------------------------------------- required correspondences
BASE = parse_many("q(a) w(a)")
TARGET = parse_many("q(o1) w(o1) q(o2)")


def test_without_a_requirement_the_best_mapping_wins() -> None:
    assert ents(sme.match(BASE, TARGET)) == [{"a": "o1"}]


def test_every_mapping_keeps_a_required_correspondence() -> None:
    for found in (sme.match(BASE, TARGET, require={T("a"): T("o2")}),
                  sme.analyze(BASE, TARGET, require={T("a"): T("o2")}).mappings):
        assert ents(found) == [{"a": "o2"}]
        assert [str(b) for b in found[0].pairs if b.args] == ["q(a)"]


def test_a_required_target_takes_no_other_base_item() -> None:
    # b -> o2 contradicts a -> o2 from the target's side only.
    found = sme.match(parse_many("r(b) q(a)"), parse_many("r(o2) q(o3)"), require={T("a"): T("o2")})
    assert all(m.entities.get("b") != "o2" for m in found)
    assert found == []  # q(a) cannot go to o2 either: nothing is left


def test_a_requirement_is_checked_past_incomplete_match_hypotheses() -> None:
    # s(a,g(c)) vs s(o9,h(o8)) is incomplete (g and h do not align) and comes first.
    base = parse_many("s(a,g(c)) r(a,b)")
    target = parse_many("s(o9,h(o8)) r(o1,o2)")
    assert ents(sme.match(base, target)) == [{"a": "o1", "b": "o2"}]
    assert sme.match(base, target, require={T("a"): T("o2")}) == []


# ---------------------------------------------------------------- what aligns
def test_an_entity_never_aligns_with_an_expression() -> None:
    assert sme.match(parse_many("p(a)"), parse_many("p(f(x))")) == []


def test_non_identical_functions_align_only_when_both_are_declared() -> None:
    base, target = parse_many("p(f(a))"), parse_many("p(g(b))")
    assert sme.match(base, target, functions=frozenset({"f"})) == []
    assert ents(sme.match(base, target, functions=frozenset({"f", "g"}))) == [{"a": "b"}]


def test_an_expression_over_an_incomplete_match_is_incomplete_too() -> None:
    assert sme.match(parse_many("p(q(a,f(x)))"), parse_many("p(q(o1,g(y)))")) == []


def test_a_bare_constant_among_the_facts_is_skipped_not_the_end() -> None:
    assert ents(sme.match(parse_many("sunny p(a)"), parse_many("p(o1)"))) == [{"a": "o1"}]
    assert sme.self_score(parse_many("sunny p(a)")) == sme.self_score(parse_many("p(a)")) > 0.0


# ---------------------------------------------------------------- candidate inferences
def test_an_inference_needs_a_mapped_entity_somewhere_below_it() -> None:
    [m] = sme.match(parse_many("a(x) p(q(y)) r(x,z)"), parse_many("a(o1)"))
    assert [str(f) for f in m.inferences] == ["r(o1,skolem(z))"]


def test_an_inference_comes_back_in_aileen_syntax_at_every_depth() -> None:
    [m] = sme.match(parse_many("isa(t0,start) h(t0,isa(o1,cv_red)) h(t0,p(o1))"), parse_many("isa(t5,start) h(t5,p(o7))"))
    assert [str(f) for f in m.inferences] == ["h(t5,isa(o7,cv_red))"]


def test_an_isa_with_a_compound_or_numeric_class_is_a_relation() -> None:
    # Not attributes: their class arguments are entities like any other (unmapped: skolems).
    [m] = sme.match(parse_many("p(a) isa(a,size(big)) isa(a,3)"), parse_many("p(o1)"))
    assert sorted(str(f) for f in m.inferences) == ["isa(o1,size(skolem(big)))", "isa(o1,skolem(3))"]
    [m] = sme.match(parse_many("isa(a,size(big))"), parse_many("isa(o1,size(big))"))
    assert m.entities == {"a": "o1", "big": "big"}


# ---------------------------------------------------------------- the greedy merge
def test_a_kernel_already_in_a_mapping_does_not_stop_the_next_seed() -> None:
    # Kernels, best first: p(a)->p(o1) and q(a)->q(o1) (one mapping), then p(a)->p(o2).
    found = sme.match(parse_many("p(a) q(a)"), parse_many("p(o1) q(o1) p(o2)"), params=sme.Params(cutoff=0.0))
    assert ents(found) == [{"a": "o1"}, {"a": "o2"}]


def test_a_cutoff_of_one_keeps_the_best_mapping_and_its_equals() -> None:
    found = sme.match(parse_many("p(a)"), parse_many("p(o1) p(o2)"), params=sme.Params(cutoff=1.0))
    assert ents(found) == [{"a": "o1"}, {"a": "o2"}]


def test_a_mapping_at_exactly_the_cutoff_is_kept() -> None:
    found = sme.match(parse_many("p(a) q(a)"), parse_many("p(o1) q(o1) p(o2)"), params=sme.Params(cutoff=0.5))
    assert ents(found) == [{"a": "o1"}, {"a": "o2"}]
    assert found[1].score * 2 == found[0].score


def test_a_kernel_under_an_inconsistent_expression_is_a_root_of_its_mapping() -> None:
    # p(q(a),r(a)) -> p(q(o1),r(o2)) maps a twice: not ok, so q's and r's MHs are roots.
    found = sme.match(parse_many("p(q(a),r(a))"), parse_many("p(q(o1),r(o2))"))
    assert [(m.entities, m.root_pairs) for m in found] == [
        ({"a": "o1"}, [(parse("q(a)"), parse("q(o1)"))]), ({"a": "o2"}, [(parse("r(a)"), parse("r(o2)"))])]


# ---------------------------------------------------------------- what a match reports
def test_a_match_reports_both_self_scores_and_its_match_hypotheses() -> None:
    base, target = parse_many("p(a) q(a)"), parse_many("p(o1)")
    r = sme.analyze(base, target)
    assert r.base_self_score == sme.self_score(base) and r.target_self_score == sme.self_score(target)
    assert (r.mh_count, r.kernel_count) == (3, 1)  # p(a)->p(o1), a->o1 and the functor pair p/p


def test_generalized_entities_count_as_entities_not_functor_pairs() -> None:
    [m] = sme.match([parse("p(gen_ent(0,c))")], [parse("p(o1)")])
    assert m.entities == {"gen_ent(0,c)": "o1"} and m.mh_count == 3


# ---------------------------------------------------------------- ranking kernels (SME v4's evidence)
ONE = sme.Params(max_mappings=1)


def test_a_kernel_whose_entity_three_facts_support_outranks_a_richer_looking_one() -> None:
    # a -> o1 takes evidence from p, q and u (3 x 8 x 0.0005): that kernel outranks w(a,c)'s,
    # although w's root comes first and has two entities of its own.
    base = parse_many("w(a,c) p(a) q(a) u(a)")
    target = parse_many("w(o2,o3) p(o1) q(o1) u(o1)")
    assert ents(sme.match(base, target, params=ONE)) == [{"a": "o1"}]


def test_a_kernel_whose_entity_two_facts_support_outranks_one_with_one() -> None:
    base = parse_many("w(a) p(a) q(a)")
    target = parse_many("w(o2) p(o1) q(o1)")
    assert ents(sme.match(base, target, params=ONE)) == [{"a": "o1"}]


def test_a_nested_expression_adds_its_own_score_to_its_parents_evidence() -> None:
    # s(t(a)) -> s(t(o2)): t's local score plus s's trickled down, then a's: more than p and q.
    base = parse_many("p(a) q(a) s(t(a))")
    target = parse_many("p(o1) q(o1) s(t(o2))")
    assert ents(sme.match(base, target, params=ONE)) == [{"a": "o2"}]
