"""The benchmark scripts' command lines: counts checked, and bad input said on one line.

Why here: a count of 0 (`--repeat 0`, `--trials 0`) timed or simulated nothing, and the scripts
printed inf and nan with exit status 0, or crashed with a traceback deep inside a run. Bad input
reads as the `aileen` command says it (`aileen.cli`): one line on stderr naming what was
expected, exit status 2. argparse's own error prints its usage first; `Parser` leaves it out,
and `at_least` is the one rule for a count, so that every script refuses alike.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable
from typing import NoReturn

__all__ = ["Parser", "at_least", "count"]


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
