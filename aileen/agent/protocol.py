"""What a learner must answer to be taught: the `Learner` protocol the interpreter types against.

Why a protocol, not the `Agent` class: three kinds of learner sit at the trainer's table, the
ASP agent (`aileen.agent.Agent`), the Soar agent (`aileen.soar.learner.SoarAgent`, which has
the ASP agent's eyes but not its mind) and the baselines of the experiments
(`aileen.experiments.baselines`, the ASP agent's eyes with another learner behind them). The
interpreter (`aileen.curriculum.interpreter`) needs of them only what is listed here: look at
a new scene, watch a demonstration, answer the paper's signals and hear the trainer's
verdicts. tests/test_learner_protocol.py checks that each of them has every member, with the
parameters spelled as here.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Protocol, runtime_checkable

import numpy as np

from aileen.agent.records import Answer

if TYPE_CHECKING:
    from aileen.agent.body import WorldBody

#: The trainer's verdicts, each with the signal whose answer it judges.
VERDICTS: dict[str, str] = {"wrong": "verify", "right": "verify", "confirm": "react"}


@runtime_checkable
class Learner(Protocol):
    """A learner the trainer can teach (`Interpreter.run`)."""

    def new_scene(self) -> None:
        """The trainer set up a new scene: object identities from the last one are gone."""

    def perceive(self, image: np.ndarray, action: Any = None) -> Any:
        """Look at the camera image (what the hand has just done: `action`); the state seen."""

    def describe_scene(self) -> list[str]:
        """What it sees now, one line per object (the lesson's transcript)."""

    def locate(self, u: float, v: float) -> str:
        """Its id of the object seen at pixel (u, v), where the trainer points."""

    def watch(self, action: str, u: float | None, v: float | None, image: np.ndarray) -> None:
        """The trainer did one primitive action (its hand at pixel (u, v)); the table after."""

    def episode_now(self) -> int:
        """Its episodic memory's current index (where a demonstration starts)."""

    def inform(self, content: str, *, demo_start: int | None = None) -> Answer:
        """The trainer says `content` holds: comprehend it, learn from what failed."""

    def verify(self, content: str, *, demo_start: int | None = None) -> Answer:
        """Does `content` hold in the scene (or the demonstration since `demo_start`)?"""

    def react(self, content: str, body: "WorldBody") -> Answer:
        """Carry out the action `content` asks for, through `body`."""

    def generate(self, content: str = "") -> Answer:
        """Say what is seen, in learned words."""

    def told_wrong(self, answer: Answer) -> None:
        """The trainer says the last verify answer was wrong (stores go on `answer`)."""

    def told_right(self, answer: Answer) -> None:
        """The trainer, grading the last verify answer, lets it stand."""

    def confirmed(self, answer: Answer) -> None:
        """The trainer confirms the last react reached its goal."""

    def save(self, path: str) -> None:
        """Save what was learned."""


def give_verdict(learner: Learner, what: str, answer: Answer) -> None:
    """Tell `learner` the trainer's verdict `what` (one of `VERDICTS`) on its last answer; what
    it learns from it goes on `answer`. Both consoles say their verdicts through here."""
    {"wrong": learner.told_wrong, "right": learner.told_right, "confirm": learner.confirmed}[what](answer)
