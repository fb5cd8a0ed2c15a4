"""The clingo boundary: rule lookup, Term <-> Symbol, messages with file:line:col."""

from __future__ import annotations

import os
from pathlib import Path

import clingo
import pytest
from hypothesis import given
from hypothesis import strategies as st

from aileen.errors import UserError
from aileen.reasoning import asp
from aileen.terms import Term, fn, parse, parse_many

SHIPPED = ("comprehension.lp", "actions.lp", "planning.lp")


def test_rules_dir_holds_the_shipped_files():
    d = asp.rules_dir()
    for name in SHIPPED:
        assert (d / name).is_file()


def test_rules_dir_env_override(tmp_path, monkeypatch):
    (tmp_path / "comprehension.lp").write_text("x.\n")
    monkeypatch.setenv("AILEEN_RULES", str(tmp_path))
    assert asp.rules_dir() == tmp_path
    assert asp.rule_path("comprehension.lp") == tmp_path / "comprehension.lp"
    monkeypatch.setenv("AILEEN_RULES", str(tmp_path / "missing"))
    with pytest.raises(UserError, match="AILEEN_RULES"):
        asp.rules_dir()


def test_user_directory_overrides_file_by_file(tmp_path):
    (tmp_path / "actions.lp").write_text("% mine\n")
    paths = asp.rule_paths(["actions.lp", "planning.lp"], tmp_path)
    assert paths[0] == tmp_path / "actions.lp"
    assert paths[1] == asp.rules_dir() / "planning.lp"


def test_missing_rules_directory_and_file(tmp_path):
    with pytest.raises(UserError, match="not a directory"):
        asp.rule_path("actions.lp", tmp_path / "nope")
    with pytest.raises(UserError, match="nothing.lp"):
        asp.rule_path("nothing.lp", tmp_path)


_name = st.from_regex(r"[a-z][a-z0-9_]{0,6}", fullmatch=True).filter(lambda s: s != "not")
_terms = st.recursive(
    st.one_of(_name.map(Term), st.integers(-1000, 1000).map(Term),
              st.from_regex(r'[a-z "\\]{0,5}', fullmatch=True).map(lambda s: Term('"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'))),
    lambda inner: st.builds(lambda n, args: Term(n, tuple(args)), _name, st.lists(inner, min_size=1, max_size=3)),
    max_leaves=8,
)


@given(_terms)
def test_symbol_round_trip(t):
    s = asp.to_symbol(t)
    assert asp.from_symbol(s) is t
    # the same text on both sides (strings aside, whose escapes clingo prints its own way)
    if '"' not in str(t):
        assert str(s) == str(t)


def test_conversions_are_cached_and_typed():
    t = parse("h(t0,w(o1,o2))")
    assert asp.to_symbol(t) is asp.to_symbol(t)
    s = clingo.Function("isa", [clingo.Function("o1"), clingo.Number(3)])
    assert asp.from_symbol(s) is fn("isa", "o1", 3)
    with pytest.raises(ValueError):
        asp.from_symbol(clingo.Function("a", [], False))
    with pytest.raises(ValueError):
        asp.from_symbol(clingo.Infimum)


def _write(tmp_path: Path, name: str, text: str) -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


def test_syntax_error_names_file_line_col(tmp_path):
    p = _write(tmp_path, "comprehension.lp", "a.\n" * 11 + "    foo(X :- bar.\n")
    with pytest.raises(asp.AspError) as err:
        asp.new_control([p])
    msg = str(err.value)
    assert msg.startswith(f"{p}:12:11: error: syntax error, unexpected :-")
    assert "\n" not in msg


def test_grounding_error_names_file_line_col(tmp_path):
    p = _write(tmp_path, "x.lp", "p(X) :- not q(X).\n")
    with pytest.raises(asp.AspError) as err:
        asp.solve_once([p], [])
    assert str(err.value).startswith(f"{p}:1:1: error: unsafe variables in:")
    assert "'X' is unsafe" in str(err.value)


def test_solve_once_returns_shown_terms(tmp_path):
    p = _write(tmp_path, "x.lp", "b(X) :- a(X). #show b/1.\n")
    assert set(asp.solve_once([p], parse_many("a(1). a(f(x))."))) == set(parse_many("b(1). b(f(x))."))
    q = _write(tmp_path, "y.lp", ":- a(1).\n")
    assert asp.solve_once([q], parse_many("a(1).")) is None


