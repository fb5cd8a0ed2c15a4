"""The evaluation: protocol oracle, trial runner, output files, react benchmark, plots, CLI."""

from __future__ import annotations

import csv
import json
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from aileen.cli import main
from aileen.errors import UserError
from aileen.experiments import plots, react, runner, tables
from aileen.experiments.protocol import make_trial, oracle_curve

# The reference's visual one-shot oracle (../shared/reference/README.md, 20,000 trials).
REFERENCE_ORACLE = [0.21, 0.68, 1.30, 1.93, 2.54, 3.07, 3.54, 3.91, 4.21, 4.44, 4.62, 4.74, 4.83, 4.90, 4.94,
                    4.97, 4.98, 4.99, 5.00, 5.00, 5.00, 5.00, 5.00, 5.00]


def _rows(path: Path) -> list[dict[str, str]]:
    with path.open(newline="") as fh:
        return list(csv.DictReader(fh))


# --------------------------------------------------------------------------- protocol oracle

def test_protocol_oracle_reproduces_the_reference_visual_ceiling():
    curves = np.array([oracle_curve(make_trial("visual", s)) for s in range(1500)], dtype=float)
    mean = curves.mean(axis=0)
    assert mean.shape == (24,)
    assert np.all(np.abs(mean - np.array(REFERENCE_ORACLE)) < 0.12), np.round(mean, 2)
    assert abs(mean.sum() - 94.8) < 1.0


@given(st.integers(0, 10_000), st.sampled_from(["visual", "spatial", "action"]))
def test_cross_situational_ceiling_never_exceeds_the_oracle(seed, experiment):
    trial = make_trial(experiment, seed)
    ceiling, oracle = runner.cross_situational_curve(trial), oracle_curve(trial)
    assert all(0 <= c <= o for c, o in zip(ceiling, oracle))
    assert ceiling[-1] == oracle[-1] == 5  # every word pinned by the end of a full trial


def test_cross_situational_ceiling_pins_words_across_lessons():
    from aileen.curriculum.lesson import Lesson, ObjectSpec
    from aileen.experiments.protocol import Trial

    def item(text: str, shape: str, colour: str, signal: str = "inform") -> Lesson:
        return Lesson(signal, text, [ObjectSpec(shape, colour)])

    lessons = [item("blue sphere", "sphere", "blue"), item("blue box", "box", "blue"), item("green cone", "cone", "green")]
    gen = [item("blue sphere", "sphere", "blue", "verify"), item("green sphere", "sphere", "green", "verify"),
           item("blue box", "box", "blue", "verify")]
    trial = Trial("visual", 0, lessons, gen, [])
    assert oracle_curve(trial) == [1, 2, 3]
    # lesson 1: "blue sphere" is passed as seen; lesson 2 pins blue, hence sphere; "green" stays
    # entangled with cone after lesson 3, so "green sphere" is not yet sure.
    assert runner.cross_situational_curve(trial) == [1, 2, 2]


# --------------------------------------------------------------------------- pure helpers

@given(st.lists(st.integers(0, 5), min_size=1, max_size=30))
def test_holds_from_is_the_start_of_the_final_run_at_five(curve):
    h = runner.holds_from([float(x) for x in curve])
    if curve[-1] != 5:
        assert h is None
    else:
        assert h is not None and 1 <= h <= len(curve)
        assert all(x == 5 for x in curve[h - 1:])
        assert h == 1 or curve[h - 2] < 5


def test_holds_from_examples():
    assert runner.holds_from([0, 5, 4, 5, 5]) == 4
    assert runner.holds_from([5, 5]) == 1
    assert runner.holds_from([5, 4.9]) is None


def _trial(t: int, gens: list[int], cmds: list[int]) -> runner.TrialResult:
    recs = [runner.LessonRecord(t, i + 1, "x", c, g, 5, 5) for i, (g, c) in enumerate(zip(gens, cmds))]
    return runner.TrialResult("visual", t, 0, recs)


def test_summary_means_and_stds_and_headline():
    res = runner.ExperimentResult("visual", "truth", 0, [_trial(0, [1, 5], [4, 0]), _trial(1, [3, 5], [2, 1])])
    res.summary = runner.summarise(res.trials)
    s1, s2 = res.summary
    assert (s1.generality_mean, s1.generality_std) == (2.0, 1.0)
    assert (s1.commands_mean, s1.commands_std) == (3.0, 1.0)
    assert (s2.generality_mean, s2.generality_std, s2.commands_mean) == (5.0, 0.0, 0.5)
    h = runner.headline(res, 1.0)
    assert h.holds_from == 2 and h.final_generality == 5.0 and h.commands_per_trial == 3.5
    assert h.area_pct_of_oracle == pytest.approx(100 * 7 / 10)


