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
import re

import numpy as np

from aileen.curriculum.lesson import ActionSpec, Lesson, ObjectSpec
from aileen.domain import channels, relations
from aileen.world import catalog, stacks
from aileen.world.appearance import Appearance

STREAM = 0x0B7EC7  # the naming draws' own stream of the lesson's seed
PLACEHOLDER = re.compile(r"<[^<>\s]+>")  # a script's name for an object ("<obj1>"), in a sentence too
# An object a sentence names by its place in `objects` ("<obj2>": the second), said once drawn
# (the script reader writes its placeholders so: `legacy._template`).
TEMPLATE = re.compile(r"<obj(\d+)>")


def sentence(kind: str, objects: list[ObjectSpec], relation: str | None = None,
             action: ActionSpec | None = None) -> str | None:
    """What the trainer says for a described lesson: "small purple sphere", "red box left of
    blue cone", "move red box right of blue cone", "push red sphere" (relations by their word:
    `behind2` is said "behind"). `kind` is the original's lesson type without "-word"
    (visual, spatial, action). None for a visual lesson whose object has neither colour nor
    shape: there is nothing to call it yet."""
    if kind == "visual":
        o = objects[0]
        return o.describe() if any(c.name in o.appearance for c in channels.drawn()) else None
    if kind == "spatial":
        assert relation is not None
        return f"{objects[0].describe()} {relations.get(relation).word} {objects[1].describe()}"
    assert action is not None
    words = [action.verb, objects[0].describe()]
    if action.relation:
        words += [relations.get(action.relation).word, objects[1].describe()]
    return " ".join(words)


def open_objects(objects: list[ObjectSpec]) -> bool:
    """Does any described object leave its kind (its colour, its shape: a drawn channel) to
    the trainer?"""
    return any(channels.kind_of(o.appearance) is None for o in objects)


def choices(lesson: Lesson, i: int, channel: channels.Channel) -> tuple[str, ...]:
    """The values objects[i] may be drawn with in a channel: its own, else any; the object
    something must rest on (the second of an "on" layout or goal) only a shape that can
    carry (a flat top)."""
    spec = lesson.objects[i]
    if channel.name in spec.appearance:
        return (spec.appearance[channel.name],)
    if channel.name == "shape":
        goal = lesson.action.relation if lesson.action is not None else None
        carries = any(r is not None and relations.get(r).stacked for r in (lesson.relation, goal))
        if i == 1 and carries:
            return tuple(s for s in channel.values if s in stacks.FLAT_TOPS)
    return catalog.drawable(channel.values)


def shape_choices(lesson: Lesson, i: int) -> tuple[str, ...]:
    """The shapes objects[i] may be drawn as (`choices` of the shape channel)."""
    return choices(lesson, i, channels.SHAPE)


def draw_kind(lesson: Lesson, i: int, rng: np.random.Generator, taken: set[Appearance]) -> Appearance:
    """The kind of objects[i] (its drawn channels' values: shape, colour): its own where
    given, the rest drawn, preferring a kind not already `taken` (so each described object
    stays the only one of its kind)."""
    kinds = channels.kinds(lambda c: choices(lesson, i, c))
    fresh = [k for k in kinds if k not in taken] or kinds
    return fresh[int(rng.integers(len(fresh)))]


def name(lesson: Lesson, *, seed: int) -> Lesson:
    """The lesson with its open objects drawn and its sentence said with them; a lesson
    without `name_objects` comes back as it is."""
    if not lesson.name_objects:
        return lesson
    rng = np.random.default_rng([seed, STREAM])
    taken = {k for k in (channels.kind_of(o.appearance) for o in lesson.objects) if k is not None}
    objects = []
    for i, spec in enumerate(lesson.objects):
        if channels.kind_of(spec.appearance) is not None:
            objects.append(spec)
            continue
        kind = draw_kind(lesson, i, rng, taken)
        taken.add(kind)
        objects.append(spec.with_values(**kind))
    if TEMPLATE.search(lesson.content):  # the script's own sentence, its placeholders said as drawn
        said = TEMPLATE.sub(lambda m: objects[int(m.group(1)) - 1].describe(), lesson.content)
    else:
        said = sentence(lesson.kind, objects, lesson.relation, lesson.action)
    return dataclasses.replace(lesson, objects=objects, content=said or lesson.content, name_objects=False)
