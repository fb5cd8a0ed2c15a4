"""`aileen run` and `aileen teach` through the CLI entry point."""

from __future__ import annotations

import io
import json
from pathlib import Path

import pytest

from aileen.cli import main

ROOT = Path(__file__).resolve().parents[1]
LESSONS = ROOT / "lessons"


def run_json(capsys, *args: str) -> tuple[int, list[dict]]:
    rc = main(["run", *args, "--json", "--perception", "truth"])
    out = capsys.readouterr().out
    return rc, [json.loads(line) for line in out.splitlines() if line.strip()]


def test_demo_curriculum_ends_with_a_successful_react(capsys) -> None:
    rc, lessons = run_json(capsys, str(LESSONS / "demo.toml"))
    assert rc == 0
    for rec in lessons:
        assert {"signal", "content", "result", "reason", "commands"} <= rec.keys()
    last = lessons[-1]
    assert last["signal"] == "react"
    assert last["result"] == "success"
    assert last["goal_holds"] is True
    assert sum(r["commands"] for r in lessons) > 0


def test_json_records_name_their_file_and_note(capsys) -> None:
    """With several files, `index` starts again at 1 in each: a record names its file, and
    carries the lesson's note (where an angle or a case is written down)."""
    rc, lessons = run_json(capsys, str(LESSONS / "visual.toml"), str(LESSONS / "grain.toml"))
    files = [r["file"] for r in lessons]
    assert files[0].endswith("visual.toml") and files[-1].endswith("grain.toml")
    assert [r["index"] for r in lessons if r["file"] == files[-1]][0] == 1
    assert next(r for r in lessons if r["file"] == files[-1])["note"] == "38 degrees"


def test_memory_is_saved_and_reused(tmp_path, capsys) -> None:
    mem = tmp_path / "memory.json"
    rc, first = run_json(capsys, str(LESSONS / "demo.toml"), "--memory", str(mem))
    assert rc == 0 and mem.exists()
    rc, second = run_json(capsys, str(LESSONS / "demo.toml"), "--memory", str(mem))
    assert rc == 0
    assert not any(r["created"] for r in second)  # every word was already known
    # what is stored again is only evidence of a relation word's direction (an example that
    # still changes where its region holds: memory/extent.py), never a visual word
    stored = {c for r in second for c in r["stored"]}
    assert stored <= {"r_left_of"}, stored


def test_invalid_lesson_file_names_file_and_line_and_keeps_memory(tmp_path, capsys) -> None:
    mem = tmp_path / "memory.json"
    assert main(["run", str(LESSONS / "demo.toml"), "--memory", str(mem), "--perception", "truth"]) == 0
    before = mem.read_bytes()
    bad = tmp_path / "bad.toml"
    bad.write_text('[[lesson]]\nsignal = "inform"\ncontent = "red box"\nobjects = ["red box"]\n\n'
                   '[[lesson]]\nsignal = "inform"\ncontent = "teal box"\nobjects = ["teal box"]\n')
    capsys.readouterr()
    rc = main(["run", str(LESSONS / "demo.toml"), str(bad), "--memory", str(mem), "--perception", "truth"])
    err = capsys.readouterr().err
    assert rc == 2
    assert f"{bad}:9:" in err and "teal" in err
    assert len(err.strip().splitlines()) == 1
    assert mem.read_bytes() == before


def test_corrupt_memory_file_is_an_error_and_left_alone(tmp_path, capsys) -> None:
    mem = tmp_path / "memory.json"
    mem.write_text('{"format": "aileen-concept-memory", "version": 1, "concepts": [')
    before = mem.read_bytes()
    rc = main(["run", str(LESSONS / "demo.toml"), "--memory", str(mem), "--perception", "truth"])
    assert rc == 2
    assert str(mem) in capsys.readouterr().err
    assert mem.read_bytes() == before


def test_original_format_json_script_runs(capsys) -> None:
    rc, lessons = run_json(capsys, str(LESSONS / "original-format.json"))
    assert {r["signal"] for r in lessons} == {"inform", "verify", "react"}
    wrong = [(r["index"], r["content"], r["reason"]) for r in lessons if r["correct"] is False]
    assert rc == 0 and not wrong, wrong
    assert lessons[-1]["signal"] == "react" and lessons[-1]["goal_holds"] is True


def test_missing_file_is_a_user_error(capsys) -> None:
    assert main(["run", "no/such/file.toml"]) == 2
    assert "no such lesson file" in capsys.readouterr().err


def test_teach_reads_a_script_from_stdin(monkeypatch, capsys) -> None:
    script = "\n".join([
        "scene red box", "inform red box",
        "scene blue cone", "inform blue cone",
        "scene red box with 2 distractors", "verify red box",
        "show",
    ]) + "\n"
    monkeypatch.setattr("sys.stdin", io.StringIO(script))
    rc = main(["teach", "--perception", "truth", "--seed", "4"])
    out = capsys.readouterr().out
    assert rc == 0
    assert "created r_red" in out
    assert 'verify  "red box"\n' in out
    verify_block = out.split('verify  "red box"', 1)[1]
    assert "answer:   success" in verify_block.splitlines()[2]
    assert "knows: " in out and "red (visual)" in out


