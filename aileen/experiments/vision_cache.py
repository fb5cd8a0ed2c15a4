"""What the visual module saw in an image, kept for the other trials of one run that see it.

Why: `aileen experiment all` runs each trial of an experiment once per learner (ours, the
paper's, nearest neighbour, COBWEB, TRESTLE): the same lessons and exam items, laid out from
the same seeds, so the same images, perceived again by every learner. Vision is a pure
function of the image (`aileen.perception.perceive`), and about half of all perceptions in a
run repeat one already made. `SharedVision` hands back the first result for an image seen
again: in this process from memory, and across the worker processes of one run through a
folder (`shared`, which `local_backend.shared_pool` opens for the pool's life) where each
result is written once, atomically, under the digest of the image's bytes. The detections are the
very ones vision gave, so every figure of the run is unchanged.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import pickle
import shutil
import tempfile
import threading
from collections import OrderedDict
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from aileen.perception.perceiver import Detection, Perceiver
from aileen.world.camera import DEFAULT_CAMERA, Camera

__all__ = ["SharedVision", "shared", "vision", "ENV", "stats"]

#: The environment variable that names the run's shared folder to its worker processes.
ENV = "AILEEN_VISION_CACHE"
#: Images remembered per process (the least recently seen go first).
KEPT = 4096

_MEMORY: OrderedDict[str, tuple[Detection, ...]] = OrderedDict()
_LOCK = threading.Lock()
_STATS = {"seen": 0, "remembered": 0, "shared": 0}


def stats() -> dict[str, int]:
    """This process's counts: images looked at, answered from memory, answered from the folder."""
    return dict(_STATS)


def digest(image: np.ndarray) -> str:
    """The image's identity: its shape, type and bytes."""
    h = hashlib.blake2b(repr((image.shape, image.dtype.str)).encode(), digest_size=20)
    h.update(np.ascontiguousarray(image).data)
    return h.hexdigest()


class SharedVision:
    """A perceiver answering an image seen before (in this process, or by another process
    writing to `folder`) with what `live` answered then; else asking `live`."""

    def __init__(self, live: Perceiver, folder: str | os.PathLike[str] | None = None) -> None:
        self.live = live
        self.folder = Path(folder) if folder else None

    def __call__(self, image: np.ndarray) -> list[Detection]:
        key = digest(image)
        with _LOCK:
            _STATS["seen"] += 1
            known = _MEMORY.get(key)
            if known is not None:
                _MEMORY.move_to_end(key)
                _STATS["remembered"] += 1
        if known is None and self.folder is not None:
            known = self._read(key)
            if known is not None:
                with _LOCK:
                    _STATS["shared"] += 1
        if known is None:
            known = tuple(self.live(image))
            self._write(key, known)
        with _LOCK:
            _MEMORY[key] = known
            while len(_MEMORY) > KEPT:
                _MEMORY.popitem(last=False)
        return list(known)

    def _read(self, key: str) -> tuple[Detection, ...] | None:
        assert self.folder is not None
        try:
            data = (self.folder / f"{key}.pickle").read_bytes()
            found = pickle.loads(data)
        except (OSError, pickle.UnpicklingError, EOFError, AttributeError, ValueError):
            return None  # not there (yet), or unreadable: vision answers
        return found if isinstance(found, tuple) and all(isinstance(d, Detection) for d in found) else None

    def _write(self, key: str, dets: tuple[Detection, ...]) -> None:
        if self.folder is None:
            return
        try:
            fd, tmp = tempfile.mkstemp(dir=self.folder, prefix=".part-")
            with os.fdopen(fd, "wb") as fh:
                fh.write(pickle.dumps(dets, protocol=pickle.HIGHEST_PROTOCOL))
            os.replace(tmp, self.folder / f"{key}.pickle")  # whole or not at all
        except OSError:
            with contextlib.suppress(OSError, UnboundLocalError):
                os.unlink(tmp)


def vision(camera: Camera = DEFAULT_CAMERA) -> SharedVision:
    """The shipped visual module (`aileen.agent.core.vision`), sharing what it saw with the
    run's other trials (through the folder `shared` names, when one is open)."""
    from aileen.agent.core import vision as live_vision

    return SharedVision(live_vision(camera), os.environ.get(ENV) or None)


@contextlib.contextmanager
def shared() -> Iterator[Path]:
    """A folder for the run's processes to share what vision saw: named to the processes
    started inside the block (through `ENV`), removed at its end."""
    folder = Path(tempfile.mkdtemp(prefix="aileen-vision-"))
    old = os.environ.get(ENV)
    os.environ[ENV] = str(folder)
    try:
        yield folder
    finally:
        if old is None:
            os.environ.pop(ENV, None)
        else:
            os.environ[ENV] = old
        shutil.rmtree(folder, ignore_errors=True)
