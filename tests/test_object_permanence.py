"""Object permanence: an object the agent watched another being put on (or saw another resting
on) stays in its state, under that one, while a top-down camera cannot see it; and only then."""

from __future__ import annotations

import numpy as np
import pytest

from aileen.agent.body import WorldBody
from aileen.agent.core import Agent
from aileen.agent.records import AgentParams, ablation_params
from aileen.agent.state import Tracker
from aileen.curriculum import lessonfile
from aileen.curriculum.interpreter import Interpreter
from aileen.domain.calculi import MOVE_MIN, RESTS_ON
from aileen.perception.perceiver import Detection
from aileen.perception.truth import TruthVision
from aileen.terms import fn
from aileen.world.camera import DEFAULT_CAMERA
from aileen.world.render import render
from aileen.world.sim import World

RED_BOX = ("cv_box", "cv_red", "cv_large")
BLUE_BOX = ("cv_box", "cv_blue", "cv_small")
BLUE_SPHERE = ("cv_sphere", "cv_blue", "cv_small")


def _det(percepts: tuple[str, ...], x: float, y: float, half: float = 0.05, level: int = 0) -> Detection:
    return Detection(percepts, (x - half, y - half, x + half, y + half), (0.0, 0.0, 1.0, 1.0), level)


# ------------------------------------------------------------------ the tracker alone


def _put_on(t: Tracker, lower: tuple[str, ...] = BLUE_BOX) -> tuple[str, str]:
    """The red box is picked up from (0.7, 0.7) and put down over the lower object at (0.3, 0.3),
    which the camera then does not see; returns (upper id, lower id)."""
    up, low = t.assign([_det(RED_BOX, 0.7, 0.7, 0.065), _det(lower, 0.3, 0.3, 0.035)])
    assert t.assign([_det(lower, 0.3, 0.3, 0.035)], held=up) == [low]
    return up, low


def test_an_object_put_down_over_one_that_vanishes_stays_under_it() -> None:
    t = Tracker()
    up, low = _put_on(t)
    ids = t.assign([_det(RED_BOX, 0.31, 0.3, 0.065)], released=up)
    assert ids == [up, low]
    assert t.known[low].under == up and t.known[low].hidden and t.known[low].box_m == pytest.approx((0.265, 0.265, 0.335, 0.335))
    assert t.known[up].level == 1 and not t.known[up].hidden  # it rests on the hidden one
    assert t.known[low].note == f" (hidden under {up})" and t.known[up].note == " (on top)"


def test_without_permanence_the_hidden_object_is_gone() -> None:
    t = Tracker(permanence=False)
    up, low = _put_on(t)
    assert t.assign([_det(RED_BOX, 0.31, 0.3, 0.065)], released=up) == [up]
    assert t.known[up].level == 0


def test_an_object_seen_resting_on_another_keeps_it_when_that_one_vanishes() -> None:
    t = Tracker()
    low, up = t.assign([_det(BLUE_BOX, 0.3, 0.3), _det(RED_BOX, 0.32, 0.3, level=1)])
    # a later frame: the lower one is not seen (nothing was moved), the upper one read on the table
    assert t.assign([_det(RED_BOX, 0.325, 0.3)]) == [up, low]
    assert t.known[low].under == up and t.known[up].level == 1
    assert t.assign([_det(RED_BOX, 0.32, 0.3)]) == [up, low]  # and it stays so
    # an object on the table that vanishes (no upper one seen on it) is not kept
    t2 = Tracker()
    a, b = t2.assign([_det(BLUE_BOX, 0.3, 0.3), _det(RED_BOX, 0.38, 0.3)])
    assert t2.assign([_det(RED_BOX, 0.38, 0.3)]) == [b]


def test_lifting_the_upper_object_ends_the_memory() -> None:
    t = Tracker()
    up, low = _put_on(t)
    t.assign([_det(RED_BOX, 0.31, 0.3, 0.065)], released=up)
    assert t.assign([], held=up) == []  # lifted, and the lower one not seen either: nothing kept
    assert t.hidden == {}
    # put back, it is not "put down over" an object last seen hidden: the memory needs a sighting
    assert t.assign([_det(BLUE_BOX, 0.3, 0.3, 0.035)]) == [low]  # seen again where it was
    assert t.known[low].under is None and low not in t.moved


