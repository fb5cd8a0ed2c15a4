"""perceive(): objects, percepts and QSR facts from camera images; placing at a sampled
region and perceiving again gives the requested relations."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from aileen.domain import calculi
from aileen.errors import UserError
from aileen.world.geometry import CARDINALS, cardinal, rcc8
from aileen.perception.regions import RegionEmpty, sample_region
from aileen.perception.detector import load_detector
from aileen.perception.scene import perceive
from aileen.terms import fn, parse
from aileen.world.camera import Table
from aileen.world.catalog import ELONGATED_FOOTPRINTS, SHAPES
from aileen.world.render import render, save_png
from aileen.world.sim import World


def scene_world() -> World:
    w = World()
    w.add("box", "red", 0.2, 0.5)
    w.add("cone", "blue", 0.6, 0.5)
    w.add("sphere", "green", 0.6, 0.8)
    return w


def test_known_scene_facts() -> None:
    s = perceive(render(scene_world(), seed=4, noise=1.5).image)
    assert [o.id for o in s.objects] == ["o1", "o2", "o3"]  # west to east, then south to north
    text = {str(f) for f in s.facts}
    assert {"isa(o1,cv_box)", "isa(o1,cv_red)", "isa(o2,cv_cone)", "isa(o2,cv_blue)",
            "isa(o3,cv_sphere)", "isa(o3,cv_green)"} <= text  # fmt: skip
    assert {"cone_w(o1,o2)", "dc(o1,o2)", "cone_e(o2,o1)", "cone_n(o3,o2)", "cone_s(o2,o3)", "dc(o3,o2)"} <= text
    sectors = {str(f) for f in perceive(render(scene_world(), seed=4, noise=1.5).image,
                                        senses=calculi.senses("sectors")).facts}
    assert {"w(o1,o2)", "e(o2,o1)", "n(o3,o2)", "s(o2,o3)"} <= sectors and "cone_w(o1,o2)" not in sectors
    assert "isa(o1,cv_medium)" in text
    # percepts first (one per channel), then a direction and a topology fact per ordered pair:
    # same sizes, ordinary distances, nothing stacked are unmarked (no fact)
    assert len(s.facts) == 3 * 3 + 2 * 6
    assert s.facts[:9] == tuple(f for o in s.objects for f in o.percept_facts())
    assert s.get("o2").shape == "cone" and s.get("o2").colour == "blue"


# the shapes the shipped detector knows (the capsule joined the catalog after it was trained)
DETECTED = tuple(s for s in SHAPES if s in load_detector().classes)
# ... of a footprint as long as it is wide: objects of the same size, 0.1 m apart either way, touch
SQUARE_OR_ROUND = tuple(s for s in DETECTED if s not in ELONGATED_FOOTPRINTS)


@pytest.mark.parametrize("a", SQUARE_OR_ROUND)
@pytest.mark.parametrize("b", SQUARE_OR_ROUND)
def test_touching_objects_are_ec(a: str, b: str) -> None:
    # edge to edge, side by side and one behind the other; 0.5 m puts centres on cell borders
    for (x1, y1), (x2, y2), d in (((0.40, 0.5), (0.50, 0.5), "cone_w"), ((0.37, 0.40), (0.37, 0.50), "cone_s")):
        w = World()
        w.add(a, "yellow", x1, y1)
        w.add(b, "purple", x2, y2)
        s = perceive(render(w, seed=9).image)
        assert len(s.objects) == 2
        ids = {o.colour: o.id for o in s.objects}
        y, p = ids["yellow"], ids["purple"]
        text = {str(f) for f in s.facts}
        assert {f"ec({y},{p})", f"{d}({y},{p})", f"isa({y},cv_{a})", f"isa({p},cv_{b})"} <= text


def test_empty_table() -> None:
    s = perceive(render(World(), seed=2).image)
    assert s.objects == () and s.facts == ()


def test_held_fact() -> None:
    s = perceive(render(scene_world()).image, held=["o9"])
    assert s.facts[-1] == parse("held(o9)")


def test_image_files(tmp_path) -> None:
    img = render(scene_world()).image
    p = tmp_path / "scene.png"
    save_png(img, str(p))
    assert perceive(p).facts == perceive(img).facts
    empty = tmp_path / "empty.png"
    empty.write_bytes(b"")
    with pytest.raises(UserError, match="empty.png: empty file"):
        perceive(empty)
    text = tmp_path / "notes.png"
    text.write_text("hello")
    with pytest.raises(UserError, match="notes.png: not an image"):
        perceive(text)
    with pytest.raises(UserError, match="cannot read"):
        perceive(tmp_path / "missing.png")
    with pytest.raises(UserError, match="uint8"):
        perceive(img.astype(np.float64))


def _nearest(scene, xy):
    return min(scene.objects, key=lambda o: math.dist(o.centre_m, xy))


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    st.sampled_from(CARDINALS),
    st.sampled_from(["dc", "ec"]),
    st.floats(0.25, 0.75),
    st.floats(0.25, 0.75),
    st.integers(0, 2**20),
)
def test_placed_sample_has_requested_relations(direction, rel, x2, y2, seed) -> None:
    w = World()
    w.add("cylinder", "red", x2, y2)
    w.add("sphere", "yellow", 0.9 if x2 < 0.5 else 0.1, 0.9)  # a bystander
    before = perceive(render(w, seed=seed % 1000).image)
    ref = _nearest(before, (x2, y2)).id
    rng = np.random.default_rng(seed)
    try:
        x, y = sample_region(0.10, [fn(direction, "x", ref), fn(rel, "x", ref)], before.boxes(), Table(), rng)
    except RegionEmpty:
        assume(False)
    w.add("box", "blue", x, y)
    after = perceive(render(w, seed=seed % 1000 + 1).image, senses=calculi.senses("sectors"))
    assert len(after.objects) == 3
    me = _nearest(after, (x, y))
    other = _nearest(after, (x2, y2))
    assert me.colour == "blue" and other.colour == "red"
    assert cardinal(me.box_m, other.box_m) == direction
    assert rcc8(me.box_m, other.box_m) == rel
    facts = {str(f) for f in after.facts}
    assert f"{direction}({me.id},{other.id})" in facts and f"{rel}({me.id},{other.id})" in facts
