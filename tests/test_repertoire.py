"""The wide protocol's repertoire experiment (sizes, distance, contact, comparatives) and the
mechanisms it leans on: mutual exclusivity over relation words (by role), and merges that keep
a direction."""

from __future__ import annotations

import subprocess
import sys

import pytest

from aileen.agent import Agent, AgentParams
from aileen.agent.disjunction import keeps_a_meaning
from aileen.analogy.sage import Generalization
from aileen.curriculum.interpreter import Interpreter
from aileen.curriculum.lesson import Lesson, ObjectSpec
from aileen.curriculum.sentences import read_content
from aileen.domain import relations
from aileen.experiments import runner, wide
from aileen.experiments.protocol import lesson_words, make_trial, oracle_curve
from aileen.perception.truth import TruthVision
from aileen.terms import parse


def test_the_repertoire_trial_teaches_and_examines_every_repertoire_word() -> None:
    words = set(wide.repertoire_words())
    assert {"small", "medium", "large", "near", "far from", "next to", "larger than", "smaller than"} <= words
    assert not words & set(relations.directions()) and "on" not in words
    # the published words are declared side-by-side relation words (fixed, not read from the registry)
    assert all(relations.find(w) == w and not relations.of_word(w).stacked for w in wide.REPERTOIRE_RELATIONS)
    taught: set[str] = set()
    for seed in range(4):
        t = make_trial("repertoire", seed, "wide")
        assert len(t.lessons) == 20
        for lesson in t.lessons:
            taught |= lesson_words(lesson)
        # prerequisites: the visual words at several sizes, the directions, apart and touching
        sizes = {o.size for p in t.prerequisites for o in p.objects}
        assert {"small", "medium", "large"} <= sizes
        assert any(p.relation and p.relation.endswith(" ec") for p in t.prerequisites)
        notes = {x.note for x in t.specificity}
        assert notes <= {wide.VISUAL_OTHER_SIZE, wide.SPATIAL_OUTSIDE, wide.SPATIAL_SWAPPED}
        for x in t.specificity:
            if x.note == wide.SPATIAL_SWAPPED:  # only a relation whose roles matter is swapped
                assert not relations.of_word(read_content(x.content).relation).symmetric
        assert oracle_curve(t)[-1] == 5
    assert words <= taught


def test_the_repertoire_is_the_wide_protocols_alone() -> None:
    with pytest.raises(ValueError, match="wide protocol"):
        make_trial("repertoire", 0, "paper")
    r = subprocess.run([sys.executable, "-m", "aileen", "experiment", "repertoire", "--protocol", "paper",
                        "--out", "unused-dir"], capture_output=True, text=True)
    assert r.returncode == 2
    assert r.stderr.strip().count("\n") == 0 and "wide protocol only" in r.stderr


def test_a_repertoire_trial_ends_with_every_near_miss_refused() -> None:
    t = runner.run_trial("repertoire", 1, 0, protocol="wide", perception="truth")
    assert t.records[-1].specificity == 5


def _agent() -> tuple[Agent, Interpreter]:
    v = TruthVision()
    agent = Agent(params=AgentParams(seed=0), perceiver=v)
    return agent, Interpreter(agent, on_frame=v.see_frame)


def test_larger_than_and_smaller_than_do_not_take_each_others_meaning() -> None:
    """Both use the same size relations, with the roles the other way round: by predicate
    names alone each would look like the other, and exclusivity would strip them."""
    agent, interp = _agent()
    for i, (c, s) in enumerate((("red", "box"), ("blue", "cone"), ("green", "sphere"))):
        for j, z in enumerate(("small", "large")):
            interp.run(Lesson("inform", f"{c} {s}", [ObjectSpec(s, c, z)]), index=2 * i + j, seed=2 * i + j)
    a, b = ObjectSpec("box", "red"), ObjectSpec("cone", "blue")
    interp.run(Lesson("inform", "red box larger than blue cone", [a, b], relation="larger than"), index=10, seed=10)
    interp.run(Lesson("inform", "red box smaller than blue cone", [a, b], relation="smaller than"), index=11, seed=11)
    assert not agent.grounding.relations_claimed_by_others("r_larger_than")
    assert not agent.grounding.relations_claimed_by_others("r_smaller_than")
    swapped = interp.run(Lesson("verify", "red box larger than blue cone", [a, b], relation="smaller than"),
                         index=12, seed=12)
    assert swapped.answer.result == "failure"


