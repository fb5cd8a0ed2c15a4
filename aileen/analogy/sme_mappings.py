"""SME's results: a global mapping (`Mapping`), everything a comparison produced
(`MatchResult`), and a mapping's candidate inferences.

Why a module of its own: what a mapping says (its correspondences, translated back into
AILEEN syntax, and the inferences it licenses, computed lazily) is read by every caller,
while how mappings are found (`sme_hypotheses.py`, `sme_merge.py`) is read by none. Split
from `sme.py`, which re-exports `Mapping` and `MatchResult`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from aileen.analogy.sme_descriptions import _SKOLEM, _Desc, _from_sme, is_entity
from aileen.terms import Term

__all__ = ["Mapping", "MatchResult"]


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
