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

Where each part lives (one job per module; this module keeps the overview, the entry points
`match` and `analyze`, and re-exports every name that lived here before the split, so
`sme.X` works as before):

- `sme_descriptions.py`: `Params`, what an entity is, the `isa` conversion, and a description
  prepared once for matching (expressions, parents, orders, functor index, `self_score`);
- `sme_hypotheses.py`: steps 1-2, the match hypotheses of one comparison and their
  structural consistency (and required correspondences);
- `sme_merge.py`: steps 3, 4 and 6, structural evaluation, kernels, the greedy merge and
  the similarity of each mapping;
- `sme_mappings.py`: `Mapping`, `MatchResult` and step 5, candidate inferences.
"""

from __future__ import annotations

from collections.abc import Iterable

# The pieces live in modules of one job each (the module was split at 555 lines); every name
# that lived here is re-exported, so `sme.X` works as before.
from aileen.analogy.sme_descriptions import (  # noqa: F401  (re-exported)
    _ISA_PREFIX, _SKOLEM, ENTITY_FUNCTORS, Params, _as_fact_tuple, _Desc, _from_sme, _identity_score, _prepare,
    _to_sme, is_entity, self_score,
)
from aileen.analogy.sme_mappings import Mapping, MatchResult, _candidate_inferences, _translate  # noqa: F401
from aileen.analogy.sme_merge import _Engine
from aileen.terms import Term

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
