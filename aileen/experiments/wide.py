"""The wide protocol: the paper's curricula, laid out and examined where people still use the words.

Why: on the paper's protocol (relations laid out within 10 degrees of the axis, specificity
items that differ from what is said in every way) the agent sits at the one-shot oracle, so the
protocol cannot tell a good learner from a better one. The wide protocol keeps the paper's
trial shapes (same lessons, same exam sizes, same oracle) and changes where the scenes lie:

* relations are laid out over the whole region a person accepts (`relations.wide`: uniform in
  angle up to 40 degrees off the axis, uniform in distance), in lessons and generality exams;
* the specificity exam is made of near misses:
  - visual: an object that shares the phrase's colour or its shape (never both);
  - spatial: the opposite or a perpendicular layout (`TrainerRelation.near_miss`), or the
    role-swapped one (the reference in the relation to the mover);
  - action: the wrong object moved (the reference is moved so that the sentence's relation
    ends true), or the right object moved to the wrong place.

Each specificity item's `note` names its kind ("near miss: ..."), so the runner can report
every kind separately. The directional words are read from `relations.directions()`.
"""

from __future__ import annotations

import math

import numpy as np

from aileen.curriculum.lesson import ActionSpec, Lesson, ObjectSpec, Source
from aileen.domain import relations
from aileen.experiments.protocol import (
    EXAM_ITEMS,
    MAX_DISTRACTORS,
    colour_shape_pairs,
    move_sentence,
    phrase,
    two_objects,
)
from aileen.world.catalog import COLOURS, SHAPES

# The kinds of near miss, as written in a specificity item's note.
VISUAL_SAME_COLOUR = "near miss: same colour"
VISUAL_SAME_SHAPE = "near miss: same shape"
SPATIAL_ROTATED = "near miss: opposite or perpendicular"
SPATIAL_SWAPPED = "near miss: roles swapped"
ACTION_WRONG_MOVER = "near miss: wrong object moved"
ACTION_WRONG_PLACE = "near miss: moved to the wrong place"


def directions() -> tuple[str, ...]:
    return relations.directions()


def _src(kind: str, i: int) -> Source:
    return Source(path=f"<wide {kind}>", index=i + 1)


def _distractors(rng: np.random.Generator) -> int:
    return int(rng.integers(0, MAX_DISTRACTORS + 1))


def opposite(word: str) -> str:
    """The directional word whose heading is turned half a circle from `word`'s."""
    h = relations.of_word(word).heading
    assert h is not None, f"{word!r} has no direction"
    for w in directions():
        other = relations.of_word(w).heading
        assert other is not None
        if abs(math.remainder(other - h - math.pi, 2 * math.pi)) < 1e-6:
            return w
    raise ValueError(f"no directional word opposite to {word!r}")


def _other_direction(rng: np.random.Generator, word: str) -> str:
    others = [r for r in directions() if r != word]
    return others[int(rng.integers(len(others)))]


def _balanced(rng: np.random.Generator, n: int) -> list[str]:
    rels = [directions()[i % len(directions())] for i in range(n)]
    return [rels[i] for i in rng.permutation(n)]


# --------------------------------------------------------------------------- visual

def visual_exams(rng: np.random.Generator) -> tuple[list[Lesson], list[Lesson]]:
    """Generality as in the paper; specificity: an object sharing the colour or the shape."""
    pairs = colour_shape_pairs()
    gen, spec = [], []
    for k, i in enumerate(rng.choice(len(pairs), size=EXAM_ITEMS, replace=False)):
        c, s = pairs[i]
        gen.append(Lesson("verify", f"{c} {s}", [ObjectSpec(s, c)], distractors=_distractors(rng),
                          source=_src("generality", k), expect="success"))
    for k, i in enumerate(rng.choice(len(pairs), size=EXAM_ITEMS, replace=False)):
        c, s = pairs[i]
        if k % 2 == 0:  # same colour, another shape
            shapes = [x for x in SHAPES if x != s]
            obj, note = ObjectSpec(shapes[int(rng.integers(len(shapes)))], c), VISUAL_SAME_COLOUR
        else:
            colours = [x for x in COLOURS if x != c]
            obj, note = ObjectSpec(s, colours[int(rng.integers(len(colours)))]), VISUAL_SAME_SHAPE
        spec.append(Lesson("verify", f"{c} {s}", [obj], distractors=_distractors(rng),
                           source=_src("specificity", k), expect="failure", note=note))
    return gen, spec


