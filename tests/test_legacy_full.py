"""Every item of the original JSON scripts (issue 10, point 8): the reader, the trainer's false
sentences, located errors, and a whole script run through `aileen run --json`."""

from __future__ import annotations

import inspect
import json
import os
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from aileen.cli import main
from aileen.curriculum import falsehood, grading, trainer
from aileen.curriculum.formats import load_curriculum
from aileen.curriculum.legacy import loads
from aileen.curriculum.lesson import ActionSpec, ObjectSpec, Step
from aileen.domain import actions, composites, relations
from aileen.errors import UserError
from aileen.world import catalog
from aileen.world.sim import World

FULL = Path(__file__).resolve().parent.parent / "lessons" / "original-full.json"
# Stacking ("on") and push need the world's layers and push (issue 10 points 4 and 5); until the
# world has them, the run leaves out the lessons that need them and the whole-file run is skipped.
WORLD_STACKS_AND_PUSHES = "onto" in inspect.signature(World.place).parameters and hasattr(World, "push_away")
SETTINGS = settings(max_examples=int(os.environ.get("AILEEN_FUZZ_EXAMPLES", "60")), deadline=None,
                    suppress_health_check=[HealthCheck.too_slow])


def _one(lesson: dict) -> object:
    return loads(json.dumps([lesson], indent=2), "s.json")[0]


# ------------------------------------------------------------------ the reader


def test_composite_push_generate_and_sizes_map_to_records() -> None:
    wall = _one({"lesson-type": "composite-word", "content": "wall", "description": {"composite": "wall"},
                 "signal": "inform", "distractors": 0})
    assert wall.composite == "wall" and wall.objects == [ObjectSpec("box")] * 3
    tower = _one({"lesson-type": "composite-word", "signal": "verify",
                  "description": {"composite": "tower", "objects": [{"color": "red", "shape": "box"}, "<obj2>"]}})
    assert tower.content == "tower" and tower.objects == [ObjectSpec("box", "red"), ObjectSpec()]
    push = _one({"lesson-type": "action-word", "content": "push red sphere", "signal": "inform",
                 "description": {"objects": ["<obj1>"], "relations": [], "action": "push",
                                 "trace-actions": [{"name": "push", "argument": "<obj1>"}],
                                 "<obj1>": {"color": "red", "shape": "sphere", "size": "medium"}}})
    assert push.action == ActionSpec("push") and push.demonstration == [Step("push", 0)]
    assert push.objects == [ObjectSpec("sphere", "red", "medium")]
    react = _one({"lesson-type": "action-word", "signal": "react",
                  "description": {"objects": ["<obj1>"], "action": "push", "<obj1>": {"color": "blue", "shape": "cube"}}})
    assert react.content == "push blue box" and react.demonstration is None
    gen = _one({"lesson-type": "spatial-word", "signal": "generate", "concept": "object",
                "description": {"objects": ["<obj1>", "<obj2>"], "relation": "left-of"}})
    assert gen.signal == "generate" and gen.concept == "object" and gen.objects == [ObjectSpec(), ObjectSpec()]


@pytest.mark.parametrize("spelling, name", [
    ("left-of", "left of"), ("right-of", "right of"), ("front-of", "in front of"), ("behind", "behind"),
    ("near", "near"), ("distant", "far from"), ("next-to", "next to"), ("on", "on"), ("larger-than", "larger than"),
    ("left-of-ec", "left of ec"), ("right-of-ec", "right of ec"), ("front-of-ec", "in front of ec"),
    ("behind-ec", "behind ec"), ("behind1", "behind1"), ("behind2", "behind2"), ("behind3", "behind3"),
    ("behind-disjunctive", "behind disjunctive"),
])
def test_every_original_relation_is_read_and_said_by_its_word(spelling: str, name: str) -> None:
    lesson = _one({"lesson-type": "spatial-word", "signal": "inform",
                   "description": {"objects": [{"color": "red", "shape": "box"}, {"color": "blue", "shape": "box"}],
                                   "relation": spelling}})
    assert lesson.relation == name
    # the trainer says the word, never the layout's name ("behind2" is said "behind")
    assert lesson.content == f"red box {relations.get(name).word} blue box"


@pytest.mark.parametrize("value, expect", [("True", "success"), ("TRUE", "success"), ("true", "success"),
                                           (True, "success"), ("False", "failure"), ("fAlSe", "failure"),
                                           (False, "failure")])
