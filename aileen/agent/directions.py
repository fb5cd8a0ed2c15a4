"""The agent's sense of where relation words hold: each word's direction as a region.

A part of the agent (issue 20), held by it and used by grounding, learning and acting: with
several grains of direction perceived (`AgentParams.extents`), a relation word's direction is
the region the size principle picks from its examples and near misses (`memory/extent.py`),
read from the concept memory as it is; SME then matches the word's other facts. This module
decides which words have a direction at all (mutual exclusivity: a word with more than a
direction leaves direction to the words that are a direction alone, unless its examples' sides
are no coincidence: `SIDES_BY_CHANCE`); the acting part puts an
object where the region holds surely (`extent.surest`). It keeps no state of its own: everything is derived from the memory, so
an undo or a reload needs nothing reset here.
"""

from __future__ import annotations

import functools
from collections.abc import Callable

import numpy as np

from aileen.domain import calculi
from aileen.memory import extent, reach
from aileen.memory.concept import ConceptMemory
from aileen.memory.semantic import part_of

# Mutual exclusivity reads a word with more than a direction ("near": close) as leaving the side
# to the direction words; its examples overrule that when chance hardly explains the sides they
# lie on: the posterior that the word holds on every side (`extent.sideless`) is under this.
# "northeast of" shown four times between 35 and 52 degrees, each time close by: under 0.001,
# a direction. Examples on random sides: about 1 % of three, fewer of more, read as one; two
# examples 12 degrees apart: 0.03, still sideless (one more example decides).
SIDES_BY_CHANCE = 0.01
# A word whose examples' directions are most likely the whole circle says nothing of side
# (declared in `extent`, read by `memory show` too).
SIDELESS = extent.SIDELESS


@functools.lru_cache(maxsize=1)
def direction_predicates() -> frozenset[str]:
    """Every direction relation of every grain (`*_eq` included)."""
    return frozenset(r for c in calculi.CALCULI if c.is_direction for r in c.relations)


@functools.lru_cache(maxsize=1)
def band_predicates() -> frozenset[str]:
    """Every relation of the finer grains of the other senses (`calculi.FINER`: distance in
    bands): every pair apart has one in each measure, so matched one by one by SME they would
    only tell how far apart an example happened to stand."""
    return frozenset(r for c in calculi.FINER for r in c.relations)


@functools.lru_cache(maxsize=1)
def region_predicates() -> frozenset[str]:
    """Every relation whose meaning is learned as a region rather than matched by SME: every
    grain of direction and the finer grains of the other senses (`calculi.FINER`)."""
    return direction_predicates() | band_predicates()


def common(relation: str) -> bool:
    """Is `relation` what nearly every pair of objects has (`dc`: `Calculus.common`)?"""
    c = calculi.calculus_of(relation)
    return c is not None and relation in c.common


# What a relation word's description holds beyond a direction (close, far, touching, larger),
# declared in `extent` (`memory show` reads it too)
marks = extent.marks
marked = extent.marked


