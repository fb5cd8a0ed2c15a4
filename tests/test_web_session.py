"""The console's session without a web framework: table edits, lessons, the replayable transcript."""

from __future__ import annotations

import json
import tomllib

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


def _replayed(s: Session, tmp_path, capsys) -> list[dict]:
    path = tmp_path / "session.toml"
    path.write_text(s.lesson_file())
    main(["run", str(path), "--json", "--memory", str(tmp_path / "replay.json")])
    return [json.loads(line) for line in capsys.readouterr().out.splitlines() if line.strip()]


def test_a_wrong_where_the_trainer_graded_the_answer_right_replays_as_given(tmp_path, capsys) -> None:
    """The person at the console said `wrong` to an answer the trainer's grading found right
    (their "right of" is not the trainer's): the console learned from it, the downloaded
    file's replay took the verdict as the trainer's and let the answer stand, and answered
    the next question otherwise. A verdict's record was numbered like the lesson after it."""
    s = Session(Agent(), seed=3)
    teach_red_box_left_of_blue_cone(s)
    s.edit("layout", content="red box left of blue cone")
    first = s.lesson("verify", "red box right of blue cone")
    # the trainer expects the "no" the agent gave (graded wrong all the same: the agent knows no
    # "right of" yet, and an untaught word's "no" is no answer)
    assert first["result"] == first["expected"] == "failure" and first["correct"] is False
    verdict = s.lesson("wrong", "")
    assert verdict["stored"] and verdict["index"] == first["index"]
    again = s.lesson("verify", "red box right of blue cone")
    assert again["result"] == "success"  # the person's word, learned from their verdict
    lessons = [r for r in s.records if r["signal"] != "wrong"]
    assert [r["index"] for r in lessons] == list(range(1, len(lessons) + 1))
    replay = _replayed(s, tmp_path, capsys)
    keys = ("signal", "content", "result")
    assert [{k: r[k] for k in keys} for r in replay] == [{k: r[k] for k in keys} for r in lessons]
    # a run puts the verdict's stores on the lesson it judges
    stores = [r["stored"] + [x for v in s.records if v["signal"] == "wrong" and v["index"] == r["index"]
                             for x in v["stored"]] for r in lessons]
    assert [r["stored"] for r in replay] == stores


def test_right_lets_a_no_stand_and_replays_as_given(tmp_path, capsys) -> None:
    """The console's `right`: a "no" to a relation it knows becomes a near miss of it; the file
    replays it (`feedback = "wrong"` with the answer as `expect`)."""
    s = Session(Agent(), seed=3)
    teach_red_box_left_of_blue_cone(s)
    s.edit("clear")
    s.edit("add", object="red box", at=[0.5, 0.75])
    s.edit("add", object="blue cone", at=[0.5, 0.5])
    asked = s.lesson("verify", "red box left of blue cone")
    assert asked["result"] == "failure"
    kept = s.lesson("right", "")
    assert kept["stored"] == ["r_left_of"] and kept["index"] == asked["index"]
    replay = _replayed(s, tmp_path, capsys)
    assert replay[-1]["stored"] == ["r_left_of"] and replay[-1]["result"] == "failure"


def test_no_to_the_agents_question_is_one_lesson_of_the_file_and_replays_the_same(tmp_path, capsys) -> None:
    """`no` wrote the asked lesson a second time: the replay read "bx" as said in two lessons,
    took it as meant from the first copy on and learned there what the console had not."""
    s = Session(Agent(), seed=3)
    s.edit("add", object="red box")
    s.lesson("inform", "red box")
    s.edit("clear")
    s.edit("add", object="blue box")
    asked = s.lesson("inform", "blue bx")
    assert asked["asked_about"] == "bx" and not asked["created"]
    told = s.lesson("no", "")
    assert set(told["created"]) == {"r_blue", "r_bx"} and told["index"] == asked["index"]
    s.lesson("verify", "blue bx")
    assert s.lesson_file().count('content = "blue bx"') == 2  # the asked lesson once, the verify
    replay = _replayed(s, tmp_path, capsys)
    keys = ("signal", "content", "result", "created")
    assert [{k: r[k] for k in keys} for r in replay] == [{k: r[k] for k in keys} for r in s.records if r is not asked]


