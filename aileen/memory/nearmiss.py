"""Near misses: negative examples that narrow a concept (SAGE's extension, McLure et al. 2015).

Why: a concept learned from positive examples alone can over-reach. "grox", taught on green
boxes while "box" is a known word and "green" is not, accepts a green cylinder (query-time
mutual exclusivity strips the percepts another word claims, and leaves grox the colour). When the trainer says the agent's "yes" was wrong, the
scene is a near miss: compared with the concept's description it matched, the facts of the
description that the near miss lacks are what made the difference. They become *required* for
that description: a query's match must keep them (and mutual exclusivity may not strip them).

Required facts are computed from the stored near misses when a query needs them, not stored,
because SAGE renames a generalization's entities as it merges examples.
"""

from __future__ import annotations

from collections.abc import Sequence

from aileen.analogy import sme
from aileen.analogy.sage import GeneralizationContext, SageParams
from aileen.domain import calculi
from aileen.terms import Term

Key = tuple[str, int]  # (description kind, index), as `GeneralizationContext.descriptions` gives


def _names_concept(fact: Term, concept: str) -> bool:
    if fact.name == concept:
        return True
    return fact.name == "isa" and len(fact.args) == 2 and str(fact.args[1]) == concept


def required(context: GeneralizationContext, near_misses: Sequence[Sequence[Term]],
             params: SageParams) -> dict[Key, frozenset[Term]]:
    """Per description of the concept, the facts some near miss lacks where it matched the
    description best (the membership fact itself excepted). Descriptions that no near miss
    matches at all have none."""
    out: dict[Key, frozenset[Term]] = {}
    if not near_misses:
        return out
    for kind, i, facts in context.descriptions(params):
        need: set[Term] = set()
        for nm in near_misses:
            ms = sme.match(facts, list(nm), functions=params.functions, params=params.sme)
            if not ms:
                continue
            kept = ms[0].pairs
            # a band of a finer grain (`calculi.FINER`) is read as a region by the size
            # principle (memory/reach.py), never required one by one
            need.update(f for f in facts if f not in kept and not _names_concept(f, context.concept)
                        and not calculi.is_finer(f.name))
        if need:
            out[(kind, i)] = frozenset(need)
    return out


def keeps(mapping: sme.Mapping, need: frozenset[Term]) -> bool:
    """Does a match keep every required fact?"""
    return all(f in mapping.pairs for f in need)
