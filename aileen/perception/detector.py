"""The shape detector at runtime: the shipped ONNX network (run by `inference`: onnxruntime
where installed, else OpenCV's dnn module).

The network (trained by `aileen.perception.train`; torch only there, in `net`, `warmstart`
and `distill`) is a small single-stage centre-heatmap detector in the manner of CenterNet:
for an RGB image of H x W it outputs, at stride 8, a (4 + 2 + 2 + 1) x H/8 x W/8 map: one
centre heatmap per shape class (sigmoid already applied), the sub-cell offset of the centre
(x, y, in cells), the box size (w, h, in cells) and the level score (sigmoid: the object
centred there rests on another one). A model without the level map (8 maps) reads every
object as on the table. Peaks of the heatmap are objects (`aileen.perception.decoding`); no
anchors, no NMS over boxes, and touching objects stay apart because their centres do.

Loading is cached per process and per path: opening a network takes a few ms and the agent
perceives after every action.
"""

from __future__ import annotations

import json
import os
import threading
from collections.abc import Sequence
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

import cv2
import numpy as np

from aileen.errors import UserError
from aileen.perception.decoding import DEFAULT_THRESHOLD, N_CLASSES, STRIDE, carrier_peak, decode, peak_box
from aileen.perception.inference import BACKEND_ENV, backend_name, open_network
from aileen.perception.ownpixels import OwnPixels, Window
from aileen.perception.pixels import crop_window, object_windows, overlap_share, unexplained_around
from aileen.world.camera import DEFAULT_CAMERA, Camera
from aileen.world.catalog import ELONGATED_FOOTPRINTS, SHAPES
from aileen.world.stacks import FLAT_TOPS

__all__ = [
    "RawDetection",
    "Detector",
    "DEFAULT_MODEL",
    "REBUILD_HINT",
    "decode",
    "detect",
    "load_detector",
    "check_image",
]

REBUILD_HINT = (
    "rebuild it with: aileen perception dataset --n 12000 --seed 0 --out /tmp/aileen-data && "
    "aileen perception train /tmp/aileen-data --out {path}"
)


def _default_model() -> Path:
    return Path(str(resources.files("aileen") / "models" / "detector.onnx"))


DEFAULT_MODEL = _default_model()

Box = tuple[float, float, float, float]


@dataclass(frozen=True)
class RawDetection:
    """One object as the detector network found it, before `perceive` measures its channels
    (the agent is handed `aileen.perception.perceiver.Detection`s, percepts and boxes only).
    Pixels are continuous image coordinates (u right, v down); metres are table coordinates
    (x east, y north) through the camera model."""

    box_px: Box  # (u0, v0, u1, v1)
    box_m: Box  # (x0, y0, x1, y1)
    centre_px: tuple[float, float]
    centre_m: tuple[float, float]
    shape: str  # catalog shape name
    score: float  # heatmap peak of the chosen shape
    shape_scores: dict[str, float] = field(default_factory=dict)
    level_score: float = 0.0  # the network's belief that it rests on another object
    level: int = 0  # 0 on the table, 1 resting on another object (set by `perception.stacking`)
    occluders: tuple[Box, ...] = ()  # pixel boxes of what rests on it (set by `perception.stacking`)
    footprint_m: float | None = None  # measured side or diameter, metres (set by `perceive`, once)


def check_image(image: object, camera: Camera = DEFAULT_CAMERA, *, what: str = "image") -> np.ndarray:
    """The image as a (H, W, 3) uint8 RGB array matching the camera, or a clear UserError."""
    if not isinstance(image, np.ndarray):
        raise UserError(f"{what}: expected an RGB image as a numpy array (H, W, 3) uint8, got {type(image).__name__}")
    if image.dtype != np.uint8:
        raise UserError(f"{what}: expected dtype uint8, got {image.dtype}")
    if image.ndim != 3 or image.shape[2] != 3:
        raise UserError(f"{what}: expected shape (H, W, 3), got {image.shape}")
    if image.shape[:2] != (camera.height, camera.width):
        raise UserError(
            f"{what}: expected {camera.height}x{camera.width} pixels for this camera, got {image.shape[0]}x{image.shape[1]}"
        )
    if camera.height % STRIDE or camera.width % STRIDE:
        raise UserError(f"{what}: image sides must be multiples of {STRIDE}, got {image.shape[1]}x{image.shape[0]}")
    return image


def shape_classes(classes: object) -> bool:
    """Whether a model's metadata "classes" is a list of distinct catalog shapes (a model may
    know fewer than the catalog: one trained before a shape joined it)."""
    return (isinstance(classes, list) and bool(classes) and all(isinstance(c, str) and c in SHAPES for c in classes)
            and len(set(classes)) == len(classes))