def test_describe_does_not_demonstrate_the_sentence_sent_with_it() -> None:
    """The page sent the text box with every signal: `describe` then demonstrated the box's
    "move the red box right of the blue cone" (the box moved, a `generate` lesson with a
    demonstration went into the file, and a second describe was refused)."""
    s = Session(Agent(), seed=3)
    s.edit("layout", content="move red box right of blue cone")
    table = list(s.table.objects)
    for _ in range(2):
        r = s.lesson("describe", "move the red box right of the blue cone")
        assert r["signal"] == "generate" and r["content"] == ""
    assert s.table.objects == table and "demonstration" not in s.lesson_file()


# ---------------------------------------------------------------------------- describe, graded as a person would

def test_describing_three_objects_is_graded_and_true() -> None:
    """The agent lists three or more objects as "A and B and C"; that is graded, and true here."""
    s = Session(Agent(), seed=2)
    for obj, at in [("red box", [0.3, 0.3]), ("blue cone", [0.6, 0.6]), ("green sphere", [0.2, 0.8])]:
        s.edit("clear")
        s.edit("add", object=obj, at=at)
        s.lesson("inform", obj)
    s.edit("clear")
    for obj, at in [("red box", [0.3, 0.3]), ("blue cone", [0.6, 0.6]), ("green sphere", [0.2, 0.8])]:
        s.edit("add", object=obj, at=at)
    r = s.lesson("describe", "")
    assert r["said"].count(" and ") == 2 and r["correct"] is True, r


def _world(*objs):
    from aileen.world.camera import Table
    from aileen.world.sim import World

    w = World(Table(), seed=0)
    for shape, colour, x in objs:
        w.add(shape, colour, x, 0.5)
    return w.objects()


@pytest.mark.parametrize("said,truth", [
    ("red box and blue cone and green sphere", True),
    ("red box and something and green sphere", True),
    ("red box and blue cone and purple sphere", False),
    ("red box and red box", False),  # one red box cannot be two of the things said
    ("red box and blue cone left of green sphere", True),
    ("red box and blue cone right of green sphere", False),
    ("red box and glorp", None),  # a word the trainer does not know: not graded, never false
    ("red box and", None),
    ("glorp", None),
])
def test_the_trainer_grades_conjunctions_and_leaves_what_it_cannot_read_ungraded(said, truth) -> None:
    from aileen.curriculum import grading

    objects = _world(("box", "red", 0.2), ("cone", "blue", 0.45), ("sphere", "green", 0.75))
    assert grading.content_true(said, objects) is truth


# ---------------------------------------------------------------------------- undo, forget, plain errors

def test_undo_takes_the_memory_table_and_transcript_back_to_before_the_lesson(tmp_path, capsys) -> None:
    s = Session(Agent(), seed=4)
    s.edit("add", object="red box", at=[0.3, 0.5])
    s.lesson("inform", "red box")
    s.edit("add", object="blue cone", relation="right of", of="red box")
    memory = json.loads(json.dumps(s.agent.memory.to_dict()))  # a copy: to_dict shares the annotations
    table, blocks, records = list(s.table.objects), list(s.blocks), list(s.records)
    s.lesson("inform", "move the red box behind the blue cone")  # demonstrated: the table moves
    s.lesson("verify", "red box")
    assert s.table.objects != table and s.agent.memory.to_dict() != memory
    s.undo_lesson()
    s.undo_lesson()
    assert s.agent.memory.to_dict() == memory
    assert (s.table.objects, s.blocks, s.records) == (table, blocks, records)
    # lessons after an undo go on as if the undone ones were never given: the file replays the same
    s.lesson("inform", "blue cone")
    s.lesson("verify", "red box right of blue cone")
    path = tmp_path / "session.toml"
    path.write_text(s.lesson_file())
    assert main(["run", str(path), "--json"]) == 1  # "right of" untaught: its "no" is graded wrong
    replay = [json.loads(line) for line in capsys.readouterr().out.splitlines() if line.strip()]
    keys = ("signal", "content", "result", "referents", "created", "stored", "correct")
    assert [{k: r[k] for k in keys} for r in replay] == [{k: r[k] for k in keys} for r in s.records]


