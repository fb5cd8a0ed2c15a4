"""A push demonstration the trainer spells out has room to be shown, whichever object it
pushes: the verb's declared room (north of the object, away from the trainer) holds for every
object a step of the verb's own actions is done to, not only for the object the sentence
names. ("push the red box" shown wrong by pushing the blue cone aborted lessons/push.toml at
seed 0: the cone stood at the far edge.)"""

from __future__ import annotations

from pathlib import Path

import pytest

from aileen.curriculum import trainer
from aileen.curriculum.demonstration import demonstrate
from aileen.curriculum.formats import load_curriculum
from aileen.curriculum.lesson import Lesson, Step
from aileen.domain import actions
from aileen.world.camera import Table

PUSH = Path(__file__).resolve().parents[1] / "lessons" / "push.toml"


def _other_pushed() -> Lesson:
    """push.toml's lesson whose demonstration pushes the object the sentence does not name."""
    for lesson in load_curriculum(PUSH).lessons:
        steps = lesson.demonstration or []
        if any(s.action == "push" and s.obj != 0 for s in steps):
            return lesson
    raise AssertionError("push.toml has no lesson that pushes its second object")


@pytest.mark.parametrize("seed", range(40))
def test_a_spelled_out_push_of_the_other_object_can_be_shown(seed: int) -> None:
    lesson = _other_pushed()
    setup = trainer.layout(lesson, seed=seed)
    demonstrate(lesson, setup, seed=seed)  # raises when the push would carry it off the table


def test_the_room_is_the_verbs_own_declaration() -> None:
    room = actions.verb("push").room
    assert room is not None
    lesson = _other_pushed()
    table = Table()
    half = 0.05
    shown = trainer._room_to_show(lesson, 1, half, table)
    # at the far edge there is no room ahead; in the middle there is
    assert not shown(table.width / 2, table.depth - half - 0.01)
    assert shown(table.width / 2, table.depth / 2)
    # an object nothing is done to may stand anywhere
    plain = Lesson(lesson.signal, lesson.content, lesson.objects,
                   demonstration=[Step("pick_up", 1), Step("place", 1, relation="left_of", ref=0)],
                   action=lesson.action)
    assert trainer._room_to_show(plain, 1, half, table)(table.width / 2, table.depth - half - 0.01)


def test_a_demonstration_with_no_room_is_a_layout_the_run_skips() -> None:
    """Where a spelled-out push would still carry an object off the table (a file that puts
    it at the far edge itself), the lesson is one the trainer cannot show: a `LayoutError`
    (the run skips it with its reason), not a mistake in the file."""
    from aileen.curriculum.stage import LayoutError
    from aileen.errors import NoRoom
    from aileen.world.sim import World

    w = World()
    box = w.add("box", "red", 0.5, w.table.depth - 0.06)
    with pytest.raises(NoRoom):
        w.push_away(box)
    lesson = _other_pushed()
    setup = trainer.layout(lesson, seed=0)
    far = setup.world.copy()
    # move the pushed object to the far edge, as if the table had been laid out that way
    target = setup.ids[1]
    far.pick_up(target)
    far.place(target, 0.5, far.table.depth - 0.06)
    with pytest.raises(LayoutError, match="off the table"):
        demonstrate(lesson, type(setup)(**{**setup.__dict__, "world": far}), seed=0)
