"""A relation word's distance, learned at the grain its examples show: the size principle on a line.

Why (issue 20, "the same applies to distance"): the agent perceives distance at two grains, the
coarse `qdist` (close, far, and nothing in between) and the bands of `calculi.DBAND`. A word
taught only at the coarse grain is a lookup of it: "close to" shown at a tenth of an object's
width and told `wrong` at a third cannot narrow (both are `qd_close`), and a word shown a hand's
breadth apart on every side ("vicinal of": no close, no far fact) is accepted across the table,
since a description without a fact of distance matches every distance. As for directions
(memory/extent.py), the regions that hold every example are weighed by the size principle (Xu &
Tenenbaum 2007): a smaller one makes the examples less of a coincidence.

The hypotheses are runs of bands (the line of distances is not a circle), all built from the
declarations:

* the coarse calculus's regions (`qd_close`, `qd_far`), one family;
* every run of adjacent bands (an interval: any width, any position), one family;
* the whole line ("no distance": "left of", "larger than"), one family.

The prior is uniform over the families, then within each. A band's size is one: the bands
widen with the distance (`calculi.BAND_EDGES`) about as a ratio scale does, so each is about as
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

import numpy as np

from aileen.domain import calculi
from aileen.memory.extent import ACCEPT, FAR_MISSES, NOISE, SURE, cell_of, counts
from aileen.terms import Term

__all__ = ["BAND", "ReachEvidence", "band_of", "evidence", "hypotheses", "news", "predictive", "surest", "unbounded"]

BAND = calculi.DBAND
ReachEvidence = tuple[tuple[int, ...], tuple[int, ...]]  # (positive, negative) counts per band


@functools.lru_cache(maxsize=1)
def _index() -> dict[str, int]:
    return {r: k for k, r in enumerate(BAND.relations)}


def _coarse() -> list[np.ndarray]:
    """The coarse grain's regions as runs of bands: close and far (the edges `calculi.QD_CLOSE`
    and `QD_MID` are band edges). What lies between is no region of its own: it is what
    perception does not mark, not a thing a word names."""
    edges = np.array(calculi.BAND_EDGES)
    return [edges < calculi.QD_CLOSE, edges >= calculi.QD_MID]  # a band's lower edge: within or beyond


@functools.lru_cache(maxsize=1)
def hypotheses() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(membership H x N, size in bands H, log prior H) of every region (see the module doc)."""
    n = len(BAND.relations)
    intervals = []
    for lo in range(n):
        for hi in range(lo, n):
            m = np.zeros(n, dtype=bool)
            m[lo:hi + 1] = True
            intervals.append(m)
    families = [_coarse(), intervals, [np.ones(n, dtype=bool)]]
    masks, logp = [], []
    for fam in families:
        for m in fam:
            masks.append(m)
            logp.append(-math.log(len(families)) - math.log(len(fam)))
    member = np.array(masks)
    return member, member.sum(axis=1).astype(float), np.array(logp)


@functools.lru_cache(maxsize=1)
def _near_miss_loglik() -> np.ndarray:
    """H x N: a near miss's log likelihood per band under each region: `NOISE` inside; outside,
    near the edge (geometric fall of one band, on whichever side has an outside) for half of
    a teacher's near misses, anywhere outside for the other half (`FAR_MISSES`)."""
    member, size, _ = hypotheses()
    n = member.shape[1]
    idx = np.arange(n)
    lo = np.argmax(member, axis=1)
    hi = n - 1 - np.argmax(member[:, ::-1], axis=1)
    dist = np.where(idx[None, :] < lo[:, None], lo[:, None] - idx[None, :],
                    np.where(idx[None, :] > hi[:, None], idx[None, :] - hi[:, None], 0))
    keep = math.exp(-1.0)
    sides = (lo > 0).astype(float) + (hi < n - 1).astype(float)
    near = (1 - keep) / np.maximum(sides, 1)[:, None] * keep ** (np.maximum(dist, 1) - 1)
    far = 1.0 / np.maximum(n - size, 1)[:, None]
    with np.errstate(divide="ignore"):
        outside = np.log((1 - NOISE) * ((1 - FAR_MISSES) * near + FAR_MISSES * far))
    out = np.where(dist == 0, math.log(NOISE / n), outside)
    out.setflags(write=False)
    return out


