"""The table a person edits in the teaching console: objects with explicit positions.

Every object the console puts on the table gets its position written down, so each lesson
can be stated as a lesson file would state it (`objects = [{shape, colour, size, position}]`)
and replayed by `aileen run` on the very same table. Nothing here reads the agent: this is
the trainer's side, which knows shapes and colours because it put them there.

Positions are table metres (see `aileen.world.camera`). A spot is accepted when the object's
footprint stays on the table and clear of every other footprint by `GAP` metres, so the
trainer's own after-settling check (objects must not touch) passes.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, replace

import numpy as np

from aileen.curriculum import trainer
from aileen.curriculum.lesson import Lesson, ObjectSpec, Source
from aileen.curriculum.sentences import parse_object
from aileen.curriculum.stage import scene_lesson
from aileen.domain import channels, relations
from aileen.errors import UserError
from aileen.world import catalog
from aileen.world.appearance import Appearance, BodyChannels
from aileen.world.camera import Table

GAP = 0.01  # m of clearance between footprints for a hand-placed object
TRIES = 400  # random spots tried before saying the table is full
MAX_OBJECTS = 12  # a console table, not a warehouse
# distractors the trainer lays out beside a sentence's objects or a whole table in one call;
# `shuffle` scatters up to MAX_OBJECTS (less the objects kept)
LAID_OUT_DISTRACTORS = 8
UNDO_DEPTH = 50


@dataclass(frozen=True)
class Placed(BodyChannels):
    """One object on the console's table, as the trainer knows it."""

    appearance: Appearance  # every channel's value
    x: float
    y: float
    distractor: bool = False

    @property
    def half(self) -> float:
        return 0.5 * catalog.SIZES[self.size]

    def box_m(self) -> tuple[float, float, float, float]:
        h = self.half
        return self.x - h, self.y - h, self.x + h, self.y + h

    def describe(self) -> str:
        """Its words, a channel at its default left unsaid: "red box", "large red box"."""
        said = {c.name: None for c in channels.CHANNELS if self.appearance.get(c.name) == c.default}
        return ObjectSpec(appearance=self.appearance.replace(**said)).describe()

    def spec(self) -> ObjectSpec:
        return ObjectSpec(appearance=self.appearance, position=(self.x, self.y))


def whole(spec: ObjectSpec, description: str) -> Appearance:
    """What an object described for the console's table looks like: every channel the trainer
    draws (colour and shape) must be said; a channel with a default is as said or its default."""
    drawn = channels.drawn()
    if any(c.name not in spec.appearance for c in drawn):
        names = sorted(c.name for c in drawn)
        said = f"both {names[0]} and {names[1]}" if len(names) == 2 else f"{', '.join(names[:-1])} and {names[-1]}"
        example = ObjectSpec(appearance={c.name: c.values[0] for c in drawn}).describe()
        raise UserError(f"say {said}, e.g. {example!r} (got {description!r})")
    rest = {c.name: c.default for c in channels.CHANNELS if c.default is not None}
    return channels.appearance_of({**rest, **spec.appearance})


