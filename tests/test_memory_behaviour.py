"""The concept memory's behaviours one by one (issue 27): the order of answers, the top k
concepts, roles named by a ground question, near misses, projection's guards, SAGE's merge of
a third example, the thresholds. Each test names the behaviour it holds, and fails when that
behaviour is broken (tools/mutation.py checks it against the memory's mutants)."""

from __future__ import annotations

import random

import pytest

from aileen.analogy import sme
from aileen.analogy.sage import Generalization, GeneralizationContext, SageParams, gen_ent
from aileen.errors import UserError
from aileen.memory.concept import ConceptMemory, Projection, time_chain
from aileen.terms import Term, parse, parse_many


def facts_of(infs) -> list[tuple[str, float]]:  # noqa: ANN001
    return [(str(i.fact), round(i.similarity, 3)) for i in infs]


def visual(params: SageParams, **concepts: str) -> ConceptMemory:
    """A memory with one example per visual concept: `r_x="cv_red cv_box"` stores
    `isa(a,cv_red) isa(a,cv_box) isa(a,r_x)`, in the order given."""
    m = ConceptMemory(params)
    for name, percepts in concepts.items():
        m.create(name, "visual")
        m.store([f"isa(a,{p})" for p in percepts.split()] + [f"isa(a,{name})"], name)
    return m


# ---------------------------------------------------------------- query
def test_query_answers_best_first() -> None:
    # Every object is a mapping of its own (no cutoff): the more percepts it shares, the better.
    m = visual(SageParams(match=0.3, sme=sme.Params(cutoff=0.0)), r_thing="cv_red cv_box cv_large")
    scene = parse_many("isa(o2,cv_red) isa(o1,cv_red) isa(o1,cv_box) isa(o3,cv_red) isa(o3,cv_box) isa(o3,cv_large)")
    assert facts_of(m.query(scene, "isa(X,r_thing)")) == [
        ("isa(o3,r_thing)", 1.0), ("isa(o1,r_thing)", 0.667), ("isa(o2,r_thing)", 0.333)]


def test_query_breaks_ties_by_the_facts_text() -> None:
    m = visual(SageParams(match=0.3), r_thing="cv_red cv_box cv_large")
    scene = parse_many("isa(o2,cv_red) isa(o2,cv_box) isa(o1,cv_red) isa(o1,cv_box)")
    assert facts_of(m.query(scene, "isa(X,r_thing)")) == [("isa(o1,r_thing)", 0.667), ("isa(o2,r_thing)", 0.667)]


def test_query_accepts_a_match_exactly_at_the_threshold() -> None:
    # The example has two facts besides its membership; the scene shares one: exactly 0.5.
    at = visual(SageParams(match=0.5), r_thing="cv_red cv_box")
    scene = parse_many("isa(o4,cv_red) isa(o4,cv_sphere)")
    [inf] = at.query(scene, "isa(O,r_thing)")
    assert inf.similarity == pytest.approx(0.5)
    assert at.query(scene, "isa(O,r_thing)", exhaustive=True) == [inf]
    above = visual(SageParams(match=0.5 + 1e-9), r_thing="cv_red cv_box")
    assert above.query(scene, "isa(O,r_thing)") == [] == above.query(scene, "isa(O,r_thing)", exhaustive=True)


def test_query_keeps_each_fact_once_with_its_best_support() -> None:
    # Two kept examples (nothing merges at assimilation 1.0) both infer isa(o1,r_thing).
    m = ConceptMemory(SageParams(assimilation=1.0, match=0.3))
    m.create("r_thing", "visual")
    m.store(parse_many("isa(a,cv_red) isa(a,cv_blue) isa(a,r_thing)"), "r_thing")
    m.store(parse_many("isa(b,cv_red) isa(b,cv_box) isa(b,r_thing)"), "r_thing")
    [inf] = m.query(parse_many("isa(o1,cv_red) isa(o1,cv_box)"), "isa(X,r_thing)")
    assert (inf.similarity, inf.source, inf.index) == (1.0, "example", 1)
    assert inf.binding == {Term("X"): Term("o1")} and inf.concept == "r_thing"


def test_a_description_made_only_of_the_concepts_own_facts_supports_nothing() -> None:
    # Nothing but r_x facts describes r_x: a match has no evidence beyond the answer itself,
    # so its similarity is 0, not 1 (the denominator leaves out the facts the query asks about).
    m = ConceptMemory(SageParams(match=0.1))
    m.create("r_x", "spatial")
    m.store(parse_many("r_x(a,b) r_x(b,c) r_x(a,c)"), "r_x")
    scene = parse_many("r_x(o1,o2) r_x(o2,o3)")
    [mapping] = sme.match(m.descriptions("r_x")[0], scene)[:1]
    assert parse("r_x(o1,o3)") in mapping.inferences  # SME does infer it
    assert m.query(scene, "r_x(X,Y)") == []
    assert m.query(scene, "r_x(X,Y)", exhaustive=True) == []


def test_an_inference_about_an_unknown_entity_is_no_answer() -> None:
    m = visual(SageParams(match=0.1), r_thing="cv_red")
    m.create("r_pair", "spatial")
    m.store(parse_many("w(a,b) isa(a,cv_red) r_pair(a,b)"), "r_pair")
    # b has no correspondent in the scene: r_pair(o1, skolem(b)) is inferred, never answered.
    assert m.query(parse_many("isa(o1,cv_red)"), "r_pair(X,Y)", exhaustive=True) == []


# ---------------------------------------------------------------- ground questions name the roles
#: `r_on(a,b)`: a is on b; the colours and sizes say more than st_on, so SME's best mapping
#: overall puts the roles the other way round on a scene where the blue small one is on top.
ON = ["st_on(a,b)", "isa(a,cv_red)", "isa(b,cv_blue)", "isa(a,cv_large)", "isa(b,cv_small)"]
ON_SCENE = parse_many("isa(o1,cv_red) isa(o2,cv_blue) isa(o1,cv_large) isa(o2,cv_small) st_on(o2,o1)")


@pytest.fixture
def on() -> ConceptMemory:
    m = ConceptMemory(SageParams(match=0.3))
    m.create("r_on", "spatial")
    m.store(ON + ["r_on(a,b)"], "r_on")
    m.create("r_under", "visual")
    m.store(ON + ["isa(b,r_under)"], "r_under")
    return m


def test_a_ground_relation_question_aligns_the_concepts_roles_with_the_named_objects(on: ConceptMemory) -> None:
    best = sme.match(on.descriptions("r_on")[0], ON_SCENE)
    assert [mp.entities["a"] for mp in best] == ["o1"]  # the only mapping SME gives: roles swapped
    assert facts_of(on.query(ON_SCENE, "r_on(o2,o1)")) == [("r_on(o2,o1)", 0.321)]
    assert facts_of(on.query(ON_SCENE, "r_on(o2,o1)", exhaustive=True)) == [("r_on(o2,o1)", 0.321)]


def test_a_free_relation_question_takes_the_best_mapping_overall(on: ConceptMemory) -> None:
    assert facts_of(on.query(ON_SCENE, "r_on(X,Y)")) == [("r_on(o1,o2)", 0.679)]


