"""Terms <-> working-memory structures: the one boundary between `aileen.terms.Term` and Soar.

A fact is an identifier with `^predicate` and its arguments as `^arg1`, `^arg2`, ...:
`isa(o1,cv_red)` is `(<f> ^predicate isa ^arg1 o1 ^arg2 cv_red)`. A nested term is a nested
identifier of the same shape (`h(t0,isa(o1,cv_red))`: `^arg2` is a fact); a constant is a
symbol, a number an integer. The same shapes go both ways: onto the input-link (perceived
facts, inferences) and off the output-link (the facts of a command).

Off the output-link every name is checked as the memory file will read it back: a predicate
is a lowercase ASP constant (`isa`, `r_left_of`; not `5`, not `||`, not `Isa`), a constant
argument is a lowercase constant or an integer (not `|o 1|`, not a float), a `^fact` is a
structure (not a bare `^fact foo`). Anything else is a `MalformedFact` with a message that
names the offending value, so a bad command gets `^status error` and never a stored fact that
would break the saved file.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from typing import Any

from aileen.soar.kernel import SoarKernel, WMNode
from aileen.terms import Term

#: A lowercase ASP constant, as the memory file's term parser reads one back.
CONSTANT = re.compile(r"[a-z][A-Za-z0-9_]*")
_KEYWORDS = frozenset({"not"})  # ASP keywords are no constants
MAX_ARGS = 16  # a fact's arguments: ^arg1 .. ^arg16


class MalformedFact(ValueError):
    """An output-link structure that is not a fact (no `^predicate`, a gap in its args, a
    name the memory file cannot read back)."""


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


def is_constant(name: object) -> bool:
    """Is `name` a symbol the memory file reads back as the same constant?"""
    return isinstance(name, str) and CONSTANT.fullmatch(name) is not None and name not in _KEYWORDS


def symbol(value: object, what: str) -> str:
    """`value` as a constant name (a concept, a predicate); MalformedFact otherwise."""
    if isinstance(value, WMNode):
        raise MalformedFact(f"{what} must be a symbol, found a structure ({value.name})")
    if not is_constant(value):
        raise MalformedFact(f"{what} {_show(value)} is not a lowercase ASP constant")
    return str(value)


def term(value: "str | int | float | WMNode") -> Term:
    """The term an output-link value stands for: a constant, or a fact structure."""
    if isinstance(value, WMNode):
        if value.error:
            raise MalformedFact(value.error)
        pred = symbol(value.get("predicate"), "a fact's ^predicate") if "predicate" in value.attrs \
            else _no_predicate(value)
        for attr, vals in value.attrs.items():
            if len(vals) > 1 and (attr == "predicate" or _arg_index(attr) is not None):
                raise MalformedFact(f"fact {pred}: ^{attr} has {len(vals)} values")
        args = []
        i = 1
        while f"arg{i}" in value.attrs:
            if i > MAX_ARGS:
                raise MalformedFact(f"fact {pred}: more than {MAX_ARGS} arguments")
            args.append(term(value.attrs[f"arg{i}"][0]))
            i += 1
        extra = [a for a in value.attrs if (_arg_index(a) or 0) >= i]
        if extra:
            raise MalformedFact(f"fact {pred}: ^{extra[0]} without ^arg{i}")
        return Term(pred, tuple(args))
    if isinstance(value, bool) or isinstance(value, float):
        raise MalformedFact(f"a fact argument cannot be a float ({value})")
    if isinstance(value, int):
        return Term(value)
    if not is_constant(value):
        raise MalformedFact(f"argument {_show(value)} is not a lowercase ASP constant or an integer")
    return Term(value)


def fact(value: "str | int | float | WMNode") -> Term:
    """A `^fact` (or `^pattern`): a structure with a `^predicate`, never a bare constant."""
    if not isinstance(value, WMNode):
        raise MalformedFact(f"a ^fact must be a structure with a ^predicate, found the constant {_show(value)}")
    return term(value)


def facts(values: Iterable["str | int | float | WMNode"]) -> list[Term]:
    return [fact(v) for v in values]


def terms(values: Iterable["str | int | float | WMNode"]) -> list[Term]:
    return [term(v) for v in values]


def _no_predicate(node: WMNode) -> str:
    raise MalformedFact(f"a fact with no ^predicate ({node.name})")


def _arg_index(attr: str) -> int | None:
    return int(attr[3:]) if attr.startswith("arg") and attr[3:].isdigit() else None


def _show(value: object) -> str:
    if isinstance(value, str):
        return f"|{value}|" if not value or not re.fullmatch(r"[A-Za-z0-9_\-]+", value) else value
    return repr(value)
