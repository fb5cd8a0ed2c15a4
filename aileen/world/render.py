"""The top-down camera: an RGB image of the table drawn with OpenCV and numpy, plus ground truth.

This module composes a frame: the lit table, each object's colours from its sprite, contact
shadows, sensor noise, and the ground truth with each object's visible share. How each shape
looks from above (its sprite: coverage, brightness and highlight maps on its own patch) is
`aileen.world.shading`, split off so each file holds one job.

Lighting: a directional light (azimuth, elevation), an overall intensity and a gentle linear
gradient across the table. With `seed=None` the light is fixed (from the north-west, neutral
intensity, no gradient) and the image is fully deterministic; with a seed, all of these vary
modestly (intensity only, never hue, so colours stay recognisable) and sensor noise can be
added. Only `aileen.world.camera.Camera` converts between metres and pixels.

Speed: each object is shaded on its own small patch (`aileen.world.shading`); the wooden
table texture is computed once per image size and cached.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import cv2
import numpy as np

from aileen.world import catalog
from aileen.world.appearance import LOOKS, Appearance, BodyChannels
from aileen.world.camera import DEFAULT_CAMERA, Camera
from aileen.world.records import WorldObject
from aileen.world.shading import (  # AMBIENT, DIFFUSE, OUTLINE_DARK, Patch: re-exported, their home before the split
    AMBIENT,
    DIFFUSE,
    OUTLINE_DARK,
    Patch,
    alpha_on,
    paint_looks,
    patch_grid,
    shade_patch,
)
from aileen.world.sim import World

__all__ = ["Truth", "Frame", "Lighting", "render", "lighting_for_seed", "NEUTRAL_LIGHTING", "save_png"]


@dataclass(frozen=True)
class Truth(BodyChannels):
    """Ground truth for one visible (not held) object; for training and evaluation only."""

    id: str
    appearance: Appearance  # every channel's value (shape, colour, size, any declared look)
    box_px: tuple[float, float, float, float]  # (u0, v0, u1, v1): pixel i spans [i, i+1)
    box_m: tuple[float, float, float, float]  # (x0, y0, x1, y1) metres
    centre_m: tuple[float, float]
    level: int = 0  # 0 on the table, 1 resting on another object
    on: str | None = None  # the id of the object it rests on
    visible: float = 1.0  # share of its drawn pixels that no object drawn over it covers


@dataclass(frozen=True)
class Frame:
    """One camera image (H, W, 3) uint8 RGB and the truth for the objects drawn in it."""

    image: np.ndarray
    truth: list[Truth]


@dataclass(frozen=True)
class Lighting:
    """A directional light and a table-wide brightness gradient.

    `azimuth` is the compass direction the light comes from, in radians counter-clockwise
    from east (so pi*3/4 is the north-west); `elevation` is its angle above the table.
    The brightness at a table point is `intensity * (1 + gradient * d)` where `d` in [-1, 1]
    is the point's position along `gradient_dir` (radians, from east) from the table centre.
    """

    azimuth: float = 3.0 * math.pi / 4.0
    elevation: float = math.radians(50.0)
    intensity: float = 1.0
    gradient: float = 0.0
    gradient_dir: float = 0.0

    def direction(self) -> np.ndarray:
        """Unit vector toward the light, table frame (x east, y north, z up)."""
        ce = math.cos(self.elevation)
        return np.array(
            [ce * math.cos(self.azimuth), ce * math.sin(self.azimuth), math.sin(self.elevation)], dtype=np.float32
        )


NEUTRAL_LIGHTING = Lighting()


def lighting_for_seed(seed: int | None) -> Lighting:
    """The lighting of a seeded render: modest, random variation; `None` gives the neutral light."""
    if seed is None:
        return NEUTRAL_LIGHTING
    rng = np.random.default_rng([seed, 0x11647])
    return Lighting(
        azimuth=float(rng.uniform(0.0, 2.0 * math.pi)),
        elevation=float(math.radians(rng.uniform(35.0, 70.0))),
        intensity=float(rng.uniform(0.85, 1.1)),
        gradient=float(rng.uniform(0.0, 0.08)),
        gradient_dir=float(rng.uniform(0.0, 2.0 * math.pi)),
    )


@lru_cache(maxsize=8)
def _table_texture(width: int, height: int) -> np.ndarray:
    """A light wooden table top (H, W, 3) float32 RGB, the same for every render of a size.

    The grain is a sum of slow waves across the image height, slightly warped along the
    width, plus fine noise: enough that a detector cannot treat the table as a flat colour.
    """
    rng = np.random.default_rng(20200)
    v = (np.arange(height, dtype=np.float32) + 0.5) / height
    u = (np.arange(width, dtype=np.float32) + 0.5) / width
    uu, vv = np.meshgrid(u, v)
    warp = 0.02 * np.sin(2 * np.pi * (1.3 * uu + rng.uniform()))
    grain = np.zeros_like(uu)
    for freq, amp in ((7.0, 0.025), (23.0, 0.015), (61.0, 0.01)):
        grain += amp * np.sin(2 * np.pi * (freq * (vv + warp) + rng.uniform()))
    fine = rng.normal(0.0, 0.012, size=uu.shape).astype(np.float32)
    gain = (1.0 + grain + fine).astype(np.float32)
    tex = np.asarray(catalog.TABLE_RGB, dtype=np.float32)[None, None, :] * gain[..., None]
    tex.setflags(write=False)
    return tex


@lru_cache(maxsize=8)
def _table_u8(width: int, height: int) -> np.ndarray:
    img = np.clip(_table_texture(width, height) + 0.5, 0, 255).astype(np.uint8)
    img.setflags(write=False)
    return img


def _gain_at(light: Lighting, camera: Camera, x: float, y: float) -> float:
    """Brightness factor of the light at a table point (intensity and gradient)."""
    t = camera.table
    dx = (x - t.width / 2.0) / (t.width / 2.0)
    dy = (y - t.depth / 2.0) / (t.depth / 2.0)
    d = dx * math.cos(light.gradient_dir) + dy * math.sin(light.gradient_dir)
    return light.intensity * (1.0 + light.gradient * d)


def _background(light: Lighting, camera: Camera) -> np.ndarray:
    """The lit table as uint8 RGB (a fresh, writable array)."""
    w, h = camera.width, camera.height
    if light.intensity == 1.0 and light.gradient == 0.0:
        return _table_u8(w, h).copy()
    # The gain is linear in position: an outer sum of one row and one column, applied by
    # OpenCV (several times faster than the same product in numpy).
    us = (np.arange(w, dtype=np.float32) + 0.5) / w * 2.0 - 1.0
    vs = 1.0 - (np.arange(h, dtype=np.float32) + 0.5) / h * 2.0  # +1 at the north (top) edge
    cx, cy = math.cos(light.gradient_dir), math.sin(light.gradient_dir)
    row = np.float32(light.intensity * light.gradient * cx) * us
    col = np.float32(light.intensity) + np.float32(light.intensity * light.gradient * cy) * vs
    gain = col[:, None] + row[None, :]
    return cv2.multiply(_table_texture(w, h), cv2.cvtColor(gain, cv2.COLOR_GRAY2RGB), dtype=cv2.CV_8U)


# The contact shadow an object casts on the one it rests on: displaced away from the light
# by this share of its footprint per unit of cot(elevation) (at most half its radius),
# blurred by SHADOW_BLUR px, darkening by up to SHADOW_DARK.
SHADOW_REACH = 0.12
SHADOW_BLUR = 1.5
SHADOW_DARK = 0.4


def _draw_shadow(img: np.ndarray, upper: WorldObject, lower: WorldObject, camera: Camera, L: np.ndarray) -> None:
    """Darken the lower object where the upper one's soft shadow falls on it, in place."""
    horiz = math.hypot(float(L[0]), float(L[1]))
    k = min(SHADOW_REACH * horiz / max(float(L[2]), 1e-3), 0.25)
    # Away from the light: image u follows -L_x, image v (down) follows +L_y.
    du = -float(L[0]) / max(horiz, 1e-9) * k * upper.footprint * camera.px_per_m_x
    dv = float(L[1]) / max(horiz, 1e-9) * k * upper.footprint * camera.px_per_m_y
    grid = patch_grid(lower, camera, margin=1.0)
    if grid is None:
        return
    window = grid[0]
    u0, v0, u1, v1 = window
    shade = alpha_on(upper, camera, window, (du, dv))
    shade = cv2.GaussianBlur(shade, (0, 0), SHADOW_BLUR)
    shade *= alpha_on(lower, camera, window)
    gain = 1.0 - SHADOW_DARK * shade
    patch = img[v0:v1, u0:u1].astype(np.float32) * gain[..., None]
    img[v0:v1, u0:u1] = cv2.convertScaleAbs(patch)


