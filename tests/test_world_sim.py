"""The pymunk table: determinism, primitive actions and their errors, settling."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.errors import UserError
from aileen.world import catalog
from aileen.world.appearance import Appearance
from aileen.world.camera import Table
from aileen.world.sim import World, WorldObject


def four() -> World:
    w = World(seed=3)
    w.add("box", "red", 0.2, 0.2, angle=0.3)
    w.add("cone", "green", 0.8, 0.2)
    w.add("sphere", "blue", 0.2, 0.8, size="small")
    w.add("cylinder", "yellow", 0.8, 0.8, size="large", shade=2)
    return w


def state(w: World) -> list[tuple[str, float, float, float, bool]]:
    return [(o.id, o.x, o.y, o.angle, o.held) for o in w.objects()]


def script(w: World) -> None:
    """A run with pushes and overlapping placements: plenty of contacts to diverge on."""
    w.pick_up("obj1")
    w.place("obj1", 0.75, 0.25)  # onto the cone
    w.pick_up("obj3")
    w.place("obj3", 0.78, 0.77)  # onto the cylinder
    w.push("obj2", -0.8, 0.5)
    w.settle()


# ----------------------------------------------------------------------------- basics


def test_add_and_snapshot() -> None:
    w = four()
    objs = w.objects()
    assert [o.id for o in objs] == ["obj1", "obj2", "obj3", "obj4"]
    o = w.get("obj4")
    assert (o.shape, o.colour, o.size, o.shade, o.held) == ("cylinder", "yellow", "large", 2, False)
    assert (o.x, o.y) == pytest.approx((0.8, 0.8))
    assert o.footprint == catalog.SIZES["large"]
    assert w.get("obj3").footprint == catalog.SIZES["small"]


@given(
    angle=st.floats(-10.0, 10.0, allow_nan=False),
    x=st.floats(0.2, 0.8),
    y=st.floats(0.2, 0.8),
    shape=st.sampled_from(catalog.SHAPES),
)
def test_box_m_is_tight_around_the_footprint(angle: float, x: float, y: float, shape: str) -> None:
    o = WorldObject("obj1", Appearance(shape=shape, colour="red", size="medium"), 0, x, y, angle, False)
    x0, y0, x1, y1 = o.box_m()
    if shape == "box":
        h = o.footprint / 2
        c, s = math.cos(angle), math.sin(angle)
        corners = [(x + c * a - s * b, y + s * a + c * b) for a in (-h, h) for b in (-h, h)]
        xs, ys = [p[0] for p in corners], [p[1] for p in corners]
        assert (x0, y0, x1, y1) == pytest.approx((min(xs), min(ys), max(xs), max(ys)), abs=1e-12)
    elif shape in catalog.ELONGATED_FOOTPRINTS:
        # a lying capsule: the stadium's outline, sampled finely, touches its box on every side
        w = catalog.ELONGATED_FOOTPRINTS[shape]
        r, a = o.footprint / 2 * w, o.footprint / 2 * (1 - w)
        c, s = math.cos(angle), math.sin(angle)
        pts = [(x + c * e * a + r * math.cos(t), y + s * e * a + r * math.sin(t))
               for e in (-1, 1) for t in (k * 2 * math.pi / 3600 for k in range(3600))]
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        assert (x0, y0, x1, y1) == pytest.approx((min(xs), min(ys), max(xs), max(ys)), abs=1e-6)
        assert x1 - x0 <= o.footprint + 1e-12 and y1 - y0 <= o.footprint + 1e-12
    else:
        assert (x0, y0, x1, y1) == pytest.approx((x - 0.05, y - 0.05, x + 0.05, y + 0.05), abs=1e-12)


def test_unknown_names_list_the_valid_ones() -> None:
    w = World()
    with pytest.raises(UserError, match="unknown shape 'pyramid'.*box, cone, sphere, cylinder"):
        w.add("pyramid", "red", 0.5, 0.5)
    with pytest.raises(UserError, match="unknown colour 'pink'.*red, green, blue, yellow, purple"):
        w.add("box", "pink", 0.5, 0.5)
    with pytest.raises(UserError, match="unknown size 'huge'"):
        w.add("box", "red", 0.5, 0.5, size="huge")
    with pytest.raises(UserError, match="shade"):
        w.add("box", "red", 0.5, 0.5, shade=len(catalog.SHADES["red"]))
    assert w.objects() == []


@pytest.mark.parametrize("x,y", [(0.02, 0.5), (0.5, 0.99), (-1.0, 0.5), (0.5, 1.5), (float("nan"), 0.5)])
def test_add_off_the_table_is_refused(x: float, y: float) -> None:
    w = World()
    with pytest.raises(UserError, match="cannot add"):
        w.add("sphere", "red", x, y)
    assert len(w) == 0


def test_add_respects_a_custom_table() -> None:
    w = World(Table(2.0, 0.5))
    w.add("box", "red", 1.9, 0.25)
    with pytest.raises(UserError, match="off the table"):
        w.add("box", "red", 1.0, 0.48)


# ----------------------------------------------------------------------------- actions


def test_point_records_and_does_nothing_physical() -> None:
    w = four()
    before = state(w)
    w.point("obj2")
    assert w.last_pointed == "obj2"
    assert state(w) == before
    with pytest.raises(UserError, match="no object 'obj9'"):
        w.point("obj9")
    assert w.last_pointed == "obj2"


def test_pick_up_and_place() -> None:
    w = four()
    w.pick_up("obj2")
    assert w.held == "obj2"
    held = w.get("obj2")
    assert held.held and [o.held for o in w.objects()] == [False, True, False, False]
    report = w.place("obj2", 0.5, 0.5)
    assert w.held is None and not w.get("obj2").held
    assert (w.get("obj2").x, w.get("obj2").y) == pytest.approx((0.5, 0.5), abs=1e-9)
    assert report.settled and report.moved == {}


def test_a_held_object_is_off_the_table_and_does_not_collide() -> None:
    w = World()
    a = w.add("box", "red", 0.5, 0.5)
    w.pick_up(a)
    b = w.add("sphere", "blue", 0.5, 0.5)  # where a stood: free while a is held
    r = w.settle()
    assert r.moved == {} and (w.get(b).x, w.get(b).y) == (0.5, 0.5)
    assert (w.get(a).x, w.get(a).y) == (0.5, 0.5) and w.get(a).held  # a keeps its last position


@pytest.mark.parametrize(
    "act,msg",
    [
        (lambda w: w.pick_up("obj1"), "already held"),
        (lambda w: w.pick_up("obj2"), "already holding obj1"),
        (lambda w: w.pick_up("nope"), "no object 'nope'"),
        (lambda w: w.place("obj2", 0.5, 0.5), "the held object is obj1"),
        (lambda w: w.place("obj1", 0.99, 0.5), "off the table"),
        (lambda w: w.place("obj1", 0.5, -0.2), "off the table"),
        (lambda w: w.place("ghost", 0.5, 0.5), "no object 'ghost'"),
    ],
)
def test_action_errors_while_holding_leave_the_world_unchanged(act, msg: str) -> None:  # type: ignore[no-untyped-def]
    w = four()
    w.pick_up("obj1")
    before = (state(w), w.held)
    with pytest.raises(UserError, match=msg):
        act(w)
    assert (state(w), w.held) == before


def test_place_with_nothing_held_is_refused() -> None:
    w = four()
    before = state(w)
    with pytest.raises(UserError, match="nothing is held"):
        w.place("obj1", 0.5, 0.5)
    assert state(w) == before and w.held is None


def test_remove() -> None:
    w = four()
    w.point("obj3")
    w.remove("obj3")
    assert [o.id for o in w.objects()] == ["obj1", "obj2", "obj4"]
    assert w.last_pointed is None
    w.pick_up("obj1")
    w.remove("obj1")
    assert w.held is None
    assert w.add("box", "red", 0.5, 0.5) == "obj5"  # ids are never reused
    with pytest.raises(UserError):
        w.remove("obj3")


# ----------------------------------------------------------------------------- settling


def test_a_collision_free_scene_does_not_move_and_ends_at_once() -> None:
    w = four()
    before = state(w)
    r = w.settle()
    assert r.settled and r.moved == {} and r.steps <= 3
    assert state(w) == before


@pytest.mark.parametrize("shape", catalog.SHAPES)
def test_overlapping_objects_are_pushed_apart_and_reported(shape: str) -> None:
    w = World()
    a = w.add(shape, "red", 0.5, 0.5)
    b = w.add("sphere", "blue", 0.2, 0.2)
    far = w.add("cone", "green", 0.85, 0.85)
    w.pick_up(b)
    r = w.place(b, 0.53, 0.52)
    assert r.settled
    assert set(r.moved) == {a, b}
    pa, pb = w.get(a), w.get(b)
    assert r.moved[a] == pytest.approx(math.hypot(pa.x - 0.5, pa.y - 0.5))
    assert r.moved[b] == pytest.approx(math.hypot(pb.x - 0.53, pb.y - 0.52))
    # Apart now: no more overlap than pymunk's slop (the footprints are 0.10 m).
    assert _clearance(pa, pb) >= -0.002
    assert far not in r.moved
    # And at rest: settling again moves nothing.
    assert w.settle().moved == {}


@pytest.mark.parametrize("shape", catalog.SHAPES)
def test_placing_exactly_on_top_still_separates(shape: str) -> None:
    w = World()
    a = w.add(shape, "red", 0.5, 0.5)
    b = w.add(shape, "blue", 0.2, 0.2)
    w.pick_up(b)
    r = w.place(b, 0.5, 0.5)
    assert r.settled and set(r.moved) == {a, b}
    pa, pb = w.get(a), w.get(b)
    assert _clearance(pa, pb) >= -0.002


def _axis(o: WorldObject) -> tuple[tuple[float, float], tuple[float, float], float]:
    """A round footprint as a segment with a radius: a disc's is a point, a lying capsule's
    its axis; a box as its centre and half its diagonal's projection does not matter here:
    a box's clearance is read from centre distance (squares 0.10 m apart cannot overlap)."""
    w = catalog.ELONGATED_FOOTPRINTS.get(o.shape, 1.0)
    a, r = o.footprint / 2 * (1 - w), o.footprint / 2 * w
    c, s = math.cos(o.angle), math.sin(o.angle)
    return (o.x - c * a, o.y - s * a), (o.x + c * a, o.y + s * a), r


