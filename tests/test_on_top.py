"""Where the agent puts an object on top of another: over the carrier, and, near the table's
edge, where the table lets the mover's centre be (lessons/stacking.toml at seed 5: a cylinder
7 cm from the edge, a box put on it off the table)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from console_helpers import teach_piped
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


def _teach_after_stacking(tmp_path: Path, capsys, lines: list[str]) -> tuple[int, str]:
    """`aileen teach` on a memory taught lessons/stacking.toml (seed 5), `lines` on stdin:
    the exit status and what it printed."""
    memory = tmp_path / "m.json"
    assert main(["run", str(STACKING), "--perception", "truth", "--seed", "5", "--memory", str(memory)]) == 0
    capsys.readouterr()
    rc = teach_piped(tmp_path, ["--memory", str(memory), "--perception", "truth", "--seed", "0"], lines)
    return rc, capsys.readouterr().out


def test_an_object_under_another_is_moved_after_the_upper_one_is_moved_away(tmp_path: Path, capsys) -> None:
    """The agent took the red box off the blue one, picked the blue box up, then found no
    next state: the trace of its own acting held the red box's steps, which no demonstration
    of "move" has (`EpisodicMemory.trace` leaves out actions on other objects)."""
    rc, out = _teach_after_stacking(tmp_path, capsys, ["scene red box on blue box", "place green cylinder at 0.2 0.2",
                                                       "react move the blue box on the green cylinder"])
    assert rc == 0, out
    assert "place(o1,free), pick_up(o2), place(o2)" in out and "answer:   success" in out


def test_what_the_world_refuses_is_said_with_the_objects_as_they_look() -> None:
    """"cannot place obj3 on obj1" named the simulator's ids, which read as the agent's o3 and o1."""
    from aileen.agent.body import WorldBody
    from aileen.errors import UserError
    from aileen.world.sim import World

    world = World()
    box, sphere = world.add("box", "red", 0.3, 0.5), world.add("sphere", "green", 0.7, 0.5)
    body = WorldBody(world)
    world.pick_up(box)
    with pytest.raises(UserError) as exc:
        body.put("place", 0.7, 0.5, onto=body.camera.to_pixels(0.7, 0.5))
    assert "cannot place the red box on the green sphere" in exc.value.message
    assert not re.search(r"\bobj\d", exc.value.message)


def test_an_object_up_on_a_stack_is_taken_down_before_another_goes_on_it(tmp_path: Path, capsys) -> None:
    """"move the green cylinder on the red box" with the red box on the blue one: the agent
    picked the cylinder up, the world refused (a stack is two high) and it put it back; a
    person takes the red box down first (the planner now plans no place the world refuses)."""
    _rc, out = _teach_after_stacking(tmp_path, capsys, [
        "place red box at 0.3 0.5", "place blue box at 0.7 0.5", "place green cylinder at 0.5 0.2",
        "react move the red box on the blue box", "react move the green cylinder on the red box"])
    second = out.split('react   "move the green')[1]
    assert "place(o1,free)" in second and "answer:   success" in second and "the goal holds" in second
    assert "put back(" not in second


def test_a_spot_that_holds_as_measured_is_taken_where_none_holds_with_room_for_noise() -> None:
    """"move the red box far from the blue cone", the cone in the middle of the table (boxes
    as the detector measured them): the strip where "far from" holds at the table's edge is
    narrower than the room kept for the measurements' noise, and the agent said "no room"
    where its own verify said yes."""
    from console_helpers import truth_console

    from aileen.perception.regions import RegionEmpty, region_ok, sample_region
    from aileen.terms import parse
    from aileen.world.camera import DEFAULT_CAMERA

    agent, _con = truth_console()
    cone = {"o2": (0.4975, 0.4487, 0.6019, 0.5517)}
    far = [parse("qd_far(o1,o2)")]
    with pytest.raises(RegionEmpty):
        sample_region((0.1043, 0.1004), far, cone, DEFAULT_CAMERA.table, np.random.default_rng(0), subject="o1")
    x, y = agent.acting._spot((0.1043, 0.1004), far, cone, "o1")
    assert region_ok(x, y, (0.1043, 0.1004), [("qd_far", "o2")], cone, DEFAULT_CAMERA.table, slack=0.0)


def test_the_lower_object_is_put_on_the_one_that_was_on_it(tmp_path: Path, capsys) -> None:
    """"move the blue box on the red box" with the red box on the blue one: the agent took the
    red box off, picked the blue box up and found no next state (its own steps on the red box,
    the reference, were read as steps of the move)."""
    _rc, out = _teach_after_stacking(tmp_path, capsys, ["scene red box on blue box",
                                                        "react move the blue box on the red box"])
    assert "answer:   success" in out and "the goal holds" in out


def test_a_sphere_as_the_target_of_on_is_refused_before_the_pick_up(tmp_path: Path, capsys) -> None:
    """The agent picked the red box up, the world refused (a sphere has no flat top) and it put
    it back: the planner knows the world's refusals, so it is said before anything is done."""
    _rc, out = _teach_after_stacking(tmp_path, capsys, [
        "place blue sphere at 0.5 0.5", "inform blue sphere", "place red box at 0.2 0.5",
        "react move the red box on the blue sphere"])
    assert "answer:   failure: no plan of mine puts the red box on the blue sphere" in out
    assert "acted:    nothing" in out and "put back(" not in out
