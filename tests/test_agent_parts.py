"""The agent is made of parts, not mixins (issue 21): each part keeps its own caches, and a
copy of the agent (the console's undo, `forget`) is a whole agent whose parts are its own.

Why test the back-references: `restore` and `forget` copy the agent's namespace into the agent
the caller holds; a part copied with it that still pointed at the snapshot would read the
snapshot's memories, and learning after an undo would go into a memory nobody holds.
"""

from __future__ import annotations

from aileen.agent import Agent
from aileen.agent.part import Part
from aileen.curriculum.interpreter import Interpreter
from aileen.curriculum.lesson import Lesson, ObjectSpec
from aileen.perception.truth import TruthVision

PARTS = ("reading", "grounding", "demonstrations", "composites", "learning", "acting", "generation", "feedback")


class _SharedVision(TruthVision):
    """Ground-truth eyes that a copy of the agent shares, as it shares the shipped vision."""

    def __deepcopy__(self, memo: dict) -> "_SharedVision":
        return self


def _taught() -> tuple[Agent, Interpreter]:
    vision = _SharedVision()
    agent = Agent(perceiver=vision)
    interp = Interpreter(agent, on_frame=vision.see_frame)
    for i, (colour, shape) in enumerate((("red", "box"), ("blue", "cone"))):
        interp.run(Lesson("inform", f"{colour} {shape}", [ObjectSpec(shape, colour)]), index=i, seed=i)
    return agent, interp


def _parts_belong_to(agent: Agent) -> None:
    for name in PARTS:
        part = getattr(agent, name)
        assert isinstance(part, Part) and part.agent is agent, name
    assert agent.lexicon._meaning_of.__self__ is agent  # the lexicon reads this agent's memory


def test_the_agent_inherits_no_job() -> None:
    assert Agent.__mro__ == (Agent, object)
    agent, _ = _taught()
    _parts_belong_to(agent)
    # the parts' caches are theirs, not the agent's namespace
    assert not {"_evidence", "_direction_seen", "_pins", "_relation_claims", "_said", "_discourse"} & set(vars(agent))


def test_a_restored_agent_owns_its_parts_and_learns_into_its_own_memory() -> None:
    agent, interp = _taught()
    snap = agent.snapshot()
    _parts_belong_to(snap)
    interp.run(Lesson("inform", "green sphere", [ObjectSpec("sphere", "green")]), index=5, seed=5)
    agent.restore(snap)
    _parts_belong_to(agent)
    assert agent.semantic.concept("green") is None
    r = interp.run(Lesson("inform", "green cylinder", [ObjectSpec("cylinder", "green")]), index=6, seed=6)
    assert "r_green" in r.answer.created and "r_green" in agent.memory and "r_green" not in snap.memory


def test_a_forgetting_agent_owns_its_parts() -> None:
    agent, interp = _taught()
    assert agent.forget("r_cone") == "cone"
    _parts_belong_to(agent)
    r = interp.run(Lesson("verify", "blue cone", [ObjectSpec("cone", "blue")]), index=7, seed=7)
    assert r.answer.result == "failure" and "cone" in (r.answer.reason or "")
