"""Cost of a sweep on Ray against the local process pool, trial for trial.

Run: python benchmarks/sweep.py [--trials 24] [--workers 2] [--lessons 4] [--repeat 2]
                              [--address HOST:PORT]

The same grid (visual trials, the detector, the first `--lessons` lessons of each, two SAGE
points, 4 trials per seed) runs on both backends at two sizes, 8 trials (one seed) and
`--trials` (a multiple of 8), with
`--workers` processes (local) or CPUs (a Ray started for the run, or the cluster at
`--address`). A straight line through the two sizes parts each backend's wall time into a
fixed cost (starting workers or Ray, importing, loading the model) and a cost per trial.
Prints both, the per-trial overhead of Ray over the pool (target <= 10 %), the ratio of the
full sweep's wall times (target <= 1.2x), and whether the two backends wrote the same
sweep.csv (they must). A line that measures nothing (a cost per trial of 0 or less, one run
per size, runs of a size apart by as much as the sizes, or a fixed cost below 0: `fit`) is
said to be not measurable at this size (noise), and not held against the target.
"""

from __future__ import annotations

import sys
import tempfile
from dataclasses import dataclass
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_args  # noqa: E402

from aileen.errors import UserError  # noqa: E402
from aileen.experiments import sweep  # noqa: E402
from aileen.experiments.grid import parse_grid  # noqa: E402

GRID = """experiment = "visual"
trials = {trials}
seeds = {seeds}
perception = "detector"
lessons = {lessons}
[params]
assimilation = [0.01, 0.6]
match = [0.75]
"""


def _grid_text(n: int, lessons: int) -> str:
    """A grid of n trials (a multiple of 8): 2 points x n / 8 seeds x 4 trials per seed."""
    return GRID.format(trials=4, seeds=list(range(n // 8)), lessons=lessons)


def _run(backend: str, n: int, workers: int, lessons: int, address: str | None, root: Path) -> tuple[float, bytes]:
    out = root / f"{backend}-{n}"
    out.mkdir()
    grid = parse_grid(_grid_text(n, lessons))
    assert len(sweep.jobs_of(grid)) == n, (n, len(sweep.jobs_of(grid)))
    t = time.perf_counter()
    rep = sweep.run_sweep(grid, out, backend=backend, jobs=workers, address=address, plot=False)
    wall = time.perf_counter() - t
    assert rep.ran == n and not rep.failures, rep.failures
    return wall, (out / "sweep.csv").read_bytes()


@dataclass(frozen=True)
class Fit:
    """A backend's wall times at two sweep sizes parted into a fixed cost and a cost per trial;
    `why` says why the line is no measurement (None when it is one)."""

    small: float  # best wall time of the small sweep, s
    full: float  # best wall time of the full sweep, s
    per: float  # s per trial: the line's slope
    fixed: float  # s: the line at 0 trials
    why: str | None


def fit(small_walls: list[float], full_walls: list[float], small: int, full: int) -> Fit:
    """The line through the best wall time at each size, and whether it measures anything.

    Why the check: under noise a two-point line printed a negative cost per trial and an
    overhead of -1336.5 % against the 10 % target. A cost per trial of 0 or less is no
    measurement, nor one from a single run per size (its noise unknown), nor one where the
    runs of one size differ by as much as the two sizes do (the rise is noise), nor one whose
    fixed cost is below 0 (the local pool's line read "fixed -0.34 s + 0.579 s per trial" at a
    load average of 5: no sweep starts for less than nothing, so the two points are noise)."""
    w_small, w_full = min(small_walls), min(full_walls)
    per = (w_full - w_small) / (full - small)
    rise = w_full - w_small
    spread = max(max(small_walls) - w_small, max(full_walls) - w_full)
    fixed = w_small - small * per
    why = None
    if per <= 0:
        why = f"the {full}-trial sweep took no longer than the {small}-trial one"
    elif min(len(small_walls), len(full_walls)) < 2:
        why = "one run per size, its noise unknown (--repeat 2 or more)"
    elif spread >= rise:
        why = f"runs of one size differ by {spread:.2f} s, the sizes by {rise:.2f} s"
    elif fixed < 0:
        why = f"the line puts the fixed cost at {fixed:.2f} s, below 0"
    return Fit(w_small, w_full, per, fixed, why)


def main() -> None:
    ap = bench_args.Parser(description=__doc__.splitlines()[0])
    ap.add_argument("--trials", type=int, default=24, help="trials of the full sweep (a multiple of 8, at least 16)")
    ap.add_argument("--workers", type=bench_args.count, default=2)
    ap.add_argument("--lessons", type=bench_args.count, default=4, help="training lessons per trial")
    ap.add_argument("--address", default=None, help="a running Ray cluster (default: Ray started for the run)")
    ap.add_argument("--repeat", type=bench_args.count, default=2,
                    help="runs of each sweep; the best counts (default 2)")
    args = ap.parse_args()
    if args.trials % 8 or args.trials < 16:
        ap.error("--trials must be a multiple of 8, at least 16")
    try:  # Ray installed, --address an address that answers: before the local sweeps, not after
        from aileen.experiments import ray_backend

        ray_backend.preflight(args.address)
    except UserError as exc:
        ap.exit(2, f"{ap.prog}: {exc.format()}\n")
    print(bench_args.host_line())
    small = 8
    walls: dict[tuple[str, int], list[float]] = {}
    csvs = {}
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        for r in range(args.repeat):  # alternating, so that a busy spell on the machine hits both
            for backend in ("local", "ray"):
                for n in (small, args.trials):
                    where = root / f"{r}"
                    where.mkdir(exist_ok=True)
                    wall, csvs[backend, n] = _run(backend, n, args.workers, args.lessons,
                                                  args.address if backend == "ray" else None, where)
                    walls.setdefault((backend, n), []).append(wall)
    fits = {}
    for backend in ("local", "ray"):
        fits[backend] = fit(walls[backend, small], walls[backend, args.trials], small, args.trials)
        f = fits[backend]
        cost = (f"fixed {f.fixed:.2f} s + {f.per:.3f} s per trial" if f.why is None
                else f"not measurable at this size (noise): {f.why}")
        print(f"{backend:5s}: {small} trials {f.small:.2f} s, {args.trials} trials {f.full:.2f} s "
              f"(best of {args.repeat} repeat{'s' if args.repeat != 1 else ''}); {cost} ({args.workers} workers)")
        print("       every run: " + ", ".join(f"{n} trials " + " / ".join(f"{w:.2f}" for w in walls[backend, n]) + " s"
                                      for n in (small, args.trials)))
    lw, rw = fits["local"].full, fits["ray"].full
    if fits["local"].why is None and fits["ray"].why is None:
        overhead = fits["ray"].per / fits["local"].per - 1.0
        print(f"Ray per-trial overhead over the pool: {overhead * 100:+.1f} % (target <= 10 %)")
    else:
        print(f"Ray per-trial overhead over the pool: not measurable at this size (noise), from {args.repeat} "
              f"repeat{'s' if args.repeat != 1 else ''}: more --trials or --repeat")
    print(f"{args.trials}-trial sweep: Ray {rw:.2f} s / local {lw:.2f} s = {rw / lw:.2f}x, best of {args.repeat} "
          f"(target <= 1.2x)")
    same = all(csvs["ray", n] == csvs["local", n] for n in (small, args.trials))
    print(f"sweep.csv identical on both backends: {same}")


if __name__ == "__main__":
    main()