def test_undo_of_a_verdict_and_of_a_forget() -> None:
    s = Session(Agent(), seed=3)
    s.edit("add", object="red box", at=[0.3, 0.5])
    s.lesson("inform", "red box")
    s.edit("clear")
    s.edit("add", object="red cone", at=[0.6, 0.5])
    s.lesson("verify", "red cone")
    before = json.loads(json.dumps(s.agent.memory.to_dict()))
    s.lesson("wrong", "")
    assert "r_cone" in s.agent.memory
    assert s.undo_lesson()["undone"]["signal"] == "wrong"
    assert s.agent.memory.to_dict() == before and not s.blocks[-1].rstrip().endswith('feedback = "wrong"')
    s.lesson("wrong", "")  # the verdict can be given again: the agent is back at its verify answer
    assert "r_cone" in s.agent.memory

    words = s.agent.semantic.words()
    f = s.forget("cone")
    assert f == {"forgot": "r_cone", "word": "cone", "concepts": len(s.agent.memory)}
    assert "r_cone" not in s.agent.memory and s.agent.semantic.concept("cone") is None
    assert "cone" not in s.agent.memory.to_dict().get("annotations", {}).get("lexicon", {}).get("positions", {})
    r = s.lesson("verify", "red cone")
    assert "I do not know the word 'cone'" in r["reason"]
    s.undo_lesson()  # the verify
    s.undo_lesson()  # the forget
    assert s.agent.semantic.words() == words and "r_cone" in s.agent.memory
    with pytest.raises(UserError, match="no concept 'purple'"):
        s.forget("purple")


def test_undo_reaches_back_a_bounded_number_of_steps() -> None:
    from aileen.web.history import UNDO_LESSONS

    s = Session(Agent(perceiver=None), seed=1)
    s.edit("add", object="red box", at=[0.3, 0.5])
    for _ in range(UNDO_LESSONS + 2):
        s.lesson("verify", "red box")
    for _ in range(UNDO_LESSONS):
        s.undo_lesson()
    assert len(s.records) == 2
    with pytest.raises(UserError, match="no lesson to undo"):
        s.undo_lesson()


def test_lesson_errors_are_plain_words_without_lesson_file_places() -> None:
    s = Session(Agent(), seed=1)
    with pytest.raises(UserError, match="the table is empty"):
        s.lesson("describe", "")
    s.edit("add", object="red box", at=[0.1, 0.1])
    s.edit("add", object="blue cone", at=[0.26, 0.1])
    for signal, content, says in [
            ("inform", "move the red box on the blue cone", "cannot place the medium red box on the medium blue cone"),
            ("inform", "move the red box left of the blue cone", "already there"),
            ("react", "red box", "react needs something to do")]:
        with pytest.raises(UserError) as err:
            s.lesson(signal, content)
        text = err.value.format()
        assert says in text and "<console>" not in text and "lesson 1" not in text and "obj1" not in text, text
    assert s.records == [] and s.blocks == []
    # a sentence the agent cannot read is its answer, not an error: never "no", nothing learned
    record = s.lesson("inform", "red box left of")
    assert record["understood"] is False and record["result"] == "not understood"
    assert "I could not read 'red box left of'" in record["reason"] and record["commands"] == 0
    assert record["correct"] is None


# ---------------------------------------------------------------------------- kept beside the memory file

def _taught(tmp_path) -> Session:
    s = Session(Agent(), seed=6, memory_path=str(tmp_path / "m.json"))
    s.edit("add", object="red box", at=[0.3, 0.5])
    s.lesson("inform", "red box")
    s.edit("add", object="blue cone", at=[0.7, 0.4])
    s.lesson("verify", "red box")
    return s


