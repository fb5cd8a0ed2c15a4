"""The analogical concept memory: create, store, query and project (the paper's section 4).

Why: concepts in AILEEN are generalization contexts (SAGE over SME), not rules. The agent
creates a concept when a word is new, stores examples when comprehension fails, queries the
memory to recognise concepts in a scene (candidate inferences that fit a pattern, accepted
when the match is similar enough) and projects an action concept onto the episodic trace of
what it has done so far, to get the next state it should bring about.

Everything here is pure computation on `Term`s except `save` / `load`.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Collection, Iterable
from dataclasses import dataclass, field, replace
from functools import lru_cache
from typing import Any

from aileen.analogy import sme
from aileen.analogy.sage import Generalization, GeneralizationContext, SageParams
from aileen.errors import UserError
from aileen.memory import codec, compact, nearmiss, persist, retrieval
from aileen.terms import Term, TermSyntaxError, as_term, parse, sort_key, unify

__all__ = [
    "KINDS",
    "Concept",
    "StoreResult",
    "Inference",
    "Projection",
    "ConceptMemory",
]

#: Concept kinds the agent creates.
from aileen.memory.kinds import KINDS  # noqa: E402  (re-exported)


class Concept:
    """A concept symbol, its kind and its generalization context, with the scenes the trainer
    said are not this concept although the agent thought so (`near_misses`,
    memory/nearmiss.py).

    A concept loaded from a compact file (`memory/compact.py`) holds only where it lies in
    the file until its context or near misses are first asked for: a memory of 100,000
    concepts loads in a fraction of a second and costs little at rest."""

    __slots__ = ("symbol", "kind", "_context", "_near_misses", "_source", "_at")

    def __init__(self, symbol: str, kind: str, context: GeneralizationContext | None = None,
                 near_misses: list[list[Term]] | None = None, *,
                 source: "compact.Source | None" = None, at: int = 0) -> None:
        self.symbol = symbol
        self.kind = kind
        self._source = source
        self._at = at
        if source is None:
            self._context = context if context is not None else GeneralizationContext(symbol)
            self._near_misses = near_misses if near_misses is not None else []

    def _read(self) -> None:
        assert self._source is not None
        self._context, self._near_misses = self._source.read(self._at, self.symbol)
        self._source = None

    @property
    def loaded(self) -> bool:
        """Whether the context has been made into terms (always, unless read from a compact file)."""
        return self._source is None

    @property
    def context(self) -> GeneralizationContext:
        if self._source is not None:
            self._read()
        return self._context

    @context.setter
    def context(self, value: GeneralizationContext) -> None:
        if self._source is not None:
            self._read()
        self._context = value

    @property
    def near_misses(self) -> list[list[Term]]:
        if self._source is not None:
            self._read()
        return self._near_misses

    @near_misses.setter
    def near_misses(self, value: list[list[Term]]) -> None:
        if self._source is not None:
            self._read()
        self._near_misses = value

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Concept):
            return NotImplemented
        return (self.symbol, self.kind, self.context, self.near_misses) == (
            other.symbol, other.kind, other.context, other.near_misses)

    __hash__ = None  # type: ignore[assignment]  (mutable, as the dataclass it replaces)

    def __repr__(self) -> str:
        if self._source is not None:
            return f"Concept(symbol={self.symbol!r}, kind={self.kind!r}, <not read yet>)"
        return (f"Concept(symbol={self.symbol!r}, kind={self.kind!r}, context={self._context!r}, "
                f"near_misses={self._near_misses!r})")


@dataclass(frozen=True)
class StoreResult:
    """Counts in the concept's context after a store, and what happened to the example."""

    generalizations: int
    examples: int
    action: str = "kept"  # "kept", "merged" or "new_generalization"
    similarity: float = 0.0


@dataclass
class Inference:
    """A fact the memory infers about a scene, with the evidence behind it."""

    fact: Term
    similarity: float
    concept: str
    source: str  # "generalization" or "example"
    index: int
    binding: dict[Term, Term]
    mapping: sme.Mapping = field(repr=False)


@dataclass
class Projection:
    """The next desired state of an action, projected from the trace so far."""

    facts: list[Term]
    complete: bool
    similarity: float
    time_point: Term | None = None  # the skolem time point the facts hold at
    after: Term | None = None  # the trace's latest time point
    unresolved: list[Term] = field(default_factory=list)  # next-state facts about unknown entities
    source: str | None = None
    index: int | None = None
    mapping: sme.Mapping | None = field(default=None, repr=False)


