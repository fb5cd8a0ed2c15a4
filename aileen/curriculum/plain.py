"""A trainer's error as the person at a console reads it.

Why: the trainer's messages are written for lesson files ("x.toml:3: lesson 1: demonstration
step 2 (place(1) [right of 2]): no free spot right of obj2 on the table"). At a console there
is no file, no lesson number and no step list: the console's own bookkeeping. `aileen teach`
printed them as they were ("<teach>: ... obj2"), where the browser console named the objects;
both now say it one way.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

__all__ = ["already", "plain"]

_ALREADY = "not clearly false at the start"


def plain(message: str, names: Sequence[str]) -> str:
    """`message` without the lesson number and demonstration step, the objects named by
    `names` (the lesson's objects in order: obj1 / objects[1] is names[0]), and a goal that
    already holds said as what to do about it."""
    text = re.sub(r"^lesson \d+: ", "", message)
    text = re.sub(r"^demonstration step \d+ \(.*?\): ", "", text)
    if _ALREADY in text:
        text = already(names)

    def name(m: re.Match) -> str:
        k = int(m.group(1)) - 1
        return f"the {names[k]}" if 0 <= k < len(names) else m.group(0)

    text = re.sub(r"\bobj(\d+)\b", name, text)
    return re.sub(r"\bobjects\[(\d+)\]", name, text)


def already(names: Sequence[str], relation: str | None = None) -> str:
    """An action's goal that holds before it is shown, and what to do about it: the mover
    (`names[0]`) is already there, or already `relation` the reference where it is known."""
    if len(names) < 2:
        return "that is already so on the table: change the table first, so that the demonstration shows the change"
    where = f"{relation.replace('_', ' ')} the {names[1]}" if relation else "there"
    return f"the {names[0]} is already {where}: move it elsewhere first, so that the demonstration shows the change"
