"""The one boundary to clingo: rule files loaded, Term <-> Symbol conversion, solving.

Every other module hands `aileen.terms.Term`s in and gets `Term`s back; only this module
imports clingo. Rule files are loaded *by path* so that clingo's messages carry
`file:line:col`; those messages only reach us through the logger callback (the exception
alone says "parsing failed"), so every `Control` here gets a collecting logger and a
failure becomes a one-line `UserError` such as
`asp/comprehension.lp:12:5: error: syntax error, unexpected ...`.

Where the rules come from and whether their text can be given to clingo:
`aileen.reasoning.rulefiles` (its names are re-exported here).
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import clingo

from aileen.errors import UserError
from aileen.lru import LruMemory
from aileen.reasoning import watchdog
from aileen.reasoning.rulefiles import (  # noqa: F401 - re-exported
    AspError, check_rule_text, own_files, rule_path, rule_paths, rules_dir, shipped_instead,
)
from aileen.terms import Term

__all__ = [
    "AspError",
    "Messages",
    "rules_dir",
    "rule_path",
    "rule_paths",
    "to_symbol",
    "from_symbol",
    "facts_program",
    "new_control",
    "ground_and_solve",
    "solve_once",
    "Incremental",
    "check_rule_files",
    "check_rule_text",
    "RulesError",
    "RulesTimeout",
    "RulesUnsatisfiable",
    "set_solve_limit",
    "solve_limit",
]

class RulesError(UserError):
    """The user's rules, not a lesson, failed: the run stops (exit 2) with what was learned
    saved, where a lesson's own failure would be graded and the run go on."""


class RulesTimeout(RulesError):
    """Grounding or solving took longer than the user's rules are allowed (`--rules-timeout`)."""


class RulesUnsatisfiable(RulesError):
    """The user's rules have no answer set where the shipped rules always have one (a
    constraint `:- obj(O).` in comprehension.lp made every lesson the agent's "failure")."""


# Solving budget per call, seconds (None: no limit), and what to name in the error: set once
# per run by the command line (`set_solve_limit`), so the layers between need not carry it.
_SOLVE_LIMIT: float | None = None
_SOLVE_LABEL = "the rules"


def set_solve_limit(seconds: float | None, label: str | None = None, *,
                    megabytes: float | None = watchdog.DEFAULT_MEMORY_MB) -> None:
    """Limit every later clingo call: a solve that runs longer than `seconds` is interrupted
    with `RulesTimeout` naming `label` (the rule directory); a grounding that does, or any
    call that grows the process by more than `megabytes`, ends the run through the watchdog
    (grounding cannot be interrupted in-process: `reasoning.watchdog`). Very large limits
    mean none (they are capped at `watchdog.MAX_SECONDS`)."""
    global _SOLVE_LIMIT, _SOLVE_LABEL
    _SOLVE_LIMIT = None if seconds is None else min(float(seconds), watchdog.MAX_SECONDS)
    _SOLVE_LABEL = label or "the rules"
    watchdog.set_limits(_SOLVE_LIMIT, megabytes, _SOLVE_LABEL)


def solve_limit() -> tuple[float | None, str]:
    """The limit `set_solve_limit` set (seconds, None for none) and what it names: a search of
    many calls (the planner's horizons) holds its whole run to it as well."""
    return _SOLVE_LIMIT, _SOLVE_LABEL


# ------------------------------------------------------------------------ messages

_LOC = re.compile(r"^(?P<path>.*?):(?P<line>\d+):(?P<col>\d+)(?:-(?:\d+:)?\d+)?: (?P<kind>error|warning|info|note): ")


def _one_line(message: str) -> str:
    """clingo's text with its location shortened to `file:line:col` and folded onto one line."""
    lines = [ln.strip() for ln in message.strip().splitlines() if ln.strip()]
    if not lines:
        return ""
    first = _LOC.sub(lambda m: f"{m['path']}:{m['line']}:{m['col']}: {m['kind']}: ", lines[0])
    rest = [_LOC.sub(lambda m: f"{m['path']}:{m['line']}:{m['col']}: {m['kind']}: ", ln) for ln in lines[1:]]
    return " ".join([first, *rest])


@dataclass
class Messages:
    """What clingo said through the logger, kept in order."""

    items: list[tuple[clingo.MessageCode, str]] = field(default_factory=list)

    def __call__(self, code: clingo.MessageCode, message: str) -> None:
        self.items.append((code, message))

    @property
    def errors(self) -> list[str]:
        return [_one_line(m) for c, m in self.items if ": error: " in m or c == clingo.MessageCode.RuntimeError]

    @property
    def warnings(self) -> list[str]:
        return [_one_line(m) for c, m in self.items if ": error: " not in m and c != clingo.MessageCode.RuntimeError]

    def raise_for(self, exc: BaseException, what: str) -> None:
        errs = self.errors
        if errs:
            more = f" (and {len(errs) - 1} more)" if len(errs) > 1 else ""
            raise AspError(errs[0] + more, messages=errs) from exc
        raise AspError(f"{what}: {exc}") from exc