def check_metadata(meta: object, path: Path) -> dict:
    """The model's metadata, checked field by field: a wrong value would otherwise surface as
    a traceback mid-run (a string threshold) or silently (a threshold of 2.0 detects nothing)."""

    def bad(what: str) -> UserError:
        return UserError(f"{path}: malformed model metadata: {what}; " + REBUILD_HINT.format(path=path.with_suffix(".onnx")))

    if not isinstance(meta, dict):
        raise bad(f"expected a JSON object, found {type(meta).__name__}")
    for key in ("classes", "threshold"):  # every model `aileen perception train` writes has them
        if key not in meta:
            raise bad(f"no \"{key}\"")
    if "classes" in meta:
        cl = meta["classes"]
        if not shape_classes(cl):
            raise bad(f"\"classes\" must be a list of distinct shape names of {', '.join(SHAPES)}, found {cl!r}"[:300])
    if "threshold" in meta:
        t = meta["threshold"]
        if isinstance(t, bool) or not isinstance(t, (int, float)) or not 0.0 < t < 1.0:
            raise bad(f"\"threshold\" must be a number between 0 and 1 (exclusive), found {t!r}"[:300])
    if "input_size" in meta:
        sz = meta["input_size"]
        if (not isinstance(sz, list) or len(sz) != 2
                or not all(isinstance(x, int) and not isinstance(x, bool) and x > 0 for x in sz)):
            raise bad(f"\"input_size\" must be [height, width] in pixels, found {sz!r}"[:300])
    return meta


class Detector:
    """A loaded detector network; `detect(image)` -> list of RawDetection."""

    def __init__(self, path: Path, meta: dict, backend: str | None = None) -> None:
        self.path = path
        self.meta = meta
        self.classes: tuple[str, ...] = tuple(meta.get("classes", SHAPES))
        self.threshold = float(meta.get("threshold", DEFAULT_THRESHOLD))
        self._lock = threading.Lock()
        self._buf: np.ndarray | None = None
        try:
            self._net = open_network(path, backend)
        except ValueError as exc:
            raise UserError(f"{path}: not a valid ONNX detector model ({exc}); " + REBUILD_HINT.format(path=path)) from None

    @property
    def backend(self) -> str:
        """The runtime that runs the network: "onnxruntime" or "opencv" (`inference`)."""
        return self._net.backend

    @property
    def scores_levels(self) -> bool:
        """Whether the model says which objects rest on others (a level map, or one set of
        maps per level), by its metadata."""
        return "level" in str(self.meta.get("outputs", ""))

    @property
    def shapes(self) -> tuple[str, ...]:
        """The catalog's shapes this model was trained on, in catalog order (what `eval` and
        `compare` draw for it)."""
        return tuple(s for s in SHAPES if s in self.classes)

    @property
    def untrained(self) -> frozenset[str]:
        """The catalog's shapes this model was not trained on: it reads each as another shape
        (the shipped model and the capsule, docs/perception.md)."""
        return frozenset(SHAPES) - frozenset(self.shapes)

    @property
    def layered(self) -> bool:
        """Whether the model has one set of maps per level (its level scores are 0 or 1)."""
        return int(self.meta.get("layers", 1)) == 2

    def raw(self, image: np.ndarray) -> np.ndarray:
        """The network output (C + 4, C + 5 or 2 (C + 4), h, w) for an RGB uint8 image (see `decode`)."""
        with self._lock:  # a cv2.dnn.Net is not re-entrant, and the input buffer is shared
            # One input buffer, refilled in place: handing cv2.dnn a fresh blob each call
            # costs about 0.9 ms (a quarter of its forward pass) in re-setup.
            shape = (1, 3, image.shape[0], image.shape[1])
            if self._buf is None or self._buf.shape != shape:
                self._buf = np.empty(shape, dtype=np.float32)
            # channel by channel from OpenCV's split: a quarter faster than one multiply
            # over the transposed image, the same float32 products
            for c, plane in enumerate(cv2.split(image)):
                np.multiply(plane, np.float32(1.0 / 255.0), out=self._buf[0, c])
            out = self._net.run(self._buf)
        return out[0]

    def detect(self, image: np.ndarray, camera: Camera = DEFAULT_CAMERA, *, threshold: float | None = None,
               own: OwnPixels | None = None) -> list[RawDetection]:
        """The objects in an RGB image. `own`: the image's own pixels, kept by a caller that
        reads every object's next (perceive): those (`pixels.object_windows`) are then found
        in one batch with the contested peaks' (`_carried`)."""
        image = check_image(image, camera)
        size = self.meta.get("input_size")
        if size and tuple(image.shape[:2]) != tuple(size):
            raise UserError(f"{self.path}: this model takes {size[0]}x{size[1]} images, got {image.shape[0]}x{image.shape[1]}")
        contested: list = []
        out = self.raw(image)
        peaks = decode(out, threshold=self.threshold if threshold is None else threshold, contested=contested,
                       n_classes=len(self.classes))
        if own is not None:
            own.find([w for p in peaks for w in object_windows(image, _image_box(p, image))]
                     + _contested_windows(image, contested))
        peaks += _carried(image, peaks, contested, self.classes, own)
        peaks = _supported(peaks, self.classes)
        peaks += _unseen_carriers(out, image, peaks, self.classes, own)
        dets = []
        for peak in peaks:
            c, score, cu, cv_, _, _, cs, level = peak
            box_px = _image_box(peak, image)
            dets.append(
                RawDetection(
                    box_px=box_px,
                    box_m=camera.box_to_metres(box_px),
                    centre_px=(cu, cv_),
                    centre_m=camera.to_metres(cu, cv_),
                    shape=self.classes[c],
                    score=score,
                    shape_scores=dict(zip(self.classes, cs.tolist())),
                    level_score=level,
                )
            )
        return dets


