"""What perception hands the agent: one `Detection` per object in an image.

A perceiver is any function from a camera image to detections (`Perceiver`): the live one
runs the detector and the channels' measures (`aileen.agent.core.vision`, over `perceive`);
the ablation's reads the simulator's ground truth (`aileen.perception.truth.TruthVision`);
an exam replays detections it recorded (`aileen.experiments.exams`). The agent's `Tracker`
gives each detection a stable id. The type lives here, in perception, so that every
perceiver and the agent read one declaration and perception never imports the agent.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

__all__ = ["Box", "Detection", "Perceiver"]

Box = tuple[float, float, float, float]


@dataclass(frozen=True)
class Detection:
    """One object in one image, as the visual module reports it: a percept symbol per
    channel (in the order of `aileen.domain.channels.CHANNELS`), its box in table metres and
    in pixels, and its height above the table in layers (0 on the table, 1 resting on another
    object)."""

    percepts: tuple[str, ...]
    box_m: Box
    box_px: Box
    level: int = 0
    footprint: float = 0.0  # measured side or diameter, metres (0: use the box)


Perceiver = Callable[[np.ndarray], list[Detection]]
