"""Mutual exclusivity over the visual concepts' meanings, without comparing every pair.

Why: a visual concept's meaning is the set of percepts it requires; exclusivity lets a
meaning give up the percepts of any strictly smaller meaning, repeated to a fixpoint (so a
word pinned down frees the words taught with it), and never down to nothing. Done naively,
every concept looks at every other one on every pass: quadratic in the number of concepts,
after every store. But the answer for a concept depends only on its own meaning and on
*which* meanings the other concepts hold now, and a vocabulary of percepts admits few
distinct meanings however many words share them, and a meaning has few percepts. So the
pass keeps an index from each meaning held to the number of concepts holding it, finds what
a meaning must give up by looking up its strict subsets in that index (2^k lookups for k
percepts, instead of a scan of every other concept), and memoises the answer per meaning
until a meaning appears or disappears. A pass is then linear in the concepts.

The result is identical to the naive pass, including its order: concepts are visited in the
order given and each sees the others' meanings as updated so far in the same pass (a pass
over A = B = {red, box} and C = {red} leaves A = {box} but B = {red, box}: B sees A's new
meaning {box} and C's {red}, and giving both up would leave nothing).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Hashable, Mapping
from typing import TypeVar

__all__ = ["exclusive"]

K = TypeVar("K", bound=Hashable)
P = TypeVar("P", bound=Hashable)


def exclusive(meanings: Mapping[K, frozenset[P]]) -> dict[K, frozenset[P]]:
    """Mutual exclusivity to a fixpoint: each meaning (in the mapping's order) gives up the
    percepts of every strictly smaller non-empty meaning that another concept holds, unless
    that would leave nothing; repeated until no meaning changes."""
    m: dict[K, frozenset[P]] = dict(meanings)
    held: Counter[frozenset[P]] = Counter(m.values())
    smaller: dict[frozenset[P], frozenset[P]] = {}  # meaning -> union of held meanings below it

    def claimed(mine: frozenset[P]) -> frozenset[P]:
        got = smaller.get(mine)
        if got is None:
            if (1 << len(mine)) <= 4 * len(held):  # few percepts: look up each strict subset
                items = list(mine)
                below = (frozenset(x for j, x in enumerate(items) if bits >> j & 1)
                         for bits in range(1, (1 << len(items)) - 1))
                got = frozenset().union(*(t for t in below if held.get(t, 0) > 0))
            else:  # many percepts, few meanings held: scan those
                got = frozenset().union(*(t for t, n in held.items() if n > 0 and t and t < mine))
            smaller[mine] = got
        return got

    changed = True
    while changed:
        changed = False
        for c, mine in m.items():
            rest = mine - claimed(mine)
            if rest and rest != mine:
                m[c] = rest
                held[mine] -= 1
                held[rest] += 1
                if held[mine] == 0 or held[rest] == 1:  # the set of meanings held changed
                    smaller.clear()
                changed = True
    return m
