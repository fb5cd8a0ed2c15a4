"""MAC/FAC retrieval: content vectors, the index kept up to date on store, and the same answers
as the exhaustive search (on a taught memory and on large synthetic ones)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.analogy.sage import SageParams
from aileen.memory.concept import CONTEXT_MAC, ConceptMemory
from aileen.memory.retrieval import best_descriptions, content_vector, dot
from aileen.terms import Term, parse, parse_many


def obj(o: str, *classes: str) -> list[Term]:
    return [parse(f"isa({o},{c})") for c in classes]


def test_content_vector_counts_class_symbols_and_predicates_as_sme_pairs_them() -> None:
    v = content_vector(parse_many("isa(o1,cv_red) isa(o2,cv_red) isa(o1,cv_box) r_left_of(o1,o2) r_left_of(o1,o2)"))
    assert v == {("cv_red", 1): 2, ("cv_box", 1): 1, ("r_left_of", 2): 1}
    nested = content_vector([parse("h(t0,r_left_of(o1,o2))"), parse("after(t1,t0)")])
    assert nested == {("h", 2): 1, ("r_left_of", 2): 1, ("after", 2): 1}


def test_dot_is_symmetric_and_zero_without_shared_functors() -> None:
    a = content_vector(obj("o1", "cv_red", "cv_box"))
    b = content_vector(obj("g", "cv_red", "cv_red2", "r_red"))
    assert dot(a, b) == dot(b, a) == 1
    assert dot(a, content_vector(obj("g", "cv_blue"))) == 0


def test_mac_cut_keeps_the_best_and_drops_zero_scores() -> None:
    assert best_descriptions([(3, 0), (0, 1), (5, 2), (3, 3), (1, 4)], 2) == [2, 0]
    assert best_descriptions([(0, 0), (0, 1)], 4) == []


@settings(max_examples=60, deadline=None)
@given(st.lists(st.integers(0, 6), max_size=30), st.integers(1, 8))
def test_mac_cut_never_drops_a_better_score_than_one_it_keeps(scores, width) -> None:
    pairs = [(s, i) for i, s in enumerate(scores)]
    kept = best_descriptions(pairs, width)
    assert len(kept) == min(width, sum(1 for s in scores if s > 0))
    if kept:
        worst = min(scores[i] for i in kept)
        assert all(s <= worst or i in kept for i, s in enumerate(scores))
        assert all(scores[i] > 0 for i in kept)


def _random_memory(n_concepts: int, examples: int, seed: int, assimilation: float = 0.01,
                   match: float = 0.75) -> ConceptMemory:
    """Visual concepts over a vocabulary of 60 percepts: concept i means percept i % 60 and
    its examples show it with two random other percepts."""
    rng = np.random.default_rng(seed)
    m = ConceptMemory(SageParams(assimilation=assimilation, match=match))
    for i in range(n_concepts):
        c = f"r_w{i}"
        m.create(c, "visual")
        for e in range(examples):
            o = f"o{e + 1}"
            others = rng.choice(60, size=2, replace=False)
            m.store(obj(o, f"cv_p{i % 60}", *(f"cv_p{j}" for j in others), c), c)
    return m


def test_fitting_finds_what_exhaustive_search_finds_on_a_large_memory() -> None:
    m = _random_memory(150, 2, seed=1)
    rng = np.random.default_rng(2)
    nonempty = 0
    for t in range(20):
        probe = obj("o9", *(f"cv_p{j}" for j in rng.choice(60, size=3, replace=False)))
        fast = m.fitting(probe, kind="visual", k=5)
        slow = m.fitting(probe, kind="visual", k=5, exhaustive=True)
        assert [(str(i.fact), round(i.similarity, 9)) for i in fast] == \
            [(str(i.fact), round(i.similarity, 9)) for i in slow], f"probe {t}"
        nonempty += bool(fast)
    assert nonempty >= 15  # the comparison is not between two empty answers


def test_query_in_a_context_with_many_kept_examples_matches_exhaustive() -> None:
    # assimilation 1.0: examples are kept, not merged, so the context grows past CONTEXT_MAC;
    # match 0.3: a probe sharing one percept besides cv_p0 with an example fits it
    m = _random_memory(1, 40, seed=3, assimilation=1.0, match=0.3)
    assert len(m.concept("r_w0").context.examples) > CONTEXT_MAC
    rng = np.random.default_rng(4)
    for _ in range(20):
        probe = obj("o9", "cv_p0", *(f"cv_p{j}" for j in rng.choice(60, size=2, replace=False)))
        pat = parse("isa(X,r_w0)")
        fast = m.query(probe, pat)
        slow = m.query(probe, pat, exhaustive=True)
        assert [(i.fact, i.similarity, i.source, i.index) for i in fast] == \
            [(i.fact, i.similarity, i.source, i.index) for i in slow]
        assert fast  # every probe holds cv_p0: the concept fits


def test_index_follows_stores_and_a_saved_memory(tmp_path) -> None:
    m = ConceptMemory()
    m.create("r_red", "visual")
    m.store(obj("o1", "cv_red", "r_red"), "r_red")
    probe = obj("o5", "cv_red", "cv_cone")
    assert [str(i.fact) for i in m.fitting(probe)] == ["isa(o5,r_red)"]
    m.create("r_cone", "visual")
    assert [str(i.fact) for i in m.fitting(probe)] == ["isa(o5,r_red)"]  # created, nothing stored yet
    m.store(obj("o2", "cv_cone", "r_cone"), "r_cone")
    assert sorted(str(i.fact) for i in m.fitting(probe)) == ["isa(o5,r_cone)", "isa(o5,r_red)"]
    assert [str(i.fact) for i in m.fitting(probe, k=1)] == ["isa(o5,r_red)"]  # created first on a tie
    path = tmp_path / "m.json"
    m.save(path)
    back = ConceptMemory.load(path)
    assert [(str(i.fact), i.similarity) for i in back.fitting(probe)] == \
        [(str(i.fact), i.similarity) for i in m.fitting(probe)]
    assert back.fitting(probe, kind="spatial") == []


def test_fitting_finds_relations_for_a_pair() -> None:
    m = ConceptMemory()
    m.create("r_left_of", "spatial")
    m.store(parse_many("isa(o1,cv_red) isa(o2,cv_box) w(o1,o2) dc(o1,o2) r_left_of(o1,o2)"), "r_left_of")
    m.create("r_red", "visual")
    m.store(obj("o1", "cv_red", "r_red"), "r_red")
    scene = parse_many("isa(o7,cv_red) isa(o8,cv_box) w(o7,o8) dc(o7,o8)")
    assert [str(i.fact) for i in m.fitting(scene, kind="spatial")] == ["r_left_of(o7,o8)"]
    assert [str(i.fact) for i in m.fitting(scene, kind="spatial", exhaustive=True)] == ["r_left_of(o7,o8)"]
    with pytest.raises(ValueError):
        m.fitting(scene, k=0)


def test_fitting_matches_exhaustive_on_a_memory_taught_the_spatial_protocol() -> None:
    """The evaluation's memory: a spatial trial's visual and spatial lessons taught (ground-truth
    vision), then every object and ordered pair of its exam scenes asked which concepts fit."""
    from aileen.agent import Agent
    from aileen.curriculum.interpreter import Interpreter
    from aileen.experiments.protocol import make_trial
    from aileen.experiments.runner import teach
    from aileen.perception.truth import TruthVision

    vision = TruthVision()
    agent = Agent(perceiver=vision)
    interp = Interpreter(agent, on_frame=vision.see_frame)
    trial = make_trial("spatial", 5)
    teach(interp, trial.prerequisites + trial.lessons[:10], 7)
    m = agent.memory
    assert len(m) >= 13
    asked = answered = 0
    for i, item in enumerate(trial.generality + trial.specificity):
        interp.run(item, index=1, seed=50 + i)
        state = agent.state
        assert state is not None
        objs = sorted(state.objects)
        for o in objs:
            facts = state.percepts(o)
            fast = [(x.fact, x.similarity) for x in m.fitting(facts, kind="visual", k=3)]
            assert fast == [(x.fact, x.similarity) for x in m.fitting(facts, kind="visual", k=3, exhaustive=True)], o
            asked += 1
            answered += bool(fast)
        for a in objs:
            for b in objs:
                if a != b:
                    facts = state.percepts(a) + state.percepts(b) + state.relations(a, b)
                    fast = [(x.fact, x.similarity) for x in m.fitting(facts, kind="spatial", k=2)]
                    slow = [(x.fact, x.similarity) for x in m.fitting(facts, kind="spatial", k=2, exhaustive=True)]
                    assert fast == slow, (a, b)
                    asked += 1
                    answered += bool(fast)
    assert answered >= asked // 2  # most questions have an answer: the comparison has content


_fact = st.one_of(
    st.builds(lambda o, c: parse(f"isa({o},{c})"), st.sampled_from(["a", "b", "c"]),
              st.sampled_from(["cv_red", "cv_box", "cv_cone"])),
    st.builds(lambda r, x, y: parse(f"{r}({x},{y})"), st.sampled_from(["w", "e", "dc", "r_left_of"]),
              st.sampled_from(["a", "b", "c"]), st.sampled_from(["a", "b", "c"])),
    st.builds(lambda x, y: parse(f"h(t0,w({x},{y}))"), st.sampled_from(["a", "b"]), st.sampled_from(["a", "c"])),
)


@settings(max_examples=200, deadline=None)
@given(st.lists(_fact, min_size=1, max_size=8), st.lists(_fact, min_size=1, max_size=8))
def test_score_bound_is_never_below_a_mappings_score(base, target) -> None:
    """The FAC pre-check may skip SME only because no mapping can score above the bound."""
    from aileen.analogy import sme
    from aileen.memory.retrieval import score_bound

    params = SageParams()
    bound = score_bound(base, content_vector(target), params)
    for m in sme.match(base, target, params=params.sme):
        assert m.score <= bound + 1e-12
