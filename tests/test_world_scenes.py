"""Scene generation: requests honoured, collision-free with a margin, reproducible, clear refusals."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.errors import UserError
from aileen.world import catalog
from aileen.world.camera import Table
from aileen.world.scenes import (
    ObjectRequest,
    build_scene,
    random_scene,
    sample_free_position,
)
from aileen.world.sim import World


def gaps_ok(world: World, margin: float) -> bool:
    """Every pair of footprint boxes, and every box and the table edge, keep `margin`."""
    boxes = [o.box_m() for o in world.objects()]
    t = world.table
    for x0, y0, x1, y1 in boxes:
        if x0 < margin - 1e-9 or y0 < margin - 1e-9 or x1 > t.width - margin + 1e-9 or y1 > t.depth - margin + 1e-9:
            return False
    for a, b in itertools.combinations(boxes, 2):
        sep = max(b[0] - a[2], a[0] - b[2], b[1] - a[3], a[1] - b[3])
        if sep < margin - 1e-9:
            return False
    return True


def test_requests_are_honoured_in_order() -> None:
    reqs = [
        ObjectRequest("box", "red"),
        ObjectRequest("cone", None),
        ObjectRequest(None, "blue", size="large"),
        ObjectRequest("sphere", "green", position=(0.5, 0.5)),
    ]
    w, ids = build_scene(reqs, distractors=3, seed=7)
    assert ids == ["obj1", "obj2", "obj3", "obj4"]
    objs = [w.get(i) for i in ids]
    assert (objs[0].shape, objs[0].colour) == ("box", "red")
    assert objs[1].shape == "cone" and objs[1].colour in catalog.COLOURS
    assert objs[2].colour == "blue" and objs[2].size == "large" and objs[2].shape in catalog.SHAPES
    assert (objs[3].x, objs[3].y) == (0.5, 0.5)
    assert len(w) == 7
    assert gaps_ok(w, 0.03)


def test_same_seed_same_scene_other_seed_other_scene() -> None:
    def snap(seed: int) -> list[tuple]:  # type: ignore[type-arg]
        w, _ = build_scene([ObjectRequest()], distractors=5, seed=seed)
        return [(o.shape, o.colour, o.shade, o.x, o.y, o.angle) for o in w.objects()]

    assert snap(3) == snap(3)
    assert snap(3) != snap(4)


@settings(max_examples=15, deadline=None)
@given(n=st.integers(0, 25), seed=st.integers(0, 10_000), margin=st.sampled_from([0.0, 0.01, 0.03, 0.05]))
def test_generated_scenes_are_collision_free_and_do_not_move(n: int, seed: int, margin: float) -> None:
    w = random_scene(n, seed=seed, margin=margin)
    assert len(w) == n
    assert gaps_ok(w, margin)
    r = w.settle()
    assert r.settled and r.moved == {}


def test_a_crowded_table_still_fits_through_the_fallbacks() -> None:
    # 49 medium objects is the most a 7 x 7 grid holds with a 0.03 m margin.
    w = random_scene(49, seed=1)
    assert len(w) == 49 and gaps_ok(w, 0.03)


@pytest.mark.parametrize(
    "kw,msg",
    [
        ({"distractors": 60}, "cannot place 60 objects of 0.10 m on a 1.0 x 1.0 m table with margin 0.03 m"),
        ({"distractors": 5, "table": Table(0.3, 0.3)}, "cannot place 5 objects of 0.10 m on a 0.3 x 0.3 m table"),
        ({"distractors": 1, "margin": 0.5}, "cannot place 1 objects of 0.10 m .* margin 0.50 m"),
        ({"distractors": -1}, "distractors must be >= 0"),
        ({"distractors": 2, "distractor_ok": lambda s, c: False}, "rejects every shape and colour"),
    ],
)
def test_impossible_requests_are_refused_clearly(kw: dict, msg: str) -> None:  # type: ignore[type-arg]
    with pytest.raises(UserError, match=msg):
        build_scene([], **kw)


def test_mixed_sizes_are_named_in_the_refusal() -> None:
    reqs = [ObjectRequest(size="large")] * 30 + [ObjectRequest(size="small")] * 10
    with pytest.raises(UserError, match="cannot place 40 objects of up to 0.13 m"):
        build_scene(reqs)


def test_bad_names_list_the_valid_ones() -> None:
    with pytest.raises(UserError, match="expected one of: box, cone, sphere, cylinder"):
        build_scene([ObjectRequest("pyramid", "red")])
    with pytest.raises(UserError, match="expected one of: red, green, blue, yellow, purple"):
        build_scene([ObjectRequest("box", "teal")])
    with pytest.raises(UserError, match="off the table"):
        build_scene([ObjectRequest("box", "red", position=(1.2, 0.5))])


def test_distractor_filter_and_balance() -> None:
    w, ids = build_scene([ObjectRequest("box", "red")], distractors=12, seed=2, distractor_ok=lambda s, c: c != "red")
    distractors = [o for o in w.objects() if o.id not in ids]
    assert len(distractors) == 12 and all(o.colour != "red" for o in distractors)
    # Balanced: four distractors in an empty scene show four shapes (and four colours).
    w4 = random_scene(4, seed=9)
    assert len({o.shape for o in w4.objects()}) == 4 and len({o.colour for o in w4.objects()}) == 4


def test_random_objects_avoid_fixed_ones() -> None:
    reqs = [ObjectRequest("box", "red", position=(0.5, 0.5))] + [ObjectRequest()] * 10
    for seed in range(5):
        w, _ = build_scene(reqs, seed=seed, margin=0.02)
        assert gaps_ok(w, 0.02)


def test_sample_free_position() -> None:
    w = World()
    w.add("box", "red", 0.5, 0.5)
    rng = np.random.default_rng(0)
    for _ in range(50):
        x, y = sample_free_position(w, 0.1, rng, margin=0.05, predicate=lambda x, y: x < 0.5)
        assert x < 0.5
        assert max(abs(x - 0.5), abs(y - 0.5)) >= 0.1 + 0.05 - 1e-9
    with pytest.raises(UserError, match="no free position"):
        sample_free_position(w, 0.1, rng, predicate=lambda x, y: False, tries=20)
    # Same generator state, same answer.
    a = sample_free_position(w, 0.1, np.random.default_rng(5))
    b = sample_free_position(w, 0.1, np.random.default_rng(5))
    assert a == b
    # A held object is off the table: its spot is free.
    w.pick_up("obj1")
    pos = [sample_free_position(w, 0.1, rng, margin=0.0) for _ in range(300)]
    assert any(abs(x - 0.5) < 0.1 and abs(y - 0.5) < 0.1 for x, y in pos)


@settings(max_examples=10, deadline=None)
@given(
    sizes=st.lists(st.sampled_from(sorted(catalog.SIZES)), min_size=1, max_size=12),
    seed=st.integers(0, 10_000),
)
def test_mixed_sizes_are_laid_out_collision_free(sizes: list[str], seed: int) -> None:
    w, ids = build_scene([ObjectRequest(size=s) for s in sizes], distractors=2, seed=seed)
    assert [w.get(i).size for i in ids] == sizes
    assert gaps_ok(w, 0.03)
    assert w.settle().moved == {}
