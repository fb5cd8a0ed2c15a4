"""Per-lesson work against sentence length (issue 12): parsing, and a whole inform lesson.

Run: python benchmarks/sentences.py

Prints the parse time of noun phrases of 2 to 200 words (a word said many times), the time to
refuse over-long input (30,000 words; 50 MB), and the time of one inform lesson whose phrase
repeats a word 1 to 200 times (`--perception truth`). Target: time grows at most linearly
with the words, and refusing costs no more than reading the first 201 words.
"""

from __future__ import annotations

import time

from aileen.agent import Agent
from aileen.curriculum.interpreter import Interpreter
from aileen.curriculum.lesson import Lesson, ObjectSpec, Source
from aileen.errors import UserError
from aileen.memory.concept import ConceptMemory
from aileen.memory.semantic import from_concepts
from aileen.perception.truth import TruthVision
from aileen.reasoning.language import MAX_WORDS, parse


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


if __name__ == "__main__":
    main()
