"""Issue 20: the teacher protocol, its ideal observer, the balanced headline and --senses."""

from __future__ import annotations

import argparse
import csv
import hashlib
import json
import math
import threading

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.cli import main
from aileen.curriculum import trainer
from aileen.curriculum.sentences import read_content
from aileen.domain import relations
from aileen.experiments import ideal, results, runner, teacher
from aileen.experiments.protocol import lesson_words, make_trial, oracle_curve
from aileen.reasoning import language


def _key(lesson) -> tuple:  # noqa: ANN001
    return (lesson.signal, lesson.content, tuple(lesson.objects), lesson.relation, lesson.distractors,
            lesson.expect, lesson.near_miss, lesson.feedback, lesson.note)


def _digest(seed: int) -> str:
    t = make_trial("spatial", seed, "teacher")
    h = hashlib.sha1(repr(t.teacher).encode())
    for part in (t.prerequisites, t.lessons, t.generality, t.specificity):
        h.update(repr([_key(x) for x in part]).encode())
    return h.hexdigest()


# --------------------------------------------------------------------------- the protocol

def test_a_teacher_trial_is_a_function_of_its_seed() -> None:
    assert _digest(3) == _digest(3)
    assert len({_digest(s) for s in range(6)}) == 6


@given(st.integers(0, 2**32 - 1))
@settings(max_examples=60, deadline=None)
def test_teachers_draw_from_their_families(seed: int) -> None:
    t = make_trial("spatial", seed, "teacher")
    who = t.teacher
    assert who is not None
    fams = who.family_of()
    assert [w for w, f in fams.items() if f == "wide"] == list(teacher.WIDE.axes)
    extra = [w for w, f in fams.items() if f != "wide"]
    assert 1 <= len(extra) <= 2 and len(set(extra)) == len(extra)
    for s in who.senses:
        fam = teacher.FAMILIES[s.family]
        assert fam.half_angle[0] <= s.half_angle <= fam.half_angle[1] and fam.axes[s.word] == s.axis
    # sizes, and every word has its examples and at least one near miss
    assert len(t.lessons) == teacher.TRAINING_INFORMS + teacher.TRAINING_NEAR_MISSES
    assert (len(t.generality), len(t.specificity)) == (teacher.GEN_ITEMS, teacher.SPEC_ITEMS)
    words = [read_content(x.content) for x in t.lessons]  # outside the scope: the trainer's words only
    assert all(w.relation is None or w.relation in relations.words() for w in words)
    with relations.scope(*t.relations):
        said = [read_content(x.content).relation for x in t.lessons]
        assert set(said) == set(who.words())
        for w in who.words():
            informs = [i for i, (x, r) in enumerate(zip(t.lessons, said)) if r == w and x.signal == "inform"]
            misses = [i for i, (x, r) in enumerate(zip(t.lessons, said)) if r == w and x.signal == "verify"]
            assert len(informs) >= 3 and misses and min(misses) > min(informs)
        for x in t.lessons:
            if x.signal == "verify":
                assert (x.near_miss, x.expect, x.feedback, x.note) == (True, "failure", "wrong", teacher.EDGE)
        # the one-shot oracle reads the teacher's words
        assert oracle_curve(t)[-1] == teacher.GEN_ITEMS


def test_every_word_is_one_relation_word_of_the_agents_grammar() -> None:
    for fam in teacher.FAMILIES.values():
        for word in fam.axes:
            p = language.parse(f"red box {word} blue cone")
            assert p.relation is not None and p.relation.word == word.replace(" ", "_")
            assert p.words == ("red", "box", "blue", "cone", word.replace(" ", "_"))


def test_a_trials_relations_never_reach_the_registry() -> None:
    before = (relations.known(), relations.words(), relations.phrases())
    t = make_trial("spatial", 11, "teacher")
    h = t.teacher.sense("left of").half_angle
    a, b = _P(0.5 + 0.1 * math.cos(math.radians(180 - h - 1)), 0.5 + 0.1 * math.sin(math.radians(180 - h - 1))), _P(0.5, 0.5)
    assert relations.holds("left of", a, b)  # a person's 45 degrees
    with relations.scope(*t.relations):
        assert relations.get("left of").accepts(a, b) is False  # this teacher's h
        assert relations.find("to the left of") == "left of"
        extra = [w for w in t.teacher.words() if w not in teacher.WIDE.axes]
        assert all(relations.find(w) == w for w in extra)
        seen: list[object] = []
        th = threading.Thread(target=lambda: seen.append(relations.find(extra[0])))
        th.start()
        th.join()
        assert seen == [None]  # another thread's runs do not see this trial's words
    assert (relations.known(), relations.words(), relations.phrases()) == before
    assert all(relations.find(w) is None for fam in (teacher.DIAGONAL, teacher.NARROW) for w in fam.axes)


