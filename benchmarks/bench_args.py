"""The benchmark scripts' command lines: counts checked, and bad input said on one line.

Why here: a count of 0 (`--repeat 0`, `--trials 0`) timed or simulated nothing, and the scripts
printed inf and nan with exit status 0, or crashed with a traceback deep inside a run. Bad input
reads as the `aileen` command says it (`aileen.cli`): one line on stderr naming what was
expected, exit status 2. argparse's own error prints its usage first; `Parser` leaves it out,
and `at_least` is the one rule for a count, so that every script refuses alike.
"""

from __future__ import annotations

import argparse
import os
import time
from collections.abc import Callable
from typing import NoReturn

__all__ = ["Parser", "at_least", "count", "host_line", "reference_work_ms"]


class Parser(argparse.ArgumentParser):
    """argparse's parser whose errors are one line, `PROG: MESSAGE`, with exit status 2."""

    def error(self, message: str) -> NoReturn:
        self.exit(2, f"{self.prog}: {message}\n")


def at_least(least: int) -> Callable[[str], int]:
    """An argparse `type=`: a whole number >= `least` (argparse names the flag in its error)."""

    def whole(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a whole number >= {least}, not {text!r}") from None
        if value < least:
            raise argparse.ArgumentTypeError(f"expected a whole number >= {least}, not {value}")
        return value

    whole.__name__ = f"whole number >= {least}"  # what argparse calls the type, should it ever say
    return whole


# How many times to run, time or draw something: nothing to report below 1.
count = at_least(1)


# A fixed piece of pure-Python work (dict lookups, arithmetic, a call), as the project's own
# time goes: the same work took 2.0x longer on the same 2-core host from one day to the next
# (the code that measured `aileen experiment all` at 56.5 s took 112.4 s there at stop 53), so
# a figure printed without the host's speed beside it cannot be compared with a target.
_STEPS = 1_000_000


def _reference_work() -> int:
    table = {k: k * 7 for k in range(64)}
    total = 0
    for i in range(_STEPS):
        total += table[i & 63] ^ (i >> 3)
    return total


def reference_work_ms(repeat: int = 5) -> float:
    """The median time of the fixed work (`_reference_work`), in ms: the host's speed for
    Python code at this moment (lower is faster)."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        _reference_work()
        times.append((time.perf_counter() - t0) * 1000)
    return sorted(times)[len(times) // 2]


def host_line() -> str:
    """One line saying how fast and how busy this host is now, printed before a benchmark's
    figures: its cores, its load average, and the fixed work's time."""
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    return (f"host: {os.cpu_count()} cores, load average {load:.2f}, reference work "
            f"{reference_work_ms():.0f} ms (a fixed {_STEPS:,} steps of Python; lower is faster)")
