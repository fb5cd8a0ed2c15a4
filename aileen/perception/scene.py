"""`perceive(image) -> Scene`: the agent's one view of the world.

Detector boxes and shape percepts, the colour module's colour percept per box, and the QSR
facts between every ordered pair of objects, as `aileen.terms.Term`s:
`isa(o1,cv_box)`, `isa(o1,cv_red)`, then `w(o1,o2)`, `dc(o1,o2)`, ... Perceived ids are
`o1`, `o2`, ... ordered west to east (then south to north), so the same layout gets the same
ids; objects in one column (centres level in x to within the detector's 1-2 mm) may take
either order. The simulator's own ids never appear here.

Stacks: the detector's level score says which of two overlapping objects rests on the other
(`aileen.perception.stacking`); `PerceivedObject.level` carries it, so the stacking calculus
reports `st_on` / `st_under`, and the lower object's colour and size are measured on the
part of it that shows.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path

import cv2
import numpy as np

from aileen.domain.calculi import Calculus
from aileen.domain.channels import CHANNELS
from aileen.errors import UserError
from aileen.perception import refine
from aileen.perception.detector import RawDetection, check_image, load_detector
from aileen.perception.facts import scene_facts
from aileen.perception.ownpixels import OwnPixels
from aileen.perception.pixels import object_windows
from aileen.perception.size import measure_footprint
from aileen.perception.stacking import resolve_levels
from aileen.terms import Term, fn
from aileen.world.appearance import Appearance
from aileen.world.camera import DEFAULT_CAMERA, Camera

__all__ = ["PerceivedObject", "Scene", "perceive", "load_image"]

Box = tuple[float, float, float, float]


@dataclass(frozen=True)
class PerceivedObject:
    id: str  # o1, o2, ...
    box_px: Box  # (u0, v0, u1, v1) pixels
    box_m: Box  # (x0, y0, x1, y1) table metres
    centre_px: tuple[float, float]
    centre_m: tuple[float, float]
    values: Appearance  # channel name -> measured value ("shape": "box", "colour": "red", ...)
    footprint: float = 0.0  # measured side or diameter, metres
    level: int = 0  # 0 on the table, 1 resting on another object
    scores: dict[str, float] = field(default_factory=dict)  # shape heatmap per class, "<channel>_distance"

    @property
    def shape(self) -> str:
        return self.values["shape"]

    @property
    def colour(self) -> str:
        return self.values["colour"]

    @property
    def size(self) -> str:
        return self.values["size"]

    @property
    def percepts(self) -> tuple[str, ...]:
        """Percept symbols, one per channel in channel order."""
        return tuple(c.percept(self.values[c.name]) for c in CHANNELS)

    def percept_facts(self) -> list[Term]:
        return [fn("isa", self.id, p) for p in self.percepts]


@dataclass(frozen=True)
class Scene:
    objects: tuple[PerceivedObject, ...]
    facts: tuple[Term, ...]

    def get(self, obj_id: str) -> PerceivedObject:
        for o in self.objects:
            if o.id == obj_id:
                return o
        raise KeyError(obj_id)

    def boxes(self) -> dict[str, Box]:
        """Object id -> box in table metres (what `qsr_facts` and `sample_region` take)."""
        return {o.id: o.box_m for o in self.objects}

    def __len__(self) -> int:
        return len(self.objects)


def load_image(path: str | Path) -> np.ndarray:
    """Read an image file as RGB uint8; a clear UserError for missing, empty or non-image files."""
    p = Path(path)
    try:
        data = p.read_bytes()
    except OSError as exc:
        raise UserError(f"{p}: cannot read the image ({exc.strerror})") from None
    if not data:
        raise UserError(f"{p}: empty file, expected a PNG or JPEG image")
    img = cv2.imdecode(np.frombuffer(data, dtype=np.uint8), cv2.IMREAD_COLOR)
    if img is None:
        raise UserError(f"{p}: not an image OpenCV can read, expected a PNG or JPEG image")
    return cv2.cvtColor(img, cv2.COLOR_BGR2RGB)


def perceive(
    image: np.ndarray | str | Path,
    *,
    camera: Camera = DEFAULT_CAMERA,
    model: str | Path | None = None,
    held: Sequence[str] = (),
    senses: tuple[Calculus, ...] | None = None,
) -> Scene:
    """Objects (detector + colour module) and facts (percepts, then QSRs) of a camera image.

    `image` is an (H, W, 3) uint8 RGB array from the camera or an image file. An empty table
    gives a Scene with no objects and no facts. `held` lists perceived ids to add `held(X)`
    facts for (the agent knows what it holds; the camera does not see it). `senses` are the
    calculi of the facts (default: the default senses, `aileen.domain.calculi.senses`)."""
    what = "image"
    if isinstance(image, (str, Path)):
        what = str(image)
        image = load_image(image)
    image = check_image(image, camera, what=what)
    detector = load_detector(model)
    own = OwnPixels(image)  # each window's own pixels, found once in this call (most in one batch)
    dets = resolve_levels(detector.detect(image, camera, own=own), image, scored=detector.scores_levels,
                          layered=detector.layered)
    own.find(w for d in dets if not d.occluders for w in object_windows(image, d.box_px))  # any not found yet
    dets = refine.by_pixels(dets, image, camera, own)
    dets.sort(key=lambda d: (round(d.centre_m[0], 4), round(d.centre_m[1], 4)))
    # the footprint is measured once: the size channel and the calculi both read it
    dets = [replace(d, footprint_m=measure_footprint(image, d, camera, own)) for d in dets]
    # each channel measures all objects in one call (the colour module scores them together)
    readings = [channel.measure_all(image, dets, camera) for channel in CHANNELS]
    objects = [_perceived(f"o{i}", d, [r[i - 1] for r in readings]) for i, d in enumerate(dets, start=1)]
    facts = scene_facts(objects, senses)
    facts.extend(fn("held", h) for h in held)
    return Scene(tuple(objects), tuple(facts))


def _perceived(obj_id: str, d: RawDetection, readings: Sequence[tuple[str, float]]) -> PerceivedObject:
    """The object of a measured detection: each channel's (value, distance), in channel order."""
    values: dict[str, str] = {}
    scores = dict(d.shape_scores)
    for channel, (value, distance) in zip(CHANNELS, readings):
        values[channel.name], scores[f"{channel.name}_distance"] = value, distance
    return PerceivedObject(obj_id, d.box_px, d.box_m, d.centre_px, d.centre_m, Appearance(values),
                           d.footprint_m, d.level, scores)
