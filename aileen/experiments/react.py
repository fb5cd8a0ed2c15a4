"""The react benchmark: after training, carry out random `move X <relation> Y` tasks.

Training is one action trial's curriculum (`protocol.make_trial("action", seed)`): the visual
and spatial prerequisites, then the 20 action lessons, all taught by inform lessons. In the
wide protocol "move" is demonstrated only with "left of" and "right of", and the tasks ask for
"behind" and "in front of" (composition: one verb for every relation the agent knows). Then N
tasks, each a fresh scene with the two named objects (the mover starting in another relation
to the reference) and 0-3 distractors, given with the `react` signal. Success is the trainer's
judgement in the world (`grading.goal_holds`: the mover ends in the relation, both on the
table), not the agent's own opinion.

Each task gets a fresh agent that shares the trained concept and semantic memories (and an
empty episodic memory, its own region-sampling seed), so a task's result depends on (seed,
task index) only and the tasks can run in any number of processes. Reacting must not change
what was learned; that is checked.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from aileen.curriculum.lesson import ActionSpec, Lesson, ObjectSpec, Source
from aileen.domain import relations
from aileen.errors import UserError
from aileen.experiments.protocol import MAX_DISTRACTORS, RELATIONS, make_trial, phrase
from aileen.world.catalog import COLOURS, PAPER_SHAPES, drawing
from aileen.world.stacks import FLAT_TOPS

SHAPES = PAPER_SHAPES

DEFAULT_TASKS = 50
# The wide protocol's react benchmark is about composition: "move" is demonstrated with these
# relations only, and the tasks ask for the other directional words (known as spatial words).
DEMONSTRATED = ("left of", "right of")
# `--relations`: the tasks ask for these words instead (issue 22: acting on distance and contact
# words must reach goals that still hold after the world settles). Each word is first taught
# as a spatial word, with this many inform lessons; "move" is demonstrated as above.
DISTANCE_AND_CONTACT = ("near", "next to", "far from", "on")
RELATION_EXAMPLES = 3


@dataclass(frozen=True)
class TaskRecord:
    task: int  # 1-based
    content: str
    distractors: int
    success: bool  # the trainer sees the goal reached
    agent_result: str  # what the agent said: success / failure
    reason: str | None
    projections: int
    steps: int  # primitive actions executed
    seconds: float  # the whole task: layout, perceive, project, plan, act, perceive


@dataclass
class ReactResult:
    seed: int
    perception: str
    tasks: list[TaskRecord]
    training_commands: int = 0
    training_s: float = 0.0
    wall_s: float = 0.0
    summary: dict = field(default_factory=dict)
    protocol: str = "paper"
    relations: tuple[str, ...] = ()  # the goal words asked for (`--relations`); () the protocol's
    without: tuple[str, ...] = ()  # the agent's mechanisms switched off (`--without`)
    senses: str | None = None  # its sense of direction (`--senses`; None: the agent's own)


def parse_relations(text: str) -> tuple[str, ...]:
    """`near,next-to,far from,on` -> the relation words (each said by the trainer, and one
    `move X <word> Y` can bring about); a `UserError` naming the word otherwise."""
    out = []
    for part in text.split(","):
        name = relations.find(part) if part.strip() else None
        if name is None or name not in relations.placeable():
            words = ", ".join(w for w in relations.words() if w in relations.placeable())
            raise UserError(f"--relations: {part.strip()!r} is not a word 'move X <word> Y' can bring about; "
                            f"expected a comma-separated list of: {words}")
        word = relations.get(name).word
        if word not in out:
            out.append(word)
    return tuple(out)


def _carrier(rng: np.random.Generator, pairs: list[tuple[str, str]], not_like: tuple[str, str]) -> tuple[str, str]:
    """A (colour, shape) with a flat top, other than `not_like`: something can be put on it."""
    flat = [p for p in pairs if p[1] in FLAT_TOPS and p != not_like]
    return flat[int(rng.integers(len(flat)))]


def make_tasks(n: int, seed: int, protocol: str = "paper", words: tuple[str, ...] = ()) -> list[Lesson]:
    """N react lessons: two distinct colour-shape objects, a goal relation, a different start
    relation, 0-3 distractors; a function of (n, seed, protocol, words) alone. The wide
    protocol's goals are the directional words "move" was never demonstrated with, and its
    start layouts are wide. With `words` the goals are those words (the reference of "on" has
    a flat top), and the mover starts in a directional relation, which none of them is."""
    rng = np.random.default_rng([seed, 7])
    pairs = [(c, s) for c in COLOURS for s in SHAPES]
    goals = RELATIONS if protocol == "paper" else tuple(r for r in RELATIONS if r not in DEMONSTRATED)
    # with `words`, each word as often as the others (in a shuffled order): a figure per word
    balanced = [words[k % len(words)] for k in np.random.default_rng([seed, 17]).permutation(n)] if words else []
    out = []
    for k in range(n):
        i, j = rng.choice(len(pairs), size=2, replace=False)
        a, b = ObjectSpec(pairs[i][1], pairs[i][0]), ObjectSpec(pairs[j][1], pairs[j][0])
        goal = goals[rng.integers(len(goals))]
        if words:
            goal = balanced[k]
        if relations.of_word(goal).stacked and b.shape not in FLAT_TOPS:
            colour, shape = _carrier(rng, pairs, pairs[i])
            b = ObjectSpec(shape, colour)
        others = [r for r in RELATIONS if r != goal]
        start = others[rng.integers(len(others))]
        if protocol != "paper":
            start = relations.wide(start)
        d = int(rng.integers(0, MAX_DISTRACTORS + 1))
        out.append(Lesson("react", f"move {phrase(a)} {goal} {phrase(b)}", [a, b], relation=start,
                          distractors=d, action=ActionSpec("move", goal),
                          source=Source(path="<react task>", index=k + 1)))
    return out


def _vision(perception: str):  # noqa: ANN202
    if perception == "truth":
        from aileen.perception.truth import TruthVision

        v = TruthVision()
        return v, v.see_frame
    if perception != "detector":
        raise UserError(f"unknown perception {perception!r}; expected detector or truth")
    from aileen.experiments.vision_cache import vision  # the training's images repeat across processes

    return vision(), None


def relation_lessons(seed: int, words: tuple[str, ...]) -> list[Lesson]:
    """`RELATION_EXAMPLES` inform lessons per word ("red box near blue cone"), laid out by the
    trainer's definition of the word, in a seeded shuffled order."""
    rng = np.random.default_rng([seed, 13])
    pairs = [(c, s) for c in COLOURS for s in SHAPES]
    out = []
    for word in words:
        for _ in range(RELATION_EXAMPLES):
            i, j = rng.choice(len(pairs), size=2, replace=False)
            a, b = ObjectSpec(pairs[i][1], pairs[i][0]), ObjectSpec(pairs[j][1], pairs[j][0])
            if relations.of_word(word).stacked and b.shape not in FLAT_TOPS:
                colour, shape = _carrier(rng, pairs, pairs[i])
                b = ObjectSpec(shape, colour)
            out.append(Lesson("inform", f"{phrase(a)} {word} {phrase(b)}", [a, b], relation=word,
                              source=Source(path="<relation lesson>", index=len(out) + 1), expect="success"))
    return [out[int(k)] for k in rng.permutation(len(out))]