def test_trial_seeds_differ_and_are_stable():
    seeds = {runner.trial_seed(0, t) for t in range(50)}
    assert len(seeds) == 50
    assert runner.trial_seed(3, 4) == runner.trial_seed(3, 4) != runner.trial_seed(4, 3)


# --------------------------------------------------------------------------- trials

def test_exams_must_not_change_memory(monkeypatch):
    """A learner that stores during verify lessons is caught, not scored."""
    from aileen.agent import Agent

    monkeypatch.setattr(Agent, "verify", lambda self, content, demo_start=None: self.inform(content))
    with pytest.raises(RuntimeError, match="create/store|changed"):
        runner.run_trial("visual", 0, 0, perception="truth", lessons=1)


def test_a_trial_never_beats_its_oracle_and_learns():
    r = runner.run_trial("visual", 0, 5, perception="truth", lessons=6)
    assert [x.lesson for x in r.records] == [1, 2, 3, 4, 5, 6]
    assert all(0 <= x.generality <= x.oracle <= 5 and 0 <= x.specificity <= 5 for x in r.records)
    assert r.records[0].commands >= 2  # the first lesson's words are all new: create + store
    assert r.lessons_run == 6 * 11


def test_cli_one_trial_few_lessons_writes_the_files(tmp_path, capsys):
    out = tmp_path / "res"
    rc = main(["experiment", "visual", "--trials", "1", "--lessons", "3", "--perception", "truth",
               "--out", str(out), "--quiet"])
    assert rc == 0
    rows = _rows(out / "visual" / "trials.csv")
    assert list(rows[0]) == list(tables.TRIALS_HEADER)
    assert [int(r["lesson"]) for r in rows] == [1, 2, 3] and {r["trial"] for r in rows} == {"1"}
    assert all(int(r["generality"]) <= int(r["oracle"]) for r in rows)
    summary = _rows(out / "visual" / "summary.csv")
    assert list(summary[0]) == list(tables.SUMMARY_HEADER) and len(summary) == 3
    assert float(summary[0]["generality_std"]) == 0.0  # one trial
    data = json.loads((out / "summary.json").read_text())
    assert data["visual"]["trials"] == 1 and data["visual"]["lessons"] == 3
    assert set(data["visual"]) >= {"holds_from", "final_generality", "lowest_specificity", "commands_per_trial",
                                   "area_pct_of_oracle", "wall_s"}
    png = out / "visual" / "curve.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "visual | 1 |" in capsys.readouterr().out


def test_a_stop_while_the_figures_are_written_waits_for_summary_json(tmp_path, monkeypatch, capsys):
    # a SIGTERM between an experiment's CSVs and its summary.json entry left new CSVs beside
    # the old figures (or none); the writing now finishes, then the stop is acted on (143)
    import os
    import signal

    from aileen.experiments import output

    real = output._replace

    def replace_then_stop(src, dst):  # noqa: ANN001, ANN202
        real(src, dst)
        os.kill(os.getpid(), signal.SIGTERM)

    monkeypatch.setattr(output, "_replace", replace_then_stop)
    out = tmp_path / "res"
    rc = main(["experiment", "visual", "--trials", "1", "--lessons", "2", "--perception", "truth",
               "--out", str(out), "--quiet", "--no-plot"])
    assert rc == 128 + signal.SIGTERM
    data = json.loads((out / "summary.json").read_text())
    assert data["visual"]["trials"] == 1 and data["visual"]["lessons"] == 2
    assert len(_rows(out / "visual" / "trials.csv")) == 2
    assert "figures were written" in capsys.readouterr().err


def test_results_do_not_depend_on_jobs(tmp_path):
    a = runner.run_experiment("spatial", trials=2, seed=3, jobs=1, perception="truth", lessons=2)
    b = runner.run_experiment("spatial", trials=2, seed=3, jobs=2, perception="truth", lessons=2)
    assert runner.trials_csv(a) == runner.trials_csv(b)
    assert runner.summary_csv(a) == runner.summary_csv(b)


@pytest.mark.slow  # spawns two workers that load vision
def test_learners_sharing_vision_in_a_pool_get_what_they_get_alone():
    # in a shared pool the learners' trials read each other's detections (vision_cache);
    # what each learner then does must be what it does alone, in this process
    alone = [runner.run_experiment("visual", trials=2, seed=5, jobs=1, perception="detector", lessons=2,
                                   agent_kind=k) for k in ("asp", "paper")]
    with runner.shared_pool(2):
        pooled = [runner.run_experiment("visual", trials=2, seed=5, jobs=2, perception="detector", lessons=2,
                                        agent_kind=k) for k in ("asp", "paper")]
    for a, b in zip(alone, pooled):
        assert runner.trials_csv(a) == runner.trials_csv(b)
        assert runner.summary_csv(a) == runner.summary_csv(b)


