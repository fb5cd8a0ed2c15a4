"""The memories and scenes `memory.py` measures on: synthetic visual concepts (a vocabulary
that grows with their number, every concept a different pair of percepts), an agent taught
one spatial trial, made-up words no two of which are a typo of each other, and scenes of n
objects on a grid. Apart from the measuring, so each part of the benchmark reads the same
fixtures.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from aileen.memory.concept import ConceptMemory
from aileen.terms import Term, fn
from aileen.world.geometry import qsr_facts

__all__ = ["obj_facts", "vocabulary", "pair", "add_synthetic", "taught_agent", "new_word", "scene_facts"]


def obj_facts(o: str, percepts: Sequence[str]) -> list[Term]:
    return [fn("isa", o, p) for p in percepts]


def vocabulary(n: int) -> int:
    """Percepts needed for n different pairs."""
    return max(8, math.ceil((1 + math.sqrt(1 + 8 * n)) / 2))


def pair(i: int, v: int) -> tuple[int, int]:
    """The i-th pair (a < b) of a v-percept vocabulary."""
    a = 0
    while i >= v - 1 - a:
        i -= v - 1 - a
        a += 1
    return a, a + 1 + i


def add_synthetic(m: ConceptMemory, n: int, seed: int, prefix: str = "r_syn") -> list[tuple[str, tuple[str, str]]]:
    """n visual concepts, each meaning a different pair of synthetic percepts, each stored
    twice with a random third percept; returns (symbol, meaning)."""
    rng = np.random.default_rng(seed)
    v = vocabulary(n)
    out = []
    for i in range(n):
        a, b = pair(i, v)
        c = f"{prefix}{i}"
        m.create(c, "visual")
        meaning = (f"cv_s{a}", f"cv_s{b}")
        for e in range(2):
            extra = f"cv_s{int(rng.integers(v))}"
            m.store(obj_facts(f"o{e + 1}", [*meaning, extra, c]), c)
        out.append((c, meaning))
    return out


def taught_agent():  # noqa: ANN201
    """An agent taught one spatial trial (ground-truth vision): 9 visual and 4 spatial concepts."""
    from aileen.experiments.learners import make_agent
    from aileen.experiments.protocol import make_trial
    from aileen.experiments.trial import teach

    trial = make_trial("spatial", 0)
    agent, interp = make_agent("truth", 0)
    teach(interp, trial.prerequisites + trial.lessons, 1)
    return agent, interp


def new_word(i: int) -> str:
    """The i-th made-up word; any two differ in two letters, so none is taken for a typo of
    another (`lexicon.near_spelling`)."""
    s = ""
    i += 26 * 26
    while i:
        s = chr(ord("a") + i % 26) + s
        i //= 26
    return "zq" + s + "q" + s


def scene_facts(n: int, seed: int) -> tuple[list[str], list[Term]]:
    from aileen.world.catalog import COLOURS, SHAPES, percept

    rng = np.random.default_rng(seed)
    ids = [f"o{i + 1}" for i in range(n)]
    side = math.ceil(math.sqrt(n))
    boxes = {}
    facts: list[Term] = []
    for k, o in enumerate(ids):
        x, y = (k % side) * 0.1 + rng.uniform(0, 0.02), (k // side) * 0.1 + rng.uniform(0, 0.02)
        boxes[o] = (x, y, x + 0.05, y + 0.05)
        facts.append(fn("isa", o, percept(SHAPES[int(rng.integers(len(SHAPES)))])))
        facts.append(fn("isa", o, percept(COLOURS[int(rng.integers(len(COLOURS)))])))
    facts.extend(qsr_facts(boxes))
    return ids, facts
