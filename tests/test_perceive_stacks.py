"""perceive() on stacks: both objects found, which one is on top, and the lower one's colour
and size measured on the part of it that shows (the shipped detector)."""

from __future__ import annotations

import pytest

from aileen.perception.scene import perceive
from aileen.world.render import render
from aileen.world.sim import World

# (lower shape, lower size, upper shape, upper size, upper offset from the lower centre, m)
STACKS = [
    ("box", "large", "box", "small", (0.03, 0.0)),
    ("box", "medium", "sphere", "medium", (0.03, 0.03)),
    ("cylinder", "medium", "cone", "small", (0.0, -0.03)),
    ("cylinder", "large", "box", "medium", (-0.035, 0.02)),
    ("box", "small", "cylinder", "medium", (0.02, 0.0)),
]


def stacked(lower: str, lsize: str, upper: str, usize: str, off: tuple[float, float]) -> World:
    w = World()
    low = w.add(lower, "red", 0.45, 0.5, size=lsize)
    w.add("sphere", "yellow", 0.8, 0.2)  # a bystander on the table
    up = w.add(upper, "blue", 0.2, 0.8, size=usize)
    w.pick_up(up)
    w.place(up, 0.45 + off[0], 0.5 + off[1], onto=low)
    return w


@pytest.mark.parametrize("lower,lsize,upper,usize,off", STACKS)
@pytest.mark.parametrize("seed", [None, 5])
def test_stack_levels_percepts_and_st_on(lower, lsize, upper, usize, off, seed) -> None:
    frame = render(stacked(lower, lsize, upper, usize, off), seed=seed, noise=0.0 if seed is None else 2.0)
    s = perceive(frame.image)
    assert len(s.objects) == 3  # the partly hidden lower object is found
    by = {o.colour: o for o in s.objects}
    low, up, by3 = by["red"], by["blue"], by["yellow"]
    assert (low.shape, low.size, low.level) == (lower, lsize, 0)
    assert (up.shape, up.size, up.level) == (upper, usize, 1)
    assert (by3.shape, by3.size, by3.level) == ("sphere", "medium", 0)
    text = {str(f) for f in s.facts}
    assert f"st_on({up.id},{low.id})" in text and f"st_under({low.id},{up.id})" in text
    assert not any(f.startswith("st_") and by3.id in f for f in text)


def test_side_by_side_is_no_stack() -> None:
    w = World()
    w.add("box", "red", 0.40, 0.5)
    w.add("box", "blue", 0.50, 0.5)  # edge to edge
    s = perceive(render(w, seed=3).image)
    assert [o.level for o in s.objects] == [0, 0]
    assert not any(str(f).startswith("st_") for f in s.facts)
