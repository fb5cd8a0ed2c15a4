"""The records of learning-curve trials and what is made of them: per-lesson summaries across
trials, the headline figures, and the files an experiment writes (trials.csv, summary.csv,
curve.png, summary.json). `runner` makes the records; this module only reads them.
"""

from __future__ import annotations

import csv
import io
import json
import math
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from aileen.io import atomic_write_bytes, atomic_write_text

EXAM_ITEMS = 5


# --------------------------------------------------------------------------- records

@dataclass(frozen=True)
class LessonRecord:
    """One training lesson of one trial: what it cost and how the exams went afterwards."""

    trial: int
    lesson: int  # 1-based
    content: str
    commands: int  # create + store commands sent to concept memory during the inform lesson
    generality: int  # 0-5: exam items whose scene holds what is said, answered "success"
    specificity: int  # 0-5: exam items whose scene does not, answered "failure"
    oracle: int  # 0-5: generality items whose words have all been taught so far
    ceiling: int = -1  # 0-5: what an ideal cross-situational learner passes (`cross_situational_curve`)
    sector_ceiling: int = -1  # 0-5, wide protocol: what a learner seeing 8 CDC sectors can pass (`ceiling`)


@dataclass
class TrialResult:
    experiment: str
    trial: int
    seed: int
    records: list[LessonRecord]
    prerequisite_commands: int = 0  # teaching the known concepts first (not scored)
    seconds: float = 0.0
    lessons_run: int = 0  # every lesson the interpreter ran, exams included
    # After the last lesson: per kind of specificity item (its note), [right, items].
    final_specificity: dict[str, list[int]] = field(default_factory=dict)
    exams_reused: int = 0  # lessons after which the memory was unchanged, so the answers were too


@dataclass
class LessonSummary:
    """Across trials, one lesson: means and (population) standard deviations."""

    lesson: int
    trials: int
    commands_mean: float
    commands_std: float
    generality_mean: float
    generality_std: float
    specificity_mean: float
    specificity_std: float
    oracle_mean: float
    oracle_std: float
    ceiling_mean: float = float("nan")
    ceiling_std: float = float("nan")


@dataclass
class Headline:
    """The per-experiment figures of docs/results.md."""

    experiment: str
    trials: int
    lessons: int
    perception: str
    holds_from: int | None  # first lesson from which mean generality stays 5.0 (None: never)
    final_generality: float
    lowest_specificity: float
    commands_per_trial: float
    area_pct_of_oracle: float  # sum of mean generality / sum of mean oracle, in %
    wall_s: float
    area_pct_of_ceiling: float = float("nan")  # ... of the cross-situational learner's, in %
    oracle_area: float = float("nan")  # sum over lessons of the mean oracle
    without: tuple[str, ...] = ()  # learning mechanisms switched off (an ablation run)
    protocol: str = "paper"
    # After the last lesson, per kind of specificity item: the fraction answered right.
    near_miss_final: dict[str, float] = field(default_factory=dict)
    area_pct_of_sector_ceiling: float = float("nan")  # wide protocol: ... of the 8-sector learner's, in %


@dataclass
class ExperimentResult:
    experiment: str
    perception: str
    seed: int
    trials: list[TrialResult]
    summary: list[LessonSummary] = field(default_factory=list)
    headline: Headline | None = None
    without: tuple[str, ...] = ()
    protocol: str = "paper"


# --------------------------------------------------------------------------- one trial

def _mean_std(xs: Sequence[float]) -> tuple[float, float]:
    a = np.asarray(xs, dtype=float)
    return float(a.mean()), float(a.std())


def summarise(results: Sequence[TrialResult]) -> list[LessonSummary]:
    """Per lesson, across trials: mean and standard deviation of each figure."""
    if not results:
        return []
    n = min(len(r.records) for r in results)
    out = []
    for i in range(n):
        recs = [r.records[i] for r in results]
        cm, cs = _mean_std([x.commands for x in recs])
        gm, gs = _mean_std([x.generality for x in recs])
        sm, ss = _mean_std([x.specificity for x in recs])
        om, os_ = _mean_std([x.oracle for x in recs])
        xm, xs = _mean_std([x.ceiling for x in recs])
        out.append(LessonSummary(i + 1, len(recs), cm, cs, gm, gs, sm, ss, om, os_, xm, xs))
    return out


def holds_from(curve: Sequence[float], top: float = EXAM_ITEMS) -> int | None:
    """The first lesson (1-based) from which the curve stays at `top`; None if it ends below."""
    start = None
    for i, v in enumerate(curve):
        if v >= top - 1e-9:
            if start is None:
                start = i + 1
        else:
            start = None
    return start


