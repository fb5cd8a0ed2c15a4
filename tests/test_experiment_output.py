"""`aileen experiment`'s output folder: checked before any work, its files replaced together,
one line and exit 2 when they cannot be written, never a traceback after every trial ran."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from aileen.cli import main
from aileen.experiments import runner

TINY = ["--trials", "1", "--lessons", "2", "--perception", "truth", "--quiet", "--no-plot"]


def _no_trials(monkeypatch) -> None:  # noqa: ANN001
    def refuse(*a, **kw):  # noqa: ANN002, ANN003, ANN202
        raise AssertionError("a trial ran before the output folder was checked")

    monkeypatch.setattr(runner, "run_experiment", refuse)


@pytest.mark.parametrize("block, named", [
    ("visual", "is a file; expected a folder"),            # a file where the experiment's folder goes
    ("visual/trials.csv/", "is a folder; expected a file"),  # a folder where a CSV goes
    ("summary.json/", "is a folder"),
])
def test_an_output_path_that_cannot_be_written_is_refused_before_any_trial(tmp_path, capsys, monkeypatch,
                                                                           block, named) -> None:
    out = tmp_path / "vf"
    out.mkdir()
    target = out / block.rstrip("/")
    target.parent.mkdir(parents=True, exist_ok=True)
    target.mkdir() if block.endswith("/") else target.touch()
    _no_trials(monkeypatch)
    assert main(["experiment", "visual", *TINY, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and named in err and "Traceback" not in err


def test_a_folder_nothing_can_be_created_in_is_refused_before_any_trial(tmp_path, capsys, monkeypatch) -> None:
    from aileen.experiments import output

    def denied(*a, **kw):  # noqa: ANN002, ANN003, ANN202
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(output.tempfile, "mkstemp", denied)
    _no_trials(monkeypatch)
    assert main(["experiment", "visual", *TINY, "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "nothing can be created in" in err and "Permission denied" in err
