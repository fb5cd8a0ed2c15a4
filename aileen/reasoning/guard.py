"""Limits on the user's own rules (`--rules-timeout`, `--rules-memory`), checked before a run.

Why a child process: clingo's grounding cannot be interrupted from Python (the call holds
the run until it returns), so a rule without an end (`nn(X+1) :- nn(X).`) would hang the run
for ever. The rules are loaded and grounded once, without facts, in a spawned child process;
when it does not answer within the limit it is terminated, and when it grows past the memory
bound it reports so and ends; either way the run stops with a one-line error naming the rule
directory, before the first lesson. Rules that only blow up with a lesson's facts pass this
check; during the run every clingo call is watched under the same limits
(`reasoning.watchdog`), which ends the run with exit 2 after saving what was learned.

The child imports clingo through `aileen.reasoning.asp`, which stays the only clingo module.
"""

from __future__ import annotations

import argparse
import multiprocessing as mp
import os
from collections.abc import Sequence
from multiprocessing.connection import Connection
from pathlib import Path

from aileen.errors import UserError

__all__ = ["DEFAULT_TIMEOUT", "STARTUP_S", "check_rules", "add_limit_args"]

#: Seconds the user's rules get for grounding (here) and for each solve (in the run).
DEFAULT_TIMEOUT = 10.0
#: Seconds the child may take to start (import aileen and clingo) before the clock starts.
STARTUP_S = 60.0


def add_limit_args(p: argparse.ArgumentParser) -> None:
    """`--rules-timeout S` and `--rules-memory MB`, the same in every command that runs rules."""
    from aileen import argtypes
    from aileen.reasoning.watchdog import DEFAULT_MEMORY_MB

    p.add_argument("--rules-timeout", type=argtypes.seconds, default=DEFAULT_TIMEOUT, metavar="S",
                   help=f"seconds each clingo call may take, grounding and solving (default {DEFAULT_TIMEOUT:g}); "
                   "a call past it stops the run with exit 2, what was learned saved")
    p.add_argument("--rules-memory", type=argtypes.megabytes, default=DEFAULT_MEMORY_MB, metavar="MB",
                   help=f"megabytes of memory each clingo call may add (default {DEFAULT_MEMORY_MB:g}); "
                   "past it, the same")


def _child(groups: list[list[str]], conn: Connection, megabytes: float | None = None) -> None:
    """In the child: import, say so, ground (under the memory bound: the watchdog reports to
    the parent and ends the child), send the warnings or the error message."""
    from aileen.reasoning import asp, watchdog

    def report(message: str, status: int) -> None:
        conn.send(("limit", message.split(": ", 1)[-1]))
        conn.close()
        os._exit(status)

    watchdog.on_limit = report
    watchdog.set_limits(None, megabytes)
    conn.send(("ready", None))
    try:
        warnings = asp.check_rule_files([[Path(f) for f in g] for g in groups])
    except UserError as exc:
        conn.send(("error", exc.message))
    else:
        conn.send(("ok", warnings))
    conn.close()


def check_rules(groups: Sequence[Sequence[os.PathLike[str] | str]], *, timeout: float = DEFAULT_TIMEOUT,
                label: str = "the rules", megabytes: float | None = None) -> list[str]:
    """Load and ground each group of rule files in a child process within `timeout` seconds
    (and `megabytes` of memory growth, when given).

    Returns clingo's warnings; a syntax or grounding error is the usual `AspError`-style
    `UserError` (`file:line:col: error: ...`); running past the limit is a `RulesTimeout`
    naming `label`, and so is growing past the memory bound.
    """
    from aileen.reasoning.asp import RulesTimeout
    from aileen.reasoning.watchdog import MAX_SECONDS

    timeout = min(timeout, MAX_SECONDS)
    ctx = mp.get_context("spawn")
    parent, child = ctx.Pipe(duplex=False)
    proc = ctx.Process(target=_child, args=([[str(f) for f in g] for g in groups], child, megabytes), daemon=True)
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
    if kind == "limit":
        raise RulesTimeout(payload, path=label)
    if kind == "error":
        raise UserError(payload)
    return list(payload)