def _has_skolem(t: Term) -> bool:
    return any(s.name == "skolem" and len(s.args) == 1 for s in t)


_ANY = Term("_")


@lru_cache(maxsize=4096)  # interned terms; a scene asks the same shapes many times
def _skeleton(pattern: Term) -> Term:
    """The pattern with every entity argument made anonymous: `r_left_of(o5,Y)` ->
    `r_left_of(_,_)`, `isa(o4,r_red)` -> `isa(_,r_red)`. The facts of a description that
    have this shape are the ones a query asks about, whichever objects it names."""
    if sme.is_entity(pattern):
        return _ANY
    if pattern.name == "isa" and len(pattern.args) == 2 and not pattern.args[1].args:
        return Term("isa", (_skeleton(pattern.args[0]), pattern.args[1]))
    return Term(pattern.name, tuple(_skeleton(a) for a in pattern.args))


def _pattern_concept(pattern: Term) -> str | None:
    if pattern.name == "isa" and len(pattern.args) == 2 and not pattern.args[1].args:
        c = pattern.args[1]
        if not c.is_variable:
            return str(c)
    if isinstance(pattern.name, str):
        return pattern.name
    return None


#: A context with more descriptions than this is pre-filtered by content vectors on query.
CONTEXT_MAC = 16

#: How many changes the memory remembers for `changes_since`; a reader further behind than
#: this is told to read everything again.
CHANGE_LOG = 4096


