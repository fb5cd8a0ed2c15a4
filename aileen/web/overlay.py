"""The agent's perception drawn over the camera image: boxes, percept labels, object ids.

The boxes and labels are what the agent perceived (its own ids, its percept symbols), not the
simulator's truth, so the trainer sees what the agent sees. Objects a sentence grounded to are
drawn thick, in a colour of their own.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import cv2
import numpy as np

SCALE = 2  # the page shows the 256 px camera image at twice its size
BOX = (255, 255, 255)
HIGHLIGHT = (255, 200, 0)


@dataclass(frozen=True)
class Mark:
    """One perceived object: the agent's id, its percepts and its box in camera pixels."""

    id: str
    percepts: tuple[str, ...]  # one per channel, in channel order (shape, colour, size)
    box_px: tuple[float, float, float, float]

    @property
    def label(self) -> str:
        """`o1 medium red box`: modifiers first, the shape last."""
        return " ".join([self.id] + [p.removeprefix("cv_") for p in reversed(self.percepts)])

    def to_json(self) -> dict:
        return {"id": self.id, "percepts": list(self.percepts),
                "box_px": [round(float(b), 1) for b in self.box_px]}


def draw(image: np.ndarray, marks: Iterable[Mark] = (), highlight: Iterable[str] = (), *,
         overlay: bool = True, scale: int = SCALE) -> np.ndarray:
    """The image enlarged `scale` times (nearest pixel), with the marks drawn when `overlay`."""
    big = cv2.resize(image, None, fx=scale, fy=scale, interpolation=cv2.INTER_NEAREST)
    if not overlay:
        return big
    hot = set(highlight)
    for m in marks:
        u0, v0, u1, v1 = (int(round(c * scale)) for c in m.box_px)
        lit = m.id in hot
        cv2.rectangle(big, (u0, v0), (u1, v1), HIGHLIGHT if lit else BOX, 3 if lit else 1, cv2.LINE_AA)
        ty = v0 - 4 if v0 > 14 else v1 + 12
        cv2.putText(big, m.label, (u0, ty), cv2.FONT_HERSHEY_SIMPLEX, 0.4, (0, 0, 0), 3, cv2.LINE_AA)
        cv2.putText(big, m.label, (u0, ty), cv2.FONT_HERSHEY_SIMPLEX, 0.4, HIGHLIGHT if lit else BOX, 1, cv2.LINE_AA)
    return big


def png(image: np.ndarray) -> bytes:
    # light compression: the page redraws after every lesson, and speed beats bytes on localhost
    ok, buf = cv2.imencode(".png", cv2.cvtColor(image, cv2.COLOR_RGB2BGR), [cv2.IMWRITE_PNG_COMPRESSION, 1])
    if not ok:  # pragma: no cover - cv2 encodes any uint8 RGB image
        raise RuntimeError("PNG encoding failed")
    return buf.tobytes()
