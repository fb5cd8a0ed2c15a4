"""A tiny training run trains and exports a model cv2.dnn can run (skipped without torch)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.errors import UserError
from aileen.perception.dataset import load_dataset, write_dataset

torch = pytest.importorskip("torch")
pytest.importorskip("onnx")


def test_tiny_training_run_exports_a_runnable_model(tmp_path) -> None:
    from aileen.perception.detector import load_detector
    from aileen.perception.train import LAYER_MAPS, N_CLASSES, N_OUT, TrainConfig, make_targets, train
    from aileen.world.catalog import SHAPES

    data = write_dataset(tmp_path / "data", 6, seed=3)
    images, labels, meta = load_dataset(data)
    assert images.shape == (6, 256, 256, 3) and meta["seed"] == 3
    out = tmp_path / "tiny.onnx"
    losses = []
    info = train(data, out, TrainConfig(steps=6, batch=4, val_images=2, lr=1e-2), log=losses.append)
    assert out.is_file() and out.stat().st_size > 10_000
    meta_file = json.loads(out.with_suffix(".json").read_text())
    assert meta_file["training"]["steps"] == 6 and meta_file["classes"] == list(SHAPES)
    assert info["validation"].keys() >= {"recall", "precision", "shape_error"}
    det = load_detector(out)
    raw = det.raw(np.ascontiguousarray(images[0]))
    assert raw.shape == (N_OUT, 32, 32)  # per level: heatmaps, offset, size
    up = raw[LAYER_MAPS : LAYER_MAPS + N_CLASSES]
    assert np.all((raw[:N_CLASSES] >= 0) & (raw[:N_CLASSES] <= 1)) and np.all((up >= 0) & (up <= 1))  # sigmoids
    assert det.scores_levels
    assert isinstance(det.detect(np.ascontiguousarray(images[0])), list)
    # targets: one centre cell per visible object, in the layer of its level, heat 1 there
    t = make_targets(labels[0], 256, 256)
    visible = [o for o in labels[0] if o["visible"] >= 0.1]
    assert t[N_OUT].sum() + t[N_OUT + 1].sum() == len(visible)
    assert t[N_OUT + 1].sum() == sum(o["level"] > 0 for o in visible)
    assert np.all(t[:N_CLASSES][:, t[N_OUT] > 0].max(axis=0) == 1.0)


def test_targets_carry_levels_and_skip_hidden_objects() -> None:
    from aileen.perception.train import LAYER_MAPS, N_CLASSES, N_OUT, make_targets

    m, up = N_OUT, LAYER_MAPS  # the first mask map; the upper layer's first map (its box heatmap)

    def obj(cu: float, cv: float, level: int, visible: float) -> dict:
        return {"shape": "box", "centre_px": (cu, cv), "box_px": (cu - 13, cv - 13, cu + 13, cv + 13),
                "level": level, "visible": visible}

    t = make_targets([obj(60, 60, 0, 0.4), obj(68, 60, 1, 1.0), obj(200, 200, 0, 0.05)], 256, 256)
    assert t[m].sum() + t[m + 1].sum() == 2  # the object 5 % visible is no target
    # a box on a box one cell off: a peak in each layer's box map, its own offset and size
    assert t[m, 60 // 8, 60 // 8] == 1.0 and t[m + 1, 60 // 8, 68 // 8] == 1.0
    assert t[0, 60 // 8, 60 // 8] == 1.0 and t[up, 60 // 8, 68 // 8] == 1.0
    assert t[0, 60 // 8, 68 // 8] < 1.0 and t[up, 60 // 8, 60 // 8] < 1.0
    assert t[up + N_CLASSES + 2, 60 // 8, 68 // 8] == pytest.approx(26 / 8)
    assert t[up + N_CLASSES, 60 // 8, 68 // 8] == pytest.approx(68 / 8 - 8)


def test_starting_from_an_exported_model_reproduces_it(tmp_path) -> None:
    """--init: the folded weights of an export give back its outputs (the shipped model's
    maps become the table layer; a layered export gives back all its maps)."""
    from aileen.perception.detector import DEFAULT_MODEL, load_detector
    from aileen.perception.train import DetectorNet, export_onnx, load_onnx_weights

    image = np.ascontiguousarray(np.random.default_rng(4).integers(0, 255, (256, 256, 3), dtype=np.uint8))
    x = torch.from_numpy(image.copy()).permute(2, 0, 1)[None].float() / 255.0
    model = DetectorNet()
    load_onnx_weights(model, DEFAULT_MODEL)
    model.eval()
    with torch.no_grad():
        y = model(x)[0].numpy()
    det = load_detector(DEFAULT_MODEL)
    shipped = det.raw(image)
    # the shipped model's maps of the table layer, each where this network keeps it: its
    # shapes' heatmaps by name (a model may know fewer shapes than the catalog), then offset
    # and size
    from aileen.perception.train import N_CLASSES
    from aileen.world.catalog import SHAPES

    k = len(det.classes)
    ours = [SHAPES.index(c) for c in det.classes] + [N_CLASSES + j for j in range(4)]
    assert np.abs(y[ours] - shipped[: k + 4]).max() < 1e-4
    export_onnx(model, tmp_path / "again.onnx")
    again = DetectorNet()
    load_onnx_weights(again, tmp_path / "again.onnx")
    again.eval()
    with torch.no_grad():
        assert torch.allclose(again(x), model(x), atol=1e-4)
    with pytest.raises(UserError, match="cannot read the model"):
        load_onnx_weights(DetectorNet(), tmp_path / "missing.onnx")


def test_a_model_that_knows_fewer_shapes_gives_each_its_maps_and_a_new_shape_starts_blank(tmp_path) -> None:
    """--init from a model trained before a shape joined the catalog (its metadata lists
    its classes): every other channel comes from it, the new shape's heatmaps start at the
    background rate."""
    import json

    import onnx
    from onnx import numpy_helper

    from aileen.perception.train import LAYER_MAPS, N_CLASSES, DetectorNet, export_onnx, load_onnx_weights
    from aileen.world.catalog import SHAPES

    from aileen.perception.detector import DEFAULT_MODEL

    torch.manual_seed(3)
    full = DetectorNet()
    load_onnx_weights(full, DEFAULT_MODEL)  # trained weights (an untrained export shares its zero biases)
    with torch.no_grad():  # a head whose every channel differs from the blank start
        full.head.weight.normal_(0.0, 0.3)
        full.head.bias.uniform_(-1.0, 1.0)
    export_onnx(full, tmp_path / "full.onnx")
    g = onnx.load(str(tmp_path / "full.onnx"))
    head = [n for n in g.graph.node if n.op_type == "Conv"][-1]
    drop = SHAPES.index("capsule")
    keep = [c for c in range(2 * LAYER_MAPS) if c % LAYER_MAPS != drop]
    for init in g.graph.initializer:
        if init.name in head.input[1:3]:
            init.CopyFrom(numpy_helper.from_array(numpy_helper.to_array(init)[keep], init.name))
    onnx.save(g, str(tmp_path / "old.onnx"))
    old_classes = [c for c in SHAPES if c != "capsule"]
    (tmp_path / "old.json").write_text(json.dumps({"classes": old_classes, "threshold": 0.3, "layers": 2}))
    a, b = DetectorNet(), DetectorNet()
    load_onnx_weights(a, tmp_path / "full.onnx")
    load_onnx_weights(b, tmp_path / "old.onnx")
    for ca, cb in zip(a.body, b.body):
        if isinstance(ca, torch.nn.Conv2d):
            assert torch.equal(ca.weight, cb.weight)
    new = [k * LAYER_MAPS + drop for k in range(2)]
    same = [c for c in range(2 * LAYER_MAPS) if c not in new]
    assert torch.equal(a.head.weight[same], b.head.weight[same]) and torch.equal(a.head.bias[same], b.head.bias[same])
    assert float(b.head.weight[new].detach().abs().max()) == 0.0 and b.head.bias[new].tolist() == [-4.0, -4.0]
    assert N_CLASSES == len(SHAPES)
    # without metadata, a layered model of 16 maps is read as the catalog's first four shapes
    (tmp_path / "old.json").unlink()
    c = DetectorNet()
    load_onnx_weights(c, tmp_path / "old.onnx")
    assert torch.equal(c.head.weight, b.head.weight)


def test_training_is_reproducible(tmp_path) -> None:
    from aileen.perception.train import TrainConfig, train

    data = write_dataset(tmp_path / "data", 4, seed=1)
    cfg = TrainConfig(steps=3, batch=2, val_images=1, threads=1)
    a = train(data, tmp_path / "a.onnx", cfg, log=lambda s: None)
    b = train(data, tmp_path / "b.onnx", cfg, log=lambda s: None)
    assert (tmp_path / "a.onnx").read_bytes() == (tmp_path / "b.onnx").read_bytes()
    assert a["validation"] == b["validation"]


def test_missing_dataset(tmp_path) -> None:
    from aileen.perception.train import train

    with pytest.raises(UserError, match="images.npy: missing"):
        train(tmp_path, tmp_path / "m.onnx")


def test_train_command_rejects_a_bad_start_model_and_learning_rate(tmp_path, capsys) -> None:
    from aileen.cli import main

    data = write_dataset(tmp_path / "data", 2, seed=2)
    out = str(tmp_path / "m.onnx")
    assert main(["perception", "train", str(data), "--out", out, "--lr", "0"]) == 2
    assert "--lr must lie between 0 and 1" in capsys.readouterr().err
    assert main(["perception", "train", str(data), "--out", out, "--init", str(tmp_path / "none.onnx"), "--steps", "1"]) == 2
    err = capsys.readouterr().err
    assert "none.onnx: cannot read the model to start from" in err and len(err.strip().splitlines()) == 1


def test_training_samples_several_dataset_folders_as_one_set(tmp_path) -> None:
    from aileen.cli import main

    a = write_dataset(tmp_path / "a", 3, seed=4)
    b = write_dataset(tmp_path / "b", 4, seed=5)
    out = tmp_path / "m.onnx"
    assert main(["perception", "train", str(a), str(b), "--out", str(out), "--steps", "2", "--batch", "2",
                 "--stack-crops", "0.5"]) == 0
    training = json.loads(out.with_suffix(".json").read_text())["training"]
    assert training["data_images"] == 7 and training["data_seed"] == [4, 5] and training["stack_crops"] == 0.5


def test_folders_of_different_image_sizes_are_refused(tmp_path) -> None:
    from aileen.perception.train import train
    from aileen.world.camera import Camera

    a = write_dataset(tmp_path / "a", 2, seed=4)
    b = write_dataset(tmp_path / "b", 2, seed=5, camera=Camera(width=128, height=128))
    with pytest.raises(UserError, match="one training run takes one image size"):
        train([a, b], tmp_path / "m.onnx")


def test_train_command_rejects_a_bad_stack_crop_share(tmp_path, capsys) -> None:
    from aileen.cli import main

    data = write_dataset(tmp_path / "data", 2, seed=2)
    assert main(["perception", "train", str(data), "--out", str(tmp_path / "m.onnx"), "--stack-crops", "2"]) == 2
    assert "--stack-crops must lie in [0, 1], got 2.0" in capsys.readouterr().err


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 31), st.integers(0, 31)), max_size=3), st.integers(0, 2**31 - 1))
def test_a_stack_crop_lies_on_the_image_and_holds_an_upper_object(uppers, seed) -> None:
    from aileen.perception.train import _crop_origin

    rng = np.random.default_rng(seed)
    x, y = _crop_origin(uppers, (32, 32), 16, 1.0, rng)
    assert 0 <= x <= 16 and 0 <= y <= 16
    inside = [(cx, cy) for cx, cy in uppers if x + 2 <= cx <= x + 13 and y + 2 <= cy <= y + 13]
    # every object two cells or more from the image's edge can be held that way, and one is
    if uppers and all(2 <= c <= 29 for u in uppers for c in u):
        assert inside
