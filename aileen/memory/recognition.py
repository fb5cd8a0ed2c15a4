"""Recognition: which concepts a scene shows, and what they infer about it (the paper's
section 4, "query"). `Recognition.query` asks one concept about a scene; `fitting` asks which
concepts fit (MAC/FAC over the content index, `retrieval`).

Why a module of its own: recognising is one job, with state of its own (the content index and
the per-query caches that spare SME), and the concept memory's other jobs (holding concepts,
storing into them, reading and writing the file: `memory/concept.py`; projecting an action
onto a trace: `memory/projection.py`) neither read nor write that state. The memory owns one
`Recognition`, tells it which concept changed (`touch`) and hands it its `query` and `fitting`.

Pure computation on `Term`s.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterable, Mapping
from dataclasses import dataclass, field
from functools import lru_cache

from aileen.analogy import sme
from aileen.analogy.sage import GeneralizationContext, SageParams
from aileen.errors import UserError
from aileen.memory import nearmiss, retrieval
from aileen.memory.codec import StoredConcept
from aileen.memory.kinds import KINDS
from aileen.terms import Term, as_term, sort_key, unify

__all__ = ["CONTEXT_MAC", "Inference", "Recognition", "has_skolem", "similarity"]


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


def has_skolem(t: Term) -> bool:
    """Whether the term names a skolem (`skolem(e)`: an entity of the base that the target
    lacks): an inference about it says nothing about the scene's own objects."""
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

#: The most answers `query` keeps, over every concept (each until its concept's next store;
#: all dropped at once past this): a bound on memory (about 2 KB an answer, measured in a
#: teacher trial, which keeps a few hundred), not a tuning knob.
ANSWERS_KEPT = 8192


def similarity(m: sme.Mapping, base: list[Term], leave_out: Term | None, params: SageParams) -> float:
    """How similar a mapping makes the base description and the scene, as `params` normalise
    it: SME's own similarity (`"paper"`), or the score over the self score of the base
    without the facts of `leave_out`'s shape (`"significant"`: the facts a query asks about
    are not in the scene). Projection scores its mappings the same way."""
    if params.normalisation == "paper":
        return m.similarity
    if leave_out is None:
        kept = base
    else:
        shape = _skeleton(leave_out)
        kept = [f for f in base if unify(shape, f) is None]
    denom = sme.self_score(kept, functions=params.functions, params=params.sme)
    return 0.0 if denom <= 0 else min(1.0, m.score / denom)


class Recognition:
    """A memory's recognition: its content index (MAC/FAC, kept up to date through `touch`)
    and the caches of `query`'s pre-filter, over the memory's concepts.

    `concepts` and `order` are the memory's own (symbol -> concept, symbol -> place in the
    order of creation), read here and never written; `params` are the memory's, fixed for
    its life (the caches depend on them)."""

    def __init__(self, concepts: Mapping[str, StoredConcept], order: Mapping[str, int],
                 params: SageParams) -> None:
        self._concepts = concepts
        self._order = order
        self.params = params
        # MAC/FAC: content vectors of every description, refreshed per concept on store.
        self._index = retrieval.ContentIndex()
        # Per concept, per description and query shape: its facts, the query's denominator,
        # its functors and score bounds by shared functors (`_prefilter`); dropped on store.
        self._bounds: dict[str, dict[tuple, tuple]] = {}
        self._last_probe: tuple[tuple[Term, ...], dict] = ((), {})
        # Per concept, `query`'s answers by its arguments; dropped on store (`touch`). The
        # agent asks the same questions of concepts no lesson changed (an exam replayed after
        # a lesson that taught another word: every colour and shape word, of the same
        # objects), and a query is a function of the concept, its near misses and them.
        self._answers: dict[str, dict[tuple, list[Inference]]] = {}
        self._kept = 0  # answers in `_answers`, over every concept

    def __getstate__(self) -> dict:
        """A copy (the console's undo keeps one per lesson) or a pickle leaves the kept answers
        behind: a cache, made again as questions are asked (a copy with them took half as long
        again, 53 against 35 ms after a teacher trial)."""
        state = dict(self.__dict__)
        state["_answers"], state["_kept"] = {}, 0
        return state

    def touch(self, symbol: str, kind: str, context: GeneralizationContext) -> None:
        """The concept was created or stored into: its vectors are made again before the next
        retrieval, and its cached bounds are dropped."""
        self._index.touch(symbol, kind, context)
        self._bounds.pop(symbol, None)
        self._kept -= len(self._answers.pop(symbol, ()))

    def touch_all(self, read_all: Callable[[], None]) -> None:
        """Every concept is to be indexed before the next retrieval over all of them (a
        memory loaded from a compact file; `read_all` reads them at once first)."""
        self._index.touch_all(self._concepts, read_all)
        self._bounds.clear()
        self.forget_answers()

    def forget_answers(self) -> None:
        """Drop every kept answer of `query` (a benchmark that asks the same question again
        times the work, not the lookup)."""
        self._answers.clear()
        self._kept = 0

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
        # a near miss is appended without a store (`ConceptMemory.store_near_miss`): their
        # number is part of the question
        key = (pat, tuple(target), frozenset(ignore), frozenset(ignore_relations), exhaustive, len(c.near_misses))
        got = self._answers.get(c.symbol, {}).get(key)
        if got is None:
            got = self._query(c, target, pat, ignore, ignore_relations, exhaustive)
            if self._kept >= ANSWERS_KEPT:
                self.forget_answers()
            self._answers.setdefault(c.symbol, {})[key] = got
            self._kept += 1
        return list(got)

    def _query(self, c: StoredConcept, target: list[Term], pat: Term, ignore: Collection[Term],
               ignore_relations: Collection[str], exhaustive: bool) -> list[Inference]:
        """`query`'s answers, worked out."""
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
                    if has_skolem(inf):
                        continue
                    b = unify(pat, inf)
                    if b is not None:
                        fits.append((inf, b))
                if not fits:
                    continue
                sim = similarity(m, cand.base, pat, self.params)
                if sim < self.params.match - 1e-12:
                    continue
                for inf, b in fits:
                    old = best.get(inf)
                    if old is None or sim > old.similarity:
                        best[inf] = Inference(inf, sim, c.symbol, cand.kind, cand.index, b, m)
        return sorted(best.values(), key=lambda i: (-i.similarity, sort_key(i.fact)))

    def _prefilter(self, c: StoredConcept, target: list[Term], pat: Term, drop,  # noqa: ANN001
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
                ignore: "Callable[[str], Collection[Term]] | None" = None,
                ignore_relations: Collection[str] = ()) -> list[Inference]:
        """Which concepts fit these facts (an object's percepts, a pair's facts, a scene):
        the membership inferences (`isa(o1, r_red)`, `r_left_of(o1, o2)`) of the `k` concepts
        (of `kind`, when given) whose best inference is most similar, best first, each
        reaching the match threshold; ties go to the concept created first.

        Why not query every concept: that is linear in the number of concepts, with SME on
        every description. MAC/FAC instead: content vectors pick the concepts sharing the
        most functors with `facts` (`retrieval.ContentIndex`), and only those are queried.
        `exhaustive=True` queries every concept (and every description), for comparison.
        `ignore(concept)` gives the class symbols to leave out for that concept's query (the
        agent's mutual exclusivity, as in `query`); `ignore_relations`, the relations left out
        of every query (as in `query`)."""
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
            infs = (self.query(target, pat, name, exhaustive=exhaustive, ignore=skip, ignore_relations=ignore_relations)
                    if pat is not None else [])
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
