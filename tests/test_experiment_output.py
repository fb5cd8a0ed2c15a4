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


def _run(out: Path, *extra: str) -> int:
    return main(["experiment", "visual", *TINY, "--out", str(out), *extra])


def test_a_write_error_leaves_the_earlier_files_as_they_were(tmp_path, capsys, monkeypatch) -> None:
    # summary.json unwritable left the new CSVs beside the old summary.json, and the old plot
    # deleted; now the run's files are replaced together or not at all
    from aileen.experiments import output

    out = tmp_path / "out"
    assert _run(out, "--seed", "1") == 0
    (out / "visual" / "curve.png").write_bytes(b"an earlier run's plot")
    before = {p: p.read_bytes() for p in out.rglob("*") if p.is_file()}
    real = output._replace

    def fail_summary(src: Path, dst: Path) -> None:
        if "summary.json" in (src.name + dst.name):
            raise PermissionError(1, "Operation not permitted")
        real(src, dst)

    monkeypatch.setattr(output, "_replace", fail_summary)
    capsys.readouterr()
    assert _run(out, "--seed", "2") == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "summary.json" in err and "nothing of this run was written" in err
    assert {p: p.read_bytes() for p in out.rglob("*") if p.is_file()} == before


def test_a_summary_json_that_is_not_json_is_kept_beside_the_new_one(tmp_path, capsys) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / "summary.json").write_text("{ half a file")
    assert _run(out) == 0
    assert (out / "summary.json.bad-1").read_text() == "{ half a file"
    assert json.loads((out / "summary.json").read_text())["visual"]["trials"] == 1
    assert "kept as summary.json.bad-1" in capsys.readouterr().err


def test_a_stopped_experiment_says_that_nothing_of_it_was_written(tmp_path, capsys, monkeypatch) -> None:
    # it said only "stopped by SIGTERM"; docs/concept-memory.md said it kept finished trials
    import signal

    from aileen import lifecycle

    def stopped(*a, **kw):  # noqa: ANN002, ANN003, ANN202
        raise lifecycle.Stopped(signal.SIGTERM)

    monkeypatch.setattr(runner, "run_experiment", stopped)
    out = tmp_path / "out"
    assert _run(out) == 128 + signal.SIGTERM
    err = capsys.readouterr().err.strip()
    assert err == (f"aileen: stopped by SIGTERM; nothing of this run was written (its finished trials too); "
                   f"the files in {out} are as before")


def test_a_second_run_into_a_held_folder_is_refused_naming_the_holder(tmp_path, capsys, monkeypatch) -> None:
    # two sweeps into one --out each rewrote sweep.csv from their own rows: the first's vanished
    from aileen.experiments import output

    out = tmp_path / "out"
    out.mkdir()
    grid = tmp_path / "grid.toml"
    grid.write_text('experiment = "visual"\ntrials = 1\nlessons = 1\nperception = "truth"\n')
    _no_trials(monkeypatch)
    with output.locked(out, "aileen experiment sweep other.toml"):
        assert _run(out) == 2
        err = capsys.readouterr().err.strip()
        assert err.count("\n") == 0 and "in use by another run" in err and "sweep other.toml" in err
        assert main(["experiment", "sweep", str(grid), "--out", str(out), "--no-plot", "--quiet"]) == 2
        assert "in use by another run" in capsys.readouterr().err
    with output.locked(out, "the next run"):  # released at the end of the holder
        pass