def _reopened(tmp_path) -> Session:
    from aileen.memory.concept import ConceptMemory
    from aileen.memory.semantic import from_concepts

    mem = ConceptMemory.load(tmp_path / "m.json")
    return Session(Agent(mem, from_concepts(mem)), seed=6, memory_path=str(tmp_path / "m.json"))


def test_the_table_and_transcript_are_restored_after_a_restart(tmp_path) -> None:
    s = _taught(tmp_path)
    s.save()
    assert (tmp_path / "m.console.json").is_file()
    t = _reopened(tmp_path)
    assert "restored the table (2 objects) and 2 lessons" in t.resume()
    assert (t.table.objects, t.blocks, t.records) == (s.table.objects, s.blocks, s.records)
    assert t.version > s.version  # a page open before the restart reloads before it edits
    assert t.lesson_file() == s.lesson_file()
    assert t.lesson("verify", "red box")["index"] == 3


def test_a_memory_changed_by_another_run_sets_the_old_table_aside(tmp_path) -> None:
    s = _taught(tmp_path)
    s.save()
    s.lesson("inform", "blue cone")
    s.agent.save(str(tmp_path / "m.json"))  # the memory saved without the console's state: another program
    t = _reopened(tmp_path)
    line = t.resume()
    assert line.startswith("warning:") and "m.console.old.json" in line
    assert (tmp_path / "m.console.old.json").is_file() and not (tmp_path / "m.console.json").exists()
    assert t.table.objects == [] and t.blocks == []
    assert Session(Agent(), seed=0).resume() is None  # without --memory there is nothing to restore


@pytest.mark.parametrize("edit", [
    lambda d: "not json",
    lambda d: {**d, "format": "other"},
    lambda d: {**d, "blocks": ["[[lesson]]\nsignal = 3\n"]},
    lambda d: {**d, "table": [{"shape": "box", "colour": "red", "size": "huge", "x": 0.5, "y": 0.5,
                               "distractor": False}]},
    lambda d: {**d, "records": []},
    lambda d: {**d, "scene_version": -1},
])
def test_a_malformed_console_state_is_one_error_naming_the_file(tmp_path, edit) -> None:
    s = _taught(tmp_path)
    s.save()
    p = tmp_path / "m.console.json"
    bad = edit(json.loads(p.read_text()))
    p.write_text(bad if isinstance(bad, str) else json.dumps(bad))
    with pytest.raises(UserError) as err:
        _reopened(tmp_path).resume()
    assert str(p) in err.value.format() and "\n" not in err.value.format()


@settings(max_examples=60, deadline=None)
@given(st.data())
def test_mutated_console_states_read_or_fail_cleanly(tmp_path_factory, data) -> None:
    from aileen.web import state

    folder = tmp_path_factory.mktemp("state")
    blocks = [transcript.lesson_block("inform", "red box", [], seed=1, demonstrate=False)]
    doc = {"format": state.FORMAT, "version": state.VERSION, "scene_version": 3, "memory_sha256": None,
           "table": [{"shape": "box", "colour": "red", "size": "medium", "x": 0.5, "y": 0.5, "distractor": False}],
           "blocks": blocks, "records": [{"signal": "inform"}]}
    key = data.draw(st.sampled_from(sorted(doc)))
    value = data.draw(st.recursive(st.one_of(st.none(), st.booleans(), st.integers(), st.floats(), st.text(max_size=20)),
                                   lambda x: st.one_of(st.lists(x, max_size=3), st.dictionaries(st.text(max_size=5), x,
                                                                                                max_size=3)),
                                   max_leaves=8))
    p = folder / "m.console.json"
    p.write_text(json.dumps({**doc, key: value}))
    try:
        state.read(p)
    except UserError as exc:
        assert str(p) in exc.format()


