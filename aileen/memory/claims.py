"""Mutual exclusivity over the visual concepts' meanings, kept up to date as they change
(`Exclusivity`), with the pass from scratch it keeps up to date (`exclusive`).

Why: the lexicon asks for the exclusive meanings after every store; the class below says how
it avoids a pass over every concept. The module is one of three, split because it had grown
past one job (one module, one job): the pass from scratch, the specification every caller and
test reads, is `claims_pass.py`; the held meanings' subsets and supersets and the replay of
one part's pass, the computation, are `claims_replay.py`; this module decides what to compute
again after an update (which parts, replay or plain pass, many changes at once) and keeps the
structure. Every name once defined here is still importable from here (`exclusive`,
`_strict_subsets`, `_LOOKUP_MAX`), and the thresholds below stay here, where they are read
(tests/test_claims.py sets them to force each way).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Mapping
from types import MappingProxyType
from typing import Generic

from aileen.memory.claims_pass import K, P, exclusive
from aileen.memory.claims_pass import strict_subsets as _strict_subsets  # noqa: F401  (re-exported)
from aileen.memory.claims_replay import LOOKUP_MAX as _LOOKUP_MAX  # noqa: F401  (re-exported)
from aileen.memory.claims_replay import given_strict_subset_held, given_supersets, replay

__all__ = ["exclusive", "Exclusivity"]

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
        count = self._count
        self._acting = {k for k, m in self._raw.items() if given_strict_subset_held(count, postings, m)}
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
            for s in given_supersets(self._postings, t):
                recheck.update(self._holders[s])
        for k in recheck:
            if given_strict_subset_held(self._count, self._postings, self._raw[k]):
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

    # ------------------------------------------------------------ one part's pass
    def _compute(self, root: P) -> dict[K, frozenset[P]]:
        """The part's concepts whose exclusive meaning differs from the given one: replayed
        from its acting concepts, or (a replay past its budget) a plain pass over the part."""
        keys = self._members[root]
        acting = self._acting
        start = [k for k in keys if k in acting] if len(keys) < len(acting) else [k for k in acting if k in keys]
        if not start:
            return {}
        moved = replay(start, _REPLAY_BUDGET * len(keys) + _REPLAY_SLACK, raw=self._raw, rank=self._rank,
                       count=self._count, flat=self._flat, postings=self._postings, holders=self._holders)
        if moved is not None:
            return moved
        raw = self._raw
        out = exclusive({k: raw[k] for k in sorted(keys, key=self._rank.__getitem__)}, self._flat)
        return {k: m for k, m in out.items() if m != raw[k]}
