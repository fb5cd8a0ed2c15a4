"""Speed of the ASP reasoning: comprehension and planning in a 10-object scene.

Prints median wall time per call, grounding included (a fresh clingo Control each call,
rule files loaded by path, facts added, ground, solve; `solve_once`'s memory of answers is
emptied before each call, and the time of a question asked again is printed beside), against
the targets:
comprehend a two-reference sentence <= 20 ms, plan a 2-step move <= 50 ms.

    python benchmarks/asp.py [--objects 10] [--repeat 200] [--seed 0]
"""

from __future__ import annotations

import math
import random
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_args  # noqa: E402

from aileen.reasoning import asp  # noqa: E402
from aileen.reasoning.comprehension import RULE_FILES as COMP_FILES  # noqa: E402
from aileen.reasoning.comprehension import comprehend, working_memory  # noqa: E402
from aileen.reasoning.language import parse  # noqa: E402
from aileen.reasoning.planner import plan  # noqa: E402
from aileen.terms import Term, fn  # noqa: E402

SHAPES = ["cv_box", "cv_cone", "cv_sphere", "cv_cylinder"]
COLOURS = ["cv_red", "cv_green", "cv_blue", "cv_yellow", "cv_purple"]
DIRS = ["s", "sw", "w", "nw", "n", "ne", "e", "se"]
# The goals move o1 against o2 and o3 against o4; every object has its own (colour, shape).
MIN_OBJECTS, MAX_OBJECTS = 4, len(COLOURS) * len(SHAPES)


def pointed_object(n: int) -> str:
    """The object the hard goal points at: o5, beside the two pairs the goal moves, or the
    last object of a smaller scene (a goal may name only objects of the state)."""
    return f"o{min(n, 5)}"


def scene(n: int, rng: random.Random) -> tuple[list[Term], list[Term], dict[str, str], list[tuple[str, str]]]:
    """n objects with distinct (colour, shape), random positions, all pairwise CDC + RCC8 facts,
    inferred visual concept facts, and the semantic memory for their words."""
    combos = [(c, s) for c in COLOURS for s in SHAPES]
    rng.shuffle(combos)
    pos = [(rng.random(), rng.random()) for _ in range(n)]
    facts: list[Term] = []
    inferred: list[Term] = []
    for i in range(n):
        o = f"o{i + 1}"
        c, s = combos[i]
        facts += [fn("isa", o, c), fn("isa", o, s)]
        inferred += [fn("isa", o, "r_" + c[3:]), fn("isa", o, "r_" + s[3:])]
        for j in range(n):
            if i == j:
                continue
            dx, dy = pos[j][0] - pos[i][0], pos[j][1] - pos[i][1]
            ang = math.degrees(math.atan2(dx, dy)) + 22.5
            ang += 360 if ang < 0 else 0
            d = DIRS[int(ang // 45) % 8]
            p = f"o{j + 1}"
            facts += [fn(d, o, p), fn("dc", o, p)]
            if d in ("w", "nw", "sw"):
                inferred.append(fn("r_left_of", o, p))
    words = {c[3:]: "r_" + c[3:] for c in COLOURS} | {s[3:]: "r_" + s[3:] for s in SHAPES}
    words |= {"left_of": "r_left_of", "move_right_of": "r_move_right_of"}
    return facts, inferred, words, combos


def median_ms(fn_, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn_()
        times.append(time.perf_counter() - t)
    return statistics.median(times) * 1000


def main() -> None:
    ap = bench_args.Parser(description=__doc__.splitlines()[0])
    ap.add_argument("--objects", type=int, default=10)
    ap.add_argument("--repeat", type=bench_args.count, default=200)
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args()
    if not MIN_OBJECTS <= args.objects <= MAX_OBJECTS:
        ap.error(f"expected {MIN_OBJECTS} <= --objects <= {MAX_OBJECTS} (the goals move o1 against o2 and o3 "
                 f"against o4; each object has its own colour and shape), not {args.objects}")
    rng = random.Random(args.seed)
    facts, inferred, words, combos = scene(args.objects, rng)
    (c1, s1), (c2, s2) = combos[0], combos[1]
    sentence = f"the {c1[3:]} {s1[3:]} left of the {c2[3:]} {s2[3:]}"
    parsed = parse(sentence)

    def run_comprehend() -> None:
        asp.forget_answers()  # clingo's work every time, not `solve_once`'s memory of the answer
        comprehend(parse(sentence), words=words, facts=facts, inferred=inferred)

    run_comprehend()  # warm caches (imports, symbol tables)
    comp = median_ms(run_comprehend, args.repeat)
    comprehend(parse(sentence), words=words, facts=facts, inferred=inferred)
    again = median_ms(lambda: comprehend(parse(sentence), words=words, facts=facts, inferred=inferred), args.repeat)
    wm = working_memory(parsed, words={w: c for w, c in words.items() if w in parsed.words}, facts=facts, inferred=inferred)
    files = asp.rule_paths(COMP_FILES)
    load = median_ms(lambda: asp.new_control(files), args.repeat)
    parse_ms = median_ms(lambda: parse(sentence), args.repeat)

    def opposite(a: str, b: str) -> str:
        """The direction a is NOT in relative to b now (its opposite), so the goal needs a move."""
        now = next(f.name for f in facts if f.args == (Term(a), Term(b)) and f.name in DIRS)
        return DIRS[(DIRS.index(now) + 4) % 8]

    goal = [fn(opposite("o1", "o2"), "o1", "o2"), fn("dc", "o1", "o2")]
    result = plan(facts, goal)
    planned = median_ms(lambda: plan(facts, goal), args.repeat)
    hard_goal = [fn(opposite("o1", "o2"), "o1", "o2"), fn(opposite("o3", "o4"), "o3", "o4"),
                 fn("pointed", pointed_object(args.objects))]
    hard = plan(facts, hard_goal)
    planned5 = median_ms(lambda: plan(facts, hard_goal), max(10, args.repeat // 4))

    print(f"scene: {args.objects} objects, {len(facts)} facts, {len(inferred)} inferred; working memory {len(wm)} facts")
    print(f"comprehend {sentence!r}: median {comp:.2f} ms (target <= 20 ms)"
          f"  [of which parse {parse_ms:.3f} ms, Control + load rules {load:.2f} ms]")
    print(f"  the same question again (the answer remembered by solve_once): median {again:.2f} ms")
    print(f"plan {', '.join(map(str, goal))} -> {', '.join(map(str, result.actions))}: median {planned:.2f} ms (target <= 50 ms)")
    print(f"plan {', '.join(map(str, hard_goal))} -> {hard.depth} steps: median {planned5:.2f} ms")


if __name__ == "__main__":
    main()
