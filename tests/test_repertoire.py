"""The wider repertoire at the agent's level (ground-truth vision, so these stay fast): sizes,
comparatives, generation, composite words; and their bad input."""

from __future__ import annotations

import re
from types import SimpleNamespace

import numpy as np
import pytest

from aileen.agent import Agent
from aileen.curriculum.interpreter import Interpreter
from aileen.curriculum.lesson import Lesson, ObjectSpec, parse_object
from aileen.curriculum.lessonfile import loads
from aileen.errors import UserError
from aileen.perception.size import measure_size
from aileen.perception.truth import TruthVision
from aileen.world import catalog
from aileen.world.camera import DEFAULT_CAMERA
from aileen.world.render import render
from aileen.world.sim import World


def make() -> tuple[Agent, Interpreter]:
    vision = TruthVision()
    agent = Agent(perceiver=vision)
    return agent, Interpreter(agent, on_frame=vision.see_frame)


def run(interp: Interpreter, signal: str, content: str, objects: list[str], seed: int, **kw):
    return interp.run(Lesson(signal, content, [parse_object(o) for o in objects], **kw), index=1, seed=seed)


@pytest.mark.parametrize("seed", range(3))
def test_size_is_measured_from_the_objects_own_pixels_at_any_turn(seed: int) -> None:
    rng = np.random.default_rng(seed)
    w = World()
    truth = {}
    for x, y in [(0.2, 0.2), (0.5, 0.5), (0.8, 0.8), (0.2, 0.8), (0.8, 0.2)]:
        size = list(catalog.SIZES)[int(rng.integers(3))]
        obj = w.add(catalog.SHAPES[int(rng.integers(4))], catalog.COLOURS[int(rng.integers(5))], x, y, size=size,
                    shade=int(rng.integers(4)), angle=float(rng.uniform(0, 1.6)))
        truth[obj] = size
    frame = render(w, seed=seed, noise=2.0)
    for t in frame.truth:
        seen = SimpleNamespace(box_px=t.box_px, shape=t.shape)  # what the detector reports
        assert measure_size(frame.image, seen, DEFAULT_CAMERA)[0] == truth[t.id]


def test_three_word_phrases_teach_a_size_word_beside_colour_and_shape_words() -> None:
    agent, interp = make()
    for i, (said, shown) in enumerate([("red box", "small red box"), ("blue cone", "large blue cone"),
                                       ("red cone", "red cone"), ("blue box", "large blue box")]):
        run(interp, "inform", said, [shown], seed=10 + i)
    r = run(interp, "inform", "large red box", ["large red box"], seed=20)
    assert r.answer.created == ["r_large"]
    assert agent.meaning("r_large") == frozenset({parse_one("cv_large")})
    yes = run(interp, "verify", "large blue cone", ["large blue cone"], seed=21, distractors=2)
    no = run(interp, "verify", "large red cone", ["small red cone"], seed=22)
    assert yes.correct and no.correct


def parse_one(text: str):
    from aileen.terms import Term

    return Term(text)


def test_comparatives_are_learned_over_the_size_comparison_and_hold_either_way_round() -> None:
    agent, interp = make()
    for i, o in enumerate(["small red box", "large blue cone", "green sphere", "blue box", "small green cone"]):
        spec = parse_object(o)
        run(interp, "inform", f"{spec.colour} {spec.shape}", [o], seed=30 + i)
    for i, (a, b) in enumerate([("red box", "blue cone"), ("green sphere", "red box")]):
        run(interp, "inform", f"{a} larger than {b}", [a, b], seed=40 + i, relation="larger than")
    ok = run(interp, "verify", "blue cone larger than green sphere", ["blue cone", "green sphere"], seed=50,
             relation="larger than")
    wrong = run(interp, "verify", "red box larger than blue cone", ["red box", "blue cone"], seed=51,
                relation="smaller than")
    same = Lesson("verify", "green sphere larger than red box",
                  [ObjectSpec("sphere", "green"), ObjectSpec("box", "red")], relation="larger than", near_miss=True)
    miss = interp.run(same, index=1, seed=52)
    assert ok.correct and ok.expected == "success"
    assert wrong.correct and wrong.expected == "failure"
    assert miss.correct and miss.expected == "failure"