def headline(res: ExperimentResult, wall_s: float) -> Headline:
    s = res.summary
    gen = [x.generality_mean for x in s]
    orc = [x.oracle_mean for x in s]
    per_trial = float(np.mean([sum(r.commands for r in t.records) for t in res.trials]))
    area = 100.0 * sum(gen) / sum(orc) if sum(orc) > 0 else float("nan")
    ceil = sum(x.ceiling_mean for x in s)
    kinds: dict[str, list[int]] = {}
    for t in res.trials:
        for kind, (right, items) in t.final_specificity.items():
            k = kinds.setdefault(kind, [0, 0])
            k[0] += right
            k[1] += items
    return Headline(res.experiment, len(res.trials), len(s), res.perception, holds_from(gen),
                    gen[-1] if gen else float("nan"), min((x.specificity_mean for x in s), default=float("nan")),
                    per_trial, area, wall_s, 100.0 * sum(gen) / ceil if ceil > 0 else float("nan"), sum(orc),
                    res.without, res.protocol, {k: round(r / n, 3) for k, (r, n) in sorted(kinds.items())},
                    _sector_area(res))


def _sector_area(res: ExperimentResult) -> float:
    """Generality area as % of the sector ceiling's (wide protocol; nan otherwise)."""
    recs = [r for t in res.trials for r in t.records]
    top = sum(r.sector_ceiling for r in recs)
    if not recs or any(r.sector_ceiling < 0 for r in recs) or top <= 0:
        return float("nan")
    return 100.0 * sum(r.generality for r in recs) / top


# --------------------------------------------------------------------------- files

def write_text(path: Path, text: str) -> None:
    """Write via a temporary file and a rename (`aileen.io`), so readers never see half a file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    atomic_write_text(path, text)


def write_bytes(path: Path, data: bytes) -> None:
    """Binary twin of `write_text` (`aileen.io`)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    atomic_write_bytes(path, data)


def _csv(rows: Sequence[Sequence], header: Sequence[str]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    w.writerows(rows)
    return buf.getvalue()


TRIALS_HEADER = ("trial", "lesson", "commands", "generality", "specificity", "oracle")
SUMMARY_HEADER = ("lesson", "trials", "commands_mean", "commands_std", "generality_mean", "generality_std",
                  "specificity_mean", "specificity_std", "oracle_mean", "oracle_std", "ceiling_mean", "ceiling_std")


def _r(x: float) -> float:
    return round(x, 4)


def trials_csv(res: ExperimentResult) -> str:
    rows = [(r.trial + 1, r.lesson, r.commands, r.generality, r.specificity, r.oracle)
            for t in res.trials for r in t.records]
    return _csv(rows, TRIALS_HEADER)


def summary_csv(res: ExperimentResult) -> str:
    rows = [(s.lesson, s.trials, _r(s.commands_mean), _r(s.commands_std), _r(s.generality_mean),
             _r(s.generality_std), _r(s.specificity_mean), _r(s.specificity_std), _r(s.oracle_mean),
             _r(s.oracle_std), _r(s.ceiling_mean), _r(s.ceiling_std)) for s in res.summary]
    return _csv(rows, SUMMARY_HEADER)


def headline_dict(h: Headline) -> dict:
    d = asdict(h)
    d["without"] = list(h.without)
    for k, v in d.items():
        if isinstance(v, float):
            d[k] = None if math.isnan(v) else round(v, 3)
    return d


def write_experiment(res: ExperimentResult, out: Path, *, plot: bool = True,
                     baselines: "dict[str, ExperimentResult] | None" = None) -> list[str]:
    """DIR/<experiment>/trials.csv, summary.csv and curve.png (with the baselines' curves);
    each baseline's CSVs under DIR/<experiment>/baselines/<name>/. Returns notes for the user
    (e.g. why there is no plot)."""
    d = Path(out) / res.experiment
    write_text(d / "trials.csv", trials_csv(res))
    write_text(d / "summary.csv", summary_csv(res))
    for name, other in (baselines or {}).items():
        write_text(d / "baselines" / name / "trials.csv", trials_csv(other))
        write_text(d / "baselines" / name / "summary.csv", summary_csv(other))
    notes: list[str] = []
    if plot:
        from aileen.experiments import plots

        notes += plots.plot_curve(res, d / "curve.png", baselines=baselines)
    return notes


def update_summary_json(out: Path, key: str, value: dict) -> None:
    """Merge one experiment's headline into DIR/summary.json (other experiments' stay)."""
    path = Path(out) / "summary.json"
    data: dict = {}
    if path.exists():
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, json.JSONDecodeError):
            data = {}
    data[key] = value
    write_text(path, json.dumps(data, indent=2, sort_keys=True) + "\n")


def trial_words_check(res: ExperimentResult) -> list[str]:
    """Every trial's generality against its oracle: the lines where it exceeds it (should be none)."""
    bad = []
    for t in res.trials:
        for r in t.records:
            if r.generality > r.oracle:
                bad.append(f"trial {t.trial + 1} lesson {r.lesson}: generality {r.generality} > oracle {r.oracle}")
    return bad


