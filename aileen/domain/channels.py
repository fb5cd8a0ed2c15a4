"""Perceptual channels: what the visual module reports about each object.

A channel is a sense with a finite set of values (the world's names for them) and one function
that measures it from the camera image. Each value is seen as a percept symbol (`cv_red`); the
agent knows which channel a percept belongs to (its own senses), never what any word means.
The order of `CHANNELS` is the order of an object's percept facts.

To add a channel: declare it here with its values, the world attribute that holds the true
value (for the trainer, data sets and ground-truth ablations), and its `measure` function,
`measure(image, detection, camera) -> (value, distance)`, named by dotted path so that this
module stays free of OpenCV.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property
from typing import Any

from aileen.world import catalog


@dataclass(frozen=True)
class Channel:
    name: str  # "colour"
    values: tuple[str, ...]  # the world's names: "red", "green", ...
    attribute: str  # the ground-truth attribute of a world object holding the value
    measure_path: str  # "module:function" measuring it from an image and a detection

    def percept(self, value: str) -> str:
        """The percept symbol the agent sees for a value: `red` -> `cv_red`."""
        return catalog.percept(value)

    @cached_property
    def percepts(self) -> tuple[str, ...]:
        return tuple(self.percept(v) for v in self.values)

    @cached_property
    def measure(self) -> Callable[..., tuple[str, float]]:
        module, _, func = self.measure_path.partition(":")
        return getattr(importlib.import_module(module), func)

    def truth(self, obj: Any) -> str:
        """The true value of a world object (or its ground-truth record)."""
        return str(getattr(obj, self.attribute))


SHAPE = Channel("shape", catalog.SHAPES, "shape", "aileen.perception.detector:measure_shape")
COLOUR = Channel("colour", catalog.COLOURS, "colour", "aileen.perception.color:measure_colour")
SIZE = Channel("size", tuple(catalog.SIZES), "size", "aileen.perception.size:measure_size")

CHANNELS: tuple[Channel, ...] = (SHAPE, COLOUR, SIZE)


def of_percept() -> dict[str, str]:
    """Percept symbol -> channel name, for every channel: the agent's knowledge of its senses."""
    return {p: c.name for c in CHANNELS for p in c.percepts}


def truth_percepts(obj: Any) -> tuple[str, ...]:
    """An object's percept symbols from ground truth, in channel order."""
    return tuple(c.percept(c.truth(obj)) for c in CHANNELS)
