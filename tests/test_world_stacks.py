"""Stacks and the push in the world: the rules, their refusals, and the physics that carries them."""

from __future__ import annotations

import pytest

from aileen.errors import UserError
from aileen.world import catalog
from aileen.world.sim import World


def stack(shape: str = "box", upper: str = "box", at: tuple[float, float] | None = None) -> tuple[World, str, str]:
    w = World(seed=1)
    low = w.add(shape, "red", 0.4, 0.4)
    up = w.add(upper, "blue", 0.7, 0.4, size="small")
    w.pick_up(up)
    x, y = at if at is not None else (0.0, 0.0)
    w.place(up, x, y, onto=low)
    return w, low, up


def test_place_onto_centres_the_object_and_records_the_stack() -> None:
    w, low, up = stack()
    o = w.get(up)
    assert (o.x, o.y) == pytest.approx((0.4, 0.4))
    assert (o.level, o.on) == (1, low)
    assert (w.get(low).level, w.get(low).on) == (0, None)
    assert w.carries(low) == up and w.carries(up) is None


def test_place_onto_keeps_a_point_over_the_lower_object() -> None:
    w, low, up = stack(at=(0.43, 0.37))
    assert (w.get(up).x, w.get(up).y) == pytest.approx((0.43, 0.37))


def test_layers_do_not_collide() -> None:
    # the upper object overlaps its support and stays exactly where it was put
    w, low, up = stack(at=(0.43, 0.37))
    report = w.settle()
    assert report.moved == {} and (w.get(up).x, w.get(up).y) == pytest.approx((0.43, 0.37), abs=1e-9)


@pytest.mark.parametrize("shape", ["sphere", "cone"])
def test_no_stack_on_a_round_top(shape: str) -> None:
    w = World()
    low = w.add(shape, "red", 0.4, 0.4)
    up = w.add("box", "blue", 0.7, 0.4)
    w.pick_up(up)
    with pytest.raises(UserError, match=f"a {shape} has no flat top"):
        w.place(up, 0.4, 0.4, onto=low)
    assert w.held == up  # nothing changed


def test_no_second_object_on_a_loaded_one_and_no_third_level() -> None:
    w, low, up = stack("box", "cylinder")
    third = w.add("box", "green", 0.8, 0.8, size="small")
    w.pick_up(third)
    with pytest.raises(UserError, match=f"{up} already rests on it"):
        w.place(third, 0.4, 0.4, onto=low)
    with pytest.raises(UserError, match="at most 2 objects high"):
        w.place(third, 0.4, 0.4, onto=up)
    with pytest.raises(UserError, match="cannot rest on itself"):
        w.place(third, 0.4, 0.4, onto=third)


def test_the_lower_object_cannot_be_picked_up_and_the_upper_frees_it() -> None:
    w, low, up = stack()
    with pytest.raises(UserError, match=f"cannot pick up {low}: {up} rests on it"):
        w.pick_up(low)
    w.pick_up(up)
    assert w.carries(low) is None and w.get(up).on is None
    w.place(up, 0.8, 0.8)
    w.pick_up(low)  # free again
    assert w.held == low


def test_the_upper_object_rides_along_and_copies_keep_the_stack() -> None:
    w, low, up = stack()
    pusher = w.add("box", "green", 0.4, 0.28)  # 2 cm south of the stack
    copy = w.copy()
    for world in (w, copy):
        world.push_away(pusher)
    low_o, up_o = w.get(low), w.get(up)
    assert low_o.y > 0.4 + 0.01  # shoved north
    assert (up_o.x - low_o.x, up_o.y - low_o.y) == pytest.approx((0.0, 0.0), abs=1e-4)
    assert copy.objects() == w.objects()  # the same calls replay identically on a copy
    assert copy.get(up).on == low


def test_removing_the_lower_object_drops_the_upper_one() -> None:
    w, low, up = stack()
    w.remove(low)
    assert (w.get(up).level, w.get(up).on) == (0, None)


# ----------------------------------------------------------------------------- push


@pytest.mark.parametrize("shape,size", [("box", "medium"), ("sphere", "small"), ("cylinder", "large")])
def test_push_slides_about_one_footprint_north(shape: str, size: str) -> None:
    w = World()
    o = w.add(shape, "red", 0.5, 0.3, size=size)
    report = w.push_away(o)
    after = w.get(o)
    side = catalog.SIZES[size]
    assert report.settled and after.x == pytest.approx(0.5, abs=1e-6)
    assert after.y - 0.3 == pytest.approx(side, rel=0.05)
    assert report.moved[o] == pytest.approx(side, rel=0.05)


def test_push_shoves_what_it_runs_into() -> None:
    w = World()
    o = w.add("box", "red", 0.5, 0.3)
    ahead = w.add("box", "blue", 0.5, 0.41)  # 1 cm ahead
    report = w.push_away(o)
    assert ahead in report.moved and w.get(ahead).y > 0.41 + 0.05
    assert w.get(ahead).y - w.get(o).y >= 0.1 - 1e-3  # still apart, not through each other


def test_push_is_deterministic() -> None:
    runs = []
    for _ in range(2):
        w = World(seed=4)
        o = w.add("cylinder", "red", 0.5, 0.3)
        w.add("sphere", "blue", 0.52, 0.42)
        w.push_away(o)
        runs.append(w.objects())
    assert runs[0] == runs[1]


def test_push_refusals_change_nothing() -> None:
    w = World()
    edge = w.add("box", "red", 0.5, 0.9)
    with pytest.raises(UserError, match="push it off the table's far edge"):
        w.push_away(edge)
    assert w.get(edge).y == 0.9
    w2, low, up = stack()
    with pytest.raises(UserError, match=f"{up} rests on it"):
        w2.push_away(low)
    with pytest.raises(UserError, match=f"it rests on {low}"):
        w2.push_away(up)
    held = w.add("box", "blue", 0.2, 0.2)
    w.pick_up(held)
    with pytest.raises(UserError, match="it is held"):
        w.push_away(held)
