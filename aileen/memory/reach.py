"""A relation word's distance, learned at the grain its examples show: the size principle on a line.

Why (issue 20, "the same applies to distance"): the agent perceives distance at two grains, the
coarse `qdist` (close, far, and nothing in between) and the bands of `calculi.DBAND`. A word
taught only at the coarse grain is a lookup of it: "close to" shown at a tenth of an object's
width and told `wrong` at a third cannot narrow (both are `qd_close`), and a word shown a hand's
breadth apart on every side ("vicinal of": no close, no far fact) is accepted across the table,
since a description without a fact of distance matches every distance. As for directions
(memory/extent.py), the regions that hold every example are weighed by the size principle (Xu &
Tenenbaum 2007): a smaller one makes the examples less of a coincidence.

Distance is measured two ways (`calculi.FINER`, each in the same bands): `dband`, qdist's gap
(the widest empty band between the footprints along an axis), and `dgap`, the gap two discs of
the footprints would leave (the same on every side; qdist's shrinks on the diagonals: two
spheres 0.14 m apart leave 4 cm side by side and nothing corner to corner). A teacher who means
how far apart the things are speaks of the second; a grader who lays "near" out by qdist, of
the first. The word's examples pick: each measure's regions are hypotheses beside the other's.
A pair is judged by the posterior over all of them (`Reading.holds`), so examples that fit both
measures alike (all on the axes) leave a pair on a diagonal in doubt, not refused; where to put
an object for the word is read in the measure holding most of the posterior (`Reading.within`).

The hypotheses are runs of bands of one measure (the line of distances is not a circle), all
built from the declarations:

* the coarse calculus's regions (`qd_close`, `qd_far`) on qdist's measure, one family;
* per measure, every run of adjacent bands (an interval: any width, any position), one family;
* the whole line ("no distance": "left of", "larger than"), one family.

The prior is uniform over the families, then within each. A region of one measure explains the
examples' bands in that measure (each example has a band in each), so given a measure a word's
reading is what it would be with that measure alone. A band's size is one: the bands widen with
the distance (`calculi.BAND_EDGES`) about as a ratio scale does, so each is about as
likely a place for a teacher's example. Near misses are read as a teacher shows them, near the
edge (a geometric fall of one band) or, for half of them, anywhere outside, as for directions.

The answer is the posterior predictive: a band belongs to the word when the regions holding it
have posterior at least one half. Evidence comes from the concept memory as it is: the band
facts between the word's two roles in its descriptions and near misses. Pure functions.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from aileen.domain import calculi
from aileen.memory.extent import ACCEPT, FAR_MISSES, NOISE, SURE, cell_of, counts
from aileen.terms import Term

__all__ = ["MEASURES", "Cells", "Reading", "ReachEvidence", "cells", "runs", "evidence", "hypotheses", "news", "predictive", "read",
           "seen", "surest", "unbounded"]

MEASURES: tuple[calculi.Calculus, ...] = calculi.FINER  # the first is qdist's measure
ReachEvidence = tuple[tuple[int, ...], tuple[int, ...]]  # (positive, negative) counts per band of every measure, in turn


@functools.lru_cache(maxsize=1)
def _parts() -> tuple[tuple[int, int], ...]:
    """Each measure's [start, stop) among the cells (its bands, measure after measure)."""
    out, at = [], 0
    for m in MEASURES:
        out.append((at, at + len(m.relations)))
        at += len(m.relations)
    return tuple(out)


@functools.lru_cache(maxsize=None)
def _index(m: int) -> dict[str, int]:
    return {r: k for k, r in enumerate(MEASURES[m].relations)}


def _coarse(n: int) -> list[np.ndarray]:
    """The coarse grain's regions as runs of qdist's bands: close and far (the edges
    `calculi.QD_CLOSE` and `QD_MID` are band edges). What lies between is no region of its
    own: it is what perception does not mark, not a thing a word names."""
    edges = np.array(calculi.BAND_EDGES)
    assert len(edges) == n
    return [edges < calculi.QD_CLOSE, edges >= calculi.QD_MID]  # a band's lower edge: within or beyond


