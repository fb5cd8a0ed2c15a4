"""The top-down camera: an RGB image of the table drawn with OpenCV and numpy, plus ground truth.

The shapes have the same footprint size (the capsule's length) and differ only in how they
look from above, as a real overhead camera would see them:

- box: a square (rotated with the body) with a flat top and a bevel on each edge; each
  bevel faces another way, so the four bevels have four brightnesses, and a dark outline.
- cylinder: a flat, evenly lit disk with a chamfered rim: a ring that is bright on the side
  facing the light and dark on the other, inside a dark outline.
- sphere: a disk with a smooth radial (Lambert) gradient, dark at the limb, and a white
  specular highlight displaced toward the light.
- cone: a disk whose brightness depends on the direction around the centre (each slope
  faces another way), faint slope lines running to the apex, and a bright apex point.
- capsule: lying on its side, a stadium half as wide as long (rotated with the body),
  shaded like a sphere drawn out along its axis, a specular streak along the top and a
  faint seam across its middle.

Lighting: a directional light (azimuth, elevation), an overall intensity and a gentle linear
gradient across the table. With `seed=None` the light is fixed (from the north-west, neutral
intensity, no gradient) and the image is fully deterministic; with a seed, all of these vary
modestly (intensity only, never hue, so colours stay recognisable) and sensor noise can be
added. Only `aileen.world.camera.Camera` converts between metres and pixels.

Speed: each object is shaded on its own small patch (about 30x30 pixels for a medium object
on the 256x256 default) with vectorised numpy; the wooden table texture is computed once per
image size and cached.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import cv2
import numpy as np

from aileen.world import catalog
from aileen.world.appearance import LOOKS, Appearance, BodyChannels, Canvas
from aileen.world.camera import DEFAULT_CAMERA, Camera
from aileen.world.sim import World, WorldObject, footprint_half_extent

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

# Shading constants: ambient + diffuse * (n . L), normalised so a flat top under the light
# has brightness 1.0 (its colour is then exactly the catalog shade times the intensity).
AMBIENT = 0.45
DIFFUSE = 0.65
OUTLINE_DARK = 0.55  # brightness of the dark outline at an object's edge


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


def _shade_patch(
    shape: str, X: np.ndarray, Y: np.ndarray, angle: float, r_px: float, L: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """Alpha, brightness and specular (None: no highlight) maps of one object on its patch.

    X, Y are the pixel centres in units of the footprint's half size, relative to the
    object's centre (X east, Y north). `r_px` is the half size in pixels, for antialiasing.
    """
    declared = catalog.DECLARED_SHAPES.get(shape)
    if declared is not None:
        return _shade_declared(declared, X, Y, angle, r_px, L)
    flat = AMBIENT + DIFFUSE * float(L[2])

    def lambert(nx: np.ndarray | float, ny: np.ndarray | float, nz: np.ndarray | float) -> np.ndarray:
        return (AMBIENT + DIFFUSE * np.maximum(0.0, nx * L[0] + ny * L[1] + nz * L[2])) / flat

    spec = None
    if shape in catalog.SQUARE_FOOTPRINTS:
        c, s = math.cos(angle), math.sin(angle)
        bx = X * c + Y * s  # along the box's own x axis
        by = -X * s + Y * c
        ax, ay = np.abs(bx), np.abs(by)
        cheb = np.maximum(ax, ay)
        sd = (cheb - 1.0) * r_px
        bevel = 0.2
        t = math.sqrt(0.5)  # bevels slope at 45 degrees
        on_x = ax >= ay  # the east/west bevels (in the box's frame), else north/south
        sx = np.where(on_x, np.sign(bx), 0.0)
        sy = np.where(on_x, 0.0, np.sign(by))
        # The bevel's outward normal in the table frame.
        nx = (sx * c - sy * s) * t
        ny = (sx * s + sy * c) * t
        bright = np.where(cheb > 1.0 - bevel, lambert(nx, ny, t), 1.0)
        edge_dist = (1.0 - cheb) * r_px
    elif shape in catalog.ELONGATED_FOOTPRINTS:
        # A lying capsule: a cylinder with hemispherical ends, its axis along the body's x.
        w = catalog.ELONGATED_FOOTPRINTS[shape]  # end radius, in half lengths
        c, s = math.cos(angle), math.sin(angle)
        bx = X * c + Y * s
        by = -X * s + Y * c
        dx = bx - np.clip(bx, -(1.0 - w), 1.0 - w)  # from the nearest point of the axis
        dist = np.sqrt(dx * dx + by * by)
        sd = (dist - w) * r_px
        edge_dist = -sd
        rho = np.minimum(dist / w, 1.0)
        nz = np.sqrt(1.0 - rho * rho)
        nx, ny = (dx * c - by * s) / w, (dx * s + by * c) / w  # the surface normal, table frame
        bright = lambert(nx, ny, nz)
        # The seam where the capsule's two halves meet, a faint line across its middle.
        bright = bright * np.where(np.abs(bx) * r_px < 0.5, 0.85, 1.0)
        hx, hy, hz = L[0], L[1], L[2] + 1.0  # Blinn half vector with the camera above
        hn = math.sqrt(float(hx * hx + hy * hy + hz * hz))
        spec = 0.6 * np.maximum(0.0, (nx * hx + ny * hy + nz * hz) / hn) ** 30
    else:
        rho = np.sqrt(X * X + Y * Y)
        sd = (rho - 1.0) * r_px
        edge_dist = -sd
        safe = np.maximum(rho, 1e-6)
        ux, uy = X / safe, Y / safe  # outward unit direction
        if shape == "sphere":
            nz = np.sqrt(np.clip(1.0 - rho * rho, 0.0, 1.0))
            bright = lambert(X, Y, nz)
            hx, hy, hz = L[0], L[1], L[2] + 1.0  # Blinn half vector with the camera above
            hn = math.sqrt(float(hx * hx + hy * hy + hz * hz))
            ndoth = np.maximum(0.0, (X * hx + Y * hy + nz * hz) / hn)
            spec = 0.75 * ndoth**40
        elif shape == "cylinder":
            rim = 0.8
            t = math.sqrt(0.5)
            bright = np.where(rho > rim, lambert(ux * t, uy * t, t), 1.0)
            # A thin dark groove where the chamfer meets the top.
            groove = np.abs(rho - rim) * r_px
            bright = bright * np.where(groove < 0.6, 0.8, 1.0)
        elif shape == "cone":
            slope = math.atan2(1.3, 1.0)  # height 1.3 x radius: steep sides
            st, ct = math.sin(slope), math.cos(slope)
            bright = lambert(ux * st, uy * st, ct)
            # Slope lines: twelve faint rays from the apex.
            psi = np.arctan2(Y, X)
            k = 12
            ray = np.abs(((psi * k / (2 * math.pi)) + 0.5) % 1.0 - 0.5) * (2 * math.pi / k) * rho * r_px
            bright = bright * np.where((ray < 0.5) & (rho > 0.15), 0.88, 1.0)
            spec = 0.8 * np.clip(1.0 - rho / 0.12, 0.0, 1.0)  # the bright apex point
        else:  # pragma: no cover - shapes are checked when objects are added
            raise ValueError(shape)
    # A dark outline, about a pixel wide, where the object meets the table.
    bright = bright * (OUTLINE_DARK + (1.0 - OUTLINE_DARK) * np.clip(edge_dist, 0.0, 1.0))
    alpha = np.clip(0.5 - sd, 0.0, 1.0)
    return (
        np.ascontiguousarray(alpha, dtype=np.float32),
        np.ascontiguousarray(bright, dtype=np.float32),
        None if spec is None else np.ascontiguousarray(spec, dtype=np.float32),
    )


def _shade_declared(
    declared: catalog.Shape, X: np.ndarray, Y: np.ndarray, angle: float, r_px: float, L: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """`_shade_patch` for a declared shape: the silhouette of its footprint (a square turned
    by `angle`, or a disc), its top shaded by its own render function, the dark outline."""
    if declared.footprint == "square":
        c, s = math.cos(angle), math.sin(angle)
        cheb = np.maximum(np.abs(X * c + Y * s), np.abs(-X * s + Y * c))
        sd = (cheb - 1.0) * r_px
    else:
        sd = (np.sqrt(X * X + Y * Y) - 1.0) * r_px
    alpha = np.clip(0.5 - sd, 0.0, 1.0)
    canvas = Canvas(X, Y, angle, r_px, L, alpha, np.ones_like(X), None, None)
    if declared.render is not None:
        declared.render(declared.name, canvas)
    bright = canvas.bright * (OUTLINE_DARK + (1.0 - OUTLINE_DARK) * np.clip(-sd, 0.0, 1.0))
    return (
        np.ascontiguousarray(alpha, dtype=np.float32),
        np.ascontiguousarray(bright, dtype=np.float32),
        None if canvas.spec is None else np.ascontiguousarray(canvas.spec, dtype=np.float32),
    )


def _paint_looks(obj: WorldObject, X: np.ndarray, Y: np.ndarray, r_px: float, L: np.ndarray, alpha: np.ndarray,
                 bright: np.ndarray, spec: np.ndarray | None, rgb: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray]:
    """Each declared look the camera shows (`appearance.LOOKS`, in channel order) paints its
    value over the body: bright, specular and colour maps after them."""
    canvas = Canvas(X, Y, obj.angle, r_px, L, alpha, bright, spec, rgb)
    for name, look in LOOKS.items():
        if look.render is not None and name in obj.appearance:
            look.render(obj.appearance[name], canvas)
    return (np.asarray(canvas.bright, dtype=np.float32),
            None if canvas.spec is None else np.asarray(canvas.spec, dtype=np.float32),
            np.asarray(canvas.rgb, dtype=np.float32))


Patch = tuple[int, int, int, int]  # (u0, v0, u1, v1) integer pixel window


def _patch_grid(
    obj: WorldObject, camera: Camera, margin: float = 1.0, shift: tuple[float, float] = (0.0, 0.0)
) -> tuple[Patch, np.ndarray, np.ndarray, float] | None:
    """The pixel window around an object's footprint (plus `margin` px, its centre moved by
    `shift` px) and the window's pixel centres in units of the footprint's half size
    (X east, Y north), with that half size in pixels; None when off the image."""
    cu, cv = camera.to_pixels(obj.x, obj.y)
    cu, cv = cu + shift[0], cv + shift[1]
    r_u = obj.footprint / 2.0 * camera.px_per_m_x
    r_v = obj.footprint / 2.0 * camera.px_per_m_y
    half = footprint_half_extent(obj.shape, obj.footprint, obj.angle) / (obj.footprint / 2.0)
    u0 = max(0, int(math.floor(cu - half * r_u - margin)))
    u1 = min(camera.width, int(math.ceil(cu + half * r_u + margin)))
    v0 = max(0, int(math.floor(cv - half * r_v - margin)))
    v1 = min(camera.height, int(math.ceil(cv + half * r_v + margin)))
    if u0 >= u1 or v0 >= v1:
        return None
    X = ((np.arange(u0, u1, dtype=np.float32) + 0.5 - cu) / r_u)[None, :]
    Y = ((cv - 0.5 - np.arange(v0, v1, dtype=np.float32)) / r_v)[:, None]
    X, Y = (np.ascontiguousarray(a) for a in np.broadcast_arrays(X, Y))
    return (u0, v0, u1, v1), X, Y, 0.5 * (r_u + r_v)


def _alpha_on(obj: WorldObject, camera: Camera, window: Patch, shift: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    """The object's coverage (0..1) on a given pixel window, its centre moved by `shift` px."""
    u0, v0, u1, v1 = window
    cu, cv = camera.to_pixels(obj.x, obj.y)
    r_u = obj.footprint / 2.0 * camera.px_per_m_x
    r_v = obj.footprint / 2.0 * camera.px_per_m_y
    X = ((np.arange(u0, u1, dtype=np.float32) + 0.5 - cu - shift[0]) / r_u)[None, :]
    Y = ((cv + shift[1] - 0.5 - np.arange(v0, v1, dtype=np.float32)) / r_v)[:, None]
    X, Y = (np.ascontiguousarray(a) for a in np.broadcast_arrays(X, Y))
    alpha, _, _ = _shade_patch(obj.shape, X, Y, obj.angle, 0.5 * (r_u + r_v), np.array([0.0, 0.0, 1.0], np.float32))
    return alpha


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
    grid = _patch_grid(lower, camera, margin=1.0)
    if grid is None:
        return
    window = grid[0]
    u0, v0, u1, v1 = window
    shade = _alpha_on(upper, camera, window, (du, dv))
    shade = cv2.GaussianBlur(shade, (0, 0), SHADOW_BLUR)
    shade *= _alpha_on(lower, camera, window)
    gain = 1.0 - SHADOW_DARK * shade
    patch = img[v0:v1, u0:u1].astype(np.float32) * gain[..., None]
    img[v0:v1, u0:u1] = cv2.convertScaleAbs(patch)


def _draw_object(
    img: np.ndarray, obj: WorldObject, camera: Camera, light: Lighting, L: np.ndarray
) -> tuple[float, float, float, float] | None:
    """Draw one object onto `img` in place; return its tight pixel box, or None if not visible."""
    grid = _patch_grid(obj, camera)
    if grid is None:
        return None
    (u0, v0, u1, v1), X, Y, r_px = grid
    alpha, bright, spec = _shade_patch(obj.shape, X, Y, obj.angle, r_px, L)
    drawn = alpha > 0.0
    rows = np.flatnonzero(drawn.any(axis=1))
    if rows.size == 0:
        return None
    cols = np.flatnonzero(drawn.any(axis=0))
    gain = _gain_at(light, camera, obj.x, obj.y)
    rgb = np.asarray(catalog.SHADES[obj.colour][obj.shade], dtype=np.float32)
    if LOOKS:
        bright, spec, rgb = _paint_looks(obj, X, Y, r_px, L, alpha, bright, spec, rgb)
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
    own = _alpha_on(obj, camera, window)
    cover = np.zeros_like(own)
    for o in later:
        np.maximum(cover, _alpha_on(o, camera, window), out=cover)
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
