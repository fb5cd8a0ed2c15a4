"""Mutual exclusivity over the visual concepts' meanings, without comparing every pair: the
pass from scratch (`exclusive`), the specification that `claims.Exclusivity` keeps up to date.

Why: a visual concept's meaning is the set of percepts it requires; exclusivity lets a
meaning give up the percepts of any strictly smaller meaning, repeated to a fixpoint (so a
word pinned down frees the words taught with it), and never down to nothing (nor, for the
visual words, down to percepts every object has: see `exclusive`). Done naively,
every concept looks at every other one on every pass: quadratic in the number of concepts,
after every store. But the answer for a concept depends only on its own meaning and on
*which* meanings the other concepts hold now, and a vocabulary of percepts admits few
distinct meanings however many words share them, and a meaning has few percepts. So the
pass keeps an index from each meaning held to the number of concepts holding it, finds what
a meaning must give up by looking up its strict subsets in that index (2^k lookups for k
percepts, instead of a scan of every other concept; the subsets of each meaning are listed
once). A pass is then linear in the concepts.

The result is identical to the naive pass, including its order: concepts are visited in the
order given and each sees the others' meanings as updated so far in the same pass (a pass
over A = {red, box}, B = {red, box, large} and C = {red} leaves A = {box} but B = {red, box,
large}: B sees A's new meaning {box} and C's {red}, and giving both up would leave {large}
alone, which it may; with `uninformative` = {large} it keeps all three).

Two concepts with the same given meaning give up nothing (`exclusive`): their examples show
the same things, so exclusivity cannot tell which of them names what, and the order of the
pass would decide. "red" and "box", each shown once on a red box, stay as they were when
"crimson" is shown on a red box and a red sphere ({red} alone); before, "red" (first in the
pass) gave up its colour to the synonym and kept the box, and a modifier that means a shape
taught the lexicon that modifiers name shapes (syntax then tells "red" from "box").

Split off `claims.py` (which re-exports `exclusive`) so that the pass, which every caller and
test reads as the specification, stands apart from the incremental structure built on it.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Hashable, Mapping
from functools import lru_cache
from typing import TypeVar

__all__ = ["exclusive", "strict_subsets", "K", "P"]


@lru_cache(maxsize=1 << 16)
def strict_subsets(mine: frozenset) -> tuple[frozenset, ...]:
    """The non-empty strict subsets of a meaning (listed once per meaning, across passes)."""
    items = list(mine)
    return tuple(frozenset(x for j, x in enumerate(items) if bits >> j & 1)
                 for bits in range(1, (1 << len(items)) - 1))

K = TypeVar("K", bound=Hashable)
P = TypeVar("P", bound=Hashable)


def exclusive(meanings: Mapping[K, frozenset[P]],
              uninformative: frozenset[P] = frozenset()) -> dict[K, frozenset[P]]:
    """Mutual exclusivity to a fixpoint: each meaning (in the mapping's order) gives up the
    percepts of every strictly smaller non-empty meaning that another concept holds, unless
    that would leave nothing, or only `uninformative` percepts (ones every object has, which
    would make the meaning hold of everything: the meaning then keeps what the others claim,
    a conjunction or a synonym of them), or its given meaning is another concept's given
    meaning too (the module doc); repeated until no meaning changes."""
    m: dict[K, frozenset[P]] = dict(meanings)
    held: Counter[frozenset[P]] = Counter(m.values())
    shared = {t for t, n in held.items() if n > 1}  # given meanings two concepts hold
    empty: frozenset[P] = frozenset()
    scan = 4 * len(held)

    def claimed(mine: frozenset[P]) -> frozenset[P]:
        if (1 << len(mine)) <= scan:  # few percepts: look its strict subsets up
            got = [t for t in strict_subsets(mine) if held.get(t, 0) > 0]
        else:  # many percepts, few meanings held: scan those instead
            got = [t for t, n in held.items() if n > 0 and t and t < mine]
        return empty.union(*got) if got else empty

    changed = True
    while changed:
        changed = False
        for c, mine in m.items():
            if meanings[c] in shared:
                continue
            rest = mine - claimed(mine)
            if rest != mine and not rest <= uninformative:
                m[c] = rest
                held[mine] -= 1
                held[rest] += 1
                changed = True
    return m

