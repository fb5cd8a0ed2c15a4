"""Issue 11, point 6: typicality of an answer, concept quality, weak comprehension stores."""

from __future__ import annotations

import json

from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.agent import Agent, AgentParams
from aileen.cli import main
from aileen.curriculum.interpreter import Interpreter
from aileen.curriculum.lesson import Lesson, ObjectSpec
from aileen.memory import quality
from aileen.memory.concept import ConceptMemory
from aileen.perception.truth import TruthVision
from aileen.terms import parse


def _store(mem: ConceptMemory, sector: str, concept: str) -> None:
    from aileen.agent import disjunction

    facts = [parse(f"{sector}(o1,o2)"), parse("dc(o1,o2)")]
    mem.store(facts + [parse(f"{concept}(o1,o2)")], concept,
              accept=lambda merged: disjunction.keeps_a_meaning(merged, mem.params.probability, facts))


def _left_of_memory() -> ConceptMemory:
    mem = ConceptMemory(AgentParams().sage())
    for c in ("r_left_of", "r_behind"):
        mem.create(c, "spatial")
    for sector in ("w", "w", "w", "sw"):  # a main disjunct and a rare one
        _store(mem, sector, "r_left_of")
    for sector in ("n", "nw"):
        _store(mem, sector, "r_behind")
    return mem


def test_an_instance_of_the_main_disjunct_is_more_typical_than_a_rare_one() -> None:
    mem = _left_of_memory()
    main_ = mem.query([parse("w(a,b)"), parse("dc(a,b)")], parse("r_left_of(a,b)"))[0]
    rare = mem.query([parse("sw(a,b)"), parse("dc(a,b)")], parse("r_left_of(a,b)"))[0]
    assert quality.typicality(mem, main_) == 0.75 and quality.typicality(mem, rare) == 0.25


def test_quality_counts_and_separation() -> None:
    mem = _left_of_memory()
    q = quality.quality(mem, "r_left_of")
    assert (q.examples_seen, q.generalizations, q.examples_apart) == (4, 1, 1)
    assert q.separation == 1.0 and q.confused_with == []
    _store(mem, "nw", "r_left_of")
    q = quality.quality(mem, "r_left_of")  # nw is also behind's: that description does not separate
    assert q.confused_with == ["r_behind"] and q.separation == round(2 / 3, 3)


def test_memory_show_prints_quality(tmp_path, capsys) -> None:
    path = tmp_path / "m.json"
    _left_of_memory().save(path)
    assert main(["memory", "show", str(path)]) == 0
    out = capsys.readouterr().out
    assert "quality: 4 examples seen, 1 generalizations + 1 apart" in out
    assert main(["memory", "show", str(path), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["r_behind"]["quality"]["examples_seen"] == 2


def _agent(**params) -> tuple[Agent, Interpreter]:  # noqa: ANN003
    v = TruthVision()
    agent = Agent(params=AgentParams(seed=0, **params), perceiver=v)
    return agent, Interpreter(agent, on_frame=v.see_frame)


def test_a_verify_answer_carries_typicality() -> None:
    agent, interp = _agent()
    interp.run(Lesson("inform", "red box", [ObjectSpec("box", "red")]), index=1, seed=1)
    r = interp.run(Lesson("verify", "red box", [ObjectSpec("box", "red")], distractors=2), index=2, seed=2)
    assert r.answer.ok
    assert set(r.answer.typicality) == {f"isa({o},r_red)" for o in r.answer.referents["red box"]} | \
        {f"isa({o},r_box)" for o in r.answer.referents["red box"]}
    assert all(0.0 < t <= 1.0 for t in r.answer.typicality.values())
    assert r.to_json()["typicality"] == r.answer.typicality


def test_a_weak_success_is_stored_and_a_clear_one_is_not() -> None:
    lessons = [Lesson("inform", "red box", [ObjectSpec("box", "red")]),
               Lesson("inform", "red box", [ObjectSpec("box", "red")], distractors=1)]
    stored = {}
    for margin in (0.0, 0.05, 0.3):  # 0.3: every match below 1.05 counts as weak
        agent, interp = _agent(weak_margin=margin)
        stored[margin] = [interp.run(x, index=i, seed=i).answer.commands for i, x in enumerate(lessons)]
    assert stored[0.0][1] == 0  # understood: nothing to learn
    assert stored[0.05][1] == stored[0.0][1]  # a clear success (similarity 1.0 > 0.80) stores nothing
    assert stored[0.3][1] == 2  # within the margin: both words stored again


@settings(max_examples=25, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(["w", "sw", "nw", "n", "e", "s"]), st.integers(0, 5)), min_size=1, max_size=24))
def test_separation_by_the_content_index_is_every_concept_asked(stores) -> None:
    """`aileen memory show` judges separation against the concepts the content index finds
    most alike once a kind has many concepts (asking each of them for each concept was
    quadratic); on random memories it says what asking every concept says."""
    mem = ConceptMemory(AgentParams().sage())
    for k in range(6):
        mem.create(f"r_w{k}", "spatial")
    for sector, k in stores:
        _store(mem, sector, f"r_w{k}")
    for c in mem.concepts():
        assert quality.quality(mem, c.symbol, exhaustive=False) == quality.quality(mem, c.symbol, exhaustive=True)


def test_by_default_every_other_concept_of_its_kind_is_asked_up_to_the_bound(monkeypatch) -> None:
    """`quality` asks every other concept of the concept's kind while there are at most
    `EXHAUSTIVE_UP_TO` of them (other kinds and itself not counted), else the content index's
    most alike; past the bound it no longer lists them all (that made `memory show` quadratic:
    90 s for 10,000 concepts, 42 s after, the same text)."""
    mem = ConceptMemory(AgentParams().sage())
    for c, p in (("r_a", "cv_red"), ("r_b", "cv_blue"), ("r_c", "cv_green")):
        mem.create(c, "visual")
        mem.store([parse(f"isa(o1,{p})"), parse(f"isa(o1,{c})")], c)
    for k in range(4):
        mem.create(f"r_s{k}", "spatial")
    asked: list[tuple[bool, list[str]]] = []

    def accepting(memory, scene, member, mine, others, every):  # noqa: ANN001, ANN202
        asked.append((every, sorted(others)))
        return []

    monkeypatch.setattr(quality, "_accepting", accepting)
    monkeypatch.setattr(quality, "EXHAUSTIVE_UP_TO", 2)
    quality.quality(mem, "r_a")
    assert asked == [(True, ["r_b", "r_c"])]
    monkeypatch.setattr(quality, "EXHAUSTIVE_UP_TO", 1)
    asked.clear()
    quality.quality(mem, "r_a")
    assert asked == [(False, [])]