@functools.lru_cache(maxsize=4096)
def _posterior(pos: tuple[int, ...], neg: tuple[int, ...]) -> np.ndarray:
    member, size, logp = hypotheses()
    n = member.shape[1]
    p = np.array(pos, dtype=float)
    k_in = member @ p
    loglik = k_in * np.log((1 - NOISE) / size) + (p.sum() - k_in) * math.log(NOISE / n)
    if any(neg):
        loglik = loglik + _near_miss_loglik() @ np.array(neg, dtype=float)
    post = logp + loglik
    post = np.exp(post - post.max())
    post /= post.sum()
    post.setflags(write=False)
    return post


def _check(pos: Sequence[int], neg: Sequence[int]) -> tuple[tuple[int, ...], tuple[int, ...]]:
    n = len(BAND.relations)
    neg = tuple(neg) if neg else (0,) * n
    if len(pos) != n or len(neg) != n:
        raise ValueError(f"evidence must have one count per distance band ({n})")
    return tuple(int(x) for x in pos), tuple(int(x) for x in neg)


def predictive(pos: Sequence[int], neg: Sequence[int] = ()) -> np.ndarray:
    """Per band, the posterior probability that the word's region holds it."""
    member, _size, _logp = hypotheses()
    out = _posterior(*_check(pos, neg)) @ member
    return out


def unbounded(pos: Sequence[int], neg: Sequence[int] = ()) -> float:
    """The posterior probability that the word says nothing of distance (the whole line)."""
    member, _size, _logp = hypotheses()
    return float(_posterior(*_check(pos, neg))[member.all(axis=1)].sum())


def news(pos: Sequence[int], neg: Sequence[int], band: int) -> bool:
    """Is one more positive example at `band` worth storing? When the word holds there without
    being sure of it (under `SURE`), or the example would change an answer somewhere (as for
    directions, `extent.news`: an example the agent accepts is evidence under the size
    principle too)."""
    now = predictive(pos, neg)
    if now[band] < SURE:
        return True
    more = list(pos)
    more[band] += 1
    return bool(((now >= ACCEPT) != (predictive(more, neg) >= ACCEPT)).any())


def surest(within: np.ndarray, sure: float = SURE) -> int:
    """Where to put an object to make the word true: the middle band of the longest run of
    bands the word holds of with belief at least `sure` (room on both sides for the settling
    and the camera's error), or the band it holds of most surely when none is that sure."""
    best: tuple[int, int] | None = None  # (length, first band)
    k = 0
    while k < len(within):
        if within[k] >= sure:
            j = k
            while j + 1 < len(within) and within[j + 1] >= sure:
                j += 1
            if best is None or j - k + 1 > best[0]:
                best = (j - k + 1, k)
            k = j + 1
        else:
            k += 1
    if best is None:
        return int(np.argmax(within))
    return best[1] + (best[0] - 1) // 2


def band_of(facts: Iterable[Term], a: Term, b: Term) -> int | None:
    """The distance band of a from b among `facts`, None when there is none (one object rests
    on the other, or the bands are not perceived)."""
    return cell_of(_index(), facts, a, b)


def evidence(concept: str, descriptions: Iterable[dict[Term, int] | Sequence[Term]],
             near_misses: Iterable[Sequence[Term]] = ()) -> ReachEvidence:
    """Positive counts per band from the concept's descriptions (a generalization's fact
    counts, or an example's facts: count 1) and negative ones from its near misses, each
    between the word's two roles as its membership fact names them (`extent.counts`)."""
    return counts(_index(), concept, descriptions, near_misses)
