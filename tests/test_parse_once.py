"""A lesson's sentence is parsed once (issue 21): the agent reads it (`Reading.read`), and
comprehension, learning, acting and the trainer's verdict on the answer all take that parse.

Counted by patching the parser the agent's modules call (`aileen.reasoning.language.parse`),
counting only calls made inside the agent's signals and verdicts (the trainer reads the
sentence too, to lay the scene out and grade: that is the trainer's reading, not the agent's).
"""

from __future__ import annotations

import functools
from collections import Counter

import pytest

from aileen.agent import Agent, AgentParams
from aileen.curriculum.interpreter import Interpreter
from aileen.curriculum.lesson import ActionSpec, Lesson, ObjectSpec
from aileen.perception.truth import TruthVision
from aileen.reasoning import language

SIGNALS = ("inform", "verify", "react", "generate", "told_wrong", "told_right", "confirmed")


class Counted:
    """An agent whose parses are counted per lesson, with its interpreter."""

    def __init__(self, monkeypatch: pytest.MonkeyPatch) -> None:
        v = TruthVision()
        self.agent = Agent(params=AgentParams(seed=0), perceiver=v)
        self.interp = Interpreter(self.agent, on_frame=v.see_frame)
        self.inside = 0
        self.parses: Counter[str] = Counter()
        real = language.parse

        def parse(sentence: str, **kw):  # noqa: ANN003, ANN202
            if self.inside:
                self.parses[sentence] += 1
            return real(sentence, **kw)

        monkeypatch.setattr(language, "parse", parse)
        for name in SIGNALS:
            monkeypatch.setattr(self.agent, name, self._counting(getattr(self.agent, name)))

    def _counting(self, method):  # noqa: ANN001, ANN202
        @functools.wraps(method)
        def call(*a, **kw):  # noqa: ANN002, ANN003, ANN202
            self.inside += 1
            try:
                return method(*a, **kw)
            finally:
                self.inside -= 1
        return call

    def run(self, lesson: Lesson, seed: int):  # noqa: ANN201
        self.parses.clear()
        return self.interp.run(lesson, index=1, seed=seed)


def _o(text: str) -> ObjectSpec:
    colour, shape = text.split()
    return ObjectSpec(shape, colour)


def _teach_objects(c: Counted, objs: list[str]) -> None:
    for i, o in enumerate(objs):
        c.run(Lesson("inform", o, [_o(o)]), seed=i)
        assert c.parses == {o: 1}


def test_inform_verify_and_the_verdicts_parse_the_sentence_once(monkeypatch) -> None:
    c = Counted(monkeypatch)
    _teach_objects(c, ["red box", "blue cylinder", "green cone"])
    r = c.run(Lesson("inform", "red box left of blue cylinder", [_o("red box"), _o("blue cylinder")],
                     relation="left of"), seed=10)
    assert r.answer.created == ["r_left_of"] and c.parses == {"red box left of blue cylinder": 1}
    # a wrong "no": learned as an inform lesson, from the verify's parse
    r = c.run(Lesson("verify", "green cone", [_o("green cone")], expect="failure", feedback="wrong"), seed=11)
    assert c.parses == {"green cone": 1}
    r = c.run(Lesson("verify", "red cone", [_o("red cone")], expect="success", feedback="wrong"), seed=12)
    assert r.answer.result == "failure" and "r_cone" not in r.answer.created  # cone is known
    assert c.parses == {"red cone": 1}
    # a wrong "yes": near misses, from the verify's parse
    r = c.run(Lesson("verify", "blue cylinder left of red box", [_o("blue cylinder"), _o("red box")],
                     relation="right of", expect="failure", feedback="wrong"), seed=13)
    assert c.parses == {"blue cylinder left of red box": 1}
    # a "no" let stand (told_right)
    r = c.run(Lesson("verify", "red box left of blue cylinder", [_o("red box"), _o("blue cylinder")],
                     relation="right of", expect="failure", feedback="wrong"), seed=14)
    assert c.parses == {"red box left of blue cylinder": 1}


def test_a_confirmed_react_parses_the_sentence_once(monkeypatch) -> None:
    c = Counted(monkeypatch)
    _teach_objects(c, ["red cylinder", "blue box", "green cone"])
    for i, (a, b) in enumerate([("red cylinder", "blue box"), ("green cone", "red cylinder")]):
        said = f"move {a} right of {b}"
        c.run(Lesson("inform", said, [_o(a), _o(b)], action=ActionSpec("move", "right of")), seed=20 + i)
        assert c.parses == {said: 1}
    said = "move blue box right of green cone"
    r = c.run(Lesson("react", said, [_o("blue box"), _o("green cone")], action=ActionSpec("move", "right of"),
                     feedback="confirm"), seed=30)
    assert r.goal_holds and r.answer.stored == ["r_move"]
    assert c.parses == {said: 1}
