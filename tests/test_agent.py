"""The agent's behaviour over lessons: active learning, verify, specificity, react.

These use ground-truth vision (`TruthVision`) so that they test learning and acting, not
the detector; `test_agent_detector.py` runs the same loop through the shipped detector.
"""

from __future__ import annotations

import pytest

from aileen.agent import Agent
from aileen.curriculum.interpreter import Interpreter
from aileen.curriculum.lesson import ActionSpec, Lesson, ObjectSpec
from aileen.memory.episodic import EpisodicMemory
from aileen.memory.semantic import SemanticMemory, concept_symbol, from_concepts
from aileen.perception.truth import TruthVision
from aileen.terms import Term, parse


def make() -> tuple[Agent, Interpreter]:
    vision = TruthVision()
    agent = Agent(perceiver=vision)
    return agent, Interpreter(agent, on_frame=vision.see_frame)


def obj(text: str) -> ObjectSpec:
    colour, shape = text.split()
    return ObjectSpec(shape, colour)


def inform(interp: Interpreter, content: str, objects: list[str], seed: int, **kw):
    return interp.run(Lesson("inform", content, [obj(o) for o in objects], **kw), index=1, seed=seed)


def verify(interp: Interpreter, content: str, objects: list[str], seed: int, **kw):
    return interp.run(Lesson("verify", content, [obj(o) for o in objects], **kw), index=1, seed=seed)


def teach_visual(interp: Interpreter) -> None:
    for i, o in enumerate(["red box", "blue cylinder", "red cylinder", "blue box", "green cone", "red cone"]):
        inform(interp, o, [o], seed=100 + i)


def test_first_lesson_creates_and_stores_each_unknown_word() -> None:
    agent, interp = make()
    r = inform(interp, "red box", ["red box"], seed=1)
    assert r.answer.result == "failure"
    assert "I do not know the word 'red'" in r.answer.reason
    assert sorted(r.answer.created) == ["r_box", "r_red"]
    assert sorted(r.answer.stored) == ["r_box", "r_red"]
    assert r.answer.commands == 4
    assert agent.semantic.concept("red") == "r_red"


def test_active_learning_stores_nothing_when_the_lesson_is_understood() -> None:
    agent, interp = make()
    inform(interp, "red box", ["red box"], seed=1)
    before = agent.memory.to_dict()
    again = inform(interp, "red box", ["red box"], seed=2)
    assert again.answer.result == "success"
    assert again.answer.commands == 0
    assert agent.memory.to_dict() == before


def test_verify_with_an_unknown_word_fails_with_that_reason() -> None:
    agent, interp = make()
    inform(interp, "red box", ["red box"], seed=1)
    r = verify(interp, "green box", ["green box"], seed=3)
    assert r.answer.result == "failure"
    assert "I do not know the word 'green'" in r.answer.reason
    assert r.answer.commands == 0  # verify never learns


def test_specificity_red_does_not_fire_on_blue() -> None:
    agent, interp = make()
    teach_visual(interp)
    assert verify(interp, "red box", ["red box"], seed=7, distractors=2).answer.result == "success"
    r = verify(interp, "red box", ["blue box"], seed=8)
    assert r.answer.result == "failure"
    assert r.correct is True
    assert verify(interp, "blue cylinder", ["red cylinder"], seed=9, distractors=1).answer.result == "failure"


def test_mutual_exclusivity_separates_words_taught_together() -> None:
    """After "green cone" (both new) and "red cone", `cone` means the shape alone, so
    `green` must no longer need a cone: "green box" is recognised once "box" is known."""
    agent, interp = make()
    inform(interp, "green cone", ["green cone"], seed=1)
    inform(interp, "red cone", ["red cone"], seed=2)
    inform(interp, "blue box", ["blue box"], seed=3)
    inform(interp, "yellow box", ["yellow box"], seed=4)
    r = verify(interp, "green box", ["green box"], seed=5, distractors=2)
    assert r.answer.result == "success", r.answer.reason
    # and it stays specific: a green box is not a "green cone"
    assert verify(interp, "green cone", ["green box"], seed=6).answer.result == "failure"


def test_relation_is_learned_from_one_example_when_the_objects_are_known() -> None:
    agent, interp = make()
    teach_visual(interp)
    r = inform(interp, "red box left of blue cylinder", ["red box", "blue cylinder"], seed=20, relation="left of")
    assert r.answer.created == ["r_left_of"]
    assert r.answer.stored == ["r_left_of"]
    # the example leaves out the percepts the known words account for
    ex = agent.memory.examples("r_left_of")[0]
    assert not any("cv_" in f for f in ex)
    ok = verify(interp, "green cone left of red cone", ["green cone", "red cone"], seed=21, relation="left of",
                distractors=2)
    assert ok.answer.result == "success", ok.answer.reason
    wrong = verify(interp, "green cone left of red cone", ["green cone", "red cone"], seed=22, relation="behind")
    assert wrong.answer.result == "failure"
    assert "'left of' does not hold" in wrong.answer.reason


