"""Does the table, once settled, still show what the lesson describes?

The trainer lays a lesson out collision-free and lets physics settle it; objects can then
slide out of the described relation (the paper lost points to this in its spatial results).
`shows` says why a settled table no longer shows the lesson, or None; the trainer then draws
again. Split from the trainer's layout, which asks it after every attempt.
"""

from __future__ import annotations

from aileen.curriculum.lesson import Lesson, goal_relation
from aileen.curriculum.stage import Setup
from aileen.domain import composites, relations
from aileen.domain.table_geometry import extent, gap
from aileen.world.footprints import clearance

__all__ = ["GOAL_AWAY_ANGLE", "goal_false_at_start", "shows"]

# An action lesson starts with the goal clearly false: the moved object lies at least this far
# (degrees) from the goal direction, so the demonstration shows a change the camera can see.
GOAL_AWAY_ANGLE = relations.HOLDS_HALF_ANGLE + 22.5
# ... and for a distance word, the gap (in larger footprints) lies this share outside its
# region: "far from" laid out 3.5 footprints apart against its 3.6 was "so already" to the
# agent and "does NOT hold" to the trainer.
GOAL_AWAY_SHARE = 0.15


def goal_false_at_start(lesson: Lesson, setup: Setup) -> bool:
    """Is the action's goal clearly false on the table (the mover at least `GOAL_AWAY_ANGLE`
    off the goal's direction, and the goal's relation not holding), so that a demonstration
    shows a change the camera can see? True for a lesson without a goal relation."""
    goal = goal_relation(lesson)
    if goal is None or len(setup.ids) < 2:
        return True
    a, b = setup.world.get(setup.ids[0]), setup.world.get(setup.ids[1])
    grel = relations.get(goal)
    if grel.distance is not None:
        r = gap(a, b) / max(extent(a), extent(b), 1e-6)
        if grel.distance.lo * (1 - GOAL_AWAY_SHARE) < r <= grel.distance.hi * (1 + GOAL_AWAY_SHARE):
            return False
    return not (grel.accepts(a, b)
                or (grel.direction is not None and relations.angle_off(goal, a, b) < GOAL_AWAY_ANGLE - 5.0))


def shows(lesson: Lesson, setup: Setup, *, goal: bool = True) -> str | None:
    """After settling: does the scene still show what the lesson describes? None if so.
    `goal`: an action lesson's goal must be clearly false at the start (not for a react on a
    table the teacher set by hand: `trainer._set_for_agent`)."""
    world = setup.world
    if lesson.relation is not None:
        a, b = world.get(setup.ids[0]), world.get(setup.ids[1])
        rel = relations.get(lesson.relation)
        if lesson.near_miss:
            if rel.accepts(a, b):
                return f"after settling, the near miss {a.colour} {a.shape} {lesson.relation} {b.colour} {b.shape} holds"
        elif not rel.clear(a, b):
            return f"after settling, {a.colour} {a.shape} is no longer clearly {lesson.relation} {b.colour} {b.shape}"
    if goal and lesson.relation is None and not goal_false_at_start(lesson, setup):
        return f"after settling, the goal {goal_relation(lesson)} is not clearly false at the start"
    if goal and lesson.relation is not None and goal_relation(lesson) is not None and len(setup.ids) >= 2:
        # a start relation that holds the goal too ("next to" for "move ... near"): the agent
        # learned the verb from a demonstration that showed no change
        a, b = world.get(setup.ids[0]), world.get(setup.ids[1])
        if relations.get(goal_relation(lesson)).accepts(a, b):
            return f"the goal {goal_relation(lesson)} holds at the start ({lesson.relation} lays it out there)"
    if lesson.composite is not None:
        parts = [world.get(i) for i in setup.ids]
        if not composites.get(lesson.composite).accepts(parts):
            return f"after settling, the parts no longer form a {lesson.composite}"
    objs = world.objects()
    for i, o in enumerate(objs):
        for p in objs[i + 1:]:
            if getattr(o, "on", None) == p.id or getattr(p, "on", None) == o.id:
                continue
            # the footprints themselves, as the physics has them: the boxes around two round
            # objects near each other on a diagonal meet while the objects stand apart (boxes
            # apart are footprints apart, so the boxes are asked first)
            if relations.gap(o, p) <= 0.0 and clearance(o.outline(), p.outline()) <= 0.0:
                return f"after settling, {o.id} and {p.id} overlap"
    return None