# ------------------------------------------------------------------------ conversion

_TO_SYM: dict[Term, clingo.Symbol] = {}
_FROM_SYM: dict[clingo.Symbol, Term] = {}
_CACHE_LIMIT = 200_000


_ESCAPE = re.compile(r'\\(.)')
_UNESCAPE_MAP = {"n": "\n"}


def _unescape(body: str) -> str:
    """The text of an ASP string literal body (`\\"`, `\\\\`, `\\n`), non-ASCII kept as is."""
    return _ESCAPE.sub(lambda m: _UNESCAPE_MAP.get(m.group(1), m.group(1)), body)


def _escape(text: str) -> str:
    return text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")


def to_symbol(term: Term) -> clingo.Symbol:
    """The clingo symbol for a Term (cached: terms are interned, so the lookup is by identity)."""
    s = _TO_SYM.get(term)
    if s is not None:
        return s
    name = term.name
    if isinstance(name, int):
        s = clingo.Number(name)
    elif name.startswith('"'):
        s = clingo.String(_unescape(name[1:-1]))
    else:
        s = clingo.Function(name, [to_symbol(a) for a in term.args])
    if len(_TO_SYM) > _CACHE_LIMIT:
        _TO_SYM.clear()
    _TO_SYM[term] = s
    return s


def from_symbol(sym: clingo.Symbol) -> Term:
    """The Term for a clingo symbol (numbers, strings, functions, tuples as `""`-named terms)."""
    t = _FROM_SYM.get(sym)
    if t is not None:
        return t
    st = sym.type
    if st == clingo.SymbolType.Number:
        t = Term(sym.number)
    elif st == clingo.SymbolType.String:
        t = Term('"' + _escape(sym.string) + '"')
    elif st == clingo.SymbolType.Function:
        if not sym.positive:
            raise ValueError(f"classically negated symbol {sym} has no Term form")
        t = Term(sym.name, tuple(from_symbol(a) for a in sym.arguments))
    else:
        raise ValueError(f"symbol {sym} (#inf/#sup) has no Term form")
    if len(_FROM_SYM) > _CACHE_LIMIT:
        _FROM_SYM.clear()
    _FROM_SYM[sym] = t
    return t


def facts_program(facts: Iterable[Term]) -> str:
    """Facts as ASP text (`Term.__str__` is cached, so this is a join)."""
    return "".join(f"{f}.\n" for f in facts)


# ------------------------------------------------------------------------ solving

def new_control(files: Sequence[Path], *, args: Sequence[str] = (), messages: Messages | None = None) -> tuple[clingo.Control, Messages]:
    """A Control with `files` loaded by path; a syntax error raises `AspError` naming file:line:col."""
    msgs = messages if messages is not None else Messages()
    ctl = clingo.Control(list(args), logger=msgs, message_limit=50)
    for path in files:
        check_rule_text(Path(path))
        try:
            ctl.load(str(path))
        except RuntimeError as exc:
            msgs.raise_for(exc, f"loading {path}")
    return ctl, msgs


def _ground(ctl: clingo.Control, msgs: Messages, parts: Sequence[tuple[str, Sequence[clingo.Symbol]]]) -> None:
    try:
        with watchdog.watch("grounding"):
            ctl.ground(parts)
    except RuntimeError as exc:
        msgs.raise_for(exc, "grounding")


def ground_and_solve(ctl: clingo.Control, msgs: Messages, parts: Sequence[tuple[str, Sequence[clingo.Symbol]]] = (("base", ()),)) -> list[Term] | None:
    """Ground `parts`, solve, return the shown atoms of the first model (None if unsatisfiable)."""
    _ground(ctl, msgs, parts)
    return _solve(ctl, msgs)


def _solve(ctl: clingo.Control, msgs: Messages) -> list[Term] | None:
    """The model clingo ends on: the only one for stratified programs, the optimum when the
    rules have `#minimize` (clingo reports ever better models and stops at the optimum).
    Solving runs in clingo's own thread so that a budget (`set_solve_limit`) can stop it."""
    result: list[clingo.Symbol] | None = None

    def on_model(model: clingo.Model) -> None:
        nonlocal result
        result = model.symbols(shown=True)

    try:
        with watchdog.watch("solving", grace=watchdog.SOLVE_GRACE), ctl.solve(on_model=on_model, async_=True) as handle:
            if not handle.wait(_SOLVE_LIMIT):
                handle.cancel()
                advice = ("a busy machine is slower; raise --rules-timeout" if _SOLVE_LABEL == watchdog.SHIPPED
                          else "simplify the rules or raise --rules-timeout")
                raise RulesTimeout(f"solving took longer than {_SOLVE_LIMIT:g} s; {advice}", path=_SOLVE_LABEL)
            handle.get()
    except RuntimeError as exc:
        msgs.raise_for(exc, "solving")
    return None if result is None else [from_symbol(s) for s in result]


