"""The size channel: small, medium or large, from the object's measured footprint.

The detector's box is axis-aligned, so a box-shaped object turned by 45 degrees has a box
1.4 times its side. The footprint is instead measured on the object's own pixels: inside the
detection box, its own pixels (`aileen.perception.pixels`: saturated, of its chromaticity) form a
mask whose minimum-area rectangle has the object's side (or a round object's diameter) as its
longer edge; a touching neighbour of another colour inside a turned box's box does not
stretch it (a lying capsule's length is the longer edge too; its own pixels are closed over
its specular streak first and looked for a few pixels past its box). The side is converted to metres
and read as the nearest catalogued size, with thresholds half-way between neighbouring
sizes. No ground truth is used.

An object with another resting on it is measured on the part of it that shows: the pixels
of what rests on it are left out (`RawDetection.occluders`, `aileen.perception.pixels`). The part that
shows is often a crescent or a corner, too little for a rectangle, and of one of the same
colour as what rests on it hardly anything can be told apart. Its size comes from its
detection box instead (the detector is trained to box a partly hidden object's whole
footprint): a disk's box side is its diameter; a square's box is its side times
|cos t| + |sin t|, with the turn t read from the square's visible straight edges. What the
camera cannot see at all it cannot measure.
"""

from __future__ import annotations

from collections.abc import Sequence

import cv2
import numpy as np

from aileen.perception.ownpixels import OwnPixels
from aileen.perception.pixels import OWN_BOX_GROW, crop_window, hidden_mask, own_pixels
from aileen.world import catalog
from aileen.world.camera import DEFAULT_CAMERA, Camera


def _turn(mask: np.ndarray, hidden: np.ndarray | None) -> float | None:
    """A square's turn (radians, modulo 90 degrees) from the orientation of its visible
    straight edges: the mask's gradient directions, fourfold, averaged on the circle, away
    from the hidden part's border; None when too little edge shows."""
    m = mask.astype(np.float32)
    gx = cv2.Sobel(m, cv2.CV_32F, 1, 0, ksize=3)
    gy = cv2.Sobel(m, cv2.CV_32F, 0, 1, ksize=3)
    mag = np.hypot(gx, gy)
    sel = mag > 0
    if hidden is not None:
        sel &= ~(cv2.dilate(hidden.astype(np.uint8), np.ones((5, 5), np.uint8)) > 0)
    # the edge pixels by flat index (a `take` costs a fraction of boolean indexing on
    # arrays this small; the values and their order are the same)
    idx = np.flatnonzero(sel)
    if len(idx) < 10:
        return None
    z = np.sum(mag.take(idx) * np.exp(4j * np.arctan2(gy.take(idx), gx.take(idx))))
    return float(np.angle(z)) / 4.0


# A lying capsule's specular streak runs its whole length and splits its colour in two: its
# own pixels are closed over gaps this wide (px) before they are measured.
STREAK_PX = 4


