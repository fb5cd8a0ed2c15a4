"""The ideal observer: exact Bayesian inference over the teacher protocol's family of teachers.

Why: the one-shot oracle credits an item once its words have been taught, and its specificity
is full marks; on the teacher protocol no learner can reach that, because a few examples do
not say where a teacher's edge lies. The ideal observer is the ceiling for learners that are
given the same examples: it knows the family of teachers (`teacher.FAMILIES`: per word its
axis and the range its half-angle h is drawn from, uniformly) and how the trainer lays out
(`WordPrior`), and from the examples seen it computes the exact posterior over h:

* a positive example at |offset| t off the axis: the trainer draws offsets uniformly within
  h - `lay` (the size principle: likelihood 1 / (h - lay) each, zero when t > h - lay + `tol`);
* a near miss at |offset| f (told `wrong`, or answered no and not corrected: either way the
  trainer's verdict is known): the trainer draws f uniformly between h + band[0] and
  h + band[1], so h lies in [f - band[1] - tol, f - band[0] + tol] (and below f: the word does
  not hold there), and the likelihood is flat in h.

The posterior density is then (h - lay)^-n on an interval [A, B] (n positives), so every
probability is in closed form. An exam item at |offset| t holds when t < h; the observer says
yes when P(h > t | examples) >= 0.5, which is the answer that is right more often than not for
every item, so no learner that judges an item by the word's region, given the same examples,
is right more often on average. A word not yet shown (no positive example) is unknown: the
observer says no, as the one-shot oracle counts it. `tol` absorbs what settling may move an
object (nothing, for objects apart; the trainer's clear standard allows `CLEAR_MARGIN`).

Angles come from the trainer's own tables (the settled scene), never from the agent's eyes.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

from aileen.curriculum.lesson import Lesson
from aileen.curriculum.sentences import read_content


@dataclass(frozen=True)
class WordPrior:
    """What the observer knows of a word before any example: the family's, not the teacher's."""

    word: str
    axis: float  # degrees counter-clockwise from east
    half_angle: tuple[float, float]  # h is uniform in this range
    lay: float  # positives lie uniformly within h - lay of the axis
    band: tuple[float, float]  # near misses lie between h + band[0] and h + band[1] off the axis
    tol: float = 0.5  # degrees an observed offset may differ from the drawn one


def priors(family_of: Mapping[str, str]) -> dict[str, WordPrior]:
    """The observer's priors for a trial's words (word -> family name): the family's axis and
    half-angle range, and the protocol's layout margins."""
    from aileen.experiments import teacher

    out = {}
    for word, fam in family_of.items():
        f = teacher.FAMILIES[fam]
        out[word] = WordPrior(word, f.axes[word], f.half_angle, teacher.LAY_MARGIN, teacher.NEAR_MISS_BAND,
                              teacher.LAY_MARGIN - teacher.CLEAR_MARGIN)
    return out


def offset(direction: float, axis: float) -> float:
    """Degrees (0-180) between a direction and an axis, both counter-clockwise from east."""
    return abs(math.degrees(math.remainder(math.radians(direction - axis), 2 * math.pi)))


