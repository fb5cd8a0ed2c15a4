"""MAC/FAC retrieval (Forbus, Gentner & Law 1995): cheap content vectors first, SME on the few best.

Why: asking *which* concept fits a scene means matching it against every generalization and
kept example of every concept, and SME on each is what costs. MAC ("many are called") scores
every description by the dot product of content vectors, counts of the functors SME would
pair (a predicate such as `r_left_of/2`, or a class symbol: `isa(O, cv_red)` is the attribute
`cv_red/1` to SME); FAC ("few are chosen") runs SME only on the best of them.

What is exact and what is not: SME only pairs expressions with identical functors, so a
description whose dot product with the probe is 0 can have no mapping, and dropping it never
changes an answer. Keeping only the `width` best of the rest is the heuristic part: a
description with fewer shared functors could, in principle, give a better match. The tests
compare against the exhaustive search (`ConceptMemory.fitting(..., exhaustive=True)`).

The index is kept up to date on store: `ContentIndex.touch(concept)` marks a concept whose
context changed, and its vectors are recomputed (only its own) before the next retrieval.
Vectors of descriptions that did not change (kept examples, by identity; generalizations,
by identity and size) are reused, so a store into a context of 1000 examples does not
recompute 1000 vectors.
"""

from __future__ import annotations

import heapq
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from aileen.analogy import sme
from aileen.analogy.sage import Bound, GeneralizationContext, SageParams
from aileen.memory.codec import gc_paused
from aileen.terms import Term

__all__ = ["Feature", "content_vector", "dot", "feature", "score_bound", "ContentIndex", "best_descriptions",
           "MAC_WIDTH", "StoreFilter"]

Feature = tuple[object, int]  # (functor, arity) as SME pairs them
Vector = dict[Feature, int]

#: Descriptions (or concepts) kept by the MAC stage; SME runs on these only.
MAC_WIDTH = 8


_ENTITY = sme.ENTITY_FUNCTORS


def _walk(t: Term, out: Vector) -> None:
    """Count `t`'s functors into `out` (t is an expression, not an entity)."""
    args = t.args
    if t.name == "isa" and len(args) == 2 and not args[1].args and isinstance(args[1].name, str):
        key: Feature = (args[1].name, 1)  # the class symbol: SME's attribute
        args = args[:1]
    else:
        key = (t.name, len(args))
    out[key] = out.get(key, 0) + 1
    for a in args:
        if a.args and a.name not in _ENTITY:
            _walk(a, out)


def content_vector(facts: Iterable[Term]) -> Vector:
    """Counts of the functors SME would pair: predicates by name and arity, and each `isa`
    class symbol as the attribute it becomes. Repeated facts count once (SME sees a set)."""
    out: Vector = {}
    for f in dict.fromkeys(facts):
        if f.args and f.name not in _ENTITY:
            _walk(f, out)
    return out


def dot(a: Vector, b: Vector) -> int:
    """The MAC score: the dot product of two content vectors."""
    if len(a) > len(b):
        a, b = b, a
    return sum(n * b.get(k, 0) for k, n in a.items())


def best_descriptions(scores: Sequence[tuple[int, int]], width: int) -> list[int]:
    """MAC's cut: of (score, position) pairs, the positions of the `width` best scores above
    0, best first, ties going to the earlier position (so the cut depends on the order things
    were stored in, never on hashing or timing; keeping every tie instead would run SME on
    hundreds of descriptions that share one functor with the probe)."""
    ranked = sorted((p for p in scores if p[0] > 0), key=lambda p: (-p[0], p[1]))
    return [p[1] for p in ranked[:width]]


@dataclass
class _Entry:
    """One concept's descriptions as the index has them."""

    kind: str
    descriptions: list[tuple[str, int, Vector]]  # (generalization|example, index, vector)
    example_cache: dict[int, tuple[list[Term], Vector]]  # id(example) -> (example, vector)
    gen_cache: dict[int, tuple[object, int, Vector]]  # id(generalization) -> (g, size, vector)


