"""`aileen experiment sweep GRID.toml`: the learning curve's area over a grid of SAGE thresholds,
mechanisms, protocols and seeds, each trial an independent task for a backend.

Why: SAGE's thresholds decide what the concept memory merges and accepts, and the original's
authors moved them around without a published sweep; a sweep is hundreds of independent
trials, which a process pool or a Ray cluster runs equally well. A trial is fully decided by
its job (point, seed, trial index): the trial's lessons and exams come from
`trial.trial_seed(seed, trial)`, the same at every point (so points are compared on the same
lessons: the differences are the thresholds', not the dice's), and nothing depends on which
worker ran it or when. The result files are therefore identical for any backend and any
number of workers.

Files under DIR:
- `sweep.csv`: one row per (point, seed, trial). Rows are appended as trials finish (a sweep
  that is stopped and started again skips the rows already there) and the file is rewritten
  in grid order when the sweep ends.
- `sweep-summary.csv`: per point, the curve area as % of the one-shot oracle, the balanced
  area (generality and specificity, the headline), commands per trial and the lowest mean
  specificity (the file's columns and versions: `sweep_csv.py`).
- `heatmap.png` (or `heatmap-<fixed axis values>.png`, e.g. `heatmap-visual.png`, one per value of the other swept axes): the
  balanced area (the headline, `balanced_pct_oracle`) over the grid's two heat-map axes.
"""

from __future__ import annotations

import math
import shutil
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from aileen.errors import UserError
from aileen.experiments.grid import Grid, Point, load_grid
from aileen.experiments.sweep_csv import (  # noqa: F401 - the file's columns, re-exported
    AXES,
    HEADER,
    HEADER_BEFORE_BALANCED,
    HEADER_BEFORE_PROTOCOL,
    KEY,
    SUMMARY_HEADER,
    Appender,
    balanced,
    csv_text,
    first_line,
    fmt,
    read_rows,
    row_key,
)
from aileen.experiments.output import LOCK_NAME, locked, out_folder

@dataclass(frozen=True)
class Job:
    """One trial of a sweep: everything that decides its result, and nothing else."""

    point: Point
    seed: int
    trial: int  # 0-based within (point, seed)
    perception: str
    lessons: int | None

    def label(self) -> str:
        return f"point ({self.point.label()}) seed {self.seed} trial {self.trial + 1}"


def jobs_of(grid: Grid) -> list[Job]:
    """Every trial of the grid, in grid order (point, seed, trial)."""
    return [Job(p, s, t, grid.perception, grid.lessons)
            for p in grid.points() for s in grid.seeds for t in range(grid.trials)]


def run_job(job: Job) -> dict:
    """Run one trial and return its sweep.csv row (strings). Pure in its job: any process, any
    order, the same row."""
    from aileen.experiments.trial import run_trial

    p = job.point
    res = run_trial(p.experiment, job.trial, job.seed, perception=job.perception, lessons=job.lessons,
                    without=p.without, sage=p.sage(), protocol=p.protocol)
    recs = res.records
    gen = [r.generality for r in recs]
    spec = [r.specificity for r in recs]
    orc = sum(r.oracle for r in recs)
    ng, ns = res.exam_items
    row = {**_key_values(job),
           "balanced_pct_oracle": fmt(balanced(sum(gen), sum(spec), orc, ng * len(recs), ns * len(recs))),
           "exam_items": f"{ng} {ns}",
           "area_pct_oracle": fmt(100.0 * sum(gen) / orc) if orc > 0 else "nan",
           "commands": str(sum(r.commands for r in recs)),
           "min_specificity": str(min(spec)),
           "final_generality": str(gen[-1]),
           "generality_sum": str(sum(gen)),
           "oracle_sum": str(orc),
           "generality": " ".join(map(str, gen)),
           "specificity": " ".join(map(str, spec))}
    return row


def _key_values(job: Job) -> dict[str, str]:
    p = job.point
    return {"experiment": p.experiment, "protocol": p.protocol, "without": "+".join(p.without) or "-",
            "assimilation": repr(p.assimilation), "probability": repr(p.probability), "match": repr(p.match),
            "perception": job.perception, "lessons": "all" if job.lessons is None else str(job.lessons),
            "seed": str(job.seed), "trial": str(job.trial + 1)}


