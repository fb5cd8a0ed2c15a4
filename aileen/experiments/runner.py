"""Running the paper's learning-curve experiments (DESIGN.md section 10): all trials of one
experiment, checked first, in `jobs` processes, with a progress bar, into one `ExperimentResult`.

Trials are independent and seeded from (seed, trial index) alone, so they run in parallel
processes (`jobs`) and give the same numbers whatever `jobs` is.

Why the module is this small: it once held every part of a run, and each part that is a job
of its own now lives in its own module; this one only puts them together. One trial (the
learner taught, examined after every lesson, its records) is `trial`'s; the learner it is
given, `learners`'; the cross-situational ceiling, `ceiling`'s (beside the sector ceiling);
the worker processes, `local_backend`'s (the pool the sweep already ran on); the records and
the text of the files, `results`'; an experiment's folder, `output`'s. Every name that moved
is still handed on from here, so `runner.X` keeps working.
"""

from __future__ import annotations

import time
from collections.abc import Sequence

from aileen.agent.records import ABLATIONS, ablation_params  # noqa: F401  (re-exported)
from aileen.errors import UserError
from aileen.experiments.ceiling import cross_situational_curve  # noqa: F401  (re-exported)
from aileen.experiments.learners import (  # noqa: F401  (re-exported)
    PERCEPTIONS,
    SENSING,
    make_agent,
    make_agent_replayable,
    perceived_senses,
    senses_of,
)
from aileen.experiments.local_backend import (  # noqa: F401  (re-exported)
    _SHARED_POOL,
    HASH_ORDER_SENSITIVE,
    fixed_hash_seed,
    pool_map,
    shared_pool,
)
from aileen.experiments.output import write_experiment  # noqa: F401  (re-exported)
from aileen.experiments.protocol import (  # noqa: F401  (re-exported)
    AGENT_KINDS,
    EXPERIMENTS,
    PROTOCOL_EXPERIMENTS,
    PROTOCOLS,
    Trial,
    lesson_words,
    make_trial,
    not_in_protocol,
    oracle_curve,
)
from aileen.experiments.results import (  # noqa: F401  (the records and reports, re-exported)
    EXAM_ITEMS,
    ExperimentResult,
    GroupRecord,
    Headline,
    LessonRecord,
    LessonSummary,
    TrialResult,
    headline,
    holds_from,
    summarise,
    trial_words_check,
)
from aileen.experiments.tables import (  # noqa: F401  (the files' text, re-exported)
    headline_dict,
    summary_csv,
    trials_csv,
    update_summary_json,
    write_bytes,
    write_text,
)
from aileen.experiments.trial import (  # noqa: F401  (re-exported)
    Progress,
    memory_digest_of,
    run_trial,
    teach,
    trial_seed,
)

# The names the parts had here before they moved, for callers that still use them.
_make_agent, _make_agent_replayable = make_agent, make_agent_replayable
_memory_digest_of, _pool_map, _fixed_hash_seed = memory_digest_of, pool_map, fixed_hash_seed

DEFAULT_TRIALS: dict[str, int] = {"visual": 10, "spatial": 10, "action": 5, "repertoire": 10}


def _trial_job(args: tuple) -> TrialResult:
    """In a worker: one trial, its finished lessons put on the queue (None: no progress bar)."""
    experiment, trial, seed, perception, lessons, without, agent_kind, protocol, senses, queue = args
    tick = (lambda n: queue.put(n)) if queue is not None else None
    return run_trial(experiment, trial, seed, perception=perception, lessons=lessons, progress=tick,
                     without=without, agent_kind=agent_kind, protocol=protocol, senses=senses)


