"""Per-lesson work against sentence length (issue 12), and comprehension of a teacher's
sentences (issue 26).

Run: python benchmarks/sentences.py  (it takes no options but --help)

Prints the parse time of noun phrases of 2 to 200 words (a word said many times), the time to
refuse over-long input (30,000 words; 50 MB), and the time of one inform lesson whose phrase
repeats a word 1 to 200 times (`--perception truth`). Target: time grows at most linearly
with the words, and refusing costs no more than reading the first 201 words.

Then, for an agent taught with lessons/visual.toml and lessons/spatial.toml (ground-truth
vision), the time to read each kind of teacher's sentence (the grammar) and to comprehend it
on a table of four objects (`verify`: reading, grounding in the concept memory, comprehension
in clingo, "the"/numbers/"not"/"and" judged). Target: comprehension under 10 ms a sentence.
"""

from __future__ import annotations

import argparse
import sys
import time

from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_args  # noqa: E402

from aileen.agent import Agent
from aileen.agent.body import WorldBody
from aileen.curriculum.formats import load_curriculum
from aileen.curriculum.interpreter import Interpreter
from aileen.curriculum.lesson import Lesson, ObjectSpec, Source
from aileen.errors import UserError
from aileen.memory.concept import ConceptMemory
from aileen.memory.semantic import from_concepts
from aileen.perception.truth import TruthVision
from aileen.reasoning import language
from aileen.reasoning.language import MAX_WORDS


def parse(sentence: str):  # noqa: ANN201
    """`language.parse` read afresh (it keeps what it read: the benchmark times the reading)."""
    language._parse.cache_clear()
    return language.parse(sentence)
from aileen.world.camera import DEFAULT_CAMERA
from aileen.world.sim import World

TEACHER = [
    "the red box is left of the blue cone",
    "is the red box left of the blue cone?",
    "the red box is not right of the blue cone",
    "the red box and the green sphere are left of the blue cone",
    "the green sphere is right of the red box and left of the blue cone",
    "is there a red box?",
    "are there two cones?",
    "the red one is left of the blue one",
    "Is the yellow cylinder BEHIND the blue cone?",
    "red box left of blue cone",
]


def _best(f, repeat: int = 5) -> float:
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        best = min(best, time.perf_counter() - t0)
    return best


def _refuse(text: str) -> None:
    try:
        parse(text)
    except UserError:
        return
    raise AssertionError("not refused")


def main() -> None:
    # No options, but the command line is read: `--help` says what this measures instead of
    # running the whole benchmark, and anything else is refused on one line.
    bench_args.Parser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    for n in (2, 10, 50, 100, MAX_WORDS):
        s = " ".join(["red"] * (n - 1) + ["box"])
        print(f"parse {n:>4} words: {_best(lambda: parse(s)) * 1e6:8.1f} us")
    long = " ".join(["red"] * 30_000)
    print(f"refuse 30,000 words: {_best(lambda: _refuse(long)) * 1e6:8.1f} us")
    huge = "red " * 12_500_000
    print(f"refuse 50 MB:        {_best(lambda: _refuse(huge), 1) * 1e6:8.1f} us")
    for n in (1, 10, 100, MAX_WORDS - 1):
        content = " ".join(["red"] * n + ["box"])
        vision = TruthVision()
        memory = ConceptMemory()
        agent = Agent(memory, from_concepts(memory), perceiver=vision)
        interp = Interpreter(agent, on_frame=vision.see_frame)
        lesson = Lesson("inform", content, [ObjectSpec("box", "red")], source=Source("<bench>"))
        t0 = time.perf_counter()
        r = interp.run(lesson, index=1, seed=1)
        dt = time.perf_counter() - t0
        print(f"inform lesson, 'red' x {n:>3}: {dt * 1e3:7.1f} ms  (stored {', '.join(r.answer.stored)})")
    teacher()


def teacher() -> None:
    """Reading and comprehending a teacher's sentences, per kind (issue 26)."""
    vision = TruthVision()
    agent = Agent(perceiver=vision)
    interp = Interpreter(agent, on_frame=vision.see_frame)
    for name in ("visual.toml", "spatial.toml"):
        cur = load_curriculum(Path(__file__).resolve().parent.parent / "lessons" / name)
        for i, lesson in enumerate(cur.lessons):
            interp.run(lesson, index=i + 1, seed=cur.lesson_seed(i))
    world = World(DEFAULT_CAMERA.table, seed=0)
    for shape, colour, x, y in (("box", "red", 0.15, 0.5), ("sphere", "green", 0.4, 0.5), ("cone", "blue", 0.7, 0.5),
                                ("cylinder", "yellow", 0.7, 0.82)):
        world.add(shape, colour, x, y)
    world.settle()
    agent.new_scene()
    agent.perceive(WorldBody(world, DEFAULT_CAMERA, seed=1, noise=0.0, on_frame=vision.see_frame).look())
    worst = 0.0
    for sentence in TEACHER:
        read = _best(lambda: parse(sentence), 20)
        answer = agent.verify(sentence)
        dt = _best(lambda: agent.verify(sentence), 30)
        worst = max(worst, dt)
        print(f"read {read * 1e3:5.2f} ms  comprehend {dt * 1e3:5.2f} ms  {answer.result:<8} {sentence!r}")
    print(f"slowest comprehension: {worst * 1e3:.2f} ms (target: under 10 ms)")


if __name__ == "__main__":
    main()
