"""Soar's semantic memory on disk (issue 24): kept in Soar's own database file beside the memory
file, reloaded from it, and what the agent knows (`SoarAgent.semantic`) read from smem. Also
the debugger's listener, and rule files that are refused with Soar's own reason."""

from __future__ import annotations

import json
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytest.importorskip("soar_sml")

from aileen.cli import main  # noqa: E402
from aileen.errors import UserError  # noqa: E402
from aileen.memory.concept import ConceptMemory  # noqa: E402
from aileen.soar.kernel import SoarKernel  # noqa: E402
from aileen.soar.learner import RULE_FILES, SoarAgent  # noqa: E402
from aileen.soar.smem import parse_smem_print, smem_path  # noqa: E402
from aileen.terms import parse  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
LESSONS = ROOT / "lessons"


def _memory() -> ConceptMemory:
    mem = ConceptMemory()
    mem.create("r_red", "visual")
    mem.store([parse("isa(o1,cv_red)"), parse("isa(o1,cv_box)"), parse("isa(o1,r_red)")], "r_red")
    mem.create("r_box", "visual")
    mem.store([parse("isa(o1,cv_red)"), parse("isa(o1,cv_box)"), parse("isa(o1,r_box)")], "r_box")
    return mem


def test_smem_survives_a_restart(tmp_path) -> None:
    """A word only smem knows (a synonym: no concept is named for it) is there after a restart,
    so the words come from Soar's database file, not from the concepts' names."""
    path = tmp_path / "m.json"
    with SoarAgent(_memory()) as agent:
        assert agent.semantic.concept("red") == "r_red"  # built from the concepts: no file yet
        agent.kernel.command("smem --add {(<w> ^word crimson ^concept r_red ^kind visual)}")
        agent.save(str(path))
    assert smem_path(path).is_file() and smem_path(path).name == "m.json.smem"
    with SoarAgent(ConceptMemory.load(path), smem=smem_path(path)) as again:
        assert again.semantic.concept("crimson") == "r_red"
        assert again.semantic.concept("box") == "r_box" and again.semantic.kind("r_box") == "visual"
    with SoarAgent(ConceptMemory.load(path)) as fresh:  # without the file: rebuilt, no synonym
        assert fresh.semantic.concept("crimson") is None and fresh.semantic.concept("red") == "r_red"


def test_a_run_keeps_smem_beside_the_memory_and_the_next_run_reads_it(tmp_path, capsys) -> None:
    mem = tmp_path / "m.json"
    assert main(["run", str(LESSONS / "push.toml"), "--agent", "soar", "--perception", "truth",
                 "--memory", str(mem)]) == 0
    capsys.readouterr()
    assert smem_path(mem).is_file()
    with SoarAgent(ConceptMemory.load(mem), smem=smem_path(mem)) as agent:
        words = agent.semantic.to_dict()
    assert words["push"] == {"concept": "r_push", "kind": "action"} and words["red"]["kind"] == "visual"
    rc = main(["run", str(LESSONS / "push.toml"), "--agent", "soar", "--perception", "truth", "--memory", str(mem),
               "--json"])
    again = [json.loads(line) for line in capsys.readouterr().out.splitlines() if line.strip()]
    assert rc == 0 and not any(r["created"] for r in again)


def test_an_smem_file_of_another_memory_is_refused(tmp_path, capsys) -> None:
    mem = tmp_path / "m.json"
    with SoarAgent(_memory()) as agent:
        agent.save(str(mem))
    other = tmp_path / "other.json"
    ConceptMemory().save(other)
    smem_path(other).write_bytes(smem_path(mem).read_bytes())
    with pytest.raises(UserError) as err:
        SoarAgent(ConceptMemory.load(other), smem=smem_path(other))
    assert "not a pair" in err.value.message and "r_box" in err.value.message
    rc = main(["run", str(LESSONS / "push.toml"), "--agent", "soar", "--perception", "truth", "--memory", str(other)])
    out = capsys.readouterr().err
    assert rc == 2 and "not a pair" in out and len(out.strip().splitlines()) == 1


def test_a_corrupt_smem_file_is_one_clear_error(tmp_path) -> None:
    mem = tmp_path / "m.json"
    _memory().save(mem)
    smem_path(mem).write_bytes(b"this is not a database\n" * 100)
    with pytest.raises(UserError) as err:
        SoarAgent(ConceptMemory.load(mem), smem=smem_path(mem))
    assert err.value.path == str(smem_path(mem))


def test_the_smem_print_parser_reads_quoted_and_wrapped_entries() -> None:
    text = ("(@1 ^concept r_red ^kind visual ^word red [+0.000])\n"
            "(@2 ^concept |r_o 1| ^kind visual\n       ^word |o 1| [+1.000])\n")
    assert parse_smem_print(text) == [{"concept": "r_red", "kind": "visual", "word": "red"},
                                      {"concept": "r_o 1", "kind": "visual", "word": "o 1"}]


