"""`aileen render`: the image it writes, the ground truth it prints, and its errors."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import cv2
import numpy as np
import pytest

from aileen.cli import main
from aileen.world.render import render
from aileen.world.scenes import random_scene


def test_json_output_and_image(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "scene.png"
    assert main(["render", "--seed", "1", "--objects", "4", "--out", str(out), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)  # exactly one JSON object
    assert set(doc) == {"seed", "image", "objects"} and doc["seed"] == 1 and doc["image"] == str(out)
    assert len(doc["objects"]) == 4
    for obj in doc["objects"]:
        assert set(obj) == {"id", "shape", "colour", "size", "x", "y", "box_px", "box_m"}
    # The file holds the same image the library renders (written BGR, read back as RGB).
    img = cv2.cvtColor(cv2.imread(str(out)), cv2.COLOR_BGR2RGB)
    frame = render(random_scene(4, seed=1), seed=1)
    assert np.array_equal(img, frame.image)
    assert [o["id"] for o in doc["objects"]] == [t.id for t in frame.truth]
    assert doc["objects"][0]["box_px"] == pytest.approx(list(frame.truth[0].box_px))
    assert not [p for p in tmp_path.iterdir() if p.name != "scene.png"]  # no temp file left


def test_table_output_and_size(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "s.png"
    assert main(["render", "--seed", "2", "--objects", "3", "--out", str(out), "--size", "128"]) == 0
    text = capsys.readouterr().out
    assert "wrote" in text and "obj1" in text and "obj3" in text
    assert cv2.imread(str(out)).shape == (128, 128, 3)
    assert main(["render", "--objects", "0", "--out", str(out), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["objects"] == []


@pytest.mark.parametrize(
    "args,msg",
    [
        (["--objects", "-1"], "--objects must be >= 0"),
        (["--objects", "80"], "cannot place 80 objects of 0.10 m"),
        (["--out", "{tmp}/missing/x.png"], "does not exist"),
        (["--out", "{tmp}"], "got a folder"),
        (["--out", "{tmp}/x.jpg"], "expected a .png"),
        (["--size", "5"], "--size must be between"),
    ],
)
def test_user_errors_are_one_line_and_exit_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], args: list[str], msg: str
) -> None:
    argv = ["render", "--out", str(tmp_path / "ok.png")] + [a.replace("{tmp}", str(tmp_path)) for a in args]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("aileen: ") and msg in err
    assert not (tmp_path / "ok.png").exists()


def test_unwritable_path_is_a_user_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    assert main(["render", "--out", str(blocker / "x.png")]) == 2
    assert "aileen: " in capsys.readouterr().err


def test_console_script_has_no_traceback(tmp_path: Path) -> None:
    p = subprocess.run(
        [sys.executable, "-m", "aileen", "render", "--objects", "99", "--out", str(tmp_path / "x.png")],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert p.returncode == 2
    assert "Traceback" not in p.stderr and p.stderr.strip().count("\n") == 0