# --------------------------------------------------------------------------- spatial

def spatial_lessons(rng: np.random.Generator, n: int = 20) -> list[Lesson]:
    out = []
    for k, rel in enumerate(_balanced(rng, n)):
        a, b = two_objects(rng)
        out.append(Lesson("inform", f"{phrase(a)} {rel} {phrase(b)}", [a, b], relation=relations.wide(rel),
                          source=_src("spatial lesson", k), expect="success"))
    return out


def spatial_exams(rng: np.random.Generator) -> tuple[list[Lesson], list[Lesson]]:
    gen, spec = [], []
    for k in range(EXAM_ITEMS):
        rel = directions()[int(rng.integers(len(directions())))]
        a, b = two_objects(rng)
        gen.append(Lesson("verify", f"{phrase(a)} {rel} {phrase(b)}", [a, b], relation=relations.wide(rel),
                          distractors=_distractors(rng), source=_src("generality", k), expect="success"))
    for k in range(EXAM_ITEMS):
        rel = directions()[int(rng.integers(len(directions())))]
        a, b = two_objects(rng)
        said = f"{phrase(a)} {rel} {phrase(b)}"
        if k % 3 == 2:  # the reference stands in the relation to the mover
            spec.append(Lesson("verify", said, [b, a], relation=relations.wide(rel), distractors=_distractors(rng),
                               source=_src("specificity", k), expect="failure", note=SPATIAL_SWAPPED))
        else:
            spec.append(Lesson("verify", said, [a, b], relation=rel, near_miss=True, distractors=_distractors(rng),
                               source=_src("specificity", k), expect="failure", note=SPATIAL_ROTATED))
    return gen, spec


# --------------------------------------------------------------------------- action

def action_lessons(rng: np.random.Generator, n: int = 20) -> list[Lesson]:
    out = []
    for k, rel in enumerate(_balanced(rng, n)):
        a, b = two_objects(rng)
        start = relations.wide(_other_direction(rng, rel))
        out.append(Lesson("inform", move_sentence(a, rel, b), [a, b], relation=start,
                          action=ActionSpec("move", relations.wide(rel)),
                          source=_src("action lesson", k), expect="success"))
    return out


def wrong_mover(rng: np.random.Generator, k: int, a: ObjectSpec, rel: str, b: ObjectSpec) -> Lesson:
    """'move a <rel> b' said, but the trainer moves b so that a ends <rel> b: b goes to the
    opposite side of a (the lesson's objects are [b, a]: objects[0] is the one moved)."""
    return Lesson("verify", move_sentence(a, rel, b), [b, a], action=ActionSpec("move", relations.wide(opposite(rel))),
                  distractors=_distractors(rng), source=_src("specificity", k), expect="failure",
                  note=ACTION_WRONG_MOVER)


def action_exams(rng: np.random.Generator) -> tuple[list[Lesson], list[Lesson]]:
    gen, spec = [], []
    for k in range(EXAM_ITEMS):
        rel = directions()[int(rng.integers(len(directions())))]
        a, b = two_objects(rng)
        gen.append(Lesson("verify", move_sentence(a, rel, b), [a, b], relation=relations.wide(_other_direction(rng, rel)),
                          action=ActionSpec("move", relations.wide(rel)), distractors=_distractors(rng),
                          source=_src("generality", k), expect="success"))
    for k in range(EXAM_ITEMS):
        said = directions()[int(rng.integers(len(directions())))]
        a, b = two_objects(rng)
        if k % 2 == 0:
            spec.append(wrong_mover(rng, k, a, said, b))
        else:
            done = _other_direction(rng, said)
            start = relations.wide(_other_direction(rng, done))
            # `done` in its plain layout (within 10 degrees of its axis), like every near miss: at
            # a diagonal, the camera's 8 sectors cannot tell 40 degrees off one axis from 50 off
            # the other (docs/results.md).
            spec.append(Lesson("verify", move_sentence(a, said, b), [a, b], relation=start,
                               action=ActionSpec("move", done), distractors=_distractors(rng),
                               source=_src("specificity", k), expect="failure", note=ACTION_WRONG_PLACE))
    return gen, spec
