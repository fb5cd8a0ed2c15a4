"""The visual and spatial modules: detector (ONNX via cv2.dnn), colour (k-means), QSRs,
region sampling, and `perceive(image) -> Scene`, the agent's one entry point.

Names are imported lazily so that `aileen.perception.qsr` (pure Python) does not pull in
OpenCV; torch is imported only by `aileen.perception.train`.
"""

from __future__ import annotations

import importlib
from typing import Any

_EXPORTS = {
    "perceive": "scene", "Scene": "scene", "PerceivedObject": "scene", "load_image": "scene",
    "detect": "detector", "Detection": "detector", "load_detector": "detector",
    "colour_of": "color", "ColourPercept": "color",
    "qsr_facts": "qsr", "cardinal": "qsr", "rcc8": "qsr",
    "sample_region": "regions", "RegionEmpty": "regions",
}  # fmt: skip

__all__ = sorted(_EXPORTS)


def __getattr__(name: str) -> Any:
    mod = _EXPORTS.get(name)
    if mod is None:
        raise AttributeError(f"module 'aileen.perception' has no attribute {name!r}")
    return getattr(importlib.import_module(f"aileen.perception.{mod}"), name)
