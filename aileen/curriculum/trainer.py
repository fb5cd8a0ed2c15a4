"""The trainer's side: lay out a lesson's scene.

The trainer knows what the agent must learn. It builds the table for a lesson from the
lesson's description (`layout`, on the table `aileen.curriculum.stage` describes); it shows an
action as primitive steps (`aileen.curriculum.demonstration`, asked here whether a drawn table
leaves room to show it) and judges with ground truth (`aileen.curriculum.grading`).
The agent never sees any of it: it only gets camera images and the trainer's sentence.

Where the original lost points to physics (objects placed too close pushed each other out of
the described relation, see the paper's spatial results), this trainer lays scenes out
collision-free with a margin, settles them, checks the described relation still holds
clearly, and otherwise draws again.

Every random choice is drawn from `numpy.random.default_rng(seed)`: same lesson, same seed,
same scene.
"""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Callable

import numpy as np

from aileen.curriculum import demonstration, placeholders, settled, sizing
from aileen.curriculum.lesson import Lesson, ObjectSpec, goal_relation
from aileen.curriculum.sentences import read_content
from aileen.curriculum.stage import (  # noqa: F401  (Skip handed on: the trainer's records)
    DEFAULT_MARGIN,
    EDGE_MARGIN,
    POSITION_TRIES,
    LayoutError,
    Setup,
    Skip,
    Spot,
    free,
    off_table,
    on_table,
)
from aileen.domain import actions, channels, composites, relations
from aileen.errors import UserError
from aileen.world import catalog
from aileen.world.appearance import Appearance
from aileen.world.camera import Table
from aileen.world.sim import World

GOAL_AWAY_ANGLE = settled.GOAL_AWAY_ANGLE
MAX_ATTEMPTS = 60  # whole layouts tried before giving up (or dropping a distractor)
FEWER_ATTEMPTS = 20  # layouts tried with each distractor fewer


def _half(shape: str, size: str) -> float:
    return 0.5 * catalog.SIZES[size]  # angle 0: boxes stand square to the table


def _said(message: str, ids: list[str], lesson: Lesson) -> str:
    """The world's message with its object ids said as the lesson describes the objects
    ("cannot place obj1 on obj2" -> "cannot place the red box on the green sphere")."""
    names = {obj_id: f"the {spec.describe()}" for obj_id, spec in zip(ids, lesson.objects)}
    return re.sub(r"\bobj\d+\b", lambda m: names.get(m.group(0), "a distractor"), message)


def _twins(lesson: Lesson) -> str | None:
    """Why a relation or action lesson's two objects cannot be told apart, or None: both
    described alike, colour and shape given ("red box left of red box" over two red boxes),
    so the sentence cannot say which is which, and no table shows it."""
    if (lesson.relation is None and lesson.action is None) or len(lesson.objects) < 2:
        return None
    a, b = lesson.objects[0], lesson.objects[1]
    if a.shape is None or a.colour is None or a.appearance != b.appearance:
        return None
    return f"objects[1] and objects[2] are both a {a.describe()}: the sentence cannot tell them apart"


def _random_spot(rng: np.random.Generator, half: float, table: Table, others: list[Spot], margin: float,
                 ok: Callable[[float, float], bool] = lambda x, y: True) -> tuple[float, float] | None:
    lo = half + EDGE_MARGIN
    if table.width - lo < lo or table.depth - lo < lo:
        return None
    for _ in range(POSITION_TRIES):
        x = rng.uniform(lo, table.width - lo)
        y = rng.uniform(lo, table.depth - lo)
        if free(x, y, half, others, margin) and ok(x, y):
            return x, y
    return None


class _Point:
    """A centre, a footprint and a size: enough for `relations.holds` while planning."""

    def __init__(self, x: float, y: float, half: float, size: str = catalog.DEFAULT_SIZE) -> None:
        self.x, self.y, self.half, self.size = x, y, half, size

    def box_m(self) -> tuple[float, float, float, float]:
        return self.x - self.half, self.y - self.half, self.x + self.half, self.y + self.half


