"""Reading JSON that people and other programs wrote: no key twice, no absurd nesting.

`json.loads` keeps the last of two equal keys without a word (one value is lost unseen) and
recurses per level (100,000 levels end in a RecursionError). The readers of memory files and
of the original AILEEN lesson scripts use these checks, so both refuse such input the same way.
"""

from __future__ import annotations

from typing import Any


def no_duplicates(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    """`object_pairs_hook` for `json.loads`: a key given twice is a `ValueError` naming it."""
    out: dict[str, Any] = {}
    for k, v in pairs:
        if k in out:
            raise ValueError(f"duplicate key {k!r}")
        out[k] = v
    return out


def deeper_than(x: Any, limit: int) -> bool:
    """Whether `x` nests lists and objects deeper than `limit` (iterative: safe on any input)."""
    stack = [(x, 1)]
    while stack:
        v, d = stack.pop()
        if isinstance(v, (dict, list)):
            if d > limit:
                return True
            stack.extend((c, d + 1) for c in (v.values() if isinstance(v, dict) else v))
    return False