def test_a_moved_upper_object_ends_the_memory() -> None:
    t = Tracker()
    up, low = _put_on(t)
    t.assign([_det(RED_BOX, 0.31, 0.3, 0.065)], released=up)
    # within MOVE_MIN of where the memory began, frame after frame: kept
    assert t.assign([_det(RED_BOX, 0.31 + MOVE_MIN * 0.9, 0.3, 0.065)]) == [up, low]
    assert t.assign([_det(RED_BOX, 0.31 + MOVE_MIN * 1.2, 0.3, 0.065)]) == [up]
    assert t.known[low].under is None and t.known[up].level == 0


def test_seeing_the_lower_object_again_ends_the_memory() -> None:
    t = Tracker()
    up, low = _put_on(t)
    t.assign([_det(RED_BOX, 0.31, 0.3, 0.065)], released=up)
    assert t.assign([_det(RED_BOX, 0.31, 0.3, 0.065), _det(BLUE_BOX, 0.3, 0.3, 0.035)]) == [up, low]
    assert t.hidden == {} and t.known[low].under is None


def test_nothing_is_kept_that_nothing_hides() -> None:
    # the object put down lies beside where the vanished one was
    t = Tracker()
    up, low = _put_on(t)
    assert t.assign([_det(RED_BOX, 0.45, 0.3, 0.065)], released=up) == [up]
    # a sphere has no flat top: nothing rests on it, so nothing put there hides it
    t = Tracker()
    up, low = _put_on(t, BLUE_SPHERE)
    assert t.assign([_det(RED_BOX, 0.31, 0.3, 0.065)], released=up) == [up]
    # the object the hand holds is out of view for that reason
    t = Tracker()
    low, up = t.assign([_det(BLUE_BOX, 0.3, 0.3), _det(RED_BOX, 0.32, 0.3, level=1)])
    assert t.assign([_det(RED_BOX, 0.32, 0.3)], held=low) == [up]


def test_where_every_object_stays_in_view_nothing_changes() -> None:
    rng = np.random.default_rng(5)
    kinds = [RED_BOX, BLUE_BOX, ("cv_cylinder", "cv_green", "cv_medium")]
    on, off = Tracker(), Tracker(permanence=False)
    xy = rng.uniform(0.1, 0.9, size=(3, 2))
    for _ in range(30):
        xy += rng.normal(0.0, 0.02, size=xy.shape)
        frame = [_det(k, float(x), float(y), level=int(rng.integers(2))) for k, (x, y) in zip(kinds, xy)]
        assert on.assign(frame) == off.assign(frame)
        assert on.known == off.known and on.moved == off.moved


def test_the_switch_is_a_mechanism_of_without() -> None:
    assert ablation_params(["object-permanence"]) == {"object_permanence": False}
    assert Agent(params=AgentParams(object_permanence=False)).tracker.permanence is False


# ------------------------------------------------------------------ the agent, the world and its eyes


class HiddenTruth(TruthVision):
    """Ground truth as a top-down camera has it: an object under 10 % visible is not seen, and
    an object on one not seen is read on the table (as the shipped detector reads it)."""

    def __call__(self, image: np.ndarray) -> list[Detection]:
        frame = self._frame
        assert frame is not None
        seen = {t.id for t in frame.truth if t.visible >= 0.1}
        out = []
        for t, d in zip(frame.truth, super().__call__(image)):
            if t.id in seen:
                out.append(Detection(d.percepts, d.box_m, d.box_px, d.level if t.on in seen else 0, d.footprint))
        return out


TAUGHT = """
[[lesson]]
signal = "inform"
content = "red box"
objects = ["red box"]

[[lesson]]
signal = "inform"
content = "blue box"
objects = ["blue box"]

[[lesson]]
signal = "inform"
content = "red box on blue box"
objects = ["medium red box", "medium blue box"]
relation = "on"

[[lesson]]
signal = "inform"
content = "blue box on red box"
objects = ["small blue box", "large red box"]
relation = "on"

[[lesson]]
note = "the upper one's box over the lower one's (RCC8 tppi), which shows"
signal = "inform"
content = "red box on blue box"
objects = ["medium red box", "small blue box"]
relation = "on"
seed = 1

[[lesson]]
note = "the two boxes alike (RCC8 eq)"
signal = "inform"
content = "red box on blue box"
objects = ["medium red box", "small blue box"]
relation = "on"
seed = 0
"""


