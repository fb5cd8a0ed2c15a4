"""Starting a network from an exported model, thinner than it (`--width`): pruning keeps the
filters of largest L1 norm and slices the next layer to match (skipped without torch)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from aileen.perception.dataset import generate, write_dataset
from aileen.world.catalog import drawn_shapes

torch = pytest.importorskip("torch")
pytest.importorskip("onnx")


def _scene() -> tuple[np.ndarray, "torch.Tensor"]:
    """A rendered stacked scene of the shapes the shipped model knows, and its network input."""
    from aileen.perception.dataset import SceneSpec

    image = np.ascontiguousarray(next(iter(generate(1, 7, SceneSpec(3, 4, 1.0, shapes=drawn_shapes())))).image)
    return image, torch.from_numpy(image.copy()).permute(2, 0, 1)[None].float() / 255.0


def _shipped(width: int):
    from aileen.perception.detector import DEFAULT_MODEL, load_detector
    from aileen.perception.net import DetectorNet
    from aileen.perception.warmstart import load_onnx_weights

    model = DetectorNet(width, load_detector(DEFAULT_MODEL).classes)
    load_onnx_weights(model, DEFAULT_MODEL)
    return model.eval()


def test_pruning_to_the_models_own_width_gives_the_model_back() -> None:
    from aileen.perception.detector import DEFAULT_MODEL, load_detector
    from aileen.perception.warmstart import prune, read_export

    exp = read_export(DEFAULT_MODEL)
    assert exp.width == 48 and exp.classes == list(load_detector(DEFAULT_MODEL).classes)
    for (w, b), (pw, pb) in zip(exp.convs, prune(exp.convs, exp.width)):
        assert np.array_equal(w, pw) and (b is None) == (pb is None) and (b is None or np.array_equal(b, pb))
    image, x = _scene()
    with torch.no_grad():
        y = _shipped(48)(x)[0].numpy()
    assert np.abs(y - load_detector(DEFAULT_MODEL).raw(image)).max() < 1e-4


def test_a_pruned_start_keeps_the_largest_filters_and_exports_a_runnable_model(tmp_path) -> None:
    from aileen.perception.detector import DEFAULT_MODEL, decode, load_detector
    from aileen.perception.train import export_onnx
    from aileen.perception.warmstart import prune, read_export

    exp = read_export(DEFAULT_MODEL)
    thin = _shipped(32)
    convs = [m for m in thin.body if isinstance(m, torch.nn.Conv2d)]
    assert [c.weight.shape[0] for c in convs] == [16, 24, 32, 32, 32, 32] and thin.head.weight.shape[1] == 32
    # the first wide conv keeps the 32 filters of largest L1 norm, in their order
    w4 = exp.convs[3][0]
    norms = np.abs(w4).sum(axis=(1, 2, 3))
    kept = np.sort(np.argsort(-norms)[:32])
    assert np.array_equal(convs[3].weight.detach().numpy(), w4[kept])
    assert norms[kept].min() >= np.delete(norms, kept).max()
    # its next conv takes exactly those input channels
    assert np.array_equal(prune(exp.convs, 32)[4][0], convs[4].weight.detach().numpy())
    assert prune(exp.convs, 32)[4][0].shape == (32, 32, 3, 3)
    export_onnx(thin, tmp_path / "thin.onnx")
    meta = json.loads((DEFAULT_MODEL.with_suffix(".json")).read_text())
    (tmp_path / "thin.json").write_text(json.dumps({**meta, "width": 32}))
    assert read_export(tmp_path / "thin.onnx").width == 32
    image, x = _scene()
    raw = load_detector(tmp_path / "thin.onnx").raw(image)
    classes = load_detector(DEFAULT_MODEL).classes  # both layers' maps: per class, then offset and size
    assert raw.shape == load_detector(DEFAULT_MODEL).raw(image).shape == (2 * (len(classes) + 4), 32, 32)
    with torch.no_grad():
        assert np.abs(thin(x)[0].numpy() - raw).max() < 1e-4
    assert isinstance(decode(raw, n_classes=len(classes)), list)


def test_pruning_away_dead_channels_changes_nothing(tmp_path) -> None:
    """Where a third of each wide conv's filters are zero (channels that are always 0), the
    pruned network drops exactly those and computes what the wide one does: the slicing of
    the next layer and the head is consistent."""
    from aileen.perception.train import export_onnx
    from aileen.perception.net import DetectorNet
    from aileen.perception.warmstart import load_onnx_weights

    wide = _shipped(48)
    rng = np.random.default_rng(5)
    convs = [m for m in wide.body if isinstance(m, torch.nn.Conv2d)]
    bns = [m for m in wide.body if isinstance(m, torch.nn.BatchNorm2d)]
    with torch.no_grad():
        for conv, bn in zip(convs[3:], bns[3:]):
            dead = rng.choice(48, 16, replace=False)
            conv.weight[dead] = 0.0
            bn.bias[dead] = 0.0  # the folded bias
    export_onnx(wide, tmp_path / "wide.onnx")
    (tmp_path / "wide.json").write_text(json.dumps({"classes": list(wide.classes), "threshold": 0.3}))
    thin = DetectorNet(32, wide.classes)
    load_onnx_weights(thin, tmp_path / "wide.onnx")
    thin.eval()
    _, x = _scene()
    with torch.no_grad():
        assert torch.allclose(thin(x), wide(x), atol=1e-5)


def test_train_command_prunes_to_a_width_and_learns_the_datas_shapes(tmp_path, capsys) -> None:
    from aileen.cli import main
    from aileen.perception.detector import DEFAULT_MODEL, load_detector

    data = tmp_path / "data"
    assert main(["perception", "dataset", "--n", "3", "--seed", "4", "--out", str(data),
                 "--shapes", ",".join(drawn_shapes())]) == 0
    assert json.loads((data / "labels.json").read_text())["shapes"] == list(drawn_shapes())
    out = tmp_path / "w32.onnx"
    assert main(["perception", "train", str(data), "--out", str(out), "--init", str(DEFAULT_MODEL),
                 "--width", "32", "--steps", "2", "--batch", "2", "--threads", "1"]) == 0
    meta = json.loads(out.with_suffix(".json").read_text())
    assert meta["width"] == 32 and meta["classes"] == list(drawn_shapes())
    image = np.ascontiguousarray(np.load(data / "images.npy")[0])
    assert load_detector(out).raw(image).shape == (2 * (len(drawn_shapes()) + 4), 32, 32)
    capsys.readouterr()
    # the width defaults to the start model's; a wider network than it is refused
    assert main(["perception", "train", str(data), "--out", str(tmp_path / "w.onnx"), "--init", str(out),
                 "--steps", "1", "--batch", "2", "--threads", "1"]) == 0
    assert json.loads((tmp_path / "w.json").read_text())["width"] == 32
    assert main(["perception", "train", str(data), "--out", str(tmp_path / "x.onnx"), "--init", str(out),
                 "--width", "48", "--steps", "1"]) == 2
    assert "cannot prune to width 48: the model is 32 wide" in capsys.readouterr().err


def test_dataset_shapes_must_be_catalog_shapes(tmp_path, capsys) -> None:
    from aileen.cli import main

    assert main(["perception", "dataset", "--n", "1", "--out", str(tmp_path / "d"), "--shapes", "box,blob"]) == 2
    assert "--shapes takes shapes of" in capsys.readouterr().err
    data = write_dataset(tmp_path / "all", 1, seed=1)
    assert json.loads((data / "labels.json").read_text())["shapes"][-1] == "capsule"
