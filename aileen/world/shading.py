"""How each shape looks from above: its coverage, brightness and highlight on its own patch.

Split from `aileen.world.render` so each file holds one job: this one draws one object's
sprite (the maps of one object on a small pixel window, in units of its footprint), that one
composes a frame from them (the lit table, the colours, contact shadows, sensor noise and
the ground truth with each object's visible share).

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

A declared shape (`catalog.Shape`) draws its top with its own render function, and each
declared look (`appearance.LOOKS`) paints its value over the body, both on a `Canvas`.

Speed: each object is shaded on its own small patch (about 30x30 pixels for a medium object
on the 256x256 default) with vectorised numpy.
"""

from __future__ import annotations

import math

import numpy as np

from aileen.world import catalog
from aileen.world.appearance import LOOKS, Canvas
from aileen.world.camera import Camera
from aileen.world.records import WorldObject, footprint_half_extent

__all__ = ["AMBIENT", "DIFFUSE", "OUTLINE_DARK", "Patch", "shade_patch", "paint_looks", "patch_grid", "alpha_on"]

# Shading constants: ambient + diffuse * (n . L), normalised so a flat top under the light
# has brightness 1.0 (its colour is then exactly the catalog shade times the intensity).
AMBIENT = 0.45
DIFFUSE = 0.65
OUTLINE_DARK = 0.55  # brightness of the dark outline at an object's edge


def shade_patch(
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
    """`shade_patch` for a declared shape: the silhouette of its footprint (a square turned
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


def paint_looks(obj: WorldObject, X: np.ndarray, Y: np.ndarray, r_px: float, L: np.ndarray, alpha: np.ndarray,
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


def patch_grid(
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


def alpha_on(obj: WorldObject, camera: Camera, window: Patch, shift: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    """The object's coverage (0..1) on a given pixel window, its centre moved by `shift` px."""
    u0, v0, u1, v1 = window
    cu, cv = camera.to_pixels(obj.x, obj.y)
    r_u = obj.footprint / 2.0 * camera.px_per_m_x
    r_v = obj.footprint / 2.0 * camera.px_per_m_y
    X = ((np.arange(u0, u1, dtype=np.float32) + 0.5 - cu - shift[0]) / r_u)[None, :]
    Y = ((cv + shift[1] - 0.5 - np.arange(v0, v1, dtype=np.float32)) / r_v)[:, None]
    X, Y = (np.ascontiguousarray(a) for a in np.broadcast_arrays(X, Y))
    alpha, _, _ = shade_patch(obj.shape, X, Y, obj.angle, 0.5 * (r_u + r_v), np.array([0.0, 0.0, 1.0], np.float32))
    return alpha