def test_teach_script_error_names_the_line(monkeypatch, capsys) -> None:
    monkeypatch.setattr("sys.stdin", io.StringIO("scene red box\nfrobnicate\n"))
    rc = main(["teach", "--perception", "truth"])
    assert rc == 2
    assert "<stdin>:2: unknown command 'frobnicate'" in capsys.readouterr().err


# Each shipped curriculum with what its header says to teach first.
CURRICULA = [
    ["demo.toml"],
    ["visual.toml"],
    ["visual.toml", "spatial.toml"],
    ["visual.toml", "action.toml"],
    ["task-demonstration.toml"],
    ["sizes.toml"],
    ["relations.toml"],
    ["generation.toml"],
    ["composites.toml"],
    ["push.toml"],
    ["stacking.toml"],
    ["visual.toml", "grain.toml"],
    ["visual.toml", "new-words.toml"],
]


@pytest.mark.parametrize("files", CURRICULA, ids=lambda fs: "+".join(fs))
def test_every_shipped_curriculum_runs_correctly(files: list[str], capsys) -> None:
    rc, lessons = run_json(capsys, *(str(LESSONS / f) for f in files))
    wrong = [(r["index"], r["content"], r["result"], r["reason"]) for r in lessons if r["correct"] is False]
    assert rc == 0 and not wrong, wrong


def test_the_curricula_above_cover_every_shipped_lesson_file() -> None:
    covered = {f for fs in CURRICULA for f in fs}
    assert covered == {p.name for p in LESSONS.glob("*.toml")}


def test_a_shape_the_detector_was_not_trained_on_is_noted(tmp_path, capsys) -> None:
    from aileen.perception.detector import load_detector
    from aileen.world.catalog import SHAPES

    lacking = [s for s in SHAPES if s not in load_detector().classes]
    if not lacking:
        pytest.skip("the shipped detector knows every catalog shape")
    shape = lacking[0]
    f = tmp_path / "odd.toml"
    f.write_text(f'[[lesson]]\nsignal = "inform"\ncontent = "red {shape}"\n'
                 f'objects = [{{ shape = "{shape}", colour = "red" }}]\n'
                 '[[lesson]]\nsignal = "inform"\ncontent = "blue box"\n'
                 'objects = [{ shape = "box", colour = "blue" }]\n')
    main(["run", str(f)])
    err = capsys.readouterr().err
    assert f"odd.toml: lesson 1 put a {shape} on the table, a shape the detector" in err
    assert "lesson 2" not in err
    main(["run", str(f), "--perception", "truth"])
    assert "not trained on" not in capsys.readouterr().err


def test_teach_notes_a_shape_the_detector_was_not_trained_on(monkeypatch, capsys) -> None:
    from aileen.perception.detector import load_detector
    from aileen.world.catalog import SHAPES

    lacking = [s for s in SHAPES if s not in load_detector().classes]
    if not lacking:
        pytest.skip("the shipped detector knows every catalog shape")
    script = f"place red {lacking[0]} at 0.3 0.5\nplace blue box\n"
    monkeypatch.setattr("sys.stdin", io.StringIO(script))
    assert main(["teach"]) == 0
    out = capsys.readouterr().out
    assert out.count(f"note: the detector was not trained on the {lacking[0]}") == 1  # once, when put down
    monkeypatch.setattr("sys.stdin", io.StringIO(script))
    assert main(["teach", "--perception", "truth"]) == 0
    assert "not trained on" not in capsys.readouterr().out


def test_a_verify_whose_is_positive_contradicts_its_own_table_is_not_graded(capsys, tmp_path: Path) -> None:
    """The probe's ispos_contra.json: "red box" over a red box with is_positive False, and
    "blue box" over a red box with is_positive True, graded the right answers WRONG."""
    script = tmp_path / "contra.json"
    script.write_text(json.dumps([
        {"lesson-type": "visual-word", "content": "red box", "description": {"color": "red", "shape": "box"},
         "signal": "verify", "is_positive": "False"},
        {"lesson-type": "visual-word", "content": "blue box", "description": {"color": "red", "shape": "box"},
         "signal": "verify", "is_positive": "True"},
        {"lesson-type": "visual-word", "content": "blue box", "description": {"color": "red", "shape": "box"},
         "signal": "verify", "is_positive": "False"}]))
    rc, records = run_json(capsys, str(script), "--memory", str(tmp_path / "m.json"))
    assert rc in (0, 1)
    assert [r["correct"] for r in records[:2]] == [None, None]
    assert records[0]["ungraded"] == "the file says the answer is failure, its own lesson says success"
    assert records[1]["ungraded"] == "the file says the answer is success, its own lesson says failure"
    # a file that agrees with itself is graded (wrong here: the empty memory knows no "blue")
    assert "ungraded" not in records[2] and records[2]["correct"] is False