class TableEdit:
    """The objects on the table, the edits made to them, and undo."""

    def __init__(self, table: Table, *, seed: int = 0) -> None:
        self.table = table
        self.objects: list[Placed] = []
        self._history: list[list[Placed]] = []
        self._rng = np.random.default_rng(seed)

    # ------------------------------------------------------------------ checks
    def _on_table(self, x: float, y: float, half: float) -> bool:
        m = half + trainer.EDGE_MARGIN
        return m <= x <= self.table.width - m and m <= y <= self.table.depth - m

    def _clear(self, cand: Placed, skip: int | None = None) -> bool:
        return all(relations.gap(cand, o) >= GAP for i, o in enumerate(self.objects) if i != skip)

    def _check_spot(self, cand: Placed, skip: int | None = None) -> None:
        if not (isinstance(cand.x, float) and isinstance(cand.y, float)) or not (
                np.isfinite(cand.x) and np.isfinite(cand.y)):
            raise UserError("a position must be two finite numbers (metres)")
        if not self._on_table(cand.x, cand.y, cand.half):
            raise UserError(f"({cand.x:.3f}, {cand.y:.3f}) is off the table for a {cand.size} object")
        if not self._clear(cand, skip):
            raise UserError(f"({cand.x:.3f}, {cand.y:.3f}) is too close to another object")

    def _index(self, i: int) -> int:
        if not isinstance(i, int) or isinstance(i, bool):  # `true` was "no object True on the table"
            shown = json.dumps(i) if isinstance(i, (bool, int, float, str, type(None))) else type(i).__name__
            raise UserError(f"'index' must be a whole number (an object's index in the scene), got {shown[:40]}")
        if not 0 <= i < len(self.objects):
            raise UserError(f"no object {i!r} on the table (there are {len(self.objects)})")
        return i

    def _push(self) -> None:
        self._history.append(list(self.objects))
        del self._history[:-UNDO_DEPTH]

    def _random_spot(self, looks: Appearance, distractor: bool = False) -> Placed:
        half = 0.5 * catalog.SIZES[looks["size"]]
        lo = half + trainer.EDGE_MARGIN
        for _ in range(TRIES):
            x = float(self._rng.uniform(lo, self.table.width - lo))
            y = float(self._rng.uniform(lo, self.table.depth - lo))
            cand = Placed(looks, x, y, distractor)
            if self._clear(cand):
                return cand
        raise UserError("no free spot left on the table")

    # ------------------------------------------------------------------ edits
    def find(self, description: str) -> int:
        """The index of the one object fitting a description such as 'blue cone'."""
        spec = parse_object(description)
        hits = [i for i, o in enumerate(self.objects) if spec.fits(o.appearance)]
        if len(hits) != 1:
            raise UserError(f"the table needs exactly one {spec.describe()} (it has {len(hits)})")
        return hits[0]

    def add(self, description: str, *, at: tuple[float, float] | None = None, relation: str | None = None,
            of: str | None = None) -> Placed:
        """Put an object described as '[size] colour shape' on the table: at a given spot, in a
        relation to another object ('left of', of='blue cone'), or on a free spot."""
        if len(self.objects) >= MAX_OBJECTS:
            raise UserError(f"the console's table holds at most {MAX_OBJECTS} objects")
        looks = whole(parse_object(description), description)
        size = looks["size"]
        if at is not None:
            cand = Placed(looks, float(at[0]), float(at[1]))
            self._check_spot(cand)
        elif relation is not None:
            if of is None:
                raise UserError(f"'{relation}' needs the object it is relative to, e.g. of = 'blue cone'")
            if relation not in relations.known() and relations.canonical(relation) not in relations.known():
                raise UserError(f"unknown relation {relation!r}; expected one of: {', '.join(relations.known())}")
            ref = self.objects[self.find(of)]
            rel = relations.get(relation)
            if rel.offset is None or rel.stacked:
                raise UserError(f"'{relation}' does not say where to put an object; place it by clicking")
            for _ in range(TRIES):
                dx, dy = relations.sample_offset(rel.name, catalog.SIZES[size], catalog.SIZES[ref.size], self._rng)
                cand = Placed(looks, ref.x + float(dx), ref.y + float(dy))
                if self._on_table(cand.x, cand.y, cand.half) and self._clear(cand) and relations.clearly_holds(
                        relations.canonical(relation), cand, ref):
                    break
            else:
                raise UserError(f"no free spot {relation} the {ref.describe()}")
        else:
            cand = self._random_spot(looks)
        self._push()
        self.objects.append(cand)
        return cand

    def move(self, i: int, at: tuple[float, float]) -> Placed:
        i = self._index(i)
        cand = replace(self.objects[i], x=float(at[0]), y=float(at[1]))
        self._check_spot(cand, skip=i)
        self._push()
        self.objects[i] = cand
        return cand

    def remove(self, i: int) -> Placed:
        i = self._index(i)
        self._push()
        return self.objects.pop(i)

    def clear(self) -> None:
        self._push()
        self.objects = []

    def shuffle_distractors(self, n: int) -> list[Placed]:
        """Take the distractors away and scatter `n` new ones, each of a kind not on the table."""
        if not isinstance(n, int) or isinstance(n, bool) or not 0 <= n <= MAX_OBJECTS:
            raise UserError(f"distractors must be a whole number from 0 to {MAX_OBJECTS}")
        self._push()
        keep = [o for o in self.objects if not o.distractor]
        if len(keep) + n > MAX_OBJECTS:
            self.objects = self._history.pop()
            raise UserError(f"the console's table holds at most {MAX_OBJECTS} objects")
        self.objects = keep
        taken = {channels.kind_of(o.appearance) for o in keep}
        kinds = [k for k in channels.kinds() if k not in taken] or channels.kinds()
        order = self._rng.permutation(len(kinds))
        rest = {c.name: c.default for c in channels.CHANNELS if c.default is not None}
        added = []
        try:
            for d in range(n):
                looks = channels.appearance_of({**rest, **kinds[int(order[d % len(kinds)])]})
                added.append(self._random_spot(looks, distractor=True))
                self.objects.append(added[-1])
        except UserError:
            self.objects = self._history.pop()
            raise
        return added

    def lay_out(self, content: str, *, distractors: int = 0) -> None:
        """A fresh table laid out as a lesson would be ('red box left of blue cone'); the
        trainer's own layout does it, and its positions are written down."""
        self._lay_out(scene_lesson(content, distractors=distractors, source=Source("<console>")))

    def _lay_out(self, lesson: Lesson) -> None:
        try:
            setup = trainer.layout(lesson, seed=int(self._rng.integers(2**31)), table=self.table)
        except UserError as exc:
            raise UserError(f"cannot lay out {lesson.content!r}: {exc.message}") from None
        roles = set(setup.distractor_ids)
        placed = [Placed(o.appearance, float(o.x), float(o.y), o.id in roles)
                  for o in setup.world.objects() if not o.held]
        self._push()
        self.objects = placed

    def set_table(self, items: list[tuple[str, tuple[float, float] | None]], *, relation: str | None = None,
                  distractors: int = 0) -> None:
        """The whole table in one edit (one undo step): objects by description, each at a
        given spot or a free one; or, with `relation`, two objects laid out by the trainer in
        it ('red box', 'left of', 'blue cone'); and `distractors` more of kinds not named.
        On any error the table is left as it was."""
        if not isinstance(distractors, int) or isinstance(distractors, bool) or \
                not 0 <= distractors <= LAID_OUT_DISTRACTORS:
            raise UserError(f"distractors must be a whole number from 0 to {LAID_OUT_DISTRACTORS}")
        if len(items) + distractors > MAX_OBJECTS:
            raise UserError(f"the console's table holds at most {MAX_OBJECTS} objects")
        if relation is not None:
            name = relations.canonical(relation)  # an unknown one is a UserError listing the known
            if len(items) != 2 or any(at is not None for _d, at in items):
                raise UserError("a relation lays out exactly two objects, without positions")
            specs = [self._spec(d) for d, _at in items]
            self._lay_out(Lesson("inform", f"{specs[0].describe()} {relation} {specs[1].describe()}", specs,
                                 relation=name, distractors=distractors, source=Source("<console>")))
            return
        old, depth = list(self.objects), len(self._history)
        try:
            self.objects = []
            for description, at in items:
                self.add(description, at=at)
            if distractors:
                self.shuffle_distractors(distractors)
        except UserError:
            self.objects = old
            del self._history[depth:]
            raise
        del self._history[depth:]
        self._history.append(old)
        del self._history[:-UNDO_DEPTH]

    @staticmethod
    def _spec(description: str) -> ObjectSpec:
        spec = parse_object(description)
        whole(spec, description)
        return spec

    def restore(self, objects: list[Placed]) -> None:
        """The table as it was saved or before an undone lesson (not an edit: no undo step)."""
        self.objects = list(objects)

    def set_all(self, objects: list[Placed]) -> None:
        """The table as the world left it after a lesson (an undoable edit like any other)."""
        self._push()
        self.objects = list(objects)

    def undo(self) -> None:
        if not self._history:
            raise UserError("nothing to undo")
        self.objects = self._history.pop()
