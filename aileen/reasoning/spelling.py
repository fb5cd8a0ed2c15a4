"""Two words one slip apart: the typing slips a trainer makes.

The grammar reads "lef of" as "left of" (`aileen.reasoning.grammar`), and the agent takes a new
word one slip from a known one for a typo rather than a new meaning
(`aileen.agent.lexicon.near_spelling`): both ask the same question, here, below both.
"""

from __future__ import annotations

__all__ = ["one_edit"]


def one_edit(a: str, b: str) -> bool:
    """Are two different words one edit apart: a letter inserted, deleted or replaced, or two
    neighbouring letters swapped (the slips a typing trainer makes)?"""
    if a == b or abs(len(a) - len(b)) > 1:
        return False
    if len(a) != len(b):
        short, long_ = (a, b) if len(a) < len(b) else (b, a)
        i = next((k for k in range(len(short)) if short[k] != long_[k]), len(short))
        return short[i:] == long_[i + 1:]
    diff = [k for k in range(len(a)) if a[k] != b[k]]
    if len(diff) == 1:
        return True
    return len(diff) == 2 and diff[1] == diff[0] + 1 and a[diff[0]] == b[diff[1]] and a[diff[1]] == b[diff[0]]