@functools.lru_cache(maxsize=1)
def hypotheses() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(membership H x cells, size in bands H, log prior H, scope H x cells, measure H) of
    every region (see the module doc). A region's scope is the cells its likelihood reads: its
    measure's bands (the whole line reads the first measure's: each example counted once);
    its measure is -1 for the whole line."""
    parts = _parts()
    total = parts[-1][1]
    families: list[tuple[int, list[np.ndarray]]] = []  # (measure, regions over its bands)
    for m, (a, b) in enumerate(parts):
        n = b - a
        if m == 0:
            families.append((0, _coarse(n)))
        intervals = []
        for lo in range(n):
            for hi in range(lo, n):
                r = np.zeros(n, dtype=bool)
                r[lo:hi + 1] = True
                intervals.append(r)
        families.append((m, intervals))
    families.append((-1, [np.ones(parts[0][1] - parts[0][0], dtype=bool)]))
    masks, scopes, sizes, logp, measure = [], [], [], [], []
    for m, fam in families:
        a, b = parts[max(m, 0)]
        for r in fam:
            mask = np.zeros(total, dtype=bool)
            scope = np.zeros(total, dtype=bool)
            scope[a:b] = True
            if m < 0:
                mask[:] = True
            else:
                mask[a:b] = r
            masks.append(mask)
            scopes.append(scope)
            sizes.append(float(r.sum()))
            logp.append(-math.log(len(families)) - math.log(len(fam)))
            measure.append(m)
    return np.array(masks), np.array(sizes), np.array(logp), np.array(scopes), np.array(measure)


@functools.lru_cache(maxsize=1)
def _near_miss_loglik() -> np.ndarray:
    """H x cells: a near miss's log likelihood per band under each region: `NOISE` inside;
    outside, near the edge (geometric fall of one band, on whichever side has an outside) for
    half of a teacher's near misses, anywhere outside for the other half (`FAR_MISSES`); 0 in
    the cells a region does not read."""
    member, size, _, scope, measure = hypotheses()
    out = np.zeros(member.shape)
    for m, (a, b) in enumerate(_parts()):
        rows = (measure == m) | ((measure < 0) & (m == 0))
        mem = member[rows][:, a:b]
        n = b - a
        idx = np.arange(n)
        lo = np.argmax(mem, axis=1)
        hi = n - 1 - np.argmax(mem[:, ::-1], axis=1)
        dist = np.where(idx[None, :] < lo[:, None], lo[:, None] - idx[None, :],
                        np.where(idx[None, :] > hi[:, None], idx[None, :] - hi[:, None], 0))
        keep = math.exp(-1.0)
        sides = (lo > 0).astype(float) + (hi < n - 1).astype(float)
        near = (1 - keep) / np.maximum(sides, 1)[:, None] * keep ** (np.maximum(dist, 1) - 1)
        far = 1.0 / np.maximum(n - size[rows], 1)[:, None]
        with np.errstate(divide="ignore"):
            outside = np.log((1 - NOISE) * ((1 - FAR_MISSES) * near + FAR_MISSES * far))
        block = out[rows]
        block[:, a:b] = np.where(dist == 0, math.log(NOISE / n), outside)
        out[rows] = block
    out.setflags(write=False)
    return out


@functools.lru_cache(maxsize=4096)
def _posterior(pos: tuple[int, ...], neg: tuple[int, ...]) -> np.ndarray:
    member, size, logp, scope, measure = hypotheses()
    p = np.array(pos, dtype=float)
    seen = scope @ p  # each region's examples: those with a band in its measure
    k_in = (member & scope) @ p
    loglik = k_in * np.log((1 - NOISE) / size) + (seen - k_in) * np.log(NOISE / scope.sum(axis=1))
    if any(neg):
        loglik = loglik + _near_miss_loglik() @ np.array(neg, dtype=float)
    # a measure that saw fewer examples than another (a memory saved before it was perceived)
    # is no hypothesis: its regions would explain less
    post = np.where(seen < seen.max(), -np.inf, logp + loglik)
    post = np.exp(post - post.max())
    post /= post.sum()
    post.setflags(write=False)
    return post


def _check(pos: Sequence[int], neg: Sequence[int]) -> tuple[tuple[int, ...], tuple[int, ...]]:
    n = _parts()[-1][1]
    neg = tuple(neg) if neg else (0,) * n
    if len(pos) != n or len(neg) != n:
        raise ValueError(f"evidence must have one count per distance band of every measure ({n})")
    return tuple(int(x) for x in pos), tuple(int(x) for x in neg)


Cells = tuple[int | None, ...]  # a pair's cell in each measure (None: no band in it)


@dataclass(frozen=True)
class Reading:
    """A word's distance as read from its examples: the measure most of the posterior lies in
    and, given it, per band how surely the word holds there (where to aim a react); how surely
    the word says nothing of distance; and the posterior over every region, which judges a
    pair (`holds`: averaged over the measures, so examples that fit both equally leave a pair
    that only one measure calls far from them in doubt, not refused)."""

    measure: calculi.Calculus
    within: np.ndarray
    unbounded: float
    posterior: np.ndarray
    counts: tuple[int, ...]  # the positive examples per cell the reading was made from

    def holds(self, at: Cells) -> float:
        """The posterior probability that the word holds of a pair at the cells `at`
        (`cells`)."""
        cols = [c for c in at if c is not None]
        return float(self.posterior @ hypotheses()[0][:, cols].any(axis=1)) if cols else 0.0

    def outside(self, at: Cells) -> float:
        """The probability that a pair at the cells `at` lies outside the word's distance,
        where a band is no finer than its edges: the word's edge may fall inside the band at
        either end of its region, so a pair in such a band lies outside with the chance that
        it is nearer that end than every example seen in the band (1 / (k + 1) for k examples
        there: which of them lies lowest is a coin among k + 1). Why: a `wrong` told a little
        short of a far word's examples, in the band its nearest examples lie in, says where
        the edge is, not that the side was wrong (`Directions.evidence`); `1 - holds(at)`
        would call that band the word's for sure."""
        member, _size, _logp, _scope, measure = hypotheses()
        lo, hi, first, last = _ends()
        # each region reads the pair's cell in its own measure (none there: not inside, as
        # `holds` has it); the whole line (measure -1, the appended -1) holds everywhere and
        # has no edge
        cell = np.array([-1 if c is None else c for c in at] + [-1])[measure]
        rows = np.flatnonzero(cell >= 0)
        inside = measure < 0
        inside[rows] = member[rows, cell[rows]]
        edge = (cell >= 0) & inside & (((cell == lo) & (lo > first)) | ((cell == hi) & (hi < last)))
        k = np.array(self.counts, dtype=float)[np.maximum(cell, 0)]
        share = np.where(edge, 1.0 / (k + 1.0), 0.0)
        return float(self.posterior @ np.where(inside, share, 1.0))