@pytest.mark.slow  # trains in this process, then in two workers
def test_react_does_not_depend_on_jobs():
    one, two = (react.run_react(4, seed=2, perception="truth", jobs=j) for j in (1, 2))
    assert one.training_commands == two.training_commands
    assert [(t.task, t.content, t.success, t.agent_result, t.projections, t.steps) for t in one.tasks] == \
        [(t.task, t.content, t.success, t.agent_result, t.projections, t.steps) for t in two.tasks]


@pytest.mark.parametrize("argv, text", [
    (["--trials", "0"], "--trials"),
    (["--jobs", "0"], "--jobs"),
    (["--lessons", "0"], "--lessons"),
])
def test_cli_bad_numbers_exit_2(tmp_path, capsys, argv, text):
    assert main(["experiment", "visual", "--out", str(tmp_path), *argv]) == 2
    err = capsys.readouterr().err
    assert text in err and err.count("\n") == 1


@pytest.mark.parametrize("agent", ["soar", "paper", "nearest"])
def test_cli_react_with_another_agent_is_refused_not_run_with_ours(tmp_path, capsys, agent):
    """react trains and drives the ASP agent; asked for another, it says so (exit 2) instead of
    running ours under that name."""
    assert main(["experiment", "react", "--agent", agent, "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "react runs the asp agent" in err and err.count("\n") == 1
    assert not any(tmp_path.iterdir())


def test_cli_out_is_a_file_exits_2(tmp_path, capsys):
    f = tmp_path / "f"
    f.write_text("x")
    assert main(["experiment", "visual", "--out", str(f)]) == 2
    assert "expected a folder" in capsys.readouterr().err


@pytest.mark.skipif(not Path(__file__).resolve().parents[1].joinpath("aileen/models/detector.onnx").exists(),
                    reason="no trained detector shipped yet")
def test_one_lesson_with_the_detector():
    r = runner.run_trial("visual", 0, 0, perception="detector", lessons=1)
    assert len(r.records) == 1 and r.records[0].generality <= r.records[0].oracle


# --------------------------------------------------------------------------- react

def test_react_tasks_are_well_formed_and_seeded():
    tasks = react.make_tasks(40, 1)
    assert [t.content for t in tasks] == [t.content for t in react.make_tasks(40, 1)]
    assert [t.content for t in tasks] != [t.content for t in react.make_tasks(40, 2)]
    for t in tasks:
        assert t.signal == "react" and t.action is not None
        assert t.relation != t.action.relation  # the mover starts elsewhere
        assert 0 <= t.distractors <= 3 and t.objects[0] != t.objects[1]
    assert {t.distractors for t in tasks} == {0, 1, 2, 3}


def test_react_benchmark_runs_and_reports(tmp_path):
    res = react.run_react(3, seed=0, perception="truth")
    s = res.summary
    assert s["tasks"] == 3 and 0.0 <= s["success_rate"] <= 1.0
    assert res.training_commands > 0
    assert all(t.projections >= 1 for t in res.tasks if t.agent_result == "success")
    rows = list(csv.reader(react.tasks_csv(res).splitlines()))
    assert tuple(rows[0]) == react.TASKS_HEADER and len(rows) == 4


def test_react_over_distance_and_contact_words_is_balanced_and_reaches_its_goals():
    words = react.parse_relations("near, next-to,far-from,on,close to")
    assert words == react.DISTANCE_AND_CONTACT  # spellings read as the trainer's words, once each
    tasks = react.make_tasks(20, 3, "wide", words)
    assert [t.content for t in tasks] == [t.content for t in react.make_tasks(20, 3, "wide", words)]
    goals = [t.action.relation for t in tasks]
    assert sorted(goals.count(w) for w in words) == [5, 5, 5, 5]
    for t in tasks:
        assert t.relation in react.RELATIONS or t.relation.endswith(" wide")  # starts in a direction
        if t.action.relation == "on":
            assert t.objects[1].shape in ("box", "cylinder")  # something can rest on it
    res = react.run_react(8, seed=3, perception="truth", protocol="wide", words=words)
    s = res.summary
    assert s["relations"] == list(words) and sum(n for _, n in s["by_relation"].values()) == 8
    assert s["success_rate"] == 1.0, s["failures"]
    with pytest.raises(UserError, match="'larger than' is not a word 'move X <word> Y' can bring about"):
        react.parse_relations("near,larger than")
    with pytest.raises(UserError, match="'nearby'"):
        react.parse_relations("nearby")


# --------------------------------------------------------------------------- plots and reference

def test_packaged_reference_matches_the_published_summary():
    ref = plots.load_reference()
    assert {k: len(v) for k, v in ref.items()} == {"visual": 24, "spatial": 20, "action": 20}
    assert sum(p.generality for p in ref["visual"]) == pytest.approx(83.1, abs=0.05)
    assert ref["action"][-1].generality == pytest.approx(4.4)
    assert sum(p.commands for p in ref["visual"]) == pytest.approx(27, abs=0.05)


def test_bad_reference_file_names_its_line(tmp_path):
    p = tmp_path / "ref.csv"
    p.write_text("experiment,lesson,runs,mean_store_commands,mean_generality,mean_specificity\nvisual,1,10,x,0,5\n")
    with pytest.raises(UserError) as e:
        plots.load_reference(p)
    assert e.value.format().startswith(f"{p}:2")


def test_plot_without_reference_says_so(tmp_path):
    res = runner.ExperimentResult("visual", "truth", 0, [_trial(0, [1, 5], [4, 0])])
    res.summary = runner.summarise(res.trials)
    notes = plots.plot_curve(res, tmp_path / "c.png", reference={})
    assert notes and "not found" in notes[0]
    assert (tmp_path / "c.png").stat().st_size > 1000


def test_plot_without_matplotlib_is_a_user_error(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    res = runner.ExperimentResult("visual", "truth", 0, [_trial(0, [1], [1])])
    res.summary = runner.summarise(res.trials)
    with pytest.raises(UserError, match=r"aileen\[plot\]"):
        plots.plot_curve(res, tmp_path / "c.png")


def test_cli_without_switches_a_mechanism_off_and_says_so(tmp_path, capsys):
    args = ["experiment", "visual", "--trials", "1", "--lessons", "3", "--perception", "truth",
            "--out", str(tmp_path), "--no-plot", "--quiet"]
    assert main(args + ["--without", "mutual-exclusivity", "--without", "syntactic-bootstrapping"]) == 0
    head = json.loads((tmp_path / "summary.json").read_text())["visual"]
    assert head["without"] == ["mutual-exclusivity", "syntactic-bootstrapping"]
    capsys.readouterr()
    assert main(args + ["--without", "telepathy"]) == 2
    assert "unknown mechanism 'telepathy'" in capsys.readouterr().err


def test_each_mechanism_earns_its_place():
    """On the same trial, summed over the lessons, the full agent's generality is higher than
    that of the paper's learner (both mechanisms off), with specificity kept at 5."""
    full = runner.run_trial("visual", 0, 5, perception="truth")
    plain = runner.run_trial("visual", 0, 5, perception="truth",
                             without=("mutual-exclusivity", "syntactic-bootstrapping"))
    g_full = sum(r.generality for r in full.records)
    g_plain = sum(r.generality for r in plain.records)
    assert g_full > g_plain
    assert all(r.specificity == 5 for r in full.records)


def test_react_takes_the_agents_ablations_and_says_which() -> None:
    # `react --without one-verb` and `--senses` were accepted and ignored: the same tasks, the
    # same agent; summary.json named neither (nor the seed)
    plain = react.run_react(2, seed=0, perception="truth", protocol="wide")
    alone = react.run_react(2, seed=0, perception="truth", protocol="wide", without=("one-verb",), senses="cones")
    assert plain.summary["success_rate"] == 1.0
    assert alone.summary["success_rate"] == 0.0  # "move behind" is never shown: without one verb, no word for it
    assert (alone.summary["seed"], alone.summary["without"], alone.summary["senses"]) == (0, ["one-verb"], "cones")
    # the sense used, as the learning curves record it (it recorded the raw flag: None)
    assert (plain.summary["without"], plain.summary["senses"]) == ([], runner.senses_of())
    assert plain.summary["senses"] is not None


def test_every_learner_records_the_sense_it_perceives_with():
    # the paper's learner beside ours (--baselines) was recorded as senses '' (printed "-")
    from aileen.experiments.baselines import paper_params

    res = runner.run_experiment("visual", trials=1, lessons=1, perception="truth", agent_kind="paper")
    assert res.senses == paper_params(0).senses_of_direction != ""
    assert runner.perceived_senses("asp", ("cones",)) == runner.senses_of(("cones",)) != runner.senses_of()
