"""The action models (`asp/actions.lp`, and each declared action's own model file) held to
their declarations in `aileen/domain/actions.py`: a checked table.

Why: the agent perceives what an action declares it changes (the hand's grasp, the marks a
deed leaves, what the camera shows), and the planner reasons with what the `.lp` rules say.
Were the two to disagree, a plan would count on a fluent that the agent never sees come true
(or the other way round: "push" planned as any action that moves something). So every
declared action must be modelled, and the effects its rules write (`add(F(...),t) :-
occurs(A(...),t), ...` and `del(...)`) must name exactly the fluents it declares, each with
its declared number of arguments. Actions that only a rule file knows (a user's `slide`,
docs/asp.md) are planned as the file says; they are not checked.

The rules are read as text (statements, comments stripped): no clingo here.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from aileen.domain import actions
from aileen.errors import UserError

__all__ = ["Effects", "check", "read_effects"]

_BLOCK_COMMENT = re.compile(r"%\*.*?\*%", re.S)
_LINE_COMMENT = re.compile(r"%[^\n]*")
_END = re.compile(r"\.(?=\s|$)")  # a statement's final period (not the ".." of a range)
_HEAD_EFFECT = re.compile(r"^(add|del)\(\s*([A-Za-z_]\w*)")
_OCCURS = re.compile(r"\boccurs\(\s*([a-z_]\w*)\s*[(,]")
_ACTION = re.compile(r"^action\(\s*([a-z_]\w*)\s*[(),]")
_FLUENT_USE = re.compile(r"\b(?:add|del|holds|init|goal)\(\s*([a-z_]\w*)\s*\(")


@dataclass
class Effects:
    """What the rule files say of one action: where it is modelled, what it adds and deletes
    (fluent name -> the line that says so)."""

    modelled: tuple[Path, int] | None = None
    adds: dict[str, tuple[Path, int]] = field(default_factory=dict)
    dels: dict[str, tuple[Path, int]] = field(default_factory=dict)
    unnamed: tuple[Path, int] | None = None  # an effect whose fluent is a variable (add(F,t))


def _statements(path: Path, text: str) -> Iterable[tuple[int, str]]:
    """(line, statement) for each statement of a rule file, comments removed."""
    text = _BLOCK_COMMENT.sub(lambda m: "\n" * m.group().count("\n"), text)
    text = _LINE_COMMENT.sub("", text)
    start = 0
    for m in _END.finditer(text):
        stmt = text[start:m.start()]
        stripped = stmt.strip()
        if stripped:
            line = text.count("\n", 0, start + len(stmt) - len(stmt.lstrip())) + 1
            yield line, " ".join(stripped.split())
        start = m.end()


def _arity(stmt: str, at: int) -> int:
    """The number of arguments of the term whose "(" is at `at`."""
    depth, count = 0, 1
    for ch in stmt[at:]:
        if ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
            if depth == 0:
                return count
        elif ch == "," and depth == 1:
            count += 1
    return count


def read_effects(paths: Sequence[Path]) -> tuple[dict[str, Effects], list[tuple[str, int, Path, int]]]:
    """Each modelled action's effects, and every fluent term the rules use (name, arity, file,
    line) in `add`, `del`, `holds`, `init` and `goal`."""
    effects: dict[str, Effects] = {}
    uses: list[tuple[str, int, Path, int]] = []
    for path in paths:
        try:
            text = path.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError):
            continue  # clingo's own load names what is wrong with it
        for line, stmt in _statements(path, text):
            head, _, body = stmt.partition(":-")
            head = head.strip()
            m = _ACTION.match(head)
            if m:
                effects.setdefault(m.group(1), Effects()).modelled = (path, line)
            for u in _FLUENT_USE.finditer(stmt):
                uses.append((u.group(1), _arity(stmt, u.end() - 1), path, line))
            e = _HEAD_EFFECT.match(head)
            if e is None:
                continue
            for act in dict.fromkeys(_OCCURS.findall(body)):
                record = effects.setdefault(act, Effects())
                if e.group(2)[0].isupper() or e.group(2)[0] == "_":
                    record.unnamed = record.unnamed or (path, line)
                    continue
                side = record.adds if e.group(1) == "add" else record.dels
                side.setdefault(e.group(2), (path, line))
    return effects, uses


_CHECKED: set[tuple] = set()  # (declarations' version, each file's stamp) already found to agree


def _stamp(paths: Sequence[Path]) -> tuple:
    out: list[object] = [actions.version()]
    for p in paths:
        try:
            st = p.stat()
            out.append((str(p), st.st_mtime_ns, st.st_size))
        except OSError:
            out.append((str(p), None, None))
    return tuple(out)


def check(paths: Sequence[Path]) -> None:
    """Refuse rule files that disagree with the declared actions and fluents: a `UserError`
    naming the file and line (or the file, when something is missing from it). Checked once
    per version of the files and of the declarations."""
    stamp = _stamp(paths)
    if stamp in _CHECKED:
        return
    _check(paths)
    _CHECKED.add(stamp)


def _declared_in(act: "actions.PrimitiveAction") -> str:
    """The file that declares `act`: the module of its world call (a declaration of one's own,
    `AILEEN_DOMAIN`), else aileen/domain/actions.py (a message named the shipped file for a
    user's own declaration)."""
    import inspect

    try:
        source = inspect.getsourcefile(getattr(act.world, "function", act.world))  # (a guarded one's own)
    except TypeError:
        source = None
    package = Path(actions.__file__).resolve().parents[1]  # aileen/
    if source is None or Path(source).resolve().is_relative_to(package):
        return "aileen/domain/actions.py"
    return source


def _check(paths: Sequence[Path]) -> None:
    effects, uses = read_effects(paths)
    declared = ", ".join(sorted(actions.FLUENTS))
    for name, arity, path, line in uses:
        f = actions.FLUENTS.get(name)
        if f is not None and f.arity != arity:
            raise UserError(f"the fluent {name} has {f.arity} argument(s) in aileen/domain/actions.py, "
                            f"here {arity}", path=str(path), line=line)
    where = str(paths[0]) if paths else "actions.lp"
    for act in actions.ACTIONS.values():
        found = effects.get(act.name)
        if found is None or found.modelled is None:
            raise UserError(f"the declared action {act.name} has no model: expected 'action({act.name}(...))' "
                            f"and its rules (poss, add, del)", path=where)
        if found.unnamed is not None:
            path, line = found.unnamed
            raise UserError(f"an effect of {act.name} names its fluent by a variable; write it out "
                            f"(add(rel(P,A,B),t), add(held(O),t)) so it can be held to its declaration",
                            path=str(path), line=line)
        for side, said, want in (("adds", found.adds, act.adds), ("deletes", found.dels, act.dels)):
            extra = [f for f in said if f not in want]
            if extra:
                path, line = said[extra[0]]
                known = "" if extra[0] in actions.FLUENTS else f" (declared fluents: {declared})"
                raise UserError(f"{act.name} {side} {extra[0]} here, but {_declared_in(act)} declares it "
                                f"{side} only {', '.join(want) or 'nothing'}{known}", path=str(path), line=line)
            missing = [f for f in want if f not in said]
            if missing:
                path, line = found.modelled
                raise UserError(f"{act.name} {side} {missing[0]} in {_declared_in(act)}, but no rule "
                                f"'{'add' if side == 'adds' else 'del'}({missing[0]}(...),t) :- occurs({act.name}(...),t)' "
                                f"says so", path=str(path), line=line)
