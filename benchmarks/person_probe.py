"""A person's answers to new direction words: random teachers, a few examples, a `wrong` or two.

Run: python benchmarks/person_probe.py [--files 24] [--seed 0] [--perception truth|detector]
     [--inside 0.5] [--outside 15] [--keep DIR]

Why (issue 20): the teacher protocol grades every item, also those a person could answer
either way (just inside a teacher's edge, just outside it); this asks only what a person
would answer one way. Each lesson file (written here, run with `aileen run
lessons/visual.toml FILE --json` in a child process, as a user would run it) teaches two new
words, each its own teacher's: an axis that is a multiple of 45 degrees and a half-angle h
from one of the teacher protocol's families (narrow 4-10, diagonal 10-20, wide 20-50
degrees); 3-5 examples laid uniformly within h - 1 of the axis; 0-2 verify lessons just
past the edge (h + 2 to h + 9) that the trainer marks `wrong`. Then 4 items well inside (at
most `--inside` times h off the axis: a person says yes) and 4 well outside (at least h +
`--outside` off: a person says no). The items inside are counted apart by whether they lie
between the examples shown (a person says yes) or beyond them on one side (the teacher says
yes; a person who does not know the teacher's axis might not). It prints how many of those
the agent answered right, by family and side, and every miss with its teacher. Nothing of
the words is told to the agent but the lessons. The lesson files are kept with `--keep DIR`.
"""

from __future__ import annotations

import math
import random
from pathlib import Path

import bench_args
from probe_files import run_file, run_probe

from aileen.experiments.teacher import FAMILIES as TEACHER_FAMILIES
from aileen.world.catalog import COLOURS, PAPER_SHAPES

WORDS = ("blick of", "dax of", "toma of", "fep of", "wug of", "zorp of")  # new words, none declared
# family -> the range of its half-angle (degrees), as the teacher protocol draws them
FAMILIES = {name: family.half_angle for name, family in TEACHER_FAMILIES.items()}
# Where an item lies: inside the teacher's region and between the examples shown (a person
# says yes), inside it but beyond every example on one side (the teacher says yes; a person
# not told the axis might not), or well outside (everyone says no).
SIDES = ("between", "beyond", "outside")


def _pair(rng: random.Random) -> tuple[tuple[str, str], tuple[str, str]]:
    """Two objects that differ in colour and in shape (each phrase names one object)."""
    a = (rng.choice(COLOURS), rng.choice(PAPER_SHAPES))
    while True:
        b = (rng.choice(COLOURS), rng.choice(PAPER_SHAPES))
        if b[0] != a[0] and b[1] != a[1]:
            return a, b


def _lesson(rng: random.Random, signal: str, word: str, degrees: float, *, expect: str | None = None,
            wrong: bool = False, note: str = "") -> str:
    """A lesson whose first object lies `degrees` (counter-clockwise from east) from the second."""
    (c1, s1), (c2, s2) = _pair(rng)
    r = rng.uniform(0.17, 0.3)
    cx, cy = rng.uniform(0.4, 0.6), rng.uniform(0.4, 0.6)
    x, y = cx + r * math.cos(math.radians(degrees)), cy + r * math.sin(math.radians(degrees))
    out = (f'[[lesson]]\nsignal = "{signal}"\ncontent = "{c1} {s1} {word} {c2} {s2}"\n'
           f'objects = [{{ shape = "{s1}", colour = "{c1}", position = [{x:.3f}, {y:.3f}] }}, '
           f'{{ shape = "{s2}", colour = "{c2}", position = [{cx:.3f}, {cy:.3f}] }}]\n')
    if expect:
        out += f'expect = "{expect}"\n'
    if wrong:
        out += 'feedback = "wrong"\n'
    return out + f'note = "{note}"\n\n'


def lesson_file(seed: int, index: int, inside: float, outside: float) -> tuple[str, list[dict | None]]:
    """A probe file's text, and per lesson what it asks (None for teaching lessons)."""
    rng = random.Random(f"{seed}/{index}")
    text = f'title = "person probe {seed}/{index}"\nseed = {seed}\n\n'
    asks: list[dict | None] = []
    for word in rng.sample(WORDS, 2):
        axis = rng.choice(range(0, 360, 45))
        family = rng.choice(sorted(FAMILIES))
        h = rng.uniform(*FAMILIES[family])
        teacher = f"{word}: axis {axis}, half-angle {h:.0f} ({family})"
        shown = []
        for _ in range(rng.randint(3, 5)):
            off = rng.uniform(-h + 1, h - 1)
            shown.append(off)
            text += _lesson(rng, "inform", word, axis + off, note=f"{teacher}, shown {off:+.0f}")
            asks.append(None)
        for _ in range(rng.randint(0, 2)):
            off = rng.choice((-1, 1)) * (h + rng.uniform(2, 9))
            text += _lesson(rng, "verify", word, axis + off, expect="failure", wrong=True,
                            note=f"{teacher}, wrong at {off:+.0f}")
            asks.append(None)
        for yes in (True, False):
            for _ in range(4):
                off = (rng.uniform(-inside * h, inside * h) if yes
                       else rng.choice((-1, 1)) * rng.uniform(h + outside, 180.0))
                text += _lesson(rng, "verify", word, axis + off, expect="success" if yes else "failure",
                                note=f"{teacher}, asked {off:+.0f}")
                # a yes between the examples shown is a person's; one beyond them, the teacher's
                side = ("between" if min(shown) <= off <= max(shown) else "beyond") if yes else "outside"
                asks.append({"teacher": teacher, "family": family, "off": off, "side": side})
    return text, asks


def main() -> None:
    ap = bench_args.Parser(description=__doc__.splitlines()[0])
    ap.add_argument("--files", type=int, default=24)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--perception", choices=("truth", "detector"), default="truth")
    ap.add_argument("--inside", type=float, default=0.5, help="items inside lie at most this share of h off the axis")
    ap.add_argument("--outside", type=float, default=15.0, help="items outside lie at least h + this many degrees off")
    ap.add_argument("--keep", type=Path, default=None, help="keep the lesson files in this folder")
    args = ap.parse_args()
    if args.files < 1 or not 0.0 < args.inside <= 1.0 or args.outside < 0.0:
        ap.error("expected --files >= 1, 0 < --inside <= 1 and --outside >= 0")
    t = run_probe(args.files, lambda i: lesson_file(args.seed, i, args.inside, args.outside),
                  lambda i: f"probe-{args.seed}-{i}.toml", lambda path: run_file(path, args.seed, args.perception),
                  lambda ask: (ask["family"], ask["side"]), lambda ask: f"{ask['teacher']}, asked {ask['off']:+.0f}",
                  args.keep)
    right, total, misses = t.right, t.total, t.misses
    print(f"person probe, seed {args.seed}, {args.files} files, perception {args.perception}, inside <= "
          f"{args.inside:g} h, outside >= h + {args.outside:g} degrees")
    for family in sorted(FAMILIES):
        cells = [f"{side} {right[(family, side)]} of {total[(family, side)]}" for side in SIDES]
        print(f"  {family}: " + ", ".join(cells))
    for side in SIDES:
        print(f"{side}: {sum(right[(f, side)] for f in FAMILIES)} of {sum(total[(f, side)] for f in FAMILIES)}")
    print(f"right: {sum(right.values())} of {sum(total.values())}")
    for m in misses:
        print("  miss: " + m)


if __name__ == "__main__":
    main()
