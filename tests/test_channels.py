"""A channel and a shape are each one declaration (issue 21, build item 1; docs/architecture.md,
recipes "Add a channel" and "Add a shape").

Each test declares, inside the test only, a channel "texture" (plain, striped) with its render
function and measure, or a fifth shape "ring" with its footprint and render function, and
teaches it end to end with ground-truth vision: the trainer draws it, lays it out and grades
it, the lesson readers and the sentence reader read it, the camera draws it, the truth vision
reports it, and the agent learns its words from examples. Nothing else is touched: the
declarations are the whole recipe. Outside the `with` block the domain is as it was.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from aileen.agent import Agent
from aileen.curriculum import legacy, lessonfile, trainer
from aileen.curriculum.interpreter import Interpreter
from aileen.curriculum.lesson import Lesson, ObjectSpec
from aileen.curriculum.sentences import parse_object, read_content
from aileen.domain import channels
from aileen.errors import UserError
from aileen.perception.truth import TruthVision
from aileen.world import catalog
from aileen.world.appearance import Appearance, Canvas
from aileen.world.render import render
from aileen.world.sim import World

# ----------------------------------------------------------------------------- the declarations


def stripes(value: str, canvas: Canvas) -> None:
    """Render function of "texture": a striped object has dark diagonal bands across its top."""
    if value == "striped":
        band = np.floor((canvas.X + canvas.Y) * 2.5) % 2 == 0
        canvas.bright = canvas.bright * np.where(band, 0.45, 1.0)


def measure_texture(image: np.ndarray, detection, camera) -> tuple[str, float]:  # noqa: ANN001
    """Measure of "texture": how much the brightness varies over the middle of the object's box
    (a plain top is nearly flat; a striped one alternates)."""
    u0, v0, u1, v1 = detection.box_px
    cu, cv, hu, hv = (u0 + u1) / 2, (v0 + v1) / 2, (u1 - u0) / 4, (v1 - v0) / 4
    patch = image[int(cv - hv):int(cv + hv) + 1, int(cu - hu):int(cu + hu) + 1].astype(float).mean(axis=2)
    spread = float(patch.std() / max(patch.mean(), 1.0))
    return ("striped" if spread > 0.15 else "plain"), abs(spread - 0.15)


TEXTURE = channels.Channel("texture", ("plain", "striped"), measure_texture, render=stripes)


def ring_top(name: str, canvas: Canvas) -> None:
    """Render function of the shape "ring": a torus seen from above, bright on its crown, with a
    dark hole in the middle."""
    rho = np.sqrt(canvas.X * canvas.X + canvas.Y * canvas.Y)
    crown = np.clip(1.0 - np.abs(rho - 0.7) / 0.3, 0.0, 1.0)
    canvas.bright = np.where(rho < 0.4, 0.25, 0.6 + 0.45 * crown)


RING = catalog.Shape("ring", footprint="disc", render=ring_top)


# ----------------------------------------------------------------------------- helpers


def _teach(interp: Interpreter, lessons: list[Lesson], seed: int) -> list:
    return [interp.run(lesson, index=i + 1, seed=seed + i) for i, lesson in enumerate(lessons)]


def _visual_curriculum(rng: np.random.Generator) -> list[Lesson]:
    """Every colour-shape kind once and every shape word alone, shuffled (the paper's visual
    lessons), read from the declarations: a declared shape is among them."""
    items = [ObjectSpec(s, c) for s in channels.SHAPE.values for c in channels.COLOUR.values]
    items += [ObjectSpec(s) for s in channels.SHAPE.values]
    order = rng.permutation(len(items))
    return [Lesson("inform", items[i].describe(), [items[i]]) for i in order]


def _truth_agent() -> tuple[Agent, Interpreter]:
    vision = TruthVision()
    agent = Agent(perceiver=vision)
    return agent, Interpreter(agent, on_frame=vision.see_frame)


# ----------------------------------------------------------------------------- the record


def test_an_appearance_is_a_frozen_mapping_equal_whatever_its_order() -> None:
    a = Appearance(shape="box", colour="red", size="large")
    b = Appearance([("size", "large"), ("colour", "red"), ("shape", "box")])
    assert a == b and hash(a) == hash(b) and a == {"shape": "box", "colour": "red", "size": "large"}
    assert list(a) == ["shape", "colour", "size"] and list(b) == ["size", "colour", "shape"]
    assert a.replace(size=None, texture="striped") == Appearance(shape="box", colour="red", texture="striped")
    assert a == Appearance(shape="box", colour="red", size="large")  # replace made a copy
    assert len({a, b, a.replace(colour="blue")}) == 2
    with pytest.raises(TypeError):
        Appearance(shape=3)  # type: ignore[arg-type]
    import pickle

    assert pickle.loads(pickle.dumps(a)) == a


# ----------------------------------------------------------------------------- (c) a channel


def test_the_trainers_remembered_readings_follow_the_vocabulary() -> None:
    """`read_content` remembers its readings: one made before a channel is declared is not
    handed out while it is, nor one made inside its scope after it; a caller that changes the
    lists it was given changes no later reading."""
    sentence = "striped red box left of plain blue cone"
    before = read_content(sentence)
    assert before.unknown == ["striped", "plain"] and before.phrases == [ObjectSpec("box", "red"),
                                                                         ObjectSpec("cone", "blue")]
    with channels.scope(TEXTURE):
        inside = read_content(sentence)
        assert inside.unknown == [] and inside.phrases[0] == ObjectSpec("box", "red", texture="striped")
    after = read_content(sentence)
    assert after.unknown == ["striped", "plain"] and after.phrases == before.phrases
    after.unknown.append("mine")
    after.phrases.clear()
    again = read_content(sentence)
    assert again.unknown == ["striped", "plain"] and len(again.phrases) == 2


def test_a_declared_channel_reaches_the_readers_the_world_and_the_camera() -> None:
    with channels.scope(TEXTURE):
        # the sentence reader, the lesson readers (TOML and the original JSON) read it
        assert parse_object("striped red box") == ObjectSpec("box", "red", texture="striped")
        assert parse_object("striped red box").describe() == "striped red box"
        assert read_content("striped red box left of plain blue cone").phrases == [
            ObjectSpec("box", "red", texture="striped"), ObjectSpec("cone", "blue", texture="plain")]
        toml = ('[[lesson]]\nsignal = "inform"\ncontent = "striped red box"\n'
                'objects = [{ shape = "box", colour = "red", texture = "striped" }]\n')
        assert lessonfile.loads(toml).lessons[0].objects == [ObjectSpec("box", "red", texture="striped")]
        script = json.dumps([{"lesson-type": "visual-word", "signal": "inform", "content": "striped red box",
                              "description": {"color": "red", "shape": "box", "texture": "striped"}}])
        assert legacy.loads(script).lessons[0].objects == [ObjectSpec("box", "red", texture="striped")]
        with pytest.raises(UserError, match="unknown texture 'wavy'; expected one of: plain, striped"):
            lessonfile.loads(toml.replace('texture = "striped"', 'texture = "wavy"'))

        # the world holds it (its default when nobody says), the camera draws it, the truth has it
        world = World()
        plain = world.add("box", "red", 0.3, 0.5)
        striped = world.add("box", "red", 0.7, 0.5, texture="striped")
        assert world.get(plain).appearance == Appearance(shape="box", colour="red", size="medium", texture="plain")
        frame = render(world)
        by_id = {t.id: t for t in frame.truth}
        assert channels.truth_percepts(by_id[striped]) == ("cv_box", "cv_red", "cv_medium", "cv_striped")

        def spread(t) -> float:  # noqa: ANN001
            u0, v0, u1, v1 = (int(round(v)) for v in t.box_px)
            patch = frame.image[v0 + 4:v1 - 4, u0 + 4:u1 - 4].astype(float).mean(axis=2)
            return float(patch.std())

        assert spread(by_id[striped]) > 3 * spread(by_id[plain])
        # its measure reads it back from the image, through the live perceiver's detections
        from aileen.perception.scene import perceive

        seen = perceive(frame.image)
        assert sorted(o.values["texture"] for o in seen.objects) == ["plain", "striped"]
        assert {o.values["texture"] for o in seen.objects if o.centre_m[0] > 0.5} == {"striped"}

    # outside the scope: nothing of it is left
    assert "texture" not in channels.names()
    with pytest.raises(UserError, match="cannot read 'striped'"):
        parse_object("striped red box")
    with pytest.raises(UserError, match="unknown channel 'texture'"):
        World().add("box", "red", 0.5, 0.5, texture="striped")


def test_a_declared_channel_is_drawn_by_the_trainer_and_its_distractors() -> None:
    with channels.scope(TEXTURE):
        seen = set()
        for seed in range(12):
            setup = trainer.layout(Lesson("inform", "red box", [ObjectSpec("box", "red")], distractors=3), seed=seed)
            objs = [setup.world.get(i) for i in setup.ids + setup.distractor_ids]
            seen |= {o.appearance["texture"] for o in objs}
            # distractors differ from the described object in kind (texture included) and never
            # fit the phrase: a striped red box is a fine distractor for "plain red box"
            kinds = {channels.kind_of(o.appearance) for o in objs}
            assert len(kinds) == len(objs)
            # the transcript's table names each object by its kind, texture included
            assert all(f"{o.appearance['texture']} {o.colour} {o.shape}" in line
                       for o, line in zip(setup.world.objects(), setup.describe()))
        assert seen == {"plain", "striped"}
        said = Lesson("verify", "plain red box", [ObjectSpec("box", "red", texture="plain")], distractors=8)
        allowed = trainer.distractor_kinds(said, [Appearance(shape="box", colour="red", texture="plain")])
        assert Appearance(shape="box", colour="red", texture="striped") in allowed
        assert all(not said.objects[0].fits(k) for k in allowed)
        # every drawn shape and colour, plain or striped, but the plain red box
        assert len(allowed) == len(catalog.drawn_shapes()) * len(catalog.COLOURS) * 2 - 1


def test_a_declared_channel_is_taught_end_to_end_with_ground_truth_vision() -> None:
    with channels.scope(TEXTURE):
        agent, interp = _truth_agent()
        rng = np.random.default_rng(21)
        # colours and shapes first, the trainer drawing each object's texture (the lessons say none)
        _teach(interp, _visual_curriculum(rng), seed=1000)
        # then the texture words, each taught on objects whose other words are known
        lessons = [Lesson("inform", f"{t} {c} {s}", [ObjectSpec(s, c, texture=t)])
                   for t, c, s in [("striped", "red", "box"), ("plain", "blue", "cone"),
                                   ("striped", "green", "cylinder"), ("plain", "yellow", "sphere")]]
        taught = _teach(interp, lessons, seed=2000)
        assert "r_striped" in taught[0].answer.created and "r_plain" in taught[1].answer.created

        def verify(content: str, spec: ObjectSpec, expect: str, k: int):  # noqa: ANN202
            return interp.run(Lesson("verify", content, [spec], distractors=2, expect=expect), index=1, seed=3000 + k)

        exams = [
            verify("striped purple sphere", ObjectSpec("sphere", "purple", texture="striped"), "success", 0),
            verify("striped purple sphere", ObjectSpec("sphere", "purple", texture="plain"), "failure", 1),
            verify("plain green box", ObjectSpec("box", "green", texture="plain"), "success", 2),
            verify("plain green box", ObjectSpec("box", "green", texture="striped"), "failure", 3),
            verify("yellow cone", ObjectSpec("cone", "yellow", texture="striped"), "success", 4),
        ]
        for r in exams:
            assert r.correct, (r.lesson.content, r.lesson.objects, r.answer.result, r.answer.reason)


# ----------------------------------------------------------------------------- (e) a shape


def test_a_declared_shape_is_drawn_laid_out_and_taught_with_ground_truth_vision() -> None:
    with channels.scope(RING):
        assert channels.SHAPE.values == (*catalog.SHAPES[:-1], "ring") and catalog.SHAPES[-1] == "ring"
        assert parse_object("blue ring") == ObjectSpec("ring", "blue")
        # its footprint and its render function: a disc with a dark hole in the middle
        world = World()
        obj = world.add("ring", "blue", 0.5, 0.5)
        frame = render(world, lighting=False)
        u0, v0, u1, v1 = frame.truth[0].box_px
        assert math.isclose(u1 - u0, catalog.SIZES["medium"] * 256, abs_tol=1.5)
        cu, cv = int((u0 + u1) / 2), int((v0 + v1) / 2)
        assert frame.image[cv, cu].sum() < 0.5 * frame.image[cv, int(u0 + 0.15 * (u1 - u0))].sum()
        assert channels.truth_percepts(world.get(obj))[0] == "cv_ring"
        box = world.add("box", "red", 0.2, 0.2)
        world.pick_up(box)
        with pytest.raises(UserError, match="a ring has no flat top"):
            world.place(box, 0.5, 0.5, onto=obj)

        agent, interp = _truth_agent()
        results = _teach(interp, _visual_curriculum(np.random.default_rng(5)), seed=4000)
        assert any("r_ring" in r.answer.created for r in results)
        exams = [
            interp.run(Lesson("verify", "red ring", [ObjectSpec("ring", "red")], distractors=3, expect="success"),
                       index=1, seed=5000),
            interp.run(Lesson("verify", "red ring", [ObjectSpec("box", "red")], distractors=3, expect="failure"),
                       index=1, seed=5001),
            interp.run(Lesson("verify", "ring", [ObjectSpec("ring", "yellow")], distractors=2, expect="success"),
                       index=1, seed=5002),
            interp.run(Lesson("verify", "green cylinder", [ObjectSpec("ring", "green")], expect="failure"),
                       index=1, seed=5003),
        ]
        for r in exams:
            assert r.correct, (r.lesson.content, r.lesson.objects, r.answer.result, r.answer.reason)
        # the trainer draws the declared shape like any other when a lesson leaves the shape open
        drawn = {trainer.layout(Lesson("inform", "red object", [ObjectSpec(colour="red")]), seed=s).world.objects()[0].shape
                 for s in range(40)}
        assert "ring" in drawn

    assert "ring" not in catalog.SHAPES and "ring" not in channels.SHAPE.values
    with pytest.raises(UserError, match="unknown shape 'ring'"):
        World().add("ring", "blue", 0.5, 0.5)


def test_declarations_refuse_a_name_or_percept_already_taken() -> None:
    with pytest.raises(UserError, match="already declared"):
        with channels.scope(channels.Channel("colour", ("teal",), measure_texture)):
            pass
    with pytest.raises(UserError, match="percept cv_red is already a colour"):
        with channels.scope(channels.Channel("paint", ("red", "matt"), measure_texture)):
            pass
    with pytest.raises(UserError, match="cv_box is already a shape"):
        with channels.scope(catalog.Shape("box")):
            pass
    assert channels.names() == ("shape", "colour", "size")
    assert catalog.SHAPES == ("box", "cone", "sphere", "cylinder", "capsule")  # the shipped shapes, as before


def test_a_drawing_block_limits_every_random_draw_to_its_shapes() -> None:
    from aileen.world import catalog

    outside = catalog.drawn_shapes()
    with catalog.drawing(("sphere", "box")):
        assert catalog.drawn_shapes() == ("box", "sphere")  # the catalog's order
        with catalog.drawing(catalog.PAPER_SHAPES):
            assert catalog.drawn_shapes() == catalog.PAPER_SHAPES
        assert catalog.drawn_shapes() == ("box", "sphere")
    assert catalog.drawn_shapes() == outside
    with pytest.raises(UserError):
        with catalog.drawing(("blob",)):
            pass


def test_renders_table_has_a_column_per_declared_channel(tmp_path, capsys) -> None:
    from aileen.cli import main

    with channels.scope(TEXTURE):
        assert main(["render", "--seed", "3", "--objects", "2", "--out", str(tmp_path / "r.png")]) == 0
    header = capsys.readouterr().out.splitlines()[1].split()
    assert header[:5] == ["id", "shape", "colour", "size", "texture"]


def test_the_table_names_a_channel_with_a_default_where_an_object_is_not_it() -> None:
    """A channel declared with a default (as the recipe advises) never showed in the table's
    lines: a striped yellow sphere was "yellow sphere", though the agent saw it striped."""
    with channels.scope(channels.Channel("texture", ("plain", "striped"), measure_texture, render=stripes,
                                         default="plain")):
        setup = trainer.layout(Lesson("inform", "striped yellow sphere left of red box",
                                      [ObjectSpec("sphere", "yellow", texture="striped"), ObjectSpec("box", "red")]),
                               seed=0)
        first, second = setup.describe()
        assert "striped yellow sphere" in first and "red box" in second and "plain" not in second