# --------------------------------------------------------------------------- summaries

@dataclass(frozen=True)
class PointSummary:
    """One point's figures across its trials (all seeds)."""

    point: Point
    trials: int
    area_pct_oracle: float  # sum of generality / sum of oracle over all trials and lessons, in %
    commands_per_trial: float
    lowest_specificity: float  # lowest, over lessons, of the mean specificity across trials
    final_generality: float
    balanced_pct_oracle: float = float("nan")  # the headline: both areas, % of the oracle's, pooled


def summarise(points: Sequence[Point], rows: Sequence[dict]) -> list[PointSummary]:
    """Per point (in grid order) with at least one finished trial, its `PointSummary`."""
    by: dict[tuple, list[dict]] = {}
    for r in rows:
        by.setdefault(_point_key_of_row(r), []).append(r)
    out = []
    for p in points:
        rs = by.get(_point_key(p), [])
        if not rs:
            continue
        g = sum(int(r["generality_sum"]) for r in rs)
        o = sum(int(r["oracle_sum"]) for r in rs)
        specs = [[int(x) for x in r["specificity"].split()] for r in rs]
        n = min(len(s) for s in specs)
        spec_mean = np.mean([s[:n] for s in specs], axis=0)
        items = [[int(x) for x in r["exam_items"].split()] for r in rs]
        bal = balanced(g, sum(map(sum, specs)), o, sum(i[0] * len(s) for i, s in zip(items, specs)),
                        sum(i[1] * len(s) for i, s in zip(items, specs)))
        out.append(PointSummary(p, len(rs), 100.0 * g / o if o else float("nan"),
                                float(np.mean([int(r["commands"]) for r in rs])), float(spec_mean.min()),
                                float(np.mean([int(r["final_generality"]) for r in rs])), bal))
    return out


def _point_key(p: Point) -> tuple:
    return (p.experiment, p.protocol, "+".join(p.without) or "-", p.assimilation, p.probability, p.match)


def _point_key_of_row(r: dict) -> tuple:
    return (r["experiment"], r["protocol"], r["without"], float(r["assimilation"]), float(r["probability"]),
            float(r["match"]))


def summary_rows(sums: Sequence[PointSummary]) -> list[dict]:
    out = []
    for s in sums:
        k = _point_key(s.point)
        out.append({"experiment": k[0], "protocol": k[1], "without": k[2], "assimilation": repr(k[3]),
                    "probability": repr(k[4]), "match": repr(k[5]), "trials": s.trials, "area_pct_oracle": fmt(s.area_pct_oracle),
                    "commands_per_trial": fmt(s.commands_per_trial),
                    "lowest_specificity": fmt(s.lowest_specificity), "final_generality": fmt(s.final_generality),
                    "balanced_pct_oracle": fmt(s.balanced_pct_oracle)})
    return out


def axis_value(p: Point, axis: str) -> str | float:
    """A point's value on an axis (the heat map's labels)."""
    if axis == "without":
        return "+".join(p.without) or "-"
    return getattr(p, axis)


# --------------------------------------------------------------------------- the sweep

@dataclass
class SweepReport:
    """What a sweep did: trials run now, skipped (already in sweep.csv), failed, and its files."""

    ran: int
    skipped: int
    failures: list[str]
    files: list[Path]
    summary: list[PointSummary]
    wall_s: float
    others: int = 0  # rows in sweep.csv of other grids (another `lessons`, `perception`, points): kept, not summarised


