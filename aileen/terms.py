"""The one symbolic fact type used by SME, SAGE, the memories and (at its boundary) ASP.

Terms are interned: building the same term twice returns the same object, so equality and
hashing are identity operations. SME compares and hashes facts millions of times per
experiment, and `clingo.Symbol` allocates on every `.arguments` access, so symbolic work
happens on these objects and converts to clingo only in `aileen.reasoning.asp`.

Textual form is ASP syntax: `isa(o1,cv_red)`, `h(t0,w(o1,o2))`, `skolem(gen_ent(0,r_red))`.
Names that start with an uppercase letter or `_` are variables (as in ASP); they only
matter to `unify` and `substitute`, otherwise they are ordinary constants.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator, Mapping
from typing import Union

__all__ = [
    "CONSTANT",
    "DECLARED_NAME",
    "Term",
    "TermSyntaxError",
    "const",
    "fn",
    "parse",
    "parse_many",
    "as_term",
    "as_terms",
    "unify",
    "substitute",
    "variables",
    "sort_key",
]

Name = Union[str, int]


class TermSyntaxError(ValueError):
    """Text that is not a term; `position` is the 0-based character offset of the problem."""

    def __init__(self, message: str, text: str, position: int) -> None:
        shown = text if len(text) <= 80 else text[:60] + " ... " + text[-15:]  # one readable line
        super().__init__(f"{message} at position {position} in {shown!r}")
        self.text = text
        self.position = position
        self.reason = message


_INTERN: dict[tuple[Name, tuple["Term", ...]], "Term"] = {}


class Term:
    """An interned constant, integer, quoted string, or compound `name(arg, ...)`.

    `name` is a `str` (identifiers and quoted strings, quotes included) or an `int`.
    """

    __slots__ = ("name", "args", "_str", "__weakref__")
    name: Name
    args: tuple["Term", ...]

    def __new__(cls, name: Name, args: tuple["Term", ...] = ()) -> "Term":
        key = (name, args)
        term = _INTERN.get(key)
        if term is None:
            if not isinstance(args, tuple):
                raise TypeError("Term args must be a tuple of Terms")
            for a in args:
                if not isinstance(a, Term):
                    raise TypeError(f"Term argument {a!r} is not a Term")
            if isinstance(name, bool) or not isinstance(name, (str, int)):
                raise TypeError(f"Term name {name!r} must be str or int")
            if isinstance(name, int) and args:
                raise TypeError("a number cannot have arguments")
            term = object.__new__(cls)
            object.__setattr__(term, "name", name)
            object.__setattr__(term, "args", args)
            object.__setattr__(term, "_str", None)
            term = _INTERN.setdefault(key, term)
        return term

    def __setattr__(self, key: str, value: object) -> None:
        raise AttributeError("Term is immutable")

    def __reduce__(self) -> tuple[type, tuple[Name, tuple["Term", ...]]]:
        # Unpickling goes through __new__, so terms stay interned across processes.
        return (Term, (self.name, self.args))

    def __copy__(self) -> "Term":
        return self

    def __deepcopy__(self, memo: dict) -> "Term":
        return self

    @property
    def arity(self) -> int:
        return len(self.args)

    @property
    def is_compound(self) -> bool:
        return bool(self.args)

    @property
    def is_number(self) -> bool:
        return isinstance(self.name, int)

    @property
    def is_variable(self) -> bool:
        n = self.name
        return not self.args and isinstance(n, str) and bool(n) and (n[0].isupper() or n[0] == "_")

    @property
    def is_ground(self) -> bool:
        return not any(True for _ in variables(self))

    def __str__(self) -> str:
        s = self._str
        if s is None:
            if self.args:
                s = f"{self.name}({','.join(str(a) for a in self.args)})"
            else:
                s = str(self.name)
            object.__setattr__(self, "_str", s)
        return s

    def __repr__(self) -> str:
        return f"Term({str(self)!r})"

    def __lt__(self, other: "Term") -> bool:
        return sort_key(self) < sort_key(other)

    def __iter__(self) -> Iterator["Term"]:
        """Every subterm, this one first (pre-order)."""
        stack = [self]
        while stack:
            t = stack.pop()
            yield t
            stack.extend(reversed(t.args))


def sort_key(t: Term) -> tuple:
    """A total order that is stable across runs (numbers before symbols, then by text)."""
    return (0, t.name, "") if isinstance(t.name, int) else (1, 0, str(t))


def const(name: Name) -> Term:
    return Term(name)


def fn(name: str, *args: "Term | str | int") -> Term:
    """Build `name(args...)`; plain strings and ints become constants."""
    return Term(name, tuple(a if isinstance(a, Term) else Term(a) for a in args))


# ---------------------------------------------------------------------------- parsing

_STRING = r'"(?:[^"\\]|\\.)*"'
_TOKEN = re.compile(
    r"""\s*(?:
        (?P<num>-?\d+)
      | (?P<id>_*[A-Za-z][A-Za-z0-9_']*|_)
      | (?P<str>""" + _STRING + r""")
      | (?P<punct>[(),.])
    )""",
    re.VERBOSE,
)
#: A constant's name as `parse` reads one: an identifier that is no variable (lowercase first)
#: or a quoted string. What a stored fact may be made of (`memory.compact` checks its names).
CONSTANT = re.compile(r"[a-z][A-Za-z0-9_']*|" + _STRING)
#: A name the domain declares (a calculus's relation, a channel's value): a constant in
#: lowercase letters, digits and "_", which the readers and clingo both read as itself.
DECLARED_NAME = re.compile(r"[a-z][a-z0-9_]*")


class _Parser:
    def __init__(self, text: str) -> None:
        self.text = text
        self.pos = 0
        self.tok_kind: str | None = None
        self.tok_val = ""
        self.tok_pos = 0
        self._advance()

    def _advance(self) -> None:
        text = self.text
        m = _TOKEN.match(text, self.pos)
        if m is None or m.lastgroup is None:
            rest = text[self.pos :]
            stripped = rest.lstrip()
            if not stripped:
                self.tok_kind, self.tok_val, self.tok_pos = None, "", len(text)
                self.pos = len(text)
                return
            where = len(text) - len(stripped)
            raise TermSyntaxError(f"unexpected character {stripped[0]!r}", text, where)
        self.tok_kind = m.lastgroup
        self.tok_val = m.group(m.lastgroup)
        self.tok_pos = m.start(m.lastgroup)
        self.pos = m.end()

    def error(self, expected: str) -> TermSyntaxError:
        found = "end of text" if self.tok_kind is None else repr(self.tok_val)
        return TermSyntaxError(f"expected {expected}, found {found}", self.text, self.tok_pos)

    def term(self, depth: int = 0) -> Term:
        kind, val = self.tok_kind, self.tok_val
        if depth > MAX_DEPTH:  # every step below recurses: a deeper term ends in a RecursionError
            raise TermSyntaxError(f"a term nested more than {MAX_DEPTH} deep", self.text, self.tok_pos)
        if kind == "num":
            self._advance()
            return Term(int(val))
        if kind == "str":
            self._advance()
            return Term(val)
        if kind != "id":
            raise self.error("a term")
        self._advance()
        if self.tok_kind == "punct" and self.tok_val == "(":
            self._advance()
            args = [self.term(depth + 1)]
            while self.tok_kind == "punct" and self.tok_val == ",":
                self._advance()
                args.append(self.term(depth + 1))
            if not (self.tok_kind == "punct" and self.tok_val == ")"):
                raise self.error("',' or ')'")
            self._advance()
            return Term(val, tuple(args))
        return Term(val)


#: The deepest nesting `parse` reads (the domain's facts nest two or three deep; a memory file
#: with a term nested 300 deep loaded, and its save ended in a RecursionError, losing a run).
MAX_DEPTH = 64


def parse(text: str) -> Term:
    """Parse one term in ASP syntax; a trailing '.' is allowed."""
    p = _Parser(text)
    t = p.term()
    if p.tok_kind == "punct" and p.tok_val == ".":
        p._advance()
    if p.tok_kind is not None:
        raise p.error("end of term")
    return t


def parse_many(text: str) -> list[Term]:
    """Parse facts separated by '.' and/or whitespace, e.g. the body of a `.lp` fact file."""
    p = _Parser(text)
    out: list[Term] = []
    while p.tok_kind is not None:
        out.append(p.term())
        if p.tok_kind == "punct" and p.tok_val == ".":
            p._advance()
    return out


def as_term(x: "Term | str") -> Term:
    return x if isinstance(x, Term) else parse(x)


def as_terms(xs: Iterable["Term | str"]) -> list[Term]:
    return [as_term(x) for x in xs]


# ---------------------------------------------------------------------------- matching

def unify(pattern: Term, term: Term, binding: Mapping[Term, Term] | None = None) -> dict[Term, Term] | None:
    """One-way matching: the variables of `pattern` bound so that it equals `term`, or None."""
    b: dict[Term, Term] = dict(binding) if binding else {}
    stack = [(pattern, term)]
    while stack:
        p, t = stack.pop()
        if p is t:
            continue
        if p.is_variable:
            if p.name == "_":
                continue
            bound = b.get(p)
            if bound is None:
                b[p] = t
            elif bound is not t:
                return None
            continue
        if p.name != t.name or len(p.args) != len(t.args):
            return None
        stack.extend(zip(p.args, t.args))
    return b


def substitute(t: Term, mapping: Mapping[Term, Term]) -> Term:
    """Replace every subterm found in `mapping` (outermost first)."""
    r = mapping.get(t)
    if r is not None:
        return r
    if not t.args:
        return t
    new = tuple(substitute(a, mapping) for a in t.args)
    return t if new == t.args else Term(t.name, new)


def variables(t: Term) -> Iterator[Term]:
    return (s for s in t if s.is_variable)

