"""Ground-truth vision, for ablations only.

`aileen experiment ... --perception truth` replaces the detector and colour module with the
simulator's ground truth, so that a learning curve can be split into what perception cost and
what learning cost. The agent code is unchanged: it still receives detections through its
perceiver; only their source differs. Nothing else in aileen uses this module.
"""

from __future__ import annotations

import numpy as np

from aileen.perception.perceiver import Detection
from aileen.domain.channels import truth_percepts
from aileen.world.render import Frame

Box = tuple[float, float, float, float]


class TruthVision:
    """A perceiver that reports the last rendered frame's ground truth.

    Hook `see_frame` to the body's `on_frame`, and pass the object as the agent's perceiver.
    """

    def __init__(self) -> None:
        self._frame: Frame | None = None

    def see_frame(self, frame: Frame) -> None:
        self._frame = frame

    def __call__(self, image: np.ndarray) -> list[Detection]:
        frame = self._frame
        if frame is None or frame.image is not image:
            raise RuntimeError("TruthVision was given an image it did not see rendered")
        return [Detection(truth_percepts(t), t.box_m, t.box_px, getattr(t, "level", 0), _footprint(t))
                for t in frame.truth]


def _footprint(t) -> float:
    from aileen.world import catalog

    return catalog.SIZES[t.size]