def test_is_positive_in_any_letter_case(value: object, expect: str) -> None:
    lesson = _one({"lesson-type": "visual-word", "content": "red box", "signal": "verify", "is_positive": value,
                   "description": {"color": "red", "shape": "box"}})
    assert lesson.expect == expect and not lesson.say_false


def test_negative_without_content_asks_the_trainer_for_a_false_sentence() -> None:
    visual = _one({"lesson-type": "visual-word", "signal": "verify", "is_positive": "False",
                   "description": {"color": "blue", "shape": "cone"}})
    assert visual.say_false and visual.expect == "failure"
    spatial = _one({"lesson-type": "spatial-word", "signal": "verify", "is_positive": "False",
                    "description": {"objects": [{"color": "red", "shape": "box"}, {"color": "blue", "shape": "cone"}],
                                    "relation": "left-of"}})
    assert spatial.say_false and spatial.relation == "left of"
    random = _one({"lesson-type": "visual-word", "signal": "verify", "is_positive": "false"})
    assert random.say_false and random.objects == [ObjectSpec()]
    said, setup = falsehood.prepare(random, seed=3)
    assert grading.content_true(said.content, setup.world.objects()) is False
    with_content = _one({"lesson-type": "visual-word", "signal": "verify", "is_positive": "False", "content": "red box",
                         "description": {"color": "blue", "shape": "cone"}})
    assert not with_content.say_false  # the script's own sentence is said
    with pytest.raises(UserError, match="needs 'content'"):
        _one({"lesson-type": "composite-word", "signal": "verify", "is_positive": "False",
              "description": {"composite": "wall"}})


# ------------------------------------------------------------------ located errors listing the declarations


def _located(lesson: dict, needle: str) -> UserError:
    text = json.dumps([{"lesson-type": "visual-word", "content": "red box", "signal": "inform",
                        "description": {"color": "red", "shape": "box"}}, lesson], indent=2)
    with pytest.raises(UserError) as info:
        loads(text, "script.json")
    err = info.value
    assert err.format().startswith("script.json:") and "lesson 2" in err.format()
    second = text.index("\n  {", text.index("\n  {") + 1)  # where lesson 2 starts
    assert err.line == text.count("\n", 0, text.index(needle, second)) + 1, (err.format(), needle)
    return err


SPATIAL = {"lesson-type": "spatial-word", "signal": "inform",
           "description": {"objects": [{"color": "red", "shape": "box"}, {"color": "blue", "shape": "box"}],
                           "relation": "left-of"}}


def test_misspelt_relation_size_action_and_lesson_type_list_the_declared_names() -> None:
    rel = _located({**SPATIAL, "description": {**SPATIAL["description"], "relation": "nxt-to"}}, '"nxt-to"')
    assert all(name in rel.message for name in relations.known())
    size = _located({"lesson-type": "visual-word", "signal": "inform", "description": {"shape": "box", "size": "huge"}},
                    '"size"')
    assert all(name in size.message for name in catalog.SIZES)
    act = _located({"lesson-type": "action-word", "signal": "inform", "content": "shove red box",
                    "description": {"objects": ["<obj1>"], "action": "shove", "<obj1>": {"shape": "box"}}}, '"shove"')
    assert all(name in act.message for name in actions.VERBS)
    step = _located({"lesson-type": "action-word", "signal": "inform", "content": "push red box",
                     "description": {"objects": ["<obj1>"], "action": "push", "<obj1>": {"shape": "box"},
                                     "trace-actions": [{"name": "shove", "argument": "<obj1>"}]}}, '"shove"')
    assert all(name in step.message for name in actions.ACTIONS)
    kind = _located({**SPATIAL, "lesson-type": "spatial-words"}, '"lesson-type"')
    assert "composite-word" in kind.message and "visual-word" in kind.message
    comp = _located({"lesson-type": "composite-word", "signal": "inform", "description": {"composite": "wal"}},
                    '"composite"')
    assert all(word in comp.message for word in composites.COMPOSITES)


def test_a_composite_with_too_few_parts_gets_a_one_line_reason() -> None:
    err = _located({"lesson-type": "composite-word", "signal": "inform",
                    "description": {"composite": "wall", "objects": [{"shape": "box"}, {"shape": "box"}]}}, '"objects"')
    assert "a wall has 3 parts" in err.message and "\n" not in err.format()


