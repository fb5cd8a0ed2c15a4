"""The colour module on synthetic crops: an object disk on the wooden table colour, dimmed or
brightened, with a neighbour's pixels entering from one side."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.perception.color import (
    MIN_SATURATION,
    colour_of,
    nearest_preset,
    saturation,
    tune_weights,
)
from aileen.world.catalog import COLOURS, PRESETS, SHADES, TABLE_RGB


def crop_image(
    colour_rgb, *, size: int = 32, radius: float = 12.0, gain: float = 1.0, neighbour_rgb=None,
    neighbour_side: str = "e", neighbour_depth: int = 6, square: bool = False, seed: int = 0,
):
    """An RGB image with table texture, a shaded object at the centre and optionally a
    neighbour filling a band along one side. Returns (image, box)."""
    rng = np.random.default_rng(seed)
    img = np.empty((size, size, 3), np.float32)
    img[:] = TABLE_RGB
    img *= 1 + rng.normal(0, 0.03, (size, size, 1))
    vv, uu = np.mgrid[0:size, 0:size] + 0.5
    c = size / 2
    if square:
        inside = (np.abs(uu - c) <= radius) & (np.abs(vv - c) <= radius)
    else:
        inside = (uu - c) ** 2 + (vv - c) ** 2 <= radius**2
    # lit from the north-west: brightness falls off across the object, like the renderer's shading
    shade = gain * (1.0 + 0.25 * ((c - uu) + (c - vv)) / (2 * radius))
    obj = np.asarray(colour_rgb, np.float32)[None, None, :] * shade[..., None]
    img = np.where(inside[..., None], obj, img)
    if neighbour_rgb is not None:
        band = {"e": uu > size - neighbour_depth, "w": uu < neighbour_depth,
                "n": vv < neighbour_depth, "s": vv > size - neighbour_depth}[neighbour_side]
        img = np.where(band[..., None], np.asarray(neighbour_rgb, np.float32), img)
    img = np.clip(img, 0, 255).astype(np.uint8)
    return img, (0.0, 0.0, float(size), float(size))


@pytest.mark.parametrize("colour", COLOURS)
def test_every_shade_on_table(colour: str) -> None:
    for shade in SHADES[colour]:
        for square in (False, True):
            img, box = crop_image(shade, square=square, radius=11.0 if square else 14.0)
            assert colour_of(img, box).name == colour


@pytest.mark.parametrize("colour", COLOURS)
def test_rotated_box_crop_with_much_table(colour: str) -> None:
    # a 45-degree box covers half its axis-aligned crop: the table is the largest cluster
    size = 40
    img = np.empty((size, size, 3), np.uint8)
    img[:] = TABLE_RGB
    vv, uu = np.mgrid[0:size, 0:size] + 0.5
    diamond = np.abs(uu - 20) + np.abs(vv - 20) <= 20
    img[diamond] = PRESETS[colour]
    assert colour_of(img, (0, 0, size, size)).name == colour


@pytest.mark.parametrize("colour", COLOURS)
def test_neighbour_pixels_do_not_win(colour: str) -> None:
    for other in COLOURS:
        if other == colour:
            continue
        for side in "nesw":
            img, box = crop_image(PRESETS[colour], neighbour_rgb=PRESETS[other], neighbour_side=side)
            assert colour_of(img, box).name == colour, (colour, other, side)


def test_dim_light_keeps_hue() -> None:
    # a shaded yellow is olive in RGB terms; by chromaticity it is still yellow
    dim = tuple(0.55 * v for v in PRESETS["yellow"])
    assert nearest_preset(dim)[0] == "yellow"
    img, box = crop_image(PRESETS["yellow"], gain=0.6)
    assert colour_of(img, box).name == "yellow"


def test_saturation() -> None:
    assert saturation(TABLE_RGB) < MIN_SATURATION < min(saturation(PRESETS[c]) for c in COLOURS)
    assert saturation((0, 0, 0)) == 0.0


def test_paper_mode_picks_largest_central_cluster() -> None:
    # with two clusters (object, table) the paper's score alone picks the object
    img, box = crop_image(PRESETS["blue"], radius=15.0)
    assert colour_of(img, box, k=2, match="rgb", min_saturation=0.0).name == "blue"


def test_tune_weights_prefers_centre_when_neighbour_is_large() -> None:
    # the neighbour band is bigger than the object: pure pixel share (w1 = 1) picks it
    samples = []
    for i, (c, o) in enumerate([("red", "green"), ("blue", "yellow"), ("purple", "green"), ("yellow", "blue")]):
        img, box = crop_image(PRESETS[c], radius=7.0, neighbour_rgb=PRESETS[o], neighbour_depth=14, seed=i)
        samples.append((img, box, c))
    res = tune_weights(samples)
    acc = dict(res.grid)
    assert acc[1.0] < 1.0
    assert res.accuracy == 1.0 and res.w1 < 1.0


@settings(max_examples=80, deadline=None)
@given(
    st.sampled_from(COLOURS), st.integers(0, 3), st.floats(0.7, 1.1), st.floats(9.0, 15.0),
    st.sampled_from(COLOURS), st.sampled_from("nesw"), st.integers(0, 7), st.integers(0, 1000),
)
def test_colour_property(colour, shade, gain, radius, other, side, depth, seed) -> None:
    img, box = crop_image(
        SHADES[colour][shade], gain=gain, radius=radius,
        neighbour_rgb=SHADES[other][0] if depth else None, neighbour_side=side, neighbour_depth=depth, seed=seed,
    )
    assert colour_of(img, box).name == colour


def _capsule_across(upper_rgb, lower_rgb, *, size: int = 24, half_width: float = 4.0):
    """A lying capsule (a band along the diagonal, round ends) across the middle of a box of
    another colour that fills the crop: what an object resting on another shows in its box."""
    vv, uu = np.mgrid[0:size, 0:size] + 0.5
    c = size / 2
    along, across = ((uu - c) + (vv - c)) / np.sqrt(2), ((uu - c) - (vv - c)) / np.sqrt(2)
    band = np.hypot(np.maximum(np.abs(along) - (c - half_width - 2), 0), across) <= half_width
    img = np.empty((size, size, 3), np.uint8)
    img[:] = lower_rgb
    img[band] = upper_rgb
    return img, band


@pytest.mark.parametrize("colour", COLOURS)
def test_an_object_on_another_is_read_on_its_own_pixels(colour: str) -> None:
    from aileen.perception.pixels import own_pixels

    for lower in COLOURS:
        if lower == colour:
            continue
        img, band = _capsule_across(PRESETS[colour], PRESETS[lower])
        assert band.mean() < 0.3  # the lower colour is most of the box: the larger cluster
        assert colour_of(img, (0, 0, 24, 24), upper=True).name == colour, (colour, lower)
        assert np.array_equal(own_pixels(img), band), (colour, lower)