def run_sweep(grid: Grid, out: Path, *, backend: str = "local", jobs: int = 1, address: str | None = None,
              plot: bool = True, progress: bool = False) -> SweepReport:
    """Run every trial of `grid` not already in `out/sweep.csv` on `backend`, then write the
    sorted CSV, the per-point summary and the heat maps."""
    if backend not in ("local", "ray"):
        raise UserError(f"unknown backend {backend!r}; expected local or ray")
    if jobs < 1:
        raise UserError(f"--jobs must be at least 1, got {jobs}")
    if address is not None and backend != "ray":
        raise UserError("--address needs --backend ray")
    if backend == "ray":
        from aileen.experiments import ray_backend

        ray_backend.preflight(address)  # Ray installed, the cluster answers
    if plot:
        from aileen.experiments import plots

        plots.require_matplotlib()  # before an hour of trials, not after
    if grid.perception == "detector":
        from aileen.perception.detector import load_detector

        load_detector()  # a missing or broken model fails here, before any trial runs
    csv_path = out / "sweep.csv"
    existing = read_rows(csv_path)
    if existing and first_line(csv_path) != ",".join(HEADER):
        from aileen.experiments.tables import write_text

        write_text(csv_path, csv_text(existing, HEADER))  # an older sweep.csv: today's columns first
    done = {row_key(r) for r in existing}
    wanted = list(jobs_of(grid))
    todo = [j for j in wanted if row_key(_key_values(j)) not in done]
    t0 = time.perf_counter()
    rows = list(existing)
    failures: list[str] = []
    app = Appender(csv_path, existing=csv_path.exists() and csv_path.stat().st_size > 0)
    bar = None
    if progress and todo:
        from tqdm import tqdm

        bar = tqdm(total=len(todo), desc="sweep", unit="trial", file=sys.stderr, dynamic_ncols=True)

    def on_done(job: Job, row: dict) -> None:
        app.add(row)
        rows.append(row)
        if bar is not None:
            bar.update(1)

    def on_fail(job: Job, why: str) -> None:
        msg = f"{job.label()}: {why}"
        failures.append(msg)
        print(f"aileen: trial failed: {msg}", file=sys.stderr)
        if bar is not None:
            bar.update(1)

    try:
        if todo:
            if backend == "ray":
                from aileen.experiments import ray_backend

                ray_backend.run_jobs(todo, jobs, address, run_job, on_done, on_fail)
            else:
                from aileen.experiments.local_backend import run_local

                run_local(todo, jobs, run_job, on_done, on_fail)
    finally:
        app.close()
        if bar is not None:
            bar.close()
    files = write_results(grid, out, rows, plot=plot)
    # this grid's trials only: another grid's rows in the folder are kept, not summarised
    mine = {row_key(_key_values(j)) for j in wanted}
    ours = [r for r in rows if row_key(r) in mine]
    return SweepReport(len(todo) - len(failures), len(wanted) - len(todo), failures, files,
                       summarise(grid.points(), ours), time.perf_counter() - t0, others=len(rows) - len(ours))


def write_results(grid: Grid, out: Path, rows: Sequence[dict], *, plot: bool) -> list[Path]:
    """sweep.csv in grid order (rows of other grids kept after them), the summary, the heat maps."""
    from aileen.experiments.tables import write_text

    order = {row_key(_key_values(j)): i for i, j in enumerate(jobs_of(grid))}
    mine = sorted((r for r in rows if row_key(r) in order), key=lambda r: order[row_key(r)])
    other = [r for r in rows if row_key(r) not in order]
    write_text(out / "sweep.csv", csv_text(mine + other, HEADER))
    sums = summarise(grid.points(), mine)
    write_text(out / "sweep-summary.csv", csv_text(summary_rows(sums), SUMMARY_HEADER))
    files = [out / "sweep.csv", out / "sweep-summary.csv"]
    axes = grid.heatmap_axes()
    if plot and axes is not None and sums:
        from aileen.experiments import plots

        x, y = axes
        fixed = [a for a in grid.swept() if a not in axes]
        groups: dict[tuple, list[PointSummary]] = {}
        for s in sums:
            groups.setdefault(tuple(axis_value(s.point, a) for a in fixed), []).append(s)
        for key, group in groups.items():
            name = "heatmap" + "".join(f"-{_slug(a, v)}" for a, v in zip(fixed, key)) + ".png"
            title = ", ".join(f"{a} {v}" for a, v in zip(fixed, key)) or ", ".join(grid.experiments)
            # the headline, generality and specificity together (generality alone read 100.0 in
            # every cell where the specificity it cost differed)
            cells = {(axis_value(s.point, x), axis_value(s.point, y)): s.balanced_pct_oracle for s in group}
            trials = max(s.trials for s in group)
            plots.plot_heatmap(cells, x, y, out / name,
                               title=f"balanced curve area, % of oracle: {title} ({trials} trials per cell)")
            files.append(out / name)
    return files