class _P:
    def __init__(self, x: float, y: float, half: float = 0.02) -> None:
        self.x, self.y, self.half, self.size = x, y, half, "medium"

    def box_m(self) -> tuple[float, float, float, float]:
        return self.x - self.half, self.y - self.half, self.x + self.half, self.y + self.half


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_every_layout_is_graded_by_the_teachers_own_relation_after_settling(seed: int) -> None:
    t = make_trial("spatial", seed, "teacher")
    who = t.teacher
    with relations.scope(*t.relations):
        for k, lesson in enumerate(t.lessons + t.generality + t.specificity):
            setup = trainer.layout(lesson, seed=1000 * seed + k)  # settled and checked
            word = read_content(lesson.content).relation
            s = who.sense(word)
            a, b = setup.world.get(setup.ids[0]), setup.world.get(setup.ids[1])
            off = ideal.offset(ideal.said_direction(lesson, setup), s.axis)
            holds = relations.holds(word, a, b)
            if lesson.expect == "success":
                assert holds and off < s.half_angle - teacher.CLEAR_MARGIN, (lesson.content, off, s)
                assert relations.gap(a, b) > relations.CLEAR_GAP - 0.005
            elif lesson.note == teacher.EDGE:
                # just outside the edge: within 10 degrees of it, on the table, apart
                assert not holds and s.half_angle <= off <= s.half_angle + 10.0, (lesson.content, off, s)
                assert relations.gap(a, b) > 0.0
            elif lesson.note == teacher.ROTATED:
                assert not holds and off >= 80.0
            else:
                assert lesson.note == teacher.SWAPPED and holds  # laid out the other way round
                assert off >= 180.0 - s.half_angle


# --------------------------------------------------------------------------- the ideal observer

PRIOR = ideal.WordPrior("left of", 180.0, (20.0, 50.0), 1.0, (2.0, 9.0), 0.5)


def _brute(prior: ideal.WordPrior, positives: list[float], misses: list[float], ts: np.ndarray,
           n: int = 60_001) -> np.ndarray:
    """P(h > t) for each t, by summing Bayes' rule over a fine grid of h, from the generative model."""
    h = np.linspace(prior.half_angle[0], prior.half_angle[1], n)
    w = np.ones_like(h)
    for p in positives:
        w *= np.where(p <= h - prior.lay + prior.tol, 1.0 / (h - prior.lay), 0.0)
    for f in misses:
        ok = (h + prior.band[0] - prior.tol <= f) & (f <= h + prior.band[1] + prior.tol) & (h <= f)
        w *= np.where(ok, 1.0 / (prior.band[1] - prior.band[0]), 0.0)
    return np.array([w[h > t].sum() / w.sum() for t in ts])


@given(st.floats(20.0, 50.0), st.integers(1, 6), st.integers(0, 2), st.integers(0, 2**32 - 1))
@settings(max_examples=40, deadline=None)
def test_the_posterior_equals_a_brute_force_computation(h: float, n_pos: int, n_miss: int, seed: int) -> None:
    rng = np.random.default_rng(seed)
    post = ideal.Posterior(PRIOR)
    post.positives = [float(x) for x in rng.uniform(0.0, h - PRIOR.lay, n_pos)]
    post.misses = [float(x) for x in h + rng.uniform(*PRIOR.band, n_miss)]
    assert post.inconsistent() == 0
    ts = np.linspace(15.0, 60.0, 19)
    brute = _brute(PRIOR, post.positives, post.misses, ts)
    assert [post.p_holds(float(t)) for t in ts] == pytest.approx(list(brute), abs=2e-3)


def _simulate(rule, sims: int = 3000, seed: int = 7) -> float:  # noqa: ANN001
    """Mean accuracy of a rule (positives, misses, t) -> says yes, over teachers drawn from the
    family, a few examples each, items uniform in angle."""
    rng = np.random.default_rng(seed)
    right = total = 0
    for _ in range(sims):
        h = rng.uniform(*PRIOR.half_angle)
        pos = list(rng.uniform(0.0, h - PRIOR.lay, int(rng.integers(1, 5))))
        miss = list(h + rng.uniform(*PRIOR.band, int(rng.integers(0, 2))))
        for t in rng.uniform(0.0, 65.0, 8):
            right += rule(pos, miss, t) == (t < h)
            total += 1
    return right / total


