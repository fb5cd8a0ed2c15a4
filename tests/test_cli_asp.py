"""`aileen asp ...` through the real CLI entry point: output, JSON and exit codes."""

from __future__ import annotations

import json

import pytest

from aileen.cli import main
from aileen.reasoning import asp

SCENE = """% a scene
isa(o1,cv_blue). isa(o1,cv_cone).
isa(o2,cv_red). isa(o2,cv_cylinder).
e(o1,o2). w(o2,o1). dc(o1,o2). dc(o2,o1).
word_concept(blue,cv_blue). word_concept(cone,cv_cone).
word_concept(red,cv_red). word_concept(cylinder,cv_cylinder). word_concept(left_of,e).
"""


@pytest.fixture
def scene(tmp_path):
    p = tmp_path / "scene.lp"
    p.write_text(SCENE)
    return p


def _broken_rules(tmp_path, line: int = 12, col: int = 5):
    """A copy of comprehension.lp with a syntax error starting at line:col."""
    d = tmp_path / "rules"
    d.mkdir()
    lines = asp.rule_path("comprehension.lp").read_text().splitlines()
    lines[line - 1] = " " * (col - 1) + ") oops."
    (d / "comprehension.lp").write_text("\n".join(lines) + "\n")
    return d


def test_check_ok(capsys):
    assert main(["asp", "check"]) == 0
    out = capsys.readouterr().out
    assert "comprehension.lp" in out and "planning.lp" in out


def test_syntax_error_in_a_users_rule_file_exits_2(tmp_path, capsys):
    rules = _broken_rules(tmp_path)
    assert main(["asp", "check", "--rules", str(rules)]) == 2
    err = capsys.readouterr().err.strip()
    assert "comprehension.lp:12:5: error: syntax error" in err
    assert len(err.splitlines()) == 1


def test_syntax_error_also_stops_comprehend(tmp_path, scene, capsys):
    rules = _broken_rules(tmp_path, line=3, col=1)
    assert main(["asp", "comprehend", "blue cone", "--facts", str(scene), "--rules", str(rules)]) == 2
    assert "comprehension.lp:3:1: error: syntax error" in capsys.readouterr().err


def test_check_covers_a_users_extra_files(tmp_path, capsys):
    d = tmp_path / "rules"
    d.mkdir()
    (d / "extra.lp").write_text("p(X) :- q.\n")
    assert main(["asp", "check", "--rules", str(d)]) == 2
    assert "extra.lp:1:1: error: unsafe variables" in capsys.readouterr().err


def test_comprehend_text(scene, capsys):
    assert main(["asp", "comprehend", "blue cone left of red cylinder", "--facts", str(scene)]) == 0
    out = capsys.readouterr().out
    assert "r1 'blue cone': o1" in out and "holds (o1,o2)" in out and out.strip().endswith("ok")


def test_comprehend_json_with_failures_exits_1(scene, capsys):
    assert main(["asp", "comprehend", "the green cone behind the red cylinder", "--facts", str(scene), "--json"]) == 1
    out = json.loads(capsys.readouterr().out)
    assert out["ok"] is False
    assert out["referents"] == {"r1": [], "r2": ["o2"]}
    assert sorted(out["failures"]) == [["unknown_word", "behind"], ["unknown_word", "green"]]