def train(seed: int, perception: str, protocol: str = "paper", words: tuple[str, ...] = (),
          without: tuple[str, ...] = (), senses: str | None = None):  # noqa: ANN201
    """A trained agent's memories: one action trial's prerequisites and lessons, taught (in
    the wide protocol, only the lessons whose relation is in `DEMONSTRATED`); with `words`,
    each of them taught as a spatial word before "move" is shown; `without`, `senses`: the
    agent's mechanisms switched off and its sense of direction, in training and in the tasks.
    Returns (concept memory, semantic memory, create/store commands, seconds)."""
    from aileen.agent import Agent
    from aileen.agent.records import ablated
    from aileen.curriculum.interpreter import Interpreter
    from aileen.experiments.trial import teach

    t0 = time.perf_counter()
    trial = make_trial("action", seed, protocol)
    lessons, prerequisites = trial.lessons, trial.prerequisites
    if protocol != "paper":  # every spatial word known (its spatial trial), "move" seen with two
        lessons = [x for x in lessons if x.action is not None
                   and relations.get(x.action.relation).word in DEMONSTRATED]
        spatial = make_trial("spatial", seed, protocol)
        prerequisites = spatial.prerequisites + spatial.lessons
    prerequisites = prerequisites + relation_lessons(seed, words)
    vision, hook = _vision(perception)
    agent = Agent(params=ablated(without, senses, seed=seed), perceiver=vision)
    interp = Interpreter(agent, on_frame=hook)
    rng = np.random.default_rng([seed, 3])
    base = int(rng.integers(1 << 30))
    with drawing(PAPER_SHAPES):  # as every trial (`trial.run_trial`)
        cmds = teach(interp, prerequisites, base)
        cmds += teach(interp, lessons, base + 10_000)
    return agent.memory, agent.semantic, cmds, time.perf_counter() - t0


