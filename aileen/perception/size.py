"""The size channel: small, medium or large, from the object's measured footprint.

The detector's box is axis-aligned, so a box-shaped object turned by 45 degrees has a box
1.4 times its side. The footprint is instead measured on the object's own pixels: inside the
detection box, the pixels that stand out from the table (saturated, not the pale wood) form a
mask whose minimum-area rectangle has the object's side (or a round object's diameter) as its
longer edge. The side is converted to metres and read as the nearest catalogued size, with
thresholds half-way between neighbouring sizes. No ground truth is used.

An object with another resting on it is measured on the part of it that shows: the pixels
inside the boxes of what rests on it are left out (`Detection.occluders`). The part that
shows still spans the whole side in at least one direction for an upper object offset from
the lower one's centre, so the rectangle's longer edge is still the side; what the camera
cannot see at all it cannot measure.
"""

from __future__ import annotations

from collections.abc import Sequence

import cv2
import numpy as np

from aileen.world import catalog
from aileen.world.camera import DEFAULT_CAMERA, Camera

# Table wood is pale (HSV saturation about 60/255 under any lighting); every catalogued
# colour is above 130. Half-way leaves room for shading and sensor noise.
MIN_SATURATION = 95


def footprint_px(image: np.ndarray, box_px: Sequence[float], exclude: Sequence[Sequence[float]] = ()) -> float:
    """The longer side, in pixels, of the minimum-area rectangle around the object's pixels
    inside `box_px` and outside every box in `exclude` (grown by a pixel); the box's own
    longer side when too few pixels stand out."""
    u0, v0, u1, v1 = (int(round(c)) for c in box_px)
    h, w = image.shape[:2]
    u0, v0, u1, v1 = max(0, u0), max(0, v0), min(w, u1), min(h, v1)
    fallback = float(max(u1 - u0, v1 - v0))
    if u1 - u0 < 2 or v1 - v0 < 2:
        return fallback
    hsv = cv2.cvtColor(np.ascontiguousarray(image[v0:v1, u0:u1]), cv2.COLOR_RGB2HSV)
    sat = hsv[..., 1] >= MIN_SATURATION
    if exclude:
        uu = np.arange(u0, u1)[None, :] + 0.5
        vv = np.arange(v0, v1)[:, None] + 0.5
        for b in exclude:
            sat &= ~((uu >= b[0] - 1.0) & (uu < b[2] + 1.0) & (vv >= b[1] - 1.0) & (vv < b[3] + 1.0))
    mask = sat.astype(np.uint8)
    pts = cv2.findNonZero(mask)
    if pts is None or len(pts) < 6:
        return fallback
    (_, _), (a, b), _ = cv2.minAreaRect(pts)
    return float(max(a, b)) + 1.0  # pixel centres -> pixel edges


def size_of(footprint_m: float) -> tuple[str, float]:
    """The nearest catalogued size of a footprint in metres, and its distance (metres)."""
    name = min(catalog.SIZES, key=lambda s: abs(catalog.SIZES[s] - footprint_m))
    return name, abs(catalog.SIZES[name] - footprint_m)


def measure_footprint(image: np.ndarray, detection, camera: Camera = DEFAULT_CAMERA) -> float:
    """The object's side or diameter in metres, measured on its own pixels."""
    return footprint_px(image, detection.box_px, getattr(detection, "occluders", ())) / camera.px_per_m_x


def measure_size(image: np.ndarray, detection, camera: Camera = DEFAULT_CAMERA) -> tuple[str, float]:
    """The size channel's measure (see `aileen.domain.channels`)."""
    return size_of(measure_footprint(image, detection, camera))