def test_a_ground_membership_question_aligns_the_concepts_object_with_the_named_one(on: ConceptMemory) -> None:
    assert facts_of(on.query(ON_SCENE, "isa(o1,r_under)")) == [("isa(o1,r_under)", 0.321)]
    assert facts_of(on.query(ON_SCENE, "isa(X,r_under)")) == [("isa(o2,r_under)", 0.679)]


def test_a_store_changes_the_answer_to_a_question_asked_before() -> None:
    # query's answers are kept per concept until its next store (`Recognition._answers`)
    m = visual(SageParams(match=0.6), r_grox="cv_green cv_box cv_large")
    small_cylinder = parse_many("isa(o5,cv_green) isa(o5,cv_cylinder) isa(o5,cv_small)")
    assert m.query(small_cylinder, "isa(X,r_grox)") == []
    m.store(parse_many("isa(a,cv_green) isa(a,cv_cylinder) isa(a,cv_small) isa(a,r_grox)"), "r_grox")
    assert facts_of(m.query(small_cylinder, "isa(X,r_grox)")) == [("isa(o5,r_grox)", 1.0)]


def test_a_kept_answer_is_the_one_a_fresh_memory_gives() -> None:
    # the same questions, asked between stores of random examples, of the memory that keeps its
    # answers and of a copy rebuilt from its file (which has kept none)
    rng = random.Random(7)
    percepts = ["cv_red", "cv_blue", "cv_green", "cv_box", "cv_cone", "cv_sphere", "cv_small", "cv_large"]
    m = ConceptMemory(SageParams(match=0.5))
    for name in ("r_a", "r_b"):
        m.create(name, "visual")
    scenes = [parse_many(" ".join(f"isa(o{i},{p})" for i in (1, 2) for p in rng.sample(percepts, 3)))
              for _ in range(6)]
    for step in range(8):
        name = ("r_a", "r_b")[step % 2]
        m.store(parse_many(" ".join(f"isa(a,{p})" for p in rng.sample(percepts, 3)) + f" isa(a,{name})"), name)
        if step % 3 == 2:
            m.store_near_miss(parse_many(" ".join(f"isa(a,{p})" for p in rng.sample(percepts, 3))), name)
        fresh = ConceptMemory.from_dict(m.to_dict())
        for scene in scenes:
            for name2 in ("r_a", "r_b"):
                for ignore in ((), (Term("cv_red"),)):
                    kept = m.query(scene, f"isa(X,{name2})", ignore=ignore)
                    assert facts_of(kept) == facts_of(m.query(scene, f"isa(X,{name2})", ignore=ignore))
                    assert facts_of(kept) == facts_of(fresh.query(scene, f"isa(X,{name2})", ignore=ignore))


# ---------------------------------------------------------------- near misses
@pytest.fixture
def grox() -> ConceptMemory:
    """grox, taught on one large green box, at a threshold (0.6) that a large blue box passes."""
    return visual(SageParams(match=0.6), r_grox="cv_green cv_box cv_large")


BLUE = parse_many("isa(o5,cv_blue) isa(o5,cv_box) isa(o5,cv_large)")


def test_a_near_miss_rejects_a_match_that_lacks_what_it_showed_is_needed(grox: ConceptMemory) -> None:
    assert facts_of(grox.query(BLUE, "isa(X,r_grox)")) == [("isa(o5,r_grox)", 0.667)]
    assert grox.store_near_miss(parse_many("isa(o1,cv_blue) isa(o1,cv_box) isa(o1,cv_large)"), "r_grox") == 1
    assert grox.query(BLUE, "isa(X,r_grox)") == []
    assert grox.query(BLUE, "isa(X,r_grox)", exhaustive=True) == []


def test_a_near_miss_keeps_the_matches_that_keep_what_it_showed_is_needed(grox: ConceptMemory) -> None:
    grox.store_near_miss(parse_many("isa(o1,cv_blue) isa(o1,cv_box) isa(o1,cv_large)"), "r_grox")
    green_small = parse_many("isa(o5,cv_green) isa(o5,cv_box) isa(o5,cv_small)")
    assert facts_of(grox.query(green_small, "isa(X,r_grox)")) == [("isa(o5,r_grox)", 0.667)]
    both = BLUE + parse_many("isa(o6,cv_green) isa(o6,cv_box)")
    assert facts_of(grox.query(both, "isa(X,r_grox)")) == [("isa(o6,r_grox)", 0.667)]


def test_mutual_exclusivity_never_strips_what_a_near_miss_showed_is_needed(grox: ConceptMemory) -> None:
    # Ignoring cv_green (another word's) would let the blue box match on box and large alone.
    assert facts_of(grox.query(BLUE, "isa(X,r_grox)", ignore=[Term("cv_green")])) == [("isa(o5,r_grox)", 1.0)]
    grox.store_near_miss(parse_many("isa(o1,cv_blue) isa(o1,cv_box) isa(o1,cv_large)"), "r_grox")
    assert grox.query(BLUE, "isa(X,r_grox)", ignore=[Term("cv_green")]) == []


def test_an_empty_near_miss_is_refused(grox: ConceptMemory) -> None:
    with pytest.raises(UserError, match="empty near miss"):
        grox.store_near_miss([], "r_grox")


# ---------------------------------------------------------------- mutual exclusivity at query time
def test_ignore_leaves_out_another_words_classes_and_relations() -> None:
    m = visual(SageParams(), r_grox="cv_green cv_box")
    box = parse_many("isa(o1,cv_red) isa(o1,cv_box)")
    assert m.query(box, "isa(X,r_grox)") == []
    assert facts_of(m.query(box, "isa(X,r_grox)", ignore=[Term("cv_green")])) == [("isa(o1,r_grox)", 1.0)]
    m.create("r_near", "spatial")
    m.store(parse_many("w(a,b) dc(a,b) r_near(a,b)"), "r_near")
    pair = parse_many("e(o1,o2) dc(o1,o2)")
    assert m.query(pair, "r_near(X,Y)") == []
    assert facts_of(m.query(pair, "r_near(X,Y)", ignore_relations=["w"])) == [("r_near(o1,o2)", 1.0)]
    # Only binary facts are relations: ignoring a unary predicate's name leaves it in.
    m.create("r_up", "visual")
    m.store(parse_many("held(a) isa(a,cv_red) isa(a,r_up)"), "r_up")
    assert m.query(parse_many("isa(o1,cv_red)"), "isa(X,r_up)", ignore_relations=["held"]) == []


# ---------------------------------------------------------------- fitting
@pytest.fixture
def five() -> ConceptMemory:
    """Five concepts, created in an order that is not their similarity to a large red box:
    r_d 1/3, r_half 1/2, r_full 1, r_b2 2/3 and r_tie 2/3 (a tie with r_b2, created after it)."""
    return visual(SageParams(match=0.3), r_d="cv_red cv_blue cv_cone", r_half="cv_red cv_blue",
                  r_full="cv_red cv_box cv_large", r_b2="cv_red cv_box cv_cone", r_tie="cv_red cv_box cv_sphere")


PROBE = parse_many("isa(o1,cv_red) isa(o1,cv_box) isa(o1,cv_large)")


@pytest.mark.parametrize("exhaustive", [False, True])
def test_fitting_ranks_concepts_best_first(five: ConceptMemory, exhaustive: bool) -> None:
    assert facts_of(five.fitting(PROBE, k=5, exhaustive=exhaustive)) == [
        ("isa(o1,r_full)", 1.0), ("isa(o1,r_b2)", 0.667), ("isa(o1,r_tie)", 0.667),
        ("isa(o1,r_half)", 0.5), ("isa(o1,r_d)", 0.333)]


