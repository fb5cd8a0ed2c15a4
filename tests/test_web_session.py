"""The console's session without a web framework: table edits, lessons, the replayable transcript."""

from __future__ import annotations

import json

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.agent import Agent
from aileen.cli import main
from aileen.curriculum import lessonfile
from aileen.errors import UserError
from aileen.web import transcript
from aileen.web.session import Session
from aileen.web.table import TableEdit
from aileen.world.camera import Table


def teach_red_box_left_of_blue_cone(s: Session) -> list[dict]:
    """The issue's lesson: colours and shapes one object at a time, then the relation."""
    out = []
    s.edit("add", object="red box")
    out.append(s.lesson("inform", "red box"))
    s.edit("clear")
    s.edit("add", object="blue cone")
    out.append(s.lesson("inform", "blue cone"))
    s.edit("add", object="red box", relation="left of", of="blue cone")
    out.append(s.lesson("inform", "red box left of blue cone"))
    s.edit("layout", content="red box left of blue cone", distractors=1)
    out.append(s.lesson("verify", "red box left of blue cone"))
    out.append(s.lesson("verify", "blue cone left of red box"))
    return out


def test_a_taught_relation_is_verified_and_the_referents_are_the_objects_on_the_table() -> None:
    s = Session(Agent(), seed=3)
    records = teach_red_box_left_of_blue_cone(s)
    assert records[0]["created"] == ["r_red", "r_box"] or set(records[0]["created"]) == {"r_red", "r_box"}
    assert "r_left_of" in records[2]["created"]
    yes, no = records[3], records[4]
    assert (yes["result"], yes["correct"]) == ("success", True)
    assert (no["result"], no["correct"]) == ("failure", True)
    # the grounded objects are among what the agent saw, and the view highlights them
    seen = {m["id"] for m in s.scene()["seen"]}
    assert set(yes["referents"]["red box"]) <= seen
    assert s.scene()["highlight"] == sorted({i for v in no["referents"].values() for i in v})


def test_the_downloaded_lesson_file_replays_to_the_same_answers(tmp_path, capsys) -> None:
    s = Session(Agent(), seed=5)
    records = teach_red_box_left_of_blue_cone(s)
    path = tmp_path / "session.toml"
    path.write_text(s.lesson_file())
    rc = main(["run", str(path), "--json"])
    replay = [json.loads(line) for line in capsys.readouterr().out.splitlines() if line.strip()]
    assert rc == 0
    keys = ("signal", "content", "result", "reason", "referents", "created", "stored", "expected", "correct")
    assert [{k: r[k] for k in keys} for r in replay] == [{k: r[k] for k in keys} for r in records]


def test_a_demonstrated_action_moves_the_table_and_is_written_with_its_demonstration() -> None:
    s = Session(Agent(), seed=2)
    s.edit("add", object="red box")
    s.edit("add", object="blue cone", relation="right of", of="red box")
    before = [(o.x, o.y) for o in s.table.objects]
    s.lesson("inform", "move the red box behind the blue cone")
    after = [(o.x, o.y) for o in s.table.objects]
    assert after[0] != before[0] and s.table.objects[0].y > s.table.objects[1].y
    assert 'demonstration = "auto"' in s.lesson_file()
    s.edit("undo")  # the move the lesson made can be taken back like any edit
    assert [(o.x, o.y) for o in s.table.objects] == before


def test_scene_edits_refuse_what_the_table_cannot_hold() -> None:
    s = Session(Agent(), seed=1)
    s.edit("add", object="red box", at=[0.5, 0.5])
    with pytest.raises(UserError, match="too close"):
        s.edit("add", object="blue box", at=[0.52, 0.5])
    with pytest.raises(UserError, match="off the table"):
        s.edit("add", object="blue box", at=[0.99, 0.5])
    with pytest.raises(UserError, match="colour and shape"):
        s.edit("add", object="box")
    with pytest.raises(UserError, match="no object"):
        s.edit("remove", index=4)
    with pytest.raises(UserError, match="unknown scene op"):
        s.edit("explode")
    with pytest.raises(UserError, match="unexpected field"):
        s.edit("clear", colour="red")
    assert len(s.table.objects) == 1


