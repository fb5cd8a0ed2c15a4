"""Every learner the interpreter teaches implements the `Learner` protocol (aileen/agent/protocol.py).

Checked on the classes (a Soar agent needs a kernel to be made), member by member: each
protocol method is there, callable, and takes the protocol's parameters by the same names and
kinds (a learner may take more, with defaults), so a call the interpreter makes by keyword
reaches it. On an ASP agent made here, `isinstance(agent, Learner)` holds too.
"""

from __future__ import annotations

import inspect

import pytest

from aileen.agent import Agent, Learner
from aileen.experiments import baselines
from aileen.soar.learner import SoarAgent

MEMBERS = [n for n, v in vars(Learner).items() if callable(v) and not n.startswith("_")]


def _missing(cls: type) -> list[str]:
    """What `cls` lacks of the protocol, one line each."""
    out = []
    for name in MEMBERS:
        have = getattr(cls, name, None)
        if not callable(have):
            out.append(f"{name}: not a method")
            continue
        want = inspect.signature(getattr(Learner, name)).parameters
        got = inspect.signature(have).parameters
        for pname, p in want.items():
            q = got.get(pname)
            if q is None or q.kind != p.kind or (p.default is not inspect.Parameter.empty and q.default is inspect.Parameter.empty):
                out.append(f"{name}: parameter {pname!r} is {q} (the protocol: {p})")
        for pname, q in got.items():
            if pname not in want and q.default is inspect.Parameter.empty and q.kind not in (q.VAR_POSITIONAL, q.VAR_KEYWORD):
                out.append(f"{name}: takes {pname!r}, which the interpreter never gives")
    return out


def test_the_protocol_lists_what_the_interpreter_calls() -> None:
    assert {"new_scene", "perceive", "describe_scene", "watch", "episode_now", "inform", "verify", "react",
            "generate", "told_wrong", "told_right", "confirmed"} <= set(MEMBERS)


@pytest.mark.parametrize("cls", [Agent, SoarAgent, baselines.NearestNeighbour, baselines.Cobweb, baselines.Trestle],
                         ids=lambda c: c.__name__)
def test_each_learner_implements_the_protocol(cls: type) -> None:
    assert _missing(cls) == []


def test_the_check_finds_a_learner_that_lacks_a_signal() -> None:
    class Mute(Agent):
        generate = None  # type: ignore[assignment]

    class Rude(Agent):
        def verify(self, content: str, demo_start: int | None = None):  # positional, not keyword-only
            return super().verify(content, demo_start=demo_start)

    assert _missing(Mute) == ["generate: not a method"]
    assert len(_missing(Rude)) == 1 and _missing(Rude)[0].startswith("verify: parameter 'demo_start'")


def test_an_asp_agent_is_a_learner() -> None:
    agent = Agent(perceiver=lambda image: [])
    assert isinstance(agent, Learner)
    assert not isinstance(object(), Learner)
