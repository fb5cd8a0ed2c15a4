"""A fresh learner for a trial: our agent, the paper's learner in Soar, or a baseline, with the
chosen vision, and its interpreter.

Why a module of its own: a trial (`trial.run_trial`) makes its learner here, the run of many
trials (`runner.run_experiment`) makes one here first to refuse a bad `--without`, `--senses`
or a missing extra before any work, and the benchmarks make theirs here too; none of them is
the other's job. Split out of `runner` with `trial` and the pool in `local_backend`.
"""

from __future__ import annotations

from collections.abc import Sequence

from aileen.agent.records import ablated
from aileen.errors import UserError
from aileen.experiments.protocol import AGENT_KINDS
from aileen.world.camera import DEFAULT_CAMERA

__all__ = ["PERCEPTIONS", "SENSING", "make_agent", "make_agent_replayable", "perceived_senses", "senses_of"]

PERCEPTIONS: tuple[str, ...] = ("detector", "truth")
# The learners that perceive with the agent's senses (and so take `--senses`): ours and the
# baselines that learn from its facts; the paper's learner keeps the paper's 8 sectors.
SENSING = frozenset({"asp", "nearest", "cobweb", "trestle"})


def make_agent(perception: str, seed: int, without: Sequence[str] = (), agent_kind: str = "asp",
               sage=None, senses: str | None = None):  # noqa: ANN001, ANN201
    """A fresh agent and its interpreter with the chosen vision (and mechanisms switched off);
    `agent_kind` "soar" is the paper's learner as Soar productions (aileen.soar), or a baseline
    (experiments/baselines.py); `sage` (a `SageParams`) sets the concept memory's thresholds (a
    sweep), else the agent's own (`AgentParams.sage`); `senses` the sense of direction of our
    agent and of the baselines that learn from its facts (`--senses`; None: the default)."""
    agent, interp, _replayer = make_agent_replayable(perception, seed, without, agent_kind, sage, senses)
    return agent, interp


def senses_of(without: Sequence[str] = (), senses: str | None = None) -> str:
    """The sense of direction an agent run with `--without` and `--senses` has."""
    return ablated(without, senses).senses_of_direction


def perceived_senses(agent_kind: str = "asp", without: Sequence[str] = (), senses: str | None = None) -> str:
    """The sense of direction the learner `agent_kind` perceives with, for the records: ours and
    the baselines on our facts have `senses_of`; the paper's learner (`paper`) its own
    parameters' and the Soar agent its own (the paper's learner was recorded as senses '',
    printed "-", as if it perceived none)."""
    if agent_kind in SENSING:
        return senses_of(without, senses)
    if agent_kind == "paper":
        from aileen.experiments.baselines import paper_params

        return paper_params(0).senses_of_direction
    if agent_kind == "soar":
        from aileen.soar.learner import PAPER_SENSES

        return PAPER_SENSES
    raise UserError(f"unknown agent {agent_kind!r}; expected one of {', '.join(AGENT_KINDS)}")


def make_agent_replayable(perception: str, seed: int, without: Sequence[str] = (), agent_kind: str = "asp",
                          sage=None, senses: str | None = None):  # noqa: ANN001, ANN201
    """`make_agent`, plus the agent's perceiver as an `exams.Replayer` (recorded exam scenes
    are served through it; live scenes go to the chosen vision)."""
    from aileen.agent import Agent
    from aileen.curriculum.interpreter import Interpreter
    from aileen.experiments.exams import Replayer
    from aileen.experiments.vision_cache import vision as live_vision
    from aileen.memory.concept import ConceptMemory

    params = ablated(without, senses, seed=seed)
    if agent_kind not in AGENT_KINDS:
        raise UserError(f"unknown agent {agent_kind!r}; expected one of {', '.join(AGENT_KINDS)}")
    if perception not in PERCEPTIONS:
        raise UserError(f"unknown perception {perception!r}; expected one of {', '.join(PERCEPTIONS)}")
    truth = None
    if perception == "truth":
        from aileen.perception.truth import TruthVision

        truth = TruthVision()
    replayer = Replayer(truth if truth is not None else live_vision(DEFAULT_CAMERA))
    memory = ConceptMemory(sage if sage is not None else params.sage())
    if agent_kind == "soar":
        from aileen.soar.learner import soar_agent

        agent = soar_agent(memory if sage is not None else None, without=without, perceiver=replayer, seed=seed)
    elif agent_kind != "asp":
        from aileen.experiments import baselines

        agent = baselines.make(agent_kind, seed, replayer, senses)
    else:
        agent = Agent(memory, params=params, perceiver=replayer)
    return agent, Interpreter(agent, on_frame=truth.see_frame if truth is not None else None), replayer
