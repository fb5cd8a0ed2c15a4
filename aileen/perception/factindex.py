"""A perceived state's facts indexed by object and by pair, built once per state.

Why: the agent asks, per object, for its percepts and, per ordered pair, for the relations
between the two, and a plain scan of the state's facts for each question makes asking about
every object and pair grow with the cube of the number of objects (the facts themselves grow
with its square). One pass over the facts answers every later question by lookup, in the
same order the scan gives.
"""

from __future__ import annotations

from collections.abc import Sequence

from aileen.terms import Term

__all__ = ["FactIndex"]


class FactIndex:
    """`isa` facts by their subject, and binary non-`isa` facts by their unordered pair of
    arguments, each list in the order of the facts given."""

    __slots__ = ("_objects", "_pairs", "size")

    def __init__(self, facts: Sequence[Term]) -> None:
        self._objects: dict[Term, list[Term]] = {}
        self._pairs: dict[frozenset[Term], list[Term]] = {}
        for f in facts:
            if f.name == "isa" and f.args:
                self._objects.setdefault(f.args[0], []).append(f)
            elif len(f.args) == 2:
                self._pairs.setdefault(frozenset(f.args), []).append(f)
        self.size = len(facts)  # how many facts it was built from (to notice a stale index)

    def percepts(self, obj: str | Term) -> list[Term]:
        """The `isa(obj, _)` facts."""
        return list(self._objects.get(obj if isinstance(obj, Term) else Term(obj), ()))

    def relations(self, a: str | Term, b: str | Term) -> list[Term]:
        """The binary facts (other than `isa`) between a and b, in both directions."""
        ta = a if isinstance(a, Term) else Term(a)
        tb = b if isinstance(b, Term) else Term(b)
        return list(self._pairs.get(frozenset((ta, tb)), ()))
