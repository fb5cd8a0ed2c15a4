"""The paper's evaluation protocol: training lessons and the two exams, per trial.

Recovered from the original system's generator and logs (../shared/reference): a visual
trial is the 20 colour-shape objects plus the 4 shape-only lessons, shuffled, as inform
lessons without distractors; after every lesson a generality exam (5 verify lessons whose
scene holds what is said) and a specificity exam (5 verify lessons whose scene does not), both
drawn once per trial, with 0-3 distractors. Exam items are colour-shape objects (the one-shot
oracle computed from this reproduces the published ceiling: 0.21 0.68 1.30 ...). Spatial and
action trials have 20 lessons, 5 for each of the 4 relations, shuffled: the original does not
say how its 20 were drawn, and a balanced draw makes "known by lesson 16" a property of the
learner rather than of the dice.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from typing import TYPE_CHECKING

from aileen.curriculum.lesson import ActionSpec, Lesson, ObjectSpec, Source
from aileen.world.catalog import COLOURS, SHAPES

if TYPE_CHECKING:
    from aileen.experiments.teacher import Teacher

# The paper's four directional words, as published: fixed here, so that declaring a relation
# changes no published experiment.
RELATIONS: tuple[str, ...] = ("left of", "right of", "in front of", "behind")
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
EXAM_ITEMS = 5
MAX_DISTRACTORS = 3


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
    teacher: "Teacher | None" = None  # the teacher protocol's teacher (experiments/teacher.py)

    def words(self, lesson: Lesson) -> frozenset[str]:
        return lesson_words(lesson)


def phrase(obj: ObjectSpec) -> str:
    return " ".join(w for w in (obj.colour, obj.shape) if w)


def lesson_words(lesson: Lesson) -> frozenset[str]:
    """The concept words a lesson's content uses (for the oracle): sizes, colours, shapes,
    the relation and the verb, each as one word."""
    from aileen.curriculum.sentences import read_content

    info = read_content(lesson.content)
    words: set[str] = set()
    for p in info.phrases:
        words.update(w for w in (p.size, p.colour, p.shape) if w)
    if info.relation is not None:
        # An action sentence uses two words, the verb and the relation: a learner that composes
        # them ("move" once, "behind" known) understands "move X behind Y" without ever having
        # seen that pair, so the one-shot oracle counts the verb as one word, not one per relation.
        words.add(info.relation)
        if info.verb:
            words.add(info.verb)
    return frozenset(words)


def colour_shape_pairs() -> list[tuple[str, str]]:
    """Every (colour, shape) the catalogue has: the 20 objects of the visual protocol."""
    return [(c, s) for c in COLOURS for s in SHAPES]


def _other_object(rng: np.random.Generator, not_like: tuple[str, str]) -> ObjectSpec:
    """A random object that differs from `not_like` (colour, shape) in colour or shape."""
    while True:
        c, s = COLOURS[rng.integers(len(COLOURS))], SHAPES[rng.integers(len(SHAPES))]
        if (c, s) != not_like:
            return ObjectSpec(s, c)


def two_objects(rng: np.random.Generator) -> tuple[ObjectSpec, ObjectSpec]:
    """Two different catalogue objects, drawn without replacement."""
    pairs = colour_shape_pairs()
    i, j = rng.choice(len(pairs), size=2, replace=False)
    (c1, s1), (c2, s2) = pairs[i], pairs[j]
    return ObjectSpec(s1, c1), ObjectSpec(s2, c2)


def _src(kind: str, i: int) -> Source:
    return Source(path=f"<{kind}>", index=i + 1)


def visual_lessons(rng: np.random.Generator) -> list[Lesson]:
    items: list[ObjectSpec] = [ObjectSpec(s, c) for c, s in colour_shape_pairs()] + [ObjectSpec(s, None) for s in SHAPES]
    order = rng.permutation(len(items))
    out = []
    for k, i in enumerate(order):
        obj = items[i]
        placed = obj if obj.colour else ObjectSpec(obj.shape, COLOURS[rng.integers(len(COLOURS))])
        out.append(Lesson("inform", phrase(obj), [placed], source=_src("visual lesson", k), expect="success"))
    return out


def visual_exams(rng: np.random.Generator) -> tuple[list[Lesson], list[Lesson]]:
    pairs = colour_shape_pairs()
    gen, spec = [], []
    for k, i in enumerate(rng.choice(len(pairs), size=EXAM_ITEMS, replace=False)):
        c, s = pairs[i]
        gen.append(Lesson("verify", f"{c} {s}", [ObjectSpec(s, c)], distractors=int(rng.integers(0, MAX_DISTRACTORS + 1)),
                          source=_src("generality", k), expect="success"))
    for k, i in enumerate(rng.choice(len(pairs), size=EXAM_ITEMS, replace=False)):
        c, s = pairs[i]
        spec.append(Lesson("verify", f"{c} {s}", [_other_object(rng, (c, s))],
                           distractors=int(rng.integers(0, MAX_DISTRACTORS + 1)),
                           source=_src("specificity", k), expect="failure"))
    return gen, spec


def _relations_balanced(rng: np.random.Generator, n: int) -> list[str]:
    rels = [RELATIONS[i % len(RELATIONS)] for i in range(n)]
    return [rels[i] for i in rng.permutation(n)]


def spatial_lessons(rng: np.random.Generator, n: int = 20) -> list[Lesson]:
    out = []
    for k, rel in enumerate(_relations_balanced(rng, n)):
        a, b = two_objects(rng)
        out.append(Lesson("inform", f"{phrase(a)} {rel} {phrase(b)}", [a, b], relation=rel,
                          source=_src("spatial lesson", k), expect="success"))
    return out


def _different_relation(rng: np.random.Generator, rel: str) -> str:
    others = [r for r in RELATIONS if r != rel]
    return others[rng.integers(len(others))]


def spatial_exams(rng: np.random.Generator) -> tuple[list[Lesson], list[Lesson]]:
    gen, spec = [], []
    for k in range(EXAM_ITEMS):
        rel = RELATIONS[rng.integers(len(RELATIONS))]
        a, b = two_objects(rng)
        gen.append(Lesson("verify", f"{phrase(a)} {rel} {phrase(b)}", [a, b], relation=rel,
                          distractors=int(rng.integers(0, MAX_DISTRACTORS + 1)),
                          source=_src("generality", k), expect="success"))
    for k in range(EXAM_ITEMS):
        rel = RELATIONS[rng.integers(len(RELATIONS))]
        a, b = two_objects(rng)
        spec.append(Lesson("verify", f"{phrase(a)} {rel} {phrase(b)}", [a, b], relation=_different_relation(rng, rel),
                           distractors=int(rng.integers(0, MAX_DISTRACTORS + 1)),
                           source=_src("specificity", k), expect="failure"))
    return gen, spec


def move_sentence(a: ObjectSpec, rel: str, b: ObjectSpec) -> str:
    return f"move {phrase(a)} {rel} {phrase(b)}"


def action_lessons(rng: np.random.Generator, n: int = 20) -> list[Lesson]:
    out = []
    for k, rel in enumerate(_relations_balanced(rng, n)):
        a, b = two_objects(rng)
        start = _different_relation(rng, rel)  # the object starts somewhere else
        out.append(Lesson("inform", move_sentence(a, rel, b), [a, b], relation=start, action=ActionSpec("move", rel),
                          source=_src("action lesson", k), expect="success"))
    return out


def action_exams(rng: np.random.Generator) -> tuple[list[Lesson], list[Lesson]]:
    gen, spec = [], []
    for k in range(EXAM_ITEMS):
        rel = RELATIONS[rng.integers(len(RELATIONS))]
        a, b = two_objects(rng)
        gen.append(Lesson("verify", move_sentence(a, rel, b), [a, b], relation=_different_relation(rng, rel),
                          action=ActionSpec("move", rel), distractors=int(rng.integers(0, MAX_DISTRACTORS + 1)),
                          source=_src("generality", k), expect="success"))
    for k in range(EXAM_ITEMS):
        said = RELATIONS[rng.integers(len(RELATIONS))]
        done = _different_relation(rng, said)
        a, b = two_objects(rng)
        spec.append(Lesson("verify", move_sentence(a, said, b), [a, b], relation=_different_relation(rng, done),
                           action=ActionSpec("move", done), distractors=int(rng.integers(0, MAX_DISTRACTORS + 1)),
                           source=_src("specificity", k), expect="failure"))
    return gen, spec


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
    from aileen.experiments import wide

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
    from aileen.experiments import teacher

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