def _image_box(peak: tuple, image: np.ndarray) -> Box:
    """A peak's box in pixels, clipped to the image: its detection's box."""
    h, w = image.shape[:2]
    _, _, cu, cv_, bw, bh, _, _ = peak
    return max(0.0, cu - bw / 2), max(0.0, cv_ - bh / 2), min(float(w), cu + bw / 2), min(float(h), cv_ + bh / 2)


# What shows of an object under another, at least (pixels; counted as
# `pixels.unexplained_around` does): a small box 13 % visible under a medium cylinder leaves
# 12. Around 600 single objects of every kind, anywhere, lit and noised as in training, it
# found none.
CARRIER_PIXELS = 6


def _contested_windows(image: np.ndarray, contested: list) -> list[Window]:
    """The boxes of the contested upper-layer peaks, whose own pixels `_carried` reads."""
    return [w for w in (crop_window(image, peak_box(up)) for up, _ in contested) if w[2] - w[0] >= 2 and w[3] - w[1] >= 2]


def _carried(image: np.ndarray, peaks: list, contested: list, classes: Sequence[str],
             own: OwnPixels | None = None) -> list:
    """The upper-layer peaks that lost to a lower-layer one (`decode`'s `contested`) but stand
    on something: around them show saturated pixels that neither they nor any other peak
    (the one they lost to aside) accounts for (`pixels.unexplained_around`; a peak of a
    shape that lies on its side, by the model's `classes`, read as one). An object on the
    table read twice leaves only wood around it. Their own pixels are found together (in
    `own`, when the caller keeps the image's)."""
    own = OwnPixels(image) if own is None else own
    own.find(_contested_windows(image, contested))
    out = []
    for up, rival in contested:
        others = [peak_box(k) for k in peaks if k is not rival]
        lying = classes[up[0]] in ELONGATED_FOOTPRINTS
        if unexplained_around(image, peak_box(up), others, own=own, elongated=lying) >= CARRIER_PIXELS:
            out.append(up)
    return out


# An upper-layer peak whose box lies this much (of the smaller box) over a lower-layer peak
# that cannot carry it is that object read twice (`_supported`).
TWICE_OVERLAP = 0.5


def _carries(low: tuple, up: tuple, classes: Sequence[str]) -> bool:
    """Whether a lower-layer peak could carry an upper one: of a shape with a flat top, its
    box (2 px to spare) under the upper one's centre."""
    u0, v0, u1, v1 = peak_box(low)
    return classes[low[0]] in FLAT_TOPS and u0 - 2 <= up[2] <= u1 + 2 and v0 - 2 <= up[3] <= v1 + 2


# A carrier's lower-layer peak is looked for at this block score (`decode`'s bar is 0.3), within
# this many of the upper object's box sides of its centre (the largest object under the
# smallest, its centre at most 95 % of its half side off: about 1.8).
CARRIER_FLOOR = 0.15
CARRIER_REACH = 2.0


