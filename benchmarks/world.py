"""Speed of the world: camera renders per second and settle times, on one thread.

Run: python benchmarks/world.py [--repeat N]

Targets (issue 2): >= 500 renders/s at 256x256 with 4 objects, and settle <= 20 ms for 4
objects, on one core. Figures are medians over repeats, so a busy machine shows less noise.
"""

from __future__ import annotations

import os
import statistics
import sys
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import cv2  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_args  # noqa: E402

from aileen.world.render import render  # noqa: E402
from aileen.world.scenes import random_scene  # noqa: E402
from aileen.world.sim import World  # noqa: E402


def renders_per_second(n_objects: int, *, seed: int | None, noise: float, n: int) -> float:
    world = random_scene(n_objects, seed=3)
    render(world, seed=seed, noise=noise)  # warm the texture cache
    t = time.perf_counter()
    for k in range(n):
        render(world, seed=None if seed is None else seed + k, noise=noise)
    return n / (time.perf_counter() - t)


def settle_ms(world: World, act: str) -> tuple[float, int, int]:
    """Time one settle after `act`: 'free' (a generated scene), 'overlap' (a placement into
    another), 'stack' (a placement on top of another) or 'push' (`push_away`, hand and slide)."""
    objs = world.objects()
    if act == "push":
        o = min(objs, key=lambda o: o.y)  # the southernmost has room to go north
        t = time.perf_counter()
        r = world.push_away(o.id)
        return (time.perf_counter() - t) * 1e3, r.steps, len(r.moved)
    if act == "stack":
        flat = [o for o in objs if o.shape in ("box", "cylinder")]
        a = flat[0] if flat else world.get(world.add("box", "red", 0.5, 0.5))
        b = next(o for o in objs if o.id != a.id)
        world.pick_up(b.id)
        t = time.perf_counter()
        r = world.place(b.id, a.x + 0.02, a.y, onto=a.id)
        return (time.perf_counter() - t) * 1e3, r.steps, len(r.moved)
    if act == "overlap":
        a, b = objs[0], objs[1]
        world.pick_up(b.id)
        t = time.perf_counter()
        r = world.place(b.id, a.x + 0.02, a.y + 0.01)  # place() settles
    else:
        t = time.perf_counter()
        r = world.settle()
    return (time.perf_counter() - t) * 1e3, r.steps, len(r.moved)


def main() -> None:
    ap = bench_args.Parser(description=__doc__)
    ap.add_argument("--repeat", type=bench_args.count, default=20, help="settle repeats per case (default 20)")
    # at least one render in each of the four timed runs of a case
    ap.add_argument("--renders", type=bench_args.at_least(4), default=2000,
                    help="renders per render case (default 2000)")
    args = ap.parse_args()
    cv2.setNumThreads(1)

    print("renders per second (256x256, one thread)")
    for n_obj, seed, noise, label in (
        (4, None, 0.0, "4 objects, neutral light"),
        (4, 0, 0.0, "4 objects, seeded lighting"),
        (4, 0, 4.0, "4 objects, seeded lighting + noise 4"),
        (20, 0, 0.0, "20 objects, seeded lighting"),
    ):
        rates = [renders_per_second(n_obj, seed=seed, noise=noise, n=args.renders // 4) for _ in range(4)]
        print(f"  {label:<40} {statistics.median(rates):8.0f} /s")

    print("settle (median over repeats; steps; objects moved)")
    for n_obj in (4, 20):
        for act in ("free", "overlap", "stack", "push"):
            runs = [settle_ms(random_scene(n_obj, seed=100 + r), act) for r in range(args.repeat)]
            ms = statistics.median(r[0] for r in runs)
            worst = max(r[0] for r in runs)
            steps = statistics.median(r[1] for r in runs)
            moved = statistics.median(r[2] for r in runs)
            print(
                f"  {n_obj:2d} objects, {act:<8} {ms:7.2f} ms (max {worst:6.2f})  "
                f"steps {steps:5.0f}  moved {moved:3.0f}"
            )


if __name__ == "__main__":
    main()