@pytest.mark.parametrize("exhaustive", [False, True])
def test_fitting_keeps_the_k_best_concepts(five: ConceptMemory, exhaustive: bool) -> None:
    assert facts_of(five.fitting(PROBE, k=2, exhaustive=exhaustive)) == [
        ("isa(o1,r_full)", 1.0), ("isa(o1,r_b2)", 0.667)]
    assert facts_of(five.fitting(PROBE, k=1, exhaustive=exhaustive)) == [("isa(o1,r_full)", 1.0)]


def test_fitting_only_asks_concepts_of_the_kind_given(five: ConceptMemory) -> None:
    five.create("r_on", "spatial")
    five.store(parse_many("isa(a,cv_red) isa(a,cv_box) st_on(a,b) r_on(a,b)"), "r_on")
    assert five.fitting(PROBE, kind="spatial") == five.fitting(PROBE, kind="spatial", exhaustive=True) == []
    assert [str(i.fact) for i in five.fitting(PROBE, kind="visual", k=1)] == ["isa(o1,r_full)"]
    with pytest.raises(UserError, match="kind"):
        five.fitting(PROBE, kind="smell")


def test_fitting_leaves_out_what_ignore_names_for_each_concept(five: ConceptMemory) -> None:
    # With cv_blue another word's, r_half is red alone (1.0), and r_d red and cone (1/2).
    got = five.fitting(PROBE, k=5, ignore=lambda c: [Term("cv_blue")] if c in ("r_half", "r_d") else [])
    assert facts_of(got) == [("isa(o1,r_half)", 1.0), ("isa(o1,r_full)", 1.0), ("isa(o1,r_b2)", 0.667),
                             ("isa(o1,r_tie)", 0.667), ("isa(o1,r_d)", 0.5)]


def test_a_concept_without_its_own_fact_fits_nothing() -> None:
    m = ConceptMemory(SageParams(match=0.1))
    m.create("r_odd", "visual")
    m.store(parse_many("isa(a,cv_red) isa(a,cv_box)"), "r_odd")
    assert m.fitting(PROBE) == [] == m.fitting(PROBE, exhaustive=True)


def test_fitting_finds_a_relation_concept_by_its_own_predicate() -> None:
    m = ConceptMemory()
    m.create("r_on", "spatial")
    m.store(parse_many("st_on(a,b) isa(a,cv_red) r_on(a,b)"), "r_on")
    [inf] = m.fitting(parse_many("st_on(o1,o2) isa(o1,cv_red)"))
    assert str(inf.fact) == "r_on(o1,o2)" and inf.binding == {Term("X0"): Term("o1"), Term("X1"): Term("o2")}


# ---------------------------------------------------------------- project
RIGHT = ("isa(t0,start) h(t0,w(o1,o2)) h(t0,dc(o1,o2)) after(t1,t0) h(t1,held(o1)) h(t1,dc(o1,o2)) "
         "after(t2,t1) h(t2,e(o1,o2)) h(t2,dc(o1,o2)) r_move_right_of(o1,o2)")


@pytest.fixture
def right() -> ConceptMemory:
    m = ConceptMemory()
    m.create("r_move_right_of", "action")
    m.store(parse_many(RIGHT), "r_move_right_of")
    return m


def test_project_keeps_the_named_roles_when_the_start_looks_like_the_end_with_them_swapped(
        right: ConceptMemory) -> None:
    # Move o5 right of o6, where o6 already stands right of o5: the start looks like the
    # action's end state with o6 as the mover; the trace names o5 as the mover.
    trace = parse_many("isa(t0,start) h(t0,e(o6,o5)) h(t0,dc(o6,o5)) r_move_right_of(o5,o6)")
    p = right.project(trace, "r_move_right_of")
    assert {str(f) for f in p.facts} == {"held(o5)", "dc(o5,o6)"}
    assert not p.complete and p.after == Term("t0") and p.source == "example" and p.index == 0


def test_project_starts_the_action_at_the_traces_start() -> None:
    # Three later states of the action each share more with the trace's start than the
    # action's own start does; the next state is still the action's second.
    m = ConceptMemory()
    m.create("r_act", "action")
    m.store(parse_many(
        "isa(t0,start) h(t0,p(o1)) after(t1,t0) h(t1,q(o1)) h(t1,r(o1)) h(t1,s(o1)) "
        "after(t2,t1) h(t2,q(o1)) h(t2,r(o1)) h(t2,s(o1)) h(t2,u(o1)) "
        "after(t3,t2) h(t3,q(o1)) h(t3,r(o1)) h(t3,s(o1)) h(t3,v(o1)) r_act(o1)"), "r_act")
    p = m.project(parse_many("isa(t0,start) h(t0,p(o5)) h(t0,q(o5)) h(t0,r(o5)) h(t0,s(o5)) r_act(o5)"), "r_act")
    assert {str(f) for f in p.facts} == {"q(o5)", "r(o5)", "s(o5)"}
    assert p.time_point == parse("skolem(t1)") and not p.complete


def test_project_with_nothing_matched_is_not_complete(right: ConceptMemory) -> None:
    for trace in ("h(t0,zz(o5,o6))", "zz(o5)", "r_move_right_of(o5,o6)"):
        p = right.project(parse_many(trace), "r_move_right_of")
        assert p == Projection(facts=[], complete=False, similarity=0.0, after=p.after), trace
        assert p.mapping is None and p.time_point is None
    assert right.project(parse_many("h(t0,zz(o5,o6))"), "r_move_right_of").after == Term("t0")


def test_project_reports_facts_about_unknown_entities_apart(right: ConceptMemory) -> None:
    # The trace shows one object only: the next state's fact about the action's second object
    # has no object to be about yet, and stays unresolved.
    p = right.project(parse_many("isa(t0,start) h(t0,held(o5))"), "r_move_right_of")
    assert [str(f) for f in p.facts] == ["held(o5)"]
    assert [str(f) for f in p.unresolved] == ["dc(o5,skolem(o2))"]


def test_project_at_the_actions_last_state_is_complete_with_nothing_to_do(right: ConceptMemory) -> None:
    trace = parse_many("isa(t0,start) h(t0,w(o5,o6)) h(t0,dc(o5,o6)) after(t1,t0) h(t1,held(o5)) "
                       "h(t1,dc(o5,o6)) after(t2,t1) h(t2,e(o5,o6)) h(t2,dc(o5,o6)) r_move_right_of(o5,o6)")
    p = right.project(trace, "r_move_right_of")
    assert p.facts == [] and p.complete and p.after == Term("t2") and p.time_point is None


def test_project_in_the_middle_of_the_action_is_not_complete() -> None:
    m = ConceptMemory()
    m.create("r_act", "action")
    m.store(parse_many("isa(t0,start) h(t0,p(o1)) after(t1,t0) h(t1,q(o1)) after(t2,t1) h(t2,r(o1)) "
                       "after(t3,t2) h(t3,s(o1)) r_act(o1)"), "r_act")
    p = m.project(parse_many("isa(t0,start) h(t0,p(o5)) after(t1,t0) h(t1,q(o5)) r_act(o5)"), "r_act")
    assert [str(f) for f in p.facts] == ["r(o5)"] and not p.complete
    p = m.project(parse_many("isa(t0,start) h(t0,p(o5)) after(t1,t0) h(t1,q(o5)) after(t2,t1) h(t2,r(o5)) "
                             "r_act(o5)"), "r_act")
    assert [str(f) for f in p.facts] == ["s(o5)"] and p.complete


