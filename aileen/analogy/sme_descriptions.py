"""SME's descriptions: the parameters, what counts as an entity, and a description prepared
for matching (its expressions each once, children before parents, with parents, orders, an
index by functor and its self score).

Why a module of its own: preparing a description is independent of any comparison (its
result is cached by the facts and reused across the dozens of matches a lesson makes), and
it is the one place that knows AILEEN's conventions at SME's boundary (`isa(O, C)` as the
attribute `isa:C(O)`, `gen_ent`/`skolem` terms as entities). Split from `sme.py`, which
keeps the algorithm's overview and the entry points (`match`, `analyze`) and re-exports
every name that lived there.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from functools import lru_cache

from aileen.terms import Term, as_term

__all__ = ["Params", "is_entity", "self_score", "ENTITY_FUNCTORS"]

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