# ---------------------------------------------------------------------------- the debugger


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


REMOTE = """
import sys
import soar_sml as sml
k = sml.Kernel.CreateRemoteConnection(True, "127.0.0.1", int(sys.argv[1]))
if k.HadError():
    sys.exit("no connection: " + k.GetLastErrorDescription())
a = k.GetAgent("aileen")
print(a.ExecuteCommandLine("print --depth 2 <s>"))
print(a.ExecuteCommandLine("smem --query {(<w> ^word red)}"))
k.Shutdown()
"""


def test_soars_cli_attaches_to_the_listening_agent(tmp_path) -> None:
    port = _free_port()
    with SoarAgent(_memory(), listen=port) as agent:
        assert agent.kernel.port == port
        remote = subprocess.Popen([sys.executable, "-c", REMOTE, str(port)], stdout=subprocess.PIPE,
                                  stderr=subprocess.PIPE, text=True)
        t0 = time.monotonic()
        while remote.poll() is None and time.monotonic() - t0 < 60:
            agent.kernel.pump()  # as the agent does between lessons and after every decision
            time.sleep(0.005)
        out, err = remote.communicate(timeout=5)
    assert remote.returncode == 0, err
    assert "^io" in out and "^superstate nil" in out  # the remote side sees the agent's state
    assert "^concept r_red" in out  # and its semantic memory


def test_a_port_in_use_is_one_clear_error(capsys) -> None:
    with socket.socket() as s:
        s.bind(("0.0.0.0", 0))
        s.listen()
        port = s.getsockname()[1]
        with pytest.raises(UserError) as err:
            SoarKernel(listen=port)
    assert str(port) in err.value.message


def test_soar_listen_is_for_the_soar_agent(capsys) -> None:
    rc = main(["run", str(LESSONS / "push.toml"), "--perception", "truth", "--soar-listen", str(_free_port())])
    assert rc == 2 and "--agent soar" in capsys.readouterr().err


# ---------------------------------------------------------------------------- rule files


@pytest.mark.parametrize("text,reason,line", [
    ("# fine\nsp {ok (state <s> ^x) --> (<s> ^y 1)}\nsp {bad (state <s> ^x <v> --> (<s> ^y <v>)}\n",
     "Expected variable or constant for test", 3),
    ("sp {bad (state <s> ^x <v>) -->\n   (<s> ^y (+ <v> |a| ^ ))}\n", "", 1),
    ("sp {bad (state <s> -^x) -->}\n", "no positive conditions", 1),
])
def test_a_bad_rule_keeps_soars_reason_at_file_and_line(tmp_path, text, reason, line) -> None:
    bad = tmp_path / "bad.soar"
    bad.write_text(text)
    with SoarKernel() as k, pytest.raises(UserError) as err:
        k.source(bad)
    assert err.value.path == str(bad) and err.value.line == line
    assert reason in err.value.message and not err.value.message.startswith(("(Ignoring", "*", "#"))


def test_a_rule_soar_warns_about_is_refused(tmp_path) -> None:
    bad = tmp_path / "bad.soar"
    bad.write_text("sp {unconnected (<s> ^x <v>) --> (<s> ^y <v>)}\n")
    with SoarKernel() as k, pytest.raises(UserError) as err:
        k.source(bad)
    assert "not connected" in err.value.message and err.value.path == str(bad)


def test_rules_refuses_a_soar_file_it_would_ignore(tmp_path, capsys) -> None:
    (tmp_path / "answer.soar").write_text((ROOT / "aileen" / "soar" / "agent" / "answer.soar").read_text())
    (tmp_path / "extra.soar").write_text("# my own rules\n")
    rc = main(["run", str(LESSONS / "visual.toml"), "--agent", "soar", "--perception", "truth",
               "--rules", str(tmp_path)])
    err = capsys.readouterr().err
    assert rc == 2 and "extra.soar" in err and RULE_FILES[0] in err and len(err.strip().splitlines()) == 1


def test_a_semantic_memory_that_is_a_folder_is_refused_before_any_lesson(tmp_path, capsys) -> None:
    """It was passed over, every lesson ran, and the save at the end named the memory file."""
    from aileen.cli import main

    memory = tmp_path / "m.json"
    (tmp_path / "m.json.smem").mkdir()
    lessons = Path(__file__).resolve().parents[1] / "lessons" / "visual.toml"
    rc = main(["run", str(lessons), "--agent", "soar", "--perception", "truth", "--memory", str(memory)])
    out, err = capsys.readouterr()
    assert rc == 2 and "m.json.smem:" in err and "not a file" in err and "lesson  1" not in out