def _unseen_carriers(out: np.ndarray, image: np.ndarray, peaks: list, classes: Sequence[str],
                     own: OwnPixels | None = None) -> list:
    """Carriers `decode` did not keep, for the upper-layer peaks nothing kept carries: the
    strongest lower-layer peak of a shape with a flat top under the upper one's centre, read
    at `CARRIER_FLOOR` (`decoding.carrier_peak`), when the image shows a sliver of an
    object around the upper one (`pixels.unexplained_around`, `CARRIER_PIXELS`, the evidence
    `_carried` reads), of another hue than the upper object's: an object standing on the
    table that the upper layer read leaves only wood around it, and a shape the model does
    not know, read as a smaller one on top (the shipped model's capsule: a small sphere),
    leaves the rest of itself, of its own hue."""
    flat = [i for i, c in enumerate(classes) if c in FLAT_TOPS]
    lower = [p for p in peaks if p[7] < 0.5]
    added: list = []
    for up in peaks:
        if up[7] < 0.5 or any(_carries(q, up, classes) for q in lower + added):
            continue
        reach = CARRIER_REACH * max(up[4], up[5])
        cand = carrier_peak(out, up, flat, CARRIER_FLOOR, reach, n_classes=len(classes))
        if cand is None:
            continue
        others = [peak_box(k) for k in peaks + added if k is not up]
        lying = classes[up[0]] in ELONGATED_FOOTPRINTS
        if unexplained_around(image, peak_box(up), others, own=own, elongated=lying, unlike=True) >= CARRIER_PIXELS:
            added.append(cand)
    return added


def _supported(peaks: list, classes: tuple[str, ...]) -> list:
    """The peaks without the upper-layer ones that nothing could carry: no lower-layer peak
    of a shape with a flat top (`world.stacks.FLAT_TOPS`) lies under its centre, and its
    box lies mostly (`TWICE_OVERLAP`) over a lower-layer peak of a shape without one. That
    is the one object read in both layers, boxed differently (a capsule's upper-layer reading,
    a cell or two off along its length, escapes `_same_object`)."""
    lower = [p for p in peaks if p[7] < 0.5]
    out = []
    for p in peaks:
        if p[7] >= 0.5 and not any(_carries(q, p, classes) for q in lower) and any(
                classes[q[0]] not in FLAT_TOPS and overlap_share(peak_box(p), peak_box(q)) > TWICE_OVERLAP for q in lower):
            continue
        out.append(p)
    return out


_CACHE: dict[tuple[Path, str], Detector] = {}
_SHIPPED: dict[str | None, Detector] = {}  # the shipped model by $AILEEN_DETECTOR_BACKEND, for the fast path
_CACHE_LOCK = threading.Lock()


def load_detector(path: str | Path | None = None, backend: str | None = None) -> Detector:
    """The detector at `path` (default: the shipped model) on the runtime `backend` names
    (default: `$AILEEN_DETECTOR_BACKEND`, else onnxruntime where installed, else OpenCV;
    `inference.backend_name`), loaded once per process.

    A missing or corrupt file raises UserError naming the path and how to rebuild it. The
    shipped model, once loaded, is handed back without asking the file system again (the
    agent perceives after every action; resolving the path cost about 60 us a call)."""
    if path is None and backend is None:
        det = _SHIPPED.get(os.environ.get(BACKEND_ENV))
        if det is not None:
            return det
    p = Path(path) if path is not None else DEFAULT_MODEL
    p = p.resolve() if p.exists() else p
    runtime = backend_name(backend)
    with _CACHE_LOCK:
        det = _CACHE.get((p, runtime))
        if det is None:
            if not p.is_file():
                raise UserError(f"{p}: detector model not found; " + REBUILD_HINT.format(path=p))
            if p.stat().st_size == 0:
                raise UserError(f"{p}: detector model is empty; " + REBUILD_HINT.format(path=p))
            meta_path = p.with_suffix(".json")
            meta: dict = {}
            if meta_path.is_file():
                try:
                    meta = json.loads(meta_path.read_text())
                except (OSError, ValueError, RecursionError) as exc:
                    why = "nested too deeply" if isinstance(exc, RecursionError) else str(exc)
                    raise UserError(f"{meta_path}: unreadable model metadata ({why}); "
                                    + REBUILD_HINT.format(path=p)) from None
                meta = check_metadata(meta, meta_path)
            det = Detector(p, meta, runtime)
            _CACHE[(p, runtime)] = det
        if path is None and backend is None:
            _SHIPPED[os.environ.get(BACKEND_ENV)] = det
        return det


def detect(image: np.ndarray, camera: Camera = DEFAULT_CAMERA, *, model: str | Path | None = None) -> list[RawDetection]:
    """Detect the objects in an RGB image with the shipped (or given) model."""
    return load_detector(model).detect(image, camera)


def measure_shape(image: np.ndarray, detection: RawDetection, camera: Camera = DEFAULT_CAMERA) -> tuple[str, float]:
    """The shape channel's measure (see `aileen.domain.channels`): the detector's own class,
    with 1 - its heatmap peak as the distance."""
    return detection.shape, 1.0 - float(detection.score)
