"""What can stand on the table: shapes, colours (with shade variants) and sizes.

Names here are the trainer's words and the simulator's ground truth. The agent's percept
symbols (`cv_red`, `cv_box`, ...) are derived with `percept()`; no rule may depend on their
spelling, but people read them.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator
from contextvars import ContextVar
from dataclasses import dataclass
from typing import Any

from aileen.errors import UserError

SHAPES: tuple[str, ...] = ("box", "cone", "sphere", "cylinder", "capsule")
COLOURS: tuple[str, ...] = ("red", "green", "blue", "yellow", "purple")
# Seen from above, these shapes' footprints are squares; every other shape's is a disc.
SQUARE_FOOTPRINTS: tuple[str, ...] = ("box",)
# Shapes that lie on their side, seen from above as a stadium (a rectangle with round ends):
# its length is the size, its width this share of it. The capsule of the original AILEEN's
# `visual-word-generation` branch; lying, because standing it looks like a sphere from above.
ELONGATED_FOOTPRINTS: dict[str, float] = {"capsule": 0.5}
# Shapes no random draw takes (the trainer's distractors, placeholders and false sentences,
# the experiments, the console's random objects): a capsule stands on the table where a
# lesson names one. The shipped detector was trained before it joined the catalog and cannot
# see it (docs/perception.md, "The capsule"); empty this once a detector that sees it ships.
UNDRAWN_SHAPES: tuple[str, ...] = ("capsule",)


# The paper's evaluation drew these four; its protocols and the ones built on them (wide,
# teacher, react) draw them still, inside `drawing(PAPER_SHAPES)`, so that their figures
# compare across releases whatever shapes the catalog gains.
PAPER_SHAPES: tuple[str, ...] = ("box", "cone", "sphere", "cylinder")
_DRAWING: ContextVar[tuple[str, ...] | None] = ContextVar("drawn_shapes", default=None)


def drawn_shapes() -> tuple[str, ...]:
    """The shapes random draws take: those of the innermost `drawing` block, else every shape
    but `UNDRAWN_SHAPES`."""
    scoped = _DRAWING.get()
    if scoped is not None:
        return scoped
    return tuple(s for s in SHAPES if s not in UNDRAWN_SHAPES)


def drawable(values: tuple[str, ...]) -> tuple[str, ...]:
    """Of a channel's `values`, those random draws take: every value that is no shape, and
    the shapes of `drawn_shapes()`."""
    drawn = drawn_shapes()
    return tuple(v for v in values if v not in SHAPES or v in drawn)


@contextlib.contextmanager
def drawing(shapes: tuple[str, ...]) -> Iterator[None]:
    """Within the block, random draws (distractors, placeholders, false sentences) take only
    `shapes` (catalog names, kept in the catalog's order)."""
    for s in shapes:
        check_shape(s)
    token = _DRAWING.set(tuple(s for s in SHAPES if s in shapes))
    try:
        yield
    finally:
        _DRAWING.reset(token)


# RGB (0-255). The first shade of each colour is its preset: the colour module matches a
# measured mean RGB to the nearest preset. The others are the variants the scenario
# generator draws from, so perception must generalise over shade.
SHADES: dict[str, tuple[tuple[int, int, int], ...]] = {
    "red": ((200, 30, 30), (225, 45, 40), (175, 20, 25), (210, 55, 50)),
    "green": ((40, 170, 50), (60, 190, 70), (30, 145, 45), (75, 175, 60)),
    "blue": ((35, 70, 205), (50, 95, 225), (25, 55, 175), (65, 90, 200)),
    "yellow": ((230, 205, 40), (245, 220, 60), (215, 190, 30), (235, 200, 70)),
    "purple": ((140, 45, 175), (160, 65, 195), (120, 35, 155), (150, 70, 180)),
}
PRESETS: dict[str, tuple[int, int, int]] = {c: SHADES[c][0] for c in COLOURS}

# Footprint side length / diameter in metres.
SIZES: dict[str, float] = {"small": 0.07, "medium": 0.10, "large": 0.13}
DEFAULT_SIZE = "medium"

TABLE_RGB: tuple[int, int, int] = (196, 178, 150)  # light wood


@dataclass(frozen=True)
class Shape:
    """A shape beyond the shipped four: its name, its footprint seen from above ("disc" or
    "square": the physics, the layouts and the camera's silhouette follow it) and its render
    function, `render(name, canvas)`, which shades its top over that footprint
    (`aileen.world.appearance.Canvas`: set `bright` and `spec`). It has no flat top: nothing
    is stacked on it. Declared through `aileen.domain.channels` (`declare`, `scope`), which
    also makes it a value of the shape channel."""

    name: str
    footprint: str = "disc"
    render: Callable[[str, Any], None] | None = None


DECLARED_SHAPES: dict[str, Shape] = {}  # name -> declaration, for shapes beyond the shipped four


def add_shape(shape: Shape) -> None:
    """Make a declared shape one the table can hold (`SHAPES`, `SQUARE_FOOTPRINTS`)."""
    global SHAPES, SQUARE_FOOTPRINTS
    if shape.footprint not in ("disc", "square"):
        raise UserError(f"shape {shape.name!r}: footprint {shape.footprint!r}; expected 'disc' or 'square'")
    if shape.name in SHAPES:
        raise UserError(f"shape {shape.name!r} is already in the catalogue")
    DECLARED_SHAPES[shape.name] = shape
    SHAPES = (*SHAPES, shape.name)
    if shape.footprint == "square":
        SQUARE_FOOTPRINTS = (*SQUARE_FOOTPRINTS, shape.name)


def remove_shape(name: str) -> None:
    """Take a declared shape out of the catalogue again (the end of a declaration's scope)."""
    global SHAPES, SQUARE_FOOTPRINTS
    if DECLARED_SHAPES.pop(name, None) is not None:
        SHAPES = tuple(s for s in SHAPES if s != name)
        SQUARE_FOOTPRINTS = tuple(s for s in SQUARE_FOOTPRINTS if s != name)


def percept(name: str) -> str:
    """The percept symbol for a shape or colour name: `red` -> `cv_red`."""
    return f"cv_{name}"


def check_shape(name: str) -> str:
    if name not in SHAPES:
        raise UserError(f"unknown shape {name!r}; expected one of: {', '.join(SHAPES)}")
    return name


def check_colour(name: str) -> str:
    if name not in COLOURS:
        raise UserError(f"unknown colour {name!r}; expected one of: {', '.join(COLOURS)}")
    return name


def check_size(name: str) -> str:
    if name not in SIZES:
        raise UserError(f"unknown size {name!r}; expected one of: {', '.join(SIZES)}")
    return name
