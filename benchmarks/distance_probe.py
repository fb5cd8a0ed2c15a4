"""A person's answers to new distance words: random teachers, a few examples on every side, a `wrong` or two.

Run: python benchmarks/distance_probe.py [--files 24] [--seed 0] [--perception truth|detector]
     [--senses all|cones|sectors] [--without MECHANISM] [--margin 0.04] [--keep DIR]

Why (issue 20, "the same applies to distance"): a word's distance can be finer or coarser than
the agent's coarse distance sense (close, far, nothing marked in between). Each lesson file
(written here, run with `aileen run lessons/visual.toml FILE --json` in a child process, as a
user would run it) teaches two new words, each its own teacher's: a range of distances between
the centres of two medium round objects (a sphere and a cylinder, so that the gap the agent
sees is the same on every side) from one of three families,

* `close`: from 0.135 m (about two widths of a turned box: clear of touching) up to 0.16-0.20 m;
* `band`: a stretch 0.05-0.10 m long starting 0.18-0.24 m apart (a hand's breadth);
* `far`: from 0.30-0.36 m apart on (as far as the table allows);

3-5 examples laid within it, on sides spread round the circle (the teacher means distance, not
side); 0-2 verify lessons just outside it (0.015-0.035 m past an edge) that the trainer marks
`wrong`; then 4 items in the middle half of the range (a person says yes) and 4 at least
`--margin` metres outside it (a person says no), on random sides. It prints how many the agent
answered right, by family and by yes or no, and every miss. `--without distance-bands` is the
agent with every grain of direction and the coarse grain of distance alone, as before this
mechanism: its ablation (`--senses cones` perceives no bands either, nor the finer directions).
"""

from __future__ import annotations

import math
import random
from pathlib import Path

import bench_args
from probe_files import run_file, run_probe

from aileen.world.catalog import COLOURS, PAPER_SHAPES, SIZES

ROUND = tuple(s for s in PAPER_SHAPES if s in ("sphere", "cylinder"))
WORDS = ("blick of", "dax of", "toma of", "fep of", "wug of", "zorp of")  # new words, none declared
LO, HI = 0.135, 0.44  # centre distances the table holds on every family's sides (metres)
APART = 0.002  # the least gap between the two objects' footprint boxes (metres): apart to the agent's QSRs


def _region(rng: random.Random, family: str) -> tuple[float, float]:
    """The teacher's range of centre distances for a word of `family`."""
    if family == "close":
        return LO, rng.uniform(0.16, 0.20)
    if family == "band":
        lo = rng.uniform(0.18, 0.24)
        return lo, lo + rng.uniform(0.05, 0.10)
    return rng.uniform(0.30, 0.36), HI


FAMILIES = ("close", "band", "far")


def _pair(rng: random.Random) -> tuple[tuple[str, str], tuple[str, str]]:
    """Two objects that differ in colour and in shape (each phrase names one object), both
    round: the gap between them is then the centres' distance less the same sum whatever the
    side and turn, so the teacher's distances are the gaps the agent sees."""
    s1, s2 = rng.sample(ROUND, 2)
    c1, c2 = rng.sample(COLOURS, 2)
    return (c1, s1), (c2, s2)


def _lesson(rng: random.Random, signal: str, word: str, distance: float, degrees: float, *,
            expect: str | None = None, wrong: bool = False, note: str = "") -> str:
    """A lesson whose first object's centre lies `distance` metres from the second's, at
    `degrees` counter-clockwise from east (the second placed so that both fit on the table)."""
    (c1, s1), (c2, s2) = _pair(rng)
    dx, dy = distance * math.cos(math.radians(degrees)), distance * math.sin(math.radians(degrees))
    while max(abs(dx), abs(dy)) < SIZES["medium"] + APART:
        # the agent's QSRs read the boxes around the footprints (QSRlib's): a pair 0.135 m
        # apart on a diagonal has boxes that meet and reads as touching to it, not as a
        # distance (docs/perception.md, known limits), so such a side is drawn again (the
        # trainer refused such a file until stop 44: "after settling, obj1 and obj2 overlap")
        degrees = rng.uniform(0, 360)
        dx, dy = distance * math.cos(math.radians(degrees)), distance * math.sin(math.radians(degrees))
    lo, hi = 0.08, 0.92
    cx = rng.uniform(max(lo, lo - dx), min(hi, hi - dx))
    cy = rng.uniform(max(lo, lo - dy), min(hi, hi - dy))
    out = (f'[[lesson]]\nsignal = "{signal}"\ncontent = "{c1} {s1} {word} {c2} {s2}"\n'
           f'objects = [{{ shape = "{s1}", colour = "{c1}", size = "medium", position = [{cx + dx:.3f}, {cy + dy:.3f}] }}, '
           f'{{ shape = "{s2}", colour = "{c2}", size = "medium", position = [{cx:.3f}, {cy:.3f}] }}]\n')
    if expect:
        out += f'expect = "{expect}"\n'
    if wrong:
        out += 'feedback = "wrong"\n'
    return out + f'note = "{note}"\n\n'


