"""A scene's facts, built in one place: each object's percepts (one per channel, in channel
order), then the relation of every ordered pair in every calculus (a major, b minor).

`perceive()` uses it for perception's own ids and the agent for its tracked ids, so the two
can never disagree about what a scene's facts are.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol

from aileen.domain.calculi import CALCULI, Body, Calculus, pair_relations
from aileen.terms import Term, fn


class Object(Body, Protocol):
    id: str
    percepts: tuple[str, ...]


def scene_facts(objects: Sequence[Object], calculi: tuple[Calculus, ...] | None = None) -> list[Term]:
    """`isa(o,p)` for each percept of each object, then `r(a,b)` for each relation of each
    ordered pair of distinct objects in each of `calculi` (default: the default senses,
    `aileen.domain.calculi.senses`)."""
    facts: list[Term] = [fn("isa", o.id, p) for o in objects for p in o.percepts]
    for a in objects:
        for b in objects:
            if a is not b:
                facts.extend(fn(r, a.id, b.id) for r in pair_relations(a, b, calculi))
    return facts


def static_facts(held: Object, objects: Sequence[Object]) -> list[Term]:
    """Relations of the static calculi (those that depend on the objects alone, such as
    size comparison) between an object out of view (held) and the visible ones: what the
    agent still knows of it from when it last saw it."""
    static = [c for c in CALCULI if c.static]
    facts: list[Term] = []
    for o in objects:
        for a, b in ((held, o), (o, held)):
            for c in static:
                r = c.compute(a, b)
                if r is not None:
                    facts.append(fn(r, a.id, b.id))
    return facts
