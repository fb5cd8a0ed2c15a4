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


def duplicate_key_line(text: str) -> int | None:
    """The line (1-based) of the first key given twice in one object of the JSON `text`, None
    when there is none: `no_duplicates` names the key, this says where (a scan of strings and
    brackets, iterative, so safe on text `json.loads` refused for its depth)."""
    stack: list[set[str] | None] = []  # per open bracket: the object's keys so far (None: a list)
    line, i, n = 1, 0, len(text)
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
        elif c in "{[":
            stack.append(set() if c == "{" else None)
        elif c in "}]":
            if stack:
                stack.pop()
        elif c == '"':
            j, start_line = i + 1, line
            while j < n and text[j] != '"':
                if text[j] == "\\":
                    j += 1
                elif text[j] == "\n":
                    line += 1
                j += 1
            key = text[i + 1:j]
            k = j + 1
            while k < n and text[k] in " \t\r\n":
                k += 1
            if k < n and text[k] == ":" and stack and stack[-1] is not None:
                if key in stack[-1]:
                    return start_line
                stack[-1].add(key)
            i = j
        i += 1
    return None