def test_comprehend_words_file(tmp_path, scene, capsys):
    words = tmp_path / "words.lp"
    words.write_text("word_concept(move_right_of,r_move_right_of).\n")
    assert main(["asp", "comprehend", "move the blue cone right of the red cylinder", "--facts", str(scene),
                 "--words", str(words), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["goal"] == "r_move_right_of(o1,o2)"


def test_unparseable_sentence_exits_2(scene, capsys):
    assert main(["asp", "comprehend", "left of cone", "--facts", str(scene)]) == 2
    assert "'left of' (word 1)" in capsys.readouterr().err


def test_bad_facts_file_names_line(tmp_path, capsys):
    p = tmp_path / "bad.lp"
    p.write_text("isa(o1,cv_red).\nisa(o1 cv_red).\n")
    assert main(["asp", "plan", "--facts", str(p), "--goal", "held(o1)."]) == 2
    assert f"{p}:2:8: expected ',' or ')'" in capsys.readouterr().err


def test_missing_facts_file(tmp_path, capsys):
    assert main(["asp", "plan", "--facts", str(tmp_path / "none.lp"), "--goal", "held(o1)."]) == 2
    assert "none.lp" in capsys.readouterr().err


def test_plan_text(scene, capsys):
    assert main(["asp", "plan", "--facts", str(scene), "--goal", "w(o1,o2). dc(o1,o2)."]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out == ["1. pick_up(o1)", "2. place(o1,goal) [w(o1,o2), dc(o1,o2)]"]


def test_plan_json(scene, capsys):
    assert main(["asp", "plan", "--facts", str(scene), "--goal", "w(o1,o2). dc(o1,o2).", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["depth"] == 2
    assert out["plan"][1] == {"action": "place(o1,goal)", "relations": ["w(o1,o2)", "dc(o1,o2)"]}


def test_no_plan_exits_1(scene, capsys):
    assert main(["asp", "plan", "--facts", str(scene), "--goal", "w(o1,o2).", "--max-depth", "1"]) == 1
    assert "no plan within depth 1" in capsys.readouterr().out


@pytest.mark.parametrize("goal", ["w(o1,o2). w(o2,o1).", "sz_larger(o1,o2)."])
def test_a_goal_that_can_never_hold_says_so_indented_as_a_plan(scene, capsys, goal):
    """"no plan within depth 6" as if a deeper search might help, and on one line where a plan
    is indented."""
    assert main(["asp", "plan", "--facts", str(scene), "--goal", goal, "--json"]) == 1
    text = capsys.readouterr().out
    out = json.loads(text)
    assert out["plan"] is None and out["never"] is True and "can never hold" in out["message"]
    assert text.startswith("{\n  ")


def test_a_state_holding_two_objects_exits_2_naming_the_line(tmp_path, capsys):
    facts = tmp_path / "held2.lp"
    facts.write_text("held(o1).\nheld(o2).\nobj(o3).\n")
    assert main(["asp", "plan", "--facts", str(facts), "--goal", "held(o3)."]) == 2
    err = capsys.readouterr().err
    assert f"{facts}:2: held(o2) with held(o1): the hand holds one object at most" in err and err.count("\n") == 1


def test_bad_goal_exits_2(scene, capsys):
    assert main(["asp", "plan", "--facts", str(scene), "--goal", "w(o1,"]) == 2
    assert "--goal" in capsys.readouterr().err


@pytest.mark.parametrize("goal", ["wst(o1,o2).", "foo(o1).", "w(o1).", "held(o1,o2).", "w(o1,o1)."])
def test_a_goal_no_calculus_declares_exits_2(scene, capsys, goal):
    """A misspelt relation was planned as a placement and exit 0 ("wst(o1,o2)")."""
    assert main(["asp", "plan", "--facts", str(scene), "--goal", goal]) == 2
    err = capsys.readouterr().err
    assert goal.rstrip(".") in err and ("no relation the agent perceives" in err or "to itself" in err)
    assert err.count("\n") == 1


def test_comprehend_says_undecided_where_a_word_is_unknown(scene, capsys):
    """An unknown word leaves the relation undecided (`relation_holds` null in --json), never
    "does not hold": a sentence the agent cannot ground is not false."""
    assert main(["asp", "comprehend", "blue cone near red cylinder", "--facts", str(scene)]) in (0, 1)
    out = capsys.readouterr().out
    assert "near(r1,r2): undecided" in out and "does not hold" not in out


def _doc_sessions() -> list[tuple[str, str, int | None]]:
    """The `$ aileen asp ...` commands docs/asp.md shows on its example files, each with the
    output shown under it (and the exit status where an `echo $?` follows)."""
    from pathlib import Path

    text = (Path(__file__).resolve().parents[1] / "docs" / "asp.md").read_text()
    out: list[tuple[str, str, int | None]] = []
    for block in text.split("```"):
        lines = block.splitlines()
        for i, line in enumerate(lines):
            if not line.startswith("$ aileen asp") or "docs/examples" not in line or "--rules" in line:
                continue
            shown = []
            for nxt in lines[i + 1:]:
                if nxt.startswith("$"):
                    break
                shown.append(nxt)
            after = lines[i + 1 + len(shown)] if i + 1 + len(shown) < len(lines) else ""
            status = int(lines[i + 2 + len(shown)]) if after == "$ echo $?" else None
            out.append((line[2:], "\n".join(shown), status))
    return out


@pytest.mark.parametrize("command, shown, status", _doc_sessions(), ids=lambda x: str(x)[:60])
def test_the_asp_docs_example_commands_print_what_the_docs_show(command, shown, status, capsys, monkeypatch):
    import shlex
    from pathlib import Path

    monkeypatch.chdir(Path(__file__).resolve().parents[1])
    rc = main(shlex.split(command)[1:])
    assert capsys.readouterr().out.strip() == shown.strip()
    if status is not None:
        assert rc == status


def test_the_docs_show_their_asp_examples() -> None:
    assert len(_doc_sessions()) >= 4


def _rules_with(tmp_path, name: str, rule: str):
    """A rule directory holding a copy of the shipped `name` with `rule` added at its end."""
    d = tmp_path / "rules"
    d.mkdir(exist_ok=True)
    (d / name).write_text(asp.rule_path(name).read_text() + "\n" + rule + "\n")
    return d


@pytest.mark.parametrize("name,what", [("comprehension.lp", "comprehension"), ("actions.lp", "planning")])
def test_check_solves_the_rules_on_a_sample_scene_and_names_the_file_that_leaves_no_answer(tmp_path, capsys, name,
                                                                                          what) -> None:
    """`:- obj(O).` grounds: `asp check` said "ok", and then every lesson was the agent's
    failure (comprehension) or "no plan within depth 36" (a react)."""
    rules = _rules_with(tmp_path, name, ":- obj(O).")
    assert main(["asp", "check", "--rules", str(rules)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert f"{rules / name}: the {what} program has no answer set on a sample scene" in err, err


def test_the_rules_that_lose_their_answer_only_in_some_scene_stop_the_call_with_a_rules_error(tmp_path) -> None:
    """Past the sample, a program of one's own with no answer set is the rules' error (the run
    stops), not the agent's failure nor "no plan"; with the shipped rules, "no plan" as it was."""
    from aileen.reasoning import comprehension, planner
    from aileen.reasoning.language import parse
    from aileen.terms import fn

    scene = [fn("isa", o, p) for o, p in (("o1", "cv_red"), ("o2", "cv_blue"), ("o3", "cv_green"))]
    rules = _rules_with(tmp_path, "comprehension.lp", ":- obj(o3).")
    with pytest.raises(asp.RulesUnsatisfiable, match=r"rules: the comprehension program has no answer set with "
                                                     r".*comprehension.lp, where the shipped rules always have one"):
        comprehension.comprehend(parse("red box"), words={}, facts=scene, rules=rules)
    assert comprehension.comprehend(parse("red box"), words={}, facts=scene).ok is False  # shipped: an answer
    rules = _rules_with(tmp_path, "actions.lp", "#program step(t).\n:- obj(o3).")
    with pytest.raises(asp.RulesUnsatisfiable, match=r"rules: the planning program has no answer set at depth 1, "
                                                     r"with no goal, with .*actions.lp, where the shipped"):
        planner.plan(scene, [fn("held", "o1")], max_depth=2, rules=rules)
    with pytest.raises(planner.NoPlan, match="no plan within depth 0"):
        planner.plan(scene, [fn("held", "o1")], max_depth=0)
