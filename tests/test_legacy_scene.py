"""A scene the original's instructor saved (`{"interaction": ..., "scene": [Webots nodes]}`) runs as one lesson (issue 22)."""

from __future__ import annotations

import json

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.curriculum import grading, legacy, trainer
from aileen.errors import UserError
from aileen.world.catalog import COLOURS


def _node(rgb: tuple[float, float, float], geometry: str, size: str | None = "Small") -> str:
    said = f'   description "{size}"\n' if size else ""
    return ("Solid {\n   recognitionColors %g %g %g\n   translation 0.4 0.45 -0.2\n   children [\n"
            "       Shape {\n          appearance PBRAppearance {\n          baseColor %g %g %g\n        }\n"
            "        geometry %s {\n          radius 0.02\n        }\n        }\n    ]\n%s}"
            % (*rgb, *rgb, geometry, said))


def _scene(content: str, signal: str, *nodes: str, **extra: object) -> str:
    return json.dumps({"interaction": {"content": content, "signal": signal, "concept": "", **extra},
                       "scene": list(nodes)})


def test_a_saved_scene_of_one_object_is_a_visual_lesson() -> None:
    c = legacy.loads(_scene("cylinder", "inform", _node((1, 1, 0), "Cylinder")), "s.json")
    (lesson,) = c.lessons
    assert (lesson.signal, lesson.content) == ("inform", "cylinder")
    (obj,) = lesson.objects
    assert dict(obj.appearance) == {"colour": "yellow", "shape": "cylinder", "size": "small"}


def test_a_saved_scene_of_a_relation_is_a_spatial_lesson_with_its_other_objects() -> None:
    c = legacy.loads(_scene("red cone near red box", "verify", _node((0.9, 0.1, 0.1), "Cone", "Large"),
                            _node((0.1, 0.1, 0.9), "Sphere", None), _node((0.9, 0.1, 0.1), "Box", "Medium")),
                     "s.json")
    (lesson,) = c.lessons
    assert lesson.relation == "near" and lesson.distractors == 0
    assert [dict(o.appearance) for o in lesson.objects] == [
        {"colour": "red", "shape": "cone", "size": "large"}, {"colour": "red", "shape": "box", "size": "medium"},
        {"colour": "blue", "shape": "sphere"}]


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_saved_scenes_other_objects_stand_on_the_table_as_saved_at_every_seed(seed: int) -> None:
    """scene3.json of the probe: its green sphere was a random distractor, another at each seed."""
    c = legacy.loads(_scene("red box left of blue cone", "verify", _node((0.9, 0.1, 0.1), "Box", "Medium"),
                            _node((0.1, 0.1, 0.9), "Cone", None), _node((0.1, 0.9, 0.1), "Sphere", None)), "s.json")
    (lesson,) = c.lessons
    setup = trainer.layout(lesson, seed=seed)
    kinds = sorted((o.appearance["colour"], o.shape) for o in setup.world.objects())
    assert kinds == [("blue", "cone"), ("green", "sphere"), ("red", "box")]
    # without is_positive a verify is graded against the table the trainer lays out
    assert lesson.expect is None and grading.expected(lesson, setup) == "success"


@pytest.mark.parametrize("nodes, expected", [
    ([], "'scene' must be a non-empty list"),
    ([42], "must be a Webots node as a string"),
    (["Solid { geometry Box { } }"], "has no colour"),
    ([_node((1, 0, 0), "Teapot")], "unknown geometry 'Teapot'"),
])
def test_a_malformed_saved_scene_is_refused_in_one_line(nodes: list, expected: str) -> None:
    with pytest.raises(UserError) as err:
        legacy.loads(json.dumps({"interaction": {"content": "box", "signal": "inform"}, "scene": nodes}), "s.json")
    assert expected in str(err.value) and "s.json" in str(err.value) and "\n" not in str(err.value)


@settings(max_examples=40, deadline=None)
@given(st.tuples(*[st.floats(0, 1)] * 3), st.sampled_from(["Box", "Cylinder", "Cone", "Sphere"]))
def test_any_colour_and_shape_of_a_node_is_read_as_a_catalogue_value(rgb: tuple, geometry: str) -> None:
    c = legacy.loads(_scene(geometry.lower(), "inform", _node(rgb, geometry, None)), "s.json")
    (obj,) = c.lessons[0].objects
    assert obj.appearance["shape"] == geometry.lower()
    assert obj.appearance["colour"] in COLOURS


def test_a_node_without_a_base_colour_is_read_by_its_recognition_colour() -> None:
    node = "Solid {\n recognitionColors 0.1 0.2 0.9\n children [ Shape { geometry Sphere { radius 0.03 } } ]\n}"
    (obj,) = legacy.loads(_scene("sphere", "inform", node), "s.json").lessons[0].objects
    assert (obj.appearance["colour"], obj.appearance["shape"]) == ("blue", "sphere")


@pytest.mark.parametrize("entry, words", [
    ("hello world", "'scene' entry 2 must be a Webots node as a string"),
    (_node((0.9, 0.1, 0.1), "Plane"), "'scene' entry 2: unknown geometry 'Plane'"),
    ("Solid {\n children [ Shape { geometry Box { size 0.1 0.1 0.1 } } ]\n}", "'scene' entry 2 has no colour"),
])
def test_a_saved_scene_error_names_the_entry_line(entry: str, words: str) -> None:
    """The probe's scene/garbage.json ("hello world" was said to have no colour), plane.json,
    nocolor.json: the errors named no line."""
    text = json.dumps({"interaction": {"content": "red box", "signal": "inform"},
                       "scene": [_node((0.9, 0.1, 0.1), "Box"), entry]}, indent=1)
    with pytest.raises(UserError, match=words) as err:
        legacy.loads(text, "s.json")
    assert err.value.line == 8  # {, "interaction": {, 2 fields, }, "scene": [, entry 1, entry 2


@pytest.mark.parametrize("data, words, line", [
    ({"interaction": {"content": "red box"}, "scene": ["x"]}, "'interaction' must be", 2),
    ({"interaction": {"content": "red box", "signal": "inform"}, "scene": []}, "'scene' must be", 6),
])
def test_a_saved_scene_interaction_or_scene_error_names_its_line(data: dict, words: str, line: int) -> None:
    with pytest.raises(UserError, match=words) as err:
        legacy.loads(json.dumps(data, indent=1), "s.json")
    assert err.value.line == line
