"""The domain declared once (aileen/domain): a new relation is one declaration; the ASP action
models and the calculi agree with their Python declarations."""

from __future__ import annotations

import re

import pytest

from aileen.agent import Agent
from aileen.curriculum.interpreter import Interpreter
from aileen.curriculum.lesson import Lesson, ObjectSpec
from aileen.domain import actions, calculi, channels, composites, relations
from aileen.perception.truth import TruthVision
from aileen.reasoning import asp
from aileen.world import catalog


@pytest.fixture
def toy_relation():
    """A relation no library code knows: 'above right of', north-east of the reference."""
    saved_rel, saved_alias = dict(relations.RELATIONS), dict(relations._ALIASES)
    relations.declare(relations.directional("above right of", 45.0, aliases=("up right of",)))
    yield "above right of"
    relations.RELATIONS.clear(), relations.RELATIONS.update(saved_rel)
    relations._ALIASES.clear(), relations._ALIASES.update(saved_alias)


def _lesson(signal: str, content: str, relation: str, distractors: int = 0) -> Lesson:
    return Lesson(signal, content, [ObjectSpec("box", "red"), ObjectSpec("cone", "blue")], relation=relation,
                  distractors=distractors)


def test_a_toy_relation_is_laid_out_taught_and_examined_through_its_declaration_alone(toy_relation) -> None:
    assert relations.canonical("up-right-of") == toy_relation
    vision = TruthVision()
    agent = Agent(perceiver=vision)
    interp = Interpreter(agent, on_frame=vision.see_frame)
    for i, o in enumerate(["red box", "blue cone"]):
        interp.run(Lesson("inform", o, [ObjectSpec(*reversed(o.split()))]), index=1, seed=300 + i)
    first = interp.run(_lesson("inform", "red box above right of blue cone", toy_relation), index=1, seed=310)
    assert first.answer.created == ["r_above_right_of"]
    yes = interp.run(_lesson("verify", "red box above right of blue cone", toy_relation, 2), index=1, seed=311)
    no = interp.run(_lesson("verify", "red box above right of blue cone", "left of"), index=1, seed=312)
    assert yes.expected == "success" and yes.correct, yes.answer.reason
    assert no.expected == "failure" and no.correct


def test_every_calculus_relation_has_a_converse_in_the_same_calculus() -> None:
    names = [r for c in calculi.CALCULI for r in c.relations]
    assert len(names) == len(set(names))  # one calculus per predicate
    for c in calculi.CALCULI:
        for r in c.relations:
            assert c.converse_of(r) in c.relations and c.converse_of(c.converse_of(r)) == r


def test_the_action_models_in_asp_are_exactly_the_declared_actions() -> None:
    text = asp.rule_path("actions.lp").read_text()
    modelled = set(re.findall(r"^action\((\w+)\(", text, re.M))
    assert modelled == set(actions.ACTIONS)
    for name in actions.ACTIONS:
        assert re.search(rf"^poss\({name}\(", text, re.M), f"{name} has no preconditions in actions.lp"


def test_channels_cover_the_catalogue_and_name_distinct_percepts() -> None:
    percepts = channels.of_percept()
    assert len(percepts) == sum(len(c.values) for c in channels.CHANNELS)
    assert {c.name for c in channels.CHANNELS} == {"shape", "colour", "size"}
    assert set(channels.SIZE.values) == set(catalog.SIZES)


def test_composites_use_declared_relations_and_parts() -> None:
    for comp in composites.COMPOSITES.values():
        for i, rel, j in comp.arrangement:
            assert relations.find(rel) == rel and 0 <= i < len(comp.parts) and 0 <= j < len(comp.parts)


def test_verbs_demonstrate_with_declared_actions() -> None:
    for v in actions.VERBS.values():
        assert all(step in actions.ACTIONS for step in v.steps)
        assert ("place" in v.steps) == v.takes_relation


def test_every_declared_converse_names_its_relation_back() -> None:
    """`relations.converse` (a direction's opposite, a symmetric word itself, a comparative's
    declared converse) is read by the original scripts' reader: one that did not name back
    would accept a sentence that says other than its table."""
    from aileen.domain import relations

    for name in relations.known():
        other = relations.converse(name)
        if other is not None:
            assert relations.converse(other) == relations.get(name).word, name
    assert relations.converse("larger than") == "smaller than" and relations.converse("near") == "near"
    assert relations.converse("on") is None