def test_no_rule_given_the_same_examples_beats_the_ideal_observer_on_average() -> None:
    def observer(pos, miss, t):  # noqa: ANN001, ANN202
        post = ideal.Posterior(PRIOR, list(pos), list(miss))
        return post.p_holds(t) >= 0.5

    def tightest(pos, miss, t):  # noqa: ANN001, ANN202 - the smallest region the examples allow
        return t < max(max(pos) + PRIOR.lay, PRIOR.half_angle[0])

    def loosest(pos, miss, t):  # noqa: ANN001, ANN202 - the largest one
        return t < min([PRIOR.half_angle[1]] + list(miss))

    def middle(pos, miss, t):  # noqa: ANN001, ANN202 - halfway between the two
        lo = max(max(pos) + PRIOR.lay, PRIOR.half_angle[0])
        return t < 0.5 * (lo + min([PRIOR.half_angle[1]] + list(miss)))

    best = _simulate(observer)
    for rule in (tightest, loosest, middle, lambda pos, miss, t: t < 35.0):
        assert best > _simulate(rule)


def test_the_observer_knows_no_word_before_its_first_example() -> None:
    from aileen.curriculum.lesson import Lesson, ObjectSpec

    obs = ideal.IdealObserver({"left of": PRIOR})
    item = Lesson("verify", "red box left of blue cone", [ObjectSpec("box", "red"), ObjectSpec("cone", "blue")])
    obs.learn_words(["red", "box", "blue", "cone"])
    assert not obs.says_yes(item, 180.0)  # never shown
    obs.see("left of", 175.0, True)
    assert obs.says_yes(item, 181.0) and obs.says_yes(item, 160.0)  # within the smallest h
    assert not obs.says_yes(item, 0.0) and not obs.says_yes(item, 90.0)
    obs.see("left of", 180.0 + 27.0, False)  # a near miss 27 degrees off: h is below 25.5
    assert obs.p_holds("left of", 180.0 + 26.0) == 0.0


# --------------------------------------------------------------------------- the runner and the headline

def test_a_teacher_trial_reports_the_ideal_and_the_families() -> None:
    r = runner.run_trial("spatial", 0, 4, perception="truth", protocol="teacher", lessons=4)
    assert r.exam_items == (teacher.GEN_ITEMS, teacher.SPEC_ITEMS)
    t = make_trial("spatial", runner.trial_seed(4, 0), "teacher")
    assert set(r.groups) == set(t.teacher.family_of().values())
    for i, rec in enumerate(r.records):
        assert 0 <= rec.ideal_generality <= rec.oracle and 0 <= rec.ideal_specificity <= teacher.SPEC_ITEMS
        rows = [g[i] for g in r.groups.values()]
        assert sum(g.generality for g in rows) == rec.generality
        assert sum(g.specificity for g in rows) == rec.specificity
        assert sum(g.oracle for g in rows) == rec.oracle
        assert sum(g.ideal_generality for g in rows) == rec.ideal_generality
        assert sum(g.generality_items for g in rows) == teacher.GEN_ITEMS
    assert sum(n for _, n in r.final_specificity.values()) == teacher.SPEC_ITEMS
    assert r.ideal_final_specificity.keys() == r.final_specificity.keys()


def _result(gen: list[int], spec: list[int], oracle: list[int], ideal_g: int = -1, ideal_s: int = -1,
            items: tuple[int, int] = (5, 5)) -> results.ExperimentResult:
    recs = [results.LessonRecord(0, i + 1, "x", 0, g, s, o, o, ideal_generality=ideal_g, ideal_specificity=ideal_s)
            for i, (g, s, o) in enumerate(zip(gen, spec, oracle))]
    res = results.ExperimentResult("spatial", "truth", 0, [results.TrialResult("spatial", 0, 0, recs, exam_items=items)])
    res.summary = results.summarise(res.trials)
    res.headline = results.headline(res, 1.0)
    return res


def test_the_balanced_area_counts_specificity_beside_generality() -> None:
    top = _result([2, 5], [5, 5], [2, 5]).headline
    assert top.balanced_pct_oracle == pytest.approx(100.0) and top.area_pct_of_oracle == pytest.approx(100.0)
    # full generality beside no specificity: the generality-only figure hides it
    half = _result([2, 5], [0, 0], [2, 5]).headline
    assert half.area_pct_of_oracle == pytest.approx(100.0)
    assert half.balanced_pct_oracle == pytest.approx(100.0 * (7 / 10) / (7 / 10 + 1))
    assert math.isnan(half.balanced_pct_ideal)
    ours = _result([6, 12], [12, 6], [6, 12], ideal_g=12, ideal_s=12, items=(12, 12)).headline
    assert ours.balanced_pct_ideal == pytest.approx(100.0 * (18 / 24 + 18 / 24) / 2)
    assert ours.exam_items == (12, 12)