def distractor_kinds(lesson: Lesson, described: list[Appearance]) -> list[Appearance]:
    """The kinds (shape, colour: `channels.kinds`) a distractor may have in this lesson.

    A distractor differs from every described object in colour or shape (so each described
    object stays unique), and fits none of the object phrases in the trainer's sentence (so a
    distractor never answers the question: a specificity exam stays a specificity exam).
    Where the sentence has a word the trainer cannot read ("kube"), it cannot tell what fits
    that word: a distractor then shares no value (neither colour nor shape) with the objects
    the word is said of, this lesson's own and those earlier lessons of the file said it of
    (`Lesson.unread_said_of`: a "kube" taught on a red box and a blue box keeps every box and
    every red or blue object off a "kube" exam's table).
    """
    read = read_content(lesson.content)
    allowed = [k for k in channels.kinds() if k not in described and not any(p.fits(k) for p in read.phrases)]
    if not read.unknown:
        return allowed
    seen = [*described, *(o.appearance for o in lesson.unread_said_of)]
    return [k for k in allowed if not any(s.get(c) == v for s in seen for c, v in k.items())]


def _appearance(spec: ObjectSpec, kind: Appearance, size: str) -> Appearance:
    """What a planned object looks like: its kind, its size, and every other channel as the
    lesson says or its default."""
    rest = {c.name: spec.appearance.get(c.name, c.default) for c in channels.CHANNELS if c.default is not None}
    return channels.appearance_of({**rest, **kind, "size": size})


def layout(lesson: Lesson, *, seed: int, table: Table = Table(), margin: float = DEFAULT_MARGIN) -> Setup:
    """Build the lesson's table: its objects (ids in `lesson.objects` order) and distractors.

    With `relation`, objects[0] stands clearly in it to objects[1] (well inside the sector,
    1.5-4 object sizes away). For an action lesson without a layout relation, objects[0]
    starts clearly outside the action's goal relation and there is room to reach it. The
    scene is settled and checked again, and an action lesson's demonstration must find its
    spot; a layout that physics spoiled is drawn anew.

    Trying harder before giving up: a comparative gets the sizes the lesson leaves open chosen
    to fit it; a crowded table gets other positions (`MAX_ATTEMPTS` layouts), then fewer
    distractors, one at a time. Sizes given that rule a comparative out are laid out as given
    when the lesson is an exam whose right answer may be a failure (a near miss: the trainer
    grades the sentence against the table). What still cannot be laid out raises
    `LayoutError` with the reason; hand-given positions that are off the table or contradict
    the relation are mistakes in the file (`UserError`).
    """
    rng = np.random.default_rng(seed)
    if margin < 0:
        raise UserError(f"margin must be >= 0 m, got {margin}")
    for spec_i, spec in enumerate(lesson.objects):
        if spec.position is not None:
            x, y = spec.position
            why = off_table(x, y, spec.size or catalog.DEFAULT_SIZE, table)
            if why is not None:
                raise lesson.source.error(line=lesson.source.line_of("objects"),
                                          message=f"objects[{spec_i + 1}] position ({x}, {y}) is off the table: {why}")
    if lesson.relation is not None and len(lesson.objects) < 2:  # "red box left of", typed at a console
        word = relations.get(lesson.relation).word
        raise lesson.source.error(f"'{word}' needs a second object: '<colour> <shape> {word} <colour> <shape>'")
    twins = _twins(lesson)
    if twins is not None:
        raise LayoutError(f"cannot lay out this lesson: {twins}", lesson)
    asked, notes = lesson, []
    ruled_out = sizing.ruled_out(lesson)
    if ruled_out is not None:
        if lesson.signal != "verify" or lesson.expect == "success":
            raise LayoutError(f"cannot lay out this lesson: {ruled_out}", lesson)
        lesson = dataclasses.replace(lesson, near_miss=True)
        notes.append(f"{ruled_out}: laid out as given, so the sentence is false")
    for_agent = _set_for_agent(lesson)  # a react on a table set by hand: tried as it stands
    reason = "no attempt"
    crowded = None  # why the lesson's own number of distractors could not be laid out
    distractors = lesson.distractors
    while distractors >= 0:
        trial = lesson if distractors == lesson.distractors else dataclasses.replace(lesson, distractors=distractors)
        tries = MAX_ATTEMPTS if trial is lesson else FEWER_ATTEMPTS
        fitted: list[int] = []  # how many distractors found room, in the attempts that ran out of it
        for attempt in range(1, tries + 1):
            planned = _plan(trial, rng, table, margin, fitted)
            if isinstance(planned, str):
                reason = planned
                if _fixed(lesson):
                    raise lesson.source.error(f"cannot lay out this lesson: {reason}",
                                              line=lesson.source.line_of("objects"))
                continue
            spots, n_described = planned
            world = World(table, seed=seed)
            ids = [world.put(s.appearance, s.x, s.y, shade=s.shade) for s in spots]
            try:
                for s, obj_id in zip(spots, ids):
                    if s.on is not None:  # stack it: lift it off and put it on top
                        world.pick_up(obj_id)
                        world.place(obj_id, s.x, s.y, onto=ids[s.on])
            except UserError as exc:  # the world refuses the stack (a sphere has no flat top)
                raise LayoutError(f"cannot lay out this lesson: {_said(exc.message, ids, lesson)}", lesson) from None
            world.settle()
            setup = Setup(world, ids[:n_described], ids[n_described:], seed, attempt,
                          {o.id: (o.x, o.y) for o in world.objects()})
            problem = (settled.shows(trial, setup, goal=not for_agent)
                       or (None if for_agent else _demonstrable(trial, setup)))
            if problem is None:
                if distractors < asked.distractors:
                    notes.append(f"laid out with {distractors} of {asked.distractors} distractors: with all, {crowded}")
                setup.notes = notes
                return setup
            reason = _said(problem, ids, lesson)
            if _fixed(lesson) and trial.distractors == 0:
                raise lesson.source.error(f"cannot lay out this lesson: {reason}",
                                          line=lesson.source.line_of("objects"))
        if crowded is None:
            crowded = reason
        # one distractor fewer; or straight down to as many as ever found room
        distractors = min(distractors - 1, max(fitted, default=distractors))
    raise LayoutError(f"cannot lay out this lesson: {reason}", lesson)


