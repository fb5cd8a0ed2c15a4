"""Terms <-> working-memory structures: the one boundary between `aileen.terms.Term` and Soar.

A fact is an identifier with `^predicate` and its arguments as `^arg1`, `^arg2`, ...:
`isa(o1,cv_red)` is `(<f> ^predicate isa ^arg1 o1 ^arg2 cv_red)`. A nested term is a nested
identifier of the same shape (`h(t0,isa(o1,cv_red))`: `^arg2` is a fact); a constant is a
symbol, a number an integer. The same shapes go both ways: onto the input-link (perceived
facts, inferences) and off the output-link (the facts of a command).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from aileen.soar.kernel import SoarKernel, WMNode
from aileen.terms import Term


class MalformedFact(ValueError):
    """An output-link structure that is not a fact (no `^predicate`, a gap in its args)."""


def put(kernel: SoarKernel, parent: Any, attr: str, term: Term) -> Any:
    """Add `term` under `(parent ^attr ...)`; returns the WME (remove it to retract it)."""
    if not term.args:
        return kernel.add(parent, attr, term.name if isinstance(term.name, int) else str(term))
    ident = kernel.add(parent, attr)
    kernel.add(ident, "predicate", str(term.name))
    for i, a in enumerate(term.args, 1):
        put(kernel, ident, f"arg{i}", a)
    return ident


def put_all(kernel: SoarKernel, parent: Any, attr: str, terms: Iterable[Term]) -> list[Any]:
    return [put(kernel, parent, attr, t) for t in terms]


def term(value: "str | int | float | WMNode") -> Term:
    """The term an output-link value stands for: a constant, or a fact structure."""
    if isinstance(value, WMNode):
        pred = value.get("predicate")
        if pred is None or isinstance(pred, WMNode):
            raise MalformedFact(f"a fact with no ^predicate ({value.name})")
        args = []
        i = 1
        while f"arg{i}" in value.attrs:
            args.append(term(value.attrs[f"arg{i}"][0]))
            i += 1
        extra = [a for a in value.attrs if a.startswith("arg") and a[3:].isdigit() and int(a[3:]) >= i]
        if extra:
            raise MalformedFact(f"fact {pred}: ^{extra[0]} without ^arg{i}")
        return Term(str(pred), tuple(args))
    if isinstance(value, float):
        raise MalformedFact(f"a fact argument cannot be a float ({value})")
    return Term(value)


def terms(values: Iterable["str | int | float | WMNode"]) -> list[Term]:
    return [term(v) for v in values]