def test_names_from_before_the_split_still_import_from_session() -> None:
    """`session` was split into modules of one job each; what callers imported from it still works."""
    from aileen.web import edits, history, session, view

    assert session.arrows is view.arrows and session._seen_at is view.seen_at and session._marks is view.marks_of
    assert session.View is view.View and session._Step is history.Step
    assert session.UNDO_LESSONS == history.UNDO_LESSONS and session.EDITS is edits.EDITS
    assert session._text is edits.text and session._opt_text is edits.opt_text and session._number is edits.number
    s = Session(Agent(perceiver=None), seed=1)
    assert session._xy(s, {"at": [0.1, 0.2]}) == (0.1, 0.2)


def test_a_console_state_with_a_key_it_does_not_know_is_refused(tmp_path) -> None:
    # it was read, and the next save dropped the key without a word (a memory file refuses them)
    from aileen.web import state

    p = tmp_path / "m.console.json"
    state.write(p, state.Saved(2, [], [], [], None))
    doc = json.loads(p.read_text())
    assert sorted(doc) == sorted(state.KEYS)  # what is written is what is read
    p.write_text(json.dumps({**doc, "notes": "mine"}))
    with pytest.raises(UserError, match="unknown key 'notes'; expected format, version"):
        state.read(p)


def test_right_where_the_trainer_cannot_grade_writes_the_persons_answer_as_expected(tmp_path, capsys) -> None:
    """`right` on a "no" to a word of the person's own, which the trainer cannot grade: the
    file says what the person expects, and its replay lets the answer stand as the console
    did (the near miss stored again)."""
    s = Session(Agent(), seed=3)
    teach_red_box_left_of_blue_cone(s)
    s.edit("clear")
    s.edit("add", object="red box", at=[0.3, 0.5])
    s.edit("add", object="blue cone", at=[0.6, 0.5])
    assert s.lesson("inform", "red box zorp blue cone")["created"] == ["r_zorp"]
    s.edit("clear")
    s.edit("add", object="red box", at=[0.5, 0.8])
    s.edit("add", object="blue cone", at=[0.5, 0.5])
    asked = s.lesson("verify", "red box zorp blue cone")
    assert asked["result"] == "failure" and asked["expected"] is None
    assert s.lesson("right", "")["stored"] == ["r_zorp"]
    assert s.lesson_file().rstrip().endswith('feedback = "wrong"\nexpect = "failure"')
    replay = _replayed(s, tmp_path, capsys)
    assert replay[-1]["result"] == "failure" and replay[-1]["stored"] == ["r_zorp"] and replay[-1]["correct"] is True


def test_memory_files_of_one_stem_keep_a_state_file_each(tmp_path) -> None:
    # `--memory x.json` and `--memory x.amem` shared x.console.json: one session's table and
    # transcript were lost (set aside as "saved with another version")
    from aileen.memory.concept import ConceptMemory
    from aileen.memory.semantic import from_concepts
    from aileen.web import state

    names = ["x.json", "x.amem", "x"]
    assert len({state.path_for(tmp_path / n) for n in names}) == 3
    assert state.path_for(tmp_path / "m.json") == tmp_path / "m.console.json"  # as before
    for n, thing in zip(names, ["red box", "blue cone", "green sphere"]):
        s = Session(Agent(), seed=1, memory_path=str(tmp_path / n))
        s.edit("add", object=thing, at=[0.5, 0.5])
        s.lesson("inform", thing)
        s.save()
    for n, thing in zip(names, ["red box", "blue cone", "green sphere"]):
        mem = ConceptMemory.load(tmp_path / n)
        t = Session(Agent(mem, from_concepts(mem)), seed=1, memory_path=str(tmp_path / n))
        assert t.resume().startswith("restored") and [r["content"] for r in t.records] == [thing]


