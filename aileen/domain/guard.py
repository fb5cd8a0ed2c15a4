"""A user's own function, named when it fails: one line, never a traceback.

Why: a calculus's compute, a relation's accepts or a channel's measure of one's own
(`AILEEN_DOMAIN`) runs deep inside a lesson; an error there showed as a raw traceback or as "a
defect inside aileen", and a user could not tell it was their function. `guarded` wraps such a
function so that its error is a `UserError` naming what it was for and where it is; aileen's
own functions keep their traceback (an error there is a defect).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from aileen.errors import UserError

__all__ = ["Guarded", "failed", "guarded", "named", "two_numbers"]


def named(function: object) -> str:
    """Where a user's function is, for a message: `file:line name` ("./texture.py:12 measure"),
    else its module and name (a function of an installed module, a callable object)."""
    code = getattr(function, "__code__", None)
    name = getattr(function, "__qualname__", None) or type(function).__name__
    if code is not None:
        return f"{code.co_filename}:{code.co_firstlineno} {name}"
    return f"{getattr(function, '__module__', '?')}.{name}"


def failed(what: str, function: object, exc: BaseException) -> UserError:
    """The one line for an error raised inside a user's own function: what it was for, where
    the function is and what went wrong (its first line)."""
    first = (str(exc).strip().splitlines() or [""])[0]
    return UserError(f"{what} {named(function)} failed: {type(exc).__name__}: {first}")


@dataclass(frozen=True)
class Guarded:
    """A user's function, called as itself, whose error is `failed`'s one line (a class, not a
    closure: what holds it may be pickled to a worker as the function is)."""

    what: str  # what it is for: "relation 'level with': its accepts"
    function: Callable[..., Any]
    # What a result must be, where a malformed one would crash later, far from the function
    # (an offset returning None was "cannot unpack" in the trainer): what was expected, or None
    shape: Callable[[Any], str | None] | None = None

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        try:
            result = self.function(*args, **kwargs)
        except UserError:
            raise
        except Exception as exc:  # noqa: BLE001 - the user's own function: named, not a traceback
            raise failed(self.what, self.function, exc) from None
        expected = self.shape(result) if self.shape is not None else None
        if expected is not None:
            said = repr(result)
            said = said if len(said) <= 60 else said[:57] + "..."
            raise UserError(f"{self.what} {named(self.function)} failed: it returned {said}; expected {expected}")
        return result


def two_numbers(result: object) -> str | None:
    """Why `result` is not a pair of finite numbers (an offset `(dx, dy)`), or None when it is."""
    import math
    import numbers

    if (isinstance(result, (tuple, list)) and len(result) == 2
            and all(isinstance(v, numbers.Real) and not isinstance(v, bool) and math.isfinite(v) for v in result)):
        return None
    return "(dx, dy): two finite numbers"


def guarded(what: str, function: Any, shape: Callable[[Any], str | None] | None = None) -> Any:
    """`function` as a `Guarded` when it is a user's own (defined outside the package), its
    result held to `shape` when one is given; aileen's own functions, and what is not a
    function, as they are."""
    if not callable(function) or isinstance(function, Guarded):
        return function
    module = getattr(function, "__module__", None) or ""
    return function if module == "aileen" or module.startswith("aileen.") else Guarded(what, function, shape)
