"""A trainer's console over an agent with ground-truth vision, as the console tests drive it."""

from __future__ import annotations

from aileen.agent import Agent, AgentParams
from aileen.curriculum.console import Console
from aileen.perception.truth import TruthVision


def truth_console(**params: object) -> tuple[Agent, Console]:
    """An agent (seed 0, `params` beside it) that sees through ground truth, and its console."""
    v = TruthVision()
    agent = Agent(params=AgentParams(seed=0, **params), perceiver=v)
    return agent, Console(agent, on_frame=v.see_frame)
