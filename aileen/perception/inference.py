"""Runs the detector's ONNX network: onnxruntime where it is installed, else OpenCV's dnn.

Why two runtimes: OpenCV is a runtime dependency anyway (the colour module, the renderer),
and its `dnn` module runs the shipped network, so a plain install needs nothing more. But
for a network this small onnxruntime's kernels are about 2.5 times faster on one thread
(2.6 against 6.2 ms on a 2-core Xeon; docs/perception.md, "Speed"), and the forward pass is
most of `perceive()`. The `fast` extra (`pip install -e ".[fast]"`) installs it.

`AILEEN_DETECTOR_BACKEND` picks one: `auto` (the default: onnxruntime if it imports, else
OpenCV), `onnxruntime` or `opencv`. The two agree to float32's precision (the same network
in float32, different summation orders) and a test holds their `perceive()` outputs equal in
everything discrete on rendered scenes.

This is the only module that talks to either runtime about networks.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Protocol

import cv2
import numpy as np

from aileen.errors import UserError

__all__ = ["BACKENDS", "BACKEND_ENV", "Network", "backend_name", "open_network"]

BACKEND_ENV = "AILEEN_DETECTOR_BACKEND"
BACKENDS = ("auto", "onnxruntime", "opencv")


class Network(Protocol):
    """A loaded network with one input and one output."""

    backend: str

    def run(self, x: np.ndarray) -> np.ndarray:
        """The output for a float32 NCHW input (the caller may reuse `x` after the call)."""
        ...


class _OpenCVNet:
    backend = "opencv"

    def __init__(self, path: Path) -> None:
        self._net = cv2.dnn.readNetFromONNX(str(path))

    def run(self, x: np.ndarray) -> np.ndarray:
        self._net.setInput(x)
        return self._net.forward()


class _OrtNet:
    backend = "onnxruntime"

    def __init__(self, path: Path, ort) -> None:  # noqa: ANN001 (the module, imported lazily)
        so = ort.SessionOptions()
        # As many threads as OpenCV is told to use (experiment workers set 1), never spinning
        # between calls: the agent perceives once per action, and a spinning pool would take
        # a core from the reasoner in between.
        so.intra_op_num_threads = max(1, cv2.getNumThreads())
        so.inter_op_num_threads = 1
        so.execution_mode = ort.ExecutionMode.ORT_SEQUENTIAL
        so.graph_optimization_level = ort.GraphOptimizationLevel.ORT_ENABLE_ALL
        so.add_session_config_entry("session.intra_op.allow_spinning", "0")
        so.log_severity_level = 3
        self._session = ort.InferenceSession(str(path), so, providers=["CPUExecutionProvider"])
        self._input = self._session.get_inputs()[0].name
        self.threads = so.intra_op_num_threads

    def run(self, x: np.ndarray) -> np.ndarray:
        return self._session.run(None, {self._input: x})[0]


def _onnxruntime():  # noqa: ANN202
    try:
        import onnxruntime
    except ImportError:
        return None
    return onnxruntime


def backend_name(requested: str | None = None) -> str:
    """The runtime `open_network` would use: `requested`, else `$AILEEN_DETECTOR_BACKEND`,
    else `auto`, resolved to `onnxruntime` or `opencv`."""
    want = (requested or os.environ.get(BACKEND_ENV) or "auto").strip().lower()
    if want not in BACKENDS:
        raise UserError(f"{BACKEND_ENV}={want!r}: expected one of {', '.join(BACKENDS)}")
    if want == "auto":
        return "onnxruntime" if _onnxruntime() is not None else "opencv"
    if want == "onnxruntime" and _onnxruntime() is None:
        raise UserError(f"{BACKEND_ENV}=onnxruntime, but onnxruntime is not installed: "
                        "pip install -e \".[fast]\" (or choose opencv)")
    return want


def open_network(path: Path, backend: str | None = None) -> Network:
    """The ONNX network at `path` on the runtime `backend_name(backend)` names.

    A file neither runtime can read raises ValueError with the runtime's own reason (the
    caller names the file and how to rebuild it)."""
    name = backend_name(backend)
    if name == "onnxruntime":
        ort = _onnxruntime()
        try:
            return _OrtNet(path, ort)
        except Exception as exc:  # onnxruntime raises its own exception types for bad files
            raise ValueError(str(exc).strip().splitlines()[-1][:120]) from None
    try:
        return _OpenCVNet(path)
    except cv2.error as exc:
        raise ValueError(str(exc).strip().splitlines()[-1][:120]) from None
