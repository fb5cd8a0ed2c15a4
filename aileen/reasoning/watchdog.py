"""Limits on every clingo call, grounding included: time, memory, and stop signals.

Why a thread: clingo's grounding cannot be interrupted (there is no API for it, and it does not
return to Python until done), so rules that blow up only on a lesson's facts (`nn(O,0) :-
obj(O). nn(O,X+1) :- nn(O,X).`) ground for ever, taking about 100 MB a second, and no signal
handler runs meanwhile. Clingo releases the interpreter lock while it works, so a thread can
watch the call: when it runs past its time limit, past its memory bound, or a stop signal
arrives (`aileen.lifecycle.wakeup_fd`) while the main thread is inside it, the watchdog ends
the process the one way left, after saving what was learned (`lifecycle.emergency`): one line
naming the rules and the limit, exit status 2 (128 + the signal's number for a signal).

The calls are watched only once limits are set (`set_limits`, by the command line from
`--rules-timeout` and `--rules-memory`); experiments and library use set none, and pay nothing.
Solving can be interrupted and keeps its in-process limit (`asp._solve`), which ends in a
`RulesTimeout` like any error; the watchdog gives it `SOLVE_GRACE` seconds more before it
steps in. Memory is the process's resident size, read from /proc where there is one (else
the peak, from `resource`), counted from the call's start.
"""

from __future__ import annotations

import contextlib
import os
import select
import threading
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass

__all__ = ["DEFAULT_MEMORY_MB", "MAX_SECONDS", "SOLVE_GRACE", "Limits", "set_limits", "limits", "watch",
           "resident_bytes"]

#: Megabytes one clingo call may add to the process before it is stopped (`--rules-memory`).
DEFAULT_MEMORY_MB = 2048.0
#: The longest wait any clock here is given: larger limits (`--rules-timeout 1e9`) mean "no
#: limit", and the operating system's timers overflow on them.
MAX_SECONDS = 7 * 24 * 3600.0
#: Seconds past the limit before the watchdog ends a solve that its own limit did not stop.
SOLVE_GRACE = 2.0
#: How often a running call is looked at, seconds.
POLL = 0.05


@dataclass(frozen=True)
class Limits:
    """Per clingo call: seconds (None: no limit), megabytes of growth (None: no bound), and
    what to name in the error (the rule directory)."""

    seconds: float | None = None
    megabytes: float | None = None
    label: str = "the rules"


@dataclass
class _Call:
    what: str
    start: float
    deadline: float | None
    main: bool
    limits: Limits
    rss0: int | None = None  # taken by the watchdog when it first sees the call


_limits = Limits()
_lock = threading.Lock()
_current: _Call | None = None
_firing = False
_thread: threading.Thread | None = None
#: What ends the process when a limit is passed: (message, exit status) -> never returns.
#: `lifecycle.emergency` by default; the rule-check child (`guard`) reports to its parent instead.
on_limit: Callable[[str, int], None] | None = None


def set_limits(seconds: float | None, megabytes: float | None = DEFAULT_MEMORY_MB, label: str | None = None) -> None:
    """Watch every later clingo call of this process under these limits."""
    global _limits
    secs = None if seconds is None else min(float(seconds), MAX_SECONDS)
    _limits = Limits(secs, megabytes, label or "the rules")
    if secs is not None or megabytes is not None:
        _start_thread()


def limits() -> Limits:
    return _limits


def resident_bytes() -> int:
    """The process's resident memory now (Linux), else its peak so far."""
    try:
        with open("/proc/self/statm", "rb") as fh:
            return int(fh.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        import resource
        import sys

        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        return peak if sys.platform == "darwin" else peak * 1024


@contextlib.contextmanager
def watch(what: str, *, grace: float = 0.0) -> Iterator[None]:
    """Watch the clingo call inside the block (`what`: "grounding", "solving") under the
    limits; a no-op when none are set. Cheap: the call is only published for the watchdog,
    which looks every `POLL` seconds, so calls shorter than that are hardly ever seen."""
    global _current
    lim = _limits
    if lim.seconds is None and lim.megabytes is None:
        yield
        return
    now = time.monotonic()
    call = _Call(what, now, None if lim.seconds is None else now + lim.seconds + grace,
                 threading.current_thread() is threading.main_thread(), lim)
    _current = call
    try:
        yield
    finally:
        with _lock:
            if _current is call:
                _current = None
            firing = _firing
        if firing:  # the watchdog is saving and ending the process: wait for it
            while True:
                time.sleep(3600)


def _start_thread() -> None:
    global _thread
    with _lock:
        if _thread is None or not _thread.is_alive():
            _thread = threading.Thread(target=_loop, name="aileen-clingo-watchdog", daemon=True)
            _thread.start()


def _drain(sock) -> list[int]:  # noqa: ANN001
    got: list[int] = []
    with contextlib.suppress(OSError, ValueError):
        while True:
            data = sock.recv(64)
            if not data:
                break
            got.extend(data)
    return got


def _loop() -> None:
    """Every POLL seconds (or at once on a signal): is a call running past a limit?"""
    global _firing
    from aileen import lifecycle

    while True:
        sock = lifecycle.wakeup_fd()
        signals: list[int] = []
        if sock is None:
            time.sleep(POLL)
        else:
            try:
                ready, _, _ = select.select([sock], [], [], POLL)
                signals = _drain(sock) if ready else []
            except (OSError, ValueError):  # the socket was closed (uninstall): look again
                time.sleep(POLL)
        call = _current
        if call is None:
            continue  # a signal between calls is Python's to handle
        if call.rss0 is None and call.limits.megabytes is not None:
            call.rss0 = resident_bytes()
        reason = _reason(call, signals)
        if reason is None:
            continue
        with _lock:
            if _current is not call:
                continue
            _firing = True
        _fire(*reason)


# What the limits name when the rules are the shipped ones: a call past a limit is then a
# slow machine or a hard search, and the advice is the limit, not the rules.
SHIPPED = "the shipped rules"


def _advice(label: str, flag: str) -> str:
    if label == SHIPPED:
        return f" (a busy machine is slower); raise {flag}"
    return f" (a rule that never ends on these facts, such as 'n(X+1) :- n(X).'?); fix the rules or raise {flag}"


def _reason(call: _Call, signals: list[int]) -> tuple[str, int] | None:
    from aileen import lifecycle

    lim = call.limits
    stop = [s for s in signals if s in lifecycle.STOP_SIGNALS]
    if stop and call.main:  # the main thread cannot act on it until clingo returns
        return f"stopped by {lifecycle.signal_name(stop[0])} while clingo was {call.what}", lifecycle.exit_status(stop[0])
    if call.deadline is not None and time.monotonic() > call.deadline:
        return f"{lim.label}: {call.what} took longer than {lim.seconds:g} s" + _advice(lim.label, "--rules-timeout"), 2
    if lim.megabytes is not None and call.rss0 is not None:
        grown = (resident_bytes() - call.rss0) / 2**20
        if grown > lim.megabytes:
            return (f"{lim.label}: {call.what} took more than {lim.megabytes:g} MB of memory"
                    + _advice(lim.label, "--rules-memory"), 2)
    return None


def _fire(message: str, status: int) -> None:
    from aileen import lifecycle

    (on_limit or lifecycle.emergency)(message, status)
    os._exit(status)  # pragma: no cover - both of them end the process