class ConceptMemory:
    """Named concepts, each a SAGE generalization context, sharing one `SageParams`."""

    def __init__(self, params: SageParams | None = None) -> None:
        self.params = params or SageParams()
        self._concepts: dict[str, Concept] = {}
        self._order: dict[str, int] = {}  # each concept's place in the order of creation
        # JSON data that other memories keep in the same file (the agent's lexicon: where
        # words stood in phrases, which sense each percept comes from); opaque here.
        self.annotations: dict[str, Any] = {}
        # MAC/FAC: content vectors of every description, refreshed per concept on store.
        self._index = retrieval.ContentIndex()
        # Per concept, per description and query shape: its facts, the query's denominator,
        # its functors and score bounds by shared functors (`_prefilter`); dropped on store.
        self._bounds: dict[str, dict[tuple, tuple]] = {}
        self._last_probe: tuple[tuple[Term, ...], dict] = ((), {})
        # SAGE's store: per description, what its exact content filter needs (`store`).
        self._store_filter = retrieval.StoreFilter()
        # The concepts created or stored into, in order (`changes_since`), from change number
        # `_log_start` on.
        self._log: list[str] = []
        self._log_start = 0

    # ------------------------------------------------------------------ contents
    def __contains__(self, symbol: object) -> bool:
        return str(symbol) in self._concepts

    def __len__(self) -> int:
        return len(self._concepts)

    def concepts(self) -> list[Concept]:
        return list(self._concepts.values())

    def has(self, symbol: str | Term) -> bool:
        """Whether the concept has been created."""
        return str(symbol) in self._concepts

    def changes_since(self, mark: int | None) -> tuple[int, dict[str, str] | None]:
        """The concepts created or stored into since `mark` (a number this method returned
        before), each with its kind, in the order they were first touched, and the mark to ask
        with next time. `None` in place of the concepts when `mark` is None or too far behind
        (the memory keeps the last `CHANGE_LOG` changes): read every concept again.

        Why: what is derived from every concept's descriptions (the agent's lexicon) is kept
        up to date from the concepts that changed, whoever stored into them, instead of being
        made again after every store."""
        now = self._log_start + len(self._log)
        if mark is None or not self._log_start <= mark <= now:
            return now, None
        touched = dict.fromkeys(self._log[mark - self._log_start:])
        return now, {s: self._concepts[s].kind for s in touched if s in self._concepts}

    def _changed(self, symbol: str) -> None:
        self._log.append(symbol)
        if len(self._log) > CHANGE_LOG:
            drop = len(self._log) // 2
            del self._log[:drop]
            self._log_start += drop

    def significant_facts(self, concept: str | Term) -> list[Term]:
        """What the concept's descriptions hold with probability >= the probability threshold:
        each generalization's significant facts, then every kept example's facts (an example
        is a description of probability 1), without repeats."""
        c = self.concept(concept)
        out: dict[Term, None] = {}
        for _kind, _i, facts in c.context.descriptions(self.params):
            out.update(dict.fromkeys(facts))
        return list(out)

    def required_classes(self, concept: str | Term) -> frozenset[Term]:
        """The class symbols (`cv_red` of `isa(X, cv_red)`) that the concept's descriptions
        hold with probability >= the probability threshold, the concept's own left out: as
        `significant_facts` has them, without putting the facts in order (the lexicon reads
        this for every visual concept)."""
        c = self.concept(concept)
        own = Term(str(concept))
        low = self.params.probability - 1e-12
        out: set[Term] = set()
        for g in c.context.generalizations:
            size = g.size
            out.update(f.args[1] for f, n in g.counts.items()
                       if f.name == "isa" and len(f.args) == 2 and size and n / size >= low)
        for ex in c.context.examples:
            out.update(f.args[1] for f in ex if f.name == "isa" and len(f.args) == 2)
        out.discard(own)
        return frozenset(out)

    def descriptions(self, concept: str | Term) -> list[list[Term]]:
        """The facts that count of each generalization (its significant facts) and each kept
        example, as queries match them."""
        c = self.concept(concept)
        return [facts for _kind, _i, facts in c.context.descriptions(self.params)]

    def concept(self, symbol: str | Term) -> Concept:
        c = self._concepts.get(str(symbol))
        if c is None:
            raise UserError(f"unknown concept {str(symbol)!r}")
        return c

    def generalizations(self, concept: str | Term) -> list[dict[str, float]]:
        """Each generalization's facts, printed, with their probabilities (most probable first)."""
        return [
            {str(f): p for f, p in g.probabilities().items()}
            for g in self.concept(concept).context.generalizations
        ]

    def examples(self, concept: str | Term) -> list[list[str]]:
        return [[str(f) for f in ex] for ex in self.concept(concept).context.examples]

    # ------------------------------------------------------------------ create / store
    def create(self, symbol: str | Term, kind: str) -> Concept:
        """Create a concept and its empty context; creating an existing one returns it."""
        name = str(symbol)
        try:
            t = parse(name)
        except TermSyntaxError:
            t = None
        if t is None or t.args or t.is_variable or t.is_number or name.startswith('"'):
            raise UserError(f"concept symbol {name!r} is not a lowercase ASP constant")
        if kind not in KINDS:
            raise UserError(f"concept kind {kind!r} is not one of {', '.join(KINDS)}")
        c = self._concepts.get(name)
        if c is not None:
            if c.kind != kind:
                raise UserError(f"concept {name!r} already exists as a {c.kind} concept, not {kind}")
            return c
        c = Concept(name, kind)
        self._concepts[name] = c
        self._order[name] = len(self._order)
        self._index.touch(name, kind, c.context)
        self._changed(name)
        return c

    def store(self, facts: Iterable[Term | str], concept: str | Term, *,
              accept: "Callable[[Generalization], bool] | None" = None,
              exhaustive: bool = False) -> StoreResult:
        """Add an example (facts) to a concept's context; it must have been created. `accept`
        may refuse the merge SAGE would make (the example is then kept apart).

        SAGE's comparison with the concept's descriptions goes through an exact content
        filter (`retrieval.StoreFilter`): SME runs only on descriptions whose similarity
        bound can reach the best found, with the same result as matching every description,
        which `exhaustive=True` does."""
        c = self.concept(concept)
        ex = [as_term(f) for f in facts]
        if not ex:
            raise UserError(f"cannot store an empty example for {c.symbol!r}")
        bounds = None if exhaustive else self._store_filter.bounds(c.symbol, c.context, self.params)
        r = c.context.add(ex, self.params, accept, bounds=bounds)
        self._index.touch(c.symbol, c.kind, c.context)
        self._bounds.pop(c.symbol, None)
        self._changed(c.symbol)
        return StoreResult(len(c.context.generalizations), len(c.context.examples), r.action, r.similarity)

    def store_near_miss(self, facts: Iterable[Term | str], concept: str | Term) -> int:
        """Keep a near miss (a scene the concept wrongly accepted) for the concept; it narrows
        every description it matches (memory/nearmiss.py). Returns the number kept."""
        c = self.concept(concept)
        nm = list(dict.fromkeys(as_term(f) for f in facts))
        if not nm:
            raise UserError(f"cannot store an empty near miss for {c.symbol!r}")
        c.near_misses.append(nm)
        return len(c.near_misses)

    # ------------------------------------------------------------------ query
    def _similarity(self, m: sme.Mapping, base: list[Term], leave_out: Term | None) -> float:
        p = self.params
        if p.normalisation == "paper":
            return m.similarity
        if leave_out is None:
            kept = base
        else:
            shape = _skeleton(leave_out)
            kept = [f for f in base if unify(shape, f) is None]
        denom = sme.self_score(kept, functions=p.functions, params=p.sme)
        return 0.0 if denom <= 0 else min(1.0, m.score / denom)

    def query(self, scene: Iterable[Term | str], pattern: Term | str,
              concept: str | Term | None = None, *, ignore: Collection[Term] = (),
              ignore_relations: Collection[str] = (), exhaustive: bool = False) -> list[Inference]:
        """Facts fitting `pattern` (uppercase names are variables) that the memory infers about
        `scene`, best first, each only once (its best support) and only when the match's
        similarity reaches the match threshold. The concept is the pattern's (`isa(O, r_red)`
        -> `r_red`, `r_left_of(A, B)` -> `r_left_of`) unless given; an unknown concept gives
        no inferences.

        `ignore` names class symbols (e.g. `cv_cone`) whose `isa` facts are left out of the
        concept's descriptions for this query: the agent's mutual exclusivity, when another
        word already accounts for them; `ignore_relations` likewise names relation predicates
        (`cone_w`) whose binary facts are left out (exclusivity over relation words).

        In a context with more than `CONTEXT_MAC` descriptions, SME runs only on those whose
        content vectors share the most with the scene (MAC/FAC, `retrieval`); `exhaustive`
        matches every description instead."""
        pat = as_term(pattern)
        name = str(concept) if concept is not None else _pattern_concept(pat)
        c = self._concepts.get(name) if name is not None else None
        if c is None:
            return []
        target = [f if isinstance(f, Term) else as_term(f) for f in scene]
        best: dict[Term, Inference] = {}
        drop = None
        need = nearmiss.required(c.context, c.near_misses, self.params)
        keep = frozenset().union(*need.values()) if need else frozenset()
        if ignore or ignore_relations:
            skip, skip_rel = frozenset(ignore), frozenset(ignore_relations)

            def drop(f: Term) -> bool:  # mutual exclusivity never strips what a near miss showed is needed
                if f in keep or len(f.args) != 2:
                    return False
                return (f.args[1] in skip) if f.name == "isa" else f.name in skip_rel

        only = None
        if not exhaustive:
            only = self._prefilter(c, target, pat, drop, frozenset(ignore) | frozenset(ignore_relations))
            if not only:
                return []
        # The question names who plays which role (`r_on(o2,o1)`: o2 is the one on top): SME is
        # asked for the best mapping that puts the concept's own role entities on those objects,
        # not only for its best mappings overall, which may all have the roles the other way.
        roles = pat.args if pat.name != "isa" else pat.args[:1]
        ground = all(sme.is_entity(a) and not a.is_variable for a in roles)

        def require(base: list[Term]) -> dict[Term, Term]:
            mine = c.context.membership(base)
            if not ground or mine is None or len(mine) != len(roles):
                return {}
            return {x: y for x, y in zip(mine, roles) if sme.is_entity(x)}

        for cand in c.context.match(target, self.params, drop=drop, only=only, require=require):
            must = need.get((cand.kind, cand.index), frozenset())
            for m in cand.mappings:
                if must and not nearmiss.keeps(m, must):
                    continue
                fits = []
                for inf in m.inferences:
                    if _has_skolem(inf):
                        continue
                    b = unify(pat, inf)
                    if b is not None:
                        fits.append((inf, b))
                if not fits:
                    continue
                sim = self._similarity(m, cand.base, pat)
                if sim < self.params.match - 1e-12:
                    continue
                for inf, b in fits:
                    old = best.get(inf)
                    if old is None or sim > old.similarity:
                        best[inf] = Inference(inf, sim, c.symbol, cand.kind, cand.index, b, m)
        return sorted(best.values(), key=lambda i: (-i.similarity, sort_key(i.fact)))

    def _prefilter(self, c: Concept, target: list[Term], pat: Term, drop,  # noqa: ANN001
                   ignore: frozenset) -> set[tuple[str, int]]:
        """The descriptions worth running SME on: in a context with more than `CONTEXT_MAC`
        descriptions, the best by content vector (MAC); then only those whose similarity
        bound (`retrieval.score_bound` over the query's denominator) reaches the match
        threshold, which never drops a description that could answer."""
        key = tuple(target)
        if self._last_probe[0] != key:  # the same scene is often asked about several concepts
            self._last_probe = (key, retrieval.content_vector(target))
        probe = self._last_probe[1]
        descs = self._index.descriptions(c.symbol, self.params)
        only = None
        if len(descs) > CONTEXT_MAC:
            scores = [(retrieval.dot(probe, v), pos) for pos, (_k, _i, v) in enumerate(descs)]
            only = {descs[pos][:2] for pos in retrieval.best_descriptions(scores, retrieval.MAC_WIDTH)}
        p = self.params
        bounded = p.normalisation == "significant" and not p.functions
        shape = _skeleton(pat)
        memo = self._bounds.setdefault(c.symbol, {})
        keep: set[tuple[str, int]] = set()
        for kind, i, _vec in descs:
            if only is not None and (kind, i) not in only:
                continue
            key = (kind, i, shape, ignore)
            got = memo.get(key)
            if got is None:
                if kind == "generalization":
                    facts = c.context.generalizations[i].significant(p.probability)
                else:
                    facts = c.context.examples[i]
                if drop is not None:
                    facts = [f for f in facts if not drop(f)]
                kept = [f for f in facts if unify(shape, f) is None]
                denom = sme.self_score(kept, functions=p.functions, params=p.sme) if bounded and facts else 0.0
                got = memo[key] = (facts, denom, frozenset(retrieval.content_vector(facts)), {})
            facts, denom, feats, bounds = got
            if not facts:
                continue
            if bounded:
                shared = feats.intersection(probe)
                bound = bounds.get(shared)
                if bound is None:
                    bound = bounds[shared] = retrieval.score_bound(facts, probe, p)
                best = 0.0 if denom <= 0 else min(1.0, bound / denom)
                if best < p.match - 1e-12:
                    continue
            keep.add((kind, i))
        return keep

    def fitting(self, facts: Iterable[Term | str], *, kind: str | None = None, k: int = 5,
                exhaustive: bool = False,
                ignore: "Callable[[str], Collection[Term]] | None" = None) -> list[Inference]:
        """Which concepts fit these facts (an object's percepts, a pair's facts, a scene):
        the membership inferences (`isa(o1, r_red)`, `r_left_of(o1, o2)`) of the `k` concepts
        (of `kind`, when given) whose best inference is most similar, best first, each
        reaching the match threshold; ties go to the concept created first.

        Why not query every concept: that is linear in the number of concepts, with SME on
        every description. MAC/FAC instead: content vectors pick the concepts sharing the
        most functors with `facts` (`retrieval.ContentIndex`), and only those are queried.
        `exhaustive=True` queries every concept (and every description), for comparison.
        `ignore(concept)` gives the class symbols to leave out for that concept's query (the
        agent's mutual exclusivity, as in `query`)."""
        if k < 1:
            raise ValueError(f"k must be at least 1, not {k}")
        if kind is not None and kind not in KINDS:
            raise UserError(f"concept kind {kind!r} is not one of {', '.join(KINDS)}")
        target = [as_term(f) for f in facts]
        order = self._order
        if exhaustive:
            names = [n for n, c in self._concepts.items() if kind is None or c.kind == kind]
        else:
            probe = retrieval.content_vector(target)
            names = self._index.candidates(probe, self.params, kind=kind,
                                           width=max(k, retrieval.MAC_WIDTH), order=order)
        found: list[tuple[float, int, list[Inference]]] = []
        for name in names:
            pat = self._membership(name)
            skip = ignore(name) if ignore is not None else ()
            infs = self.query(target, pat, name, exhaustive=exhaustive, ignore=skip) if pat is not None else []
            if infs:
                found.append((infs[0].similarity, order[name], infs))
        found.sort(key=lambda x: (-x[0], x[1]))
        return [inf for _s, _o, infs in found[:k] for inf in infs]

    def _membership(self, concept: str) -> Term | None:
        """The pattern of the concept's own fact in its descriptions: `isa(X, c)` or
        `c(X1, ..., Xn)`; None when its descriptions hold neither."""
        c = self._concepts[concept]
        sym = Term(concept)
        for _kind, _i, facts in c.context.descriptions(self.params):
            for f in facts:
                if f.name == "isa" and len(f.args) == 2 and f.args[1] is sym:
                    return Term("isa", (Term("X"), sym))
                if f.name == concept and f.args:
                    return Term(concept, tuple(Term(f"X{i}") for i in range(len(f.args))))
        return None

    # ------------------------------------------------------------------ project
    def project(self, trace: Iterable[Term | str], concept: str | Term) -> Projection:
        """The state after the trace's latest time point, as the action concept has it.

        The trace is `h(T, Fact)`, `after(T1, T0)` and `isa(t0, start)` facts. Candidate
        inferences `after(S, latest)` name the next time point S (a skolem); the facts are those
        of the inferences `h(S, F)`, with the trace's entities in them. `complete` is true when
        the generalization has no time point after S (or the trace already reached its last).
        """
        c = self.concept(concept)
        facts = [as_term(f) for f in trace]
        chain = time_chain(facts)
        latest = chain[-1] if chain else None
        trace_index = {t: i for i, t in enumerate(chain)}
        # Keep every mapping (no cutoff): a weaker one may be the temporally coherent one.
        params = replace(self.params, sme=replace(self.params.sme, cutoff=0.0))
        best: Projection | None = None
        best_key: tuple = ()
        anchors = _anchors(facts, c.symbol)

        def require(base: list[Term]) -> dict[Term, Term]:
            # The action's start aligns with the trace's start, and its arguments with the
            # trace's when the trace names them (`r_move_right_of(o1,o2)`): otherwise a start
            # state that looks like the end state with the roles swapped can win the match.
            req: dict[Term, Term] = {}
            for key, b in _anchors(base, c.symbol).items():
                t = anchors.get(key)
                if t is not None and len(t) == len(b):
                    req.update((x, y) for x, y in zip(b, t) if sme.is_entity(x) and sme.is_entity(y))
            return req

        for cand in c.context.match(facts, params, require=require):
            has_next = {f.args[1] for f in cand.base if f.name == "after" and len(f.args) == 2}
            base_index = {t: i for i, t in enumerate(time_chain(cand.base))}
            for m in cand.mappings:
                sim = self._similarity(m, cand.base, None)
                proj = self._project_one(m, latest, has_next, sim)
                if proj is None:
                    continue
                # Coherent: every trace time point mapped lies as far from the start as its
                # correspondent in the action (t1 is the action's second state, not its third).
                coherent = all(
                    base_index.get(b) == trace_index[t] for b, t in m.pairs.items() if t in trace_index
                )
                proj.source, proj.index, proj.mapping = cand.kind, cand.index, m
                key = (coherent, sim, len(proj.facts))
                if best is None or key > best_key:
                    best, best_key = proj, key
        if best is None:
            return Projection(facts=[], complete=False, similarity=0.0, after=latest)
        return best

    @staticmethod
    def _project_one(m: sme.Mapping, latest: Term | None, has_next: set[Term], sim: float) -> Projection | None:
        if latest is None:
            return None
        inv = {t: b for b, t in m.pairs.items()}
        nxt: Term | None = None
        for inf in m.inferences:
            if inf.name == "after" and len(inf.args) == 2 and inf.args[1] is latest and inf.args[0].name == "skolem":
                nxt = inf.args[0]
                break
        if nxt is None:
            base_latest = inv.get(latest)
            if base_latest is None:
                return None
            # The trace reached a time point of the action: complete when it is the last.
            return Projection(facts=[], complete=base_latest not in has_next, similarity=sim, after=latest)
        out: list[Term] = []
        unresolved: list[Term] = []
        for inf in m.inferences:
            if inf.name == "h" and len(inf.args) == 2 and inf.args[0] is nxt:
                f = inf.args[1]
                (unresolved if _has_skolem(f) else out).append(f)
        base_tp = nxt.args[0]
        return Projection(facts=out, complete=base_tp not in has_next, similarity=sim,
                          time_point=nxt, after=latest, unresolved=unresolved)

    # ------------------------------------------------------------------ persistence (memory/codec.py)
    def to_dict(self) -> dict[str, Any]:
        self.read_all()
        return codec.encode(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any], path: str = "<memory>") -> "ConceptMemory":
        """Rebuild a memory from `to_dict` output; malformed entries raise `UserError`."""
        return codec.decode(cls, data, path)

    def adopt(self, symbol: str, kind: str, source: compact.Source, index: int) -> None:
        """Take in a concept of a compact file, read from it when first used (`compact.decode`)."""
        self._concepts[symbol] = Concept(symbol, kind, source=source, at=index)
        self._order[symbol] = len(self._order)
        self._index.touch_all(self._concepts, self.read_all)

    def read_all(self) -> None:
        """Read every concept not read yet (of a memory loaded from a compact file) at once:
        what a retrieval over every concept or a save needs, faster than one at a time."""
        lazy = [c for c in self._concepts.values() if not c.loaded]
        if not lazy:
            return
        with codec.gc_paused():
            for c in lazy:
                c.context  # noqa: B018 - reads it

    def save(self, path: str | os.PathLike[str], form: str | None = None) -> None:
        """Write the memory (temporary file, then rename): as versioned JSON, or in the
        compact form (`form="compact"`, or a path ending in `compact.SUFFIX`, `.amem`)."""
        self.read_all()
        if (form or file_form(path)) == "compact":
            persist.write_bytes_atomic(path, compact.encode(self))
        else:
            persist.write_json_atomic(path, self.to_dict())

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> "ConceptMemory":
        """Read a memory saved by `save`, in either form (told apart by the file's first
        bytes, not its name); any problem is a `UserError` naming the path."""
        raw = persist.read_bytes(path)
        if compact.is_compact(raw):
            return compact.decode(cls, raw, str(path))
        return cls.from_dict(persist.parse_json(raw, str(path)), str(path))


