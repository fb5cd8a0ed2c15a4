"""Declarations of your own, loaded by every aileen process: `AILEEN_DOMAIN`.

Why: the domain is declared once (`channels.declare`, `relations.declare`, `actions.declare`,
...), and a declaration made when a module is imported lasts for the process. A user who adds a
channel, a shape, a relation or a verb of their own should not edit the package to have every
command see it: `aileen run`, `teach`, `serve`, `experiment` and the worker processes a pool or
Ray starts (which inherit the environment) each load the modules named here before any work.

`AILEEN_DOMAIN` names Python modules, separated by `os.pathsep` (":" on Linux) or commas: an
importable module name (`mylab.texture`) or a `.py` file's path (`./texture.py`). Each is
imported once per process; one that fails to import is a one-line `UserError` naming it, the
line of it that failed (the last traceback frame inside it) and why (exit 2), never a traceback.
"""

from __future__ import annotations

import contextlib
import importlib
import importlib.util
import os
import re
import sys
from pathlib import Path

from aileen.errors import UserError

__all__ = ["ENV", "entries", "load"]

ENV = "AILEEN_DOMAIN"

_LOADED: set[str] = set()


def entries(spec: str | None = None) -> list[str]:
    """The modules `spec` names (default: `$AILEEN_DOMAIN`), in order."""
    return _entries(os.environ.get(ENV, "") if spec is None else spec)


def _entries(spec: str) -> list[str]:
    return [e.strip() for e in re.split(rf"[,{re.escape(os.pathsep)}]", spec) if e.strip()]


def _is_file(entry: str) -> bool:
    return entry.endswith(".py") or os.sep in entry


def _key(entry: str) -> str:
    """What an entry loads, whatever it is called: a file by its resolved path ("./texture.py"
    and "texture.py" are one module, imported once), a module by its name."""
    return str(Path(entry).expanduser().resolve()) if _is_file(entry) else entry


def _import(entry: str) -> None:
    if _is_file(entry):
        path = Path(entry).expanduser().resolve()
        if not path.is_file():
            raise UserError("no such Python file")  # (load names the variable and the entry)
        name = "aileen_domain_" + re.sub(r"\W", "_", path.stem)
        spec = importlib.util.spec_from_file_location(name, path)
        if spec is None or spec.loader is None:  # pragma: no cover - a .py file always has one
            raise UserError("cannot load it as a Python module")
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        try:
            spec.loader.exec_module(module)
        except BaseException:
            del sys.modules[name]
            raise
    else:
        importlib.import_module(entry)


def _line_in(entry: str, exc: BaseException) -> str:
    """Where in the user's module `exc` was raised, for the message: " (line 3)" (" (its file,
    line 3)" for a module named by its import name), from the last traceback frame inside that
    file; "" when none is (a syntax error says its line itself). An AttributeError from
    `channels.Chanel` named the module but not the line."""
    if _is_file(entry):
        source: str | None = _key(entry)
    else:
        try:
            spec = importlib.util.find_spec(entry)
        except (ImportError, ValueError):
            spec = None
        source = spec.origin if spec is not None and spec.origin else None
    if source is None:
        return ""
    line = None
    tb = exc.__traceback__
    while tb is not None:
        with contextlib.suppress(OSError, ValueError):
            if os.path.samefile(tb.tb_frame.f_code.co_filename, source):
                line = tb.tb_lineno
        tb = tb.tb_next
    if line is None:
        return ""
    return f" (line {line})" if _is_file(entry) else f" ({source}, line {line})"


def load(spec: str | None = None) -> list[str]:
    """Import the modules `spec` names (default: `$AILEEN_DOMAIN`), each once per process;
    returns the entries loaded by this call. A module that fails is a `UserError` naming it
    (its own `UserError`, from a declaration it makes, keeps its message)."""
    spec = os.environ.get(ENV, "") if spec is None else spec
    done = []
    if _entries(spec):
        # The shipped domain, declared before any of one's own: a declaration is checked
        # against every word declared so far (`spoken`), so a shipped word is always there.
        from aileen.domain import actions, calculi, channels, relations  # noqa: F401
    for entry in _entries(spec):
        if _key(entry) in _LOADED:
            continue
        try:
            _import(entry)
        except UserError as exc:
            raise UserError(f"{ENV}: {entry!r}: {exc.format()}") from None
        except Exception as exc:  # noqa: BLE001 - any failure of a user's module is named, not a traceback
            first = (str(exc).strip().splitlines() or [""])[0]
            at = _line_in(entry, exc)
            raise UserError(f"{ENV}: cannot load {entry!r}{at}: {type(exc).__name__}: {first}") from None
        _LOADED.add(_key(entry))
        done.append(entry)
    return done

