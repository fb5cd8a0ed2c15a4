"""Where the agent puts an object on top of another: over the carrier, and, near the table's
edge, where the table lets the mover's centre be (lessons/stacking.toml at seed 5: a cylinder
7 cm from the edge, a box put on it off the table)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.cli import main
from aileen.perception.regions import on_top_of

STACKING = Path(__file__).resolve().parents[1] / "lessons" / "stacking.toml"


@settings(max_examples=200, deadline=None)
@given(st.floats(0.02, 0.98), st.floats(0.02, 0.98), st.floats(0.04, 0.14), st.floats(0.03, 0.07),
       st.integers(0, 2**31 - 1))
def test_a_spot_on_top_is_over_the_carrier_and_within_the_table(cx, cy, side, half, seed) -> None:
    box = (cx - side / 2, cy - side / 2, cx + side / 2, cy + side / 2)
    within = (half, half, 1.0 - half, 1.0 - half)
    x, y = on_top_of(box, np.random.default_rng(seed), within=within)
    assert within[0] <= x <= within[2] and within[1] <= y <= within[3]
    # over the carrier wherever the table leaves any of it
    if box[0] <= within[2] and box[2] >= within[0] and box[1] <= within[3] and box[3] >= within[1]:
        assert box[0] - 1e-9 <= x <= box[2] + 1e-9 and box[1] - 1e-9 <= y <= box[3] + 1e-9


def test_without_bounds_the_draw_is_as_before() -> None:
    box = (0.4, 0.4, 0.5, 0.5)
    a = on_top_of(box, np.random.default_rng(3))
    b = on_top_of(box, np.random.default_rng(3), within=(0.0, 0.0, 1.0, 1.0))
    assert a == b


def test_the_stacking_curriculum_reaches_its_goals_near_the_edge(capsys) -> None:
    rc = main(["run", str(STACKING), "--perception", "truth", "--seed", "5"])
    out = capsys.readouterr().out
    assert rc == 0, out[-2000:]
    assert "the goal does NOT hold" not in out
