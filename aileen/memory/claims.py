"""Mutual exclusivity over the visual concepts' meanings, without comparing every pair.

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
over A = B = {red, box} and C = {red} leaves A = {box} but B = {red, box}: B sees A's new
meaning {box} and C's {red}, and giving both up would leave nothing).
"""

from __future__ import annotations

import heapq
from collections import Counter
from collections.abc import Hashable, Iterable, Iterator, Mapping
from functools import lru_cache
from types import MappingProxyType
from typing import Generic, TypeVar

__all__ = ["exclusive", "Exclusivity"]


@lru_cache(maxsize=1 << 16)
def _strict_subsets(mine: frozenset) -> tuple[frozenset, ...]:
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
    a conjunction or a synonym of them); repeated until no meaning changes."""
    m: dict[K, frozenset[P]] = dict(meanings)
    held: Counter[frozenset[P]] = Counter(m.values())
    empty: frozenset[P] = frozenset()
    scan = 4 * len(held)

    def claimed(mine: frozenset[P]) -> frozenset[P]:
        if (1 << len(mine)) <= scan:  # few percepts: look its strict subsets up
            got = [t for t in _strict_subsets(mine) if held.get(t, 0) > 0]
        else:  # many percepts, few meanings held: scan those instead
            got = [t for t, n in held.items() if n > 0 and t and t < mine]
        return empty.union(*got) if got else empty

    changed = True
    while changed:
        changed = False
        for c, mine in m.items():
            rest = mine - claimed(mine)
            if rest != mine and not rest <= uninformative:
                m[c] = rest
                held[mine] -= 1
                held[rest] += 1
                changed = True
    return m


#: Meanings of up to this many percepts find their held strict subsets by looking each one up
#: (2^k - 2 lookups); larger ones through the percepts' postings.
_LOOKUP_MAX = 6

#: A replay that has visited this many times the concepts of its part (and `_REPLAY_SLACK`
#: more) gives way to a plain pass over the part.
_REPLAY_BUDGET = 2
_REPLAY_SLACK = 16
#: An update that changes more than one in this many meanings is one plain pass over every
#: concept (`_bulk`: the lexicon's first reading of a memory), not kept up to date.
_BULK_SHARE = 8


class Exclusivity(Generic[K, P]):
    """`exclusive` kept up to date while meanings change a few at a time: `update` sets, adds
    or removes meanings and returns the keys whose exclusive meaning changed; `meanings()` is
    always exactly what `exclusive` gives for the meanings now held (same order, same answers:
    tests/test_claims.py holds them equal over random update sequences).

    Why: the lexicon asks for the exclusive meanings after every store, and a store changes
    one concept's meaning; a pass over every concept costs what the lexicon has grown to
    (65-73 ms at 10,000 concepts). Two facts make most of that pass unnecessary:

    - **Parts that never meet.** A concept gives up only percepts of strict subsets of its
      meaning, and meanings only shrink, so two concepts can affect each other only through
      shared percepts. The percepts are grouped by the meanings that hold them together
      (union-find; a group is never split, which only makes the parts larger than they need
      be), and the concepts with them. The pass over every concept gives, on each part, what
      a pass over that part alone gives (the order within it is kept, and the extra passes a
      part sees while others still change change nothing). An update recomputes only the
      parts whose meanings it changed: a new word about colours and shapes does not touch
      the words about sizes or the words of another vocabulary.
    - **Who acts.** Within a part, a concept can give up percepts only while another holds a
      strict subset of its meaning. The set of such *acting* concepts is kept up to date on
      each change (looking only at the changed meanings' strict subsets and supersets), and
      the pass is replayed from the given meanings visiting only the visits that can change
      something, in the same order and passes: a concept's visit depends only on its meaning
      and on which of its strict subsets are held, so a visit is skipped exactly when neither
      changed since its last one (in the first pass: when it does not act). When a meaning
      starts or stops being held, the concepts holding a strict superset of it are visited:
      later in this pass if they come after the one that changed, else in the next pass. A
      replay that cascades over most of its part (`_REPLAY_BUDGET`) gives way to a plain pass
      over the part, which gives the same answer.
    """

    def __init__(self) -> None:
        self._raw: dict[K, frozenset[P]] = {}  # the given meanings, in pass order
        self._rank: dict[K, int] = {}
        self._next_rank = 0
        self._count: dict[frozenset[P], int] = {}  # given meaning -> concepts holding it
        self._holders: dict[frozenset[P], set[K]] = {}
        self._postings: dict[P, dict[int, set[frozenset[P]]]] = {}  # percept -> size -> meanings
        self._acting: set[K] = set()
        self._flat: frozenset[P] = frozenset()
        self._result: dict[K, frozenset[P]] = {}
        # The concepts whose exclusive meaning differs from the given one, while not prepared.
        self._moved_all: dict[K, frozenset[P]] = {}
        # Prepared for small updates (`_prepare`): who holds which meaning, the meanings by
        # percept, and the parts: a union-find over percepts, each part's concepts and moved ones.
        self._prepared = False
        self._parent: dict[P, P] = {}
        self._members: dict[P, set[K]] = {}  # part (its root percept) -> concepts
        self._moved: dict[P, dict[K, frozenset[P]]] = {}  # part -> concepts whose meaning moved
        self._views = (MappingProxyType(self._result), MappingProxyType(self._raw))

    def __getstate__(self) -> dict:
        state = dict(self.__dict__)
        del state["_views"]  # (views cannot be copied or pickled; made again from the dicts)
        return state

    def __setstate__(self, state: dict) -> None:
        self.__dict__.update(state)
        self._views = (MappingProxyType(self._result), MappingProxyType(self._raw))

    # ------------------------------------------------------------ reading
    def meanings(self) -> Mapping[K, frozenset[P]]:
        """The exclusive meanings (a live read-only view, in pass order; the same object
        every time)."""
        return self._views[0]

    def given(self) -> Mapping[K, frozenset[P]]:
        """The meanings as given (a live read-only view)."""
        return self._views[1]

    def acting(self) -> frozenset[K]:
        """The concepts whose given meaning has a held non-empty strict subset."""
        self._prepare()
        return frozenset(self._acting)

    def part_of(self, key: K) -> frozenset[K]:
        """The concepts of `key`'s part (those it may affect or be affected by)."""
        m = self._raw.get(key)
        if not m:
            return frozenset({key}) if m is not None else frozenset()
        self._prepare()
        return frozenset(self._members[self._find(next(iter(m)))])

    # ------------------------------------------------------------ many changes at once
    def _prepare(self) -> None:
        """Build what small updates need, from the meanings held (once, after a bulk update)."""
        if self._prepared:
            return
        holders: dict[frozenset[P], set[K]] = {}
        for k, m in self._raw.items():
            got = holders.get(m)
            if got is None:
                holders[m] = {k}
            else:
                got.add(k)
        postings: dict[P, dict[int, set[frozenset[P]]]] = {}
        for m in holders:
            for p in m:
                postings.setdefault(p, {}).setdefault(len(m), set()).add(m)
            if m:
                self._join(m)
        self._holders, self._postings = holders, postings
        self._acting = {k for k, m in self._raw.items() if self._given_strict_subset_held(m)}
        find, members, moved = self._find, self._members, self._moved
        for k, m in self._raw.items():
            if m:
                members[find(next(iter(m)))].add(k)
        for k, m in self._moved_all.items():
            moved[find(next(iter(self._raw[k])))][k] = m
        self._moved_all = {}
        self._prepared = True

    def _unprepare(self) -> None:
        """Drop what small updates need (a bulk update follows): the moved meanings stay."""
        if not self._prepared:
            return
        self._moved_all = {k: m for part in self._moved.values() for k, m in part.items()}
        self._holders, self._postings = {}, {}
        self._parent, self._members, self._moved = {}, {}, {}
        self._prepared = False

    def _bulk(self, changes: Mapping[K, frozenset[P] | None],
              uninformative: frozenset[P] | None) -> dict[K, frozenset[P] | None]:
        """`update` for many changes at once: one plain pass over every concept."""
        self._unprepare()
        raw, rank, count, result = self._raw, self._rank, self._count, self._result
        before: dict[K, frozenset[P] | None] = {}
        if not raw and None not in changes.values():  # the first reading: all at once
            fresh = {k: frozenset(m) for k, m in changes.items()}  # type: ignore[arg-type]
            raw.update(fresh)
            result.update(fresh)
            rank.update(zip(fresh, range(self._next_rank, self._next_rank + len(fresh))))
            self._next_rank += len(fresh)
            count.update(Counter(fresh.values()))
            before = dict.fromkeys(fresh)
            changes = {}
        for k, new in changes.items():
            old = raw.get(k)
            if new is not None:
                new = frozenset(new)
            if new == old:
                continue
            before[k] = result.get(k)
            if old is not None:
                n = count[old] - 1
                if n:
                    count[old] = n
                else:
                    del count[old]
            if new is None:
                if old is not None:
                    del raw[k], rank[k], result[k]
                    self._moved_all.pop(k, None)
                continue
            if old is None:
                rank[k] = self._next_rank
                self._next_rank += 1
            raw[k] = result[k] = new
            count[new] = count.get(new, 0) + 1
        flat_changed = uninformative is not None and frozenset(uninformative) != self._flat
        if flat_changed:
            self._flat = frozenset(uninformative)  # type: ignore[arg-type]
        if not before and not flat_changed:
            return {}
        self._acting = set()  # (found again by `_prepare`)
        # (the given meanings are in pass order: a new key is added last, a changed one stays)
        out = exclusive(raw, self._flat)
        old_moved = self._moved_all
        self._moved_all = {k: m for k, m in out.items() if m != raw[k]}
        changed: dict[K, frozenset[P] | None] = {}
        for k in {*old_moved, *self._moved_all}:
            if k in before or k not in raw:
                continue
            now = self._moved_all.get(k, raw[k])
            if now != result[k]:
                changed[k] = result[k]
                result[k] = now
        for k, was in before.items():
            if k in raw:
                result[k] = self._moved_all.get(k, raw[k])
                if result[k] != was:
                    changed[k] = was
            else:
                changed[k] = was
        return changed

    # ------------------------------------------------------------ changing
    def update(self, changes: Mapping[K, frozenset[P] | None],
               uninformative: frozenset[P] | None = None) -> dict[K, frozenset[P] | None]:
        """Set each key's meaning (`None` removes the key; a new key goes last in the order)
        and, when given, the `uninformative` percepts. Returns the keys whose exclusive
        meaning changed (removed keys included), each with its exclusive meaning before
        (None for a new key)."""
        if (len(changes) * _BULK_SHARE > len(self._raw)
                or (uninformative is not None and frozenset(uninformative) != self._flat)):
            return self._bulk(changes, uninformative)
        self._prepare()
        flipped: list[frozenset[P]] = []  # meanings that started or stopped being held
        touched: list[K] = []
        before: dict[K, frozenset[P] | None] = {}
        parts: set[P] = set()  # roots of the parts to compute again (before unions)
        for k, new in changes.items():
            old = self._raw.get(k)
            if new is not None:
                new = frozenset(new)
            if new == old:  # unchanged, or the removal of a key never held
                continue
            before[k] = self._result.get(k)
            if old is not None:
                self._release(k, old, flipped)
                if old:
                    root = self._find(next(iter(old)))
                    self._members[root].discard(k)
                    self._moved[root].pop(k, None)
                    parts.add(root)
            if new is None:
                if old is not None:
                    del self._raw[k], self._rank[k], self._result[k]
                    self._acting.discard(k)
                continue
            if old is None:
                self._rank[k] = self._next_rank
                self._next_rank += 1
            self._result[k] = new
            self._raw[k] = new
            self._hold(k, new, flipped)
            if new:
                root = self._join(new)
                self._members[root].add(k)
                parts.add(root)
            touched.append(k)
        if not before:  # (a change of the uninformative percepts went to `_bulk`)
            return {}
        # who acts now: the changed keys, and the holders of strict supersets of a meaning
        # that started or stopped being held
        recheck = set(touched)
        for t in flipped:
            for s in self._given_supersets(t):
                recheck.update(self._holders[s])
        for k in recheck:
            if self._given_strict_subset_held(self._raw[k]):
                self._acting.add(k)
            else:
                self._acting.discard(k)
        changed: dict[K, frozenset[P] | None] = {}
        for root in {self._find(r) for r in parts}:
            old_moved = self._moved[root]
            new_moved = self._compute(root)
            self._moved[root] = new_moved
            for k in {*old_moved, *new_moved}:
                if k in before:
                    continue
                now, was = new_moved.get(k, self._raw[k]), self._result[k]
                if now != was:
                    self._result[k] = now
                    changed[k] = was
        for k, was in before.items():
            if k not in self._raw:
                changed[k] = was
                continue
            if self._raw[k]:
                now = self._moved[self._find(next(iter(self._raw[k])))].get(k, self._raw[k])
                self._result[k] = now
            if self._result[k] != was:
                changed[k] = was
        return changed

    def _hold(self, k: K, m: frozenset[P], flipped: list[frozenset[P]]) -> None:
        n = self._count.get(m, 0)
        self._count[m] = n + 1
        self._holders.setdefault(m, set()).add(k)
        if n == 0:
            for p in m:
                self._postings.setdefault(p, {}).setdefault(len(m), set()).add(m)
            flipped.append(m)

    def _release(self, k: K, m: frozenset[P], flipped: list[frozenset[P]]) -> None:
        n = self._count[m] - 1
        self._holders[m].discard(k)
        if n:
            self._count[m] = n
            return
        del self._count[m], self._holders[m]
        for p in m:
            by_size = self._postings[p]
            by_size[len(m)].discard(m)
            if not by_size[len(m)]:
                del by_size[len(m)]
            if not by_size:
                del self._postings[p]
        flipped.append(m)

    # ------------------------------------------------------------ parts (union-find)
    def _find(self, p: P) -> P:
        parent = self._parent
        root = p
        while parent[root] != root:
            root = parent[root]
        while parent[p] != root:
            parent[p], p = root, parent[p]
        return root

    def _join(self, m: frozenset[P]) -> P:
        """Put the percepts of `m` in one part; returns its root."""
        root: P | None = None
        for p in m:
            if p not in self._parent:
                self._parent[p] = p
                self._members[p] = set()
                self._moved[p] = {}
            r = self._find(p)
            if root is None or r == root:
                root = r
                continue
            if len(self._members[r]) > len(self._members[root]):
                root, r = r, root
            self._parent[r] = root
            self._members[root] |= self._members.pop(r)
            self._moved[root].update(self._moved.pop(r))
        assert root is not None
        return root

    # ------------------------------------------------------------ subsets and supersets
    def _given_supersets(self, t: frozenset[P]) -> Iterator[frozenset[P]]:
        """The given meanings held that are strict supersets of `t` (non-empty)."""
        if not t:
            return
        lists = [self._postings.get(p) for p in t]
        if any(x is None for x in lists):
            return
        best = min(lists, key=lambda by: sum(len(s) for s in by.values()))  # type: ignore[union-attr]
        for size, ms in best.items():  # type: ignore[union-attr]
            if size > len(t):
                for s in ms:
                    if t < s:
                        yield s

    def _given_strict_subset_held(self, mine: frozenset[P]) -> bool:
        if len(mine) < 2:
            return False
        count = self._count
        if len(mine) == 2:
            return any(frozenset((p,)) in count for p in mine)
        if len(mine) <= _LOOKUP_MAX:
            return any(t in count for t in _strict_subsets(mine))
        for p in mine:
            for size, ms in self._postings.get(p, {}).items():
                if size < len(mine) and any(s < mine for s in ms):
                    return True
        return False

    # ------------------------------------------------------------ one part's pass
    def _compute(self, root: P) -> dict[K, frozenset[P]]:
        """The part's concepts whose exclusive meaning differs from the given one: replayed
        from its acting concepts, or (a replay past its budget) a plain pass over the part."""
        keys = self._members[root]
        acting = self._acting
        start = [k for k in keys if k in acting] if len(keys) < len(acting) else [k for k in acting if k in keys]
        if not start:
            return {}
        moved = self._replay(start, _REPLAY_BUDGET * len(keys) + _REPLAY_SLACK)
        if moved is not None:
            return moved
        raw = self._raw
        out = exclusive({k: raw[k] for k in sorted(keys, key=self._rank.__getitem__)}, self._flat)
        return {k: m for k, m in out.items() if m != raw[k]}

    def _replay(self, start: list[K], budget: int) -> dict[K, frozenset[P]] | None:
        """`exclusive` from the given meanings, visiting only the visits that can change
        something, from the acting concepts `start` (see the class's docstring); returns the
        keys whose meaning moved, or None past `budget` visits."""
        raw, rank, count, flat = self._raw, self._rank, self._count, self._flat
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
            if len(mine) <= _LOOKUP_MAX:
                got = [t for t in _strict_subsets(mine) if held(t) > 0]
            else:
                seen: set[frozenset[P]] = set()
                for p in mine:
                    for size, ms in self._postings.get(p, {}).items():
                        if size < len(mine):
                            seen.update(s for s in ms if s < mine)
                    seen.update(s for s in cur_postings.get(p, ()) if s < mine)
                got = [t for t in seen if held(t) > 0]
            return empty.union(*got) if got else empty

        def holders_of_supersets(t: frozenset[P]) -> Iterator[K]:
            for s in self._given_supersets(t):
                for y in self._holders[s]:
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