def test_time_chain_follows_after_links_from_the_start() -> None:
    assert time_chain(parse_many("after(t2,t1) isa(t0,start) after(t1,t0) h(t3,p(a))")) == [
        Term("t0"), Term("t1"), Term("t2")]
    # Without a start, the first time point that follows none; a loop ends the chain.
    assert time_chain(parse_many("h(t5,p(a)) after(t6,t5) after(t5,t6)")) == []
    assert time_chain(parse_many("after(t6,t5) after(t7,t6) after(t6,t7)")) == [Term("t5"), Term("t6"), Term("t7")]
    assert time_chain(parse_many("isa(t0,start(x)) h(t1,p(a))")) == [Term("t1")]


# ---------------------------------------------------------------- store and SAGE
def test_store_reports_what_happened_to_the_example() -> None:
    m = ConceptMemory()
    m.create("r_red", "visual")
    first = m.store(parse_many("isa(o2,cv_red) isa(o2,cv_cylinder) isa(o2,r_red)"), "r_red")
    assert (first.action, first.similarity) == ("kept", 0.0)
    second = m.store(parse_many("isa(o3,cv_red) isa(o3,cv_cube) isa(o3,r_red)"), "r_red")
    assert second.action == "new_generalization" and 0.5 < second.similarity < 1.0
    third = m.store(parse_many("isa(o4,cv_red) isa(o4,cv_cube) isa(o4,r_red)"), "r_red")
    assert (third.generalizations, third.examples, third.action) == (1, 0, "merged")
    # SME's similarity: the generalization's two significant facts against the example's three.
    assert third.similarity == pytest.approx(0.8)


def test_store_may_be_refused_a_merge() -> None:
    m = ConceptMemory()
    m.create("r_red", "visual")
    m.store(parse_many("isa(o2,cv_red) isa(o2,r_red)"), "r_red")
    r = m.store(parse_many("isa(o3,cv_red) isa(o3,r_red)"), "r_red", accept=lambda g: False)
    assert (r.generalizations, r.examples, r.action) == (0, 2, "kept") and r.similarity == pytest.approx(1.0)
    assert m.examples("r_red") == [["isa(o2,cv_red)", "isa(o2,r_red)"], ["isa(o3,cv_red)", "isa(o3,r_red)"]]


def test_add_result_names_the_kept_examples_index_and_the_best_similarity() -> None:
    ctx = GeneralizationContext("r_x")
    strict = SageParams(assimilation=0.99)
    r0 = ctx.add(parse_many("isa(a,cv_red) isa(a,cv_box)"), strict)
    assert (r0.action, r0.index, r0.similarity) == ("kept", 0, 0.0)
    r1 = ctx.add(parse_many("isa(b,cv_red) isa(b,cv_cone)"), strict)
    assert (r1.action, r1.index) == ("kept", 1) and 0.0 < r1.similarity < 0.99
    r2 = ctx.add(parse_many("isa(c,cv_blue)"), strict)  # shares nothing: no match at all
    assert (r2.action, r2.index, r2.similarity) == ("kept", 2, 0.0)
    r3 = ctx.add(parse_many("isa(d,cv_red) isa(d,cv_box)"), strict)
    assert (r3.action, r3.index, r3.similarity) == ("new_generalization", 0, 1.0)
    assert len(ctx.examples) == 2  # the example it merged with left the examples
    r4 = ctx.add(parse_many("isa(e,cv_red) isa(e,cv_box)"), strict)
    assert (r4.action, r4.index, r4.similarity) == ("merged", 0, 1.0)


def test_add_merges_into_the_most_similar_description() -> None:
    ctx = GeneralizationContext("r_x")
    strict = SageParams(assimilation=0.5)
    ctx.add(parse_many("isa(a,cv_red) isa(a,cv_box) isa(a,cv_large)"), strict)
    ctx.add(parse_many("isa(b,cv_blue) isa(b,cv_cone) isa(b,cv_small)"), strict)
    r = ctx.add(parse_many("isa(c,cv_blue) isa(c,cv_cone) isa(c,cv_large)"), strict)
    assert (r.action, r.index) == ("new_generalization", 0) and r.similarity == pytest.approx(2 / 3)
    assert [str(f) for f in ctx.examples[0]] == ["isa(a,cv_red)", "isa(a,cv_box)", "isa(a,cv_large)"]


def test_probabilities_list_the_most_probable_first_then_by_text() -> None:
    g = Generalization("k", {parse("p(b)"): 1, parse("p(a)"): 1, parse("q(a)"): 3, parse("r(a)"): 2}, 3)
    assert [(str(f), p) for f, p in g.probabilities().items()] == [
        ("q(a)", 1.0), ("r(a)", pytest.approx(2 / 3)), ("p(a)", pytest.approx(1 / 3)), ("p(b)", pytest.approx(1 / 3))]


def test_a_fact_exactly_at_the_probability_threshold_counts() -> None:
    g = Generalization("k", {parse("p(a)"): 3, parse("q(a)"): 2, parse("r(a)"): 5}, 5)
    assert [str(f) for f in g.significant(0.6)] == ["r(a)", "p(a)"]
    assert [str(f) for f in g.significant(0.4)] == ["r(a)", "p(a)", "q(a)"]
    assert g.probability(parse("s(a)")) == 0.0
    assert Generalization("k", {}, 0).probability(parse("p(a)")) == 0.0


def test_merging_a_third_example_generalizes_a_shared_concrete_entity_it_aligns_with_another() -> None:
    # The first two examples share the start t0 and the object o1 by name, so the
    # generalization keeps them concrete; the third aligns o9 with o1: o1 must be generalized
    # in the facts already there and in the new example's facts alike.
    ctx = GeneralizationContext("r_move")
    params = SageParams()
    ctx.add(parse_many("isa(t0,start) h(t0,dc(o1,o2)) after(t1,t0) h(t1,held(o1))"), params)
    ctx.add(parse_many("isa(t0,start) h(t0,dc(o1,o3)) after(t1,t0) h(t1,held(o1))"), params)
    [g] = ctx.generalizations
    assert any(Term("o1") in set(f) for f in g.counts)
    r = ctx.add(parse_many("isa(t0,start) h(t0,dc(o9,o8)) after(t1,t0) h(t1,held(o9))"), params)
    assert r.action == "merged"
    [g] = ctx.generalizations
    assert g.size == 3
    assert not any(Term(o) in set(f) for f in g.counts for o in ("o1", "o9", "o8"))
    # Every fact held in all three examples: nothing was split between an old and a new name.
    assert sorted(g.probabilities().values()) == [1.0] * 4
    held = [f for f in g.counts if f.name == "h" and f.args[1].name == "held"]
    assert len(held) == 1 and held[0].args[1].args[0].name == "gen_ent"


