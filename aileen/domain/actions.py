"""The body's primitive actions and the verbs the trainer teaches with them, declared once.

A `PrimitiveAction` says everything the rest of aileen needs about one thing the hand can do:

* `name`: its symbol in plans, traces and transcripts (`pick_up(o1)`), and the name of its
  action model in `asp/actions.lp` (a test holds the two together);
* `spellings`: how lesson files may write it in demonstration steps (`pick-up`, `pickup`);
* `touches`: the hand goes to an object, addressed by where it is seen in the image (the
  trainer's pointing during a demonstration, the agent's own body when it acts);
* `hand`: what it does to what the agent holds (`grasp`, `release`, or nothing);
* `world`: the call that carries it out in the simulator (the trainer's demonstrations and the
  agent's body both end here).

A `Verb` is a word the trainer teaches with a demonstration: `move` (with a relation: "move X
left of Y", pick X up and place it so) or `push` (one object: "push X"). What the verb means is
learned from the demonstration; the declaration only tells the trainer how to demonstrate it.

To add an action: declare it below with its world call, and write its model (preconditions and
effects) in `asp/actions.lp` under the same name.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from aileen.errors import UserError
from aileen.world.sim import SettleReport, World

WorldCall = Callable[[World, str, "tuple[float, float] | None", "str | None"], "SettleReport | None"]


@dataclass(frozen=True)
class PrimitiveAction:
    name: str
    spellings: tuple[str, ...]
    touches: bool  # addressed at an object's pixel
    hand: str | None  # "grasp" | "release" | None
    world: WorldCall  # (world, object id, position or None, object to rest on or None)
    syntax: str  # how a demonstration step writes it (docs and error messages)


def _point(world: World, obj: str, position: tuple[float, float] | None, onto: str | None) -> None:
    world.point(obj)


def _pick_up(world: World, obj: str, position: tuple[float, float] | None, onto: str | None) -> None:
    world.pick_up(obj)


def _place(world: World, obj: str, position: tuple[float, float] | None, onto: str | None) -> SettleReport:
    if position is None:
        raise UserError(f"place({obj}) has no position")
    if onto is None:
        return world.place(obj, position[0], position[1])
    return world.place(obj, position[0], position[1], onto=onto)


def _push(world: World, obj: str, position: tuple[float, float] | None, onto: str | None) -> SettleReport:
    return world.push_away(obj)


ACTIONS: dict[str, PrimitiveAction] = {
    a.name: a
    for a in (
        PrimitiveAction("point", ("point",), True, None, _point, "point N"),
        PrimitiveAction("pick_up", ("pick_up", "pickup", "pick-up", "pick up"), True, "grasp", _pick_up, "pick_up N"),
        PrimitiveAction("place", ("place", "put"), False, "release", _place,
                        "place N <relation> M | place N at X Y | place N on M"),
        PrimitiveAction("push", ("push",), True, None, _push, "push N"),
    )
}


@dataclass(frozen=True)
class Verb:
    """A verb the trainer demonstrates: with a relation (`move X <r> Y`) or on one object."""

    name: str
    takes_relation: bool
    steps: tuple[str, ...]  # the primitive actions of its demonstration, on object 1 (place: <r> object 2)


VERBS: dict[str, Verb] = {
    v.name: v
    for v in (
        Verb("move", True, ("pick_up", "place")),
        Verb("push", False, ("push",)),
    )
}


def action(name: str) -> PrimitiveAction:
    """The action for a spelling; an unknown one is a `UserError` listing them."""
    key = name.strip().lower().replace("-", "_").replace(" ", "_")
    for a in ACTIONS.values():
        if key == a.name or key in {s.replace("-", "_").replace(" ", "_") for s in a.spellings}:
            return a
    raise UserError(f"unknown action {name!r}; expected one of: {', '.join(ACTIONS)}")


def verb(name: str) -> Verb:
    try:
        return VERBS[name]
    except KeyError:
        raise UserError(f"unknown verb {name!r}; expected one of: {', '.join(VERBS)}") from None
