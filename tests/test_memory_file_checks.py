"""The memory file is checked before anything is learned (issue 23): every parameter's type
and range, unknown keys, what stands at the path (nothing, a FIFO, a device, a symbolic link
loop, a read-only file), and the lock file beside it. Each case is one line naming the file
and exit 2, the file untouched, never a hang or a traceback."""

from __future__ import annotations

import json
import os
import threading
from dataclasses import fields
from pathlib import Path

import pytest

from aileen.analogy import sme
from aileen.cli import main
from aileen.memory import codec
from aileen.memory.concept import ConceptMemory

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture()
def lesson(tmp_path: Path) -> Path:
    a = tmp_path / "a.toml"
    a.write_text('[[lesson]]\nsignal = "inform"\ncontent = "red box"\nobjects = ["red box"]\n')
    return a


@pytest.fixture()
def saved(tmp_path: Path, lesson: Path) -> dict:
    """A real memory file's content, after one lesson."""
    m = tmp_path / "saved.json"
    assert main(["run", str(lesson), "--perception", "truth", "--memory", str(m)]) == 0
    return json.loads(m.read_text())


def run_on(tmp_path: Path, lesson: Path, doc: dict | str, capsys) -> tuple[int, str, bool]:  # noqa: ANN001
    """`aileen run` on a memory file holding `doc`: exit code, stderr, whether the file is unchanged."""
    m = tmp_path / "m.json"
    text = doc if isinstance(doc, str) else json.dumps(doc)
    m.write_text(text)
    capsys.readouterr()
    rc = main(["run", str(lesson), "--perception", "truth", "--memory", str(m)])
    return rc, capsys.readouterr().err, m.read_text() == text


BAD_PARAMS = [
    (("sme", "cutoff"), 5, "\"params\".\"sme\".\"cutoff\""),
    (("sme", "cutoff"), "NaN", "\"params\".\"sme\".\"cutoff\""),
    (("sme", "cutoff"), "0.8", "\"params\".\"sme\".\"cutoff\""),
    (("sme", "max_mappings"), 0, "\"params\".\"sme\".\"max_mappings\""),
    (("sme", "max_mappings"), 2.5, "\"params\".\"sme\".\"max_mappings\""),
    (("sme", "same_functor"), 0, "\"params\".\"sme\".\"same_functor\""),
    (("sme", "trickle_down"), -1, "\"params\".\"sme\".\"trickle_down\""),
    (("sme", "trickle_down"), [8], "\"params\".\"sme\".\"trickle_down\""),
    (("assimilation",), True, "\"params\".\"assimilation\""),
    (("probability",), "0.6", "\"params\".\"probability\""),
    (("match",), 1.5, "\"params\".\"match\""),
    (("match",), "Infinity", "\"params\".\"match\""),
    (("normalisation",), "cosine", "\"params\".\"normalisation\""),
    (("functions",), "f", "\"params\".\"functions\""),
    (("sme",), [], "\"params\".\"sme\""),
]


@pytest.mark.parametrize("where,value,field", BAD_PARAMS, ids=[f"{'.'.join(w)}={v!r}" for w, v, _ in BAD_PARAMS])
def test_a_bad_parameter_is_named_and_the_file_left_alone(tmp_path, lesson, saved, capsys, where, value, field) -> None:
    node = saved["params"]
    for k in where[:-1]:
        node = node[k]
    marker = "\"__VALUE__\""
    node[where[-1]] = "__VALUE__"
    text = json.dumps(saved).replace(marker, value if value in ("NaN", "Infinity") else json.dumps(value))
    rc, err, same = run_on(tmp_path, lesson, text, capsys)
    assert rc == 2 and same, err
    assert err.count("\n") == 1 and field in err and "m.json" in err, err
    assert "Traceback" not in err


@pytest.mark.parametrize("place", ["top", "params", "sme", "concept", "generalization", "fact"])
def test_an_unknown_key_is_refused_not_dropped_at_the_next_save(tmp_path, lesson, saved, capsys, place) -> None:
    node = {"top": saved, "params": saved["params"], "sme": saved["params"]["sme"], "concept": saved["concepts"][0],
            "generalization": None, "fact": None}[place]
    if node is None:  # one lesson makes an example; make it a generalization of two
        c = saved["concepts"][0]
        c["generalizations"] = [{"examples": 2, "next_entity": 1, "facts": [{"fact": "isa(gen_ent(0,r_red),cv_red)",
                                                                              "count": 2}]}]
        node = c["generalizations"][0] if place == "generalization" else c["generalizations"][0]["facts"][0]
    node["my_note"] = "keep me"
    rc, err, same = run_on(tmp_path, lesson, saved, capsys)
    assert rc == 2 and same and "unknown key \"my_note\"" in err, err


