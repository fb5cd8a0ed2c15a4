"""The table geometry the trainer's relation kinds read (`domain/table_geometry.py`): what each
function promises, on random footprints and directions."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from aileen.domain.table_geometry import angle_from, extent, gap, on_table, resting_on, ring, touch_length


@dataclass
class Square:
    """An axis-aligned footprint of side `side` centred at (x, y)."""

    x: float
    y: float
    side: float
    size: str = "medium"
    on: str | None = None
    held: bool = False
    id: str = "o"

    def box_m(self) -> tuple[float, float, float, float]:
        h = self.side / 2
        return self.x - h, self.y - h, self.x + h, self.y + h


coord = st.floats(0.0, 1.0)
side = st.floats(0.02, 0.2)
heading = st.floats(-math.pi, math.pi)


@given(coord, coord, side, coord, coord, side)
def test_gap_is_symmetric_and_negative_only_when_the_footprints_overlap(x1, y1, s1, x2, y2, s2) -> None:  # noqa: ANN001
    a, b = Square(x1, y1, s1), Square(x2, y2, s2)
    assert gap(a, b) == gap(b, a)
    overlap = abs(x1 - x2) < (s1 + s2) / 2 and abs(y1 - y2) < (s1 + s2) / 2
    assert (gap(a, b) < 0) == overlap


@given(heading, side, side, st.floats(0.0, 0.1))
def test_two_squares_laid_at_the_touching_length_are_that_gap_apart(theta, fa, fb, g) -> None:  # noqa: ANN001
    length = touch_length(theta, fa, fb, g)
    a = Square(0.5 + length * math.cos(theta), 0.5 + length * math.sin(theta), fa)
    b = Square(0.5, 0.5, fb)
    assert math.isclose(gap(a, b), g, abs_tol=1e-9)


@given(heading, coord, coord, coord, coord)
def test_the_angle_from_a_heading_is_between_0_and_180_and_0_along_it(h, x1, y1, x2, y2) -> None:  # noqa: ANN001
    a, b = Square(x1, y1, 0.1), Square(x2, y2, 0.1)
    off = angle_from(h, a, b)
    assert 0.0 <= off <= 180.0
    if math.hypot(x1 - x2, y1 - y2) > 1e-6:
        bearing = math.atan2(y1 - y2, x1 - x2)
        assert angle_from(bearing, a, b) < 1e-6
        assert math.isclose(angle_from(bearing + math.pi, a, b), 180.0, abs_tol=1e-6)


@given(st.integers(0, 2**32 - 1), heading, st.floats(0.0, 90.0), st.floats(0.01, 0.5))
def test_a_ring_offset_has_its_length_within_its_half_angle(seed, h, half, length) -> None:  # noqa: ANN001
    dx, dy = ring(np.random.default_rng(seed), h, half, length)
    assert math.isclose(math.hypot(dx, dy), length, rel_tol=1e-9)
    off = abs(math.degrees(math.remainder(math.atan2(dy, dx) - h, 2 * math.pi)))
    assert off <= half + 1e-6


def test_what_stands_on_the_table_and_what_rests_on_what() -> None:
    table, top, held = Square(0.5, 0.5, 0.1, id="a"), Square(0.5, 0.5, 0.05, on="a", id="b"), Square(0.2, 0.2, 0.1, held=True)
    assert on_table(table) and not on_table(top) and not on_table(held)
    assert resting_on(top, table) and not resting_on(table, top)
    assert extent(Square(0.0, 0.0, 0.08)) == 0.08
