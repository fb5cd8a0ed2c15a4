"""The perception data hold stacks, labelled with level and visible share."""

from __future__ import annotations

from aileen.perception.dataset import generate


def test_generated_scenes_hold_labelled_stacks() -> None:
    samples = list(generate(40, seed=11))
    objs = [o for s in samples for o in s.objects]
    uppers = [o for o in objs if o.level == 1]
    assert uppers, "no stacks in 40 scenes"
    assert all(o.visible == 1.0 for o in uppers)  # nothing rests on an upper object
    assert any(0.1 <= o.visible < 0.99 for o in objs if o.level == 0)  # partly hidden lower objects
    assert all(0.0 <= o.visible <= 1.0 for o in objs)
    # an upper object knows how much of the one under it shows: the least visible object
    # on the table within the upper one's footprint of it
    for s in samples:
        for u in (o for o in s.objects if o.level == 1):
            under = [o.visible for o in s.objects if o.level == 0 and o.visible < 1.0
                     and abs(o.centre_m[0] - u.centre_m[0]) < 0.07 and abs(o.centre_m[1] - u.centre_m[1]) < 0.07]
            assert u.support_visible in under
    assert all(o.support_visible == 1.0 for o in objs if o.level == 0)
    # reproducible from the seed
    again = list(generate(40, seed=11))
    assert [o for s in again for o in s.objects] == objs


def test_rows_of_touching_boxes_when_asked() -> None:
    from aileen.domain import relations
    from aileen.perception.dataset import SceneSpec
    from aileen.world.sim import WorldObject

    def as_placed(o) -> WorldObject:
        return WorldObject("o", o.appearance, 0, o.centre_m[0], o.centre_m[1], 0.0, False)

    rows = 0
    for s in generate(20, seed=5, spec=SceneSpec(3, 6, 0.0, 1.0)):
        boxes = [as_placed(o) for o in s.objects if o.shape == "box" and o.level == 0]
        touching = sum(1 for i, a in enumerate(boxes) for b in boxes[i + 1:] if abs(relations.gap(a, b)) < 1e-6)
        rows += touching >= 1
    assert rows == 20  # every scene starts with a row