def solve_once(files: Sequence[Path], facts: Iterable[Term], *, args: Sequence[str] = ()) -> list[Term] | None:
    """Load `files`, add `facts` to `base`, ground, and return the first model's shown atoms.

    For stratified programs such as comprehension there is exactly one model; None means the
    program is unsatisfiable (a user rule with a constraint, for instance).

    Answers are remembered (`_ANSWERS`): the same rule files (by path and version), options
    and facts give the same answer, and an experiment asks the same question again and
    again (an exam item replayed after a lesson that did not change what the agent infers
    of its scene: three quarters of the comprehension calls of a trial, at 2-3 ms of
    clingo each; issue 25). Errors are not remembered.
    """
    program = facts_program(facts)
    key = _answer_key(files, args, program)
    if key is not None:
        known = _ANSWERS.get(key)
        if known is not None:
            return None if known is _UNSAT else list(known)
    ctl, msgs = new_control(files, args=args)
    ctl.add("base", [], program)
    model = ground_and_solve(ctl, msgs)
    if key is not None:
        _ANSWERS.put(key, _UNSAT if model is None else tuple(model))
    return model


def forget_answers() -> None:
    """Empty `solve_once`'s memory of answers (benchmarks time clingo's own work)."""
    _ANSWERS.clear()


#: How many answers `solve_once` keeps (the least recently used go first).
ANSWERS_KEPT = 1024
_ANSWERS: LruMemory[tuple[Term, ...] | object] = LruMemory(ANSWERS_KEPT)
_UNSAT = object()


def _answer_key(files: Sequence[Path], args: Sequence[str], program: str) -> tuple | None:
    """What decides `solve_once`'s answer: each rule file's path and version (inode, size,
    modification time: a file written again is read again), the options and the facts; None
    (not remembered) when a file cannot be looked at."""
    stamps = []
    for f in files:
        try:
            st = os.stat(f)
        except OSError:
            return None
        stamps.append((str(f), st.st_ino, st.st_size, st.st_mtime_ns))
    return (tuple(stamps), tuple(args), program)


class Incremental:
    """The multi-shot incremental pattern driven one horizon at a time.

    `base` is grounded once (rules plus facts); each `horizon(t)` grounds `step(t)` and
    `check(t)` (`check(0)` alone for t = 0), switches the `query(t)` external on and the
    previous one off, and solves. Calling it with 0, 1, 2, ... is iterative deepening.
    """

    def __init__(self, files: Sequence[Path], facts: Iterable[Term], *, args: Sequence[str] = ()) -> None:
        self.ctl, self.msgs = new_control(files, args=args)
        self.ctl.add("base", [], facts_program(facts))
        _ground(self.ctl, self.msgs, [("base", [])])
        self.t = -1

    def horizon(self, t: int) -> list[Term] | None:
        if t != self.t + 1:
            raise ValueError(f"horizons must be visited in order: expected {self.t + 1}, got {t}")
        num = clingo.Number(t)
        parts: list[tuple[str, Sequence[clingo.Symbol]]] = [("check", [num])]
        if t > 0:
            parts.insert(0, ("step", [num]))
        _ground(self.ctl, self.msgs, parts)
        if t > 0:
            self.ctl.release_external(clingo.Function("query", [clingo.Number(t - 1)]))
        self.ctl.assign_external(clingo.Function("query", [num]), True)
        self.t = t
        return _solve(self.ctl, self.msgs)


def check_rule_files(groups: Iterable[Sequence[Path]], *, horizon: int = 1) -> list[str]:
    """Load and ground each group of rule files with no facts; return the warnings.

    Incremental programs are grounded up to `horizon`; a syntax or grounding error raises
    `AspError` (`file:line:col: error: ...`).
    """
    warnings: list[str] = []
    for files in groups:
        ctl, msgs = new_control(files)
        parts: list[tuple[str, Sequence[clingo.Symbol]]] = [("base", []), ("check", [clingo.Number(0)])]
        for t in range(1, horizon + 1):
            parts += [("step", [clingo.Number(t)]), ("check", [clingo.Number(t)])]
        _ground(ctl, msgs, parts)
        warnings.extend(msgs.warnings)
    return warnings
