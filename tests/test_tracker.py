"""The tracker keeps agent ids stable across frames, also when a percept is read differently."""

from __future__ import annotations

from aileen.agent.state import Tracker
from aileen.perception.perceiver import Detection


def _det(percepts: tuple[str, ...], x: float, y: float) -> Detection:
    return Detection(percepts, (x - 0.05, y - 0.05, x + 0.05, y + 0.05), (0.0, 0.0, 1.0, 1.0))


def test_same_percepts_keep_their_id_nearest_first() -> None:
    t = Tracker()
    a, b = t.assign([_det(("cv_red", "cv_box"), 0.2, 0.2), _det(("cv_red", "cv_box"), 0.8, 0.8)])
    assert t.assign([_det(("cv_red", "cv_box"), 0.75, 0.8), _det(("cv_red", "cv_box"), 0.25, 0.2)]) == [b, a]


def test_what_the_hand_put_down_keeps_its_id_though_read_differently() -> None:
    t = Tracker()
    cone, sphere = t.assign([_det(("cv_purple", "cv_cone"), 0.4, 0.2), _det(("cv_blue", "cv_sphere"), 0.5, 0.6)])
    assert t.assign([_det(("cv_purple", "cv_cone"), 0.4, 0.2)]) == [cone]  # the sphere is held
    after = [_det(("cv_purple", "cv_cone"), 0.4, 0.2), _det(("cv_blue", "cv_cylinder"), 0.2, 0.3)]
    # without knowing what was released, a new reading is a new object
    fresh = Tracker()
    fresh.known = dict(t.known)
    assert fresh.assign(after)[1] not in (cone, sphere)
    # the object the hand let go is what appeared
    assert t.assign(after, released=sphere) == [cone, sphere]
    assert sphere in t.moved and t.known[sphere].percepts == ("cv_blue", "cv_cylinder")


def test_a_released_object_seen_with_its_own_percepts_is_matched_as_usual() -> None:
    t = Tracker()
    box, other = t.assign([_det(("cv_red", "cv_box"), 0.2, 0.2), _det(("cv_green", "cv_cone"), 0.7, 0.7)])
    t.assign([_det(("cv_green", "cv_cone"), 0.7, 0.7)])
    # a stranger appears too: the released box takes its own reading, the stranger a new id
    ids = t.assign([_det(("cv_green", "cv_cone"), 0.7, 0.7), _det(("cv_red", "cv_box"), 0.5, 0.5),
                    _det(("cv_blue", "cv_sphere"), 0.1, 0.9)], released=box)
    assert ids[:2] == [other, box] and ids[2] not in (box, other)


def test_an_object_read_differently_where_it_stood_keeps_its_id() -> None:
    """The lower box of a stack was seen large, and medium once the upper one was lifted off:
    it took a new id, and the plan's next step (made with the old one) crashed the react."""
    t = Tracker()
    low, up = t.assign([_det(("cv_blue", "cv_box", "cv_large"), 0.3, 0.3), _det(("cv_red", "cv_box", "cv_medium"), 0.3, 0.32)])
    assert t.assign([_det(("cv_blue", "cv_box", "cv_medium"), 0.3, 0.31)], held=up) == [low]
    assert t.known[low].percepts == ("cv_blue", "cv_box", "cv_medium")
    # elsewhere, or differing in two percepts, it is another object
    t2 = Tracker()
    a, = t2.assign([_det(("cv_blue", "cv_box", "cv_large"), 0.3, 0.3)])
    assert t2.assign([_det(("cv_blue", "cv_box", "cv_medium"), 0.6, 0.6)]) != [a]
    t3 = Tracker()
    b, = t3.assign([_det(("cv_blue", "cv_box", "cv_large"), 0.3, 0.3)])
    assert t3.assign([_det(("cv_red", "cv_cone", "cv_large"), 0.3, 0.3)]) != [b]