def test_shuffle_replaces_only_distractors_and_undo_restores() -> None:
    s = Session(Agent(), seed=4)
    s.edit("add", object="red box")
    s.edit("shuffle", distractors=3)
    first = list(s.table.objects)
    assert sum(o.distractor for o in first) == 3 and first[0].describe() == "red box"
    s.edit("shuffle", distractors=1)
    assert sum(o.distractor for o in s.table.objects) == 1 and s.table.objects[0] == first[0]
    s.edit("undo")
    assert s.table.objects == first


def test_bad_lessons_are_one_line_errors_and_change_nothing() -> None:
    s = Session(Agent(), seed=1)
    s.edit("add", object="red box")
    for signal, content in [("shout", "red box"), ("inform", ""), (3, "red box"), ("inform", "red\nbox")]:
        with pytest.raises(UserError) as err:
            s.lesson(signal, content)
        assert "\n" not in err.value.format()
    with pytest.raises(UserError, match="exactly one blue cone"):
        s.lesson("inform", "move the red box left of the blue cone")
    with pytest.raises(UserError, match="verdict on the last verify lesson"):
        s.lesson("wrong", "")
    assert s.records == [] and s.blocks == []


def test_describe_says_what_the_agent_sees_in_its_words_and_replays() -> None:
    s = Session(Agent(perceiver=None), seed=2)
    s.edit("add", object="red box", at=[0.3, 0.5])
    s.lesson("inform", "red box")
    r = s.lesson("describe", "")
    assert r["signal"] == "generate" and r["said"] == "red box" and r["correct"] is True
    assert 'signal = "generate"' in s.lesson_file()


@settings(max_examples=30, deadline=None)
def _parses(content: str) -> bool:
    """Lesson files only hold sentences the agent's parser reads (checked when loading)."""
    from aileen.errors import UserError
    from aileen.reasoning import language

    try:
        language.parse(content)
    except UserError:
        return False
    return True


@given(st.lists(st.tuples(st.floats(0.06, 0.94), st.floats(0.06, 0.94)), min_size=1, max_size=5),
       st.integers(0, 2**31), st.sampled_from(["inform", "verify"]),
       st.lists(st.from_regex(r"[A-Za-z][A-Za-z0-9_-]{0,7}", fullmatch=True), min_size=1, max_size=6)
       .map(" ".join).filter(_parses))
def test_lesson_blocks_read_back_as_the_same_lesson(spots, seed, signal, content) -> None:
    t = TableEdit(Table())
    for x, y in spots:
        try:
            t.add("large green cylinder", at=(x, y))
        except UserError:
            pass
    specs = [o.spec() for o in t.objects]
    block = transcript.lesson_block(signal, content, specs, seed=seed, demonstrate=False)
    lesson = lessonfile.loads(transcript.document([block], title="t", seed=0, description="d")).lessons[0]
    assert (lesson.signal, lesson.content, lesson.seed) == (signal, content, seed)
    assert lesson.objects == specs  # positions survive to the last bit


def test_a_wrong_verdict_teaches_and_goes_into_the_lesson_file() -> None:
    s = Session(Agent(), seed=3)
    s.edit("add", object="red box", at=[0.3, 0.5])
    s.lesson("inform", "red box")
    s.edit("clear")
    s.edit("add", object="red cone", at=[0.6, 0.5])
    r = s.lesson("verify", "red cone")  # "cone" is a new word: the answer is a failure
    assert r["result"] == "failure"
    w = s.lesson("wrong", "")
    assert w["signal"] == "wrong" and "r_cone" in w["stored"]
    assert s.lesson_file().rstrip().endswith('feedback = "wrong"')