def _draw_object(
    img: np.ndarray, obj: WorldObject, camera: Camera, light: Lighting, L: np.ndarray
) -> tuple[float, float, float, float] | None:
    """Draw one object onto `img` in place; return its tight pixel box, or None if not visible."""
    grid = patch_grid(obj, camera)
    if grid is None:
        return None
    (u0, v0, u1, v1), X, Y, r_px = grid
    alpha, bright, spec = shade_patch(obj.shape, X, Y, obj.angle, r_px, L)
    drawn = alpha > 0.0
    rows = np.flatnonzero(drawn.any(axis=1))
    if rows.size == 0:
        return None
    cols = np.flatnonzero(drawn.any(axis=0))
    gain = _gain_at(light, camera, obj.x, obj.y)
    rgb = np.asarray(catalog.SHADES[obj.colour][obj.shade], dtype=np.float32)
    if LOOKS:
        bright, spec, rgb = paint_looks(obj, X, Y, r_px, L, alpha, bright, spec, rgb)
    colour = (bright * np.float32(gain))[..., None] * rgb
    if spec is not None:
        colour += (spec * np.float32(255.0 * min(gain, 1.0)))[..., None]
    colour_u8 = cv2.convertScaleAbs(colour)  # rounds and saturates
    patch = img[v0:v1, u0:u1]
    img[v0:v1, u0:u1] = cv2.blendLinear(colour_u8, patch, alpha, 1.0 - alpha)
    return (float(u0 + cols[0]), float(v0 + rows[0]), float(u0 + cols[-1] + 1), float(v0 + rows[-1] + 1))