def test_generate_says_learned_words_in_the_trainers_order_and_leaves_out_what_it_cannot_name() -> None:
    agent, interp = make()
    for i, (said, shown) in enumerate([("red box", "small red box"), ("green cone", "large green cone"),
                                       ("blue box", "blue box"), ("large red box", "large red box"),
                                       ("small blue box", "small blue box")]):
        run(interp, "inform", said, [shown], seed=60 + i)
    one = run(interp, "generate", "", ["large green box"], seed=70)
    assert one.answer.said == "large green box" and one.correct
    unknown_colour = run(interp, "generate", "", ["large yellow box"], seed=71)
    assert unknown_colour.answer.said == "large box" and unknown_colour.correct
    nothing = run(interp, "generate", "", ["purple sphere"], seed=72)
    assert nothing.answer.said == "something" and nothing.answer.result == "failure"


def test_generate_names_a_relation_that_holds_between_two_objects() -> None:
    agent, interp = make()
    for i, o in enumerate(["red box", "blue cone", "green sphere", "red cone", "blue sphere", "green box"]):
        run(interp, "inform", o, [o], seed=80 + i)
    for i, (a, b, rel) in enumerate([("red box", "blue cone", "left of"), ("green sphere", "red box", "behind")]):
        run(interp, "inform", f"{a} {rel} {b}", [a, b], seed=90 + i, relation=rel)
    r = run(interp, "generate", "", ["blue cone", "green sphere"], seed=95, relation="behind")
    assert r.answer.said in ("blue cone behind green sphere", "green sphere left of blue cone",
                             "blue cone left of green sphere", "green sphere behind blue cone")
    assert r.correct  # what it chose is true of the table


def test_a_word_said_alone_over_several_objects_is_learned_for_the_group() -> None:
    agent, interp = make()
    first = interp.run(Lesson("inform", "wall", [ObjectSpec("box")] * 3, composite="wall"), index=1, seed=100)
    assert first.answer.created == ["r_wall"]
    found = interp.run(Lesson("verify", "wall", [ObjectSpec("box")] * 3, composite="wall", distractors=2),
                       index=1, seed=101)
    scattered = interp.run(Lesson("verify", "wall", [ObjectSpec("box")] * 3, distractors=1), index=1, seed=102)
    assert found.expected == "success" and found.correct and len(next(iter(found.answer.referents.values()))) == 3
    assert scattered.expected == "failure" and scattered.correct


@pytest.mark.parametrize("text, message", [
    ('[[lesson]]\nsignal = "generate"\n', "a generate lesson needs something on the table"),
    ('[[lesson]]\nsignal = "inform"\ncontent = "wall"\ncomposite = "wall"\nobjects = ["box", "box"]\n',
     "has 3 parts, 2 objects given"),
    ('[[lesson]]\nsignal = "inform"\ncontent = "red box nera blue box"\nobjects = ["red box", "blue box"]\n'
     'relation = "nera"\n', "unknown relation 'nera'; expected one of: left of"),
    ('[[lesson]]\nsignal = "inform"\ncontent = "push it"\nobjects = ["red box"]\naction = "shove"\n',
     "expected '<verb> [<relation>]' with verb one of move, push"),
    ('[[lesson]]\nsignal = "inform"\ncontent = "huge box"\nobjects = [{ shape = "box", size = "huge" }]\n',
     "unknown size 'huge'; expected one of: small, medium, large"),
    ('[[lesson]]\nsignal = "inform"\ncontent = "move red box larger than blue box"\nobjects = ["red box", '
     '"blue box"]\naction = "move larger than"\n', "where it stands does not decide that"),
])
def test_bad_repertoire_input_names_the_file_line_and_what_was_expected(text: str, message: str) -> None:
    with pytest.raises(UserError, match=re.escape(message)) as err:
        loads(text, "bad.toml")
    assert err.value.format().startswith("bad.toml:")
