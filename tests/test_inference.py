"""The detector's network on either runtime (`aileen.perception.inference`): onnxruntime (the
`fast` extra) and OpenCV's dnn give the same perception, everything discrete equal and every
float to float32's precision; the backend switch says what it expects."""

from __future__ import annotations

import numpy as np
import pytest

from aileen.errors import UserError
from aileen.perception import inference
from aileen.perception.dataset import SceneSpec, generate
from aileen.perception.detector import DEFAULT_MODEL, load_detector
from test_perceive_reference import differences


def test_an_unknown_backend_is_refused_with_the_choices(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(inference.BACKEND_ENV, "tensorrt")
    with pytest.raises(UserError, match="AILEEN_DETECTOR_BACKEND='tensorrt': expected one of auto, onnxruntime, opencv"):
        inference.backend_name()


def test_without_onnxruntime_auto_is_opencv_and_asking_for_it_says_how_to_install(
        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(inference, "_onnxruntime", lambda: None)
    monkeypatch.delenv(inference.BACKEND_ENV, raising=False)
    assert inference.backend_name() == inference.backend_name("auto") == "opencv"
    with pytest.raises(UserError, match=r'not installed: pip install -e "\.\[fast\]"'):
        inference.backend_name("onnxruntime")


def test_opencv_runs_the_shipped_model() -> None:
    det = load_detector(backend="opencv")
    assert det.backend == "opencv"
    img = next(iter(generate(1, 5, SceneSpec(3, 3, 0.0)))).image
    out = det.raw(img)
    assert out.shape[1:] == (32, 32) and np.isfinite(out).all()


def test_a_file_that_is_no_network_is_refused_on_either_runtime(tmp_path) -> None:  # noqa: ANN001
    bad = tmp_path / "m.onnx"
    bad.write_bytes(b"not a network at all")
    for backend in ("opencv",) + (("onnxruntime",) if inference._onnxruntime() else ()):
        with pytest.raises(UserError, match="m.onnx: not a valid ONNX detector model"):
            load_detector(bad, backend=backend)


def _detections(det, img) -> list[dict]:  # noqa: ANN001
    return [{"class": d.shape, "level": d.level, "box_px": [float(v) for v in d.box_px],
             "score": float(d.score)} for d in det.detect(img)]


def test_both_runtimes_see_the_same_objects() -> None:
    pytest.importorskip("onnxruntime")
    cv, ort = load_detector(DEFAULT_MODEL, backend="opencv"), load_detector(DEFAULT_MODEL, backend="onnxruntime")
    assert (cv.backend, ort.backend) == ("opencv", "onnxruntime")
    images = [s.image for s in generate(24, 77, SceneSpec(1, 6, 0.5, 0.2))]
    for i, img in enumerate(images):
        a, b = cv.raw(img), ort.raw(img)
        assert a.shape == b.shape
        np.testing.assert_allclose(b, a, rtol=1e-4, atol=1e-5, err_msg=f"scene {i}")
        assert differences(_detections(ort, img), _detections(cv, img)) == [], f"scene {i}"


def test_perceive_is_the_same_on_both_runtimes(monkeypatch: pytest.MonkeyPatch) -> None:
    pytest.importorskip("onnxruntime")
    from perceive_reference import scene_record

    from aileen.perception.scene import perceive

    images = [s.image for s in generate(16, 91, SceneSpec(2, 5, 0.6))]
    records = {}
    for backend in ("opencv", "onnxruntime"):
        monkeypatch.setenv(inference.BACKEND_ENV, backend)
        assert load_detector().backend == backend
        records[backend] = [scene_record(perceive(img)) for img in images]
    assert differences(records["onnxruntime"], records["opencv"]) == []