def _slug(axis: str, value: object) -> str:
    """A file-name part for one fixed axis value: `visual`, `without-mutual-exclusivity`, `match-0.75`."""
    if axis in ("experiment", "protocol"):
        return str(value)
    if axis == "without":
        return "all-mechanisms" if value == "-" else f"without-{value}"
    return f"{axis}-{value}"


# --------------------------------------------------------------------------- command

def sweep_command(grid_path: str | None, out: str, *, backend: str, jobs: int, address: str | None,
                  plot: bool, progress: bool) -> int:
    """The CLI's `experiment sweep`: run, print the per-point table; exit 1 when trials failed."""
    if grid_path is None:
        raise UserError("experiment sweep needs a grid file: aileen experiment sweep GRID.toml --out DIR")
    grid = load_grid(grid_path)
    made = not Path(out).exists()
    path = out_folder(out)
    try:
        with locked(path, f"aileen experiment sweep {grid_path}"):
            rep = run_sweep(grid, path, backend=backend, jobs=jobs, address=address, plot=plot, progress=progress)
    except UserError:
        # refused before any trial finished (`--address nonsense`): the folder this command
        # made is taken away again, not left empty
        if made and path.is_dir() and not any(p for p in path.iterdir() if p.name != LOCK_NAME):
            shutil.rmtree(path)
        raise
    except KeyboardInterrupt as exc:  # a stop signal: what finished is in sweep.csv
        from aileen import lifecycle

        if lifecycle.kept(exc) is None:
            lifecycle.set_kept(exc, f"the trials that finished are in {path / 'sweep.csv'}: the same command "
                               "runs the rest")
        raise
    print(format_summary(rep.summary))
    print(f"{rep.ran} trials run, {rep.skipped} already done, {len(rep.failures)} failed; "
          f"{rep.wall_s:.1f} s; wrote " + ", ".join(str(f) for f in rep.files))
    if rep.others:
        print(f"aileen: note: {path / 'sweep.csv'} also holds {rep.others} trials of another grid (other points, "
              "lessons or perception): kept after this grid's, not in its summary; use another --out to keep "
              "them apart", file=sys.stderr)
    if rep.failures:
        print(f"aileen: {len(rep.failures)} trials failed (listed above); run the sweep again to retry them",
              file=sys.stderr)
        return 1
    return 0


def format_summary(sums: Sequence[PointSummary]) -> str:
    head = ("experiment", "protocol", "without", "assim.", "prob.", "match", "trials", "balanced % oracle",
            "area % oracle", "cmds/trial", "lowest spec.")
    lines = [" | ".join(head)]
    for s in sums:
        p = s.point
        lines.append(" | ".join(str(v) for v in (
            p.experiment, p.protocol, "+".join(p.without) or "-", p.assimilation, p.probability, p.match, s.trials,
            "-" if math.isnan(s.balanced_pct_oracle) else f"{s.balanced_pct_oracle:.1f}",
            "-" if math.isnan(s.area_pct_oracle) else f"{s.area_pct_oracle:.1f}",
            f"{s.commands_per_trial:.1f}", f"{s.lowest_specificity:.2f}")))
    from aileen.experiments.results import SPECIFICITY_ALONE

    notes = [f"note: {s.point.experiment} ({'+'.join(s.point.without) or 'all mechanisms'}): balanced "
             f"{s.balanced_pct_oracle:.1f} % is high from specificity alone (generality {s.area_pct_oracle:.1f} % "
             "of the oracle): a learner that says no to everything scores 50 to 100 % here (docs/results.md)"
             for s in sums if s.balanced_pct_oracle - s.area_pct_oracle > SPECIFICITY_ALONE]
    return "\n".join(lines + notes)