class ContentIndex:
    """Content vectors of every description of every concept, with an inverted index from
    functor to the concepts whose descriptions hold it (so a probe only touches concepts
    that share a functor with it)."""

    def __init__(self) -> None:
        self._entries: dict[str, _Entry] = {}
        self._postings: dict[Feature, dict[str, int]] = {}  # functor -> concept -> max count
        self._dirty: dict[str, tuple[str, GeneralizationContext]] = {}
        self._every: Mapping[str, Any] | None = None
        self._read_all: Callable[[], None] | None = None

    def touch(self, concept: str, kind: str, context: GeneralizationContext) -> None:
        """The concept's context changed (created, stored into, loaded): refresh it before
        the next retrieval."""
        self._dirty[concept] = (kind, context)

    def touch_all(self, concepts: Mapping[str, Any], read_all: "Callable[[], None] | None" = None) -> None:
        """Every concept of `concepts` (symbol -> an object with `kind` and `context`) is to
        be indexed before the next retrieval over all concepts, its context read only then
        (a memory loaded lazily from a compact file); `read_all` reads them all at once
        first. Asking for one concept's descriptions indexes that one only."""
        self._every = concepts
        self._read_all = read_all

    def descriptions(self, concept: str, params: SageParams) -> list[tuple[str, int, Vector]]:
        """The concept's descriptions' vectors, in `GeneralizationContext.descriptions` order."""
        if self._every is not None and concept not in self._entries and concept not in self._dirty:
            c = self._every.get(concept)
            if c is not None:
                self._dirty[concept] = (c.kind, c.context)
        self._refresh(params, everything=False)
        e = self._entries.get(concept)
        return [] if e is None else e.descriptions

    def _refresh(self, params: SageParams, everything: bool = True) -> None:
        if everything and self._every is not None:
            every, self._every = self._every, None
            if self._read_all is not None:
                self._read_all()
            for name, c in every.items():
                if name not in self._dirty and name not in self._entries:
                    self._dirty[name] = (c.kind, c.context)
        if len(self._dirty) > 1000:  # many new vectors: none of them garbage
            with gc_paused():
                self._index_dirty(params)
        else:
            self._index_dirty(params)

    def _index_dirty(self, params: SageParams) -> None:
        while self._dirty:
            concept, (kind, ctx) = self._dirty.popitem()
            old = self._entries.get(concept)
            if old is not None:
                for f in {f for _k, _i, v in old.descriptions for f in v}:
                    self._postings[f].pop(concept, None)
            entry = _Entry(kind, [], {}, {})
            for i, g in enumerate(ctx.generalizations):
                hit = old.gen_cache.get(id(g)) if old is not None else None
                if hit is not None and hit[0] is g and hit[1] == g.size:
                    vec = hit[2]
                else:
                    # (the facts that count, unordered: a vector of counts needs no order, and
                    # ordering them prints every fact, most of the index's first build)
                    low, size = params.probability - 1e-12, g.size
                    vec = content_vector([f for f, n in g.counts.items() if size and n / size >= low])
                entry.gen_cache[id(g)] = (g, g.size, vec)
                entry.descriptions.append(("generalization", i, vec))
            for i, ex in enumerate(ctx.examples):
                hit = old.example_cache.get(id(ex)) if old is not None else None
                vec = hit[1] if hit is not None and hit[0] is ex else content_vector(ex)
                entry.example_cache[id(ex)] = (ex, vec)
                entry.descriptions.append(("example", i, vec))
            self._entries[concept] = entry
            for _k, _i, v in entry.descriptions:
                for f, n in v.items():
                    post = self._postings.setdefault(f, {})
                    if n > post.get(concept, 0):
                        post[concept] = n

    def candidates(self, probe: Vector, params: SageParams, *, kind: str | None = None,
                   width: int = MAC_WIDTH, order: dict[str, int] | None = None) -> list[str]:
        """MAC over concepts: those sharing a functor with the probe, ranked by their best
        description's dot product with it, the `width` best; `order` (concept -> creation
        rank) breaks ties so the answer never depends on set or dict order."""
        self._refresh(params)
        rank = order or {}
        # Each concept's score: the probe against the concept's per-functor maximum over its
        # descriptions (its best description's dot product when it has one description, an
        # upper bound on it otherwise), summed straight from the postings.
        acc: dict[str, int] = {}
        get = acc.get
        for f, n in probe.items():
            for c, m in self._postings.get(f, {}).items():
                acc[c] = get(c, 0) + n * m
        if kind is not None:
            entries = self._entries
            acc = {c: v for c, v in acc.items() if entries[c].kind == kind}
        # the best scores first (few distinct scores: the probe's functors times small
        # counts), and within a score the concepts created first
        by_score: dict[int, list[str]] = {}
        for c, v in acc.items():
            by_score.setdefault(v, []).append(c)
        last = len(rank)
        out: list[str] = []
        for v in sorted(by_score, reverse=True):
            tied = by_score[v]
            need = width - len(out)
            out += heapq.nsmallest(need, tied, key=lambda c: (rank.get(c, last), c)) if len(tied) > need \
                else sorted(tied, key=lambda c: (rank.get(c, last), c))
            if len(out) >= width:
                break
        return out


def feature(fact: Term) -> Feature:
    """The functor SME pairs a fact by (see `content_vector`)."""
    if fact.name == "isa" and len(fact.args) == 2 and not fact.args[1].args and isinstance(fact.args[1].name, str):
        return (fact.args[1].name, 1)
    return (fact.name, len(fact.args))