def test_an_untaught_words_no_is_not_graded_right(tmp_path: Path, capsys) -> None:
    """"I do not know the word 'zorp of'" says nothing of the table: a verify the trainer
    expects false is not answered right by it (it was graded right, and the run exited 0)."""
    lesson = tmp_path / "unk.toml"
    lesson.write_text('''seed = 1
[[lesson]]
signal = "inform"
content = "red box"
objects = [{ shape = "box", colour = "red" }]

[[lesson]]
signal = "verify"
content = "red box zorp of red box"
objects = [{ shape = "box", colour = "red", position = [0.3, 0.5] }, { shape = "box", colour = "red", position = [0.6, 0.5] }]
expect = "failure"

[[lesson]]
signal = "verify"
content = "red box"
objects = [{ shape = "cone", colour = "blue" }]
''')
    rc, lessons = run_json(capsys, str(lesson))
    unknown, known = lessons[1], lessons[2]
    assert unknown["result"] == "failure" and "zorp" in unknown["reason"]
    assert unknown["correct"] is False and rc == 1
    # a known word's "no" is still an answer, and right
    assert (known["result"], known["expected"], known["correct"]) == ("failure", "failure", True)


class _Closed(io.StringIO):
    """An output nobody reads any more (`aileen run ... | head -3`, after head ended)."""

    def write(self, text: str) -> int:
        raise BrokenPipeError(32, "Broken pipe")


def test_a_run_into_a_closed_output_says_where_the_memory_went(tmp_path, capsys, monkeypatch) -> None:
    """`aileen run ... | head -3` exited 141 saying nothing of the memory, as a signal's line does."""
    memory = tmp_path / "m.json"
    monkeypatch.setattr("sys.stdout", _Closed())
    assert main(["run", str(LESSONS / "demo.toml"), "--perception", "truth", "--memory", str(memory)]) == 141
    err = capsys.readouterr().err
    assert err.startswith("aileen: stopped: the output was closed"), err
    assert err.rstrip().endswith(f"; what was learned is saved in {memory}"), err
    assert memory.is_file()


def test_rules_of_ones_own_with_no_answer_set_stop_the_run_and_keep_what_was_learned(tmp_path: Path, capsys) -> None:
    """A comprehension.lp with no answer set in a scene made every lesson the agent's
    "failure" and exit 1; the run stops at the first such call, exit 2, the memory saved."""
    from aileen.reasoning import asp

    rules = tmp_path / "rules"
    rules.mkdir()
    (rules / "comprehension.lp").write_text(asp.rule_path("comprehension.lp").read_text() + "\n:- obj(o3).\n")
    lessons = tmp_path / "l.toml"
    lessons.write_text("seed = 3\n" + "".join(
        f'[[lesson]]\nsignal = "inform"\ncontent = "{c}"\nobjects = {o}\n'
        for c, o in [("red box", '["red box"]'), ("red box", '["red box", "blue cone", "green cylinder"]'),
                     ("blue cone", '["blue cone"]')]))
    memory = tmp_path / "m.json"
    code = main(["run", str(lessons), "--rules", str(rules), "--perception", "truth", "--memory", str(memory)])
    captured = capsys.readouterr()
    err = captured.err.strip().splitlines()[-1]
    assert code == 2, captured.err
    assert f"{rules}: the comprehension program has no answer set" in err and "(lesson 2: inform 'red box')" in err
    assert err.endswith(f"what was learned is saved in {memory}") and memory.is_file()
    assert "lesson  3" not in captured.out


@pytest.mark.parametrize("command", ["run", "teach"])
def test_missing_shipped_rules_stop_before_the_first_lesson(command, tmp_path, monkeypatch, capsys) -> None:
    """A broken install (no asp/ rule files) was each lesson's "failure: no ASP rules found",
    graded, and the memory saved; now one line and exit 2 before any lesson, no file written."""
    from aileen.domain import predicates

    monkeypatch.delenv("AILEEN_RULES", raising=False)
    monkeypatch.setattr(predicates, "shipped_rules", lambda: None)
    monkeypatch.setattr("sys.stdin", io.StringIO("scene red box\ninform red box\n"))
    mem = tmp_path / "memory.json"
    files = [str(LESSONS / "demo.toml")] if command == "run" else []
    rc = main([command, *files, "--memory", str(mem), "--perception", "truth"])
    out, err = capsys.readouterr()
    assert rc == 2
    assert "lesson" not in out and "created" not in out
    assert len(err.strip().splitlines()) == 1 and "no ASP rules found" in err
    assert not mem.exists()