def test_optimisation_returns_the_optimum(tmp_path):
    p = _write(tmp_path, "o.lp", "1 { c(1..5) } 1. #minimize { X : c(X) }. #show c/1.\n")
    assert asp.solve_once([p], []) == [parse("c(1)")]


def test_check_rule_files_grounds_shipped_rules_cleanly():
    groups = [asp.rule_paths(["comprehension.lp"]), asp.rule_paths(["actions.lp", "planning.lp"])]
    assert asp.check_rule_files(groups) == []


def test_check_rule_files_reports_warnings(tmp_path):
    p = _write(tmp_path, "w.lp", "a :- b.\n")
    warnings = asp.check_rule_files([[p]])
    assert any(w.startswith(f"{p}:1:6: info: atom does not occur in any rule head") for w in warnings)


def test_strings_keep_unicode_quotes_and_newlines():
    t = Term('"caf\u00e9 \\"q\\" a\\\\b\\nc"')
    s = asp.to_symbol(t)
    assert s.string == 'caf\u00e9 "q" a\\b\nc'
    assert asp.from_symbol(s) is t


def test_benchmark_script_runs(capsys, monkeypatch):
    """benchmarks/asp.py stays runnable (its figures are printed, never asserted)."""
    import runpy
    import sys

    script = Path(__file__).resolve().parent.parent / "benchmarks" / "asp.py"
    monkeypatch.setattr(sys, "argv", [str(script), "--repeat", "2", "--objects", "6"])
    runpy.run_path(str(script), run_name="__main__")
    out = capsys.readouterr().out
    assert "comprehend" in out and "pick_up(o1), place(o1,goal)" in out


def test_solve_once_remembers_answers_by_rules_version_and_facts(tmp_path, monkeypatch):
    p = _write(tmp_path, "x.lp", "b(X) :- a(X). #show b/1.\n")
    calls = []
    real = asp.new_control
    monkeypatch.setattr(asp, "new_control", lambda *a, **k: calls.append(1) or real(*a, **k))
    first = asp.solve_once([p], parse_many("a(1)."))
    again = asp.solve_once([p], parse_many("a(1)."))
    assert first == again == [parse("b(1)")] and len(calls) == 1  # clingo asked once
    again.append(parse("junk"))  # a caller's list is its own
    assert asp.solve_once([p], parse_many("a(1).")) == [parse("b(1)")]
    assert asp.solve_once([p], parse_many("a(2).")) == [parse("b(2)")] and len(calls) == 2  # other facts
    # the rule file written again (other rules, same size): read again
    p.write_text("c(X) :- a(X). #show c/1.\n")
    os.utime(p, ns=(p.stat().st_atime_ns, p.stat().st_mtime_ns + 1_000_000))
    assert asp.solve_once([p], parse_many("a(1).")) == [parse("c(1)")] and len(calls) == 3
    q = _write(tmp_path, "y.lp", ":- a(1).\n")
    assert asp.solve_once([q], parse_many("a(1).")) is None
    assert asp.solve_once([q], parse_many("a(1).")) is None and len(calls) == 4  # unsatisfiable, remembered


def test_solve_once_does_not_remember_errors(tmp_path):
    p = _write(tmp_path, "x.lp", "p(X) :- not q(X).\n")
    for _ in range(2):
        with pytest.raises(asp.AspError, match="unsafe variables"):
            asp.solve_once([p], [])


@pytest.mark.parametrize("edit", [
    ("comprehension.lp", "#show referent/2.", "show referent/2"),
    ("planning.lp", "#show occurs/2.", "show occurs/2"),
    ("comprehension.lp", None, "derive referent/2"),  # an empty file
])
def test_rules_that_no_longer_give_what_the_agent_reads_are_refused(tmp_path, capsys, monkeypatch, edit) -> None:
    """These edits passed `aileen asp check` and then answered wrongly without a word
    (`#show referent/2.` deleted: every object "-"; `#show occurs/2.` deleted: "the goal
    already holds"; an empty comprehension.lp learned nothing). With `AILEEN_RULES` the run
    did not check the rules at all."""
    import shutil

    from aileen.cli import main

    name, line, words = edit
    rules = tmp_path / "rules"
    shutil.copytree(asp.rules_dir(), rules)
    path = rules / name
    path.write_text("" if line is None else path.read_text().replace(line, ""))
    assert main(["asp", "check", "--rules", str(rules)]) == 2
    assert f"{path}:1: error: the rules must {words}" in capsys.readouterr().err
    memory = tmp_path / "m.json"
    lessons = Path(__file__).resolve().parents[1] / "lessons" / "demo.toml"
    monkeypatch.setenv("AILEEN_RULES", str(rules))
    assert main(["run", str(lessons), "--perception", "truth", "--memory", str(memory)]) == 2
    assert words in capsys.readouterr().err and not memory.exists()