def _taught(permanence: bool, eyes: str) -> tuple[Agent, HiddenTruth | None]:
    """An agent taught two colour words and "on" (the trainer's layouts, supports in sight)."""
    truth = HiddenTruth() if eyes == "truth" else None
    agent = Agent(params=AgentParams(object_permanence=permanence), perceiver=truth)
    interp = Interpreter(agent, on_frame=truth.see_frame if truth is not None else None)
    for _ in interp.run_all(lessonfile.loads(TAUGHT), seed=0):
        pass
    return agent, truth


def _stack(agent: Agent, truth: HiddenTruth | None, upper_size: str, lower_size: str):
    """The trainer puts a red box centred on a blue one while the agent watches; returns the
    world, the body, the two world ids and the lower one's visible share."""
    world = World()
    low = world.add("box", "blue", 0.3, 0.3, size=lower_size)
    up = world.add("box", "red", 0.65, 0.45, size=upper_size)
    body = WorldBody(world, seed=3, noise=2.0, on_frame=truth.see_frame if truth is not None else None)
    agent.new_scene()
    agent.perceive(body.look())
    u, v = DEFAULT_CAMERA.to_pixels(0.65, 0.45)
    world.pick_up(up)
    agent.watch("pick_up", u, v, body.look())
    world.place(up, 0.3, 0.3, onto=low)
    visible = next(t.visible for t in render(world, seed=0).truth if t.id == low)
    agent.watch("place", None, None, body.look())
    return world, body, up, low, visible


@pytest.mark.parametrize("eyes", ["detector", "truth"])
@pytest.mark.parametrize("sizes", [("large", "small"), ("medium", "medium")])
def test_an_object_put_on_one_it_hides_rests_on_it_until_lifted(eyes: str, sizes: tuple[str, str]) -> None:
    for permanence in (True, False):
        agent, truth = _taught(permanence, eyes)
        world, body, up, low, visible = _stack(agent, truth, *sizes)
        assert visible < 0.1 and world.get(up).on == low  # the support is hidden, the stack holds
        assert agent.state is not None
        if not permanence:
            assert [s.percepts[1] for s in agent.state.objects.values()] == ["cv_red"]  # the blue box is gone
            assert not any(f.name == RESTS_ON for f in agent.state.facts)
            continue
        under = [s for s in agent.state.objects.values() if s.hidden]
        assert len(agent.state.objects) == 2 and len(under) == 1 and under[0].percepts[1] == "cv_blue"
        top = under[0].under
        assert top is not None and agent.state.objects[top].level == 1
        assert fn(RESTS_ON, top, under[0].id) in agent.state.facts
        assert f"(hidden under {top})" in " ".join(agent.describe_scene())
        # the trainer lifts the red box again: the blue one is seen, the memory is over
        u, v = DEFAULT_CAMERA.to_pixels(0.3, 0.3)
        world.pick_up(up)
        agent.watch("pick_up", u, v, body.look())
        assert agent.held == top
        assert [(s.id, s.hidden) for s in agent.state.objects.values()] == [(under[0].id, False)]


@pytest.mark.parametrize("eyes", ["detector", "truth"])
def test_the_agent_verifies_an_object_on_one_it_hides(eyes: str) -> None:
    answers = {}
    for permanence in (True, False):
        agent, truth = _taught(permanence, eyes)
        _stack(agent, truth, "large", "small")
        answers[permanence] = agent.verify("red box on blue box").result
    assert answers == {True: "success", False: "failure"}


def test_a_hidden_mark_is_labelled_and_never_read_as_seen() -> None:
    from aileen.web import overlay
    from aileen.web.view import seen_at

    hidden = overlay.Mark("o1", BLUE_BOX, (10.0, 10.0, 20.0, 20.0), under="o2")
    assert hidden.label == "o1 small blue box (hidden under o2)" and hidden.to_json()["under"] == "o2"
    assert "under" not in overlay.Mark("o2", RED_BOX, (0.0, 0.0, 30.0, 30.0)).to_json()
    assert seen_at([hidden], 15.0, 15.0) is None
    assert seen_at([hidden, overlay.Mark("o2", RED_BOX, (5.0, 5.0, 25.0, 25.0))], 15.0, 15.0) == "o2"
