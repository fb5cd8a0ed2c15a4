"""A time limit on the user's own rules (`--rules-timeout`), checked before a run.

Why a child process: clingo's grounding cannot be interrupted from Python (the call holds
the interpreter until it returns), so a rule without an end (`nn(X+1) :- nn(X).`) would hang
the run for ever. The rules are loaded and grounded once in a spawned child process; when it
does not answer within the limit it is terminated and the run stops with a one-line error
naming the rule directory, before the first lesson. Solving, which can be interrupted, is
limited in-process (`asp.set_solve_limit`). Rules that only blow up with a lesson's facts
are beyond this check (their solving is still limited).

The child imports clingo through `aileen.reasoning.asp`, which stays the only clingo module.
"""

from __future__ import annotations

import multiprocessing as mp
import os
from collections.abc import Sequence
from multiprocessing.connection import Connection
from pathlib import Path

from aileen.errors import UserError

__all__ = ["DEFAULT_TIMEOUT", "STARTUP_S", "check_rules"]

#: Seconds the user's rules get for grounding (here) and for each solve (in the run).
DEFAULT_TIMEOUT = 10.0
#: Seconds the child may take to start (import aileen and clingo) before the clock starts.
STARTUP_S = 60.0


def _child(groups: list[list[str]], conn: Connection) -> None:
    """In the child: import, say so, ground, send the warnings or the error message."""
    from aileen.reasoning import asp

    conn.send(("ready", None))
    try:
        warnings = asp.check_rule_files([[Path(f) for f in g] for g in groups])
    except UserError as exc:
        conn.send(("error", exc.message))
    else:
        conn.send(("ok", warnings))
    conn.close()


def check_rules(groups: Sequence[Sequence[os.PathLike[str] | str]], *, timeout: float = DEFAULT_TIMEOUT,
                label: str = "the rules") -> list[str]:
    """Load and ground each group of rule files in a child process within `timeout` seconds.

    Returns clingo's warnings; a syntax or grounding error is the usual `AspError`-style
    `UserError` (`file:line:col: error: ...`); running past the limit is a `RulesTimeout`
    naming `label`.
    """
    from aileen.reasoning.asp import RulesTimeout

    ctx = mp.get_context("spawn")
    parent, child = ctx.Pipe(duplex=False)
    proc = ctx.Process(target=_child, args=([[str(f) for f in g] for g in groups], child), daemon=True)
    proc.start()
    child.close()
    try:
        if not parent.poll(STARTUP_S):
            raise UserError("could not start a process to check the rules", path=label)
        parent.recv()  # "ready"
        if not parent.poll(timeout):
            raise RulesTimeout(f"grounding the rules took longer than {timeout:g} s (a rule that never "
                               "ends, such as 'n(X+1) :- n(X).'?); fix the rules or raise --rules-timeout",
                               path=label)
        kind, payload = parent.recv()
    except EOFError:
        raise UserError("the rule check ended without an answer (clingo crashed?)", path=label) from None
    finally:
        if proc.is_alive():
            proc.terminate()
        proc.join(5)
        if proc.is_alive():  # pragma: no cover - terminate is enough for clingo
            proc.kill()
            proc.join()
        parent.close()
    if kind == "error":
        raise UserError(payload)
    return list(payload)