def run_experiment(experiment: str, *, trials: int | None = None, seed: int = 0, jobs: int = 1,
                   perception: str = "detector", lessons: int | None = None,
                   progress: bool = False, without: Sequence[str] = (), agent_kind: str = "asp",
                   protocol: str = "paper", senses: str | None = None) -> ExperimentResult:
    """All trials of one experiment, in `jobs` processes; results in trial order, identical
    for any `jobs`. `senses`: the agent's sense of direction (None: the default)."""
    if experiment not in EXPERIMENTS:
        raise UserError(f"unknown experiment {experiment!r}; expected one of {', '.join(EXPERIMENTS)}")
    n = DEFAULT_TRIALS[experiment] if trials is None else trials
    if n < 1:
        raise UserError(f"--trials must be at least 1, got {n}")
    if jobs < 1:
        raise UserError(f"--jobs must be at least 1, got {jobs}")
    if lessons is not None and lessons < 1:
        raise UserError(f"--lessons must be at least 1, got {lessons}")
    if perception not in PERCEPTIONS:
        raise UserError(f"unknown perception {perception!r}; expected one of {', '.join(PERCEPTIONS)}")
    without = tuple(without)
    check_learner(without, senses, agent_kind)
    if protocol not in PROTOCOLS:
        raise UserError(f"unknown protocol {protocol!r}; expected one of {', '.join(PROTOCOLS)}")
    if experiment not in PROTOCOL_EXPERIMENTS[protocol]:
        raise UserError(f"{not_in_protocol(experiment, protocol)}; expected one of "
                        f"{', '.join(PROTOCOL_EXPERIMENTS[protocol])}")
    per_trial = len(make_trial(experiment, 0, protocol).lessons)
    if lessons is not None:
        per_trial = min(per_trial, lessons)
    t0 = time.perf_counter()
    # each learner's bar named (with --baselines three bars all read "visual:")
    bar = _bar(n * per_trial, experiment if agent_kind == "asp" else f"{experiment} ({agent_kind})") \
        if progress else None
    results = _map_trials(experiment, n, seed, jobs, perception, lessons, bar, without, agent_kind, protocol, senses)
    if bar is not None:
        bar.close()
    res = ExperimentResult(experiment, perception, seed, results, without=without, protocol=protocol,
                           senses=perceived_senses(agent_kind, without, senses), agent=agent_kind)
    res.summary = summarise(results)
    res.headline = headline(res, time.perf_counter() - t0)
    return res


def check_learner(without: Sequence[str] = (), senses: str | None = None, agent_kind: str = "asp") -> None:
    """Reject an unknown `--without` or `--senses`, and a learner whose extra is missing, as a
    `UserError` before any work (and, from the command, before its folder is made: a refused
    `--without bogus` left an empty --out folder behind)."""
    make_agent("truth", 0, tuple(without), senses=senses)
    if agent_kind != "asp":
        probe = make_agent("truth", 0, tuple(without), agent_kind)[0]
        if hasattr(probe, "close"):
            probe.close()


def _bar(total: int, what: str):  # noqa: ANN202
    import sys

    from tqdm import tqdm

    return tqdm(total=total, desc=what, unit="lesson", file=sys.stderr, leave=True, dynamic_ncols=True)


def _map_trials(experiment: str, n: int, seed: int, jobs: int, perception: str, lessons: int | None,
                bar, without: tuple[str, ...] = (), agent_kind: str = "asp",
                protocol: str = "paper", senses: str | None = None) -> list[TrialResult]:  # noqa: ANN001
    if (jobs == 1 or n == 1) and agent_kind not in HASH_ORDER_SENSITIVE:
        tick = bar.update if bar is not None else None
        return [run_trial(experiment, t, seed, perception=perception, lessons=lessons, progress=tick,
                          without=without, agent_kind=agent_kind, protocol=protocol, senses=senses)
                for t in range(n)]
    return pool_map(_trial_job, [(experiment, t, seed, perception, lessons, without, agent_kind, protocol, senses)
                                 for t in range(n)], jobs, bar)


__all__ = [
    "DEFAULT_TRIALS", "PERCEPTIONS", "LessonRecord", "TrialResult", "LessonSummary", "Headline",
    "ExperimentResult", "trial_seed", "run_trial", "run_experiment", "check_learner", "summarise", "holds_from", "headline",
    "write_experiment", "update_summary_json", "trials_csv", "summary_csv", "trial_words_check", "teach",
    "lesson_words",
]
