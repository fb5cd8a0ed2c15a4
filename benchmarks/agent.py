"""Speed of one full lesson cycle: lay out, render, perceive, comprehend, query concept
memory, answer.

Run: python benchmarks/agent.py [--repeat N] [--perception detector|truth]

The agent is first taught one spatial trial's curriculum (the 24 visual lessons, then the 20
spatial ones), so its memory holds the 9 visual and 4 spatial concepts. Then verify lessons
with 1 to 4 objects on the table are timed: 1 object = a visual sentence ("red box"), 2-4 =
a spatial sentence over two objects plus 0-2 distractors. Target (issue 7): median <= 50 ms
per cycle. Also prints the time of a react task (project, plan, act, perceive, until done),
and of generate lessons (the agent says what it sees) once 1000 more visual concepts are in
memory (target: median <= 50 ms; "which concepts fit?" goes through MAC/FAC retrieval).
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from aileen.curriculum.lesson import Lesson, ObjectSpec  # noqa: E402
from aileen.experiments import react  # noqa: E402
from aileen.experiments.learners import make_agent  # noqa: E402
from aileen.experiments.protocol import RELATIONS, make_trial, phrase  # noqa: E402
from aileen.experiments.trial import teach  # noqa: E402
from aileen.world.catalog import COLOURS, SHAPES  # noqa: E402


def lessons_with(n_objects: int, count: int, seed: int) -> list[Lesson]:
    rng = np.random.default_rng([seed, n_objects])
    pairs = [(c, s) for c in COLOURS for s in SHAPES]
    out = []
    for _ in range(count):
        i, j = rng.choice(len(pairs), size=2, replace=False)
        a, b = ObjectSpec(pairs[i][1], pairs[i][0]), ObjectSpec(pairs[j][1], pairs[j][0])
        if n_objects == 1:
            out.append(Lesson("verify", phrase(a), [a]))
        else:
            rel = RELATIONS[rng.integers(len(RELATIONS))]
            out.append(Lesson("verify", f"{phrase(a)} {rel} {phrase(b)}", [a, b], relation=rel,
                              distractors=n_objects - 2))
    return out


def timed(interp, lessons: list[Lesson], seed: int) -> str:
    """Run the lessons; `median ms | p90 ms | right/all`."""
    times, ok = [], 0
    for k, lesson in enumerate(lessons):
        t = time.perf_counter()
        r = interp.run(lesson, index=k + 1, seed=seed + k)
        times.append((time.perf_counter() - t) * 1000)
        ok += bool(r.correct)
    times.sort()
    return f"{statistics.median(times):.1f} | {times[int(0.9 * (len(times) - 1))]:.1f} | {ok}/{len(times)}"


def grow(agent, n: int, seed: int) -> None:
    """n more visual words, each learned from one example: half over real percepts (a colour,
    a shape and a size, so they compete with the taught words), half over a percept the camera
    never reports (as words for things not on this table)."""
    from aileen.domain.channels import CHANNELS
    from aileen.terms import fn

    rng = np.random.default_rng(seed)
    for i in range(n):
        word = f"w{i}"
        concept = agent.semantic.add(word, "visual")
        agent.memory.create(concept, "visual")
        if i % 2:
            facts = [fn("isa", "o1", c.percepts[int(rng.integers(len(c.percepts)))]) for c in CHANNELS]
        else:
            facts = [fn("isa", "o1", f"cv_unseen{i}"), fn("isa", "o1", "cv_medium")]
        agent.memory.store(facts + [fn("isa", "o1", concept)], concept)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=40, help="lessons timed per object count (default 40)")
    ap.add_argument("--perception", choices=("detector", "truth"), default="detector")
    args = ap.parse_args()

    trial = make_trial("spatial", 0)
    agent, interp = make_agent(args.perception, 0)
    t0 = time.perf_counter()
    teach(interp, trial.prerequisites + trial.lessons, 1)
    teach_s = time.perf_counter() - t0
    kinds = {}
    for c in agent.memory.concepts():
        kinds[c.kind] = kinds.get(c.kind, 0) + 1
    print(f"perception={args.perception}; taught {len(trial.prerequisites) + len(trial.lessons)} lessons in "
          f"{teach_s:.2f} s; memory: {kinds}")
    print("objects | median ms | p90 ms | correct")
    for n in (1, 2, 3, 4):
        print(f"{n} | {timed(interp, lessons_with(n, args.repeat, 7), 1000)}")
    grow(agent, 1000, seed=3)
    print(f"generate, {len(agent.memory)} concepts in memory | median ms | p90 ms | said something true")
    for n in (1, 2):
        said = [Lesson("generate", "", x.objects, relation=x.relation) for x in lessons_with(n, args.repeat, 11)]
        print(f"{n} object{'s' if n > 1 else ''} | {timed(interp, said, 2000)}")
    res = react.run_react(10, seed=0, perception=args.perception)
    print(f"react task (after training on an action trial): median {res.summary['task_s_median'] * 1000:.0f} ms, "
          f"{res.summary['projections_mean']} projections, {res.summary['steps_mean']} steps, "
          f"success {res.summary['success_rate'] * 100:.0f} %")


if __name__ == "__main__":
    main()
