"""Time SME on a scene of N objects against a 2-object generalization; print the growth exponent.

The scene has every ordered pair's QSR facts (one cardinal direction and one RCC8 relation,
computed from random positions) plus two percepts per object, as the perception module
produces them. The generalization is what SAGE keeps for a spatial concept such as `r_left_of`.
Run: `python benchmarks/sme.py [--seed S] [--repeat R]`.
"""

from __future__ import annotations

import math
import random
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_args  # noqa: E402

from aileen.analogy import sme  # noqa: E402
from aileen.terms import Term, fn  # noqa: E402

SHAPES = ["cv_box", "cv_cone", "cv_sphere", "cv_cylinder"]
COLOURS = ["cv_red", "cv_green", "cv_blue", "cv_yellow", "cv_purple"]
CARDINAL = ["s", "sw", "w", "nw", "n", "ne", "e", "se"]


def scene(n: int, rng: random.Random) -> list[Term]:
    """Random object positions -> percepts, cardinal direction and (dc | ec) for every ordered pair."""
    pos = [(rng.random(), rng.random()) for _ in range(n)]
    names = [f"o{i + 1}" for i in range(n)]
    facts: list[Term] = []
    for name in names:
        facts.append(fn("isa", name, rng.choice(SHAPES)))
        facts.append(fn("isa", name, rng.choice(COLOURS)))
    for i, a in enumerate(names):
        for j, b in enumerate(names):
            if i == j:
                continue
            dx, dy = pos[j][0] - pos[i][0], pos[j][1] - pos[i][1]
            ang = math.degrees(math.atan2(dx, dy)) + 22.5
            if ang < 0:
                ang += 360
            facts.append(fn(CARDINAL[int(ang // 45) % 8], a, b))
            facts.append(fn("dc" if math.hypot(dx, dy) > 0.12 else "ec", a, b))
    return facts


GENERALIZATION = [
    fn("isa", fn("gen_ent", 0, "r_left_of"), "cv_red"),
    fn("isa", fn("gen_ent", 0, "r_left_of"), "cv_box"),
    fn("isa", fn("gen_ent", 1, "r_left_of"), "cv_blue"),
    fn("isa", fn("gen_ent", 1, "r_left_of"), "cv_cone"),
    fn("w", fn("gen_ent", 0, "r_left_of"), fn("gen_ent", 1, "r_left_of")),
    fn("e", fn("gen_ent", 1, "r_left_of"), fn("gen_ent", 0, "r_left_of")),
    fn("dc", fn("gen_ent", 0, "r_left_of"), fn("gen_ent", 1, "r_left_of")),
    fn("dc", fn("gen_ent", 1, "r_left_of"), fn("gen_ent", 0, "r_left_of")),
    fn("r_left_of", fn("gen_ent", 0, "r_left_of"), fn("gen_ent", 1, "r_left_of")),
]


def time_match(facts: list[Term], repeat: int) -> float:
    """Best-of-`repeat` seconds for one match including the first inferences (fresh scene each time)."""
    best = math.inf
    for _ in range(repeat):
        sme._prepare.cache_clear()  # the scene is new every time in real use
        t0 = time.perf_counter()
        ms = sme.match(GENERALIZATION, facts)
        if ms:
            ms[0].inferences
        best = min(best, time.perf_counter() - t0)
    return best


def main() -> None:
    ap = bench_args.Parser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--repeat", type=bench_args.count, default=5)
    args = ap.parse_args()
    rng = random.Random(args.seed)
    pts = []
    pts_n = []
    print(f"{'N':>4} {'facts':>6} {'ms':>9}")
    for n in (2, 5, 10, 20, 40):
        facts = scene(n, rng)
        t = time_match(facts, args.repeat)
        if n >= 5:
            pts.append((math.log(len(facts)), math.log(t)))
            pts_n.append((math.log(n), math.log(t)))
        print(f"{n:>4} {len(facts):>6} {t * 1e3:>9.3f}")
    print(f"growth exponent in facts (N=5..40, least squares on log-log): {slope(pts):.2f}")
    print(f"growth exponent in objects N: {slope(pts_n):.2f}")


def slope(pts: list[tuple[float, float]]) -> float:
    """Least-squares slope of y on x."""
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)


if __name__ == "__main__":
    main()
