"""The one conversion between binary relation facts and their ASP-side form.

Everywhere else a relation is its own predicate (`w(o1,o2)`, `r_left_of(o1,o2)`): SME aligns
identical predicates, so the relation must be the predicate. ASP rules, though, need to talk
about any relation generically, and clingo cannot put a variable in predicate position; so on
the way into clingo a binary relation fact becomes `rel(w,o1,o2)`, and on the way back the
reverse. Comprehension and planning both convert here.
"""

from __future__ import annotations

from aileen.terms import Term

# Binary predicates that are not relations between two objects.
NOT_RELATIONS = frozenset({"isa", "obj", "rel", "word_concept"})


def is_relation(f: Term) -> bool:
    """A binary fact between two plain constants whose predicate is a relation name."""
    known = _RELATION.get(f)
    if known is None:
        known = _RELATION[f] = (
            len(f.args) == 2
            and isinstance(f.name, str)
            and f.name not in NOT_RELATIONS
            and not f.name.startswith('"')
            and all(not a.args and isinstance(a.name, str) for a in f.args)
        )
    return known


def reify(f: Term) -> Term:
    """`w(o1,o2)` -> `rel(w,o1,o2)`; any other fact unchanged."""
    r = _REIFIED.get(f)
    if r is None:
        r = _REIFIED[f] = Term("rel", (Term(f.name), f.args[0], f.args[1])) if is_relation(f) else f
    return r


# Terms are interned and never change, so whether one is a relation, and its reified form,
# are worked out once per term: every comprehension call asks them of every fact of the
# scene (issue 25).
_RELATION: dict[Term, bool] = {}
_REIFIED: dict[Term, Term] = {}


def unreify(f: Term) -> Term:
    """`rel(w,o1,o2)` -> `w(o1,o2)`; any other fact unchanged."""
    if f.name == "rel" and len(f.args) == 3 and not f.args[0].args:
        return Term(f.args[0].name, (f.args[1], f.args[2]))
    return f
