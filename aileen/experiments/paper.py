"""The paper's evaluation protocol: its training lessons and its two exams.

Recovered from the original system's generator and logs (../shared/reference): a visual
trial is the 20 colour-shape objects plus the 4 shape-only lessons, shuffled, as inform
lessons without distractors; after every lesson a generality exam (5 verify lessons whose
scene holds what is said) and a specificity exam (5 verify lessons whose scene does not), both
drawn once per trial, with 0-3 distractors. Exam items are colour-shape objects (the one-shot
oracle computed from this reproduces the published ceiling: 0.21 0.68 1.30 ...). Spatial and
action trials have 20 lessons, 5 for each of the 4 relations, shuffled: the original does not
say how its 20 were drawn, and a balanced draw makes "known by lesson 16" a property of the
learner rather than of the dice.

The other protocols (`wide`, `teacher`) build on these pieces (the published words, the exam
sizes, the objects and sentences); `protocol` assembles a trial of any of them.
"""

from __future__ import annotations

import numpy as np

from aileen.curriculum.lesson import ActionSpec, Lesson, ObjectSpec, Source
from aileen.world.catalog import COLOURS, PAPER_SHAPES

SHAPES = PAPER_SHAPES

# The paper's four directional words, as published: fixed here, so that declaring a relation
# changes no published experiment.
RELATIONS: tuple[str, ...] = ("left of", "right of", "in front of", "behind")
EXAM_ITEMS = 5
MAX_DISTRACTORS = 3


def phrase(obj: ObjectSpec) -> str:
    return " ".join(w for w in (obj.colour, obj.shape) if w)


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
