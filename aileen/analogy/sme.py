"""The Structure-Mapping Engine (SME v4, Forbus et al. 2017), in plain Python.

Why our own: the concept memory matches small descriptions (a scene, a generalization) dozens
of times per lesson, so SME must be pure Python over interned `Term`s, with no I/O and no
foreign runtime. The algorithm follows the published SME v4 (and its public regression
suite, which `tests/test_sme.py` reproduces):

1. **Match hypotheses (MHs).** Every base expression is paired with every target expression
   whose functor is identical (relations, attributes and functions alike). Arguments are then
   aligned by position: entities with entities, expressions with identical functors, and
   *function* expressions with any function expression (non-identical functions may align
   when their parents align). An MH whose arguments cannot all be aligned is *incomplete* and
   gets no children. Each expression MH also implies a functor MH (counted, score 0).
2. **Structural consistency.** An MH is inconsistent when its descendants map one item to two
   (one-to-one); incompleteness and inconsistency propagate to parents (parallel
   connectivity). Kernels are the consistent, complete MHs without such a parent, with all
   their descendants.
3. **Structural evaluation.** Local score `same_functor` for expression MHs with identical
   functors, `same_function` for non-identical function pairs, 0 for entities. Scores
   trickle down from roots to arguments, `trickle_down` times the parent's score. For
   kernels, each MH takes evidence from a greedy, one-to-one-consistent set of its parents
   (SME v4's "block most out-of-mapping contributions"); a global mapping is re-scored using
   only the MHs inside it.
4. **Greedy merge.** Kernels sorted by score; each mapping starts from the best kernel not
   already in an earlier mapping and adds every kernel consistent with it (including those
   of earlier mappings). Up to `max_mappings`, dropping those under `cutoff` times the best.
5. **Candidate inferences.** Base expressions outside the mapping that have a mapped
   argument somewhere below them (entity-supported inferences allowed), reported at their
   maximal level, translated into the target's vocabulary; unmapped entities become
   `skolem(e)`. Reverse inferences do the same from target to base.
6. **Similarity.** `2 * score / (self(base) + self(target))`, where `self(d)` is the score
   of `d` matched with itself (the identity mapping), clamped to [0, 1].

AILEEN conventions at the boundary: `isa(O, C)` with a constant class `C` becomes the
attribute `C(O)` (so a class only aligns with the identical class) and comes back as
`isa(...)` in inferences; `gen_ent(...)` and `skolem(...)` terms are entities.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from functools import lru_cache

from aileen.terms import Term, as_term

__all__ = [
    "Params",
    "Mapping",
    "MatchResult",
    "analyze",
    "match",
    "self_score",
    "is_entity",
    "ENTITY_FUNCTORS",
]

#: Compound terms with these functors are entities, not expressions.
ENTITY_FUNCTORS: frozenset[str] = frozenset({"gen_ent", "skolem"})

_ISA_PREFIX = "isa:"
_SKOLEM = "skolem"


@dataclass(frozen=True)
class Params:
    """SME's scoring and merge parameters (SME v4 defaults; 0.005/0.002/16 is the older preset)."""

    same_functor: float = 0.0005
    same_function: float = 0.0002
    trickle_down: float = 8.0
    max_mappings: int = 3
    cutoff: float = 0.8


# ----------------------------------------------------------------------------- terms


def is_entity(t: Term) -> bool:
    """Atoms, numbers, generalized entities and skolems are entities; the rest are expressions."""
    return not t.args or t.name in ENTITY_FUNCTORS


def _to_sme(t: Term) -> Term:
    """`isa(O, C)` -> attribute `isa:C(O)` (recursively inside expressions)."""
    if is_entity(t):
        return t
    if t.name == "isa" and len(t.args) == 2:
        c = t.args[1]
        if not c.args and isinstance(c.name, str):
            return Term(_ISA_PREFIX + c.name, (_to_sme(t.args[0]),))
    new = tuple(_to_sme(a) for a in t.args)
    return t if new == t.args else Term(t.name, new)