def test_a_push_lesson_with_two_objects_is_an_error() -> None:
    with pytest.raises(UserError, match="one object"):
        _one({"lesson-type": "action-word", "signal": "inform", "content": "push red box",
              "description": {"objects": ["<obj1>", "<obj2>"], "action": "push"}})


def _mutations() -> st.SearchStrategy:
    lessons = json.loads(FULL.read_text())
    junk = st.one_of(st.none(), st.booleans(), st.integers(-3, 3), st.text(max_size=12),
                     st.sampled_from(["left-of-ec", "behind9", "push", "<obj7>", "wall", "huge", "generate", "TRUE"]),
                     st.lists(st.text(max_size=6), max_size=3), st.dictionaries(st.text(max_size=8), st.text(max_size=8),
                                                                               max_size=2))

    @st.composite
    def mutated(draw: st.DrawFn) -> str:
        lesson = json.loads(json.dumps(draw(st.sampled_from(lessons))))
        for _ in range(draw(st.integers(1, 3))):
            target = lesson
            if isinstance(lesson.get("description"), dict) and draw(st.booleans()):
                target = lesson["description"]
            keys = sorted(target) + ["<obj1>", "size", "relation", "composite", "concept", "objects"]
            key = draw(st.sampled_from(keys))
            if draw(st.integers(0, 4)) == 0:
                target.pop(key, None)
            else:
                target[key] = draw(junk)
        return json.dumps([lesson], indent=2)

    return mutated()


@SETTINGS
@given(_mutations())
def test_mutated_original_lessons_are_read_or_rejected_with_a_user_error(text: str) -> None:
    try:
        loads(text, "m.json")
    except UserError as exc:
        assert exc.path == "m.json" and "\n" not in exc.message


# ------------------------------------------------------------------ the trainer's false sentences


@pytest.mark.parametrize("seed", range(6))
def test_a_false_visual_sentence_names_a_pair_not_on_the_table(seed: int) -> None:
    lesson = _one({"lesson-type": "visual-word", "signal": "verify", "is_positive": "False", "distractors": 2,
                   "description": {"color": "blue", "shape": "cone"}})
    said, setup = falsehood.prepare(lesson, seed=seed)
    assert said.content != "blue cone" and not said.say_false and said.expect == "failure"
    assert grading.content_true(said.content, setup.world.objects()) is False
    assert grading.expected(said, setup) == "failure"
    again, _ = falsehood.prepare(lesson, seed=seed)
    assert again.content == said.content  # deterministic per seed


@pytest.mark.parametrize("word", [w for w in relations.words() if not relations.of_word(w).stacked])
def test_a_false_spatial_sentence_names_the_asked_word_over_another_layout(word: str) -> None:
    lesson = _one({**SPATIAL, "signal": "verify", "is_positive": "False",
                   "description": {**SPATIAL["description"], "relation": word}})
    sentences = set()
    for seed in range(3):
        said, setup = falsehood.prepare(lesson, seed=seed)
        a, b = (setup.world.get(i) for i in setup.ids)
        assert said.content == f"{a.colour} {a.shape} {word} {b.colour} {b.shape}"
        assert relations.of_word(said.relation).word != word  # laid out in another word's relation
        assert not relations.holds(word, a, b)
        assert grading.content_true(said.content, setup.world.objects()) is False
        assert falsehood.prepare(lesson, seed=seed)[0] == said
        sentences.add(said.relation)
    assert sentences  # a layout was found every time


