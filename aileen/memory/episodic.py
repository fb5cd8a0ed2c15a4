"""Episodic memory: every perceived state and every action, with time points.

A demonstration (or the agent's own acting) becomes a trace of facts as in the paper's
Table 1: `h(T, Fact)` for what holds at time point T, `after(T1, T0)` for their order and
`isa(t0, start)` for the first one. Traces are cut from a window of episodes and focused on
the objects the sentence is about, since facts about other objects are noise to SME.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from aileen.domain import calculi
from aileen.terms import Term, fn


@dataclass(frozen=True)
class Episode:
    time: int
    facts: tuple[Term, ...]
    action: Term | None = None  # the action that led into this state (None for the first)


def time_point(i: int) -> Term:
    return Term(f"t{i}")


def _about(fact: Term, objects: frozenset[Term]) -> bool:
    """True if every entity argument of the fact is one of `objects`."""
    return all(a in objects for a in fact.args)


class EpisodicMemory:
    def __init__(self) -> None:
        self._episodes: list[Episode] = []

    def record(self, facts: Iterable[Term], action: Term | None = None) -> int:
        """Store a state (and the action that produced it); returns its time index."""
        ep = Episode(len(self._episodes), tuple(facts), action)
        self._episodes.append(ep)
        return ep.time

    def __len__(self) -> int:
        return len(self._episodes)

    def __getitem__(self, i: int) -> Episode:
        return self._episodes[i]

    @property
    def now(self) -> int:
        return len(self._episodes) - 1

    def trace(
        self,
        start: int,
        objects: Sequence[Term],
        *,
        end: int | None = None,
        extra: Iterable[Term] = (),
        movers: Sequence[Term] | None = None,
    ) -> list[Term]:
        """The trace of episodes `start..end` (inclusive; default: the latest), time points
        renumbered t0, t1, ... from `start`, holding only facts whose arguments are all in
        `objects` and that are not percepts (percepts do not change; pass them in `extra`); an
        episode of an action on another object is none of theirs (an object moved out of the
        way mid-action: the projection, made from demonstrations of the action alone, found no
        next state). `movers`: the objects whose actions are the trace's steps (default:
        `objects`): the agent's own acting on the reference of "move the blue cylinder left
        of the red box", the box taken off the cylinder first, is none of the move's steps.
        Nor distance bands (`calculi.FINER`): how far apart the objects stood, band by band,
        is what relation words learn as regions (memory/reach.py); in an action's trace every
        demonstration would end at its own band and no two would share an outcome."""
        end = self.now if end is None else end
        if not 0 <= start <= end <= self.now:
            raise IndexError(f"trace window {start}..{end} outside 0..{self.now}")
        focus = frozenset(objects)
        acting = focus if movers is None else frozenset(movers)
        out: list[Term] = [fn("isa", time_point(0), "start")]
        k = -1
        for i in range(start, end + 1):
            ep = self._episodes[i]
            if k >= 0 and ep.action is not None and ep.action.args and ep.action.args[0] not in acting:
                continue  # done to another object (moved out of the way): no step of theirs
            k += 1
            if k:
                out.append(fn("after", time_point(k), time_point(k - 1)))
            out.extend(fn("h", time_point(k), f) for f in ep.facts
                       if f.name != "isa" and _about(f, focus) and not calculi.is_finer(f.name))
        out.extend(extra)
        return out