def test_planning_past_the_solve_limit_stops_the_run(tmp_path, capsys) -> None:
    """A planning rule that cannot be solved in time (a pigeonhole in actions.lp) was the react
    lesson's answer ("failure: solving took longer ...", exit 1); the rules are at fault, not
    the agent: the run stops with exit 2, as for comprehension, and keeps what was learned."""
    import shutil

    from aileen.cli import main

    rules = tmp_path / "rules"
    rules.mkdir()
    shutil.copy(asp.rules_dir() / "actions.lp", rules / "actions.lp")
    with (rules / "actions.lp").open("a") as fh:
        fh.write("\n#program base.\npigeon(1..13). hole(1..12).\n1 { in(P, H) : hole(H) } 1 :- pigeon(P).\n"
                 ":- in(P, H), in(Q, H), P < Q.\n")
    memory = tmp_path / "m.json"
    lessons = Path(__file__).resolve().parents[1] / "lessons" / "demo.toml"
    assert main(["run", str(lessons), "--perception", "truth", "--rules", str(rules), "--rules-timeout", "2",
                 "--memory", str(memory)]) == 2
    err = capsys.readouterr().err
    assert "solving took longer than 2 s" in err and "(lesson 14: react 'move the red cylinder right of the blue box')" in err, err
    assert "r_red" in memory.read_text()


def test_a_rule_file_aileen_never_loads_is_named_and_a_folder_in_its_place_refused(tmp_path, capsys) -> None:
    """`comprehention.lp` (misspelt) was checked "ok" and never loaded; a folder or a broken
    link named comprehension.lp fell back to the shipped file without a word."""
    import shutil

    from aileen.cli import main

    rules = tmp_path / "rules"
    rules.mkdir()
    shutil.copy(asp.rules_dir() / "comprehension.lp", rules / "comprehention.lp")
    assert main(["asp", "check", "--rules", str(rules)]) == 0
    said = capsys.readouterr().out
    assert "comprehention.lp: aileen loads" in said and "did you mean comprehension.lp?" in said
    (rules / "comprehension.lp").mkdir()
    assert main(["asp", "check", "--rules", str(rules)]) == 2
    assert "comprehension.lp: not a readable file" in capsys.readouterr().err
    (rules / "comprehension.lp").rmdir()
    (rules / "comprehension.lp").symlink_to(tmp_path / "nowhere.lp")
    assert main(["asp", "check", "--rules", str(rules)]) == 2
    assert "comprehension.lp: not a readable file" in capsys.readouterr().err


def test_a_variable_in_a_facts_file_is_named_at_its_line(tmp_path, capsys) -> None:
    """`isa(o1,Red).` on line 4 was reported by clingo as `<block>:3:1: ... unsafe`."""
    from aileen.cli import main

    facts = tmp_path / "f.lp"
    facts.write_text("% a comment\n\nword_concept(red,r_red).\n isa(o1,Red).\n")
    assert main(["asp", "comprehend", "red", "--facts", str(facts)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and f"{facts}:4:" in err and "holds the variable Red" in err


def test_a_limit_passed_on_the_shipped_rules_advises_the_limit_not_the_rules() -> None:
    """With the shipped rules a run past --rules-timeout (a busy machine) said "a rule that
    never ends ...; fix the rules": there were no rules of the user's own to fix."""
    from aileen.reasoning import watchdog

    shipped, own = watchdog._advice(watchdog.SHIPPED, "--rules-timeout"), watchdog._advice("my-rules", "--rules-timeout")
    assert "busy machine" in shipped and "fix the rules" not in shipped and "--rules-timeout" in shipped
    assert "fix the rules" in own
