"""What the agent knows of the table right now: perceived objects, their facts, stable ids.

Perception numbers objects per frame; the `Tracker` gives each detection the id of the
nearest previously seen object with the same percepts, so an object keeps its id while it is
held out of view and after it is placed (traces need that). `State` indexes its facts by
object and by pair once, so the many per-object and per-pair queries of a lesson do not scan
the whole scene each time.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

from aileen.domain.calculi import MOVE_MIN
from aileen.perception.factindex import FactIndex
from aileen.perception.perceiver import Detection
from aileen.terms import Term

Box = tuple[float, float, float, float]


@dataclass(frozen=True)
class Seen:
    """An object as the agent knows it: its own id, percepts and where it was last seen."""

    id: str
    percepts: tuple[str, ...]  # one percept symbol per channel, e.g. ("cv_box", "cv_red", "cv_medium")
    box_m: Box
    box_px: Box
    level: int = 0
    footprint: float = 0.0  # measured side or diameter, metres

    @property
    def centre(self) -> tuple[float, float]:
        x0, y0, x1, y1 = self.box_m
        return (x0 + x1) / 2, (y0 + y1) / 2

    @property
    def extent(self) -> float:
        """The longer side of its box: the room it needs on the table."""
        x0, y0, x1, y1 = self.box_m
        return max(x1 - x0, y1 - y0)


@dataclass
class State:
    """The perceived state: visible objects by agent id, and its facts (percepts, QSRs, held)."""

    objects: dict[str, Seen]
    held: str | None
    facts: list[Term]
    _index: FactIndex | None = field(default=None, init=False, repr=False, compare=False)

    def _facts_index(self) -> FactIndex:
        """The facts by object and pair, built once per state (rebuilt if facts were added)."""
        if self._index is None or self._index.size != len(self.facts):
            self._index = FactIndex(self.facts)
        return self._index

    def percepts(self, obj: str) -> list[Term]:
        return self._facts_index().percepts(obj)

    def relations(self, a: str, b: str) -> list[Term]:
        """QSR facts between a and b, both directions."""
        return self._facts_index().relations(a, b)


class Tracker:
    """Keeps agent ids stable across frames: a detection takes the id of the nearest
    previously seen object with the same percepts (objects do not change colour or shape),
    so an object keeps its id while it is held out of view and after it is placed."""

    def __init__(self) -> None:
        self.known: dict[str, Seen] = {}
        self._next = 1
        self.moved: set[str] = set()  # ids whose centre shifted in the last `assign`

    def reset(self) -> None:
        self.known.clear()
        self._next = 1
        self.moved = set()

    def assign(self, detections: Sequence[Detection], released: str | None = None) -> list[str]:
        """The ids of `detections`. `released`: the object the hand has just put down; if
        no detection takes its id by its percepts, the new detection most like it does (it
        is what appeared where the hand let go: a percept read differently there, say a
        sphere seen once as a cylinder, does not make it another object)."""
        pairs = []
        for i, d in enumerate(detections):
            cx, cy = (d.box_m[0] + d.box_m[2]) / 2, (d.box_m[1] + d.box_m[3]) / 2
            for oid, s in self.known.items():
                if s.percepts == d.percepts:
                    sx, sy = s.centre
                    pairs.append((math.hypot(cx - sx, cy - sy), i, oid))
        pairs.sort()
        ids: list[str | None] = [None] * len(detections)
        used: set[str] = set()
        for _, i, oid in pairs:
            if ids[i] is None and oid not in used:
                ids[i] = oid
                used.add(oid)
        if released is not None and released in self.known and released not in used:
            new = [i for i in range(len(detections)) if ids[i] is None and not any(
                s.percepts == detections[i].percepts for s in self.known.values())]
            if new:
                mine = set(self.known[released].percepts)
                ids[max(new, key=lambda i: (len(mine & set(detections[i].percepts)), -i))] = released
        for i in range(len(detections)):
            if ids[i] is None:
                while f"o{self._next}" in self.known:
                    self._next += 1
                ids[i] = f"o{self._next}"
                self._next += 1
        self.moved = set()
        for i, d in enumerate(detections):
            oid = ids[i]
            assert oid is not None
            before = self.known.get(oid)
            if before is not None:
                cx, cy = (d.box_m[0] + d.box_m[2]) / 2, (d.box_m[1] + d.box_m[3]) / 2
                if math.hypot(cx - before.centre[0], cy - before.centre[1]) > MOVE_MIN:
                    self.moved.add(oid)
            footprint = d.footprint or max(d.box_m[2] - d.box_m[0], d.box_m[3] - d.box_m[1])
            self.known[oid] = Seen(oid, d.percepts, d.box_m, d.box_px, d.level, footprint)
        return ids  # type: ignore[return-value]


def id_order(obj_id: str) -> tuple[int, str]:
    """Sort key for agent ids: o2 before o10."""
    digits = obj_id.lstrip("o")
    return (int(digits), obj_id) if digits.isdigit() else (1 << 30, obj_id)
