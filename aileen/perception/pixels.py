"""What an object's own pixels (`aileen.perception.ownpixels`) tell: its box and outline
when it is wholly in view, and the part of an object under another that the upper one hides.

What rests on an object is left out by that object's own pixels, found the same way in its
own box (it is wholly in view), grown by a pixel for its outline.

`unexplained_around` counts the saturated pixels around an object that neither it nor any
other detection accounts for: what shows of an object under it, when the detector read that
one only at the upper one's place (`aileen.perception.detector`).
"""

from __future__ import annotations

from collections.abc import Sequence

import cv2
import numpy as np

from aileen.perception.ownpixels import (CHROMA_TOL, MIN_SATURATION, OwnPixels, Window, hue_near, own_hue_pixels,
                                         own_pixels, saturated)

__all__ = ["overlap_share", "own_pixels", "own_box", "grown_window", "object_windows", "outline_fill", "hidden_mask",
           "crop_window", "unexplained_around", "MIN_SATURATION", "CHROMA_TOL", "outline", "outline_aspect"]

Box = Sequence[float]


def crop_window(image: np.ndarray, box_px: Box) -> tuple[int, int, int, int]:
    """The integer pixel window (u0, v0, u1, v1) of a box, clipped to the image."""
    h, w = image.shape[:2]
    u0, v0, u1, v1 = box_px
    return max(0, int(round(u0))), max(0, int(round(v0))), min(w, int(round(u1))), min(h, int(round(v1)))


def overlap_share(a: Box, b: Box) -> float:
    """Intersection area of two boxes over the smaller box's area (0 when apart)."""
    w = min(a[2], b[2]) - max(a[0], b[0])
    h = min(a[3], b[3]) - max(a[1], b[1])
    if w <= 0 or h <= 0:
        return 0.0
    small = min((a[2] - a[0]) * (a[3] - a[1]), (b[2] - b[0]) * (b[3] - b[1]))
    return w * h / max(small, 1e-9)


def hidden_mask(image: np.ndarray, window: tuple[int, int, int, int], occluders: Sequence[Box],
                own: OwnPixels | None = None) -> np.ndarray | None:
    """The pixels of `window` covered by the objects resting on it (their own pixels, grown
    by a pixel, from `own` when given), or None when nothing rests on it."""
    if not occluders:
        return None
    own = OwnPixels(image) if own is None else own
    u0, v0, u1, v1 = window
    full = np.zeros(image.shape[:2], dtype=np.uint8)
    for b in occluders:
        a0, b0, a1, b1 = crop_window(image, b)
        if a1 - a0 < 2 or b1 - b0 < 2:
            continue
        full[b0:b1, a0:a1] |= own((a0, b0, a1, b1)).astype(np.uint8)
    part = cv2.dilate(full[v0:v1, u0:u1], np.ones((3, 3), np.uint8))
    return part > 0


