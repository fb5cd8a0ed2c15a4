"""Argument types shared by the subcommands (argparse `type=` callables).

Why here: the same rule (a seed is a whole number >= 0; NumPy's generators reject negative
seeds with a traceback deep inside a run) must read the same in every subcommand, and
argparse turns an `ArgumentTypeError` into its usual one-line error and exit status 2.
"""

from __future__ import annotations

import argparse
import math

__all__ = ["seed", "seconds", "megabytes"]


def seed(text: str) -> int:
    """A seed: a whole number >= 0."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"seed must be a whole number >= 0, not {text!r}") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"seed must be a whole number >= 0, not {value}")
    return value


def _positive(text: str, unit: str, what: str) -> float:
    """A positive, finite number of `unit` (the error names `what` it bounds)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number of {unit}, not {text!r}") from None
    if not math.isfinite(value) or value <= 0:
        raise argparse.ArgumentTypeError(f"{what} must be a positive number of {unit}, not {text!r}")
    return value


def seconds(text: str) -> float:
    """A time limit: a positive, finite number of seconds."""
    return _positive(text, "seconds", "the time limit")


def megabytes(text: str) -> float:
    """A memory bound: a positive, finite number of megabytes."""
    return _positive(text, "megabytes", "the memory bound")
