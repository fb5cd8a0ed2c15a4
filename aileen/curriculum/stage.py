"""The table a lesson is laid out on, as the trainer (`trainer.layout`) and its
demonstrations (`demonstration.demonstrate`) share it: `Setup` (a laid-out lesson), `Spot` (a
footprint being planned), the margins kept and the test of a free spot, and what a lesson that
finds no room becomes (`LayoutError`, `Skip`).

It stands below both: the trainer lays a lesson out and checks that its action can be shown,
and a demonstration places objects on that table with the same margins.
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass, field

from aileen.curriculum.lesson import Lesson, Source
from aileen.curriculum.sentences import action_from_content, read_content
from aileen.domain import actions, channels, relations
from aileen.errors import UserError
from aileen.world import catalog
from aileen.world.appearance import Appearance, BodyChannels
from aileen.world.camera import Table
from aileen.world.sim import World

DEFAULT_MARGIN = 0.03  # m of free space between any two footprints in a fresh scene
EDGE_MARGIN = 0.01  # m between a footprint and the table's edge
POSITION_TRIES = 400  # positions tried per object within one layout


@dataclass
class Setup:
    """A laid-out lesson: the world, and which ids the lesson's objects got."""

    world: World
    ids: list[str]  # one per Lesson.objects, in order
    distractor_ids: list[str] = field(default_factory=list)
    seed: int = 0
    attempts: int = 1  # layouts drawn until one passed the after-settling check
    start: dict[str, tuple[float, float]] = field(default_factory=dict)  # where each object stood, laid out
    # What the trainer changed to lay the lesson out (fewer distractors; sizes given that make
    # the sentence false), for the transcript.
    notes: list[str] = field(default_factory=list)

    def describe(self) -> list[str]:
        """One line per object, for transcripts: `obj1  red box   (0.412, 0.530)  [object 1]`
        (its kind: the values of the channels the trainer draws, the shape last; a size other
        than the usual one first: `large red box`, which the teacher would otherwise learn only
        from what the agent sees; so is any declared channel's value other than its default)."""
        role = {obj_id: f"object {i + 1}" for i, obj_id in enumerate(self.ids)}
        role.update({obj_id: "distractor" for obj_id in self.distractor_ids})
        lines = []
        for o in self.world.objects():
            where = "held" if o.held else f"({o.x:.3f}, {o.y:.3f})"
            kind = [o.appearance[c.name] for c in channels.drawn() if c.name != "shape"]
            size = [o.size] if o.size != catalog.DEFAULT_SIZE else []
            # a declared channel's value other than its default, as size ("striped yellow
            # sphere": the table said "yellow sphere" where the agent saw it striped)
            marked = [o.appearance[c.name] for c in channels.CHANNELS if c.default is not None and c.name != "size"
                      and o.appearance.get(c.name, c.default) != c.default]
            name = " ".join([*size, *marked, *reversed(kind), o.shape])
            lines.append(f"{o.id:<6} {name:<16} {where:<16} [{role.get(o.id, '')}]".rstrip())
        return lines


@dataclass(frozen=True)
class Spot(BodyChannels):
    """A footprint being planned: centre, half extent and what stands there."""

    x: float
    y: float
    half: float
    appearance: Appearance  # every channel's value
    shade: int
    on: int | None = None  # index (in the described objects) of the object it rests on


#: How far (m) a hand-given centre may lie inside the edge margin: a rounding error, no more.
EDGE_TOLERANCE = 1e-6


def on_table(x: float, y: float, half: float, table: Table) -> bool:
    """Does a footprint of half extent `half` centred at (x, y) keep `EDGE_MARGIN` from every
    edge? (To a micrometre: 0.05 + 0.01 is 0.060000000000000005 in floating point, and a
    medium object written at 0.06 m keeps its centimetre.)"""
    m = half + EDGE_MARGIN - EDGE_TOLERANCE
    return m <= x <= table.width - m and m <= y <= table.depth - m


