"""The learning-curve protocols and their trials: which experiments each protocol has, a
trial's lessons and exams (`make_trial`), and the one-shot oracle.

Each protocol is its own module: `paper` (the paper's protocol, kept exactly as published),
`wide` (layouts over the whole region a person accepts, near-miss exams, the repertoire) and
`teacher` (a teacher drawn per trial, whose words' regions vary). This module picks among them;
the names of the paper's pieces are handed on from here too.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

import numpy as np

from aileen.curriculum.lesson import Lesson
from aileen.experiments import teacher, wide
from aileen.experiments.paper import (  # noqa: F401  (the paper's pieces, handed on)
    EXAM_ITEMS,
    MAX_DISTRACTORS,
    RELATIONS,
    action_exams,
    action_lessons,
    colour_shape_pairs,
    move_sentence,
    phrase,
    spatial_exams,
    spatial_lessons,
    two_objects,
    visual_exams,
    visual_lessons,
)
from aileen.experiments.teacher import Teacher

EXPERIMENTS: tuple[str, ...] = ("visual", "spatial", "action", "repertoire")
# The learners an experiment can run: ours, the paper's learner in Soar, the baselines.
AGENT_KINDS: tuple[str, ...] = ("asp", "soar", "paper", "nearest", "cobweb", "trestle")
# The experiments of each protocol: the repertoire (sizes, distance, contact, comparatives) is
# the wide protocol's alone.
PROTOCOL_EXPERIMENTS: dict[str, tuple[str, ...]] = {"paper": EXPERIMENTS[:3], "wide": EXPERIMENTS,
                                                     "teacher": ("spatial",)}
# "wide" (experiments/wide.py): layouts over the whole region a person accepts, near-miss
# specificity exams; "paper": the paper's protocol, kept exactly as it was; "teacher"
# (experiments/teacher.py): a teacher drawn per trial, whose words' regions vary.
PROTOCOLS: tuple[str, ...] = ("wide", "paper", "teacher")
TRAINING_LESSONS = {"visual": 24, "spatial": 20, "action": 20}
# The most trials one experiment or one grid point runs: a trial takes about a second, so this
# is more than a day of work; past it is a slip (a grid's `trials = 99999999999999999999999`
# built its list of trials until the memory ran out, and never started one).
MAX_TRIALS = 100_000


def not_in_protocol(experiment: str, protocol: str) -> str:
    """What to say when `protocol` has no `experiment`: the protocols that have it."""
    owners = [p for p in PROTOCOLS if experiment in PROTOCOL_EXPERIMENTS[p]]
    return (f"the {experiment} experiment exists in the {' and '.join(owners)} protocol{'s' if len(owners) > 1 else ''}"
            f" only, not in the {protocol} protocol")


@dataclass(frozen=True)
class Trial:
    """One trial: what is taught, in order, and the two exams given after every lesson."""

    experiment: str
    seed: int
    lessons: list[Lesson]
    generality: list[Lesson]
    specificity: list[Lesson]
    prerequisites: list[Lesson] = field(default_factory=list)  # taught first, not scored
    # The trial's own trainer relations (the teacher protocol's words as its teacher means
    # them): known to the trainer only while the trial runs (`relations.scope`).
    relations: tuple = ()
    teacher: Teacher | None = None  # the teacher protocol's teacher (experiments/teacher.py)

    def words(self, lesson: Lesson) -> frozenset[str]:
        return lesson_words(lesson)


def lesson_words(lesson: Lesson) -> frozenset[str]:
    """The concept words a lesson's content uses (for the oracle): every channel's value said,
    the relation and the verb, each as one word."""
    from aileen.curriculum.sentences import read_content

    info = read_content(lesson.content)
    words: set[str] = set()
    for p in info.phrases:
        words.update(p.appearance.values())
    if info.relation is not None:
        # An action sentence uses two words, the verb and the relation: a learner that composes
        # them ("move" once, "behind" known) understands "move X behind Y" without ever having
        # seen that pair, so the one-shot oracle counts the verb as one word, not one per relation.
        words.add(info.relation)
        if info.verb:
            words.add(info.verb)
    return frozenset(words)


def training_lessons(experiment: str, protocol: str = "paper") -> int:
    """How many training lessons a trial of `experiment` has (the same for every seed): the
    most `--lessons` and a grid's `lessons` can keep."""
    return len(make_trial(experiment, 0, protocol).lessons)