def run_task(memory, semantic, lesson: Lesson, task: int, seed: int, perception: str,  # noqa: ANN001
             without: tuple[str, ...] = (), senses: str | None = None) -> TaskRecord:
    """One react task with a fresh agent over the trained memories."""
    from aileen.agent import Agent
    from aileen.agent.records import ablated
    from aileen.curriculum.interpreter import Interpreter

    task_seed = int(np.random.SeedSequence([seed, 11, task]).generate_state(1)[0])
    vision, hook = _vision(perception)
    agent = Agent(memory, semantic, params=ablated(without, senses, seed=task_seed), perceiver=vision)
    interp = Interpreter(agent, on_frame=hook)
    t0 = time.perf_counter()
    with drawing(PAPER_SHAPES):
        r = interp.run(lesson, index=task + 1, seed=task_seed % (1 << 30))
    dt = time.perf_counter() - t0
    a = r.answer
    if a.commands:
        raise RuntimeError(f"react task {lesson.content!r} sent {a.commands} create/store commands")
    return TaskRecord(task + 1, lesson.content, lesson.distractors, bool(r.goal_holds), a.result, a.reason,
                      a.projections, len(a.steps), dt)


def _chunk_job(args: tuple) -> tuple[list[TaskRecord], int, float]:
    """In a worker: train, then run the tasks `indices`; (records, training commands, training seconds)."""
    seed, perception, n, indices, protocol, words, without, senses, queue = args
    from aileen.experiments.trial import memory_digest_of

    memory, semantic, cmds, train_s = train(seed, perception, protocol, words, without, senses)
    before = memory_digest_of(memory, semantic)
    tasks = make_tasks(n, seed, protocol, words)
    out = []
    for i in indices:
        out.append(run_task(memory, semantic, tasks[i], i, seed, perception, without, senses))
        if queue is not None:
            queue.put(1)
    if memory_digest_of(memory, semantic) != before:
        raise RuntimeError("a react task changed the agent's memory")
    return out, cmds, train_s


