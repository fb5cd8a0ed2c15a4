"""The trainer shows an action: a lesson's demonstration as concrete primitive steps.

`demonstrate` turns the lesson's demonstration (or, for an action lesson without one, the
trainer's own demonstration of its verb) into steps with objects and positions, checked on a
copy of the table; `execute` carries one out in the world through the action's declaration
(`aileen.domain.actions`), and `pointing` says where the trainer's hand goes for it, as the
agent sees it (lessons and recorded exams alike). The layouts are `trainer`'s, which asks this module whether a
lesson's action can be shown on a table it drew; the table they share is `stage`'s.
"""

from __future__ import annotations

import numpy as np

from aileen.curriculum.lesson import Lesson, Step, auto_demonstration
from aileen.curriculum.stage import DEFAULT_MARGIN, POSITION_TRIES, LayoutError, Setup, Spot, free, on_table
from aileen.domain import actions, relations
from aileen.errors import NoRoom, UserError
from aileen.world.camera import Camera, Table
from aileen.world.sim import SettleReport, World

__all__ = ["execute", "demonstrate", "pointing"]

MOVED_TOLERANCE = 1e-3  # m: a demonstration's place may not push anything further than this


def pointing(world: World, step: Step, camera: Camera) -> tuple[float, float] | None:
    """Where the agent sees the trainer's hand go for a concrete step, before it is carried
    out: the pixel of the object a `touch` action is done to; None for a step into a region
    (the hand puts down what it holds)."""
    if not actions.action(step.action).touches:
        return None
    obj = world.get(str(step.obj))
    return camera.to_pixels(obj.x, obj.y)


def execute(world: World, step: Step) -> SettleReport | None:
    """Carry out one concrete step in the world (`place` and `push` settle and return their
    report)."""
    if not isinstance(step.obj, str):
        raise UserError(f"step {step} is not concrete: demonstrate() the lesson first")
    act = actions.action(step.action)
    if not act.touches and step.position is None:
        raise UserError(f"step {step} has no position: demonstrate() the lesson first")
    onto = str(step.ref) if (step.relation and relations.get(step.relation).stacked and step.ref is not None) else None
    return act.world(world, step.obj, step.position, onto)


def demonstrate(lesson: Lesson, setup: Setup, *, seed: int, margin: float = DEFAULT_MARGIN) -> list[Step]:
    """The lesson's demonstration as concrete primitive steps, for the interpreter to execute.

    Steps come from `lesson.demonstration`, or for an action lesson without one from the
    trainer's own demonstration of its verb (`move X <rel> Y`: pick X up, place it <rel> Y). A
    step into a region relative to another object gets a position clearly in the relation, collision-free (nothing is pushed), checked by playing
    the steps on a copy of the world: `setup.world` itself is not changed. Executing the
    returned steps with `execute` on `setup.world` reproduces the checked outcome (the world
    is deterministic).
    """
    if lesson.demonstration is not None:
        plan = lesson.demonstration
    elif lesson.action is not None:
        plan = auto_demonstration(lesson.action)
    else:
        raise lesson.source.error("nothing to demonstrate: the lesson has no demonstration and no action")
    rng = np.random.default_rng(seed)
    sim = setup.world.copy()
    table = sim.table
    out: list[Step] = []
    for n, step in enumerate(plan, 1):
        if not isinstance(step.obj, int) or not 0 <= step.obj < len(setup.ids):
            raise lesson.source.error(line=lesson.source.line_of("demonstration"), message=f"demonstration step {n} ({step}): no object {step.obj!r} in this lesson")
        obj_id = setup.ids[step.obj]
        ref_id = setup.ids[step.ref] if isinstance(step.ref, int) else None
        # a react shows nothing: the trainer tries the action itself, to know it can be done
        what = f"the trainer cannot do this itself (step {n}, {step})" if lesson.signal == "react" \
            else f"demonstration step {n} ({step})"
        try:
            if actions.action(step.action).touches:
                concrete = Step(step.action, obj_id)
                execute(sim, concrete)
            elif step.position is not None:
                concrete = Step(step.action, obj_id, position=step.position)
                execute(sim, concrete)
            else:
                assert step.relation is not None and ref_id is not None
                concrete, sim = _place_in_relation(sim, step.action, obj_id, step.relation, ref_id, rng, table,
                                                   margin)
        except LayoutError as exc:  # no spot on this table: another layout may have one
            raise LayoutError(f"{what}: {exc.reason}", lesson) from None
        except NoRoom as exc:  # no room for the move where the trainer put the objects
            raise LayoutError(f"{what}: {exc.message}", lesson) from None
        except UserError as exc:
            raise lesson.source.error(f"{what}: {exc.message}", line=lesson.source.line_of("demonstration")) from None
        out.append(concrete)
    return out


def _place_in_relation(sim: World, action: str, obj_id: str, relation: str, ref_id: str, rng: np.random.Generator,
                       table: Table, margin: float) -> tuple[Step, World]:
    """A step of `action` (one into a region) that puts the object clearly in the relation to
    the reference without pushing anything, and the world after it."""
    act = actions.action(action)
    if act.hand == actions.RELEASE and sim.held != obj_id:
        raise UserError(f"{obj_id} must be picked up before it is placed")
    obj, ref = sim.get(obj_id), sim.get(ref_id)
    if ref.held:
        raise UserError(f"cannot place next to {ref_id}: it is held")
    if relations.get(relation).stacked:
        dx, dy = relations.sample_offset(relation, obj.footprint, ref.footprint, rng)
        trial = sim.copy()
        try:
            act.world(trial, obj_id, (ref.x + dx, ref.y + dy), ref_id)
        except UserError as exc:  # refusals (a cone, a full stack) say why
            raise LayoutError(exc.message) from None
        return Step(act.name, obj_id, relation=relation, ref=ref_id, position=(ref.x + dx, ref.y + dy)), trial
    half = obj.footprint / 2
    others = [
        Spot(o.x, o.y, (o.box_m()[2] - o.box_m()[0]) / 2, o.appearance, o.shade)
        for o in sim.objects() if not o.held and o.id != ref_id and o.id != obj_id
    ]
    ref_spot = Spot(ref.x, ref.y, (ref.box_m()[2] - ref.box_m()[0]) / 2, ref.appearance, ref.shade)
    for _ in range(POSITION_TRIES):
        dx, dy = relations.sample_offset(relation, obj.footprint, ref.footprint, rng)
        x, y = ref.x + dx, ref.y + dy
        if not (on_table(x, y, half, table) and free(x, y, half, others, margin)
                and free(x, y, half, [ref_spot], 0.0)):
            continue
        trial = sim.copy()
        report = act.world(trial, obj_id, (x, y), None)
        if report is not None and any(d > MOVED_TOLERANCE for d in report.moved.values()):
            continue
        if relations.clearly_holds(relation, trial.get(obj_id), trial.get(ref_id)):
            return Step(act.name, obj_id, relation=relation, ref=ref_id, position=(x, y)), trial
    raise LayoutError(f"no free spot {relation} {ref_id} on the table")
