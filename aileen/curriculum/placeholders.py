"""Objects a lesson leaves open, drawn by the trainer and named in its sentence.

The original AILEEN's action scripts name their objects `<obj1>`, `<obj2>` and often say
nothing more of them: the original drew a random object for each and generated the sentence
from what it drew ("move red box right of blue cylinder"). A sentence generated from the open
description ("move object right of object") names nothing a learner can ground, and every
distractor would fit it. So a lesson whose sentence is generated from its description
(`Lesson.name_objects`, set by the reader of the original scripts) gets its open colours and
shapes drawn here, before it is laid out, and its sentence said again with them.

`sentence` is the one place that words a lesson's description as the trainer says it; the
script reader uses it for lessons without `content`. Every draw comes from the lesson's seed
(its own stream, so the layout's draws stay as they were): same lesson, same seed, same
objects and sentence.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from aileen.curriculum.lesson import ActionSpec, Lesson, ObjectSpec
from aileen.domain import relations
from aileen.world import catalog, stacks

STREAM = 0x0B7EC7  # the naming draws' own stream of the lesson's seed


def sentence(kind: str, objects: list[ObjectSpec], relation: str | None = None,
             action: ActionSpec | None = None) -> str | None:
    """What the trainer says for a described lesson: "small purple sphere", "red box left of
    blue cone", "move red box right of blue cone", "push red sphere" (relations by their word:
    `behind2` is said "behind"). `kind` is the original's lesson type without "-word"
    (visual, spatial, action). None for a visual lesson whose object has neither colour nor
    shape: there is nothing to call it yet."""
    if kind == "visual":
        o = objects[0]
        return o.describe() if (o.shape or o.colour) else None
    if kind == "spatial":
        assert relation is not None
        return f"{objects[0].describe()} {relations.get(relation).word} {objects[1].describe()}"
    assert action is not None
    words = [action.verb, objects[0].describe()]
    if action.relation:
        words += [relations.get(action.relation).word, objects[1].describe()]
    return " ".join(words)


def open_objects(objects: list[ObjectSpec]) -> bool:
    """Does any described object leave its colour or shape to the trainer?"""
    return any(o.shape is None or o.colour is None for o in objects)


def shape_choices(lesson: Lesson, i: int) -> tuple[str, ...]:
    """The shapes objects[i] may be drawn as: its own, else any; the object something must rest
    on (the second of an "on" layout or goal) only a shape that can carry (a flat top)."""
    spec = lesson.objects[i]
    if spec.shape is not None:
        return (spec.shape,)
    goal = lesson.action.relation if lesson.action is not None else None
    carries = any(r is not None and relations.get(r).stacked for r in (lesson.relation, goal))
    if i == 1 and carries:
        return tuple(s for s in catalog.SHAPES if s in stacks.FLAT_TOPS)
    return catalog.SHAPES


def draw_kind(lesson: Lesson, i: int, rng: np.random.Generator, taken: set[tuple[str, str]]) -> tuple[str, str]:
    """(shape, colour) for objects[i]: its own where given, the rest drawn, preferring a kind
    not already `taken` (so each described object stays the only one of its kind)."""
    spec = lesson.objects[i]
    colours = [spec.colour] if spec.colour else list(catalog.COLOURS)
    kinds = [(s, c) for s in shape_choices(lesson, i) for c in colours]
    fresh = [k for k in kinds if k not in taken] or kinds
    return fresh[int(rng.integers(len(fresh)))]


def name(lesson: Lesson, *, seed: int) -> Lesson:
    """The lesson with its open objects drawn and its sentence said with them; a lesson
    without `name_objects` comes back as it is."""
    if not lesson.name_objects:
        return lesson
    rng = np.random.default_rng([seed, STREAM])
    taken = {(o.shape, o.colour) for o in lesson.objects if o.shape and o.colour}
    objects = []
    for i, spec in enumerate(lesson.objects):
        if spec.shape and spec.colour:
            objects.append(spec)
            continue
        shape, colour = draw_kind(lesson, i, rng, taken)
        taken.add((shape, colour))
        objects.append(dataclasses.replace(spec, shape=shape, colour=colour))
    said = sentence(lesson.kind, objects, lesson.relation, lesson.action)
    return dataclasses.replace(lesson, objects=objects, content=said or lesson.content, name_objects=False)