def _from_sme(t: Term) -> Term:
    """Inverse of `_to_sme`; also walks into skolem terms."""
    if not t.args:
        return t
    name = t.name
    args = tuple(_from_sme(a) for a in t.args)
    if isinstance(name, str) and name.startswith(_ISA_PREFIX) and len(args) == 1:
        return Term("isa", (args[0], Term(name[len(_ISA_PREFIX):])))
    return t if args == t.args else Term(name, args)


class _Desc:
    """A prepared description: its expressions (each once), their parents and orders."""

    __slots__ = ("facts", "exprs", "expr_set", "parents", "order", "by_functor", "self_score", "_fn")

    def __init__(self, facts: tuple[Term, ...], functions: frozenset[str], params: Params) -> None:
        seen: dict[Term, None] = {}
        conv: list[Term] = []
        for f in facts:
            c = _to_sme(f)
            if c not in seen:
                seen[c] = None
                conv.append(c)
        self.facts = tuple(conv)
        self._fn = functions
        exprs: list[Term] = []
        expr_set: set[Term] = set()
        parents: dict[Term, list[Term]] = {}
        order: dict[Term, int] = {}

        def visit(e: Term) -> int:
            o = order.get(e)
            if o is not None:
                return o
            best = 0
            for a in e.args:
                if is_entity(a):
                    order.setdefault(a, 0)
                    ps = parents.setdefault(a, [])
                else:
                    best = max(best, visit(a))
                    ps = parents.setdefault(a, [])
                if not ps or ps[-1] is not e:  # r(a,a): one parent link, as in SME
                    ps.append(e)
            o = best + 1
            order[e] = o
            expr_set.add(e)
            exprs.append(e)
            return o

        for f in self.facts:
            if is_entity(f):
                continue  # a bare constant is not a statement
            visit(f)
        self.exprs = exprs  # children before parents, in fact order
        self.expr_set = expr_set
        self.parents = parents
        self.order = order
        by_functor: dict[tuple, list[Term]] = {}
        for e in exprs:
            by_functor.setdefault((e.name, len(e.args)), []).append(e)
        self.by_functor = by_functor
        self.self_score = _identity_score(self, params)

    def is_function(self, e: Term) -> bool:
        return e.name in self._fn


def _identity_score(d: _Desc, params: Params) -> float:
    """Score of the description matched with itself through the identity mapping."""
    score: dict[Term, float] = {}
    td = params.trickle_down
    sf = params.same_functor
    total = 0.0
    for e in sorted(d.order, key=d.order.__getitem__, reverse=True):
        s = sf if e in d.expr_set else 0.0
        for p in d.parents.get(e, ()):
            s += td * score[p]
        score[e] = s
        total += s
    return total


# Big enough for a context of a few thousand descriptions: at 256 a query over a context with
# 1000 kept examples evicted every entry before it was used again.
@lru_cache(maxsize=4096)
def _prepare(facts: tuple[Term, ...], functions: frozenset[str], params: Params) -> _Desc:
    return _Desc(facts, functions, params)


def _as_fact_tuple(xs: Iterable[Term | str]) -> tuple[Term, ...]:
    return tuple(x if isinstance(x, Term) else as_term(x) for x in xs)


def self_score(facts: Iterable[Term | str], *, functions: frozenset[str] = frozenset(),
               params: Params = Params()) -> float:
    """`self(d)`: the structural score of a description matched with itself."""
    return _prepare(_as_fact_tuple(facts), frozenset(functions), params).self_score


# ----------------------------------------------------------------------------- mappings


