"""A scene's facts, built in one place: each object's percepts (one per channel, in channel
order), then the relation of every ordered pair in every calculus (a major, b minor).

`perceive()` uses it for perception's own ids and the agent for its tracked ids, so the two
can never disagree about what a scene's facts are.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol

from aileen.domain import calculi
from aileen.domain.calculi import Body, Calculus, pair_relations, senses
from aileen.lru import LruMemory
from aileen.terms import Term, fn


class Object(Body, Protocol):
    id: str
    percepts: tuple[str, ...]


def scene_facts(objects: Sequence[Object], calculi: tuple[Calculus, ...] | None = None, *,
                remember: bool = False) -> list[Term]:
    """`isa(o,p)` for each percept of each object, then `r(a,b)` for each relation of each
    ordered pair of distinct objects in each of `calculi` (default: the default senses,
    `aileen.domain.calculi.senses`).

    The facts are a function of what the calculi read of each object (`Body`: its box,
    footprint and level) with its id and percepts. With `remember`, a scene seen again gives
    the facts kept from the first time (`_SCENES`): the agent asks so, as an experiment
    replays each exam scene to it after every lesson (issue 25)."""
    calcs = senses() if calculi is None else calculi
    if not remember:
        return _facts(objects, calcs)
    try:
        key = (tuple((o.id, tuple(o.percepts), tuple(o.box_m), o.footprint, o.level) for o in objects),
               tuple((c.name, c.compute) for c in calcs))
        hash(key)
    except (AttributeError, TypeError):  # an object without the usual fields: no memory
        key = None
    if key is not None:
        known = _SCENES.get(key)
        if known is not None:
            return list(known)
    facts = _facts(objects, calcs)
    if key is not None:
        _SCENES.put(key, tuple(facts))
    return facts


def _facts(objects: Sequence[Object], calcs: tuple[Calculus, ...]) -> list[Term]:
    """The facts, each id made a term once and each pair's arguments once (what `fn` would
    make of them, interned alike: `perceive()` builds a scene's dozens of facts every frame)."""
    ids = [_term(o.id) for o in objects]
    facts: list[Term] = [Term("isa", (i, _term(p))) for o, i in zip(objects, ids) for p in o.percepts]
    for a, ta in zip(objects, ids):
        for b, tb in zip(objects, ids):
            if a is not b:
                args = (ta, tb)
                facts.extend(Term(r, args) for r in pair_relations(a, b, calcs))
    return facts


def _term(x: Term | str) -> Term:
    """A constant as `fn` makes its arguments: a term stays itself, a string becomes one."""
    return x if isinstance(x, Term) else Term(x)


#: How many scenes' facts `scene_facts` keeps (the least recently used go first).
SCENES_KEPT = 2048
_SCENES: LruMemory[tuple[Term, ...]] = LruMemory(SCENES_KEPT)


def static_facts(held: Object, objects: Sequence[Object]) -> list[Term]:
    """Relations of the static calculi (those that depend on the objects alone, such as
    size comparison) between an object out of view (held) and the visible ones: what the
    agent still knows of it from when it last saw it."""
    static = [c for c in calculi.CALCULI if c.static]
    facts: list[Term] = []
    for o in objects:
        for a, b in ((held, o), (o, held)):
            for c in static:
                r = c.compute(a, b)
                if r is not None:
                    facts.append(fn(r, a.id, b.id))
    return facts
