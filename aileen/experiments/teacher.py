"""The teacher protocol: each trial draws a teacher, and its words mean what that teacher accepts.

Why: in the wide protocol "left of" is accepted up to 45 degrees off the axis, which is exactly
the four-cone calculus the agent perceives by default, so learning the four words there is a
lookup (issue 20). Here the words' regions vary from trial to trial and do not line up with
any one calculus:

* per cardinal word ("left of", "right of", "in front of", "behind": the `wide` family) the
  teacher draws an acceptance half-angle, uniform in [20, 50] degrees;
* and one or two more words, each a `diagonal` sector ("behind left of" at 135 degrees,
  half-angle uniform in [10, 20]) or a `narrow` band ("west of" at 180, [4, 10]).

Lessons lay the objects out uniformly in angle within the teacher's region (`LAY_MARGIN`
inside its edge, apart), checked after physics settles within `CLEAR_MARGIN` of the edge; the
training sequence also holds a few near-miss `verify` lessons just outside the edge
(`NEAR_MISS_BAND` beyond it) with `feedback = "wrong"`, so that a learner that says yes is
told so, and can find the edge. Exams: generality items inside the region; specificity items
are near misses just outside the edge (`EDGE`) and far from it (the opposite or a
perpendicular direction, `wide.SPATIAL_ROTATED`; the roles swapped, `wide.SPATIAL_SWAPPED`),
each kind reported apart by its note.

The exams are larger than the other protocols' 5 + 5 items (`GEN_ITEMS`, `SPEC_ITEMS`): with
5 or 6 words a trial, 5 items leave most words unexamined in a trial, and the per-family
tables (a family's words are 1 or 2 of a trial's) would rest on a handful of items.

A teacher's relations are `TrainerRelation`s (`relations.directional` with its acceptance
half-angle and near-miss band) that live for one trial only: `Trial.relations`, put in
`relations.scope` while the trial runs, never into the registry the published protocols read.
The family of teachers is also what the ideal observer knows (`ideal.py`, `priors`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from aileen.curriculum.lesson import Lesson, Source
from aileen.domain import relations
from aileen.experiments.paper import MAX_DISTRACTORS, RELATIONS, phrase, two_objects


@dataclass(frozen=True)
class Family:
    """A kind of word a teacher may use: its words' axes and the range of its half-angle."""

    name: str
    axes: dict[str, float]  # word -> axis, degrees counter-clockwise from east (+x, the trainer's right)
    half_angle: tuple[float, float]  # degrees; a teacher draws each word's uniformly in this range


# The cardinal words are the published four (`paper.RELATIONS`), along their declared axes.
WIDE = Family("wide", {w: relations.direction(w).axis for w in RELATIONS}, (20.0, 50.0))
DIAGONAL = Family("diagonal", {"behind left of": 135.0, "behind right of": 45.0, "front left of": 225.0,
                               "front right of": 315.0}, (10.0, 20.0))
NARROW = Family("narrow", {"west of": 180.0, "east of": 0.0, "north of": 90.0, "south of": 270.0}, (4.0, 10.0))
FAMILIES: dict[str, Family] = {f.name: f for f in (WIDE, DIAGONAL, NARROW)}
EXTRA_FAMILIES: tuple[str, ...] = ("diagonal", "narrow")
EXTRA_WORDS = (1, 2)  # how many words beyond the four cardinal ones (uniform)

# Positives are laid out uniformly in angle within h - LAY_MARGIN of the axis, and must lie
# within h - CLEAR_MARGIN after physics settles (else they are drawn again).
LAY_MARGIN = 1.0
CLEAR_MARGIN = 0.5
# Near misses just outside the edge: between these many degrees beyond the half-angle.
NEAR_MISS_BAND = (2.0, 9.0)
FAR_SUFFIX = " teacher far"  # the layout whose near misses are the opposite or a perpendicular direction

TRAINING_INFORMS = 18
TRAINING_NEAR_MISSES = 6
GEN_ITEMS = 12
SPEC_EDGE_ITEMS = 8
SPEC_FAR_ITEMS = 4  # alternately opposite / perpendicular and role-swapped
SPEC_ITEMS = SPEC_EDGE_ITEMS + SPEC_FAR_ITEMS

EDGE = "near miss: just outside the teacher's edge"
# the far near misses are named as in the wide protocol
ROTATED = "near miss: opposite or perpendicular"
SWAPPED = "near miss: roles swapped"


@dataclass(frozen=True)
class Sense:
    """One word as this teacher uses it: accepted within `half_angle` degrees of `axis`."""

    word: str
    family: str
    axis: float
    half_angle: float

    def relation(self) -> relations.TrainerRelation:
        """The teacher's layout of the word (named like the word, so it stands for the word
        inside `relations.scope`): positives within the region, near misses just outside."""
        h = self.half_angle
        return relations.directional(self.word, self.axis, word=self.word, accept_half_angle=h,
                                     lay_half_angle=h - LAY_MARGIN, clear_half_angle=h - CLEAR_MARGIN,
                                     near_miss_band=NEAR_MISS_BAND)

    def far_relation(self) -> relations.TrainerRelation:
        """The same word, whose near misses are the opposite or a perpendicular direction."""
        h = self.half_angle
        return relations.directional(self.word + FAR_SUFFIX, self.axis, word=self.word, accept_half_angle=h,
                                     lay_half_angle=h - LAY_MARGIN, clear_half_angle=h - CLEAR_MARGIN)