@dataclass
class Mapping:
    """One global interpretation of a comparison.

    `pairs` maps base items to target items (expressions and entities, in AILEEN syntax);
    `entities` is the entity part as strings. Inferences are computed on first access,
    because a large target (a whole scene) has many reverse inferences nobody asks for.
    """

    score: float
    similarity: float
    entities: dict[str, str]
    pairs: dict[Term, Term]
    mh_count: int
    root_pairs: list[tuple[Term, Term]]
    _b2t: dict[Term, Term] = field(repr=False)
    _base: _Desc = field(repr=False)
    _target: _Desc = field(repr=False)
    _inferences: list[Term] | None = field(default=None, repr=False)
    _reverse: list[Term] | None = field(default=None, repr=False)

    @property
    def inferences(self) -> list[Term]:
        """Candidate inferences from base to target, in AILEEN syntax."""
        if self._inferences is None:
            self._inferences = _candidate_inferences(self._base, self._b2t)
        return self._inferences

    @property
    def reverse_inferences(self) -> list[Term]:
        """Candidate inferences from target to base, in AILEEN syntax."""
        if self._reverse is None:
            t2b = {t: b for b, t in self._b2t.items()}
            self._reverse = _candidate_inferences(self._target, t2b)
        return self._reverse


@dataclass
class MatchResult:
    """Everything a comparison produced; `match` returns only `.mappings`."""

    mappings: list[Mapping]
    mh_count: int
    kernel_count: int
    base_self_score: float
    target_self_score: float


def _candidate_inferences(base: _Desc, b2t: dict[Term, Term]) -> list[Term]:
    supported: dict[Term, bool] = {}

    def sup(e: Term) -> bool:
        r = supported.get(e)
        if r is None:
            r = False
            if e not in b2t:
                for a in e.args:
                    if a in b2t or (a in base.expr_set and sup(a)):
                        r = True
                        # keep scanning not needed
                        break
            supported[e] = r
        return r

    out: list[Term] = []
    seen: set[Term] = set()
    for e in base.exprs:
        if not sup(e):
            continue
        if any(sup(p) for p in base.parents.get(e, ())):
            continue  # reported inside a larger inference
        t = _translate(e, b2t)
        if t not in seen:
            seen.add(t)
            out.append(_from_sme(t))
    return out


def _translate(e: Term, b2t: dict[Term, Term]) -> Term:
    t = b2t.get(e)
    if t is not None:
        return t
    if is_entity(e):
        return Term(_SKOLEM, (e,))
    return Term(e.name, tuple(_translate(a, b2t) for a in e.args))


# ----------------------------------------------------------------------------- the engine


def analyze(base: Iterable[Term | str], target: Iterable[Term | str], *,
            functions: frozenset[str] = frozenset(), params: Params = Params(),
            require: "dict[Term, Term] | None" = None) -> MatchResult:
    """Compare `base` with `target` and return the mappings (best first) and counts.

    `require` holds entity correspondences (base -> target) that every mapping must respect,
    SME's required-correspondence constraint: match hypotheses that contradict one are
    dropped before kernels form (e.g. a projection aligns the action's start with the
    trace's start)."""
    fn = frozenset(functions)
    b = _prepare(_as_fact_tuple(base), fn, params)
    t = _prepare(_as_fact_tuple(target), fn, params)
    return _Engine(b, t, params, require).run()


def match(base: Iterable[Term | str], target: Iterable[Term | str], *,
          functions: frozenset[str] = frozenset(), params: Params = Params(),
          require: "dict[Term, Term] | None" = None) -> list[Mapping]:
    """Compare `base` with `target`; up to `params.max_mappings` mappings, best first."""
    return analyze(base, target, functions=functions, params=params, require=require).mappings


