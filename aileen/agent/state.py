"""What the agent knows of the table right now: perceived objects, their facts, stable ids.

Perception numbers objects per frame; the `Tracker` gives each detection the id of the
nearest previously seen object with the same percepts, so an object keeps its id while it is
held out of view and after it is placed (traces need that). `State` indexes its facts by
object and by pair once, so the many per-object and per-pair queries of a lesson do not scan
the whole scene each time.

Object permanence (`Tracker(permanence=True)`, `--without object-permanence` switches it off):
a top-down camera does not see an object that another one put on it covers (under about 10 %
visible, the detector misses it), and then perception reads the upper object as on the table
and the lower one as gone. The tracker keeps such an object as `Seen.under` the upper one (see
`Hidden`) while nothing says it went: the agent watched the upper one put down over it, or saw
the upper one resting on it, and the upper one stays in view where it was. It ends when the
upper one is lifted or moves, or the lower one is seen again. Where every object stays in
view, nothing changes.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace

from aileen.domain.calculi import MOVE_MIN
from aileen.perception.factindex import FactIndex
from aileen.perception.perceiver import Detection
from aileen.terms import Term
from aileen.world.catalog import percept
from aileen.world.stacks import FLAT_TOPS

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
    # Not in view now: remembered lying under this object (object permanence, `Hidden`); None
    # for an object seen in this frame.
    under: str | None = None

    @property
    def hidden(self) -> bool:
        """Is it out of sight, only known to lie under another object?"""
        return self.under is not None

    @property
    def note(self) -> str:
        """What a line about it adds to its percepts: ` (on top)`, ` (hidden under o2)`."""
        if self.under is not None:
            return f" (hidden under {self.under})"
        return " (on top)" if self.level else ""

    def over(self, x: float, y: float) -> bool:
        """Does the point (x, y) lie over its box? (An object whose centre is there rests on
        it: perception's rule, `aileen.perception.stacking`.)"""
        x0, y0, x1, y1 = self.box_m
        return x0 <= x <= x1 and y0 <= y <= y1

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

    def named(self) -> list[str]:
        """The objects a sentence may name, in id order: those in view and the one in the
        hand, out of view but not gone (its look is remembered: `Agent.perceive`). "lift the
        red box", demonstrated, ends with the box held: the blue cone in view was taken for it
        and taught as a red box."""
        held = [self.held] if self.held is not None and self.held not in self.objects and self.percepts(self.held) else []
        return sorted([*self.objects, *held], key=id_order)

    def relations(self, a: str, b: str) -> list[Term]:
        """QSR facts between a and b, both directions."""
        return self._facts_index().relations(a, b)


@dataclass(frozen=True)
class Hidden:
    """An object out of sight that the agent keeps in mind under another (object permanence):
    `seen` as it was last seen, `upper` the object over it, `upper_centre` where that one was
    when the memory began (it ends when the upper one moves from there by over MOVE_MIN)."""

    seen: Seen
    upper: str
    upper_centre: tuple[float, float]


class Tracker:
    """Keeps agent ids stable across frames: a detection takes the id of the nearest
    previously seen object with the same percepts (objects do not change colour or shape),
    so an object keeps its id while it is held out of view and after it is placed.

    With `permanence`, it also keeps an object hidden under another in mind (`Hidden`, see
    the module doc): `assign` then returns its id after the detections' ids."""

    def __init__(self, permanence: bool = True) -> None:
        self.known: dict[str, Seen] = {}
        self._next = 1
        self.moved: set[str] = set()  # ids whose centre shifted in the last `assign`
        self.permanence = permanence
        self.hidden: dict[str, Hidden] = {}  # lower object's id -> what keeps it in mind
        self._last: dict[str, Seen] = {}  # the objects of the last `assign`, seen or hidden

    def reset(self) -> None:
        self.known.clear()
        self._next = 1
        self.moved = set()
        self.hidden.clear()
        self._last = {}

    def assign(self, detections: Sequence[Detection], released: str | None = None,
               held: str | None = None) -> list[str]:
        """The ids of `detections`, then (with `permanence`) those of the objects kept in mind
        under another (`Seen.under`). `released`: the object the hand has just put down; if
        no detection takes its id by its percepts, the new detection most like it does (it
        is what appeared where the hand let go: a percept read differently there, say a
        sphere seen once as a cylinder, does not make it another object). `held`: the object
        the hand holds (out of view for that reason, never hidden under another)."""
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
        # a percept read differently where an object stands (the lower box of a stack seen
        # large, then medium once the upper one is lifted off) does not make it another
        # object: an unmatched detection takes the id of an unmatched object seen last frame
        # at its place that differs from it in one percept at most (a plan's next step named
        # the old id, and the agent lost the object mid-action)
        for i, d in enumerate(detections):
            if ids[i] is not None:
                continue
            cx, cy = (d.box_m[0] + d.box_m[2]) / 2, (d.box_m[1] + d.box_m[3]) / 2
            near = [(math.hypot(cx - s.centre[0], cy - s.centre[1]), oid) for oid, s in self._last.items()
                    if oid not in used and oid != released and oid in self.known
                    and len(set(s.percepts) ^ set(d.percepts)) <= 2
                    and math.hypot(cx - s.centre[0], cy - s.centre[1]) <= s.footprint / 2]
            if near:
                ids[i] = min(near)[1]
                used.add(ids[i])
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
                centre = (d.box_m[0] + d.box_m[2]) / 2, (d.box_m[1] + d.box_m[3]) / 2
                if _shift(centre, before.centre) > MOVE_MIN:
                    self.moved.add(oid)
            footprint = d.footprint or max(d.box_m[2] - d.box_m[0], d.box_m[3] - d.box_m[1])
            self.known[oid] = Seen(oid, d.percepts, d.box_m, d.box_px, d.level, footprint)
        seen: list[str] = ids  # type: ignore[assignment]
        if not self.permanence:
            return seen
        kept = self._keep_hidden(seen, released, held)
        self._last = {i: self.known[i] for i in seen + kept}
        return seen + kept

    def _keep_hidden(self, seen: list[str], released: str | None, held: str | None) -> list[str]:
        """Object permanence: end the memories nothing supports any more, begin those this
        frame calls for, and put each remembered object (and its upper one's level) in
        `known`; returns the remembered objects' ids."""
        now = {i: self.known[i] for i in seen}
        for low, h in list(self.hidden.items()):
            up = now.get(h.upper)
            if low in now or up is None or _shift(up.centre, h.upper_centre) > MOVE_MIN:
                del self.hidden[low]  # seen again, the upper one lifted, or moved
                if low not in now:
                    self.known[low] = h.seen  # known as last seen, as any object out of view
        for low, before in self._last.items():  # only what was seen last frame goes out of sight
            if low in now or low in self.hidden or low == held or before.hidden or before.level != 0:
                continue
            upper = self._upper_over(low, before, now, released)
            if upper is not None:
                self.hidden[low] = Hidden(replace(before, under=None), upper, now[upper].centre)
        for low in sorted(self.hidden, key=id_order):
            h = self.hidden[low]
            self.known[low] = replace(h.seen, under=h.upper)
            up = self.known[h.upper]
            if up.level <= h.seen.level:
                self.known[h.upper] = replace(up, level=h.seen.level + 1)
        return sorted(self.hidden, key=id_order)

    def _upper_over(self, low: str, before: Seen, now: dict[str, Seen], released: str | None) -> str | None:
        """The object in view now that hides `low` (in view last frame, not now), if one does:
        it rests over where `low` was (its centre over `low`'s box, and `low` has a flat top),
        and either the hand has just put it down there, or it was seen resting on `low` last
        frame and has not moved since."""
        if not any(p in _FLAT_TOPS for p in before.percepts):
            return None
        for oid in sorted(now, key=id_order):
            up = now[oid]
            if oid == low or not before.over(*up.centre):
                continue
            if oid == released:
                return oid
            last = self._last.get(oid)
            if (last is not None and not last.hidden and last.level > before.level and before.over(*last.centre)
                    and _shift(up.centre, last.centre) <= MOVE_MIN):
                return oid
        return None


#: The percepts of the shapes whose flat top can carry an object (`world.stacks.FLAT_TOPS`).
_FLAT_TOPS: frozenset[str] = frozenset(percept(s) for s in FLAT_TOPS)


def _shift(a: tuple[float, float], b: tuple[float, float]) -> float:
    return math.hypot(a[0] - b[0], a[1] - b[1])


def id_order(obj_id: str) -> tuple[int, str]:
    """Sort key for agent ids: o2 before o10."""
    digits = obj_id.lstrip("o")
    return (int(digits), obj_id) if digits.isdigit() else (1 << 30, obj_id)
