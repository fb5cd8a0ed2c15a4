"""Inputs that used to end in a traceback or a clingo PANIC (issue 23): a binary facts file, a
non-ASCII name in a rule file. Each is one line naming the file (and line), exit 2."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from aileen.cli import main
from aileen.reasoning.rulefiles import _non_ascii

ROOT = Path(__file__).resolve().parents[1]
BINARY = b"\xff\xfe" + bytes(range(256)) * 3


@pytest.mark.parametrize("flag", ["--facts", "--words"])
def test_binary_facts_are_one_line_not_a_traceback(tmp_path: Path, capsys, flag: str) -> None:
    good = tmp_path / "good.lp"
    good.write_text("obj(o1). isa(o1,cv_red).\n")
    bad = tmp_path / "bin.lp"
    bad.write_bytes(b"obj(o1).\n" + BINARY)
    args = ["asp", "comprehend", "red box", "--facts", str(bad if flag == "--facts" else good)]
    if flag == "--words":
        args += ["--words", str(bad)]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err == f"aileen: {bad}:2: not UTF-8 text (byte 9); expected ASP facts such as isa(o1,cv_red).\n"


def test_a_facts_path_that_is_a_fifo_is_an_error_not_a_hang(tmp_path: Path, capsys) -> None:
    os.mkfifo(tmp_path / "f")
    assert main(["asp", "plan", "--facts", str(tmp_path / "f"), "--goal", "w(o1,o2)."]) == 2
    assert "FIFO" in capsys.readouterr().err


def _rules_with(tmp_path: Path, extra: str) -> Path:
    rules = tmp_path / "rules"
    rules.mkdir(exist_ok=True)
    (rules / "comprehension.lp").write_text((ROOT / "asp" / "comprehension.lp").read_text() + extra, encoding="utf-8")
    return rules


def _aileen(*args: str) -> subprocess.CompletedProcess:
    """In a child process: clingo's PANIC aborts the process it happens in."""
    return subprocess.run([sys.executable, "-m", "aileen", *args], capture_output=True, text=True, cwd=ROOT,
                          env={**os.environ, "PYTHONPATH": str(ROOT)}, timeout=300)


@pytest.mark.parametrize("command", ["check", "run", "comprehend"])
def test_a_non_ascii_name_in_a_rule_file_is_named_with_its_place(tmp_path: Path, command: str) -> None:
    rules = _rules_with(tmp_path, "\n% a comment may say rød\nok(\"strings may say rød\").\nrød(1).\n")
    lines = (rules / "comprehension.lp").read_text(encoding="utf-8").splitlines()
    line = next(i for i, ln in enumerate(lines, 1) if ln.startswith("rød"))
    facts = tmp_path / "f.lp"
    facts.write_text("obj(o1). isa(o1,cv_red).\n")
    args = {"check": ["asp", "check", "--rules", str(rules)],
            "run": ["run", "lessons/demo.toml", "--perception", "truth", "--rules", str(rules)],
            "comprehend": ["asp", "comprehend", "red box", "--facts", str(facts), "--rules", str(rules)]}[command]
    r = _aileen(*args)
    assert r.returncode == 2, r.stderr
    assert "PANIC" not in r.stderr and "Traceback" not in r.stderr
    assert r.stderr.strip().splitlines()[-1].startswith(f"aileen: {rules / 'comprehension.lp'}:{line}:2: error: "
                                                        "unexpected character 'ø'"), r.stderr


def test_non_ascii_in_strings_and_comments_is_fine_for_clingo_and_for_us(tmp_path: Path, capsys) -> None:
    rules = _rules_with(tmp_path, "\n% rød\n%* blå\n grøn *%\nnote(\"rød\").\n")
    assert main(["asp", "check", "--rules", str(rules)]) == 0


def test_a_rule_file_that_is_not_utf8_is_named(tmp_path: Path, capsys) -> None:
    rules = tmp_path / "rules"
    rules.mkdir()
    (rules / "comprehension.lp").write_bytes((ROOT / "asp" / "comprehension.lp").read_bytes() + b"\nx(\xff).\n")
    assert main(["asp", "check", "--rules", str(rules)]) == 2
    assert "not UTF-8 text" in capsys.readouterr().err


@pytest.mark.parametrize("text,where", [
    ('a("rød"). b.', None),
    ("a. % rød\nb(ø).", (2, 3, "ø")),
    ("a. %* ø\n*% c(ø).", (2, 6, "ø")),
    ("x.\n  yø.", (2, 4, "ø")),
    ("#script (python)\n ø = 1\n#end.\nok.", None),
    ('a("x\\"ø").', None),
    ('a("x\\\\")ø.', (1, 9, "ø")),
    ("a. % no newline at the end ø", None),
])
def test_the_scan_skips_strings_comments_and_scripts(text: str, where) -> None:  # noqa: ANN001
    assert _non_ascii(text) == where


@pytest.mark.parametrize("command, name, said", [
    ("run", "l.toml", "lesson file"), ("sweep", "g.toml", "grid file"), ("memory", "m.json", "memory file")])
def test_a_file_that_is_not_utf8_is_named_with_its_line(tmp_path: Path, capsys, command: str, name: str,
                                                        said: str) -> None:
    """It was Python's "'utf-8' codec can't decode byte 0xff in position 45" (a lesson file, a
    grid), and a memory file saved as UTF-16 "a damaged compact file" (a NUL in its first bytes)."""
    p = tmp_path / name
    p.write_bytes(b'title = "t"\n\n[[lesson]]\ncontent = "red b\xffox"\n')
    if command == "memory":
        p.write_bytes('{"format": "aileen-concept-memory"}'.encode("utf-16"))
    argv = {"run": ["run", str(p)], "sweep": ["experiment", "sweep", str(p), "--out", str(tmp_path / "o")],
            "memory": ["memory", "show", str(p)]}[command]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    line = 1 if command == "memory" else 4
    assert err.startswith(f"aileen: {p}:{line}: not UTF-8 text") and f"expected a {said} in UTF-8" in err, err