class _Engine:
    def __init__(self, base: _Desc, target: _Desc, params: Params,
                 require: "dict[Term, Term] | None" = None) -> None:
        self.require = dict(require) if require else {}
        self.b = base
        self.t = target
        self.p = params
        # MH tables, indexed by id.
        self.mb: list[Term] = []
        self.mt: list[Term] = []
        self.children: list[tuple[int, ...]] = []
        self.parents: list[list[int]] = []
        self.ok: list[bool] = []
        self.local: list[float] = []
        self.order: list[int] = []
        self.corr: list[dict[Term, Term] | None] = []  # base->target over descendants (ok MHs)
        self.index: dict[tuple[Term, Term], int] = {}
        self.functor_pairs: set[tuple] = set()

    # -- MH creation
    def _alignable(self, ba: Term, ta: Term) -> bool:
        be, te = is_entity(ba), is_entity(ta)
        if be or te:
            return be and te
        if ba.name == ta.name and len(ba.args) == len(ta.args):
            return True
        return self.b.is_function(ba) and self.t.is_function(ta)

    def _new(self, bi: Term, ti: Term, order: int, local: float) -> int:
        i = len(self.mb)
        self.mb.append(bi)
        self.mt.append(ti)
        self.children.append(())
        self.parents.append([])
        self.ok.append(True)
        self.local.append(local)
        self.order.append(order)
        self.corr.append(None)
        self.index[(bi, ti)] = i
        return i

    def _make(self, bi: Term, ti: Term) -> int:
        i = self.index.get((bi, ti))
        if i is not None:
            return i
        if is_entity(bi):
            i = self._new(bi, ti, 0, 0.0)
            self.corr[i] = {bi: ti}
            return i
        p = self.p
        if bi.name == ti.name:
            local = p.same_functor
        elif self.b.is_function(bi):
            local = p.same_function
        else:  # pragma: no cover - callers only pair alignable items
            local = p.same_functor
        self.functor_pairs.add((bi.name, ti.name))
        order = max(self.b.order[bi], self.t.order[ti])
        i = self._new(bi, ti, order, local)
        if len(bi.args) != len(ti.args) or not all(
            self._alignable(ba, ta) for ba, ta in zip(bi.args, ti.args)
        ):
            self.ok[i] = False
            return i
        kids: list[int] = []
        for ba, ta in zip(bi.args, ti.args):
            c = self._make(ba, ta)
            if c not in kids:
                kids.append(c)
        self.children[i] = tuple(kids)
        for c in kids:
            self.parents[c].append(i)
        # Completeness and consistency propagate upwards.
        b2t: dict[Term, Term] = {bi: ti}
        t2b: dict[Term, Term] = {ti: bi}
        ok = True
        for c in kids:
            if not self.ok[c]:
                ok = False
                break
            for x, y in self.corr[c].items():  # type: ignore[union-attr]
                if b2t.get(x, y) is not y or t2b.get(y, x) is not x:
                    ok = False
                    break
                b2t[x] = y
                t2b[y] = x
            if not ok:
                break
        self.ok[i] = ok
        self.corr[i] = b2t if ok else None
        return i

    def _generate(self) -> None:
        tix = self.t.by_functor
        for be in self.b.exprs:
            for te in tix.get((be.name, len(be.args)), ()):
                self._make(be, te)

    # -- evaluation
    def _global_scores(self) -> list[float]:
        """Trickle-down with each MH taking evidence from a one-to-one set of its parents."""
        n = len(self.mb)
        score = [0.0] * n
        td = self.p.trickle_down
        ok = self.ok
        ids = [i for i in range(n) if ok[i]]
        ids.sort(key=lambda i: -self.order[i])
        mb, mt = self.mb, self.mt
        for i in ids:
            s = self.local[i]
            ps = [q for q in self.parents[i] if ok[q]]
            if len(ps) == 1:
                s += td * score[ps[0]]
            elif ps:
                ps.sort(key=lambda q: -score[q])
                used_b: set[Term] = set()
                used_t: set[Term] = set()
                for q in ps:
                    if mb[q] in used_b or mt[q] in used_t:
                        continue
                    used_b.add(mb[q])
                    used_t.add(mt[q])
                    s += td * score[q]
            score[i] = s
        return score

    def _descendants(self, i: int) -> list[int]:
        out = [i]
        seen = {i}
        k = 0
        while k < len(out):
            for c in self.children[out[k]]:
                if c not in seen:
                    seen.add(c)
                    out.append(c)
            k += 1
        return out

    def _mapping_score(self, ids: set[int]) -> float:
        td = self.p.trickle_down
        sc: dict[int, float] = {}
        total = 0.0
        for i in sorted(ids, key=lambda i: -self.order[i]):
            s = self.local[i]
            for q in self.parents[i]:
                if q in ids:
                    s += td * sc[q]
            sc[i] = s
            total += s
        return total

    def _apply_required(self) -> None:
        """Drop every MH whose correspondences contradict a required one."""
        req_b2t = self.require
        req_t2b = {y: x for x, y in req_b2t.items()}
        for i, corr in enumerate(self.corr):
            if not self.ok[i] or corr is None:
                continue
            for x, y in corr.items():
                if req_b2t.get(x, y) is not y or req_t2b.get(y, x) is not x:
                    self.ok[i] = False
                    self.corr[i] = None
                    break

    def run(self) -> MatchResult:
        self._generate()
        if self.require:
            self._apply_required()
        n = len(self.mb)
        ok = self.ok
        # Roots: ok, non-entity-only-by-parent MHs without an ok parent.
        roots = [i for i in range(n) if ok[i] and not any(ok[q] for q in self.parents[i])]
        gscore = self._global_scores()
        kernels: list[tuple[float, int, list[int], dict[Term, Term]]] = []
        for r in roots:
            desc = self._descendants(r)
            kernels.append((sum(gscore[i] for i in desc), r, desc, self.corr[r]))  # type: ignore[arg-type]
        kernels.sort(key=lambda k: (-k[0], k[1]))
        mappings = self._merge(kernels)
        bs, ts = self.b.self_score, self.t.self_score
        denom = bs + ts
        out: list[Mapping] = []
        for score, ids, b2t, root_ids in mappings:
            sim = 0.0 if denom <= 0 else min(1.0, max(0.0, 2.0 * score / denom))
            fpairs = {(self.mb[i].name, self.mt[i].name) for i in ids if self.mb[i].args and not is_entity(self.mb[i])}
            ents = {str(_from_sme(x)): str(_from_sme(y)) for x, y in b2t.items() if is_entity(x)}
            pairs = {_from_sme(x): _from_sme(y) for x, y in b2t.items()}
            out.append(Mapping(
                score=score, similarity=sim, entities=ents, pairs=pairs,
                mh_count=len(ids) + len(fpairs),
                root_pairs=[(_from_sme(self.mb[i]), _from_sme(self.mt[i])) for i in root_ids],
                _b2t=b2t, _base=self.b, _target=self.t,
            ))
        return MatchResult(
            mappings=out,
            mh_count=n + len(self.functor_pairs),
            kernel_count=len(kernels),
            base_self_score=bs,
            target_self_score=ts,
        )

    def _merge(self, kernels: list) -> list[tuple[float, set[int], dict[Term, Term], list[int]]]:
        p = self.p
        results: list[tuple[float, set[int], dict[Term, Term], list[int]]] = []
        seeded: set[int] = set()  # kernel roots already inside some mapping
        seen_sets: set[frozenset[int]] = set()
        attempts = 0
        for k_index, (_, root, _desc, _corr) in enumerate(kernels):
            if len(results) >= p.max_mappings or attempts >= p.max_mappings:
                break
            if root in seeded:
                continue
            attempts += 1
            ids: set[int] = set()
            b2t: dict[Term, Term] = {}
            t2b: dict[Term, Term] = {}
            roots_in: list[int] = []
            order = [kernels[k_index]] + [k for j, k in enumerate(kernels) if j != k_index]
            for _s, r, desc, corr in order:
                consistent = True
                for x, y in corr.items():
                    if b2t.get(x, y) is not y or t2b.get(y, x) is not x:
                        consistent = False
                        break
                if not consistent:
                    continue
                b2t.update(corr)
                for x, y in corr.items():
                    t2b[y] = x
                ids.update(desc)
                roots_in.append(r)
            seeded.update(roots_in)
            key = frozenset(ids)
            if key in seen_sets:
                continue
            seen_sets.add(key)
            # Roots of the merged mapping: MHs with no parent inside it.
            mroots = [r for r in roots_in if not any(q in ids for q in self.parents[r])]
            results.append((self._mapping_score(ids), ids, b2t, mroots))
        results.sort(key=lambda m: -m[0])
        if results:
            best = results[0][0]
            results = [m for m in results if m[0] >= p.cutoff * best - 1e-12]
        return results[: p.max_mappings]