def test_merging_keeps_a_shared_concrete_entity_aligned_with_itself() -> None:
    ctx = GeneralizationContext("r_move")
    params = SageParams()
    for o in ("o2", "o3", "o4"):
        ctx.add(parse_many(f"isa(t0,start) h(t0,dc(o1,{o})) after(t1,t0) h(t1,held(o1))"), params)
    [g] = ctx.generalizations
    assert g.size == 3 and parse("h(t1,held(o1))") in g.counts and g.counts[parse("h(t1,held(o1))")] == 3


def test_merged_generalized_entities_never_collide_with_those_a_generalization_has() -> None:
    g = Generalization("c", {parse("p(gen_ent(0,c))"): 1, parse("q(gen_ent(1,c))"): 1}, 1)
    g.merge(parse_many("p(x) r(y)"), {Term("x"): gen_ent(0, "c")})
    assert g.counts[parse("p(gen_ent(0,c))")] == 2 and g.size == 2
    [r] = [f for f in g.counts if f.name == "r"]
    assert r.args[0] not in (gen_ent(0, "c"), gen_ent(1, "c")) and r.args[0].name == "gen_ent"


# ---------------------------------------------------------------- more of query
def test_query_asks_the_concept_given_whatever_the_pattern_names() -> None:
    # r_scarlet's examples name their object r_red: asked of r_scarlet, the pattern isa(X,r_red)
    # finds them; the pattern alone names r_red, which the memory does not know.
    m = ConceptMemory()
    m.create("r_scarlet", "visual")
    m.store(parse_many("isa(a,cv_red) isa(a,r_red)"), "r_scarlet")
    scene = parse_many("isa(o4,cv_red) isa(o4,cv_box)")
    assert m.query(scene, "isa(X,r_red)") == []
    assert facts_of(m.query(scene, "isa(X,r_red)", concept="r_scarlet")) == [("isa(o4,r_red)", 1.0)]


def test_query_reads_facts_given_as_text() -> None:
    m = visual(SageParams(), r_red="cv_red")
    assert facts_of(m.query(["isa(o4,cv_red)", "isa(o4,cv_box)"], "isa(O,r_red)")) == [("isa(o4,r_red)", 1.0)]


def test_a_ground_question_about_a_concept_its_examples_never_name_answers_nothing() -> None:
    m = ConceptMemory()
    m.create("r_odd", "visual")
    m.store(parse_many("isa(a,cv_red) isa(a,cv_box)"), "r_odd")
    assert m.query(parse_many("isa(o1,cv_red) isa(o1,cv_box)"), "isa(o1,r_odd)") == []


def test_query_looks_past_an_inference_about_an_unknown_entity() -> None:
    # The example's first fact infers p(o1, skolem(b)), no answer; its membership comes after.
    m = ConceptMemory(SageParams(match=0.1))
    m.create("r_t", "visual")
    m.store(parse_many("p(a,b) isa(a,cv_red) isa(a,r_t)"), "r_t")
    [mapping] = sme.match(m.descriptions("r_t")[0], parse_many("isa(o1,cv_red)"))
    assert [str(f) for f in mapping.inferences] == ["p(o1,skolem(b))", "isa(o1,r_t)"]
    assert [str(i.fact) for i in m.query(parse_many("isa(o1,cv_red)"), "isa(X,r_t)")] == ["isa(o1,r_t)"]


def test_query_looks_past_a_mapping_whose_inferences_do_not_fit_the_pattern() -> None:
    # The best mapping pairs a with o2 (red, large) and b with o1 (blue, small): r_x(o2,o1),
    # not about o3; a weaker one pairs b with o3 (blue).
    m = ConceptMemory(SageParams(match=0.3, sme=sme.Params(cutoff=0.0)))
    m.create("r_x", "spatial")
    m.store(parse_many("isa(a,cv_red) isa(a,cv_large) isa(b,cv_blue) isa(b,cv_small) r_x(a,b)"), "r_x")
    scene = parse_many("isa(o1,cv_blue) isa(o1,cv_small) isa(o2,cv_red) isa(o2,cv_large) isa(o3,cv_blue)")
    best = sme.match(m.descriptions("r_x")[0], scene, params=m.params.sme)[0]
    assert best.entities == {"a": "o2", "b": "o1"}
    assert facts_of(m.query(scene, "r_x(X,o3)")) == [("r_x(o2,o3)", 0.75)]


def test_a_near_miss_lets_a_weaker_mapping_that_keeps_what_is_needed_answer() -> None:
    # o5 (blue, box, large) is the best mapping but lacks green; o6 (green) is weaker and has it.
    m = visual(SageParams(match=0.3, sme=sme.Params(cutoff=0.0)), r_grox="cv_green cv_box cv_large")
    m.store_near_miss(parse_many("isa(o1,cv_blue) isa(o1,cv_box) isa(o1,cv_large)"), "r_grox")
    scene = BLUE + parse_many("isa(o6,cv_green)")
    assert facts_of(m.query(scene, "isa(X,r_grox)")) == [("isa(o6,r_grox)", 0.333)]


def test_a_similarity_is_at_most_one_even_when_the_scene_holds_the_concept_already() -> None:
    # o1 is already known as r_x: that mapped fact is not in the denominator, the rest is.
    m = ConceptMemory()
    m.create("r_x", "visual")
    m.store(parse_many("isa(a,cv_red) isa(a,r_x) w(a,b) isa(b,r_x)"), "r_x")
    [inf] = m.query(parse_many("isa(o1,cv_red) isa(o1,r_x) w(o1,o2)"), "isa(X,r_x)")
    assert str(inf.fact) == "isa(o2,r_x)" and inf.similarity == 1.0


def test_query_on_a_tie_keeps_the_first_descriptions_support() -> None:
    m = ConceptMemory()
    m.create("r_red", "visual")
    for _ in range(2):
        m.store(parse_many("isa(a,cv_red) isa(a,r_red)"), "r_red", accept=lambda g: False)
    [inf] = m.query(parse_many("isa(o1,cv_red)"), "isa(X,r_red)")
    assert (inf.source, inf.index, inf.similarity) == ("example", 0, 1.0)


def test_an_empty_description_does_not_hide_the_next_one() -> None:
    # The first kept example is all cv_green, which the query leaves out (another word's).
    m = ConceptMemory()
    m.create("r_t", "visual")
    m.store(parse_many("isa(a,cv_green)"), "r_t")
    m.store(parse_many("isa(b,cv_red) isa(b,r_t)"), "r_t")
    assert len(m.examples("r_t")) == 2
    scene = parse_many("isa(o1,cv_red)")
    for exhaustive in (False, True):
        got = m.query(scene, "isa(X,r_t)", ignore=[Term("cv_green")], exhaustive=exhaustive)
        assert facts_of(got) == [("isa(o1,r_t)", 1.0)], exhaustive


def test_a_description_that_cannot_reach_the_threshold_does_not_hide_the_next_one() -> None:
    m = ConceptMemory(SageParams(assimilation=1.0))
    m.create("r_t", "visual")
    m.store(parse_many("isa(a,cv_blue) isa(a,cv_cone) isa(a,r_t)"), "r_t")
    m.store(parse_many("isa(b,cv_red) isa(b,r_t)"), "r_t")
    assert facts_of(m.query(parse_many("isa(o1,cv_red)"), "isa(X,r_t)")) == [("isa(o1,r_t)", 1.0)]