def run_react(tasks: int = DEFAULT_TASKS, *, seed: int = 0, perception: str = "detector", jobs: int = 1,
              progress: bool = False, protocol: str = "paper", words: tuple[str, ...] = (),
              without: tuple[str, ...] = (), senses: str | None = None) -> ReactResult:
    """Train once in each process that runs tasks, then run the tasks; identical results for
    any `jobs`. `words`: the goal words to ask for (`DISTANCE_AND_CONTACT`, ...); () the
    protocol's own. `without`, `senses`: as `--without` and `--senses` (the agent's)."""
    from aileen.experiments.trial import memory_digest_of

    if tasks < 1:
        raise UserError(f"--trials (react tasks) must be at least 1, got {tasks}")
    if jobs < 1:
        raise UserError(f"--jobs must be at least 1, got {jobs}")
    t0 = time.perf_counter()
    bar = None
    if progress:
        import sys

        from tqdm import tqdm

        bar = tqdm(total=tasks, desc="react", unit="task", file=sys.stderr, dynamic_ncols=True)
    jobs = min(jobs, tasks)
    if jobs == 1:
        memory, semantic, cmds, train_s = train(seed, perception, protocol, words, without, senses)
        before = memory_digest_of(memory, semantic)
        lessons = make_tasks(tasks, seed, protocol, words)
        records = []
        for i, lesson in enumerate(lessons):
            records.append(run_task(memory, semantic, lesson, i, seed, perception, without, senses))
            if bar is not None:
                bar.update(1)
        if memory_digest_of(memory, semantic) != before:
            raise RuntimeError("a react task changed the agent's memory")
    else:
        from aileen.experiments.local_backend import pool_map

        chunks = [list(range(tasks))[k::jobs] for k in range(jobs)]
        # each worker trains the same agent from the same seed (no training here besides)
        parts = pool_map(_chunk_job, [(seed, perception, tasks, c, protocol, words, tuple(without), senses)
                                      for c in chunks], jobs, bar)
        records = sorted((r for p, _, _ in parts for r in p), key=lambda r: r.task)
        if len({c for _, c, _ in parts}) != 1:
            raise RuntimeError("the workers' trainings of one seed disagree")
        cmds, train_s = parts[0][1], parts[0][2]
    if bar is not None:
        bar.close()
    from aileen.experiments.learners import senses_of

    res = ReactResult(seed, perception, records, cmds, train_s, time.perf_counter() - t0, protocol=protocol,
                      relations=words, without=tuple(dict.fromkeys(without)),
                      senses=senses_of(without, senses))  # the sense used, as the curves record it (not the flag)
    res.summary = summarise(res)
    return res


def summarise(res: ReactResult) -> dict:
    """Headline figures: success rate, projections, plan steps and seconds per task."""
    t = res.tasks
    ok = [r for r in t if r.success]
    out = {
        "tasks": len(t),
        "perception": res.perception,
        "protocol": res.protocol,
        "seed": res.seed,
        "without": list(res.without),
        "senses": res.senses,
        "success_rate": round(len(ok) / len(t), 4) if t else None,
        "agent_says_success": sum(r.agent_result == "success" for r in t),
        "projections_mean": round(float(np.mean([r.projections for r in t])), 3) if t else None,
        "steps_mean": round(float(np.mean([r.steps for r in t])), 3) if t else None,
        "task_s_median": round(float(np.median([r.seconds for r in t])), 4) if t else None,
        "training_commands": res.training_commands,
        "training_s": round(res.training_s, 2),
        "wall_s": round(res.wall_s, 2),
        "failures": [f"{r.content} (distractors {r.distractors}): {r.reason or 'goal not reached'}"
                     for r in t if not r.success],
    }
    if res.relations:  # per goal word: tasks and how many reached the goal
        out["relations"] = list(res.relations)
        out["by_relation"] = {w: [sum(r.success for r in t if goal_word(r.content) == w),
                                  sum(goal_word(r.content) == w for r in t)] for w in res.relations}
    return out


def goal_word(content: str) -> str | None:
    """The relation word of a task's sentence ("move red box near blue cone" -> "near")."""
    from aileen.curriculum.sentences import read_content

    return read_content(content).relation


TASKS_HEADER = ("task", "content", "distractors", "success", "agent_result", "projections", "steps", "seconds",
                "reason")


def tasks_csv(res: ReactResult) -> str:
    from aileen.experiments.tables import _csv

    rows = [(r.task, r.content, r.distractors, int(r.success), r.agent_result, r.projections, r.steps,
             round(r.seconds, 4), r.reason or "") for r in res.tasks]
    return _csv(rows, TASKS_HEADER)
