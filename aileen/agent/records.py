"""The agent's records: its answer to a lesson, and its parameters."""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class Answer:
    """What the agent says back to the trainer for one lesson."""

    signal: str
    content: str
    result: str  # "success" | "failure"
    reason: str | None = None
    referents: dict[str, list[str]] = field(default_factory=dict)
    created: list[str] = field(default_factory=list)
    stored: list[str] = field(default_factory=list)
    steps: list[str] = field(default_factory=list)
    projections: int = 0
    goal_holds: bool | None = None
    said: str | None = None  # generate: the sentence the agent said

    @property
    def commands(self) -> int:
        """create + store commands sent to the concept memory (the paper's bar chart)."""
        return len(self.created) + len(self.stored)

    @property
    def ok(self) -> bool:
        return self.result == "success"


@dataclass(frozen=True)
class AgentParams:
    mutual_exclusivity: bool = True  # leave out of an example what known words already explain
    # Learn which perceptual channel (shape, colour) each position in a noun phrase names
    # (head noun, modifier) from the words already pinned down, and read new words by it.
    syntactic_bootstrapping: bool = True
    max_react_projections: int = 6
    plan_depth: int = 6
    seed: int = 0  # region sampling