@functools.lru_cache(maxsize=1)
def _ends() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Per region, its first and last cell and its measure's first and last cell (the whole
    line: -1 throughout, no edge)."""
    member, _size, _logp, _scope, measure = hypotheses()
    parts = _parts()
    lo = np.where(measure >= 0, np.argmax(member, axis=1), -1)
    hi = np.where(measure >= 0, member.shape[1] - 1 - np.argmax(member[:, ::-1], axis=1), -1)
    first = np.array([parts[m][0] if m >= 0 else -1 for m in measure])
    last = np.array([parts[m][1] - 1 if m >= 0 else -1 for m in measure])
    return lo, hi, first, last


@functools.lru_cache(maxsize=4096)
def _read(pos: tuple[int, ...], neg: tuple[int, ...]) -> Reading:
    member, _size, _logp, _scope, measure = hypotheses()
    post = _posterior(pos, neg)
    mass = [float(post[measure == m].sum()) for m in range(len(MEASURES))]
    m = int(np.argmax(mass))  # ties: the first, qdist's
    keep = (measure == m) | (measure < 0)
    cond = np.where(keep, post, 0.0)
    cond = cond / cond.sum()
    a, b = _parts()[m]
    within = cond @ member[:, a:b]
    within.setflags(write=False)
    return Reading(MEASURES[m], within, float(cond[member[:, a:b].all(axis=1)].sum()), post, pos)


def read(pos: Sequence[int], neg: Sequence[int] = ()) -> Reading:
    """The word's distance from its evidence (`evidence`): read in the measure holding most of
    the posterior, given that measure."""
    return _read(*_check(pos, neg))


def seen(pos: Sequence[int]) -> int:
    """How many examples the evidence holds: those with a band in the measure that has most
    (every measure has every example perceived since it was declared)."""
    return max(sum(pos[a:b]) for a, b in _parts())


def predictive(pos: Sequence[int], neg: Sequence[int] = ()) -> np.ndarray:
    """Per band of the measure the word is read in, the posterior probability that the word's
    region holds it."""
    return read(pos, neg).within


def unbounded(pos: Sequence[int], neg: Sequence[int] = ()) -> float:
    """The posterior probability that the word says nothing of distance (the whole line)."""
    return read(pos, neg).unbounded


def news(pos: Sequence[int], neg: Sequence[int], at: Cells) -> bool:
    """Is one more positive example at the cells `at` (its band in every measure: `cells`)
    worth storing? When the word holds there without being sure of it (under `SURE`), or the
    example would change an answer somewhere or the measure it is read in (as for directions,
    `extent.news`: an example the agent accepts is evidence under the size principle too)."""
    now = read(pos, neg)
    if now.holds(at) < SURE:
        return True
    more = list(pos)
    for c in at:
        if c is not None:
            more[c] += 1
    then = read(more, neg)
    return then.measure is not now.measure or bool(((now.within >= ACCEPT) != (then.within >= ACCEPT)).any())


def surest(within: np.ndarray, sure: float = SURE) -> int:
    """Where to put an object to make the word true: the middle band of the longest run of
    bands the word holds of with belief at least `sure` (room on both sides for the settling
    and the camera's error), or the band it holds of most surely when none is that sure."""
    best: tuple[int, int] | None = None  # (length, first band)
    for first, last in runs(within >= sure):
        if best is None or last - first + 1 > best[0]:
            best = (last - first + 1, first)
    if best is None:
        return int(np.argmax(within))
    return best[1] + (best[0] - 1) // 2


def runs(inside: np.ndarray) -> list[tuple[int, int]]:
    """The runs of adjacent True bands of `inside`, each as (first, last) band, in order."""
    out: list[tuple[int, int]] = []
    k = 0
    while k < len(inside):
        if inside[k]:
            j = k
            while j + 1 < len(inside) and inside[j + 1]:
                j += 1
            out.append((k, j))
            k = j + 1
        else:
            k += 1
    return out


def cells(facts: Iterable[Term], a: Term, b: Term) -> Cells | None:
    """The cells of a from b among `facts` (its band in each measure, as `evidence` counts
    them; None for a measure not perceived), None when it has no band in any (one object
    rests on the other, or the bands are not perceived)."""
    facts = list(facts)
    out = tuple(None if (k := cell_of(_index(m), facts, a, b)) is None else start + k
                for m, (start, _stop) in enumerate(_parts()))
    return None if all(c is None for c in out) else out


def evidence(concept: str, descriptions: Iterable[dict[Term, int] | Sequence[Term]],
             near_misses: Iterable[Sequence[Term]] = ()) -> ReachEvidence:
    """Positive counts per band of every measure from the concept's descriptions (a
    generalization's fact counts, or an example's facts: count 1) and negative ones from its
    near misses, each between the word's two roles as its membership fact names them
    (`extent.counts`)."""
    descriptions, near_misses = list(descriptions), list(near_misses)
    pos: list[int] = []
    neg: list[int] = []
    for m in range(len(MEASURES)):
        p, q = counts(_index(m), concept, descriptions, near_misses)
        pos += p
        neg += q
    return tuple(pos), tuple(neg)