def test_a_relation_shown_apart_and_touching_keeps_its_direction() -> None:
    """With cones, "left of" apart (dc) and touching (ec) merge into the cone alone; a merge
    that keeps only `dc` (what nearly every pair has) is still refused."""
    merged = Generalization("r_left_of", {parse("cone_w(a,b)"): 2, parse("dc(a,b)"): 1, parse("ec(a,b)"): 1}, 2)
    assert keeps_a_meaning(merged, 0.6, [parse("cone_w(x,y)"), parse("ec(x,y)")])
    only_dc = Generalization("r_left_of", {parse("w(a,b)"): 1, parse("sw(a,b)"): 1, parse("dc(a,b)"): 2}, 2)
    assert not keeps_a_meaning(only_dc, 0.6, [parse("sw(x,y)"), parse("dc(x,y)")])
    near = Generalization("r_near", {parse("qd_close(a,b)"): 2, parse("dc(a,b)"): 1, parse("ec(a,b)"): 1}, 2)
    assert keeps_a_meaning(near, 0.6, [parse("qd_close(x,y)"), parse("ec(x,y)")])
    # a generalization that still insists on `dc` does not take in a touching example
    apart = Generalization("r_near", {parse("qd_close(a,b)"): 2, parse("dc(a,b)"): 2}, 2)
    assert not keeps_a_meaning(apart, 0.6, [parse("qd_close(x,y)"), parse("ec(x,y)")])


@pytest.mark.parametrize("exclusive", [True, False])
def test_a_relation_learned_before_the_directions_lets_go_of_its_side_once_they_are_known(exclusive: bool) -> None:
    """Query-time exclusivity over relations: "far from" taught once, before any direction
    word, keeps the side it was shown on in its example; once the four directions are known
    (they claim those sides), it holds on every side. Without exclusivity it does not."""
    v = TruthVision()
    agent = Agent(params=AgentParams(seed=0, mutual_exclusivity=exclusive), perceiver=v)
    interp = Interpreter(agent, on_frame=v.see_frame)
    a, b = ObjectSpec("box", "red"), ObjectSpec("cone", "blue")
    g, y = ObjectSpec("sphere", "green"), ObjectSpec("cylinder", "yellow")
    for i, (o, said) in enumerate(((a, "red box"), (b, "blue cone"), (g, "green sphere"), (y, "yellow cylinder"))):
        interp.run(Lesson("inform", said, [o]), index=i, seed=i)
    interp.run(Lesson("inform", "red box far from blue cone", [a, b], relation="far from"), index=5, seed=50)
    assert any(parse(f).name.startswith("cone_") for f in agent.memory.examples("r_far_from")[0])
    for i, rel in enumerate(("left of", "right of", "behind", "in front of")):
        interp.run(Lesson("inform", f"red box {rel} blue cone", [a, b], relation=rel), index=6 + i, seed=6 + i)
    answers = [interp.run(Lesson("verify", "green sphere far from yellow cylinder", [g, y], relation="far from"),
                          index=10 + k, seed=seed).answer.result for k, seed in enumerate((53, 54, 56, 58))]
    if exclusive:
        assert answers == ["success"] * 4
    else:
        assert "failure" in answers


def test_relation_exclusivity_compares_meanings_by_role() -> None:
    """"smaller than" uses the same size predicates as "larger than", with the roles the other
    way round: by predicate name it would look like a strict part of "larger than" and take
    its size relations away. A side that "left of" means is taken from "near"."""
    from aileen.memory.concept import ConceptMemory

    mem = ConceptMemory(AgentParams().sage())
    described = {
        "r_larger_than": "dc(a,b) dc(b,a) sz_larger(a,b) sz_smaller(b,a)",
        "r_smaller_than": "sz_smaller(a,b) sz_larger(b,a)",
        "r_left_of": "cone_w(a,b) cone_e(b,a)",
        "r_near": "cone_w(a,b) cone_e(b,a) dc(a,b) dc(b,a) qd_close(a,b) qd_close(b,a)",
    }
    for concept, facts in described.items():
        mem.create(concept, "spatial")
        mem.store([parse(f) for f in facts.split()] + [parse(f"{concept}(a,b)")], concept)
    agent = Agent(mem, params=AgentParams(seed=0, senses_of_direction="cones"), perceiver=TruthVision())
    assert agent.grounding.relations_claimed_by_others("r_larger_than") == frozenset()
    assert agent.grounding.relations_claimed_by_others("r_smaller_than") == frozenset()
    assert agent.grounding.relations_claimed_by_others("r_near") == frozenset({"cone_w", "cone_e"})
    assert agent.grounding.relations_claimed_by_others("r_left_of") == frozenset()
