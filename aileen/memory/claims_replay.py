"""The held meanings' strict subsets and supersets, and the replay of one part's exclusive pass
over them: the inner loop of `claims.Exclusivity` (its docstring says why a replay gives what
`exclusive` gives).

Why a module of its own: `claims.Exclusivity` decides what to compute again after an update
(which parts, replay or plain pass, many changes at once); this module is the computation,
which reads the held meanings and writes nothing of the structure's, so it can be read and
checked on its own (split off `claims.py`, which had grown past one job).

The index it reads: `count`, each given meaning held -> the number of concepts holding it;
`holders`, each -> those concepts; `postings`, each percept -> meaning size -> the given
meanings held with that percept.
"""

from __future__ import annotations

import heapq
from collections.abc import Iterator, Mapping

from aileen.memory.claims_pass import K, P, strict_subsets

__all__ = ["LOOKUP_MAX", "given_strict_subset_held", "given_supersets", "replay"]

#: Meanings of up to this many percepts find their held strict subsets by looking each one up
#: (2^k - 2 lookups); larger ones through the percepts' postings.
LOOKUP_MAX = 6

Postings = Mapping[P, Mapping[int, set[frozenset[P]]]]


def given_supersets(postings: Postings[P], t: frozenset[P]) -> Iterator[frozenset[P]]:
    """The given meanings held that are strict supersets of `t` (non-empty)."""
    if not t:
        return
    lists = [postings.get(p) for p in t]
    if any(x is None for x in lists):
        return
    best = min(lists, key=lambda by: sum(len(s) for s in by.values()))  # type: ignore[union-attr]
    for size, ms in best.items():  # type: ignore[union-attr]
        if size > len(t):
            for s in ms:
                if t < s:
                    yield s


def given_strict_subset_held(count: Mapping[frozenset[P], int], postings: Postings[P],
                             mine: frozenset[P]) -> bool:
    """Whether a given meaning held is a non-empty strict subset of `mine` (`mine` acts)."""
    if len(mine) < 2:
        return False
    if len(mine) == 2:
        return any(frozenset((p,)) in count for p in mine)
    if len(mine) <= LOOKUP_MAX:
        return any(t in count for t in strict_subsets(mine))
    for p in mine:
        for size, ms in postings.get(p, {}).items():
            if size < len(mine) and any(s < mine for s in ms):
                return True
    return False


def replay(start: list[K], budget: int, *, raw: Mapping[K, frozenset[P]], rank: Mapping[K, int],
           count: Mapping[frozenset[P], int], flat: frozenset[P], postings: Postings[P],
           holders: Mapping[frozenset[P], set[K]]) -> dict[K, frozenset[P]] | None:
    """`exclusive` from the given meanings, visiting only the visits that can change
    something, from the acting concepts `start` (see `claims.Exclusivity`); returns the
    keys whose meaning moved, or None past `budget` visits."""
    moved: dict[K, frozenset[P]] = {}
    delta: dict[frozenset[P], int] = {}  # held now - held as given
    cur_postings: dict[P, set[frozenset[P]]] = {}  # of the moved keys' meanings
    cur_holders: dict[frozenset[P], set[K]] = {}
    empty: frozenset[P] = frozenset()

    def held(t: frozenset[P]) -> int:
        return count.get(t, 0) + delta.get(t, 0)

    def claimed(mine: frozenset[P]) -> frozenset[P]:
        if len(mine) < 2:
            return empty
        if len(mine) <= LOOKUP_MAX:
            got = [t for t in strict_subsets(mine) if held(t) > 0]
        else:
            seen: set[frozenset[P]] = set()
            for p in mine:
                for size, ms in postings.get(p, {}).items():
                    if size < len(mine):
                        seen.update(s for s in ms if s < mine)
                seen.update(s for s in cur_postings.get(p, ()) if s < mine)
            got = [t for t in seen if held(t) > 0]
        return empty.union(*got) if got else empty

    def holders_of_supersets(t: frozenset[P]) -> Iterator[K]:
        for s in given_supersets(postings, t):
            for y in holders[s]:
                if y not in moved:
                    yield y
        lists = [cur_postings.get(p) for p in t]
        if t and all(lists):
            for s in min(lists, key=len):  # type: ignore[arg-type]
                if t < s:
                    yield from cur_holders[s]

    def move(c: K, mine: frozenset[P], rest: frozenset[P]) -> None:
        moved[c] = rest
        delta[mine] = delta.get(mine, 0) - 1
        delta[rest] = delta.get(rest, 0) + 1
        if mine in cur_holders:
            cur_holders[mine].discard(c)
            if not cur_holders[mine]:
                del cur_holders[mine]
                for p in mine:
                    cur_postings[p].discard(mine)
        if rest not in cur_holders:
            cur_holders[rest] = set()
            for p in rest:
                cur_postings.setdefault(p, set()).add(rest)
        cur_holders[rest].add(c)

    queue = [(rank[k], k) for k in start]
    heapq.heapify(queue)
    queued = set(start)
    later: set[K] = set()
    visits = 0
    while queue:
        while queue:
            r, c = heapq.heappop(queue)
            queued.discard(c)
            visits += 1
            if visits > budget:
                return None
            if count.get(raw[c], 0) > 1:  # its given meaning is another's too: it gives up nothing
                continue
            mine = moved.get(c) or raw[c]
            rest = mine - claimed(mine)
            if rest == mine or rest <= flat:
                continue
            move(c, mine, rest)
            later.add(c)  # a concept that changed is visited again in the next pass
            flips = [t for t, on in ((mine, held(mine) == 0), (rest, held(rest) == 1)) if on]
            for t in flips:
                for y in holders_of_supersets(t):
                    if y == c:
                        continue
                    if rank[y] > r:
                        if y not in queued:
                            queued.add(y)
                            heapq.heappush(queue, (rank[y], y))
                    else:
                        later.add(y)
        queue = [(rank[k], k) for k in later]
        heapq.heapify(queue)
        queued, later = set(later), set()
    return moved