def _demonstrable(lesson: Lesson, setup: Setup) -> str | None:
    """Can the trainer show the lesson's action on this table (a free spot for each place)?
    None if so, else why not. Played on a copy: the table stays as laid out."""
    if lesson.action is None and lesson.demonstration is None:
        return None
    try:
        demonstration.demonstrate(lesson, setup, seed=setup.seed)
    except LayoutError as exc:
        return exc.reason
    return None


def _fixed(lesson: Lesson) -> bool:
    """Every position given by hand: drawing again cannot help."""
    return bool(lesson.objects) and all(o.position is not None for o in lesson.objects)


def _set_for_agent(lesson: Lesson) -> bool:
    """A react on a table the teacher set by hand (every position given; the consoles' lessons
    are): the agent tries on it as it stands. The trainer does not ask that it could do it
    itself, that there is room for the goal, or that the goal is false at the start: the
    agent says why it cannot, or that it is so already, and the goal is graded after. (The
    browser console refused "move the blue cone right of the red box" on its own layout, the
    box near the edge: "cannot lay out this lesson", where `aileen teach` let the agent try.)"""
    return lesson.signal == "react" and _fixed(lesson)


def _plan(lesson: Lesson, rng: np.random.Generator, table: Table, margin: float,
          fitted: list[int] | None = None) -> tuple[list[Spot], int] | str:
    """Positions and kinds for one attempt, or the reason it failed (when the distractors ran
    out of room, how many had found it goes on `fitted`)."""
    taken: set[Appearance] = set()
    kinds: list[Appearance] = []
    for i in range(len(lesson.objects)):
        kind = placeholders.draw_kind(lesson, i, rng, taken)
        kinds.append(kind)
        taken.add(kind)
    sizes = sizing.sizes(lesson, rng)
    halves = [_half(k["shape"], size) for k, size in zip(kinds, sizes)]
    spots: list[Spot | None] = [None] * len(lesson.objects)

    def spot(i: int, x: float, y: float) -> Spot:
        shade = int(rng.integers(len(catalog.SHADES[kinds[i]["colour"]])))
        return Spot(x, y, halves[i], _appearance(lesson.objects[i], kinds[i], sizes[i]), shade)

    placed: list[Spot] = []
    for i, spec in enumerate(lesson.objects):  # hand-given positions first
        if spec.position is not None:
            spots[i] = spot(i, *spec.position)
            placed.append(spots[i])

    relation = lesson.relation
    goal = goal_relation(lesson)
    rel = relations.get(relation) if relation else None
    if rel is not None and rel.offset is None:
        rel = None  # no layout of its own: anywhere
    goal_rel = relations.get(goal) if goal else None
    want = rel or goal_rel
    if len(lesson.objects) >= 2 and want is not None and want.offset is not None:
        f0, f1 = 2 * halves[0], 2 * halves[1]
        offset = want.near_miss if (want is rel and lesson.near_miss and want.near_miss) else want.offset
        assert offset is not None
        if spots[1] is None:
            def room(x: float, y: float) -> bool:
                # the reference needs space on the relevant side for objects[0]
                for _ in range(8):
                    dx, dy = offset(rng, f0, f1)
                    if on_table(x + dx, y + dy, halves[0], table):
                        return True
                return False
            xy = _random_spot(rng, halves[1], table, placed, margin, room)
            if xy is None:
                return f"no room for {lesson.objects[1].describe()}"
            spots[1] = spot(1, *xy)
            placed.append(spots[1])
        ref = spots[1]
        refp = _Point(ref.x, ref.y, ref.half, ref.size)
        if spots[0] is not None and rel is not None and not lesson.near_miss:
            a = _Point(spots[0].x, spots[0].y, spots[0].half, spots[0].size)
            if not rel.clear(a, refp):
                return (f"the given positions do not put {lesson.objects[0].describe()} clearly {relation} "
                        f"{lesson.objects[1].describe()}")
        if spots[0] is None:
            found = None
            others = [p for p in placed if p is not ref]
            for _ in range(POSITION_TRIES):
                if rel is not None:
                    dx, dy = offset(rng, f0, f1)
                    x, y = ref.x + dx, ref.y + dy
                    if want.stacked and not lesson.near_miss:
                        if on_table(x, y, halves[0], table):  # it is set down there, then stacked
                            found = (x, y)
                            break
                        continue
                else:
                    assert goal_rel is not None
                    x = rng.uniform(halves[0] + EDGE_MARGIN, table.width - halves[0] - EDGE_MARGIN)
                    y = rng.uniform(halves[0] + EDGE_MARGIN, table.depth - halves[0] - EDGE_MARGIN)
                    if not _clearly_false(goal_rel, _Point(x, y, halves[0], sizes[0]), refp, max(f0, f1)):
                        continue
                if (on_table(x, y, halves[0], table) and free(x, y, halves[0], others, margin)
                        and free(x, y, halves[0], [ref], 0.0)):
                    found = (x, y)
                    break
            if found is None:
                return f"no room for {lesson.objects[0].describe()} {relation or 'near'} {lesson.objects[1].describe()}"
            spots[0] = spot(0, *found)
            if want.stacked and rel is not None and not lesson.near_miss:
                spots[0] = dataclasses.replace(spots[0], on=1)
            placed.append(spots[0])

    if lesson.composite is not None and not _arrange(lesson, spots, spot, placed, halves, rng, table, margin):
        return f"no room for a {lesson.composite}"

    for i in range(len(lesson.objects)):
        if spots[i] is None:
            ok = _room_to_show(lesson, i, halves[i], table)
            xy = _random_spot(rng, halves[i], table, placed, margin, ok)
            if xy is None:
                return f"no room for {lesson.objects[i].describe()} with margin {margin} m"
            spots[i] = spot(i, *xy)
            placed.append(spots[i])

    allowed = distractor_kinds(lesson, kinds)
    if lesson.distractors and not allowed:
        return "no kind of distractor differs from the described objects and the sentence"
    order = rng.permutation(len(allowed)) if allowed else np.array([], dtype=int)
    for d in range(lesson.distractors):
        kind = allowed[int(order[d % len(allowed)])]
        size = catalog.DEFAULT_SIZE
        half = _half(kind["shape"], size)
        xy = _random_spot(rng, half, table, placed, margin)
        if xy is None:
            if fitted is not None:
                fitted.append(d)
            # random spots drawn for each object in turn found none: a search's outcome, not
            # a proof that the objects cannot fit
            return (f"found no room for {len(lesson.objects) + lesson.distractors} objects ({lesson.distractors} "
                    f"distractors of {2 * half:.2f} m) on a {table.width} x {table.depth} m table with margin {margin} m")
        shade = int(rng.integers(len(catalog.SHADES[kind["colour"]])))
        placed.append(Spot(xy[0], xy[1], half, _appearance(ObjectSpec(), kind, size), shade))
    described = [s for s in spots if s is not None]
    if goal_rel is not None and goal_rel.offset is not None and len(described) >= 2 and not _set_for_agent(lesson):
        if not _goal_reachable(goal, described[1], described[0], placed, table, margin, rng):
            return f"no free room {goal} {lesson.objects[1].describe()} for the action"
    return described + [s for s in placed if s not in described], len(described)