def test_the_prefilter_leaves_out_the_facts_the_question_asks_about() -> None:
    # Two r_x facts weigh more than the two colours that are the whole evidence: counting
    # them in the bound's denominator would drop a perfect match.
    m = ConceptMemory()
    m.create("r_x", "spatial")
    m.store(parse_many("isa(a,cv_red) isa(b,cv_blue) r_x(a,b) r_x(b,a)"), "r_x")
    scene = parse_many("isa(o1,cv_red) isa(o2,cv_blue)")
    assert facts_of(m.query(scene, "r_x(X,Y)")) == [("r_x(o1,o2)", 1.0), ("r_x(o2,o1)", 1.0)]


def test_the_prefilter_follows_a_store() -> None:
    # Significant facts {red, box} at first (the query's answer 0.5, dropped); after two red
    # cones box holds in half the examples only, the significant facts are {red}: 1.0.
    m = ConceptMemory()
    m.create("r_red", "visual")
    for shape in ("cv_box", "cv_box"):
        m.store(parse_many(f"isa(a,cv_red) isa(a,{shape}) isa(a,r_red)"), "r_red")
    sphere = parse_many("isa(o1,cv_red) isa(o1,cv_sphere)")
    assert m.query(sphere, "isa(X,r_red)") == []
    for shape in ("cv_cone", "cv_cone"):
        m.store(parse_many(f"isa(a,cv_red) isa(a,{shape}) isa(a,r_red)"), "r_red")
    assert facts_of(m.query(sphere, "isa(X,r_red)")) == [("isa(o1,r_red)", 1.0)]


def test_the_prefilter_bound_is_not_used_with_the_papers_normalisation() -> None:
    # One red of four percepts: the paper's similarity 2*1/(4+1) counts = 0.4, above 0.35,
    # while the significant bound (1 of 3) is not: the bound must not prune here.
    m = visual(SageParams(match=0.35, normalisation="paper"), r_thing="cv_red cv_box cv_large")
    [inf] = m.query(parse_many("isa(o1,cv_red)"), "isa(X,r_thing)")
    assert inf.similarity == pytest.approx(0.4)


def test_query_and_its_prefilter_use_the_sme_parameters_given() -> None:
    # The older SME preset (same functor 0.005, trickle-down 16) weighs relations and
    # attributes otherwise than the default.
    params = SageParams(match=0.3, sme=sme.Params(same_functor=0.005, same_function=0.002, trickle_down=16.0))
    m = ConceptMemory(params)
    m.create("r_x", "spatial")
    m.store(parse_many("isa(a,cv_red) w(a,b) isa(b,cv_blue) r_x(a,b)"), "r_x")
    scene = parse_many("isa(o1,cv_red) isa(o2,cv_blue)")
    kept = parse_many("isa(a,cv_red) w(a,b) isa(b,cv_blue)")
    [mapping] = sme.match(kept, scene, params=params.sme)
    want = mapping.score / sme.self_score(kept, params=params.sme)
    [inf] = m.query(scene, "r_x(X,Y)")
    assert inf.similarity == pytest.approx(want) and want != pytest.approx(
        sme.match(kept, scene)[0].score / sme.self_score(kept))


def test_the_prefilter_scores_with_the_sme_parameters_given() -> None:
    # SME's scores a tenth of the default: the similarity is the same, and the pre-filter's
    # bound must be divided by a denominator on the same scale, or it drops the answer.
    params = SageParams(sme=sme.Params(same_functor=0.00005, same_function=0.00002))
    m = visual(params, r_thing="cv_red cv_box")
    assert facts_of(m.query(RED_BOX_PROBE, "isa(X,r_thing)")) == [("isa(o1,r_thing)", 1.0)]


RED_BOX_PROBE = parse_many("isa(o1,cv_red) isa(o1,cv_box)")


# ---------------------------------------------------------------- MAC: many descriptions, many concepts
def _crowded(decoys: int) -> ConceptMemory:
    """r_t: one kept example {red} (the best answer to a large red box, 1.0), then `decoys`
    examples {red, box, large, z_i} that share more functors with it but answer it at 3/4."""
    m = ConceptMemory(SageParams(assimilation=1.0))
    m.create("r_t", "visual")
    m.store(parse_many("isa(a,cv_red) isa(a,r_t)"), "r_t")
    for i in range(decoys):
        m.store(parse_many(f"isa(a,cv_red) isa(a,cv_box) isa(a,cv_large) isa(a,cv_z{i}) isa(a,r_t)"), "r_t")
    return m


RED_BOX = parse_many("isa(o1,cv_red) isa(o1,cv_box)")
LARGE_RED_BOX = parse_many("isa(o1,cv_red) isa(o1,cv_box) isa(o1,cv_large)")


def test_a_context_of_up_to_sixteen_descriptions_is_matched_whole() -> None:
    m = _crowded(15)
    assert len(m.descriptions("r_t")) == 16
    [inf] = m.query(LARGE_RED_BOX, "isa(X,r_t)")
    assert (inf.similarity, inf.index) == (1.0, 0)


def test_a_larger_context_is_matched_only_on_the_descriptions_mac_picks_by_content() -> None:
    # Seventeen descriptions: MAC keeps the 8 sharing most functors with the scene (decoys);
    # `exhaustive` matches them all and finds the best answer MAC passed over.
    m = _crowded(16)
    [inf] = m.query(LARGE_RED_BOX, "isa(X,r_t)")
    assert inf.similarity == pytest.approx(0.75) and inf.index > 0
    [inf] = m.query(LARGE_RED_BOX, "isa(X,r_t)", exhaustive=True)
    assert (str(inf.fact), inf.similarity, inf.index) == ("isa(o1,r_t)", 1.0, 0)
    [inf] = m.fitting(LARGE_RED_BOX, exhaustive=True)
    assert (inf.similarity, inf.index) == (1.0, 0)
    [inf] = m.fitting(LARGE_RED_BOX)
    assert inf.similarity == pytest.approx(0.75)


def test_a_context_whose_descriptions_all_fall_short_answers_nothing() -> None:
    m = _crowded(16)
    assert m.query(RED_BOX, "isa(X,r_t)") == []  # MAC's 8 decoys answer at 1/2 only


@pytest.fixture
def nine() -> ConceptMemory:
    """r_best {red}, then eight concepts {red, box, z_i}: more in common with a red box by
    content, less similar to it (2/3)."""
    m = visual(SageParams(match=0.5), r_best="cv_red")
    for i in range(8):
        m.create(f"r_d{i}", "visual")
        m.store(parse_many(f"isa(a,cv_red) isa(a,cv_box) isa(a,cv_z{i}) isa(a,r_d{i})"), f"r_d{i}")
    return m


def test_fitting_asks_only_the_concepts_mac_picks_by_content(nine: ConceptMemory) -> None:
    assert facts_of(nine.fitting(RED_BOX, k=1)) == [("isa(o1,r_d0)", 0.667)]
    assert facts_of(nine.fitting(RED_BOX, k=1, exhaustive=True)) == [("isa(o1,r_best)", 1.0)]


def test_fitting_asks_k_concepts_when_k_is_wider_than_mac(nine: ConceptMemory) -> None:
    got = facts_of(nine.fitting(RED_BOX, k=9))
    assert got[0] == ("isa(o1,r_best)", 1.0) and len(got) == 9