def test_cli_teacher_protocol_with_senses_writes_the_balanced_headline(tmp_path, capsys) -> None:
    out = tmp_path / "res"
    rc = main(["experiment", "spatial", "--protocol", "teacher", "--trials", "1", "--lessons", "2", "--perception",
               "truth", "--senses", "sectors", "--out", str(out), "--quiet", "--no-plot"])
    assert rc == 0
    h = json.loads((out / "summary.json").read_text())["spatial"]
    assert h["protocol"] == "teacher" and h["senses"] == "sectors" and h["exam_items"] == [12, 12]
    assert 0 < h["balanced_pct_oracle"] <= 100 and h["balanced_pct_ideal"] > 0
    assert set(h["by_family"]) <= {"wide", "narrow", "diagonal"} and "wide" in h["by_family"]
    with (out / "spatial" / "areas.csv").open(newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert [r["group"] for r in rows][0] == "all" and {r["group"] for r in rows[1:]} == set(h["by_family"])
    with (out / "spatial" / "summary.csv").open(newline="") as fh:
        summary = list(csv.DictReader(fh))
    assert all(float(r["balanced_mean"]) == pytest.approx((float(r["generality_mean"]) + float(r["specificity_mean"])) / 2)
               for r in summary)
    printed = capsys.readouterr().out
    assert "by family" in printed and "balanced % ideal" in printed


@pytest.mark.parametrize("argv, text", [
    (["experiment", "visual", "--protocol", "teacher"], "teacher protocol"),
    (["experiment", "react", "--protocol", "teacher"], "react"),
    (["experiment", "spatial", "--agent", "soar", "--senses", "all"], "--senses"),
])
def test_cli_teacher_and_senses_bad_input_exit_2(tmp_path, capsys, argv, text) -> None:
    assert main([*argv, "--out", str(tmp_path), "--no-plot", "--quiet"]) == 2
    err = capsys.readouterr().err
    assert text in err and err.strip().count("\n") == 0


def test_cli_unknown_sense_is_refused(tmp_path, capsys) -> None:
    with pytest.raises(SystemExit) as exc:
        main(["experiment", "spatial", "--senses", "d64", "--out", str(tmp_path)])
    assert exc.value.code == 2 and "--senses" in capsys.readouterr().err


@pytest.mark.parametrize("senses", ["cones", "sectors", "all"])
def test_run_and_teach_give_the_agent_the_sense_asked_for(senses: str) -> None:
    from aileen.agent import AgentParams
    from aileen.cli import build_parser
    from aileen.curriculum.commands import make_agent
    from aileen.experiments import baselines

    for cmd in (["run", "x.toml"], ["teach"]):
        args = build_parser().parse_args([*cmd, "--perception", "truth", "--senses", senses])
        agent, _ = make_agent(args)
        assert agent.params.senses_of_direction == senses
    default = build_parser().parse_args(["teach", "--perception", "truth"])
    assert make_agent(default)[0].params.senses_of_direction == AgentParams().senses_of_direction
    assert baselines.make("nearest", 0, None, senses).params.senses_of_direction == senses
    assert baselines.make("paper", 0, None, senses).params.senses_of_direction == "sectors"  # the paper's own


def test_serve_takes_senses() -> None:
    from aileen.cli import build_parser

    args = build_parser().parse_args(["serve", "--senses", "all"])
    assert isinstance(args, argparse.Namespace) and args.senses == "all"


def test_oracle_words_of_a_teacher_lesson() -> None:
    t = make_trial("spatial", 5, "teacher")
    extra = [w for w in t.teacher.words() if w not in teacher.WIDE.axes][0]
    lesson = next(x for x in t.lessons if extra in x.content)
    with relations.scope(*t.relations):
        assert extra in lesson_words(lesson)


def test_the_printed_table_says_of_how_many_items_a_teacher_exam_is() -> None:
    # "final gen. 7.0 | lowest spec. 8.0" read as of 5, as every other protocol's
    from aileen.experiments.commands import format_table

    row = {"experiment": "spatial", "trials": 1, "holds_from": None, "final_generality": 8.0,
           "lowest_specificity": 7.0, "commands_per_trial": 8.0, "area_pct_of_oracle": 100.0,
           "balanced_pct_oracle": 80.9, "balanced_pct_ideal": 87.3, "wall_s": 1.0}
    assert "| 8.0 of 12 | 7.0 of 12 |" in format_table([{**row, "exam_items": [12, 12]}])
    assert "| 8.0 | 7.0 |" in format_table([{**row, "exam_items": [5, 5]}])