def _segment_distance(p: tuple, q: tuple, u: tuple, v: tuple) -> float:
    """The shortest distance between segments pq and uv (sampled finely: enough for a test)."""
    pts = [(p[0] + (q[0] - p[0]) * t / 200, p[1] + (q[1] - p[1]) * t / 200) for t in range(201)]
    qts = [(u[0] + (v[0] - u[0]) * t / 200, u[1] + (v[1] - u[1]) * t / 200) for t in range(201)]
    return min(math.hypot(a[0] - b[0], a[1] - b[1]) for a in pts for b in qts)


def _clearance(a: WorldObject, b: WorldObject) -> float:
    """How far apart two footprints are (negative: overlap): exact for round shapes and
    capsules; for boxes the centre distance less a side (the tests place them square)."""
    if a.shape in catalog.SQUARE_FOOTPRINTS or b.shape in catalog.SQUARE_FOOTPRINTS:
        return math.hypot(a.x - b.x, a.y - b.y) - (a.footprint + b.footprint) / 2
    (p, q, r), (u, v, s) = _axis(a), _axis(b)
    return _segment_distance(p, q, u, v) - r - s


def test_pushes_into_a_corner_keep_everything_on_the_table() -> None:
    w = World()
    for i in range(3):
        for j in range(3):
            w.add("box", "red", 0.06 + 0.11 * i, 0.06 + 0.11 * j)
    s = w.add("sphere", "blue", 0.8, 0.8)
    w.pick_up(s)
    r = w.place(s, 0.12, 0.12)
    assert r.settled and len(r.moved) >= 3
    for o in w.objects():
        x0, y0, x1, y1 = o.box_m()
        assert x0 > -1e-5 and y0 > -1e-5 and x1 < 1 + 1e-5 and y1 < 1 + 1e-5
        # And each object can be picked up and put back where it now rests.
        w.pick_up(o.id)
        w.place(o.id, o.x, o.y)


