"""A branch that adds shapes to a trained detector (`aileen perception train --branch`): the
base stays as it was, the export reads as a detector of the base's shapes and the new ones,
and a branched model cannot start another run (skipped without torch)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from aileen.perception.dataset import SceneSpec, generate
from aileen.world.catalog import SHAPES

torch = pytest.importorskip("torch")
pytest.importorskip("onnx")


def _base(classes: tuple[str, ...] = ("box", "cone", "sphere", "cylinder")):
    from aileen.perception.net import DetectorNet

    torch.manual_seed(3)
    return DetectorNet(16, classes).eval()


def _input(seed: int = 5) -> "torch.Tensor":
    image = np.ascontiguousarray(next(iter(generate(1, seed, SceneSpec(3, 4, 1.0)))).image)
    return torch.from_numpy(image.copy()).permute(2, 0, 1)[None].float() / 255.0


def test_a_closed_branch_gives_the_base_maps_back_with_the_new_shape_in_catalog_order() -> None:
    from aileen.perception.branch import BranchedNet
    from aileen.perception.net import LAYERS, layer_maps

    base = _base(("box", "sphere", "cylinder"))
    net = BranchedNet(base, ["capsule", "cone"]).eval()
    assert net.classes == ("box", "cone", "sphere", "cylinder", "capsule") and net.new == ("cone", "capsule")
    with torch.no_grad():
        last = net.branch[-1]
        last.weight.zero_()
        for k in range(LAYERS):
            last.bias[k * net.per_level + 4 + len(net.new)] = -40.0  # cover shut
        x = _input()
        want, got = base(x), net(x)
    assert got.shape[1] == LAYERS * layer_maps(5)
    for k in range(LAYERS):
        w, g = want[:, k * 7 : (k + 1) * 7], got[:, k * 9 : (k + 1) * 9]
        for i, shape in enumerate(("box", "sphere", "cylinder")):
            assert torch.allclose(g[:, net.classes.index(shape)], w[:, i], atol=1e-6)
        # the new shapes sit at the background rate, below every old heat that matters, and
        # the base's offset and size stand wherever an old shape's heat is higher
        new_heat = g[:, [1, 4]]
        assert torch.allclose(new_heat, torch.full_like(new_heat, float(torch.sigmoid(torch.tensor(-4.0)))))
        old_wins = w[:, :3].amax(dim=1) > new_heat.amax(dim=1)
        assert old_wins.any()
        assert torch.equal(g[:, 5:9][:, :, old_wins[0]], w[:, 3:7][:, :, old_wins[0]])


def test_only_the_branch_learns() -> None:
    from aileen.perception.branch import BranchedNet

    base = _base()
    before = [p.clone() for p in base.parameters()]
    net = BranchedNet(base, ["capsule"]).train()
    assert not base.training
    trainable = [p for p in net.parameters() if p.requires_grad]
    assert trainable and all(any(p is q for q in net.branch.parameters()) for p in trainable)
    opt = torch.optim.SGD(trainable, lr=0.1)
    out = net(_input())
    out.square().mean().backward()
    opt.step()
    assert all(torch.equal(a, b) for a, b in zip(before, base.parameters()))
    with pytest.raises(ValueError):
        BranchedNet(base, ["box"])


def test_the_train_command_exports_a_branched_detector_that_cannot_start_a_run(tmp_path, capsys) -> None:
    from aileen.cli import main
    from aileen.perception.detector import load_detector

    four = tmp_path / "four"
    assert main(["perception", "dataset", "--n", "3", "--seed", "4", "--out", str(four),
                 "--shapes", "box,cone,sphere,cylinder"]) == 0
    base = tmp_path / "base.onnx"
    assert main(["perception", "train", str(four), "--out", str(base), "--steps", "1", "--batch", "2",
                 "--threads", "1"]) == 0
    five = tmp_path / "five"
    assert main(["perception", "dataset", "--n", "3", "--seed", "5", "--out", str(five)]) == 0
    capsys.readouterr()
    # a branch needs a model to add shapes to, and data with a shape that model lacks
    assert main(["perception", "train", str(five), "--out", str(tmp_path / "x.onnx"), "--branch", "--steps", "1"]) == 2
    assert "--branch needs --init" in capsys.readouterr().err
    assert main(["perception", "train", str(four), "--out", str(tmp_path / "x.onnx"), "--branch",
                 "--init", str(base), "--steps", "1", "--batch", "2", "--threads", "1"]) == 2
    assert "draw no shape" in capsys.readouterr().err
    out = tmp_path / "branched.onnx"
    assert main(["perception", "train", str(five), "--out", str(out), "--branch", "--init", str(base),
                 "--steps", "2", "--batch", "2", "--threads", "1"]) == 0
    meta = json.loads(out.with_suffix(".json").read_text())
    assert meta["classes"] == list(SHAPES) and meta["branch"]["new"] == ["capsule"]
    assert meta["branch"]["base_classes"] == ["box", "cone", "sphere", "cylinder"]
    image = np.ascontiguousarray(np.load(five / "images.npy")[0])
    det = load_detector(out)
    assert det.classes == SHAPES and det.raw(image).shape == (18, 32, 32)
    det.detect(image)  # decodes with the model's five classes
    capsys.readouterr()
    assert main(["perception", "train", str(five), "--out", str(tmp_path / "y.onnx"), "--init", str(out),
                 "--steps", "1"]) == 2
    err = capsys.readouterr().err
    assert "cannot start a training run" in err and str(base) in err