def score_bound(base: Sequence[Term], probe: Vector, params: SageParams) -> float:
    """An upper bound on the structural score of any SME mapping of `base` onto a target whose
    content vector is `probe`: SME pairs only identical functors, and a mapping's score (its
    match hypotheses, trickle-down included) never exceeds the identity mapping's score of the
    base expressions it could pair: the self score of the base facts whose functor the target
    has, and of the expressions inside the others whose functor it has (`h(t, w(a, b))` onto a
    target with `w` but no `h`: `w(a, b)` may map on its own). Only without function
    predicates (non-identical functions may pair)."""
    sub: list[Term] = []

    def keep(t: Term) -> None:
        if sme.is_entity(t):
            return
        if feature(t) in probe:
            sub.append(t)  # whole: what it holds may map too
        elif not (t.name == "isa" and len(t.args) == 2):
            for a in t.args:  # it cannot map, but an expression inside it may, on its own
                keep(a)

    for f in base:
        keep(f)
    return sme.self_score(sub, functions=params.functions, params=params.sme) if sub else 0.0


@dataclass
class _Described:
    """One description as the store filter keeps it: its facts that count, its self score and
    its score bounds by the functors an example shares with it."""

    kind: str
    index: int
    facts: list[Term]
    self_score: float
    bounds: dict[frozenset[Feature], float]


@dataclass
class _Filed:
    """A concept's descriptions as the store filter has them, in `descriptions` order, with
    an inverted index from functor to the positions holding it."""

    owners: list[object]  # generalizations then examples, compared by identity
    sizes: list[int]  # each generalization's size when filed
    described: list[_Described]
    postings: dict[Feature, list[int]]


class StoreFilter:
    """SAGE's store with a content filter (`GeneralizationContext.add(..., bounds=...)`).

    Why: a store matches the new example with every description of the concept, and with a
    thousand kept examples that is a thousand SME runs. The filter is exact, not MAC's
    heuristic cut: a description sharing no functor with the example has no mapping, and for
    the others the similarity `2 score / (self(base) + self(example))` is bounded above with
    `score_bound`; SAGE runs SME from the highest bound down and stops when no bound left can
    reach the best similarity found. Per description the facts, self score and bounds by
    shared functors are computed once, and an inverted index from functor to description
    finds the ones sharing a functor with the example; a store that only appended examples
    (the usual kept example) extends the index instead of rebuilding it. Not with function
    predicates (`score_bound` does not hold there): `bounds` gives None, the store is
    exhaustive."""

    def __init__(self) -> None:
        self._filed: dict[str, _Filed] = {}

    def bounds(self, concept: str, context: GeneralizationContext, params: SageParams):  # noqa: ANN201
        """The `bounds` callable for one store into `context`, or None (exhaustive)."""
        if params.functions:
            return None
        return lambda example: self._ranked(concept, context, params, example)

    def _file(self, concept: str, ctx: GeneralizationContext, params: SageParams) -> _Filed:
        gens, exs = ctx.generalizations, ctx.examples
        sizes = [g.size for g in gens]
        old = self._filed.get(concept)
        n_old = len(old.owners) if old is not None else 0
        if (old is not None and old.sizes == sizes and n_old <= len(gens) + len(exs)
                and old.owners == [*gens, *exs[:n_old - len(gens)]]):
            # Identity first: list equality takes `is` as equal before comparing contents.
            if all(a is b for a, b in zip(old.owners, [*gens, *exs])):
                filed = old
            else:
                filed = None
        else:
            filed = None
        if filed is None:
            filed = _Filed([], sizes, [], {})
            self._filed[concept] = filed
        start = len(filed.owners)
        for pos, owner in enumerate([*gens, *exs][start:], start):
            if pos < len(gens):
                kind, i = "generalization", pos
                facts = owner.significant(params.probability)  # type: ignore[union-attr]
            else:
                kind, i = "example", pos - len(gens)
                facts = owner  # type: ignore[assignment]
            filed.owners.append(owner)
            filed.described.append(_Described(kind, i, facts, sme.self_score(
                facts, functions=params.functions, params=params.sme) if facts else 0.0, {}))
            for f in content_vector(facts):
                filed.postings.setdefault(f, []).append(pos)
        return filed

    def _ranked(self, concept: str, ctx: GeneralizationContext, params: SageParams,
                example: list[Term]) -> Iterator[Bound]:
        filed = self._file(concept, ctx, params)
        probe = content_vector(example)
        target_self = sme.self_score(example, functions=params.functions, params=params.sme)
        shared: dict[int, list[Feature]] = {}  # positions sharing a functor (no other can map)
        for f in probe:
            for pos in filed.postings.get(f, ()):
                got = shared.get(pos)
                if got is None:
                    shared[pos] = [f]
                else:
                    got.append(f)
        ranked: list[tuple[float, int]] = []
        described = filed.described
        bound_of = score_bound
        for pos, fs in shared.items():
            d = described[pos]
            key = frozenset(fs)
            sb = d.bounds.get(key)
            if sb is None:
                sb = d.bounds[key] = bound_of(d.facts, probe, params)
            denom = d.self_score + target_self
            ranked.append((-2.0 * sb / denom if denom > 0 else 0.0, pos))
        ranked.sort()
        # Made one at a time: the store usually stops after the first few.
        return (Bound(min(1.0, -s), described[pos].kind, described[pos].index, described[pos].facts)
                for s, pos in ranked)