@dataclass(frozen=True)
class Teacher:
    """The words of one trial and how far off their axes this teacher still says them."""

    senses: tuple[Sense, ...]

    def words(self) -> tuple[str, ...]:
        return tuple(s.word for s in self.senses)

    def sense(self, word: str) -> Sense:
        for s in self.senses:
            if s.word == word:
                return s
        raise KeyError(word)

    def family_of(self) -> dict[str, str]:
        return {s.word: s.family for s in self.senses}

    def relations(self) -> tuple[relations.TrainerRelation, ...]:
        return tuple(r for s in self.senses for r in (s.relation(), s.far_relation()))


def draw_teacher(rng: np.random.Generator) -> Teacher:
    """A teacher: a half-angle per cardinal word, and 1 or 2 extra words (each from a family
    drawn uniformly, the word uniformly within it, no word twice), each with its half-angle."""
    senses = [Sense(w, WIDE.name, a, float(rng.uniform(*WIDE.half_angle))) for w, a in WIDE.axes.items()]
    n_extra = int(rng.integers(EXTRA_WORDS[0], EXTRA_WORDS[1] + 1))
    taken: set[str] = set()
    while len(taken) < n_extra:
        fam = FAMILIES[EXTRA_FAMILIES[int(rng.integers(len(EXTRA_FAMILIES)))]]
        words = [w for w in fam.axes if w not in taken]
        w = words[int(rng.integers(len(words)))]
        taken.add(w)
        senses.append(Sense(w, fam.name, fam.axes[w], float(rng.uniform(*fam.half_angle))))
    return Teacher(tuple(senses))


def _src(kind: str, i: int) -> Source:
    return Source(path=f"<teacher {kind}>", index=i + 1)


def _distractors(rng: np.random.Generator) -> int:
    return int(rng.integers(0, MAX_DISTRACTORS + 1))


def _spread(rng: np.random.Generator, words: tuple[str, ...], n: int) -> list[str]:
    """`n` words, as even over `words` as can be (the extra ones drawn at random), shuffled."""
    order = [words[i] for i in rng.permutation(len(words))]
    out = [order[i % len(order)] for i in range(n)]
    return [out[i] for i in rng.permutation(n)]


def training_lessons(rng: np.random.Generator, teacher: Teacher) -> list[Lesson]:
    """`TRAINING_INFORMS` inform lessons spread over the teacher's words and
    `TRAINING_NEAR_MISSES` near-miss verify lessons (`feedback = "wrong"`), shuffled; a word's
    near misses come after its first inform."""
    words = teacher.words()
    # every word gets a near miss before any gets a second
    plan = [("inform", w) for w in _spread(rng, words, TRAINING_INFORMS)]
    plan += [("miss", w) for w in _spread(rng, words, TRAINING_NEAR_MISSES)]
    plan = [plan[i] for i in rng.permutation(len(plan))]
    changed = True
    while changed:  # move each near miss after its word's first inform
        changed = False
        for i, (kind, w) in enumerate(plan):
            if kind != "miss":
                continue
            first = next(j for j, x in enumerate(plan) if x == ("inform", w))
            if first > i:
                plan[i], plan[first] = plan[first], plan[i]
                changed = True
    out = []
    for k, (kind, w) in enumerate(plan):
        a, b = two_objects(rng)
        said = f"{phrase(a)} {w} {phrase(b)}"
        if kind == "inform":
            out.append(Lesson("inform", said, [a, b], relation=w, source=_src("lesson", k), expect="success"))
        else:
            out.append(Lesson("verify", said, [a, b], relation=w, near_miss=True, source=_src("lesson", k),
                              expect="failure", feedback="wrong", note=EDGE))
    return out


def exams(rng: np.random.Generator, teacher: Teacher) -> tuple[list[Lesson], list[Lesson]]:
    """Generality: `GEN_ITEMS` items inside the teacher's regions; specificity:
    `SPEC_EDGE_ITEMS` near misses just outside the edge, `SPEC_FAR_ITEMS` far ones (opposite or
    perpendicular, roles swapped); the words spread evenly over the items."""
    words = teacher.words()
    gen = []
    for k, w in enumerate(_spread(rng, words, GEN_ITEMS)):
        a, b = two_objects(rng)
        gen.append(Lesson("verify", f"{phrase(a)} {w} {phrase(b)}", [a, b], relation=w, distractors=_distractors(rng),
                          source=_src("generality", k), expect="success"))
    spec = []
    for k, w in enumerate(_spread(rng, words, SPEC_EDGE_ITEMS)):
        a, b = two_objects(rng)
        spec.append(Lesson("verify", f"{phrase(a)} {w} {phrase(b)}", [a, b], relation=w, near_miss=True,
                           distractors=_distractors(rng), source=_src("specificity", k), expect="failure", note=EDGE))
    for j, w in enumerate(_spread(rng, words, SPEC_FAR_ITEMS)):
        k = SPEC_EDGE_ITEMS + j
        a, b = two_objects(rng)
        said = f"{phrase(a)} {w} {phrase(b)}"
        if j % 2:  # the reference stands in the relation to the one said
            spec.append(Lesson("verify", said, [b, a], relation=w, distractors=_distractors(rng),
                               source=_src("specificity", k), expect="failure", note=SWAPPED))
        else:
            spec.append(Lesson("verify", said, [a, b], relation=w + FAR_SUFFIX, near_miss=True,
                               distractors=_distractors(rng), source=_src("specificity", k), expect="failure",
                               note=ROTATED))
    return gen, spec