def test_a_state_file_under_the_old_shared_name_is_read_when_it_goes_with_the_memory(tmp_path) -> None:
    from aileen.web import state

    s = Session(Agent(), seed=1, memory_path=str(tmp_path / "x.amem"))
    s.edit("add", object="red box", at=[0.5, 0.5])
    s.lesson("inform", "red box")
    s.save()
    legacy = tmp_path / "x.console.json"
    state.path_for(tmp_path / "x.amem").rename(legacy)  # as a console before this one wrote it
    t = Session(Agent(), seed=1, memory_path=str(tmp_path / "x.amem"))
    assert t.resume().startswith("restored") and t.blocks == s.blocks
    assert not legacy.exists() and state.path_for(tmp_path / "x.amem").is_file()
    # the old name is left alone when it holds another memory file's state (x.json's)
    other = tmp_path / "other"
    other.mkdir()
    j = Session(Agent(), seed=1, memory_path=str(other / "x.json"))
    j.edit("add", object="red box", at=[0.5, 0.5])
    j.save()
    kept = (other / "x.console.json").read_text()
    j.agent.save(str(other / "x.amem"))
    u = Session(Agent(), seed=1, memory_path=str(other / "x.amem"))
    assert u.resume() is None and (other / "x.console.json").read_text() == kept


def test_each_state_set_aside_is_kept(tmp_path) -> None:
    # a second set-aside overwrote m.console.old.json: the first transcript was lost
    firsts = []
    for thing in ("red box", "blue cone", "green sphere"):
        s = Session(Agent(), seed=1, memory_path=str(tmp_path / "m.json"))
        s.resume()
        s.edit("add", object=thing, at=[0.5, 0.5])
        s.lesson("inform", thing)
        s.save()
        with open(tmp_path / "m.json", "a") as fh:  # another program changes the memory file
            fh.write(" ")
        firsts.append(thing)
    t = Session(Agent(), seed=1, memory_path=str(tmp_path / "m.json"))
    assert t.resume() is not None
    aside = sorted(tmp_path.glob("m.console.old*.json"))
    assert [p.name for p in aside] == ["m.console.old.2.json", "m.console.old.3.json", "m.console.old.json"]
    held = " ".join(p.read_text() for p in aside)
    assert all(thing in held for thing in firsts)


@pytest.mark.parametrize("table, says", [
    ([{"shape": "box", "colour": "red", "size": "medium", "x": 5.0, "y": -3.0, "distractor": False}],
     "table object 0 at (5.0, -3.0) is off the table"),
    ([{"shape": "box", "colour": "red", "size": "medium", "x": 0.5, "y": 0.5, "distractor": False}] * 2,
     "overlap"),
    ([{"shape": "box", "colour": "red", "size": "medium", "x": 0.5, "y": 0.5, "distractor": False}] * 40,
     "40 objects; the console's table holds at most 12"),
])
def test_a_console_state_whose_table_cannot_be_shown_is_refused_at_start(tmp_path, table, says) -> None:
    # it was restored, and then every GET /api/scene answered 400 (naming table object 0 objects[1])
    s = _taught(tmp_path)
    s.save()
    p = tmp_path / "m.console.json"
    p.write_text(json.dumps({**json.loads(p.read_text()), "table": table}))
    with pytest.raises(UserError) as err:
        _reopened(tmp_path).resume()
    line = err.value.format()
    assert str(p) in line and says in line and "\n" not in line and "objects[" not in line, line


def test_the_lesson_file_says_the_options_its_replay_needs(tmp_path) -> None:
    # --senses (and --rules) were not in the downloaded file, so `aileen run` on it replayed
    # other answers; the lesson format has no key for them: its description gives the command
    import argparse

    from aileen.web import commands

    parser = argparse.ArgumentParser()
    commands.register(parser.add_subparsers())
    args = parser.parse_args(["serve", "--senses", "sectors", "--rules", "my rules", "--rules-timeout", "5"])
    assert commands.replay_options(args) == ("--senses", "sectors", "--rules", "my rules")
    assert commands.replay_options(parser.parse_args(["serve"])) == ()
    s = Session(Agent(), seed=2, replay=commands.replay_options(args))
    s.edit("add", object="red box", at=[0.5, 0.5])
    s.lesson("inform", "red box")
    description = tomllib.loads(s.lesson_file())["description"]
    assert "`aileen run session.toml --senses sectors --rules 'my rules'`" in description