def test_a_pushed_object_slides_to_a_stop_and_stays_on_the_table() -> None:
    w = World()
    a = w.add("sphere", "red", 0.5, 0.5)
    w.push(a, 5.0, 0.0)  # fast, toward the east edge
    r = w.settle()
    assert r.settled and a in r.moved
    o = w.get(a)
    assert 0.5 < o.x <= 1.0 - 0.05 + 0.002
    w.push(a, -0.3, 0.0)  # slowly: friction stops it after v^2 / (2 mu g)
    x0 = w.get(a).x
    w.settle()
    expected = 0.3**2 / (2 * w.physics.mu_table * w.physics.g)
    # pymunk moves first and brakes after, which adds up to one step's travel (v dt).
    assert expected <= x0 - w.get(a).x <= expected + 0.3 * w.physics.dt


def test_step_cap_reports_not_settled() -> None:
    w = World()
    a = w.add("sphere", "red", 0.5, 0.5)
    w.push(a, 1.0, 0.0)
    r = w.settle(max_steps=3)
    assert r.steps == 3 and not r.settled


# ----------------------------------------------------------------------------- determinism


def test_same_seed_same_calls_same_positions() -> None:
    w1, w2 = four(), four()
    script(w1)
    script(w2)
    for a, b in zip(state(w1), state(w2)):
        assert a[0] == b[0]
        assert a[1:4] == pytest.approx(b[1:4], abs=1e-9)


