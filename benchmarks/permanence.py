"""How often object permanence fixes the hidden-support cases of stacking lessons.

Run: python benchmarks/permanence.py [--scenes N] [--react]

An agent is taught the visual words and "on" (`curriculum`: an inform lesson for each
colour-shape object, then "X on Y" examples whose support shows, sizes varied), once with
object permanence and once `--without object-permanence`. Then, in N scenes (seeds 0..N-1,
the same for both), the trainer lays out two objects apart, sizes drawn at random, and moves
the first onto the second (pick up, place on: `demonstration = "auto"`) while the agent
watches; the agent is asked "X on Y" (a verify, about the table as it is then). With
`--react` the agent puts X on Y itself ("move the X on the Y", after two demonstrations of
"move") before it is asked.

A scene's support is hidden when under `HIDDEN` (10 %) of its drawn pixels show in the last
frame (the renderer's ground truth, `Truth.visible`; never seen by the agent). The benchmark
prints, for hidden and visible supports apart, how many verify answers are right ("yes":
X rests on Y in every scene where the move made the stack, the world's truth), with and
without the mechanism. The agent sees with the shipped detector (ground truth reports
hidden objects too: nothing would be lost from sight).
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_args  # noqa: E402

from aileen.agent.body import WorldBody  # noqa: E402
from aileen.agent.core import Agent  # noqa: E402
from aileen.agent.records import AgentParams  # noqa: E402
from aileen.curriculum import lessonfile, trainer  # noqa: E402
from aileen.curriculum.interpreter import CAMERA_NOISE, Interpreter  # noqa: E402
from aileen.world.catalog import SIZES  # noqa: E402
from aileen.world.render import Frame  # noqa: E402
from aileen.world.stacks import FLAT_TOPS  # noqa: E402

HIDDEN = 0.10  # a support under this share visible is hidden (docs/perception.md, "Stack measures")
COLOURS = ("red", "green", "blue", "yellow", "purple")
UPPER_SHAPES = ("box", "cylinder", "sphere", "cone")  # the shapes the shipped detector knows
LOWER_SHAPES = FLAT_TOPS  # what can carry another


# The "on" examples: sizes varied, so that "on" is learned as resting on, whatever the two
# footprints' overlap (a large object on a medium one covers much of it: RCC8 tppi, not po).
ON_EXAMPLES: tuple[tuple[tuple[str, str], tuple[str, str]], ...] = (
    (("medium", "red box"), ("medium", "blue box")),
    (("small", "green cylinder"), ("large", "red box")),
    (("large", "yellow sphere"), ("medium", "purple cylinder")),
    (("medium", "blue cone"), ("large", "green box")),
    (("large", "purple box"), ("medium", "yellow cylinder")),
    (("medium", "red cylinder"), ("small", "blue cylinder")),
)


def curriculum(react: bool) -> str:
    """The teaching: every colour-shape object once, then "X on Y" with the support in sight
    (`ON_EXAMPLES`, the trainer's "on" layout), and for `react` two demonstrations of
    "move X on Y"."""
    out = []
    for c in COLOURS:
        for s in UPPER_SHAPES:
            out.append(f'[[lesson]]\nsignal = "inform"\ncontent = "{c} {s}"\nobjects = ["{c} {s}"]\n')
    for (sa, a), (sb, b) in ON_EXAMPLES:
        out.append(f'[[lesson]]\nsignal = "inform"\ncontent = "{a} on {b}"\nobjects = ["{sa} {a}", "{sb} {b}"]\n'
                   f'relation = "on"\n')
    if react:  # one with the footprints overlapping in part, one with the upper one larger
        for (sa, a), (sb, b) in (ON_EXAMPLES[0], ON_EXAMPLES[4]):
            out.append(f'[[lesson]]\nsignal = "inform"\ncontent = "move the {a} on the {b}"\n'
                       f'objects = ["{sa} {a}", "{sb} {b}"]\ndemonstration = "auto"\n')
    return "\n".join(out)


def scene_lesson(seed: int, react: bool) -> tuple[str, str]:
    """Scene `seed`'s lesson text and its question: X (any shape) moved onto Y (a flat top),
    colours apart, sizes drawn at random."""
    rng = np.random.default_rng([seed, 22])
    ca, cb = rng.choice(len(COLOURS), size=2, replace=False)
    a = f"{COLOURS[ca]} {UPPER_SHAPES[int(rng.integers(len(UPPER_SHAPES)))]}"
    b = f"{COLOURS[cb]} {LOWER_SHAPES[int(rng.integers(len(LOWER_SHAPES)))]}"
    sa, sb = (tuple(SIZES)[int(rng.integers(len(SIZES)))] for _ in range(2))
    signal, demo = ("react", "") if react else ("inform", 'demonstration = "auto"\n')
    text = (f'[[lesson]]\nsignal = "{signal}"\ncontent = "move the {a} on the {b}"\n'
            f'objects = ["{sa} {a}", "{sb} {b}"]\n{demo}')
    return text, f"{a} on {b}"


@dataclass
class Case:
    seed: int
    stacked: bool  # the world holds X on Y after the move
    support_visible: float  # Y's visible share in the last frame
    right: bool  # the agent answered "yes" to "X on Y"
    done: bool | None = None  # react: the agent said its goal holds (None: the trainer moved X)

    @property
    def hidden(self) -> bool:
        return self.support_visible < HIDDEN


def teach(permanence: bool, react: bool) -> tuple[Agent, Interpreter, list[Frame]]:
    """A taught agent, its interpreter, and the list the last rendered frame lands in."""
    frames: list[Frame] = []

    def keep(frame: Frame) -> None:
        frames[:] = [frame]

    agent = Agent(params=AgentParams(object_permanence=permanence))
    interp = Interpreter(agent, on_frame=keep)
    for _ in interp.run_all(lessonfile.loads(curriculum(react)), seed=0):
        pass
    return agent, interp, frames


def run_scene(agent: Agent, interp: Interpreter, frames: list[Frame], seed: int, react: bool) -> Case:
    """One scene: X moved onto Y (by the trainer, watched, or by the agent), then "X on Y"?"""
    text, question = scene_lesson(seed, react)
    lesson = list(lessonfile.loads(text))[0]
    setup = trainer.layout(lesson, seed=seed)
    body = WorldBody(setup.world, interp.camera, seed=seed, noise=CAMERA_NOISE, on_frame=interp.on_frame)
    agent.new_scene()
    agent.perceive(body.look())
    done = None
    if react:
        done = agent.react(lesson.content, body).result == "success"
    else:
        interp.demonstrate(lesson, setup, body, seed=seed)
    upper, lower = setup.ids
    stacked = setup.world.get(upper).on == lower
    visible = next((t.visible for t in frames[-1].truth if t.id == lower), 0.0)
    answer = agent.verify(question)
    return Case(seed, stacked, visible, answer.result == "success", done)


def measure(permanence: bool, scenes: int, react: bool,
            progress: Callable[[int], None] | None = None) -> list[Case]:
    agent, interp, frames = teach(permanence, react)
    taught = agent.snapshot()
    out = []
    for seed in range(scenes):
        agent.restore(taught)  # each scene asked of the agent as taught (a verify learns nothing, but surely)
        out.append(run_scene(agent, interp, frames, seed, react))
        if progress is not None:
            progress(seed)
    return out


def report(with_: list[Case], without: list[Case]) -> list[str]:
    """The figures: by the support's visibility, how many answers are right with and without
    the mechanism. Scenes are compared where both runs ended alike (X on Y, the support hidden
    or not in both): a react agent without the mechanism may act on where one with it stops."""
    lines = []
    alike = [(a, b) for a, b in zip(with_, without) if a.stacked and b.stacked and a.hidden == b.hidden]
    for name, hidden in (("support hidden (< 10 % visible)", True), ("support in sight", False)):
        pairs = [(a, b) for a, b in alike if a.hidden == hidden]
        lines.append(f"{name}: {len(pairs)} scenes; right with object permanence {sum(a.right for a, _ in pairs)}, "
                     f"without {sum(b.right for _, b in pairs)}; right with it and wrong without "
                     f"{sum(a.right and not b.right for a, b in pairs)}, the other way {sum(b.right and not a.right for a, b in pairs)}")
    for name, cases in (("with", with_), ("without", without)):
        line = f"{name} it: X not on Y after the move in {sum(not c.stacked for c in cases)} scenes"
        if cases and cases[0].done is not None:
            hid = [c for c in cases if c.stacked and c.hidden]
            line += (f"; react said its goal holds in {sum(bool(c.done) for c in cases)} of {len(cases)}, "
                     f"{sum(bool(c.done) for c in hid)} of the {len(hid)} with the support hidden")
        lines.append(line)
    apart = sum(not (a.stacked == b.stacked and (not a.stacked or a.hidden == b.hidden)) for a, b in zip(with_, without))
    lines.append(f"scenes that ended differently in the two runs: {apart}")
    return lines


def main() -> None:
    ap = bench_args.Parser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenes", type=bench_args.count, default=200, help="scenes, seeds 0..N-1 (default 200)")
    ap.add_argument("--react", action="store_true", help="the agent moves X onto Y itself (react), not the trainer")
    args = ap.parse_args()
    runs = {p: measure(p, args.scenes, args.react) for p in (True, False)}
    who = "the agent itself (react)" if args.react else "the trainer, watched"
    print(f"{args.scenes} scenes (seeds 0..{args.scenes - 1}), the shipped detector, X put on Y by {who}")
    for line in report(runs[True], runs[False]):
        print(line)


if __name__ == "__main__":
    main()