def test_a_false_sentence_that_cannot_be_made_says_why() -> None:
    lesson = _one({**SPATIAL, "signal": "verify", "is_positive": "False"})
    everything = [(c, s) for c in catalog.COLOURS for s in catalog.SHAPES]
    setup = trainer.layout(_one({"lesson-type": "visual-word", "signal": "verify", "content": "red box",
                                 "description": {"color": "red", "shape": "box"}}), seed=0)
    for i, (c, s) in enumerate(everything):
        setup.world.add(s, c, 0.05 + 0.045 * (i % 20), 0.05 + 0.9 * (i // 20), size="small")
    with pytest.raises(UserError, match="every colour-shape pair is on the table"):
        falsehood.absent_pair(setup, np.random.default_rng(0))
    assert lesson.say_false


# ------------------------------------------------------------------ the whole script


def _needs_stacking_or_push(lesson: dict) -> bool:
    desc = lesson.get("description") or {}
    return desc.get("relation") == "on" or desc.get("action") == "push" or "on" in (desc.get("relations") or [])


def test_the_full_script_uses_every_item_of_point_8() -> None:
    raw = json.loads(FULL.read_text())
    c = loads(FULL.read_text(), str(FULL))
    assert {x["lesson-type"] for x in raw} == {"visual-word", "spatial-word", "action-word", "composite-word"}
    assert {x.signal for x in c} == {"inform", "verify", "react", "generate"}
    assert any(x.concept for x in c if x.signal == "generate")
    assert any("size" in (x.get("description") or {}) for x in raw)
    used = {(x.get("description") or {}).get("relation") for x in raw}
    used |= {r for x in raw for r in (x.get("description") or {}).get("relations", [])}
    assert {"left-of", "right-of", "front-of", "behind", "near", "distant", "next-to", "on", "larger-than",
            "left-of-ec", "right-of-ec", "front-of-ec", "behind-ec", "behind1", "behind2", "behind3",
            "behind-disjunctive"} <= used
    assert any(x.action == ActionSpec("push") and x.demonstration == [Step("push", 0)] for x in c)
    assert any(x.action == ActionSpec("push") and x.signal == "react" for x in c)
    undefined = [o for x in raw for o in (x.get("description") or {}).get("objects", [])
                 if isinstance(o, str) and o not in x["description"]]
    assert undefined
    spellings = {x["is_positive"] if isinstance(x["is_positive"], bool) else x["is_positive"]
                 for x in raw if "is_positive" in x}
    assert {"TRUE", "True", "true", "False", "false", False} <= spellings
    falsified = {x.kind for x in c if x.say_false}
    assert falsified == {"visual", "spatial"}
    # issue 22: placeholders the trainer names, a comparative on a crowded table, a react on "near"
    assert {x.signal for x in c if x.name_objects} >= {"inform", "verify", "react"}
    assert any(x.relation in ("larger than", "smaller than") and x.distractors >= 30 for x in c)
    assert any(x.signal == "react" and x.action is not None and x.action.relation == "near" for x in c)
    # the capsule (the original's visual-word-generation branch): taught, then tested
    capsules = [x.signal for x in c if any(o.shape == "capsule" for o in x.objects)]
    assert "inform" in capsules and "verify" in capsules[capsules.index("inform"):]


def _run(capsys, path: Path, perception: str = "truth") -> list[dict]:
    rc = main(["run", str(path), "--json", "--perception", perception])
    records = [json.loads(line) for line in capsys.readouterr().out.splitlines() if line.strip()]
    assert rc in (0, 1)
    return records


def _check_run(raw: list[dict], records: list[dict]) -> None:
    assert len(records) == len(raw)
    for lesson, rec in zip(raw, records):
        where = (rec["index"], rec["content"], rec["result"], rec["reason"])
        if lesson["signal"] == "verify":
            # graded as the original graded it: is_positive true -> success, false -> failure
            positive = str(lesson.get("is_positive", "True")).lower() == "true"
            if "is_positive" in lesson:
                assert rec["expected"] == ("success" if positive else "failure"), where
            assert rec["correct"] is True, where  # taught before tested: the agent is right
        elif lesson["signal"] == "react":
            assert rec["goal_holds"] is True, where
        elif lesson["signal"] == "generate":
            assert rec["said"] and rec["correct"] is True, where
        if lesson["lesson-type"] == "visual-word" and lesson.get("is_positive") == "False" and "content" not in lesson:
            # the trainer's false sentence, not the description (a spatial one names the asked
            # relation over another layout: test_a_false_spatial_sentence_...)
            assert rec["content"] != loads(json.dumps([lesson]), "x.json")[0].content, where


def test_the_full_script_runs_and_is_graded_as_the_original(capsys, tmp_path: Path) -> None:
    raw = json.loads(FULL.read_text())
    if not WORLD_STACKS_AND_PUSHES:
        raw = [x for x in raw if not _needs_stacking_or_push(x)]
    path = tmp_path / "original-full.json"
    path.write_text(json.dumps(raw, indent=2))
    records = _run(capsys, path)
    _check_run(raw, records)
    assert sum(1 for x in raw if x["signal"] == "verify") >= 15


@pytest.mark.skipif(not WORLD_STACKS_AND_PUSHES, reason="the world cannot stack or push yet (issue 10 points 4, 5)")
def test_the_whole_full_script_runs_as_shipped(capsys) -> None:
    _check_run(json.loads(FULL.read_text()), _run(capsys, FULL))


@pytest.mark.skipif(not WORLD_STACKS_AND_PUSHES, reason="the world cannot stack or push yet (issue 10 points 4, 5)")
@pytest.mark.parametrize("seed", [3, 12])
def test_the_whole_full_script_runs_right_at_other_seeds(capsys, seed: int) -> None:
    """At these seeds "move red box near blue cone" failed: the goal kept the fine sector
    that "near"'s examples happened to lie in (a word with no direction of its own once the
    direction words are known), and that sector had no room on the table."""
    rc = main(["run", str(FULL), "--json", "--perception", "truth", "--seed", str(seed)])
    records = [json.loads(line) for line in capsys.readouterr().out.splitlines() if line.strip()]
    assert rc in (0, 1)
    _check_run(json.loads(FULL.read_text()), records)


def _names_a_shape_the_detector_does_not_know(lesson: dict) -> bool:
    """A lesson about a shape the shipped detector was not trained on (the capsule joined the
    catalog after it; docs/perception.md): its camera cannot tell that shape, so the lesson
    runs with ground-truth vision only, until a retrained detector ships."""
    from aileen.perception.detector import load_detector

    known = set(load_detector().classes)
    desc = lesson.get("description") or {}
    objs = [o for o in desc.get("objects", []) if isinstance(o, dict)]
    objs += [v for k, v in desc.items() if k.startswith("<") and isinstance(v, dict)]
    if "shape" in desc:
        objs.append(desc)
    return any(o.get("shape") not in (None, *known) for o in objs)


@pytest.mark.skipif(not WORLD_STACKS_AND_PUSHES, reason="the world cannot stack or push yet (issue 10 points 4, 5)")
def test_the_whole_full_script_runs_right_with_the_detector(capsys, tmp_path: Path) -> None:
    raw = [x for x in json.loads(FULL.read_text()) if not _names_a_shape_the_detector_does_not_know(x)]
    path = FULL
    if len(raw) < len(json.loads(FULL.read_text())):
        path = tmp_path / "original-full.json"
        path.write_text(json.dumps(raw, indent=2))
    records = _run(capsys, path, "detector")
    _check_run(raw, records)
    assert not any("skipped" in r for r in records)
    named = [r for r, x in zip(records, loads(path.read_text(), str(path))) if x.name_objects]
    assert named and all("object" not in r["content"].split() for r in named)
    crowded = [r for r in records if any("distractors: with all" in n for n in r.get("layout_notes", []))]
    assert crowded and all(r["correct"] is True for r in crowded)


@pytest.mark.skipif(not WORLD_STACKS_AND_PUSHES, reason="the world cannot stack or push yet (issue 10 points 4, 5)")
def test_a_shape_the_detector_misreads_does_not_spoil_the_lessons_after_it(capsys) -> None:
    """The whole script with the detector, capsule lessons included: the shipped detector
    reads a capsule as a small sphere, so "capsule" is pinned to `cv_small` (sphere claims
    the shape). That one word once made head nouns name sizes, and "cone", shown once large,
    then refused every medium cone for the rest of the run (21 of 23 verify, 2 of 4 react).
    Every lesson that does not name the shape the detector cannot see is right."""
    raw = json.loads(FULL.read_text())
    records = _run(capsys, FULL, "detector")
    assert len(records) == len(raw)
    unseen = [_names_a_shape_the_detector_does_not_know(x) for x in raw]
    if not any(unseen):
        pytest.skip("the detector knows every shape of the script")
    seen = [(x, r) for x, r, u in zip(raw, records, unseen) if not u]
    _check_run([x for x, _ in seen], [r for _, r in seen])


# ------------------------------------------------------------------ the sentence held to its description (probe 48)


RED_BOX = ObjectSpec("box", "red")


@pytest.mark.parametrize("description", [None, {"shape": "box"}, {"color": None, "shape": "box"}, {"objects": [{}]}])
def test_the_sentence_fills_what_the_description_leaves_open(description: dict | None) -> None:
    """bad/omitted_colour.json, bad/nullcolour.json: "red box" over a box of a random colour
    (at seed 0 a green cylinder for "red cone") was stored as "red"."""
    lesson = {"lesson-type": "visual-word", "content": "red box", "signal": "inform"}
    if description is not None:
        lesson["description"] = description
    read = _one(lesson)
    assert read.objects == [RED_BOX] and read.content == "red box" and not read.name_objects
    for seed in range(3):
        (obj,) = trainer.layout(read, seed=seed).world.objects()
        assert (obj.appearance["colour"], obj.shape) == ("red", "box")


def test_open_spatial_objects_are_filled_in_the_sentences_order_or_from_the_other_side() -> None:
    open_two = {"lesson-type": "spatial-word", "signal": "inform", "description": {"relation": "left-of"}}
    assert _one({**open_two, "content": "red box left of blue cone"}).objects == [RED_BOX, ObjectSpec("cone", "blue")]
    # said from the other side: the blue cone is right of the red box, which stands left of it
    other = _one({**open_two, "content": "blue cone right of red box"})
    assert other.objects == [RED_BOX, ObjectSpec("cone", "blue")] and other.relation == "left of"


def test_a_word_of_the_teachers_own_contradicts_nothing() -> None:
    for content in ("rox", "wug box", "red kone", "red box nleft of blue cone"):
        lesson = _one({"lesson-type": "visual-word", "content": content, "signal": "inform",
                       "description": {"color": "red", "shape": "box"}})
        assert lesson.objects == [RED_BOX] and lesson.content == content


@pytest.mark.parametrize("lesson, said", [
    ({"lesson-type": "visual-word", "content": "blue box", "signal": "inform",
      "description": {"color": "red", "shape": "box"}}, "'blue' where the description's object 1 has colour 'red'"),
    ({"lesson-type": "visual-word", "content": "red cone", "signal": "inform",
      "description": {"color": "red", "shape": "box"}}, "'cone' where the description's object 1 has shape 'box'"),
    ({**SPATIAL, "content": "red box right of blue box"},
     "'right of' where the description's relation is 'left of'"),
    ({"lesson-type": "spatial-word", "signal": "inform", "content": "red box left of blue cone",
      "description": {"objects": [{"color": "red", "shape": "box"}, {"color": "blue", "shape": "cone"}],
                      "relation": "right-of"}}, "'left of' where the description's relation is 'right of'"),
    ({"lesson-type": "action-word", "signal": "inform", "content": "move red box left of blue cone",
      "description": {"objects": ["<obj1>", "<obj2>"], "relations": ["right-of"], "action": "move",
                      "<obj1>": {"color": "red", "shape": "box"}, "<obj2>": {"color": "blue", "shape": "cone"}}},
     "'left of' where the description's action is 'right of'"),
    ({"lesson-type": "action-word", "signal": "react", "content": "move green box left of blue cone",
      "description": {"objects": ["<obj1>", "<obj2>"], "relations": ["left-of"], "action": "move",
                      "<obj1>": {"color": "red", "shape": "box"}, "<obj2>": {"color": "blue", "shape": "cone"}}},
     "'green' where the description's object 1 has colour 'red'"),
])
def test_a_sentence_that_contradicts_its_description_is_refused_in_one_line(lesson: dict, said: str) -> None:
    """bad/content_vs_rel.json: "left of" was taught from a right-of table."""
    err = _located(lesson, '"content"')
    assert said in err.message and "\n" not in err.format(), err.format()


def test_a_verify_may_contradict_its_description_as_a_false_exam() -> None:
    exam = _one({"lesson-type": "visual-word", "content": "blue box", "signal": "verify",
                 "description": {"color": "red", "shape": "box"}})
    assert exam.objects == [RED_BOX] and grading.expected(exam, trainer.layout(exam, seed=0)) == "failure"
    # a negative exam over an open description is not made true by the sentence
    negative = _one({"lesson-type": "visual-word", "content": "red box", "signal": "verify", "is_positive": "False",
                     "description": {"shape": "box"}})
    assert negative.objects == [ObjectSpec("box")]


MOVE_LEFT = {"objects": ["<obj1>", "<obj2>"], "relations": ["left-of"], "action": "move",
             "<obj1>": {"color": "red", "shape": "box"}, "<obj2>": {"color": "blue", "shape": "cone"}}
PICK = {"name": "pick-up", "argument": "<obj1>"}


def _placed(relation: str) -> dict:
    return {"name": "place", "argument1": "<obj1>", "argument2": "<obj2>", "relation": relation}


@pytest.mark.parametrize("trace, shown", [
    ([{"name": "point", "argument": "<obj1>"}], "point(1)"),
    ([PICK, _placed("right-of")], "place(1) [right of 2]"),
    ([PICK, _placed("left-of"), PICK], "pick_up(1)"),
])
def test_a_trace_that_does_not_reach_the_goal_is_skipped_with_its_reason(trace: list, shown: str) -> None:
    """trace_point.json, trace_rightof.json: "move ... left of" taught from a point, or a right-of place."""
    lesson = _one({"lesson-type": "action-word", "signal": "inform", "content": "move red box left of blue cone",
                   "description": {**MOVE_LEFT, "trace-actions": trace}})
    assert lesson.skip is not None and "do not show 'move left of'" in lesson.skip and shown in lesson.skip


def test_a_verify_whose_trace_misses_the_goal_is_an_exam_not_skipped() -> None:
    """A verify's demonstration is an action exam: one that does not show the move is graded
    "no" (it was skipped as "nothing to learn the word from", and its exam lost)."""
    lesson = _one({"lesson-type": "action-word", "signal": "verify", "content": "move red box left of blue cone",
                   "is_positive": "False", "description": {**MOVE_LEFT, "trace-actions": [PICK, _placed("right-of")]}})
    assert lesson.skip is None and lesson.expect == "failure"


@pytest.mark.parametrize("relation", ["left-of", "left-of-ec"])
def test_a_trace_that_reaches_the_goal_is_taught(relation: str) -> None:
    lesson = _one({"lesson-type": "action-word", "signal": "inform", "content": "move red box left of blue cone",
                   "description": {**MOVE_LEFT, "trace-actions": [PICK, _placed(relation)]}})
    assert lesson.skip is None


def test_a_run_skips_a_trace_that_does_not_show_its_move(tmp_path: Path, capsys) -> None:
    script = [{"lesson-type": "action-word", "signal": "inform", "content": "move red box left of blue cone",
               "description": {**MOVE_LEFT, "trace-actions": [PICK, _placed("right-of")]}}]
    path = tmp_path / "trace.json"
    path.write_text(json.dumps(script))
    rc = main(["run", str(path), "--json", "--perception", "truth"])
    out, err = capsys.readouterr()
    (record,) = [json.loads(line) for line in out.splitlines() if line.strip()]
    assert rc == 1 and record["result"] == "skipped" and "do not show 'move left of'" in record["skipped"]
    assert not record["commands"]  # nothing learned from it
    assert "1 skipped (the file's demonstration shows nothing to learn)" in err and "(empty)" not in err


def test_webots_fields_are_ignored_at_the_lesson_and_in_a_visual_description() -> None:
    """bad/webots_fields.json, bad/webots_in_desc.json: the docs say these are ignored."""
    lesson = _one({"lesson-type": "visual-word", "content": "red box", "signal": "verify", "rgb": [1, 0, 0],
                   "language": "en", "position": [0, 0, 0], "initial_configuration": [],
                   "description": {"color": "red", "shape": "box", "rgb": [1, 0, 0], "language": "en"}})
    assert lesson.objects == [RED_BOX]


@pytest.mark.parametrize("written, count", [("2.0", 2), ("1e2", 100), ("196", 196)])
def test_distractors_are_a_whole_number_however_json_writes_it(written: str, count: int) -> None:
    """bad/distr_bigint.json was accepted while 1e9 was refused: JSON has one kind of number."""
    text = ('[{"lesson-type": "visual-word", "content": "red box", "signal": "inform", '
            '"description": {"color": "red", "shape": "box"}, "distractors": ' + written + "}]")
    assert loads(text, "s.json")[0].distractors == count
    for bad, shown in (("1.5", "1.5"), ("-1", "-1"), ("true", "true"), ('"two"', '"two"'), ("1e400", "Infinity")):
        with pytest.raises(UserError, match="'distractors' must be a whole number") as refused:
            loads(text.replace(written, bad), "s.json")
        assert refused.value.message.endswith(f"found {shown}")  # what it got, said


@pytest.mark.parametrize("signal", ["inform", "react"])
def test_is_positive_false_on_an_inform_or_react_is_refused_naming_its_line(signal: str) -> None:
    lesson = {"lesson-type": "action-word", "signal": signal, "content": "move red box left of blue cone",
              "description": MOVE_LEFT, "is_positive": "False"}
    err = _located(lesson, '"is_positive"')
    assert f"'is_positive' false on a{'n' if signal == 'inform' else ''} {signal} lesson" in err.message
    # true is what an inform says anyway (the original's lesson generator writes it)
    assert _one({**lesson, "is_positive": "True"}).expect == "success"


def test_a_false_spatial_lesson_the_world_cannot_lay_out_is_skipped_with_its_reason(capsys, tmp_path: Path) -> None:
    """A negative spatial verify over two red boxes stopped the run (exit 2) with a false reason,
    "every other relation would make the sentence true"; its positive version is skipped for
    what it is, two objects the sentence cannot tell apart (probe 51, v/neg-same.json)."""
    lesson = {"signal": "verify", "lesson-type": "spatial-word", "is_positive": "False",
              "description": {"objects": [{"color": "red", "shape": "box"}, {"color": "red", "shape": "box"}],
                              "relation": "left-of"}}
    with pytest.raises(trainer.LayoutError, match="the sentence cannot tell them apart") as err:
        falsehood.prepare(_one(lesson), seed=0)
    assert "every other relation" not in err.value.reason
    script = tmp_path / "neg-same.json"
    script.write_text(json.dumps([lesson]))
    assert main(["run", str(script), "--perception", "truth", "--json"]) == 1
    [record] = [json.loads(line) for line in capsys.readouterr().out.splitlines() if line.strip()]
    assert "cannot tell them apart" in json.dumps(record)


def test_an_ungraded_verify_names_the_key_of_the_scripts_own_format(capsys, tmp_path: Path) -> None:
    """A verify of a word the script taught was left ungraded with "give the lesson's `expect`",
    a key an original script refuses: its key is `is_positive` (probe 51)."""
    kone = {"lesson-type": "visual-word", "content": "kone", "description": {"color": "green", "shape": "cone"}}
    script = tmp_path / "own.json"
    script.write_text(json.dumps([{**kone, "signal": "inform"}, {**kone, "signal": "verify"}]))
    main(["run", str(script), "--perception", "truth"])
    out = capsys.readouterr().out
    assert "give the lesson's `is_positive`)" in out and "1 verify not graded (no `is_positive`)" in out
    assert "`expect`" not in out


@pytest.mark.parametrize("written", ["197", "1e3", "100000000000000000000"])
def test_more_distractors_than_the_table_could_hold_are_refused_in_one_line(written: str, tmp_path: Path) -> None:
    """`"distractors": 100000000000000000000` was accepted and printed back (probe 51,
    v/bigdistr.json): the table holds 196 of the smallest objects side by side."""
    text = ('[{"lesson-type": "visual-word", "content": "red box", "signal": "inform",\n'
            ' "description": {"color": "red", "shape": "box"},\n "distractors": ' + written + "}]")
    with pytest.raises(UserError, match="'distractors' must be at most 196") as refused:
        loads(text, "s.json")
    assert refused.value.line == 3 and "\n" not in refused.value.format()
    toml = tmp_path / "s.toml"
    toml.write_text('[[lesson]]\nsignal = "inform"\ncontent = "red box"\nobjects = ["red box"]\ndistractors = 197\n')
    with pytest.raises(UserError, match="distractors must be at most 196.*found 197") as refused:
        load_curriculum(toml)
    assert refused.value.line == 5


@pytest.mark.parametrize("key, value, shown", [("content", 5, "found 5"), ("content", "", 'found ""'),
                                               ("comment", ["a"], 'found ["a"]'), ("concept", 0, "found 0")])
def test_a_text_field_of_the_wrong_kind_says_what_was_found(key: str, value: object, shown: str) -> None:
    """`'content' must be a non-empty string` did not say what the file held (v/content-int.json:
    `"content": 5`)."""
    lesson = {"signal": "inform", "lesson-type": "visual-word", "content": "red box",
              "description": {"color": "red", "shape": "box"}, key: value}
    with pytest.raises(UserError, match=f"'{key}' must be") as refused:
        _one(lesson)
    assert refused.value.message.endswith(shown)
