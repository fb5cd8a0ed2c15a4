"""The top-down camera: ground-truth boxes, what each shape looks like, lighting, determinism."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.world import catalog
from aileen.world.camera import Camera, Table
from aileen.world.render import render
from aileen.world.sim import World


def one(shape: str, colour: str = "red", x: float = 0.5, y: float = 0.5, **kw: object) -> World:
    w = World()
    w.add(shape, colour, x, y, **kw)  # type: ignore[arg-type]
    return w


def drawn_mask(world: World, *, seed: int | None = None, camera: Camera = Camera()) -> np.ndarray:
    """Pixels that differ from the empty table under the same light: what the objects drew."""
    empty = render(World(world.table), seed=seed, camera=camera).image
    img = render(world, seed=seed, camera=camera).image
    return np.any(img != empty, axis=2)


def test_image_format_and_rgb_order() -> None:
    f = render(one("cylinder", "red"))
    assert f.image.shape == (256, 256, 3) and f.image.dtype == np.uint8
    r, g, b = (int(c) for c in f.image[128, 128])  # the flat top of a red cylinder
    assert r > 150 and g < 80 and b < 80  # RGB, not BGR
    small = render(one("box"), camera=Camera(width=96, height=64))
    assert small.image.shape == (64, 96, 3)


@settings(max_examples=25, deadline=None)
@given(
    shape=st.sampled_from(catalog.SHAPES),
    size=st.sampled_from(sorted(catalog.SIZES)),
    x=st.floats(0.1, 0.9),
    y=st.floats(0.1, 0.9),
    angle=st.floats(0.0, 2 * math.pi),
    seed=st.one_of(st.none(), st.integers(0, 10_000)),
)
def test_truth_box_holds_every_drawn_pixel_and_is_tight(
    shape: str, size: str, x: float, y: float, angle: float, seed: int | None
) -> None:
    w = one(shape, "blue", x, y, size=size, angle=angle)
    mask = drawn_mask(w, seed=seed)
    (t,) = render(w, seed=seed).truth
    u0, v0, u1, v1 = t.box_px
    vs, us = np.nonzero(mask)
    assert us.size > 0
    assert u0 <= us.min() and us.max() + 1 <= u1 and v0 <= vs.min() and vs.max() + 1 <= v1
    # Tight: within a pixel of the drawn extent.
    assert us.min() - u0 <= 1 and u1 - (us.max() + 1) <= 1 and vs.min() - v0 <= 1 and v1 - (vs.max() + 1) <= 1
    # And the metre box agrees with the pixel box through the camera (to about a pixel).
    px = 1.0 / 256
    assert Camera().box_to_metres(t.box_px) == pytest.approx(t.box_m, abs=1.5 * px)
    assert t.centre_m == (pytest.approx(x), pytest.approx(y))


def test_boxes_in_a_crowded_scene() -> None:
    w = World()
    spots = [(0.1 + 0.2 * i, 0.1 + 0.2 * j) for i in range(5) for j in range(5)]
    for k, (x, y) in enumerate(spots):
        w.add(catalog.SHAPES[k % 4], catalog.COLOURS[k % 5], x, y, angle=0.2 * k, shade=k % 4)
    f = render(w, seed=4)
    empty = render(World(), seed=4).image
    diff = np.any(f.image != empty, axis=2)
    inside = np.zeros_like(diff)
    for t in f.truth:
        u0, v0, u1, v1 = (int(v) for v in t.box_px)
        inside[v0:v1, u0:u1] = True
    assert not np.any(diff & ~inside)  # nothing drawn outside the boxes
    assert len(f.truth) == 25


def test_a_held_object_is_not_drawn() -> None:
    w = World()
    a = w.add("sphere", "red", 0.3, 0.3)
    w.add("box", "blue", 0.7, 0.7)
    w.pick_up(a)
    f = render(w)
    assert [t.id for t in f.truth] == ["obj2"]
    ref = World()
    ref.add("sphere", "red", 0.8, 0.2)
    ref.remove("obj1")
    ref.add("box", "blue", 0.7, 0.7)
    assert np.array_equal(f.image, render(ref).image)


def test_determinism_and_variation() -> None:
    w = one("cone", "green")
    assert np.array_equal(render(w).image, render(w).image)
    assert np.array_equal(render(w, seed=5, noise=4).image, render(w, seed=5, noise=4).image)
    assert not np.array_equal(render(w, seed=5).image, render(w, seed=6).image)
    noisy = render(w, seed=5, noise=4).image.astype(int) - render(w, seed=5).image.astype(int)
    assert 2.5 < noisy.std() < 5.5


def patch(world: World, seed: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The object's pixels (float RGB, N x 3) and its mask inside its box."""
    f = render(world, seed=seed)
    (t,) = f.truth
    u0, v0, u1, v1 = (int(v) for v in t.box_px)
    mask = drawn_mask(world, seed=seed)[v0:v1, u0:u1]
    return f.image[v0:v1, u0:u1].astype(float), mask