class Directions:
    """Where each relation word holds, as a region of directions (see the module doc).

    `memory` gives the agent's concept memory as it is now; `exclusive` is whether mutual
    exclusivity applies (`AgentParams.mutual_exclusivity`); `pedagogical` whether near misses
    are read as lying near the word's edge (`AgentParams.near_miss_edges`)."""

    def __init__(self, memory: Callable[[], ConceptMemory], exclusive: bool, pedagogical: bool = True) -> None:
        self._memory = memory
        self._exclusive = exclusive
        self._pedagogical = pedagogical

    def evidence(self, concept: str) -> extent.DirectionEvidence:
        """Positive and negative counts per fine sector, from the word's descriptions and near
        misses. A near miss the word's distance explains is no evidence of its side: when its
        examples' sides say nothing (`SIDELESS`) and their distances do (`Reading.unbounded`
        under one half), a `wrong` at a distance that may lie outside the word's (with
        probability over 1 - `extent.SURE`, `Reading.outside`: a band its examples do not
        surely hold, or a band at the end of their run, which the word's edge may cut) was
        about distance ("blick of" shown close by on every side, told wrong a little farther
        off: that side is not the word's edge; a far word told wrong a little short of its
        nearest examples, in their band: its edge lies in that band). Unless its side explains
        it better: the near miss lies more likely outside the region its examples' sides make
        (`extent.predictive` of them alone) than outside their distance. "zup of" shown 0.2 m
        apart on every side but behind, and told wrong straight behind at 0.2 m, where five of
        its six examples lie (in their band, at its end: outside with 1/6), kept saying yes
        there: the `wrong` was read as about distance."""
        descriptions, near_misses = self._described(concept)
        pos, neg = extent.evidence(concept, descriptions, near_misses)
        if not any(neg) or extent.sideless(pos, pedagogical=self._pedagogical) < SIDELESS:
            return pos, neg
        near = reach.read(reach.evidence(concept, descriptions)[0])
        if near.unbounded >= SIDELESS:
            return pos, neg
        sides = extent.predictive(pos, pedagogical=self._pedagogical)
        kept = [nm for nm in near_misses
                if (roles := extent.roles_of(nm, concept)) is None or (at := reach.cells(nm, *roles)) is None
                or (far := near.outside(at)) <= 1 - extent.SURE
                or ((k := extent.sector_of(nm, *roles)) is not None and 1.0 - sides[k] > far)]
        return extent.evidence(concept, descriptions, kept)

    def region(self, concept: str) -> np.ndarray | None:
        """Per fine sector, how surely the word's region holds it; None when its examples say
        nothing of direction: none shows one, or (mutual exclusivity) the word has more to it
        than a direction and the agent has words that are a direction alone ("near": close,
        on whichever side)."""
        return self.read(concept)[0]

    def read(self, concept: str) -> tuple[np.ndarray | None, bool]:
        """(`region`, whether it is None only because mutual exclusivity leaves the word's
        side to the direction words while chance explains the sides its examples lie on):
        one reading of the word's evidence for both."""
        own = self.evidence(concept)
        if not any(own[0]):
            return None, False
        if self._by_chance(concept, *own):
            return None, True
        return extent.predictive(*own, pedagogical=self._pedagogical), False

    def explained(self, concept: str) -> bool:
        """Is this word's direction another word's business? When every description of it
        holds more than a direction (close, far, touching, larger) and the agent has words
        whose meaning is a direction alone, which side its examples lay on is theirs to say.
        Its examples on sides no direction word covers (a diagonal between two narrow words)
        are then no reason to tie it to that side. Unless the word is a conjunction of known
        words: when what it holds beyond a direction is made of what other words hold beyond
        theirs ("far left of", once "far from" is known; not "near" once "next to", which
        says more, is known), every part of it is claimed, and it keeps its direction (issue
        20 (a): a word whose every percept is claimed keeps them). A synonym of a known word
        ("distant from" after "far from") is read so too, and its examples' sides then weigh
        until they spread round the circle. Nor is the direction of a word made of direction
        words another word's business ("behind right of": `semantic.part_of`)."""
        if not self.marked_word(concept):
            return False
        memory = self._memory()
        own = self._marks(concept)
        pos, neg = self.evidence(concept)
        mine = extent.sideless(pos, neg, pedagogical=self._pedagogical) if any(pos) else 1.0
        parts: set[tuple[str, bool]] = set()  # what other words say that is a part of this word's marks
        direction_words = False
        for c in memory.concepts():
            if c.kind != "spatial" or c.symbol == concept:
                continue
            if self.marked_word(c.symbol) and self._sideless_more(c.symbol, mine):
                theirs = self._marks(c.symbol)
                if theirs <= own:  # "far from" is part of "far left of"; "next to" is not part of "near"
                    parts |= theirs
            elif any(self.evidence(c.symbol)[0]):
                if part_of(c.symbol, concept):
                    return False  # its direction is its parts'
                direction_words = True
        return direction_words and not (own and own <= parts)

    def _sideless_more(self, concept: str, than: float) -> bool:
        """Does chance explain the sides the word's examples lie on better than `than` (another
        word's `extent.sideless`), read from its examples alone? Only such a word can be a
        part of what another holds beyond a direction: "far from" shown anywhere is a part of
        "far left of" shown on the left; "in front of", shown three times close by in front,
        is a side and closeness, and "near" shown once is not "in front of" less its side (it
        was read as that conjunction, and kept the side of its one example)."""
        pos, neg = self.evidence(concept)
        return not any(pos) or extent.sideless(pos, neg, pedagogical=self._pedagogical) > than

    def _marks(self, concept: str) -> frozenset[tuple[str, bool]]:
        """What every description of the word holds beyond a direction (`marks`)."""
        ds = self._memory().descriptions(concept)
        out = [marks(d, concept) for d in ds]
        return frozenset.intersection(*out) if out else frozenset()

    def marked_word(self, concept: str) -> bool:
        """Does every description of a relation word hold more than a direction (`marked`)? A
        word with one description that is a direction alone ("right of" shown apart, and once
        touching, kept apart) is a direction word."""
        ds = self._memory().descriptions(concept)
        return bool(ds) and all(marked(d, concept) for d in ds)

    def is_direction_word(self, concept: str) -> bool:
        """A word whose meaning is its region alone (it has a side, and no description holds
        more)."""
        return self.sided(concept) and not self.marked_word(concept)

    def sided(self, concept: str) -> bool:
        """Does the word say which side: it has a region, and its examples' directions are not
        most likely the whole circle (`SIDELESS`)? A word shown close by on sides spread round
        the circle holds on every side; it says nothing of the side, so it accounts for no
        side of a pair (`Grounding.accounted`: "wug of" shown close by after "fep of", which
        held there, lost its examples' sides to it and was read as a side of one example)."""
        pos, neg = self.evidence(concept)  # read once: `region` is None without it or by chance
        if not any(pos) or self._by_chance(concept, pos, neg):
            return False
        return extent.sideless(pos, neg, pedagogical=self._pedagogical) < SIDELESS

    def news(self, concept: str, sector: int) -> bool:
        """Would one more example of the word in `sector` tell it something (`extent.news`)?
        Of a word read as sideless by mutual exclusivity: would it make the sides its examples
        lie on no coincidence (`SIDES_BY_CHANCE`), a direction of the word's own?"""
        pos, neg = self.evidence(concept)
        if self._by_chance(concept, pos, neg):
            return self._sides_news(pos, neg, sector)
        if (self._exclusive and any(pos) and self.marked_word(concept)
                and extent.sideless(pos, neg, pedagogical=self._pedagogical) >= SIDES_BY_CHANCE
                and self._sides_news(pos, neg, sector)):
            # A word with more than a direction ("just left of": close) keeps its side only
            # while chance does not explain its examples' sides, once words that are a
            # direction alone are known (`explained`): an example it accepts now is worth
            # keeping until then ("jlo of" kept two of five examples close on the left, and
            # lost its side to "right of" taught after them).
            return True
        return extent.news(pos, neg, sector, pedagogical=self._pedagogical)

    def _sides_news(self, pos: tuple[int, ...], neg: tuple[int, ...], sector: int) -> bool:
        """Would one more example in `sector` make the sides the examples lie on no coincidence
        (`SIDES_BY_CHANCE`), or halve how likely chance makes them, or make the whole circle
        the likelier reading (`SIDELESS`: the word then says how far, `reach`)? Any other
        example on a new side changes no answer: "near" shown on yet another side is not
        stored for that (it was, once examples kept their sides: 17 % more store commands in
        the repertoire experiment, every answer the same); "nigh of" shown close by behind and
        then in front is (its distance is then read from both)."""
        more = list(pos)
        more[sector] += 1
        now = extent.sideless(pos, neg, pedagogical=self._pedagogical)
        then = extent.sideless(more, neg, pedagogical=self._pedagogical)
        return then < SIDES_BY_CHANCE or then < now / 2 or now < SIDELESS <= then

    def reach_evidence(self, concept: str) -> reach.ReachEvidence:
        """Positive and negative counts per distance band, from the word's descriptions and near misses."""
        return reach.evidence(concept, *self._described(concept))

    def _described(self, concept: str) -> tuple[list, list]:
        """The word's descriptions as the evidence reads them (each generalization's fact
        counts, each kept example), and its near misses."""
        c = self._memory().concept(concept)
        return [g.counts for g in c.context.generalizations] + list(c.context.examples), c.near_misses

    def reach(self, concept: str) -> reach.Reading | None:
        """The word's distance (`memory/reach.py`: how surely it holds of a pair, and where to
        aim); None when distance is not the word's to say: a word whose examples say which
        side (a direction word: how far apart its examples happened to lie is the distance
        words' business), a word whose descriptions hold a mark of another sense (touching,
        larger, resting on: that is what it says), or one shown at no distance (stacked)."""
        pos, neg = self.reach_evidence(concept)
        if not any(pos):
            return None
        sides, misses = self.evidence(concept)  # read once: this is asked of every pair
        if reach.seen(pos) < sum(sides):
            # examples seen apart but without a band: perceived before the bands were (a memory
            # saved by an earlier version); reading the rest alone would narrow the word to them
            return None
        if (any(sides) and not self._by_chance(concept, sides, misses)  # it has a region (`read`)
                and extent.sideless(sides, misses, pedagogical=self._pedagogical) < SIDELESS):
            return None
        qdist = calculi.calculus_by_name("qdist")
        if any(calculi.calculus_of(name) is not qdist for name, _forward in self._marks(concept)):
            return None
        return reach.read(pos, neg)

    def reach_news(self, concept: str, cells: reach.Cells) -> bool:
        """Would one more example of the word at `cells` (its band in every measure:
        `reach.cells`) tell it something (`reach.news`)?"""
        return reach.news(*self.reach_evidence(concept), cells)

    def _by_chance(self, concept: str, pos: tuple[int, ...], neg: tuple[int, ...]) -> bool:
        return (self._exclusive and any(pos) and self.explained(concept)
                and extent.sideless(pos, neg, pedagogical=self._pedagogical) >= SIDES_BY_CHANCE)
