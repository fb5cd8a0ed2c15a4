"""What "it", "that one" and "the other one" refer to: what the last lesson grounded.

Why: a teacher talks about the same things lesson after lesson ("the red box is left of the
blue cone" ... "is it near the cone?"). The agent keeps the objects its last lesson grounded,
in the order the sentence named them, and finds them again on the table now seen by how they
look (the same percepts) and, among lookalikes, by where they were. Each lesson lays its
table anew (a lesson file, the console's `scene`), so object ids do not carry over; the look
does. "it" (and "that one") is the first object the last lesson grounded, "the other one" the
second, or, when it grounded one, the one other object on the table.
"""

from __future__ import annotations

from dataclasses import dataclass

from aileen.agent.state import State, id_order


@dataclass(frozen=True)
class Mention:
    """An object a lesson grounded: how it looked and where it stood."""

    percepts: tuple[str, ...]
    centre: tuple[float, float]


def mentions(state: State, objs: list[str]) -> tuple[Mention, ...]:
    """The objects (agent ids, in the order the sentence named them) as mentions."""
    out: list[Mention] = []
    for o in dict.fromkeys(objs):
        seen = state.objects.get(o)
        if seen is not None:
            out.append(Mention(seen.percepts, seen.centre))
    return tuple(out)


def resolve(anaphor: str, last: tuple[Mention, ...], state: State, taken: set[str] = frozenset()) -> tuple[str | None, str | None]:
    """The object `anaphor` ("it" or "other") refers to on the table now, as (id, None), or
    (None, why not) in the teacher's words. `taken`: objects other references of the same
    sentence already are ("it is left of the other one")."""
    if anaphor == "it":
        found = _find(last[0], state, taken) if last else None
        if found is None:
            # what was talked about is not here: "it", with one object on the table, is that
            # one ("it is a purple cone" over a purple cone alone said it was not here)
            alone = [o for o in state.objects if o not in taken]
            if len(alone) == 1:
                return alone[0], None
        if not last:
            return None, "I do not know what 'it' is: no lesson before this one was about an object"
        return (found, None) if found else (None, "I do not see what 'it' was on this table")
    if not last:
        return None, f"I do not know what '{_said(anaphor)}' is: no lesson before this one was about an object"
    if len(last) >= 2:
        first = _find(last[0], state, set())
        found = _find(last[1], state, taken | ({first} if first else set()))
        return (found, None) if found else (None, "I do not see what 'the other one' was on this table")
    first = _find(last[0], state, set())
    rest = [o for o in sorted(state.objects, key=id_order) if o != first and o not in taken]
    if len(rest) == 1:
        return rest[0], None
    if not rest:
        return None, "I see no other object than the one we talked about"
    return None, f"I cannot tell which is 'the other one': I see {len(rest)} other objects"


def _find(m: Mention, state: State, taken: set[str]) -> str | None:
    """The object that looks like `m`, the nearest to where it stood among lookalikes."""
    same = [o for o, s in state.objects.items() if s.percepts == m.percepts and o not in taken]
    if not same:
        return None
    x, y = m.centre
    return min(same, key=lambda o: ((state.objects[o].centre[0] - x) ** 2 + (state.objects[o].centre[1] - y) ** 2,
                                    id_order(o)))


def _said(anaphor: str) -> str:
    return "it" if anaphor == "it" else "the other one"
