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

The repertoire experiment (the wide protocol's alone) teaches and examines the size words and
the relation words beyond the four directions (near, far from, next to, larger than, smaller
than), with their own near misses: the same object at another size, the relation just
outside, the comparatives with their roles swapped.

Each specificity item's `note` names its kind ("near miss: ..."), so the runner can report
every kind separately. The directional words are the published four (`paper.RELATIONS`), the
repertoire's relation words the published five (`REPERTOIRE_RELATIONS`).
"""

from __future__ import annotations

import numpy as np

from aileen.curriculum.lesson import ActionSpec, Lesson, ObjectSpec, Source
from aileen.domain import relations
from aileen.experiments.paper import (
    EXAM_ITEMS,
    MAX_DISTRACTORS,
    RELATIONS,
    colour_shape_pairs,
    move_sentence,
    phrase,
    two_objects,
    visual_lessons,
)
from aileen.world.catalog import COLOURS, PAPER_SHAPES, SIZES

SHAPES = PAPER_SHAPES

SIZE_WORDS: tuple[str, ...] = tuple(SIZES)

# The kinds of near miss, as written in a specificity item's note.
VISUAL_SAME_COLOUR = "near miss: same colour"
VISUAL_SAME_SHAPE = "near miss: same shape"
SPATIAL_ROTATED = "near miss: opposite or perpendicular"
SPATIAL_SWAPPED = "near miss: roles swapped"
SPATIAL_OUTSIDE = "near miss: just outside (distance, contact, size)"
VISUAL_OTHER_SIZE = "near miss: same colour and shape, another size"
ACTION_WRONG_MOVER = "near miss: wrong object moved"
ACTION_WRONG_PLACE = "near miss: moved to the wrong place"


def directions() -> tuple[str, ...]:
    """The four directional words of the published protocols (`paper.RELATIONS`)."""
    return RELATIONS


def _src(kind: str, i: int) -> Source:
    return Source(path=f"<wide {kind}>", index=i + 1)


def _distractors(rng: np.random.Generator) -> int:
    return int(rng.integers(0, MAX_DISTRACTORS + 1))


def opposite(word: str) -> str:
    """The direction word declared opposite to `word` (`relations.Direction.opposite`)."""
    found = relations.direction(word).opposite
    assert found is not None, f"{word!r} is declared in no family"
    return found


def _other_direction(rng: np.random.Generator, word: str) -> str:
    others = [r for r in directions() if r != word]
    return others[int(rng.integers(len(others)))]


def _balanced(rng: np.random.Generator, n: int, words: tuple[str, ...] | None = None) -> list[str]:
    words = directions() if words is None else words
    rels = [words[i % len(words)] for i in range(n)]
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


# --------------------------------------------------------------------------- repertoire

# The repertoire's relation words, as published: fixed here, so that declaring a relation
# changes no published experiment (each is declared in `relations`; a test holds them so).
REPERTOIRE_RELATIONS: tuple[str, ...] = ("next to", "near", "far from", "larger than", "smaller than")


def repertoire_words() -> tuple[str, ...]:
    """The repertoire experiment's words: the size words and the relation words beyond the
    four directions whose layout puts two objects side by side (`REPERTOIRE_RELATIONS`:
    distance, contact, size comparison)."""
    return SIZE_WORDS + REPERTOIRE_RELATIONS


def _pair(rng: np.random.Generator) -> tuple[str, str]:
    pairs = colour_shape_pairs()
    return pairs[int(rng.integers(len(pairs)))]


def _sized(size: str | None, colour: str, shape: str) -> str:
    return " ".join(w for w in (size, colour, shape) if w)


def sized_visual_lessons(rng: np.random.Generator) -> list[Lesson]:
    """The paper's visual lessons twice, each object at a random size: the repertoire's
    prerequisites, so that colour and shape words do not take on a size (shown only at the
    medium size, "red" would mean "red and medium" as far as a learner can tell; shown once
    at a random size, it would mean "red and small")."""
    out = []
    for lesson in visual_lessons(rng) + visual_lessons(rng):
        (obj,) = lesson.objects
        sized = ObjectSpec(obj.shape, obj.colour, SIZE_WORDS[int(rng.integers(len(SIZE_WORDS)))])
        out.append(Lesson(lesson.signal, lesson.content, [sized], source=lesson.source, expect=lesson.expect))
    return out


def touching_lessons(rng: np.random.Generator) -> list[Lesson]:
    """One lesson per direction with the objects in contact (the `-ec` layouts, said with the
    plain word): "left of" is then not taken to mean "apart", and a contact word learned later
    is not taken to be about a side."""
    out = []
    for k, w in enumerate(directions()):
        a, b = two_objects(rng)
        out.append(Lesson("inform", f"{phrase(a)} {w} {phrase(b)}", [a, b], relation=relations.direction(w).touching,
                          source=_src("touching lesson", k), expect="success"))
    return out


def repertoire_lessons(rng: np.random.Generator, n: int = 20) -> list[Lesson]:
    """`n` inform lessons balanced over `repertoire_words()`: a size word said in a three-word
    phrase ("large red box"), a relation word between two objects (its clear layout)."""
    out = []
    for k, w in enumerate(_balanced(rng, n, repertoire_words())):
        src = _src("repertoire lesson", k)
        if w in SIZE_WORDS:
            c, s = _pair(rng)
            out.append(Lesson("inform", _sized(w, c, s), [ObjectSpec(s, c, w)], source=src, expect="success"))
        else:
            a, b = two_objects(rng)
            out.append(Lesson("inform", f"{phrase(a)} {w} {phrase(b)}", [a, b], relation=w, source=src,
                              expect="success"))
    return out


def repertoire_exams(rng: np.random.Generator) -> tuple[list[Lesson], list[Lesson]]:
    """Generality: a sized phrase or a relation, as taught; specificity: near misses (the same
    object at another size; the relation just outside: not near enough, not touching, the
    same size; the comparatives with their roles swapped)."""
    words = repertoire_words()
    gen, spec = [], []
    for k in range(EXAM_ITEMS):
        w = words[int(rng.integers(len(words)))]
        if w in SIZE_WORDS:
            c, s = _pair(rng)
            gen.append(Lesson("verify", _sized(w, c, s), [ObjectSpec(s, c, w)], distractors=_distractors(rng),
                              source=_src("generality", k), expect="success"))
        else:
            a, b = two_objects(rng)
            gen.append(Lesson("verify", f"{phrase(a)} {w} {phrase(b)}", [a, b], relation=w,
                              distractors=_distractors(rng), source=_src("generality", k), expect="success"))
    asymmetric = tuple(w for w in words if w not in SIZE_WORDS and not relations.of_word(w).symmetric)
    for k in range(EXAM_ITEMS):
        w = (asymmetric if k % 3 == 2 else words)[int(rng.integers(len(asymmetric if k % 3 == 2 else words)))]
        src = _src("specificity", k)
        if w in SIZE_WORDS:
            c, s = _pair(rng)
            other = [z for z in SIZE_WORDS if z != w]
            spec.append(Lesson("verify", _sized(w, c, s), [ObjectSpec(s, c, other[int(rng.integers(len(other)))])],
                               distractors=_distractors(rng), source=src, expect="failure", note=VISUAL_OTHER_SIZE))
            continue
        a, b = two_objects(rng)
        said = f"{phrase(a)} {w} {phrase(b)}"
        if k % 3 == 2:  # the comparative the other way round
            spec.append(Lesson("verify", said, [b, a], relation=w, distractors=_distractors(rng), source=src,
                               expect="failure", note=SPATIAL_SWAPPED))
        else:
            spec.append(Lesson("verify", said, [a, b], relation=w, near_miss=True, distractors=_distractors(rng),
                               source=src, expect="failure", note=SPATIAL_OUTSIDE))
    return gen, spec
