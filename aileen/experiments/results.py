"""The records of learning-curve trials and what is made of them: per-lesson summaries across
trials and the headline figures. `trial` and `runner` make the records; this module only
reads them; `tables` writes them as text (trials.csv, summary.csv, areas.csv,
summary.json), `plots` draws them and `output` puts an experiment's files in its folder.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

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
    # Teacher protocol: what the ideal observer (experiments/ideal.py) answers right; -1 elsewhere.
    ideal_generality: int = -1
    ideal_specificity: int = -1


@dataclass(frozen=True)
class GroupRecord:
    """One training lesson of one trial, restricted to one group of exam items (the teacher
    protocol: the items whose word is of one family, `teacher.FAMILIES`): how many items the
    group has and how many each learner answered right."""

    generality: int
    generality_items: int
    specificity: int
    specificity_items: int
    oracle: int
    ideal_generality: int = -1
    ideal_specificity: int = -1
    edge: int = 0  # near misses just outside the teacher's edge answered right (ours)
    edge_items: int = 0
    ideal_edge: int = -1


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
    exam_items: tuple[int, int] = (EXAM_ITEMS, EXAM_ITEMS)  # generality, specificity items
    # Per group of exam items (the teacher protocol's families), per lesson.
    groups: dict[str, list[GroupRecord]] = field(default_factory=dict)
    # As `final_specificity`, for the ideal observer (teacher protocol).
    ideal_final_specificity: dict[str, list[int]] = field(default_factory=dict)


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
    ideal_generality_mean: float = float("nan")  # teacher protocol: the ideal observer's
    ideal_specificity_mean: float = float("nan")

    @property
    def balanced_mean(self) -> float:
        """The mean of the two exams' mean scores (the balanced curve)."""
        return 0.5 * (self.generality_mean + self.specificity_mean)


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
    # The headline of every protocol: the balanced curve area (the mean of the generality and
    # specificity areas) as % of the one-shot oracle's (whose specificity is full marks) and of
    # the ideal observer's (teacher protocol; nan elsewhere). `balanced`.
    balanced_pct_oracle: float = float("nan")
    balanced_pct_ideal: float = float("nan")
    specificity_pct: float = float("nan")  # the specificity area, % of full marks
    ideal_balanced_pct_oracle: float = float("nan")  # the ideal observer's own balanced area, % of the oracle's
    ideal_near_miss_final: dict[str, float] = field(default_factory=dict)
    exam_items: tuple[int, int] = (EXAM_ITEMS, EXAM_ITEMS)
    senses: str = ""  # the agent's sense of direction (`AgentParams.senses_of_direction`)
    # Per group of exam items (teacher protocol: per family of words), the same figures.
    by_family: dict[str, dict[str, float]] = field(default_factory=dict)
    agent: str = "asp"  # the learner that ran (`--agent`): asp, soar, or a baseline
    seed: int = 0


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
    senses: str = ""
    agent: str = "asp"


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
        ideal = all(x.ideal_generality >= 0 for x in recs)
        ig = _mean_std([x.ideal_generality for x in recs])[0] if ideal else float("nan")
        isp = _mean_std([x.ideal_specificity for x in recs])[0] if ideal else float("nan")
        out.append(LessonSummary(i + 1, len(recs), cm, cs, gm, gs, sm, ss, om, os_, xm, xs, ig, isp))
    return out


@dataclass(frozen=True)
class Areas:
    """Curve areas as fractions of full marks (sums over lessons and trials of what was right,
    over the items asked): ours, the one-shot oracle's generality, the ideal observer's."""

    generality: float
    specificity: float
    oracle: float
    ideal_generality: float = float("nan")
    ideal_specificity: float = float("nan")

    @property
    def balanced(self) -> float:
        """The balanced area: the mean of the generality and specificity areas."""
        return 0.5 * (self.generality + self.specificity)

    def pct_oracle(self) -> float:
        """The balanced area as % of the one-shot oracle's (its specificity is full marks)."""
        top = 0.5 * (self.oracle + 1.0)
        return 100.0 * self.balanced / top if top > 0 else float("nan")

    def pct_ideal(self) -> float:
        top = 0.5 * (self.ideal_generality + self.ideal_specificity)
        return 100.0 * self.balanced / top if top > 0 else float("nan")

    def ideal_pct_oracle(self) -> float:
        top = 0.5 * (self.oracle + 1.0)
        return 100.0 * 0.5 * (self.ideal_generality + self.ideal_specificity) / top if top > 0 else float("nan")


def areas(records: Sequence, gen_items: int, spec_items: int) -> Areas:
    """`Areas` of per-lesson records (`LessonRecord`s with `gen_items` and `spec_items` items
    each, or `GroupRecord`s, which say their own)."""
    g = s = o = ig = isp = 0.0
    ng = ns = 0
    ideal = bool(records)
    for r in records:
        g += r.generality
        s += r.specificity
        o += r.oracle
        ng += getattr(r, "generality_items", gen_items)
        ns += getattr(r, "specificity_items", spec_items)
        ideal = ideal and r.ideal_generality >= 0
        ig += r.ideal_generality
        isp += r.ideal_specificity
    nan = float("nan")
    return Areas(g / ng if ng else nan, s / ns if ns else nan, o / ng if ng else nan,
                 ig / ng if ideal and ng else nan, isp / ns if ideal and ns else nan)