def test_the_lesson_file_names_a_copy_of_the_memory_the_session_started_with(tmp_path, capsys) -> None:
    # it said to replay "from the memory the session started with (m.json)", but by then m.json
    # held the taught memory: the replay answered otherwise
    import shlex
    import shutil

    from aileen.web import state

    first = Session(Agent(), seed=4, memory_path=str(tmp_path / "m.json"))
    assert first.resume() is None
    first.edit("add", object="red box", at=[0.4, 0.5])
    first.lesson("inform", "red box")
    first.save()
    (tmp_path / "m.console.json").unlink()  # a new transcript on the taught memory
    before = (tmp_path / "m.json").read_bytes()
    s = _reopened(tmp_path)
    assert s.resume() is None
    start = state.start_path_for(tmp_path / "m.json")
    assert start.read_bytes() == before
    s.edit("add", object="blue cone", at=[0.7, 0.5])
    s.lesson("inform", "blue cone")
    s.lesson("verify", "red box")
    s.save()
    assert (tmp_path / "m.json").read_bytes() != before
    description = tomllib.loads(s.lesson_file())["description"]
    assert str(start) in description and "m.json)" not in description
    command = description.split("`")[1]
    assert command == (f"cp {shlex.quote(str(start))} replay.json && aileen run session.toml "
                       "--memory replay.json")
    (tmp_path / "session.toml").write_text(s.lesson_file())
    shutil.copyfile(start, tmp_path / "replay.json")
    main(["run", str(tmp_path / "session.toml"), "--json", "--memory", str(tmp_path / "replay.json")])
    replay = [json.loads(line) for line in capsys.readouterr().out.splitlines() if line.strip()]
    assert [(r["result"], r["created"]) for r in replay] == [(r["result"], r["created"]) for r in s.records]
    # a restart that restores the transcript keeps naming the same start
    t = _reopened(tmp_path)
    assert t.resume().startswith("restored") and t.lesson_file() == s.lesson_file()
    # without --memory the session starts from an empty memory
    u = Session(Agent(), seed=4)
    u.edit("add", object="red box", at=[0.4, 0.5])
    u.lesson("inform", "red box")
    assert "from an empty memory: `aileen run session.toml`" in tomllib.loads(u.lesson_file())["description"]


def test_autosave_keeps_each_lesson_verdict_undo_and_forget_as_it_ends(tmp_path) -> None:
    """`aileen serve --autosave` (the default): a server killed where no signal can be caught
    has every finished lesson in its memory file, and the table and transcript beside it."""
    from aileen.memory.concept import ConceptMemory
    from aileen.web import state

    mem = tmp_path / "m.json"
    s = Session(Agent(), seed=3, memory_path=str(mem), autosave=True)
    s.edit("add", object="red box")
    s.lesson("inform", "red box")
    assert {c.symbol for c in ConceptMemory.load(str(mem)).concepts()} == {"r_red", "r_box"}
    saved, _ = state.recall(str(mem), s.camera.table)
    assert saved is not None and len(saved.blocks) == 1
    s.forget("red")
    assert {c.symbol for c in ConceptMemory.load(str(mem)).concepts()} == {"r_box"}
    s.undo_lesson()  # the forget taken back
    assert {c.symbol for c in ConceptMemory.load(str(mem)).concepts()} == {"r_red", "r_box"}
    # without it, nothing is written until a save
    other = tmp_path / "n.json"
    t = Session(Agent(), seed=3, memory_path=str(other))
    t.edit("add", object="red box")
    t.lesson("inform", "red box")
    assert not other.exists()


