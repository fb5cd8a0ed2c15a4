"""`aileen experiment`: options a run would leave out without a word are refused, the learner
that ran is recorded, and a folder holds no file of an earlier run beside a new one."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from aileen.cli import main

TINY = ["--trials", "1", "--lessons", "2", "--perception", "truth", "--quiet"]


@pytest.mark.parametrize("args, words", [
    (["action", "--agent", "nearest"], "--agent nearest takes visual, spatial only"),
    (["visual", "--agent", "paper", "--without", "cones"], "--agent paper has none of them"),
    (["spatial", "--senses", "cones", "--without", "cones"], "contradicts --senses cones"),
    (["visual", "--backend", "ray"], "are for 'experiment sweep'"),
    (["react", "--baselines"], "react has no baselines"),
    (["react", "--lessons", "3"], "react's training is its protocol's"),
    (["spatial", "--senses", "sectors", "--without", "cones"], "--without cones is --senses sectors"),
    (["visual", "--lessons", "100"], "visual (wide protocol) has 24 training lessons"),
    (["all", "--lessons", "22"], "has 20 training lessons"),
    (["visual", "--without", "bogus"], "bogus"),  # (it left an empty --out folder behind)
])
def test_an_option_the_run_would_leave_out_is_refused_and_makes_no_folder(tmp_path, capsys, args, words) -> None:
    out = tmp_path / "out"
    tiny = TINY if "--lessons" not in args else [a for a in TINY if a not in ("--lessons", "2")]
    assert main(["experiment", *args, *tiny, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and words in err
    assert not out.exists()


def test_the_learner_that_ran_is_recorded_and_named(tmp_path, capsys) -> None:
    out = tmp_path / "out"
    assert main(["experiment", "visual", "--agent", "nearest", *TINY, "--no-plot", "--out", str(out),
                 "--seed", "3"]) == 0
    h = json.loads((out / "summary.json").read_text())["visual"]
    assert (h["agent"], h["seed"]) == ("nearest", 3)
    assert "visual (nearest) |" in capsys.readouterr().out


def test_a_run_without_baselines_leaves_no_earlier_baseline_beside_it(tmp_path) -> None:
    out = tmp_path / "out"
    assert main(["experiment", "visual", "--baselines", *TINY, "--no-plot", "--out", str(out)]) == 0
    assert (out / "visual" / "baselines").is_dir() and json.loads((out / "summary.json").read_text())["baselines"]
    (out / "visual" / "curve.png").write_bytes(b"an earlier run's plot")
    assert main(["experiment", "visual", *TINY, "--no-plot", "--out", str(out), "--seed", "5"]) == 0
    assert sorted(p.name for p in (out / "visual").iterdir()) == ["areas.csv", "summary.csv", "trials.csv"]
    assert json.loads((out / "summary.json").read_text())["baselines"] == {}


def test_no_progress_bars_into_a_file_or_a_pipe(tmp_path, capsys) -> None:
    # several bars at once (`all` runs experiments side by side) garbled a log and buried its
    # notes; bars are for a terminal
    assert main(["experiment", "visual", "--trials", "1", "--lessons", "2", "--perception", "truth",
                 "--out", str(tmp_path), "--no-plot"]) == 0
    err = capsys.readouterr().err
    assert "%|" not in err and "trial/s" not in err


def test_a_grid_keeping_more_lessons_than_an_experiment_has_is_refused(tmp_path, capsys) -> None:
    """It ran the 24 a visual trial has and recorded 100 in sweep.csv."""
    grid = tmp_path / "g.toml"
    grid.write_text('experiment = "visual"\ntrials = 1\nseeds = [0]\nlessons = 100\n')
    assert main(["experiment", "sweep", str(grid), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert "g.toml:4:" in err and "has 24 training lessons" in err and err.count("\n") == 0


def test_a_comparison_of_no_scenes_is_refused(capsys) -> None:
    assert main(["perception", "compare", "--plain", "0", "--stacked", "0", "shipped"]) == 2
    assert "nothing to compare" in capsys.readouterr().err


def test_the_sector_ceiling_area_is_recomputed_from_trials_csv(tmp_path) -> None:
    """summary.json's area_pct_of_sector_ceiling was in no CSV (summary.csv's ceiling is the
    cross-situational learner's)."""
    import csv

    out = tmp_path / "o"
    assert main(["experiment", "spatial", *TINY, "--no-baselines", "--out", str(out)]) == 0
    rows = list(csv.DictReader((out / "spatial" / "trials.csv").open()))
    pct = 100.0 * sum(int(r["generality"]) for r in rows) / sum(int(r["sector_ceiling"]) for r in rows)
    got = json.loads((out / "summary.json").read_text())["spatial"]["area_pct_of_sector_ceiling"]
    assert abs(pct - got) < 0.01


def test_a_number_of_trials_past_the_bound_is_refused_in_one_line(tmp_path, capsys) -> None:
    assert main(["experiment", "visual", "--trials", "100000000000", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert "--trials must be from 1 to 100000" in err and len(err.splitlines()) == 1
    assert not (tmp_path / "o").exists()


def test_a_missing_extra_is_refused_and_makes_no_folder(tmp_path, capsys) -> None:
    import importlib.util

    if importlib.util.find_spec("concept_formation") is not None:
        pytest.skip("the 'baselines' extra is installed")
    out = tmp_path / "out"
    assert main(["experiment", "visual", "--agent", "cobweb", *TINY, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "cobweb" in err.lower()
    assert not out.exists()


def test_each_learners_progress_bar_is_named(monkeypatch) -> None:
    # with --baselines the three bars all read "visual:"
    from aileen.experiments import runner

    names = []

    class Bar:
        def update(self, n: int = 1) -> None:
            pass

        def close(self) -> None:
            pass

    def bar(total: int, what: str) -> Bar:
        names.append(what)
        return Bar()

    monkeypatch.setattr(runner, "_bar", bar)
    for kind in ("asp", "nearest"):
        runner.run_experiment("visual", trials=1, lessons=1, perception="truth", progress=True, agent_kind=kind)
    assert names == ["visual", "visual (nearest)"]
