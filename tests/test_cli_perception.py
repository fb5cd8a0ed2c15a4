"""`aileen perception dataset | train | eval | compare | tune-color` through the CLI entry point."""

from __future__ import annotations

import json

import numpy as np

from aileen.cli import main


def test_dataset_and_eval_json(tmp_path, capsys) -> None:
    assert main(["perception", "dataset", "--n", "3", "--seed", "4", "--out", str(tmp_path / "d")]) == 0
    assert np.load(tmp_path / "d" / "images.npy", mmap_mode="r").shape == (3, 256, 256, 3)
    labels = json.loads((tmp_path / "d" / "labels.json").read_text())
    assert len(labels["images"]) == 3 and all(1 <= len(x) <= 6 for x in labels["images"])
    capsys.readouterr()
    assert main(["perception", "eval", "--n", "4", "--seed", "99", "--json", "--stack-share", "0"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report.keys() >= {"recall", "precision", "shape_error", "color_error", "centroid_error_m", "objects",
                             "size_error", "on_top_error", "partly_hidden_recall", "hidden", "on_unseen",
                             "on_top_error_in_sight"}
    assert report["objects"] >= 4
    assert report["recall"] > 0.9 and report["centroid_error_m"] < 0.01
    assert report["matching"] == "agree"
    assert main(["perception", "eval", "--n", "4", "--seed", "99", "--json", "--stack-share", "0",
                 "--matching", "greedy"]) == 0
    greedy = json.loads(capsys.readouterr().out)
    assert greedy["matching"] == "greedy" and greedy["recall"] == report["recall"]  # plain scenes: nothing to swap


def test_eval_text_has_confusion_matrices(capsys) -> None:
    assert main(["perception", "eval", "--n", "2", "--seed", "7"]) == 0
    out = capsys.readouterr().out
    assert "recall" in out and "truth \\ seen" in out and "cylinder" in out and "purple" in out


def test_tune_color_json(capsys) -> None:
    assert main(["perception", "tune-color", "--n", "3", "--seed", "1", "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert 0.0 <= r["w1"] <= 1.0 and abs(r["w1"] + r["w2"] - 1) < 1e-9 and len(r["grid"]) == 21


def test_bad_arguments(tmp_path, capsys) -> None:
    assert main(["perception", "dataset", "--n", "0", "--out", str(tmp_path)]) == 2
    assert "--n must be a positive integer" in capsys.readouterr().err
    assert main(["perception", "eval", "--n", "1", "--model", str(tmp_path / "x.onnx")]) == 2
    err = capsys.readouterr().err
    assert "x.onnx" in err and "aileen perception train" in err
    assert main(["perception", "train", str(tmp_path / "nodata"), "--out", str(tmp_path / "m.onnx")]) == 2
    assert "images.npy: missing" in capsys.readouterr().err


def test_eval_draws_the_shapes_asked_for_and_refuses_one_the_model_does_not_know(capsys) -> None:
    assert main(["perception", "eval", "--n", "6", "--seed", "3", "--json", "--shapes", "box,cone"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["shapes"] == ["box", "cone"]
    truths = {key.split("->")[0] for key, n in report["shape_confusion"].items() if n} - {"none"}
    assert truths and truths <= {"box", "cone"}
    assert main(["perception", "eval", "--n", "1", "--shapes", "box,blob"]) == 2
    assert "--shapes takes shapes of" in capsys.readouterr().err
    from aileen.perception.detector import load_detector
    from aileen.world.catalog import SHAPES

    lacking = [s for s in SHAPES if s not in load_detector().classes]
    if lacking:  # a catalog shape the shipped model was not trained on
        assert main(["perception", "eval", "--n", "1", "--shapes", f"box,{lacking[0]}"]) == 2
        assert f"the model does not know {lacking[0]}" in capsys.readouterr().err


def test_eval_lists_as_many_failures_as_asked(monkeypatch, capsys) -> None:
    import aileen.perception.evaluate as ev
    from aileen.perception.scene import Scene

    monkeypatch.setattr(ev, "perceive", lambda image, model=None: Scene((), ()))  # a blind perceiver misses all
    every = ev.evaluate(5, 11, stack_share=0, failures=None)
    assert every["recall"] == 0 and len(every["failures"]) == every["objects"] >= 5
    assert all("missed" in f and "% visible" in f for f in every["failures"])
    assert ev.evaluate(5, 11, stack_share=0, failures=2)["failures"] == every["failures"][:2]
    assert main(["perception", "eval", "--n", "5", "--seed", "11", "--stack-share", "0", "--json",
                 "--failures", "-1"]) == 0
    assert json.loads(capsys.readouterr().out)["failures"] == every["failures"]
    assert main(["perception", "eval", "--n", "1", "--failures", "-2"]) == 2
    assert "--failures -2: expected" in capsys.readouterr().err


def test_compare_puts_models_side_by_side_on_the_same_scenes(tmp_path, capsys) -> None:
    import shutil

    from aileen.perception.detector import load_detector

    # the shipped model under another name: the same figures in both columns
    copy = tmp_path / "copy.onnx"
    shutil.copy(load_detector().path, copy)
    shutil.copy(load_detector().path.with_suffix(".json"), copy.with_suffix(".json"))
    args = ["perception", "compare", "shipped", str(copy), "--plain", "3", "--stacked", "3", "--seeds", "5,6"]
    assert main(args + ["--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert list(r["models"]) == ["shipped", str(copy)]
    assert list(r["models"]["shipped"]) == ["plain", "stacked, seed 5", "stacked, seed 6"]
    assert r["models"]["shipped"] == r["models"][str(copy)]
    assert r["models"]["shipped"]["plain"]["stack_share"] == 0 and r["models"]["shipped"]["stacked, seed 6"]["seed"] == 6
    assert main(args) == 0
    table = capsys.readouterr().out.splitlines()
    row = next(line for line in table if line.startswith("| stacked, seed 6: on-top error"))
    cells = [c.strip() for c in row.strip("|").split("|")]
    assert len(cells) == 3 and cells[1] == cells[2] and "of" in cells[1]


def test_compare_refuses_bad_input_in_one_line(tmp_path, capsys) -> None:
    assert main(["perception", "compare", "shipped", "--seeds", "1,x"]) == 2
    assert "--seeds" in capsys.readouterr().err
    assert main(["perception", "compare", str(tmp_path / "none.onnx"), "--plain", "1", "--stacked", "0"]) == 2
    assert "none.onnx" in capsys.readouterr().err
    assert main(["perception", "compare", "shipped", "--plain", "-1"]) == 2
    assert ">= 0" in capsys.readouterr().err


def test_compare_judges_each_model_on_its_own_file(tmp_path, monkeypatch) -> None:
    # the identical columns above would also come from a compare that ran the shipped model
    # twice: each evaluation must be handed its own model
    import shutil

    import aileen.perception.compare as cmp
    from aileen.perception.detector import load_detector

    copy = tmp_path / "copy.onnx"
    shutil.copy(load_detector().path, copy)
    shutil.copy(load_detector().path.with_suffix(".json"), copy.with_suffix(".json"))
    asked: list[tuple[str | None, int, float]] = []

    def fake(n, seed, *, model=None, stack_share, shapes, failures, matching):  # noqa: ANN001, ANN202
        asked.append((model, seed, stack_share))
        return {"model": model}

    monkeypatch.setattr(cmp, "evaluate", fake)
    r = cmp.compare(["shipped", str(copy)], cmp.Battery(plain=2, stacked=2, seeds=(5, 6)))
    assert asked == [(None, 5, 0.0), (None, 5, 0.5), (None, 6, 0.5),
                     (str(copy), 5, 0.0), (str(copy), 5, 0.5), (str(copy), 6, 0.5)]
    assert r["models"][str(copy)]["stacked, seed 6"] == {"model": str(copy)}
    assert r["battery"] == {"plain": 2, "stacked": 2, "seeds": (5, 6), "matching": "agree"}


def test_tune_color_scores_crops_perception_reads_whole() -> None:
    """Its scenes have no stacks: whole crops of stacked objects (the one on top at the
    centre) made the grid fall from 100 % to 94 % and pick w1 = 0.3 (docs/perception.md)."""
    from aileen.perception.evaluate import tune_colour

    res = tune_colour(40, 777)
    assert dict(res.grid)[0.5] == 1.0 and res.w1 == 0.5