def test_a_failed_autosave_keeps_the_lesson_and_says_where_the_memory_went(tmp_path) -> None:
    from aileen.memory.store import MemoryFile

    mem = tmp_path / "m.json"
    with MemoryFile.open(mem) as held:
        s = Session(Agent(), seed=3, memory_path=str(mem), memory_file=held, autosave=True)
        mem.write_text("{}")  # another program writes the file the server holds: the save must not overwrite it
        s.edit("add", object="red box")
        record = s.lesson("inform", "red box")
    assert "r_red" in record["created"] and len(s.records) == 1
    assert "recovered" in record["autosave_error"] and mem.read_text() == "{}"


def _held_with_a_lesson(mem, held) -> Session:  # noqa: ANN001
    """A console on the held memory file `mem`, resumed, that has taught "red box"."""
    s = Session(Agent(), seed=3, memory_path=str(mem), memory_file=held)
    s.resume()
    s.edit("add", object="red box")
    s.lesson("inform", "red box")
    return s


@pytest.mark.parametrize("way", ["save", "keep"])
def test_a_save_that_went_to_the_recovery_file_keeps_the_state_beside_it_not_the_memory_file(tmp_path, way) -> None:
    """Another program wrote m.json while the console held it: the save went to m.recovered-PID.json,
    and m.console.json was stamped with the OTHER program's m.json, so the next start restored
    lessons that never taught it. The state goes beside the recovery file, stamped with it."""
    from aileen.memory.store import MemoryFile, SaveRefused
    from aileen.web import state

    mem = tmp_path / "m.json"
    with MemoryFile.open(mem) as held:
        s = _held_with_a_lesson(mem, held)
        Agent().save(str(mem))  # another program writes the file the server holds
        if way == "save":
            with pytest.raises(SaveRefused) as exc:
                s.save()
            line = exc.value.format()
        else:
            line = s.keep()
    recovered = next(tmp_path.glob("m.recovered-*[0-9].json"))
    beside = state.path_for(recovered)
    assert f"{recovered}" in line and f"the table and transcript are beside it in {beside}" in line
    assert not (tmp_path / "m.console.json").exists()
    assert state.read(beside).memory_sha256 == state.digest(recovered) and len(state.read(beside).blocks) == 1
    saved, _ = state.recall(str(mem), s.camera.table)
    assert saved is None  # m.json's next session restores no lessons that did not teach it
    saved, _ = state.recall(str(recovered), s.camera.table)
    assert saved is not None and saved.blocks == s.blocks  # serving the recovery file resumes the session


def test_the_line_on_leaving_names_the_recovery_file_and_what_became_of_the_table(tmp_path) -> None:
    """A directory put where m.json was: the line said "m.console.json: saved the memory, but not
    the table and transcript: Is a directory", never naming the recovery file with the lessons."""
    from aileen.memory.store import MemoryFile

    mem = tmp_path / "m.json"
    with MemoryFile.open(mem) as held:
        s = _held_with_a_lesson(mem, held)
        s.save()
        mem.unlink()
        mem.mkdir()
        line = s.keep()
    recovered = next(tmp_path.glob("m.recovered-*[0-9].json"))
    assert "saved the memory, but not" not in line and "Is a directory" not in line, line
    assert f"what this run learned is in {recovered}" in line, line
    assert f"the table and transcript are beside it in {recovered.with_name(recovered.stem + '.console.json')}" in line


def test_the_restore_line_counts_in_the_singular_and_is_not_said_of_nothing(tmp_path) -> None:
    """"restored the table (1 objects) and 1 lessons", and a line "restored the table (0 objects)
    and 0 lessons" when nothing was restored."""
    mem = tmp_path / "m.json"
    s = Session(Agent(), seed=3, memory_path=str(mem))
    s.edit("add", object="red box")
    s.lesson("inform", "red box")
    s.save()
    line = Session(Agent(), seed=3, memory_path=str(mem)).resume()
    assert "restored the table (1 object) and 1 lesson from" in line, line
    s.undo_lesson()
    s.edit("clear")
    s.save()
    assert s.table.objects == [] and s.blocks == []
    assert Session(Agent(), seed=3, memory_path=str(mem)).resume() is None