def too_many_lessons(lessons: int | None, experiments: Iterable[str], protocols: Iterable[str]) -> str | None:
    """Why `lessons` asks for more training lessons than one of the experiments has under one
    of the protocols, or None (it ran them all and recorded the number asked for)."""
    if lessons is None:
        return None
    for p in protocols:
        for e in experiments:
            if e in PROTOCOL_EXPERIMENTS[p] and lessons > (n := training_lessons(e, p)):
                return f"{e} ({p} protocol) has {n} training lessons, so it cannot keep the first {lessons}"
    return None


def make_trial(experiment: str, seed: int, protocol: str = "paper") -> Trial:
    """The lessons and exams of one trial; the same (experiment, seed, protocol) gives the
    same trial. The paper's trials are exactly what they were before the wide protocol."""
    if experiment not in EXPERIMENTS:
        raise ValueError(f"unknown experiment {experiment!r}; expected one of {EXPERIMENTS}")
    if protocol not in PROTOCOLS:
        raise ValueError(f"unknown protocol {protocol!r}; expected one of {PROTOCOLS}")
    if experiment not in PROTOCOL_EXPERIMENTS[protocol]:
        raise ValueError(f"{not_in_protocol(experiment, protocol)}; expected one of {PROTOCOL_EXPERIMENTS[protocol]}")
    rng = np.random.default_rng([seed, EXPERIMENTS.index(experiment)])
    if protocol == "wide":
        return _wide_trial(experiment, seed, rng)
    if protocol == "teacher":
        return _teacher_trial(experiment, seed, rng)
    prereq: list[Lesson] = []
    if experiment in ("spatial", "action"):
        prereq += visual_lessons(rng)
    if experiment == "action":
        prereq += spatial_lessons(rng, 8)
    if experiment == "visual":
        lessons = visual_lessons(rng)
        gen, spec = visual_exams(rng)
    elif experiment == "spatial":
        lessons = spatial_lessons(rng)
        gen, spec = spatial_exams(rng)
    else:
        lessons = action_lessons(rng)
        gen, spec = action_exams(rng)
    return Trial(experiment, seed, lessons, gen, spec, prereq)


def _wide_trial(experiment: str, seed: int, rng: np.random.Generator) -> Trial:
    prereq: list[Lesson] = []
    if experiment in ("spatial", "action"):
        prereq += visual_lessons(rng)
    if experiment == "repertoire":
        prereq += wide.sized_visual_lessons(rng)
    if experiment in ("action", "repertoire"):
        prereq += wide.spatial_lessons(rng, 8)
    if experiment == "repertoire":
        prereq += wide.touching_lessons(rng)
        lessons = wide.repertoire_lessons(rng)
        gen, spec = wide.repertoire_exams(rng)
    elif experiment == "visual":
        lessons = visual_lessons(rng)
        gen, spec = wide.visual_exams(rng)
    elif experiment == "spatial":
        lessons = wide.spatial_lessons(rng)
        gen, spec = wide.spatial_exams(rng)
    else:
        lessons = wide.action_lessons(rng)
        gen, spec = wide.action_exams(rng)
    return Trial(experiment, seed, lessons, gen, spec, prereq)


def _teacher_trial(experiment: str, seed: int, rng: np.random.Generator) -> Trial:
    who = teacher.draw_teacher(rng)
    prereq = visual_lessons(rng)
    lessons = teacher.training_lessons(rng, who)
    gen, spec = teacher.exams(rng, who)
    return Trial(experiment, seed, lessons, gen, spec, prereq, relations=who.relations(), teacher=who)


def oracle_curve(trial: Trial) -> list[int]:
    """Per lesson, the generality score of an ideal learner that knows every word it has
    been taught once: the exam items whose words have all been taught so far."""
    taught: set[str] = set()
    for lesson in trial.prerequisites:
        taught |= lesson_words(lesson)
    out = []
    for lesson in trial.lessons:
        taught |= lesson_words(lesson)
        out.append(sum(1 for item in trial.generality if lesson_words(item) <= taught))
    return out