def test_fitting_gives_five_concepts_unless_told(five: ConceptMemory) -> None:
    five.create("r_six", "visual")
    five.store(parse_many("isa(a,cv_red) isa(a,cv_box) isa(a,cv_large) isa(a,r_six)"), "r_six")
    assert [str(i.fact) for i in five.fitting(PROBE)] == [
        "isa(o1,r_full)", "isa(o1,r_six)", "isa(o1,r_b2)", "isa(o1,r_tie)", "isa(o1,r_half)"]


def test_fitting_binds_the_membership_patterns_variable(five: ConceptMemory) -> None:
    [inf] = five.fitting(PROBE, k=1)
    assert inf.binding == {Term("X"): Term("o1")}


def test_fitting_refuses_k_below_one_and_an_unknown_kind(five: ConceptMemory) -> None:
    with pytest.raises(ValueError, match="k must be at least 1, not 0"):
        five.fitting(PROBE, k=0)
    with pytest.raises(UserError, match="concept kind 'smell' is not one of visual, spatial, action, composite"):
        five.fitting(PROBE, kind="smell")


def test_a_loaded_memory_knows_each_concepts_kind(tmp_path, five: ConceptMemory) -> None:
    path = tmp_path / "m.json"
    five.save(path)
    back = ConceptMemory.load(path)
    assert facts_of(back.fitting(PROBE, kind="visual", k=1)) == [("isa(o1,r_full)", 1.0)]


# ---------------------------------------------------------------- contents, create, load
def test_descriptions_are_each_generalizations_significant_facts_then_each_example() -> None:
    m = ConceptMemory()
    m.create("r_red", "visual")
    m.store(parse_many("isa(a,cv_red) isa(a,cv_box) isa(a,r_red)"), "r_red")
    m.store(parse_many("isa(b,cv_red) isa(b,cv_cone) isa(b,r_red)"), "r_red")
    m.store(parse_many("w(c,d)"), "r_red")
    assert [[str(f) for f in d] for d in m.descriptions("r_red")] == [
        ["isa(gen_ent(0,r_red),cv_red)", "isa(gen_ent(0,r_red),r_red)"], ["w(c,d)"]]


def test_create_refuses_what_is_not_a_lowercase_constant() -> None:
    m = ConceptMemory()
    for bad in ("r red", "r(", "42", "f(a)", '"red"', "Red"):
        with pytest.raises(UserError, match="is not a lowercase ASP constant"):
            m.create(bad, "visual")
    with pytest.raises(UserError, match="concept kind 'smell' is not one of visual, spatial, action, composite"):
        m.create("r_x", "smell")
    assert len(m) == 0


def test_an_unknown_concept_is_named_in_the_error() -> None:
    with pytest.raises(UserError, match="unknown concept 'r_blue'"):
        ConceptMemory().concept("r_blue")


def test_a_memory_read_from_data_names_where_it_came_from_in_its_errors() -> None:
    with pytest.raises(UserError) as exc:
        ConceptMemory.from_dict({"format": "something-else", "version": 1})
    assert str(exc.value).startswith("<memory>")


# ---------------------------------------------------------------- more of project
def test_project_keeps_weaker_mappings_that_are_temporally_coherent() -> None:
    # The trace's second state looks like the action's third (six facts to one); the mapping
    # that says so scores far better, but only the coherent one reads the trace in order.
    m = ConceptMemory()
    m.create("r_act", "action")
    m.store(parse_many("isa(t0,start) h(t0,p(o1)) after(t1,t0) h(t1,q(o1)) after(t2,t1) h(t2,q(o1)) "
                       "h(t2,r(o1)) h(t2,s(o1)) h(t2,u(o1)) h(t2,v(o1)) h(t2,w(o1)) r_act(o1)"), "r_act")
    trace = parse_many("isa(t0,start) h(t0,p(o5)) after(t1,t0) h(t1,q(o5)) h(t1,r(o5)) h(t1,s(o5)) "
                       "h(t1,u(o5)) h(t1,v(o5)) h(t1,w(o5)) r_act(o5)")
    p = m.project(trace, "r_act")
    assert sorted(str(f) for f in p.facts) == ["q(o5)", "r(o5)", "s(o5)", "u(o5)", "v(o5)", "w(o5)"]
    assert p.time_point == parse("skolem(t2)") and p.similarity == pytest.approx(0.282, abs=1e-3)


def test_project_reads_the_start_from_isa_start_alone(right: ConceptMemory) -> None:
    # Other isa facts in the trace (a percept at the top level) are not its start.
    trace = parse_many("isa(t0,start) isa(o5,cv_red) h(t0,w(o5,o6)) h(t0,dc(o5,o6)) r_move_right_of(o5,o6)")
    p = right.project(trace, "r_move_right_of")
    assert {str(f) for f in p.facts} == {"held(o5)", "dc(o5,o6)"} and p.time_point == parse("skolem(t1)")


def test_project_gives_the_similarity_of_the_mapping_it_chose(right: ConceptMemory) -> None:
    trace = parse_many("isa(t0,start) h(t0,w(o5,o6)) h(t0,dc(o5,o6)) r_move_right_of(o5,o6)")
    p = right.project(trace, "r_move_right_of")
    base = right.descriptions("r_move_right_of")[0]  # a projection leaves nothing out of it
    assert p.similarity == pytest.approx(p.mapping.score / sme.self_score(base)) and 0.0 < p.similarity < 1.0
    done = parse_many("isa(t0,start) h(t0,w(o5,o6)) h(t0,dc(o5,o6)) after(t1,t0) h(t1,held(o5)) "
                      "h(t1,dc(o5,o6)) after(t2,t1) h(t2,e(o5,o6)) h(t2,dc(o5,o6)) r_move_right_of(o5,o6)")
    q = right.project(done, "r_move_right_of")
    assert q.complete and q.similarity == pytest.approx(1.0)


def test_project_on_a_tie_keeps_the_first_description() -> None:
    m = ConceptMemory()
    m.create("r_move_right_of", "action")
    for _ in range(2):
        m.store(parse_many(RIGHT), "r_move_right_of", accept=lambda g: False)
    p = m.project(parse_many("isa(t0,start) h(t0,w(o5,o6)) r_move_right_of(o5,o6)"), "r_move_right_of")
    assert (p.source, p.index) == ("example", 0)


def test_time_chain_stops_at_a_loop_back_to_any_earlier_point() -> None:
    assert time_chain(parse_many("after(t6,t5) after(t7,t6) after(t8,t7) after(t7,t8)")) == [
        Term("t5"), Term("t6"), Term("t7"), Term("t8")]


def test_time_chain_stops_at_a_loop_back_to_the_same_point() -> None:
    assert time_chain(parse_many("after(t6,t5) after(t6,t6)")) == [Term("t5"), Term("t6")]


def test_time_chain_starts_at_isa_start_even_after_other_time_points() -> None:
    assert time_chain(parse_many("h(t9,p(a)) after(t1,t0) isa(t0,start)")) == [Term("t0"), Term("t1")]


