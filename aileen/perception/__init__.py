"""The visual and spatial modules: detector (ONNX via cv2.dnn), colour (k-means), QSRs,
region sampling, and `perceive(image) -> Scene`, the agent's one entry point.

Names are imported lazily so that importing one piece does not pull in OpenCV for another;
torch is imported only by `aileen.perception.train` (and the `net`, `warmstart` and `distill` it uses). The box geometry and its QSRs
(`qsr_facts`, `cardinal`, `rcc8`) are `aileen.world.geometry`'s, handed on here.
"""

from __future__ import annotations

import importlib
from typing import Any

_EXPORTS = {
    "perceive": "scene", "Scene": "scene", "PerceivedObject": "scene", "load_image": "scene",
    "detect": "detector", "RawDetection": "detector", "load_detector": "detector",
    "Detection": "perceiver", "Perceiver": "perceiver",
    "colour_of": "color", "ColourPercept": "color",
    "qsr_facts": "aileen.world.geometry", "cardinal": "aileen.world.geometry", "rcc8": "aileen.world.geometry",
    "sample_region": "regions", "RegionEmpty": "regions",
}  # fmt: skip

__all__ = sorted(_EXPORTS)


def __getattr__(name: str) -> Any:
    mod = _EXPORTS.get(name)
    if mod is None:
        raise AttributeError(f"module 'aileen.perception' has no attribute {name!r}")
    return getattr(importlib.import_module(mod if "." in mod else f"aileen.perception.{mod}"), name)