def teach_move_right(interp: Interpreter) -> None:
    teach_visual(interp)
    inform(interp, "red box right of blue cylinder", ["red box", "blue cylinder"], seed=30, relation="right of")
    for i, (a, b) in enumerate([("red box", "blue cylinder"), ("blue box", "red cylinder")]):
        inform(interp, f"move the {a} right of the {b}", [a, b], seed=40 + i, action=ActionSpec("move", "right of"))


def test_react_after_a_demonstration_reaches_the_goal_in_the_world() -> None:
    agent, interp = make()
    teach_move_right(interp)
    lesson = Lesson("react", "move the red cylinder right of the blue box", [obj("red cylinder"), obj("blue box")],
                    action=ActionSpec("move", "right of"), distractors=2)
    r = interp.run(lesson, index=1, seed=50)
    assert r.answer.result == "success", r.answer.reason
    assert r.goal_holds is True  # the trainer's own ground truth, not the agent's belief
    assert r.answer.steps[0] == "pick_up(o1)"
    assert r.answer.steps[1].startswith("place(o1)")
    assert r.answer.projections == 2


def test_action_verify_composes_with_the_relation() -> None:
    agent, interp = make()
    teach_move_right(interp)
    right = interp.run(Lesson("verify", "move the green cone right of the red box", [obj("green cone"), obj("red box")],
                              action=ActionSpec("move", "right of")), index=1, seed=60)
    assert right.answer.result == "success", right.answer.reason
    left = interp.run(Lesson("verify", "move the green cone right of the red box", [obj("green cone"), obj("red box")],
                             action=ActionSpec("move", "left of")), index=1, seed=61)
    assert left.answer.result == "failure"


def test_react_with_an_unknown_action_says_so_and_leaves_the_world_valid() -> None:
    agent, interp = make()
    teach_visual(interp)
    lesson = Lesson("react", "move the red box right of the blue box", [obj("red box"), obj("blue box")],
                    action=ActionSpec("move", "right of"))
    r = interp.run(lesson, index=1, seed=70)
    assert r.answer.result == "failure"
    assert "I do not know the word 'move'" in r.answer.reason  # the verb alone (one verb for every relation)
    assert r.answer.steps == []


def test_semantic_memory_round_trips_through_the_concept_memory() -> None:
    agent, interp = make()
    teach_visual(interp)
    sem = from_concepts(agent.memory)
    assert sem.words() == agent.semantic.words()
    assert sem.kind("r_red") == "visual"
    assert concept_symbol("left of") == "r_left_of"
    with pytest.raises(ValueError):
        SemanticMemory().add("red", "colour")


def test_episodic_trace_is_the_papers_table_1_form() -> None:
    ep = EpisodicMemory()
    ep.record([parse("isa(o1,cv_red)"), parse("e(o1,o2)"), parse("dc(o1,o2)"), parse("n(o3,o1)")])
    ep.record([parse("held(o1)")], action=parse("pick_up(o1)"))
    ep.record([parse("w(o1,o2)"), parse("dc(o1,o2)")], action=parse("place(o1)"))
    trace = [str(t) for t in ep.trace(0, [Term("o1"), Term("o2")])]
    assert trace == [
        "isa(t0,start)", "h(t0,e(o1,o2))", "h(t0,dc(o1,o2))",
        "after(t1,t0)", "h(t1,held(o1))",
        "after(t2,t1)", "h(t2,w(o1,o2))", "h(t2,dc(o1,o2))",
    ]
    with pytest.raises(IndexError):
        ep.trace(2, [Term("o1")], end=1)


def test_same_seed_same_transcript() -> None:
    def run() -> list[tuple]:
        agent, interp = make()
        out = []
        for i, o in enumerate(["red box", "blue cone", "red cone"]):
            r = inform(interp, o, [o], seed=i)
            out.append((r.answer.result, r.answer.reason, tuple(r.answer.stored), tuple(r.seen)))
        return out

    assert run() == run()