def _arrange(lesson: Lesson, spots: list, spot, placed: list, halves: list[float], rng: np.random.Generator,
             table: Table, margin: float) -> bool:
    """Lay a composite's parts out: the first anywhere, each next one in its relation to the
    part the arrangement names (the trainer's meaning of the composite word)."""
    comp = composites.get(lesson.composite or "")
    for i in range(len(lesson.objects)):
        if spots[i] is not None:
            continue
        rule = next(((r, j) for k, r, j in comp.arrangement if k == i and spots[j] is not None), None)
        if rule is None:
            xy = _random_spot(rng, halves[i], table, placed, margin + 0.25 * (i == 0))
            if xy is None:
                return False
            spots[i] = spot(i, *xy)
        else:
            rel, j = relations.get(rule[0]), rule[1]
            ref = spots[j]
            found = None
            for _ in range(POSITION_TRIES):
                assert rel.offset is not None
                dx, dy = rel.offset(rng, 2 * halves[i], 2 * ref.half)
                x, y = ref.x + dx, ref.y + dy
                if rel.stacked:
                    if on_table(x, y, halves[i], table):  # it is set down there, then stacked
                        found = (x, y)
                        break
                    continue
                others = [p for p in placed if p is not ref]
                if on_table(x, y, halves[i], table) and free(x, y, halves[i], others, margin) \
                        and free(x, y, halves[i], [ref], 0.0):
                    found = (x, y)
                    break
            if found is None:
                return False
            spots[i] = spot(i, *found)
            if rel.stacked:
                spots[i] = dataclasses.replace(spots[i], on=j)
        placed.append(spots[i])
    return True