def footprint_px(
    image: np.ndarray, box_px: Sequence[float], exclude: Sequence[Sequence[float]] = (), *, round_shape: bool = False,
    elongated: float | None = None, own: OwnPixels | None = None,
) -> float:
    """The object's side or diameter in pixels, measured on its own pixels inside `box_px`
    (see `aileen.perception.pixels`), leaving out those of the objects in the boxes
    `exclude` (what rests on it): the longer
    side of their minimum-area rectangle; for a partly hidden object its box side (the
    detector infers the whole footprint's box), divided for a square by |cos t| + |sin t|
    with t its turn, read from its visible straight edges. The box's own longer side
    when too few pixels stand out. `elongated` (a lying capsule's width over its length):
    its length, on its own pixels closed over its specular streak, looked for a little
    past its box. `own`: the image's own pixels, when the caller keeps them."""
    own_box = box_px
    if elongated is not None:
        # its length is its longest extent, and a capsule's box, good to a pixel or two, can
        # cut its ends off: looked for a little past it (`pixels.OWN_BOX_GROW`)
        g = OWN_BOX_GROW
        box_px = (box_px[0] - g, box_px[1] - g, box_px[2] + g, box_px[3] + g)
    u0, v0, u1, v1 = crop_window(image, box_px)
    fallback = float(max(u1 - u0, v1 - v0))
    if u1 - u0 < 2 or v1 - v0 < 2:
        return fallback
    own = OwnPixels(image) if own is None else own
    hidden = hidden_mask(image, (u0, v0, u1, v1), exclude, own)
    if hidden is None and elongated is None:
        mask = own((u0, v0, u1, v1))  # the plain own pixels of the box
    else:
        mask = own_pixels(image[v0:v1, u0:u1], hidden, close=0 if elongated is None else STREAK_PX)
    pts = cv2.findNonZero(mask.astype(np.uint8))
    if pts is None or len(pts) < 6:
        return fallback
    occluded = hidden is not None and bool(hidden.any())
    if round_shape and occluded:
        return 0.5 * ((u1 - u0) + (v1 - v0))  # a disk's box is its diameter
    if occluded:
        # The box of a square turned by t is side * (|cos t| + |sin t|); the turn shows in
        # the straight edges that are left.
        t = _turn(mask, hidden)
        if t is not None:
            return _square_side(u1 - u0, v1 - v0, t)
    (_, _), (a, b), _ = cv2.minAreaRect(pts)
    side = float(max(a, b)) + 1.0  # pixel centres -> pixel edges
    if occluded:
        # A corner that shows alone is a triangle, whose rectangle runs along its long edge:
        # a square's side is never longer than its box.
        return min(side, fallback)
    if elongated is not None and not occluded:
        # Longer than its own box allows for a stadium of any turn: a neighbour of the same
        # colour, a few pixels off, was looked for past the box and closed onto it (a medium
        # capsule read large beside a box of its colour). Trust the box.
        boxed = _stadium_length(own_box[2] - own_box[0], own_box[3] - own_box[1], elongated)
        if boxed is not None and side > 1.1 * boxed:
            return boxed
    if not round_shape and side > 1.1 * fallback / SQRT2:
        # Longer than the box allows for a square of any turn but this one: a neighbour (or
        # the object under it) of the same colour merged with it. Trust box and turn.
        t = _turn(mask, None)
        if t is not None and side > 1.1 * _square_side(u1 - u0, v1 - v0, t):
            return _square_side(u1 - u0, v1 - v0, t)
    return side


SQRT2 = float(np.sqrt(2.0))


def _stadium_length(box_w: float, box_h: float, width: float) -> float | None:
    """The length L of a stadium `width` * L wide whose axis-aligned box is box_w x box_h,
    turned any way: its box is (1 - width) L |cos t| + width L by (1 - width) L |sin t| +
    width L, so (box_w - width L)^2 + (box_h - width L)^2 = ((1 - width) L)^2, whose smaller
    root is the length (the larger lies past the box). None when no stadium fits the box."""
    a = 2 * width * width - (1 - width) ** 2
    b = 2 * width * (box_w + box_h)
    c = box_w * box_w + box_h * box_h
    if abs(a) < 1e-12:
        return float(c / b) if b > 0 else None
    disc = b * b - 4 * a * c
    if disc < 0:
        return None
    roots = sorted(r for r in ((b - disc**0.5) / (2 * a), (b + disc**0.5) / (2 * a)) if r > 0)
    return float(roots[0]) if roots else None


def _square_side(box_w: float, box_h: float, turn: float) -> float:
    """The side of a square turned by `turn` whose axis-aligned box is box_w x box_h."""
    return float(0.5 * (box_w + box_h) / (abs(np.cos(turn)) + abs(np.sin(turn))))


def size_of(footprint_m: float) -> tuple[str, float]:
    """The nearest catalogued size of a footprint in metres, and its distance (metres)."""
    name = min(catalog.SIZES, key=lambda s: abs(catalog.SIZES[s] - footprint_m))
    return name, abs(catalog.SIZES[name] - footprint_m)


def measure_footprint(image: np.ndarray, detection, camera: Camera = DEFAULT_CAMERA, own: OwnPixels | None = None) -> float:
    """The object's side or diameter in metres, measured on its own pixels (once: a detection
    that carries its measured footprint is not measured again; from `own` when the caller
    keeps the image's)."""
    known = getattr(detection, "footprint_m", None)
    if known is not None:
        return float(known)
    shape = getattr(detection, "shape", "box")
    return footprint_px(image, detection.box_px, getattr(detection, "occluders", ()),
                        round_shape=shape not in catalog.SQUARE_FOOTPRINTS,
                        elongated=catalog.ELONGATED_FOOTPRINTS.get(shape), own=own) / camera.px_per_m_x


def measure_size(image: np.ndarray, detection, camera: Camera = DEFAULT_CAMERA) -> tuple[str, float]:
    """The size channel's measure (see `aileen.domain.channels`)."""
    return size_of(measure_footprint(image, detection, camera))