@dataclass
class Posterior:
    """The observer's belief about one word's half-angle: density (h - lay)^-n on [lo, hi]."""

    prior: WordPrior
    positives: list[float] = field(default_factory=list)  # |offsets| of the examples
    misses: list[float] = field(default_factory=list)  # |offsets| of the near misses

    def interval(self) -> tuple[float, float]:
        """[A, B]: the half-angles consistent with everything seen. Evidence outside the
        model (it never is when the trainer lays out as declared: `inconsistent`) is read
        as little as keeps the interval whole: a near miss as an exclusion only, and a
        positive beyond every consistent h as the smallest h that admits it."""
        lo, hi, _ = self._interval()
        return lo, hi

    def inconsistent(self) -> int:
        """How many near misses fell outside the model's band."""
        return self._interval()[2]

    def _interval(self) -> tuple[float, float, int]:
        p = self.prior
        lo = max([p.half_angle[0]] + [t + p.lay - p.tol for t in self.positives])
        hi = p.half_angle[1]
        bad = 0
        for f in sorted(self.misses):
            a, b = f - p.band[1] - p.tol, min(f - p.band[0] + p.tol, f)
            if max(lo, a) <= min(hi, b):
                lo, hi = max(lo, a), min(hi, b)
            else:
                bad += 1
                hi = min(hi, f)
        return min(lo, hi), hi, bad

    def _mass(self, a: float, b: float) -> float:
        """The integral of (h - lay)^-n from a to b (a <= b)."""
        n, c = len(self.positives), self.prior.lay
        if b <= a:
            return 0.0
        if n == 0:
            return b - a
        if n == 1:
            return math.log((b - c) / (a - c))
        return ((a - c) ** (1 - n) - (b - c) ** (1 - n)) / (n - 1)

    def p_holds(self, t: float) -> float:
        """P(h > t | what was seen): that an item t degrees off the axis holds."""
        lo, hi = self.interval()
        if hi <= lo:  # a point
            return 1.0 if t < lo else 0.0
        if t <= lo:
            return 1.0
        if t >= hi:
            return 0.0
        # for many examples the masses underflow towards 0; the ratio of the tail is stable
        n, c = len(self.positives), self.prior.lay
        if n > 1:
            # (x - c)^(1-n) scaled by (lo - c)^(n-1): 1 at lo, smaller beyond
            def g(x: float) -> float:
                return ((lo - c) / (x - c)) ** (n - 1)
            return (g(t) - g(hi)) / (1.0 - g(hi))
        return self._mass(t, hi) / self._mass(lo, hi)


class IdealObserver:
    """Per word a `Posterior`; answers exam items by posterior probability >= 0.5."""

    def __init__(self, word_priors: Mapping[str, WordPrior]) -> None:
        self.posteriors = {w: Posterior(p) for w, p in word_priors.items()}
        self.visual: set[str] = set()

    def learn_words(self, words: Sequence[str] | frozenset[str]) -> None:
        """Visual words taught (known as the one-shot oracle knows them: once taught)."""
        self.visual.update(words)

    def see(self, word: str, direction: float | None, positive: bool) -> None:
        """One example of `word`: the direction (degrees) of the said first object from the
        second on the trainer's table; positive, or a near miss."""
        post = self.posteriors.get(word)
        if post is None or direction is None:
            return
        t = offset(direction, post.prior.axis)
        (post.positives if positive else post.misses).append(t)

    def p_holds(self, word: str, direction: float) -> float:
        post = self.posteriors[word]
        return post.p_holds(offset(direction, post.prior.axis))

    def says_yes(self, item: Lesson, direction: float | None) -> bool:
        """Its answer to a verify item: every visual word known, the relation word shown, and
        the item's direction inside the word's region with posterior probability >= 0.5."""
        from aileen.experiments.protocol import lesson_words

        rel = read_content(item.content).relation
        if not (lesson_words(item) - {rel}) <= self.visual:
            return False
        if rel is None:
            return True
        post = self.posteriors.get(rel)
        if post is None or not post.positives or direction is None:
            return False
        return post.p_holds(offset(direction, post.prior.axis)) >= 0.5


def said_direction(lesson: Lesson, setup) -> float | None:  # noqa: ANN001 - trainer.Setup
    """The direction (degrees counter-clockwise from east) of the object the sentence names
    first, seen from the one it names second, on the trainer's table as the lesson left it;
    None without a relation. The described objects are looked up by the sentence's phrases (a
    role-swapped item lays them out the other way round; distractors never fit a phrase)."""
    info = read_content(lesson.content)
    if info.relation is None or len(info.phrases) != 2 or len(setup.ids) < 2:
        return None
    objs = [setup.world.get(i) for i in setup.ids]
    a = next((o for o in objs if info.phrases[0].fits(o.appearance)), None)
    b = next((o for o in objs if o is not a and info.phrases[1].fits(o.appearance)), None)
    if a is None or b is None:
        return None
    return math.degrees(math.atan2(a.y - b.y, a.x - b.x))