#: How far (points) a balanced headline may exceed its generality area before a printed table
#: says that it is high from specificity alone (`all_no_pct_oracle`).
SPECIFICITY_ALONE = 30.0


def all_no_pct_oracle(oracle_area: float, lessons: int, gen_items: int) -> float:
    """What a learner that says no to everything scores on the balanced headline, as % of the
    oracle: generality 0, specificity full marks, so 100 / (1 + o), `o` the oracle's generality
    area as a fraction of full marks. Between 50 % (an oracle at full marks from the first
    lesson) and 100 % (one that knows nothing yet): on a short run the headline is high from
    specificity alone, which the table says (`commands.format_table`)."""
    top = lessons * gen_items
    return 100.0 / (1.0 + oracle_area / top) if top > 0 else float("nan")


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
    items = res.trials[0].exam_items if res.trials else (EXAM_ITEMS, EXAM_ITEMS)
    recs = [r for t in res.trials for r in t.records[:len(s)]]
    a = areas(recs, *items)
    return Headline(res.experiment, len(res.trials), len(s), res.perception, holds_from(gen, items[0]),
                    gen[-1] if gen else float("nan"), min((x.specificity_mean for x in s), default=float("nan")),
                    per_trial, area, wall_s, 100.0 * sum(gen) / ceil if ceil > 0 else float("nan"), sum(orc),
                    res.without, res.protocol, _fractions(res.trials, "final_specificity"),
                    _sector_area(res), a.pct_oracle(), a.pct_ideal(), 100.0 * a.specificity, a.ideal_pct_oracle(),
                    _fractions(res.trials, "ideal_final_specificity"), items, res.senses,
                    by_family(res.trials, len(s)), res.agent, res.seed)


def _fractions(trials: Sequence[TrialResult], name: str) -> dict[str, float]:
    """Per kind of specificity item, the fraction right at the last lesson, over the trials."""
    kinds: dict[str, list[int]] = {}
    for t in trials:
        for kind, (right, n) in getattr(t, name).items():
            k = kinds.setdefault(kind, [0, 0])
            k[0] += right
            k[1] += n
    return {k: round(r / n, 3) for k, (r, n) in sorted(kinds.items()) if n}


def by_family(trials: Sequence[TrialResult], lessons: int) -> dict[str, dict[str, float]]:
    """Per group of exam items (teacher protocol: per family of words): the headline figures
    over those items alone. `near_miss_edge_final`: the near misses just outside the teacher's
    edge answered right at the last lesson (ours, and the ideal observer's)."""
    out: dict[str, dict[str, float]] = {}
    names = sorted({g for t in trials for g in t.groups})
    for name in names:
        recs = [r for t in trials for r in t.groups.get(name, [])[:lessons]]
        last = [t.groups[name][lessons - 1] for t in trials if len(t.groups.get(name, [])) >= lessons]
        a = areas(recs, 0, 0)
        edge_n = sum(r.edge_items for r in last)
        out[name] = {
            "generality_items": sum(r.generality_items for r in last),
            "specificity_items": sum(r.specificity_items for r in last),
            "area_pct_of_oracle": 100.0 * a.generality / a.oracle if a.oracle > 0 else float("nan"),
            "specificity_pct": 100.0 * a.specificity,
            "balanced_pct_oracle": a.pct_oracle(),
            "balanced_pct_ideal": a.pct_ideal(),
            "ideal_balanced_pct_oracle": a.ideal_pct_oracle(),
            "near_miss_edge_final": sum(r.edge for r in last) / edge_n if edge_n else float("nan"),
            "ideal_near_miss_edge_final": (sum(r.ideal_edge for r in last) / edge_n
                                           if edge_n and all(r.ideal_edge >= 0 for r in last) else float("nan")),
        }
    return out


def _sector_area(res: ExperimentResult) -> float:
    """Generality area as % of the sector ceiling's (wide protocol; nan otherwise)."""
    recs = [r for t in res.trials for r in t.records]
    top = sum(r.sector_ceiling for r in recs)
    if not recs or any(r.sector_ceiling < 0 for r in recs) or top <= 0:
        return float("nan")
    return 100.0 * sum(r.generality for r in recs) / top


def trial_words_check(res: ExperimentResult) -> list[str]:
    """Every trial's generality against its oracle: the lines where it exceeds it (should be none)."""
    bad = []
    for t in res.trials:
        for r in t.records:
            if r.generality > r.oracle:
                bad.append(f"trial {t.trial + 1} lesson {r.lesson}: generality {r.generality} > oracle {r.oracle}")
    return bad