#: The forms a memory file can take (`ConceptMemory.save`).
FORMS = ("json", "compact")


def file_form(path: str | os.PathLike[str]) -> str:
    """The form `save` writes at `path` by default: compact for a name ending in `.amem`."""
    return "compact" if str(path).endswith(compact.SUFFIX) else "json"


def _anchors(facts: Iterable[Term], concept: str) -> dict[str, tuple[Term, ...]]:
    """The start time point (`isa(T,start)`) and the concept's own fact's arguments."""
    out: dict[str, tuple[Term, ...]] = {}
    for f in facts:
        if f.name == "isa" and len(f.args) == 2 and f.args[1].name == "start" and not f.args[1].args:
            out["start"] = (f.args[0],)
        elif f.name == concept and f.args:
            out["concept"] = f.args
    return out


def time_chain(trace: Iterable[Term]) -> list[Term]:
    """The time points of a trace in order: from the start (`isa(T, start)`, else the first
    time point that follows none) along the `after(T1, T0)` links."""
    nxt: dict[Term, Term] = {}
    later: set[Term] = set()
    points: list[Term] = []
    start: Term | None = None
    for f in trace:
        if f.name == "after" and len(f.args) == 2:
            nxt[f.args[1]] = f.args[0]
            later.add(f.args[0])
            points.extend((f.args[1], f.args[0]))
        elif f.name == "isa" and len(f.args) == 2 and f.args[1].name == "start" and not f.args[1].args:
            start = f.args[0]
            points.append(start)
        elif f.name == "h" and len(f.args) == 2:
            points.append(f.args[0])
    if start is None:
        firsts = [p for p in dict.fromkeys(points) if p not in later]
        if not firsts:
            return []
        start = firsts[0]
    out = [start]
    seen = {start}
    while out[-1] in nxt and nxt[out[-1]] not in seen:
        out.append(nxt[out[-1]])
        seen.add(out[-1])
    return out


def latest_time_point(trace: Iterable[Term]) -> Term | None:
    """The last time point of a trace (see `time_chain`), or None without time points."""
    chain = time_chain(trace)
    return chain[-1] if chain else None