def test_the_four_shapes_look_different_from_above() -> None:
    looks = {}
    for shape in catalog.SHAPES:
        img, mask = patch(one(shape, "purple"))
        lum = img.mean(axis=2)
        h, w = mask.shape
        yy, xx = np.mgrid[0:h, 0:w]
        rho = np.hypot(xx + 0.5 - w / 2, yy + 0.5 - h / 2) / (w / 2)
        inner = lum[(rho < 0.5) & mask]
        looks[shape] = {
            "fill": mask.mean(),  # a square fills its box, a disk about pi/4
            "peak": lum[mask].max(),  # the sphere's highlight and the cone's apex are near white
            "inner_std": inner.std(),  # flat tops are even; sphere and cone are shaded
        }
    assert looks["box"]["fill"] > 0.95
    for s in ("cone", "sphere", "cylinder"):
        assert 0.7 < looks[s]["fill"] < 0.9
    assert looks["sphere"]["peak"] > 200 and looks["cone"]["peak"] > 200
    assert looks["cylinder"]["peak"] < 200 and looks["box"]["peak"] < 200
    assert looks["cylinder"]["inner_std"] < 3 and looks["box"]["inner_std"] < 3
    assert looks["sphere"]["inner_std"] > 8 and looks["cone"]["inner_std"] > 8


def test_cone_is_shaded_by_direction_and_sphere_by_distance() -> None:
    """Along one radius a cone's slope faces one way (even brightness); a sphere's curves."""
    spread = {}
    for shape in ("cone", "sphere"):
        img, mask = patch(one(shape, "yellow"))
        lum = img.mean(axis=2)
        h, w = mask.shape
        yy, xx = np.mgrid[0:h, 0:w]
        dx, dy = (xx + 0.5 - w / 2) / (w / 2), -(yy + 0.5 - h / 2) / (h / 2)
        rho, psi = np.hypot(dx, dy), np.degrees(np.arctan2(dy, dx))
        for bearing in (15.0, 105.0, 195.0, 285.0):  # between the cone's slope lines
            off = (psi - bearing + 180.0) % 360.0 - 180.0  # angle difference, wrapped
            radius = (np.abs(off) < 5) & (rho > 0.25) & (rho < 0.75) & mask
            assert radius.sum() >= 5, (shape, bearing)
            spread.setdefault(shape, []).append(lum[radius].std())
    assert max(spread["cone"]) < 4.0, spread
    # Every radius of the sphere varies more than any radius of the cone.
    assert min(spread["sphere"]) > 1.5 * max(spread["cone"]), spread


@pytest.mark.parametrize("colour", catalog.COLOURS)
def test_colours_survive_the_lighting(colour: str) -> None:
    """Under every seeded light the object's median colour is nearest to its own preset."""
    presets = {c: np.array(rgb, dtype=float) for c, rgb in catalog.PRESETS.items()}
    for k, shape in enumerate(catalog.SHAPES):
        for seed in (1, 2, 3, 11, 12):
            img, mask = patch(one(shape, colour, shade=(k + seed) % 4), seed=seed)
            med = np.median(img[mask], axis=0)
            # Compare chromaticity: brightness may vary with the light, hue must not.
            nearest = min(presets, key=lambda c: np.linalg.norm(med / med.sum() - presets[c] / presets[c].sum()))
            assert nearest == colour, (shape, seed, med)


def test_lighting_off_gives_flat_tops_their_catalog_colour() -> None:
    f = render(one("box", "green", shade=1), lighting=False)
    assert tuple(int(c) for c in f.image[128, 128]) == catalog.SHADES["green"][1]


def test_camera_on_a_wide_table() -> None:
    table = Table(2.0, 1.0)
    w = World(table)
    w.add("box", "red", 1.5, 0.5)
    cam = Camera(table, 256, 128)
    (t,) = render(w, camera=cam).truth
    u0, v0, u1, v1 = t.box_px
    assert (u0 + u1) / 2 == pytest.approx(192, abs=1) and (v0 + v1) / 2 == pytest.approx(64, abs=1)
    assert u1 - u0 == pytest.approx(12.8 + 1, abs=1.1)