def test_mutual_exclusivity_propagates_through_words_pinned_later() -> None:
    """'red cylinder', then 'cone' shown on a red cone, then 'purple cylinder': cylinder is
    the shape, so red is the colour, so the red in the 'cone' example was red's: a green cone
    is a cone. (One step of exclusion is not enough; the meanings must reach a fixpoint.)"""
    agent, interp = make()
    inform(interp, "red cylinder", ["red cylinder"], seed=0)
    interp.run(Lesson("inform", "cone", [ObjectSpec("cone", "red")]), index=2, seed=1)
    inform(interp, "purple cylinder", ["purple cylinder"], seed=2)
    r = interp.run(Lesson("verify", "cone", [ObjectSpec("cone", "green")]), index=4, seed=3)
    assert r.answer.result == "success", r.answer.reason
    assert interp.run(Lesson("verify", "cone", [ObjectSpec("box", "red")]), index=5, seed=4).answer.result == "failure"


def test_syntactic_bootstrapping_splits_two_new_words_at_first_sight() -> None:
    """Once pinned words show that modifiers name colours and head nouns shapes, a phrase of
    two new words ("red sphere") is split at once: red is the colour, sphere the shape."""
    agent, interp = make()
    for i, o in enumerate(["green box", "green cone", "blue box"]):
        inform(interp, o, [o], seed=10 + i)
    inform(interp, "red sphere", ["red sphere"], seed=20)
    assert verify(interp, "red box", ["red box"], seed=21, distractors=2).answer.result == "success"
    assert verify(interp, "blue sphere", ["blue sphere"], seed=22).answer.result == "success"
    assert verify(interp, "green sphere", ["green sphere"], seed=23, distractors=1).answer.result == "success"
    assert verify(interp, "red sphere", ["red cone"], seed=24).answer.result == "failure"


def test_without_syntactic_bootstrapping_two_new_words_stay_entangled() -> None:
    vision = TruthVision()
    from aileen.agent import AgentParams

    agent = Agent(perceiver=vision, params=AgentParams(syntactic_bootstrapping=False))
    interp = Interpreter(agent, on_frame=vision.see_frame)
    for i, o in enumerate(["green box", "green cone", "blue box"]):
        inform(interp, o, [o], seed=10 + i)
    inform(interp, "red sphere", ["red sphere"], seed=20)
    assert verify(interp, "red box", ["red box"], seed=21, distractors=2).answer.result == "failure"


def test_saved_memory_keeps_the_lexicon(tmp_path) -> None:
    from aileen.memory.concept import ConceptMemory

    agent, interp = make()
    for i, o in enumerate(["green box", "green cone", "blue box"]):
        inform(interp, o, [o], seed=10 + i)
    path = tmp_path / "m.json"
    agent.save(str(path))
    memory = ConceptMemory.load(path)
    vision = TruthVision()
    again = Agent(memory, from_concepts(memory), perceiver=vision)
    assert again.positions == agent.positions
    interp2 = Interpreter(again, on_frame=vision.see_frame)
    inform(interp2, "red sphere", ["red sphere"], seed=20)
    assert verify(interp2, "red box", ["red box"], seed=21).answer.result == "success"


def test_an_agent_built_on_a_trained_memory_reads_words_the_same_way() -> None:
    agent, interp = make()
    for i, o in enumerate(["green box", "green cone", "blue box"]):
        inform(interp, o, [o], seed=10 + i)
    inform(interp, "red sphere", ["red sphere"], seed=20)
    vision = TruthVision()
    fresh = Agent(agent.memory, agent.semantic, perceiver=vision)
    assert fresh.positions == agent.positions
    r = Interpreter(fresh, on_frame=vision.see_frame).run(Lesson("verify", "red box", [obj("red box")]), index=1, seed=21)
    assert r.answer.result == "success", r.answer.reason


def test_verify_holds_when_the_referent_is_not_unique_but_react_needs_one() -> None:
    agent, interp = make()
    teach_move_right(interp)
    two = [obj("red box"), obj("red box")]
    r = interp.run(Lesson("verify", "red box", two), index=1, seed=80)
    assert r.answer.result == "success", r.answer.reason
    assert len(r.answer.referents["red box"]) == 2
    react = interp.run(Lesson("react", "move the red box right of the blue cylinder",
                              [obj("red box"), obj("blue cylinder"), obj("red box")],
                              action=ActionSpec("move", "right of")), index=2, seed=81)
    assert react.answer.result == "failure"
    assert "more than one 'red box'" in react.answer.reason
    assert react.answer.steps == []


def test_a_word_is_part_of_a_word_said_with_it_as_a_run_of_words() -> None:
    from aileen.memory.semantic import concept_symbol, part_of

    def part(a: str, b: str) -> bool:
        return part_of(concept_symbol(a), concept_symbol(b))

    assert part("right of", "behind right of") and part("behind", "behind right of")
    assert part("left of", "far left of")
    assert not part("in front of", "front left of")  # not a run of its words
    assert not part("left of", "left of")  # nor the word itself
    assert not part("righ", "right of") and not part("behind right of", "behind")
