"""The camera draws stacks: the upper object over the lower one, its soft shadow on it."""

from __future__ import annotations

import numpy as np
import pytest

from aileen.world import catalog
from aileen.world.camera import DEFAULT_CAMERA
from aileen.world.render import render
from aileen.world.sim import World


def stacked(first_upper: bool) -> tuple[World, str, str]:
    """A small blue box on a large red box; `first_upper` adds the upper object first, so
    insertion order and level order disagree."""
    w = World()
    if first_upper:
        up = w.add("box", "blue", 0.8, 0.8, size="small")
        low = w.add("box", "red", 0.5, 0.5, size="large")
    else:
        low = w.add("box", "red", 0.5, 0.5, size="large")
        up = w.add("box", "blue", 0.8, 0.8, size="small")
    w.pick_up(up)
    w.place(up, 0.52, 0.52, onto=low)
    return w, low, up


def pixel(img: np.ndarray, x: float, y: float) -> np.ndarray:
    u, v = DEFAULT_CAMERA.to_pixels(x, y)
    return img[int(v), int(u)].astype(int)


@pytest.mark.parametrize("first_upper", [False, True])
def test_the_upper_object_is_drawn_over_the_lower_one(first_upper: bool) -> None:
    w, low, up = stacked(first_upper)
    frame = render(w)
    assert np.abs(pixel(frame.image, 0.52, 0.52) - catalog.SHADES["blue"][0]).max() < 12
    assert np.abs(pixel(frame.image, 0.45, 0.45) - catalog.SHADES["red"][0]).max() < 12
    truth = {t.id: t for t in frame.truth}
    assert [t.id for t in frame.truth] == [o.id for o in w.objects()]  # listed in insertion order
    assert (truth[up].level, truth[up].on, truth[up].visible) == (1, low, 1.0)
    assert (truth[low].level, truth[low].on) == (0, None)
    small, large = catalog.SIZES["small"], catalog.SIZES["large"]
    assert truth[low].visible == pytest.approx(1 - small**2 / large**2, abs=0.03)
    # the lower object's box is its whole footprint, hidden part included
    u0, v0, u1, v1 = truth[low].box_px
    assert u1 - u0 == pytest.approx(large * DEFAULT_CAMERA.px_per_m_x, abs=1.5)


def test_the_upper_object_casts_a_soft_shadow_on_the_lower_one() -> None:
    w, low, up = stacked(False)
    alone = World()
    alone.add("box", "red", 0.5, 0.5, size="large")
    with_stack = render(w, seed=7).image.astype(int)
    without = render(alone, seed=7).image.astype(int)
    # Darker somewhere on the lower object just outside the upper one, nowhere brighter,
    # and the table is untouched.
    mask_low = np.zeros(with_stack.shape[:2], bool)
    u0, v0 = DEFAULT_CAMERA.to_pixels(0.44, 0.565)
    u1, v1 = DEFAULT_CAMERA.to_pixels(0.565, 0.44)
    mask_low[int(v0):int(v1), int(u0):int(u1)] = True
    up_u0, up_v0 = DEFAULT_CAMERA.to_pixels(0.485 - 0.004, 0.555 + 0.004)
    up_u1, up_v1 = DEFAULT_CAMERA.to_pixels(0.555 + 0.004, 0.485 - 0.004)
    mask_low[int(up_v0):int(up_v1) + 1, int(up_u0):int(up_u1) + 1] = False
    diff = (with_stack - without).sum(axis=2)
    assert diff[mask_low].min() < -30
    assert diff[mask_low].max() <= 3
    table = np.ones_like(mask_low)
    table[int(v0) - 3:int(v1) + 3, int(u0) - 3:int(u1) + 3] = False
    assert np.abs(diff[table]).max() == 0