# ---------------------------------------------------------------- more of SAGE
def test_add_on_a_tie_merges_into_the_first_description() -> None:
    ctx = GeneralizationContext("r_x")
    apart = SageParams(assimilation=0.99)
    ctx.add(parse_many("isa(a,cv_red) isa(a,cv_box)"), apart)
    ctx.add(parse_many("isa(b,cv_red) isa(b,cv_cone)"), apart)
    r = ctx.add(parse_many("isa(c,cv_red) isa(c,cv_sphere)"), SageParams())
    assert (r.action, r.index) == ("new_generalization", 0)
    assert [str(f) for f in ctx.examples[0]] == ["isa(b,cv_red)", "isa(b,cv_cone)"]


def test_an_example_exactly_at_the_assimilation_threshold_is_merged() -> None:
    ctx = GeneralizationContext("r_x")
    exact = SageParams(assimilation=1.0)
    ctx.add(parse_many("isa(a,cv_red) isa(a,cv_box)"), exact)
    r = ctx.add(parse_many("isa(b,cv_red) isa(b,cv_box)"), exact)
    assert (r.action, r.similarity) == ("new_generalization", 1.0)


def test_accept_is_shown_the_generalization_the_merge_would_make() -> None:
    ctx = GeneralizationContext("r_x")
    ctx.add(parse_many("isa(a,cv_red) isa(a,cv_box)"), SageParams())
    shown: list[Generalization] = []
    r = ctx.add(parse_many("isa(b,cv_red) isa(b,cv_cone)"), SageParams(),
                accept=lambda g: shown.append(g) or False)
    [g] = shown
    assert g.size == 2 and {str(f): p for f, p in g.probabilities().items()} == {
        "isa(gen_ent(0,r_x),cv_red)": 1.0, "isa(gen_ent(0,r_x),cv_box)": 0.5, "isa(gen_ent(0,r_x),cv_cone)": 0.5}
    assert (r.action, r.index) == ("kept", 1) and ctx.generalizations == []
    r = ctx.add(parse_many("isa(c,cv_red) isa(c,cv_cone)"), SageParams(), accept=lambda g: False)
    assert (r.action, r.index) == ("kept", 2) and len(ctx.examples) == 3


def test_match_uses_the_function_predicates_given() -> None:
    # f and g pair only as declared functions; otherwise p(a,f(b)) has no counterpart.
    ctx = GeneralizationContext("r_x")
    ctx.add(parse_many("p(a,f(b))"), SageParams())
    target = parse_many("p(o1,g(o2))")
    assert ctx.match(target, SageParams()) == []
    [cand] = ctx.match(target, SageParams(functions=frozenset({"f", "g"})))
    assert cand.mappings[0].entities == {"a": "o1", "b": "o2"}


def test_fresh_generalized_entities_are_numbered_on_from_the_last() -> None:
    g = Generalization("c", {parse("p(gen_ent(0,c))"): 1, parse("q(gen_ent(1,c))"): 1}, 1)
    g.merge(parse_many("p(x) r(y) s(z)"), {Term("x"): gen_ent(0, "c")})
    assert {str(f) for f in g.counts} == {"p(gen_ent(0,c))", "q(gen_ent(1,c))", "r(gen_ent(2,c))",
                                          "s(gen_ent(3,c))"}
    assert g.next_entity == 4
    g.merge(parse_many("t(w)"), {})
    assert parse("t(gen_ent(4,c))") in g.counts and g.next_entity == 5


def test_a_generalization_of_two_examples_names_each_entity_apart() -> None:
    g = Generalization.from_pair("k", parse_many("r(a,b,c)"), parse_many("r(x,y,z)"),
                                 {Term("x"): Term("a"), Term("y"): Term("b"), Term("z"): Term("c")})
    assert [str(f) for f in g.counts] == ["r(gen_ent(0,k),gen_ent(1,k),gen_ent(2,k))"]
    assert g.next_entity == 3 and g.size == 2


def test_bad_sage_parameters_are_named_in_the_error() -> None:
    with pytest.raises(ValueError, match="normalisation must be one of .*'nope'"):
        SageParams(normalisation="nope")
    with pytest.raises(ValueError, match=r"match threshold must be in \[0, 1\], not 1.5"):
        SageParams(match=1.5)
    with pytest.raises(ValueError, match=r"assimilation threshold must be in \[0, 1\], not -0.1"):
        SageParams(assimilation=-0.1)


def test_the_store_filter_keeps_each_concepts_descriptions_apart() -> None:
    # Both concepts hold a description at index 0; a store into r_b must be matched with r_b's.
    m = ConceptMemory()
    m.create("r_a", "visual")
    m.create("r_b", "visual")
    m.store(parse_many("isa(a,cv_red) isa(a,cv_box)"), "r_a")
    m.store(parse_many("isa(a,cv_red) isa(a,cv_box)"), "r_a")
    m.store(parse_many("isa(b,cv_blue) isa(b,cv_cone)"), "r_b")
    r = m.store(parse_many("isa(c,cv_blue) isa(c,cv_cone)"), "r_b")
    assert (r.action, r.similarity, r.generalizations, r.examples) == ("new_generalization", 1.0, 1, 0)


def test_the_filtered_store_scores_with_the_sme_parameters_given() -> None:
    # The older SME preset weighs a partial match otherwise than the default: the filtered
    # store must find the similarity the exhaustive store finds with the same parameters.
    params = SageParams(sme=sme.Params(same_functor=0.005, same_function=0.002, trickle_down=16.0))
    got = []
    for exhaustive in (False, True):
        m = ConceptMemory(params)
        m.create("r_x", "spatial")
        m.store(parse_many("w(a,b) isa(a,cv_red) isa(b,cv_blue) r_x(a,b)"), "r_x")
        got.append(m.store(parse_many("w(c,d) isa(c,cv_red) isa(d,cv_green) r_x(c,d)"), "r_x",
                           exhaustive=exhaustive).similarity)
    default = sme.match(parse_many("w(a,b) isa(a,cv_red) isa(b,cv_blue) r_x(a,b)"),
                        parse_many("w(c,d) isa(c,cv_red) isa(d,cv_green) r_x(c,d)"))[0].similarity
    assert got[0] == got[1] and got[0] != pytest.approx(default)


def test_the_kept_answers_are_bounded(monkeypatch: pytest.MonkeyPatch) -> None:
    from aileen.memory import recognition

    monkeypatch.setattr(recognition, "ANSWERS_KEPT", 3)
    m = visual(SageParams(match=0.3), r_thing="cv_red cv_box cv_large")
    scenes = [parse_many(f"isa(o{k},cv_red) isa(o{k},cv_box)") for k in range(1, 8)]
    first = [facts_of(m.query(s, "isa(X,r_thing)")) for s in scenes]
    assert m._recognition._kept <= 3  # noqa: SLF001 - the bound is what this test is about
    assert [facts_of(m.query(s, "isa(X,r_thing)")) for s in scenes] == first


def test_a_copy_of_the_memory_leaves_the_kept_answers_behind_and_answers_alike() -> None:
    import copy
    import pickle

    m = visual(SageParams(match=0.3), r_thing="cv_red cv_box cv_large")
    scene = parse_many("isa(o1,cv_red) isa(o1,cv_box)")
    asked = facts_of(m.query(scene, "isa(X,r_thing)"))
    for other in (copy.deepcopy(m), pickle.loads(pickle.dumps(m))):
        assert other._recognition._kept == 0  # noqa: SLF001 - what a copy carries is the point
        assert facts_of(other.query(scene, "isa(X,r_thing)")) == asked
    assert m._recognition._kept == 1  # noqa: SLF001
