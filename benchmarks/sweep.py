"""Cost of a sweep on Ray against the local process pool, trial for trial.

Run: python benchmarks/sweep.py [--trials 24] [--workers 2] [--lessons 4] [--address HOST:PORT]

The same grid (visual trials, the detector, the first `--lessons` lessons of each, two SAGE
points, 4 trials per seed) runs on both backends at two sizes, 8 trials (one seed) and
`--trials` (a multiple of 8), with
`--workers` processes (local) or CPUs (a Ray started for the run, or the cluster at
`--address`). A straight line through the two sizes parts each backend's wall time into a
fixed cost (starting workers or Ray, importing, loading the model) and a cost per trial.
Prints both, the per-trial overhead of Ray over the pool (target <= 10 %), the ratio of the
full sweep's wall times (target <= 1.2x), and whether the two backends wrote the same
sweep.csv (they must).
"""

from __future__ import annotations

import sys
import tempfile
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
        w_small, w_full = min(walls[backend, small]), min(walls[backend, args.trials])
        per = (w_full - w_small) / (args.trials - small)
        fits[backend] = (w_small, w_full, per, w_small - small * per)
        print(f"{backend:5s}: {small} trials {w_small:.2f} s, {args.trials} trials {w_full:.2f} s (best of {args.repeat}); "
              f"fixed {fits[backend][3]:.2f} s + {per:.3f} s per trial ({args.workers} workers)")
        print("       every run: " + ", ".join(f"{n} trials " + " / ".join(f"{w:.2f}" for w in walls[backend, n]) + " s"
                                      for n in (small, args.trials)))
    lw, rw = fits["local"][1], fits["ray"][1]
    overhead = fits["ray"][2] / fits["local"][2] - 1.0
    print(f"Ray per-trial overhead over the pool: {overhead * 100:+.1f} % (target <= 10 %)")
    print(f"{args.trials}-trial sweep: Ray {rw:.2f} s / local {lw:.2f} s = {rw / lw:.2f}x (target <= 1.2x)")
    same = all(csvs["ray", n] == csvs["local", n] for n in (small, args.trials))
    print(f"sweep.csv identical on both backends: {same}")


if __name__ == "__main__":
    main()