def render(
    world: World,
    *,
    camera: Camera = DEFAULT_CAMERA,
    seed: int | None = None,
    lighting: bool = True,
    noise: float = 0.0,
) -> Frame:
    """Draw the table and every object on it (not the held one), with its ground truth.

    `seed` chooses the lighting variation and the sensor noise (None: neutral light, fully
    deterministic). `lighting=False` switches the directional light and its variation off:
    every surface shows its flat colour, outlines and highlights stay. `noise` is the
    standard deviation, in 8-bit levels, of Gaussian sensor noise added to every channel.
    Objects are drawn level by level (the table's first, then those resting on them, each
    level in insertion order), so an upper object covers the lower one, which shows its soft
    shadow; where objects of one level overlap (only while unsettled) the later covers the
    earlier. Each box covers all of its own drawn pixels, hidden ones included, so a partly
    hidden object's box is its whole footprint; `Truth.visible` says how much of it shows.
    """
    light = lighting_for_seed(seed) if lighting else NEUTRAL_LIGHTING
    L = light.direction() if lighting else np.array([0.0, 0.0, 1.0], dtype=np.float32)
    img = _background(light, camera)
    shown = sorted((o for o in world.objects() if not o.held), key=lambda o: o.level)  # stable: insertion order
    by_id = {o.id: o for o in shown}
    drawn: list[tuple[WorldObject, tuple[float, float, float, float]]] = []
    for obj in shown:
        lower = by_id.get(obj.on) if obj.on is not None else None
        if lower is not None:
            _draw_shadow(img, obj, lower, camera, L)
        box_px = _draw_object(img, obj, camera, light, L)
        if box_px is not None:
            drawn.append((obj, box_px))
    order = {o.id: k for k, o in enumerate(world.objects())}
    truth = sorted(  # in insertion order, as the world lists them
        (Truth(o.id, o.appearance, box, o.box_m(), (o.x, o.y), o.level, o.on, _visible(drawn, i, camera))
         for i, (o, box) in enumerate(drawn)),
        key=lambda t: order[t.id],
    )
    if noise > 0.0:
        img = _add_noise(img, noise, seed)
    return Frame(img, truth)


def _overlap(a: tuple[float, float, float, float], b: tuple[float, float, float, float]) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def _visible(drawn: list[tuple[WorldObject, tuple[float, float, float, float]]], i: int, camera: Camera) -> float:
    """The share of object i's drawn coverage that no object drawn after it covers."""
    obj, box = drawn[i]
    later = [o for o, b in drawn[i + 1 :] if _overlap(box, b)]
    if not later:
        return 1.0
    window = (int(box[0]), int(box[1]), int(box[2]), int(box[3]))
    own = alpha_on(obj, camera, window)
    cover = np.zeros_like(own)
    for o in later:
        np.maximum(cover, alpha_on(o, camera, window), out=cover)
    total = float(own.sum())
    return float((own * (1.0 - cover)).sum()) / total if total > 0 else 0.0


_NOISE_BANK_SIZE = 1 << 21


@lru_cache(maxsize=1)
def _noise_bank() -> np.ndarray:
    """Two million standard normal samples, drawn once (fixed seed)."""
    bank = np.random.default_rng(0x5E45).standard_normal(_NOISE_BANK_SIZE, dtype=np.float32)
    bank.setflags(write=False)
    return bank


def _add_noise(img: np.ndarray, noise: float, seed: int | None) -> np.ndarray:
    """Gaussian sensor noise with standard deviation `noise` (8-bit levels), chosen by `seed`.

    Drawing fresh normals for every pixel costs more than the whole render, so the noise
    is a window into a fixed bank of normal samples at a seeded offset, reversed or not:
    per pixel it is Gaussian, and different seeds give different (overlapping) windows.
    """
    n = img.size
    bank = _noise_bank()
    rng = np.random.default_rng([0 if seed is None else seed, 0x5E45])
    if n > bank.size:
        window = rng.standard_normal(n, dtype=np.float32)
    else:
        off = int(rng.integers(0, bank.size - n + 1))
        window = bank[off : off + n]
        if rng.integers(2):
            window = window[::-1]
    src = img.astype(np.float32)
    return cv2.addWeighted(src, 1.0, np.ascontiguousarray(window).reshape(img.shape), float(noise), 0.0, dtype=cv2.CV_8U)


def save_png(image: np.ndarray, path: str) -> None:
    """Write an RGB image as PNG atomically (`aileen.io`: keeps a link and the file's mode).

    cv2 writes BGR, so the channels are swapped here, at the boundary. Raises OSError when
    the file cannot be written.
    """
    from aileen.io import atomic_write_bytes

    ok, buf = cv2.imencode(".png", cv2.cvtColor(image, cv2.COLOR_RGB2BGR))
    if not ok:
        raise OSError(f"cannot encode a PNG for {path}")
    atomic_write_bytes(path, buf.tobytes())
