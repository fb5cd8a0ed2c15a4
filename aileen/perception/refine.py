"""Where the image's pixels correct the detector, for objects wholly in view.

The detector's boxes are regressions, good to a pixel or two, and its square-or-disc call is
learned; an object's own pixels (`aileen.perception.pixels`) are exact where it is wholly in
view, but only to the whole pixel, and a neighbour of its colour can merge with them. So the
pixels are asked only where the detector is known to slip: two touching objects whose boxes
overlap (`_touching`), and whether the object's outline is a square, a disc or long
(`_square_or_disc`). Partly hidden objects keep the detector's reading.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from aileen.perception.detector import RawDetection
from aileen.perception.ownpixels import OwnPixels
from aileen.perception.pixels import outline, own_box
from aileen.world.camera import Camera
from aileen.world.catalog import ELONGATED_FOOTPRINTS, SQUARE_FOOTPRINTS

__all__ = ["by_pixels", "SQUARE_FILL"]

Box = tuple[float, float, float, float]
# An outline filling more of its enclosing rectangle than this is a square: single objects
# of every kind gave 0.79-0.86 for discs and 0.95-1.0 for squares (`pixels.outline_fill`).
SQUARE_FILL = 0.9
# An outline shorter across than this share of its length is long: a lying capsule's
# (`pixels.outline_aspect`: 0.47-0.54 for capsules, 0.94-1.0 for every other shape).
LONG_ASPECT = 0.75


def by_pixels(dets: list[RawDetection], image: np.ndarray, camera: Camera,
              own: OwnPixels | None = None) -> list[RawDetection]:
    """The detections (same order) with the pixels' corrections: shapes first, as the
    boxes' own pixels are looked for by shape-independent means. `own`: the image's own
    pixels, when the caller keeps them (perceive finds all objects' at once)."""
    return _touching([_square_or_disc(d, image, own) for d in dets], image, camera, own)


def _square_or_disc(d: RawDetection, image: np.ndarray, own: OwnPixels | None = None) -> RawDetection:
    """A wholly visible object whose outline says square where the detector says a disc
    shape (or the other way), or long where it says round (or the other way), takes the
    detector's best-scoring shape of the outline's kind. A capsule's stadium is long
    (`outline_aspect` 0.47-0.54 on 100 single capsules, every other shape 0.94-1.0), and its
    fill (about 0.89) lies between a square's and a disc's: it is no square or disc call."""
    if d.occluders:
        return d
    found = outline(image, d.box_px, own)  # `outline_aspect` and `outline_fill`, from one look
    if found is None:
        return d
    aspect, fill = found
    if aspect < LONG_ASPECT:
        kind = [s for s in d.shape_scores if s in ELONGATED_FOOTPRINTS]
    else:
        square = fill > SQUARE_FILL
        kind = [s for s in d.shape_scores if (s in SQUARE_FOOTPRINTS) == square and s not in ELONGATED_FOOTPRINTS]
    if d.shape in kind or not kind:
        return d
    best = max(kind, key=lambda s: d.shape_scores[s])
    return replace(d, shape=best, score=d.shape_scores[best])


def _touching(dets: list[RawDetection], image: np.ndarray, camera: Camera,
              own: OwnPixels | None = None) -> list[RawDetection]:
    """Objects on one level never overlap (the world keeps them apart), but the detector's
    boxes, good to a pixel or two, of two that touch can overlap by more than contact allows
    (`geometry.DEFAULT_Q`) and read `po`. Such a pair, each wholly in view, takes its boxes from
    its own pixels (`pixels.own_box`): whole pixels, so a centre moves by up to half a pixel,
    which is why it is not done for every object."""
    touching: set[int] = set()
    for i, a in enumerate(dets):
        for j in range(i + 1, len(dets)):
            b = dets[j]
            if a.level == b.level and not a.occluders and not b.occluders and _box_overlap(a.box_px, b.box_px) > 0.0:
                touching.update((i, j))
    return [_own_box(d, image, camera, own) if i in touching else d for i, d in enumerate(dets)]


def _box_overlap(a: Box, b: Box) -> float:
    """How far two boxes reach into each other (pixels, the smaller axis), 0 when apart."""
    return max(0.0, min(min(a[2], b[2]) - max(a[0], b[0]), min(a[3], b[3]) - max(a[1], b[1])))


def _own_box(d: RawDetection, image: np.ndarray, camera: Camera, own: OwnPixels | None = None) -> RawDetection:
    """The detection with its box and centre read off its own pixels (`pixels.own_box`),
    when they can be."""
    b = own_box(image, d.box_px, own)
    if b is None:
        return d
    cu, cv_ = (b[0] + b[2]) / 2, (b[1] + b[3]) / 2
    return replace(d, box_px=b, box_m=camera.box_to_metres(b), centre_px=(cu, cv_), centre_m=camera.to_metres(cu, cv_))