def unexplained_around(image: np.ndarray, box_px: Box, others: Sequence[Box], reach: float = 0.6,
                       own: OwnPixels | None = None, elongated: bool = False, unlike: bool = False) -> int:
    """The saturated pixels within `reach` of the box's smaller side around `box_px` that are
    neither the object's own (their convex hull, grown by a pixel for its outline) nor
    inside any of the boxes `others`, in pieces thicker than a pixel. An object on the table
    alone, or beside neighbours that are detected, leaves none (the wood is not saturated);
    one resting on another leaves what shows of that one. `own`: the image's own pixels,
    when the caller keeps them. `elongated`: the object is of a shape that lies on its side
    (`catalog.ELONGATED_FOOTPRINTS`, the capsule), whose own pixels are read by their hue
    (`ownpixels.own_hue_pixels`: its highlight runs its whole length). `unlike`: only the
    pixels whose hue lies more than `ownpixels.HUE_TOL` from the object's own count (a shape the model
    does not know, read as a smaller one, leaves the rest of itself around that one)."""
    u0, v0, u1, v1 = (float(c) for c in box_px)
    r = reach * min(u1 - u0, v1 - v0)
    a0, b0, a1, b1 = crop_window(image, (u0 - r, v0 - r, u1 + r, v1 + r))
    if a1 - a0 < 2 or b1 - b0 < 2:
        return 0
    free = saturated(image[b0:b1, a0:a1])
    for o in others:
        e0, f0, e1, f1 = crop_window(image, o)
        free[max(0, f0 - b0) : max(0, f1 - b0), max(0, e0 - a0) : max(0, e1 - a0)] = False
    # what is left only shrinks from here: none left, none to count (the usual case)
    if not free.any():
        return 0
    c0, d0, c1, d1 = crop_window(image, box_px)
    if c1 - c0 >= 2 and d1 - d0 >= 2:
        # every catalogued top is convex from above: its hull fills a highlight inside it
        mine = np.zeros(free.shape, dtype=np.uint8)
        mine[d0 - b0 : d1 - b0, c0 - a0 : c1 - a0] = (
            own_hue_pixels(image[d0:d1, c0:c1]) if elongated
            else (OwnPixels(image) if own is None else own)((c0, d0, c1, d1)))
        pts = cv2.findNonZero(mine)
        if pts is not None:
            cv2.fillConvexPoly(mine, cv2.convexHull(pts), 1)
        np.greater(free, cv2.dilate(mine, _SQUARE3), out=free)  # free and not grown mine
        if unlike and mine.any():
            np.logical_and(free, ~hue_near(image[b0:b1, a0:a1], mine.view(bool)), out=free)
        if not free.any():
            return 0
    # a 2 x 2 opening drops lines a pixel wide: the dark rim of a shaded object, whose
    # colour noise strays past its own pixels; what shows of an object is thicker
    return cv2.countNonZero(cv2.morphologyEx(free.view(np.uint8), cv2.MORPH_OPEN, _SQUARE2))


_SQUARE2 = np.ones((2, 2), np.uint8)
_SQUARE3 = np.ones((3, 3), np.uint8)


# `own_box` grows the detection box by this many pixels to look for the object's edges, and
# trusts what it finds only when each side agrees with the detection's to within this share.
OWN_BOX_GROW = 3
OWN_BOX_AGREE = 0.15
# An object's edge pixels, partly covered, do not pass as its own: the box of its own
# pixels lies this far (px) inside its footprint's on every side (300 single objects of
# every kind: 0.76-0.93 px per side on average, sd 0.3-0.4).
OWN_BOX_EDGE = 0.85


def grown_window(image: np.ndarray, box_px: Box) -> Window | None:
    """The window `_whole_mask` looks in: the box grown by `OWN_BOX_GROW` (None when under 4
    pixels a side)."""
    u0, v0, u1, v1 = (float(c) for c in box_px)
    a0, b0, a1, b1 = crop_window(image, (u0 - OWN_BOX_GROW, v0 - OWN_BOX_GROW, u1 + OWN_BOX_GROW, v1 + OWN_BOX_GROW))
    return None if a1 - a0 < 4 or b1 - b0 < 4 else (a0, b0, a1, b1)


def object_windows(image: np.ndarray, box_px: Box) -> list[Window]:
    """The windows whose own pixels perception reads of an object wholly in view: its box
    grown (`grown_window`: its outline, its own box) and its box (its footprint, and what it
    hides of an object under it), those of 2 pixels a side or more."""
    box = crop_window(image, box_px)
    return [w for w in (grown_window(image, box_px), box) if w is not None and w[2] - w[0] >= 2 and w[3] - w[1] >= 2]


