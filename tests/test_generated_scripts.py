"""Scripts as the original's lesson generator and its first instructor wrote them (issue 22):
spatial lessons that name only their relation, negative action lessons without a sentence,
and the first, flat form of a visual lesson."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from aileen.cli import main
from aileen.curriculum import falsehood, grading, placeholders, rehearsal
from aileen.curriculum.legacy import loads
from aileen.curriculum.lesson import ObjectSpec
from aileen.curriculum.sentences import read_content


def _load(lessons: list[dict]):  # noqa: ANN202
    return loads(json.dumps(lessons, indent=2), "gen.json")


def _records(tmp_path: Path, capsys, lessons: list[dict]) -> tuple[int, list[dict]]:
    path = tmp_path / "gen.json"
    path.write_text(json.dumps(lessons, indent=2))
    rc = main(["run", str(path), "--json", "--perception", "truth", "--seed", "0"])
    out = capsys.readouterr().out
    return rc, [json.loads(line) for line in out.splitlines() if line.startswith("{")]


# ------------------------------------------------------------------ a relation and nothing else


def test_a_spatial_lesson_naming_only_its_relation_draws_two_objects_and_names_them() -> None:
    lesson = _load([{"lesson-type": "spatial-word", "signal": "inform", "description": {"relation": "behind"}}])[0]
    assert lesson.objects == [ObjectSpec(), ObjectSpec()] and lesson.name_objects
    named = placeholders.name(lesson, seed=3)
    a, b = named.objects
    assert named.content == f"{a.colour} {a.shape} behind {b.colour} {b.shape}"


@pytest.mark.parametrize("relation", ["left-of", "larger-than", "on"])
def test_relation_only_lessons_are_laid_out_true_and_a_negative_one_false(relation: str) -> None:
    lessons = _load([{"lesson-type": "spatial-word", "signal": "verify", "is_positive": "True",
                      "description": {"relation": relation}},
                     {"lesson-type": "spatial-word", "signal": "verify", "is_positive": "False",
                      "description": {"relation": relation}}])
    for lesson, want in zip(lessons, (True, False), strict=True):
        for seed in range(6):
            if lesson.say_false:
                said, setup = falsehood.prepare(lesson, seed=seed)
            else:
                said = placeholders.name(lesson, seed=seed)
                [setup] = rehearsal.check_curriculum([said], [seed])
            assert grading.content_true(said.content, setup.world.objects()) is want, (seed, said.content)


# ------------------------------------------------------------------ negative action lessons

MOVE = {"objects": ["<obj1>", "<obj2>"], "relations": ["right-of"], "initial_configuration": [],
        "trace-actions": [{"name": "pick-up", "argument": "<obj1>"},
                          {"name": "place", "argument1": "<obj1>", "argument2": "<obj2>", "relation": "right-of"}],
        "action": "move"}


def test_a_negative_action_lesson_without_a_sentence_is_said_falsely_of_its_demonstration() -> None:
    [lesson] = _load([{"lesson-type": "action-word", "signal": "verify", "is_positive": "False", "description": MOVE}])
    assert lesson.say_false and lesson.expect == "failure"
    for seed in range(6):
        said, setup = falsehood.prepare(lesson, seed=seed)
        info = read_content(said.content)
        assert info.verb == "move" and len(info.phrases) == 2, said.content
        mover, ref = (setup.world.get(i) for i in setup.ids[:2])
        # the sentence names the drawn objects: what the demonstration moves, and where
        assert {p.describe() for p in info.phrases} == {f"{o.colour} {o.shape}" for o in (mover, ref)}
        # judged against its own demonstration, it is false
        assert grading.expected(__import__("dataclasses").replace(said, expect=None), setup) == "failure"
        assert falsehood.prepare(lesson, seed=seed)[0].content == said.content  # seeded


def test_a_push_said_falsely_names_an_object_that_is_not_there() -> None:
    push = {"objects": ["<obj1>"], "relations": [], "action": "push",
            "trace-actions": [{"name": "push", "argument": "<obj1>"}]}
    [lesson] = _load([{"lesson-type": "action-word", "signal": "verify", "is_positive": "false", "description": push}])
    said, setup = falsehood.prepare(lesson, seed=2)
    info = read_content(said.content)
    assert info.verb == "push" and len(info.phrases) == 1
    assert not any(info.phrases[0].fits(o.appearance) for o in setup.world.objects())


def test_a_generated_negative_action_file_runs_to_its_end(tmp_path: Path, capsys) -> None:
    informs = [{"lesson-type": "action-word", "signal": "inform", "is_positive": "True", "description": MOVE}] * 2
    negative = {"lesson-type": "action-word", "signal": "verify", "is_positive": "False", "description": MOVE,
                "distractors": 1}
    rc, records = _records(tmp_path, capsys, [*informs, negative])
    assert len(records) == 3 and "skipped" not in records[2]
    assert records[2]["expected"] == "failure" and records[2]["content"].startswith("move ")
    assert rc in (0, 1)


# ------------------------------------------------------------------ the first, flat form


def test_the_first_flat_visual_form_is_read_as_a_visual_lesson() -> None:
    lessons = _load([{"lesson": "visual", "description": "box", "color": "red", "shape": "box", "signal": "inform"},
                     {"lesson": "visual", "description": "cylinder", "color": "green", "shape": "box",
                      "signal": "verify", "distractors": 2}])
    assert [(x.signal, x.content, x.objects, x.distractors) for x in lessons] == [
        ("inform", "box", [ObjectSpec("box", "red")], 0),
        ("verify", "cylinder", [ObjectSpec("box", "green")], 2)]


def test_the_flat_form_keeps_its_checks() -> None:
    from aileen.errors import UserError

    with pytest.raises(UserError, match="lesson"):
        _load([{"lesson": "juggling", "description": "box", "signal": "inform"}])
    with pytest.raises(UserError, match="colour|color"):
        _load([{"lesson": "visual", "description": "box", "color": "mauve", "shape": "box", "signal": "inform"}])


# ------------------------------------------------------------------ one object, a channel's value


def test_a_spatial_lesson_of_one_object_and_a_size_is_a_visual_lesson_at_that_size(tmp_path: Path, capsys) -> None:
    lesson = _load([{"lesson-type": "spatial-word", "signal": "inform", "content": "small green cone",
                     "description": {"objects": [{"color": "green", "shape": "cone"}], "relation": "small"}}])[0]
    assert lesson.relation is None and lesson.objects == [ObjectSpec("cone", "green", "small")]
    rc, records = _records(tmp_path, capsys, [
        {"lesson-type": "visual-word", "signal": "inform", "content": "green cone",
         "description": {"color": "green", "shape": "cone"}},
        {"lesson-type": "spatial-word", "signal": "inform", "content": "small green cone",
         "description": {"objects": [{"color": "green", "shape": "cone"}], "relation": "small"}}])
    assert len(records) == 2 and "r_small" in records[1]["created"] and "skipped" not in records[1]
    # a word that names no value of any channel is still no relation of one object
    with pytest.raises(Exception, match="must list two objects"):
        _load([{"lesson-type": "spatial-word", "signal": "inform", "content": "green cone left of",
                "description": {"objects": [{"color": "green", "shape": "cone"}], "relation": "left-of"}}])