def test_annotations_keep_a_persons_own_entries(tmp_path, lesson, saved, capsys) -> None:
    saved.setdefault("annotations", {})["my_note"] = {"taught by": "Ann"}
    rc, err, same = run_on(tmp_path, lesson, saved, capsys)
    assert rc == 0, err
    assert json.loads((tmp_path / "m.json").read_text())["annotations"]["my_note"] == {"taught by": "Ann"}


def test_the_parameter_ranges_cover_every_sme_parameter_and_its_default() -> None:
    names = {f.name for f in fields(sme.Params)}
    assert names == set(codec.SME_RANGES)
    for name in names:
        assert codec.SME_RANGES[name].holds(getattr(sme.Params(), name)), name


def test_saved_parameters_load_back_the_same(tmp_path: Path) -> None:
    from aileen.analogy.sage import SageParams

    p = SageParams(assimilation=0.3, probability=0.5, match=0.6, normalisation="paper",
                   sme=sme.Params(trickle_down=16.0, max_mappings=5, cutoff=0.5))
    mem = ConceptMemory(p)
    mem.save(tmp_path / "m.json")
    assert ConceptMemory.load(tmp_path / "m.json").params == p


# ------------------------------------------------------------------ what stands at the path


def _run_in_thread(args: list[str], limit: float = 60.0) -> int:
    """main(args), failing (not hanging) if it does not return in time."""
    out: list[int] = []
    t = threading.Thread(target=lambda: out.append(main(args)), daemon=True)
    t.start()
    t.join(limit)
    assert out, f"aileen {' '.join(args)} did not return within {limit} s (waiting on the file?)"
    return out[0]


@pytest.mark.parametrize("kind", ["fifo", "device", "loop", "directory"])
@pytest.mark.parametrize("command", ["run", "show"])
def test_a_path_that_is_not_a_regular_file_is_an_error_not_a_hang(tmp_path, lesson, capsys, kind, command) -> None:
    p = tmp_path / "m.json"
    if kind == "fifo":
        os.mkfifo(p)
    elif kind == "device":
        p = Path(os.devnull)
    elif kind == "loop":
        os.symlink(tmp_path / "other", p)
        os.symlink(p, tmp_path / "other")
    else:
        p.mkdir()
    args = (["run", str(lesson), "--perception", "truth", "--memory", str(p)] if command == "run"
            else ["memory", "show", str(p)])
    assert _run_in_thread(args) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"aileen: {p}: ") and err.count("\n") == 1, err
    assert {"fifo": "FIFO", "device": "device", "loop": "loop of symbolic links", "directory": "directory"}[kind] in err


@pytest.mark.parametrize("command", ["run", "teach", "show"])
def test_an_empty_memory_path_is_an_error(lesson, capsys, monkeypatch, command) -> None:
    import io

    monkeypatch.setattr("sys.stdin", io.StringIO("quit\n"))
    args = {"run": ["run", str(lesson), "--perception", "truth", "--memory", ""],
            "teach": ["teach", "--perception", "truth", "--memory", ""], "show": ["memory", "show", ""]}[command]
    assert main(args) == 2
    assert "empty" in capsys.readouterr().err


def test_a_read_only_memory_file_is_refused_before_the_run(tmp_path, lesson, saved, capsys) -> None:
    m = tmp_path / "m.json"
    m.write_text(json.dumps(saved))
    m.chmod(0o444)
    before = m.read_bytes()
    capsys.readouterr()
    assert main(["run", str(lesson), "--perception", "truth", "--memory", str(m)]) == 2
    err = capsys.readouterr().err
    assert "read-only" in err and "lesson" not in capsys.readouterr().out
    assert m.read_bytes() == before and (m.stat().st_mode & 0o777) == 0o444
    assert main(["memory", "show", str(m)]) == 0  # reading it is fine


def test_the_lock_never_follows_a_symbolic_link(tmp_path, lesson, capsys) -> None:
    victim = tmp_path / "precious.txt"
    victim.write_text("do not truncate me\n")
    os.symlink(victim, tmp_path / ".m.json.lock")
    assert main(["run", str(lesson), "--perception", "truth", "--memory", str(tmp_path / "m.json")]) == 2
    assert victim.read_text() == "do not truncate me\n"
    assert "symbolic link" in capsys.readouterr().err
    assert not (tmp_path / "m.json").exists()


def test_a_lock_file_that_is_a_fifo_is_refused_not_waited_on(tmp_path, lesson, capsys) -> None:
    os.mkfifo(tmp_path / ".m.json.lock")
    assert _run_in_thread(["run", str(lesson), "--perception", "truth", "--memory", str(tmp_path / "m.json")]) == 2
    assert "not a regular file" in capsys.readouterr().err