def test_copy_is_independent_and_replays_exactly() -> None:
    w = four()
    w.pick_up("obj1")
    w.place("obj1", 0.75, 0.25)  # leaves contacts behind: the copy must not depend on them
    c = w.copy()
    assert state(c) == state(w)
    c.pick_up("obj2")
    assert w.held is None and not w.get("obj2").held
    c.place("obj2", 0.5, 0.5)
    w.pick_up("obj2")
    w.place("obj2", 0.5, 0.5)
    for a, b in zip(state(w), state(c)):
        assert a[1:4] == pytest.approx(b[1:4], abs=1e-9)


@settings(max_examples=10, deadline=None)
@given(
    xs=st.lists(st.tuples(st.floats(0.1, 0.9), st.floats(0.1, 0.9)), min_size=2, max_size=4),
    shape=st.sampled_from(catalog.SHAPES),
)
def test_overlapping_placements_are_deterministic(xs: list[tuple[float, float]], shape: str) -> None:
    def run() -> list[tuple[str, float, float, float, bool]]:
        w = World(seed=1)
        ids = [w.add(shape, "red", 0.5, 0.5)]
        for i in range(len(xs)):
            ids.append(w.add(catalog.SHAPES[i % 4], "blue", 0.1 + 0.2 * i, 0.08))
        for obj, (x, y) in zip(ids[1:], xs):
            w.pick_up(obj)
            w.place(obj, x, y)
        return state(w)

    first, second = run(), run()
    for a, b in zip(first, second):
        assert a[1:4] == pytest.approx(b[1:4], abs=1e-9)