def lesson_file(seed: int, index: int, margin: float) -> tuple[str, list[dict | None]]:
    """A probe file's text, and per lesson what it asks (None for teaching lessons)."""
    rng = random.Random(f"distance {seed}/{index}")
    text = f'title = "distance probe {seed}/{index}"\nseed = {seed}\n\n'
    asks: list[dict | None] = []
    for word in rng.sample(WORDS, 2):
        family = rng.choice(FAMILIES)
        lo, hi = _region(rng, family)
        teacher = f"{word}: {lo:.3f}-{hi:.3f} m ({family})"
        n = rng.randint(3, 5)
        start = rng.uniform(0, 360)
        for k in range(n):
            d = rng.uniform(lo + 0.005, hi - 0.005)
            text += _lesson(rng, "inform", word, d, start + k * 360 / n + rng.uniform(-30, 30),
                            note=f"{teacher}, shown at {d:.3f}")
            asks.append(None)
        edges = [e for e in ((lo, -1), (hi, 1)) if LO < e[0] < HI]  # an edge the table lets one step past
        for _ in range(rng.randint(0, 2) if edges else 0):
            edge, side = rng.choice(edges)
            d = edge + side * rng.uniform(0.015, 0.035)
            text += _lesson(rng, "verify", word, d, rng.uniform(0, 360), expect="failure", wrong=True,
                            note=f"{teacher}, wrong at {d:.3f}")
            asks.append(None)
        quarter = (hi - lo) / 4
        outside = [(LO, lo - margin), (hi + margin, HI)]
        outside = [(a, b) for a, b in outside if b - a > 0.005]
        for yes in (True, False):
            for _ in range(4 if yes or outside else 0):
                if yes:
                    d = rng.uniform(lo + quarter, hi - quarter)
                else:
                    a, b = rng.choice(outside)
                    d = rng.uniform(a, b)
                text += _lesson(rng, "verify", word, d, rng.uniform(0, 360), expect="success" if yes else "failure",
                                note=f"{teacher}, asked at {d:.3f}")
                asks.append({"teacher": teacher, "family": family, "distance": d, "yes": yes})
    return text, asks


def main() -> None:
    ap = bench_args.Parser(description=__doc__.splitlines()[0])
    ap.add_argument("--files", type=int, default=24)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--perception", choices=("truth", "detector"), default="truth")
    ap.add_argument("--senses", choices=("all", "cones", "sectors"), default="all")
    ap.add_argument("--without", action="append", default=[], metavar="MECHANISM",
                    help="switch a mechanism off (repeatable), e.g. distance-bands")
    ap.add_argument("--margin", type=float, default=0.04, help="items outside lie at least this far (m) past an edge")
    ap.add_argument("--keep", type=Path, default=None, help="keep the lesson files in this folder")
    args = ap.parse_args()
    if args.files < 1 or args.margin < 0.0:
        ap.error("expected --files >= 1 and --margin >= 0")
    extra = ["--senses", args.senses, *[a for w in args.without for a in ("--without", w)]]
    t = run_probe(args.files, lambda i: lesson_file(args.seed, i, args.margin), lambda i: f"distance-{args.seed}-{i}.toml",
                  lambda path: run_file(path, args.seed, args.perception, extra),
                  lambda ask: (ask["family"], ask["yes"]),
                  lambda ask: f"{ask['teacher']}, asked at {ask['distance']:.3f}", args.keep)
    right, total, misses = t.right, t.total, t.misses
    off = "".join(f", without {w}" for w in args.without)
    print(f"distance probe, seed {args.seed}, {args.files} files, perception {args.perception}, senses {args.senses}{off}, "
          f"outside >= {args.margin:g} m past an edge")
    for family in FAMILIES:
        cells = [f"{'inside' if yes else 'outside'} {right[(family, yes)]} of {total[(family, yes)]}" for yes in (True, False)]
        print(f"  {family}: " + ", ".join(cells))
    for yes in (True, False):
        print(f"{'inside' if yes else 'outside'}: {sum(right[(f, yes)] for f in FAMILIES)} of "
              f"{sum(total[(f, yes)] for f in FAMILIES)}")
    print(f"right: {sum(right.values())} of {sum(total.values())}")
    for m in misses:
        print("  miss: " + m)


if __name__ == "__main__":
    main()
