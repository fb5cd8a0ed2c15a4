"""The agent, along its jobs: `state` (what it sees, stable ids), `lexicon` (mutual
exclusivity, word positions), `grounding` (comprehension against the concept memory),
`learning` (inform), `acting` (react), `body` (its eyes and hand), `core` (the `Agent`), `protocol` (the `Learner` any
learner the interpreter teaches answers to)."""

from aileen.agent.core import Agent
from aileen.agent.protocol import Learner
from aileen.agent.records import AgentParams, Answer
from aileen.agent.state import Seen, State, Tracker
from aileen.perception.perceiver import Detection  # perception's, handed on

__all__ = ["Agent", "AgentParams", "Answer", "Detection", "Learner", "Seen", "State", "Tracker"]
