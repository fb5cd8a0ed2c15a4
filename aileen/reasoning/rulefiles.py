"""Where the rule files come from, and whether clingo can be given them.

Why apart from `aileen.reasoning.asp` (the one module that talks to clingo): finding a rule
file and checking its text come before clingo is asked anything, and `aileen asp check`,
the planner and comprehension all name files the same way. Where the rules come from
(`rules_dir`): the `AILEEN_RULES` environment variable, else the `asp/` folder shipped
inside the package, else the repository's top-level `asp/`. A user's own directory
(`--rules DIR`) overrides shipped files of the same name, file by file.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Sequence
from pathlib import Path

import aileen
from aileen.domain import predicates
from aileen.errors import UserError

__all__ = ["AspError", "own_files", "shipped_instead", "rules_dir", "rule_path", "rule_paths", "readable_rule_paths",
           "check_rule_text", "check_reads"]


class AspError(UserError):
    """A rule file clingo rejected (syntax, unsafe variables, ...): one line, `file:line:col: error: ...`."""

    def __init__(self, message: str, *, messages: Sequence[str] = ()) -> None:
        super().__init__(message)
        self.messages = list(messages)


def rules_dir() -> Path:
    """The directory holding the shipped rule files.

    Checked in order: `$AILEEN_RULES`, `<package>/asp` (a symlink to the repo's `asp/` in a
    checkout, a real folder in an installed wheel), the repository's top-level `asp/`.
    """
    env = os.environ.get("AILEEN_RULES")
    if env:
        p = Path(env)
        if not p.is_dir():
            raise UserError(f"AILEEN_RULES={env} is not a directory")
        return p
    return _shipped_dir()


def _shipped_dir() -> Path:
    """`rules_dir` without `$AILEEN_RULES`: the shipped programs' folder
    (`predicates.shipped_rules`, looked for once per process)."""
    found = predicates.shipped_rules()
    if found is None:
        pkg = Path(aileen.__file__).resolve().parent
        raise UserError(f"no ASP rules found: looked in {pkg / 'asp'} and {pkg.parent / 'asp'} (set AILEEN_RULES)")
    return found


def own_files(files: Iterable[Path]) -> list[Path]:
    """The files of `files` that are not the shipped rules (a `--rules` directory's, an
    `AILEEN_RULES` folder's, a declared action's model): where a program made of them has no
    answer set, they are what to name."""
    shipped = _shipped_dir().resolve()
    return [f for f in files if not Path(f).resolve().is_relative_to(shipped)]


def shipped_instead(files: Iterable[Path], only: Path | None = None) -> list[Path]:
    """`files` with each of one's own (`own_files`; only `only`, when given) replaced by the
    shipped file of its name, where there is one (a declared action's model has none and
    stays): the program the shipped rules make of the same parts, to compare with."""
    shipped = _shipped_dir()
    own = set(own_files(files)) if only is None else {only}
    return [shipped / f.name if f in own and (shipped / f.name).is_file() else f for f in files]


def _user_dir(rules: "str | os.PathLike[str] | None") -> Path | None:
    if rules is None:
        return None
    p = Path(rules)
    if not p.is_dir():
        raise UserError(f"--rules {rules}: not a directory")
    return p


def rule_path(name: str, rules: "str | os.PathLike[str] | None" = None) -> Path:
    """Path of rule file `name`: the user's directory wins over the shipped one. Something of
    that name there that is no file (a folder, a broken link) is an error, not a silent
    fallback to the shipped file."""
    user = _user_dir(rules)
    if user is not None and (user / name).is_file():
        return user / name
    if user is not None and ((user / name).exists() or (user / name).is_symlink()):
        raise UserError(f"{user / name}: not a readable file (a folder or a broken link); the rules' "
                        f"{name} must be a file, or be left out to use the shipped one")
    p = rules_dir() / name
    if not p.is_file():
        raise UserError(f"rule file {name} not found in {rules_dir()}" + (f" or {user}" if user else ""))
    return p


def rule_paths(names: Iterable[str], rules: "str | os.PathLike[str] | None" = None) -> list[Path]:
    return [rule_path(n, rules) for n in names]


def readable_rule_paths(names: Iterable[str], rules: "str | os.PathLike[str] | None" = None) -> list[Path]:
    """`rule_paths`, each file opened once to see that it can be read: a `UserError` naming the
    first that is missing or unreadable. Why: a command that runs lessons calls clingo only
    inside a lesson, where a missing `asp/` (a broken install) was each lesson's "failure" (no
    ASP rules found), graded, exit 0 or 1, and the memory saved; checked before the first
    lesson, it is one line and exit 2."""
    paths = rule_paths(names, rules)
    for p in paths:
        try:
            with p.open("rb"):
                pass
        except OSError as exc:
            raise UserError(f"{p}: cannot read the rule file ({exc.strerror}); the agent needs it to reason "
                            "(reinstall aileen, or set AILEEN_RULES to a folder of the rules)") from None
    return paths


_CHECKED: dict[Path, tuple[int, int]] = {}


def check_rule_text(path: Path) -> None:
    """A rule file clingo can be given: UTF-8 text, and no character outside ASCII except in
    strings and comments. Clingo names only ASCII; its message about another character cuts
    the character's bytes in two, and the Python binding then aborts the whole process
    ("PANIC"), so we name the place first: `file:line:col: error: ...`. Checked once per
    version of the file."""
    try:
        st = path.stat()
        stamp = (st.st_mtime_ns, st.st_size)
        if _CHECKED.get(path) == stamp:
            return
        data = path.read_bytes()
    except OSError:
        return  # clingo's own load names what is wrong
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise AspError(f"{path}:{line}: error: not UTF-8 text (byte {exc.start}); a rule file must be text") from None
    where = _non_ascii(text)
    if where is not None:
        line, col, ch = where
        raise AspError(f"{path}:{line}:{col}: error: unexpected character {ch!r}: names and variables are "
                       "ASCII letters, digits and '_' (other characters may stand in \"strings\" and % comments)")
    _CHECKED[path] = stamp


def _non_ascii(text: str) -> tuple[int, int, str] | None:
    """(line, column, character) of the first non-ASCII character outside strings, comments
    and `#script` blocks, or None."""
    i, n, line, start = 0, len(text), 1, 0
    while i < n:
        c = text[i]
        if c == "\n":
            line, start = line + 1, i + 1
        elif c == "%":
            end = text.find("*%", i + 2) + 2 if text.startswith("%*", i) else text.find("\n", i)
            if end <= 1 or end == -1:
                return None
            line += text.count("\n", i, end)
            if "\n" in text[i:end]:
                start = text.rfind("\n", i, end) + 1
            i = end
            continue
        elif c == '"':
            j = i + 1
            while j < n and text[j] not in '"\n':
                j += 2 if text[j] == "\\" else 1
            i = j + 1
            continue
        elif text.startswith("#script", i):
            end = text.find("#end", i)
            if end == -1:
                return None
            line += text.count("\n", i, end)
            start = text.rfind("\n", 0, end) + 1
            i = end
            continue
        elif ord(c) > 127:
            return line, i - start + 1, c
        i += 1
    return None


def _code(text: str) -> str:
    """The text without its comments (`%` to the line's end, `%* ... *%` blocks), roughly:
    enough to see which `#show` statements and names a rule file has."""
    import re

    text = re.sub(r"%\*.*?\*%", " ", text, flags=re.S)
    return re.sub(r"%[^\n]*", "", text)


def check_reads(groups: Iterable[Sequence[Path]], reads: "dict[str, tuple[str, ...]]") -> None:
    """Each group of rule files (those clingo is given together) still gives what the program
    reads of its answer sets (`reads`: a file name -> `name/arity` signatures): where the
    group has `#show` statements (clingo then shows only what they name), one for each; where
    it has none (clingo shows every atom), each name at least in its file. An edited file that
    dropped `#show referent/2.` passed `aileen asp check` and then answered wrongly without
    a word (every object "-"); an empty comprehension.lp learned nothing. A file that cannot
    be read is left to clingo's own message."""
    import re

    for group in groups:
        codes: dict[Path, str] = {}
        for path in group:
            try:
                codes[path] = _code(path.read_text(encoding="utf-8"))
            except (OSError, UnicodeDecodeError):
                continue
        shown = {f"{m.group(1)}/{m.group(2)}" for code in codes.values()
                 for m in re.finditer(r"#show\s+(-?[a-z_]\w*)\s*/\s*(\d+)\s*\.", code)}
        any_show = any(re.search(r"#show\b", code) for code in codes.values())
        for path, code in codes.items():
            for sig in reads.get(path.name, ()):
                name = sig.split("/")[0]
                missing = sig not in shown if any_show else re.search(rf"\b{re.escape(name)}\s*\(", code) is None
                if missing:
                    what = f"show {sig} (`#show {sig}.`)" if any_show else f"derive {sig} (the file never names {name})"
                    raise AspError(f"{path}:1: error: the rules must {what}: the agent reads it from "
                                   f"{path.name}'s answers")


def unused_files(rules: "str | os.PathLike[str]", known: Iterable[str]) -> list[str]:
    """Warnings for the .lp files of a user's rule directory that aileen never loads by name
    (`comprehention.lp`, `Comprehension.LP`): checked, but used only where a loaded file
    `#include`s them; a near miss of a loaded name is said as such."""
    import difflib

    names = sorted(set(known))
    out = []
    for p in sorted(Path(rules).iterdir()):
        if not p.is_file() or p.suffix.lower() != ".lp" or p.name in names:
            continue
        near = difflib.get_close_matches(p.name.lower(), names, n=1, cutoff=0.8)
        hint = f" (did you mean {near[0]}?)" if near else ""
        out.append(f"warning: {p}: aileen loads {', '.join(names)} by name; this file is used only where one of "
                   f"them #includes it{hint}")
    return out