def off_table(x: float, y: float, size: str, table: Table) -> str | None:
    """Why a hand-given centre (x, y) is off the table for an object of `size`, or None: the
    trainer's rule (`on_table`), the same for a lesson file's `position` and the console's
    `place ... at X Y` (the console took the world's looser rule and moved the object)."""
    from aileen.world import catalog

    half = 0.5 * catalog.SIZES[size]  # angle 0: boxes stand square to the table
    if on_table(x, y, half, table):
        return None
    return (f"a {size} object needs its centre at least {half + EDGE_MARGIN:.3f} m from the edges of the "
            f"{table.width} x {table.depth} m table")


def free(x: float, y: float, half: float, others: list[Spot], margin: float) -> bool:
    """Does that footprint keep `margin` from every one of `others` (square footprints, so the
    physics has nothing to push)?"""
    for o in others:
        reach = half + o.half
        if max(abs(x - o.x) - reach, abs(y - o.y) - reach) < margin:
            return False
    return True


def scene_lesson(text: str, *, distractors: int = 0, source: Source) -> Lesson:
    """The lesson a console lays a typed scene out as: "red box left of blue cone" (objects in
    the relation), or an action's sentence, "move red box right of blue cone", laid out as the
    action's start (the mover clearly not there yet, as a lesson file's action lesson). A
    description neither reads as is a `UserError` ("move red box", a verb without its
    relation, laid out a lone box). `aileen teach`'s `scene` and the browser console's layout
    both take it from here."""
    info = read_content(text)
    action = action_from_content(text) if info.verb is not None else None
    if info.verb is not None and action is None and not info.unknown and info.phrases:
        example = ("move red box left of blue cone" if actions.verb(info.verb).takes_relation
                   else f"{info.verb} red box")
        raise UserError(f"cannot lay out {text!r} as the start of '{info.verb}': expected e.g. {example!r}")
    if info.unknown or not info.phrases or (info.verb is not None and action is None):
        raise UserError(f"cannot lay out {text!r}{_slip(text, info.unknown)}; expected '<colour> <shape> "
                        "[<relation> <colour> <shape>]' or an action's start, e.g. 'move red box left of blue cone'")
    return Lesson("inform", text, list(info.phrases), relation=None if action else info.relation, action=action,
                  distractors=distractors, source=source)


def _slip(text: str, unknown: list[str]) -> str:
    """" (did you mean 'left of'?)" for a word or phrase of `text` with a word the trainer could
    not read, close to a relation word or a channel's value (a lesson file's relation says so;
    the console's `scene red box lef of blue cone` said only that it cannot lay it out)."""
    said = text.lower().split()
    known = [*relations.words(), *(v for c in channels.CHANNELS for v in c.values)]
    for n in (3, 2, 1):
        for i in range(len(said) - n + 1):
            phrase = " ".join(said[i : i + n])
            if any(w in unknown for w in said[i : i + n]):
                close = difflib.get_close_matches(phrase, known, n=1, cutoff=0.75)
                if close and close[0] != phrase:
                    return f" (did you mean {close[0]!r}?)"
    theirs = [w for w in dict.fromkeys(said) if w in unknown]
    if theirs:
        # a word of the teacher's own: the trainer lays out only what it can read; the person
        # puts the objects down and teaches the word on them
        return (f" (the trainer does not know {theirs[0]!r}: to show a word of your own, put the objects down "
                "yourself where it holds, e.g. 'place red box at 0.3 0.5' in aileen teach, then teach it)")
    return ""


class LayoutError(UserError):
    """The trainer cannot lay this lesson out, or show its action, on the table: it tried
    other positions, sizes the lesson leaves open and fewer distractors. Not a mistake in
    the file, so the run skips the lesson (`reason` says why) and goes on."""

    def __init__(self, reason: str, lesson: Lesson | None = None) -> None:
        self.reason = reason
        located = lesson.source.error(reason) if lesson is not None else UserError(reason)
        super().__init__(located.message, path=located.path, line=located.line)


@dataclass(frozen=True)
class Skip:
    """A lesson `rehearsal.check_curriculum` could not lay out: the run skips it."""

    reason: str