def _whole_mask(image: np.ndarray, box_px: Box, own: OwnPixels | None = None) -> tuple[np.ndarray, int, int] | None:
    """An object's own pixels looked for in its box grown by `OWN_BOX_GROW` (`grown_window`;
    from `own` when given), with the window's corner (u, v); None when fewer than 12 stand
    out or they reach the window's edge (it runs on past the window: merged with a neighbour
    of its colour, or cut by the image's edge)."""
    window = grown_window(image, box_px)
    if window is None:
        return None
    a0, b0, a1, b1 = window
    mask = (OwnPixels(image) if own is None else own)(window)
    x, y, w, h = _extent(mask)
    if cv2.countNonZero(mask.view(np.uint8)) < 12 or x == 0 or y == 0 or x + w == a1 - a0 or y + h == b1 - b0:
        return None
    return mask, a0, b0


def _extent(mask: np.ndarray) -> tuple[int, int, int, int]:
    """The box (x, y, width, height) of a boolean mask's pixels, (0, 0, 0, 0) for none:
    OpenCV's `boundingRect`, a fraction of the cost of `np.nonzero` and four extremes."""
    return cv2.boundingRect(mask.view(np.uint8))


def own_box(image: np.ndarray, box_px: Box, own: OwnPixels | None = None) -> tuple[float, float, float, float] | None:
    """The box (u0, v0, u1, v1) of an object wholly in view, from its own pixels: the
    detector's box is a regression, good to a pixel or two, and two touching objects'
    boxes can then overlap by more than contact allows; the pixels' edges are exact (to the
    whole pixel, less the partly covered edge pixels: `OWN_BOX_EDGE`). None (keep the
    detector's box) when `_whole_mask` finds none, or when a side disagrees with the
    detection's by more than `OWN_BOX_AGREE` (a touching neighbour of the same colour merged
    with it). `own`: the image's own pixels found so far, when the caller keeps them."""
    found = _whole_mask(image, box_px, own)
    if found is None:
        return None
    mask, a0, b0 = found
    x, y, w, h = _extent(mask)
    e = OWN_BOX_EDGE
    out = (float(a0 + x - e), float(b0 + y - e), float(a0 + x + w + e), float(b0 + y + h + e))
    for side, ref in ((out[2] - out[0], box_px[2] - box_px[0]), (out[3] - out[1], box_px[3] - box_px[1])):
        if abs(side - ref) > OWN_BOX_AGREE * ref:
            return None
    return out


def outline(image: np.ndarray, box_px: Box, own: OwnPixels | None = None) -> tuple[float, float] | None:
    """(`outline_aspect`, `outline_fill`) of an object, from one look at its own pixels (in
    `own` when given) and one hull (refine asks both of every object wholly in view); None
    when either is."""
    found = _whole_mask(image, box_px, own)
    if found is None:
        return None
    pts = cv2.findNonZero(found[0].view(np.uint8))
    if pts is None or len(pts) < 60:
        return None
    hull = cv2.convexHull(pts)
    (_, _), (w, h), _ = cv2.minAreaRect(hull)
    if w <= 0 or h <= 0:
        return None
    aspect = float((min(w, h) + 1.0) / (max(w, h) + 1.0))
    # pixel centres: the hull of n x n pixels spans n - 1; add the half pixel all round
    fill = float((cv2.contourArea(hull) + 0.5 * cv2.arcLength(hull, True) + 1.0) / ((w + 1) * (h + 1)))
    return aspect, fill


def outline_aspect(image: np.ndarray, box_px: Box) -> float | None:
    """The short over the long side of the smallest rectangle around the convex hull of an
    object's own pixels: about 1 for a square or a disc, about a half for a lying capsule.
    None when `_whole_mask` finds no whole object, or fewer pixels than a fifth of a small one."""
    both = outline(image, box_px)
    return None if both is None else both[0]


def outline_fill(image: np.ndarray, box_px: Box) -> float | None:
    """How much of its smallest enclosing rectangle the convex hull of an object's own
    pixels fills: a square fills it (1, at any turn), a disc pi/4 (0.79); 400 single objects
    of every kind, lit and noised as in training, gave 0.79-0.86 for discs and 0.95-1.0
    for squares. None when `_whole_mask` finds no whole object, or fewer pixels than a fifth
    of a small one."""
    both = outline(image, box_px)
    return None if both is None else both[1]
