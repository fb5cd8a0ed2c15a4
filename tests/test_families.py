"""Direction families and a direction at a distance, each added inside a test through its
declaration alone (docs/architecture.md, recipes), laid out, graded and taught end to end with
ground-truth vision; the published experiments do not change when they are declared."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from aileen.agent import Agent
from aileen.curriculum import grading, trainer
from aileen.curriculum.interpreter import Interpreter
from aileen.curriculum.lesson import ActionSpec, Lesson, ObjectSpec
from aileen.curriculum.sentences import read_content
from aileen.domain import relations
from aileen.experiments import wide
from aileen.experiments.protocol import PROTOCOL_EXPERIMENTS, make_trial
from aileen.perception.truth import TruthVision

# ------------------------------------------------------------------ the declarations (recipes)


@pytest.fixture
def diagonal():
    """Recipe (a): a family of four diagonal words, each a 45-degree sector between two
    cardinal words, declared with its opposite and its grain."""
    grain = relations.Grain("diagonal", 22.5)
    with relations.kept():
        relations.declare_directions(
            relations.Direction("behind left of", 135.0, "front right of", grain, aliases=("back left of",)),
            relations.Direction("front right of", 315.0, "behind left of", grain),
            relations.Direction("behind right of", 45.0, "front left of", grain),
            relations.Direction("front left of", 225.0, "behind right of", grain),
        )
        yield "behind left of"


@pytest.fixture
def far_left():
    """Recipe (b): "far left of", the conjunction of a declared direction and a declared distance."""
    with relations.kept():
        relations.declare(relations.conjunction("far left of", "left of", "far from"))
        yield "far left of"


# ------------------------------------------------------------------ helpers


def _lesson(signal: str, content: str, relation: str, distractors: int = 0, **kw) -> Lesson:
    return Lesson(signal, content, [ObjectSpec("box", "red"), ObjectSpec("cone", "blue")], relation=relation,
                  distractors=distractors, **kw)


def _pair(setup: trainer.Setup):
    return setup.world.get(setup.ids[0]), setup.world.get(setup.ids[1])


def _taught(word: str, lessons: int, seed: int) -> tuple[Interpreter, int]:
    """An agent with ground-truth vision that knows "red box", "blue cone" and has been told
    `lessons` times of a red box `word` a blue cone, laid out over the whole region a person
    accepts (`relations.wide`: a word taught within 10 degrees of its axis is learned that
    narrow), as the wide protocol teaches."""
    vision = TruthVision()
    interp = Interpreter(Agent(perceiver=vision), on_frame=vision.see_frame)
    for i, o in enumerate(["red box", "blue cone"]):
        interp.run(Lesson("inform", o, [ObjectSpec(*reversed(o.split()))]), index=1, seed=seed + i)
    for k in range(lessons):
        first = interp.run(_lesson("inform", f"red box {word} blue cone", relations.wide(word)), index=1,
                           seed=seed + 10 + k)
        if k == 0:
            assert first.answer.created == ["r_" + word.replace(" ", "_")]
    return interp, seed + 100


def _published_trials() -> list[tuple]:
    out = []
    for protocol, experiments in PROTOCOL_EXPERIMENTS.items():
        for e in experiments:
            t = make_trial(e, 0, protocol)
            out.append((protocol, e, [[(x.content, x.relation, x.action, tuple(x.objects), x.near_miss, x.note)
                                       for x in part] for part in (t.prerequisites, t.lessons, t.generality,
                                                                   t.specificity)]))
    return out


# ------------------------------------------------------------------ (a) a diagonal family


def test_a_family_is_declared_with_opposites_grain_and_variants(diagonal) -> None:
    d = relations.direction("back-left-of")
    assert d.word == diagonal and d.opposite == "front right of" and d.grain.name == "diagonal"
    assert wide.opposite(diagonal) == "front right of" and wide.opposite("front right of") == diagonal
    assert relations.directions("diagonal") == ("behind left of", "front right of", "behind right of", "front left of")
    assert relations.directions("cardinal") == ("left of", "right of", "in front of", "behind")
    assert relations.wide(diagonal) == "behind left of wide"
    assert relations.canonical("back left of ec") == d.touching == "behind left of ec"
    assert d.region() == (135.0, 45.0)
    # the trainer's sentences and the teacher's grammar read the new words
    assert read_content("the red box behind left of the blue cone").relation == diagonal
    assert relations.spellings()["back left of"] == diagonal


def test_a_family_that_contradicts_itself_is_refused() -> None:
    grain = relations.Grain("slanted", 22.5)
    with relations.kept():
        with pytest.raises(ValueError, match="opposite 'nowhere'"):
            relations.declare_directions(relations.Direction("up left of", 135.0, "nowhere", grain))
        with pytest.raises(ValueError, match="half a circle"):
            relations.declare_directions(relations.Direction("up left of", 135.0, "down right of", grain),
                                         relations.Direction("down right of", 300.0, "up left of", grain))
        with pytest.raises(ValueError, match="overlap"):
            relations.declare_directions(relations.Direction("up left of", 135.0, "down right of", grain),
                                         relations.Direction("down right of", 315.0, "up left of", grain),
                                         relations.Direction("upper left of", 120.0, "lower right of", grain),
                                         relations.Direction("lower right of", 300.0, "upper left of", grain))
        with pytest.raises(ValueError, match="lay < clear < half_angle"):
            relations.Grain("narrow", 5.0)
        assert relations.find("up left of") is None  # nothing half-declared
    assert relations.find("up left of") is None


@pytest.mark.parametrize("layout", ["behind left of", "behind left of wide", "behind left of ec",
                                    "front left of", "behind right of wide"])
def test_the_trainer_lays_out_every_variant_of_a_declared_family(diagonal, layout: str) -> None:
    rel = relations.get(layout)
    for seed in range(3):
        a, b = _pair(trainer.layout(_lesson("inform", "x", layout, distractors=2), seed=seed))
        assert rel.clear(a, b) and rel.word in relations.which(a, b)
        assert relations.angle_off(layout, a, b) < rel.direction.grain.half_angle
        miss = trainer.layout(_lesson("inform", "x", layout, distractors=2, near_miss=True), seed=seed)
        assert not relations.holds(layout, *_pair(miss))
        # words of different grains are not disjoint: a plain diagonal layout may also be "behind"
        assert len([w for w in relations.which(a, b) if w in relations.directions("diagonal")]) == 1


def test_a_diagonal_goal_is_demonstrated_and_graded(diagonal) -> None:
    lesson = Lesson("verify", f"move the red box {diagonal} the blue cone", [ObjectSpec("box", "red"),
                    ObjectSpec("cone", "blue")], action=ActionSpec("move", diagonal))
    for seed in range(2):
        setup = trainer.layout(lesson, seed=seed)
        a, b = _pair(setup)
        assert not relations.holds(diagonal, a, b)  # the goal starts clearly false
        assert relations.angle_off(diagonal, a, b) >= trainer.GOAL_AWAY_ANGLE - 5.0
        assert grading.expected(lesson, setup) == "success"


def test_a_diagonal_word_is_taught_end_to_end_with_ground_truth_vision(diagonal) -> None:
    interp, seed = _taught(diagonal, 3, seed=400)
    said = f"red box {diagonal} blue cone"
    yes = interp.run(_lesson("verify", said, diagonal, 2), index=1, seed=seed)
    wide_yes = interp.run(_lesson("verify", said, relations.wide(diagonal), 1), index=1, seed=seed + 1)
    opposite = interp.run(_lesson("verify", said, wide.opposite(diagonal)), index=1, seed=seed + 2)
    behind = interp.run(_lesson("verify", said, "behind"), index=1, seed=seed + 3)  # its neighbour, 45 off
    for r in (yes, wide_yes):
        assert r.expected == "success" and r.correct, r.answer.reason
    for r in (opposite, behind):
        assert r.expected == "failure" and r.correct, r.answer.reason


# ------------------------------------------------------------------ (b) a direction at a distance


def test_far_left_of_is_both_words_as_a_person_judges_them(far_left) -> None:
    rel = relations.get(far_left)
    assert rel.direction == relations.direction("left of") and rel.distance == relations.get("far from").distance
    rng = np.random.default_rng(0)
    kinds = set()
    for _ in range(200):
        for f in ((0.07, 0.13), (0.10, 0.10), (0.13, 0.07)):
            dx, dy = relations.sample_offset(far_left, *f, rng)
            a, b = _P(0.5 + dx, 0.5 + dy, f[0] / 2), _P(0.5, 0.5, f[1] / 2)
            assert rel.clear(a, b) and {"left of", "far from", far_left} <= set(relations.which(a, b))
            mx, my = rel.near_miss(rng, *f)
            a = _P(0.5 + mx, 0.5 + my, f[0] / 2)
            assert not rel.accepts(a, b)
            kinds.add((relations.holds("left of", a, b), relations.holds("far from", a, b)))
    assert kinds == {(True, False), (False, True)}  # left of but not far; far but not left of


def test_far_left_of_is_laid_out_demonstrated_and_graded(far_left) -> None:
    for seed in range(3):
        setup = trainer.layout(_lesson("inform", "x", far_left, distractors=2), seed=seed)
        assert relations.clearly_holds(far_left, *_pair(setup))
        miss = trainer.layout(_lesson("inform", "x", far_left, distractors=2, near_miss=True), seed=seed)
        assert not relations.holds(far_left, *_pair(miss))
    said = Lesson("verify", "red box far left of blue cone", [ObjectSpec("box", "red"), ObjectSpec("cone", "blue")],
                  relation="left of")  # left of, not far: the sentence is false
    assert grading.expected(said, trainer.layout(said, seed=1)) == "failure"
    move = Lesson("verify", "move the red box far left of the blue cone", said.objects,
                  action=ActionSpec("move", far_left))
    assert grading.expected(move, trainer.layout(move, seed=2)) == "success"


def test_far_left_of_is_taught_end_to_end_with_ground_truth_vision(far_left) -> None:
    interp, seed = _taught(far_left, 3, seed=500)
    said = f"red box {far_left} blue cone"
    yes = interp.run(_lesson("verify", said, far_left, 1), index=1, seed=seed)
    near_by = interp.run(_lesson("verify", said, "left of"), index=1, seed=seed + 1)  # left of, not far
    far_right = interp.run(dataclasses.replace(_lesson("verify", said, "far from"), objects=[
        ObjectSpec("box", "red", position=(0.85, 0.5)), ObjectSpec("cone", "blue", position=(0.2, 0.5))]),
        index=1, seed=seed + 2)  # far, on the other side
    assert yes.expected == "success" and yes.correct, yes.answer.reason
    for r in (near_by, far_right):
        assert r.expected == "failure" and r.correct, r.answer.reason


def test_far_left_of_taught_after_both_its_parts_is_still_both(far_left) -> None:
    """Taught after "left of" and "far from", every fact of a "far left of" example is claimed
    by one of them: the word is their conjunction and keeps its direction (agent/directions.py
    `explained`), so a far pair on the other side is refused."""
    vision = TruthVision()
    interp = Interpreter(Agent(perceiver=vision), on_frame=vision.see_frame)
    for i, o in enumerate(["red box", "blue cone"]):
        interp.run(Lesson("inform", o, [ObjectSpec(*reversed(o.split()))]), index=1, seed=600 + i)
    for k, (layout, w) in enumerate((("left of wide", "left of"), ("far from", "far from"), (far_left, far_left))):
        interp.run(_lesson("inform", f"red box {w} blue cone", layout), index=1, seed=610 + k)
    far_right = interp.run(dataclasses.replace(_lesson("verify", f"red box {far_left} blue cone", "far from"), objects=[
        ObjectSpec("box", "red", position=(0.85, 0.5)), ObjectSpec("cone", "blue", position=(0.2, 0.5))]),
        index=1, seed=630)
    assert far_right.expected == "failure" and far_right.correct, far_right.answer.reason


# ------------------------------------------------------------------ the published experiments


def test_declaring_families_and_conjunctions_changes_no_published_experiment() -> None:
    before = _published_trials()
    grain = relations.Grain("diagonal", 22.5)
    with relations.kept():
        relations.declare_directions(relations.Direction("behind left of", 135.0, "front right of", grain),
                                     relations.Direction("front right of", 315.0, "behind left of", grain))
        relations.declare(relations.conjunction("far left of", "left of", "far from"),
                          relations.conjunction("near behind", "behind", "near"))
        assert "far left of" in relations.words()
        assert _published_trials() == before
    assert "far left of" not in relations.words()


class _P:
    def __init__(self, x: float, y: float, half: float, size: str = "medium") -> None:
        self.x, self.y, self.half, self.size = x, y, half, size

    def box_m(self) -> tuple[float, float, float, float]:
        return self.x - self.half, self.y - self.half, self.x + self.half, self.y + self.half


def test_a_conjunction_needs_a_direction_and_a_distance() -> None:
    from aileen.errors import UserError

    with pytest.raises(UserError, match="joins a direction and a distance"):
        relations.conjunction("far near", "near", "far from")
    assert math.isclose(relations.direction("left of").axis, 180.0)
