"""Distillation (`train --distill MODEL.onnx`): the student learns a teacher's maps beside the
labels (skipped without torch)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from aileen.errors import UserError
from aileen.perception.dataset import write_dataset

torch = pytest.importorskip("torch")
pytest.importorskip("onnx")


def _terms(lines: list[str]) -> dict[str, float]:
    """The loss terms of a run's last step line (`step N/N name value ...`)."""
    line = [s for s in lines if s.startswith("step ")][-1]
    words = line.split("(")[0].split()[2:]
    return {k: float(v) for k, v in zip(words[::2], words[1::2])}


def test_a_distilled_run_trains_and_exports(tmp_path, capsys) -> None:
    from aileen.cli import main
    from aileen.perception.detector import DEFAULT_MODEL, decode, load_detector

    data = write_dataset(tmp_path / "data", 4, seed=1)
    out = tmp_path / "d.onnx"
    assert main(["perception", "train", str(data), "--out", str(out), "--steps", "2", "--batch", "2", "--threads", "1",
                 "--width", "16", "--distill", str(DEFAULT_MODEL), "--distill-weight", "2"]) == 0
    capsys.readouterr()
    meta = json.loads(out.with_suffix(".json").read_text())
    assert meta["width"] == 16 and meta["training"]["distill"] == str(DEFAULT_MODEL)
    assert meta["training"]["distill_weight"] == 2.0
    det = load_detector(out)
    maps = det.raw(np.zeros((256, 256, 3), dtype=np.uint8))
    assert maps.shape[0] == 2 * (len(det.classes) + 4) and np.isfinite(maps).all()
    decode(maps, n_classes=len(det.classes))


def test_a_teacher_equal_to_the_start_adds_nothing(tmp_path) -> None:
    """Teacher and student both the shipped model: the distillation term is 0 and, however
    heavily weighted, changes neither the label losses nor the step (its gradient is 0)."""
    from aileen.perception.detector import DEFAULT_MODEL
    from aileen.perception.train import TrainConfig, train

    data = write_dataset(tmp_path / "data", 4, seed=3)
    base = TrainConfig(steps=1, batch=4, val_images=1, threads=1, init=str(DEFAULT_MODEL), lr=1e-3)
    plain_log: list[str] = []
    dist_log: list[str] = []
    a = train(data, tmp_path / "a.onnx", base, log=plain_log.append)
    cfg = TrainConfig(**{**base.__dict__, "distill": str(DEFAULT_MODEL), "distill_weight": 1000.0})
    b = train(data, tmp_path / "b.onnx", cfg, log=dist_log.append)
    plain, dist = _terms(plain_log), _terms(dist_log)
    assert plain["focal"] > 0.0
    assert {k: dist[k] for k in plain} == plain
    assert dist["d_heat"] == pytest.approx(0.0, abs=1e-6)
    assert dist["d_off"] == pytest.approx(0.0, abs=1e-6) and dist["d_size"] == pytest.approx(0.0, abs=1e-6)
    assert a["validation"] == b["validation"]


def test_the_term_grows_where_the_student_misses_the_teachers_object() -> None:
    from aileen.perception.distill import distill_loss
    from aileen.perception.net import layer_maps

    nc = 4
    maps = layer_maps(nc)
    teacher = torch.full((1, 2 * maps, 8, 8), -6.0)
    teacher[:, nc:maps] = 0.5
    teacher[0, 1, 3, 4] = 4.0  # the teacher sees a cone at (4, 3) on the table
    n = torch.tensor(1.0)
    same, _ = distill_loss(teacher.clone(), teacher, nc, n, 0.5)
    assert same.item() == pytest.approx(0.0, abs=1e-6)
    missed = teacher.clone()
    missed[0, 1, 3, 4] = -6.0
    _, terms = distill_loss(missed, teacher, nc, n, 0.5)
    assert terms["d_heat"] > 1.0 and terms["d_off"] == 0.0
    # offset and size count at the teacher's peak only, not on the background
    moved = teacher.clone()
    moved[0, nc, 0, 0] += 3.0
    assert distill_loss(moved, teacher, nc, n, 0.5)[1]["d_off"] < 0.01
    moved[0, nc, 0, 0] -= 3.0
    moved[0, nc, 3, 4] += 3.0
    peak = torch.sigmoid(torch.tensor(4.0)).item()
    assert distill_loss(moved, teacher, nc, n, 0.5)[1]["d_off"] == pytest.approx(3.0 * peak, rel=1e-5)


def test_a_bad_teacher_is_a_one_line_user_error(tmp_path, capsys) -> None:
    from aileen.cli import main
    from aileen.perception.detector import DEFAULT_MODEL
    from aileen.perception.distill import load_teacher

    data = write_dataset(tmp_path / "data", 2, seed=2)
    out = str(tmp_path / "m.onnx")
    assert main(["perception", "train", str(data), "--out", out, "--steps", "1",
                 "--distill", str(tmp_path / "none.onnx")]) == 2
    err = capsys.readouterr().err
    assert "none.onnx: no such model to distil from" in err and len(err.strip().splitlines()) == 1
    assert main(["perception", "train", str(data), "--out", out, "--steps", "1",
                 "--distill", str(DEFAULT_MODEL), "--distill-weight", "-1"]) == 2
    assert "--distill-weight must be" in capsys.readouterr().err
    (tmp_path / "junk.onnx").write_text("not a model")
    with pytest.raises(UserError, match="cannot read the model"):
        load_teacher(tmp_path / "junk.onnx", ("box",))