def _clearly_false(rel: relations.TrainerRelation, a: _Point, b: _Point, size: float) -> bool:
    """An action's start: the goal relation clearly does not hold, and the object is far
    enough from where it must go that the demonstration shows a change the camera sees."""
    if rel.accepts(a, b) or rel.clear(a, b):
        return False
    far = math.hypot(a.x - b.x, a.y - b.y)
    if far < size * relations.PLACE_DISTANCE[0] or far > size * 5:
        return False
    if rel.direction is not None:
        return relations.angle_off(rel.name, a, b) >= GOAL_AWAY_ANGLE
    return True


def _goal_reachable(goal: str, ref: Spot, moved: Spot, placed: list[Spot], table: Table,
                    margin: float, rng: np.random.Generator) -> bool:
    """Is there a clear, free spot in the goal relation to the reference (ignoring the moved object)?"""
    others = [s for s in placed if s is not moved and s is not ref]
    probe = np.random.default_rng(int(rng.integers(2**31)))
    hits = 0
    for _ in range(100):
        dx, dy = relations.sample_offset(goal, 2 * moved.half, 2 * ref.half, probe)
        x, y = ref.x + dx, ref.y + dy
        if relations.get(goal).stacked:
            hits += 1
            continue
        if (on_table(x, y, moved.half, table) and free(x, y, moved.half, others, margin)
                and free(x, y, moved.half, [ref], 0.0)):
            hits += 1
    return hits >= 5  # not a sliver: the demonstration (and the agent) must find it


def _room_to_show(lesson: Lesson, i: int, half: float, table: Table) -> Callable[[float, float], bool]:
    """Where an object an action lesson's verb is done to must stand for the verb to be shown:
    its declared `room` (push: room ahead of it, north, away from the trainer). That is the
    object the sentence names (object 1), and, where the lesson spells its demonstration out,
    every object a step of the verb's own actions is done to (a specificity lesson pushes the
    other object: "push 2"); anything else may go anywhere."""
    room = actions.verb(lesson.action.verb).room if lesson.action is not None else None
    if room is None or not (i == 0 or i in _shown_with_verb(lesson)):
        return lambda x, y: True
    return lambda x, y: room(x, y, half, table, EDGE_MARGIN)


def _shown_with_verb(lesson: Lesson) -> set[int]:
    """The objects (indices) that the steps of a spelled-out demonstration do the lesson's
    verb's own primitive actions to."""
    if lesson.action is None or lesson.demonstration is None:
        return set()
    steps = actions.verb(lesson.action.verb).steps
    return {s.obj for s in lesson.demonstration if s.action in steps and isinstance(s.obj, int)}
