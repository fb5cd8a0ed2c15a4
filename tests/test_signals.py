"""Nothing learned is lost on any stop signal (SIGINT, SIGTERM, SIGHUP, SIGQUIT), nor when rules
blow up in clingo: `aileen run`, `teach` and `serve` run as real processes, are sent the
signal mid-session, and the memory file must hold what they had learned (issue 23)."""

from __future__ import annotations

import json
import os
import resource
import re
import select
import signal
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest

from aileen import lifecycle
from aileen.errors import UserError
from aileen.memory.concept import ConceptMemory
from aileen.memory.store import MemoryFile

ROOT = Path(__file__).resolve().parents[1]
STOPS = [signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT, signal.SIGINT]


def concepts(path: Path) -> set[str]:
    return {c.symbol for c in ConceptMemory.load(path).concepts()} if path.exists() else set()


def aileen(*args: str, stdin=subprocess.DEVNULL, memory_cap_gb: int = 0) -> subprocess.Popen:  # noqa: ANN001
    """`python -m aileen ARGS` in a new session (a signal to it reaches no one else)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT), "PYTHONUNBUFFERED": "1"}

    def cap() -> None:  # a blow-up the code fails to stop must not take the machine down
        if memory_cap_gb:
            resource.setrlimit(resource.RLIMIT_AS, (memory_cap_gb << 30, memory_cap_gb << 30))

    return subprocess.Popen([sys.executable, "-m", "aileen", *args], stdin=stdin, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, env=env, cwd=ROOT, start_new_session=True, preexec_fn=cap)


def read_until(proc: subprocess.Popen, needle: str, timeout: float = 120.0) -> str:
    """stdout until it holds `needle` (the process keeps running). Reads the pipe unbuffered:
    a buffered reader would hold lines that `select` no longer sees."""
    seen = b""
    fd = proc.stdout.fileno()
    end = time.monotonic() + timeout
    while needle.encode() not in seen:
        left = end - time.monotonic()
        if left <= 0 or proc.poll() is not None:
            pytest.fail(f"never saw {needle!r}; got {seen[-2000:]!r}; exit {proc.poll()}")
        ready, _, _ = select.select([fd], [], [], min(left, 1.0))
        if ready:
            seen += os.read(fd, 1 << 16)
    return seen.decode()


def finish(proc: subprocess.Popen, timeout: float = 60.0) -> tuple[int, str]:
    try:
        _, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        proc.kill()
        _, err = proc.communicate()
        pytest.fail(f"the process did not end within {timeout} s of the signal: {err.decode()[-2000:]}")
    return proc.returncode, err.decode()


def created(transcript: str) -> set[str]:
    """Every concept a transcript says was created."""
    out: set[str] = set()
    for line in transcript.splitlines():
        if "learned:" in line and "created " in line:
            part = line.split("created ", 1)[1].split(";")[0].split("(")[0]
            out |= {w.strip() for w in part.split(",") if w.strip()}
    return out


# ------------------------------------------------------------------ run


@pytest.mark.parametrize("sig", STOPS, ids=lambda s: signal.Signals(s).name)
def test_run_saves_what_it_learned_on_every_stop_signal(tmp_path: Path, sig: int) -> None:
    mem = tmp_path / "m.json"
    proc = aileen("run", "lessons/visual.toml", "lessons/sizes.toml", "lessons/spatial.toml", "lessons/relations.toml",
                  "lessons/generation.toml", "--perception", "truth", "--memory", str(mem))
    seen = read_until(proc, "r_cone")  # a few lessons in, far from the end (over a hundred lessons)
    proc.send_signal(sig)
    rc, err = finish(proc)
    assert rc == 128 + sig, err
    # a signal inside a lesson is said at once, and waits for the lesson's end (lifecycle.lesson)
    waited = f"aileen: {signal.Signals(sig).name} received; finishing the lesson first"
    lines = [ln for ln in err.splitlines() if ln.startswith("aileen:") and ln != waited]
    # (the line says where the signal found the run: between lessons, or in a clingo call)
    said = rf"aileen: stopped by {signal.Signals(sig).name}( while clingo was \w+)?; what was learned is saved in "
    assert len(lines) == 1 and re.fullmatch(said + re.escape(str(mem)), lines[0]), err
    assert created(seen) <= concepts(mem)
    assert "Traceback" not in err


def test_a_run_started_ignoring_a_signal_keeps_ignoring_it(tmp_path: Path) -> None:
    """`nohup aileen run ...` starts it ignoring SIGHUP (a shell's `cmd &`, SIGINT and
    SIGQUIT): it stopped anyway, "stopped by SIGHUP", when the terminal closed."""
    mem = tmp_path / "m.json"
    env = {**os.environ, "PYTHONPATH": str(ROOT), "PYTHONUNBUFFERED": "1"}

    def ignore() -> None:
        for sig in (signal.SIGHUP, signal.SIGINT):
            signal.signal(sig, signal.SIG_IGN)

    proc = subprocess.Popen([sys.executable, "-m", "aileen", "run", "lessons/visual.toml", "lessons/sizes.toml",
                             "--perception", "truth", "--memory", str(mem)], stdin=subprocess.DEVNULL,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env, cwd=ROOT,
                            start_new_session=True, preexec_fn=ignore)
    read_until(proc, "r_cone")
    proc.send_signal(signal.SIGHUP)
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=300)
    assert proc.returncode == 0, err.decode()[-2000:]
    assert b"summary:" in out and b"stopped by" not in err
    # and a signal it was not told to ignore still stops it cleanly
    assert set(lifecycle.listened()) >= {signal.SIGTERM}


LATE_SIGNAL = """
import atexit, os, signal, sys, time
from aileen import cli
if __name__ == "__main__":
    atexit.register(lambda: (os.kill(os.getpid(), signal.SIGTERM), time.sleep(5)))
    sys.argv = ["aileen", "asp", "check"]
    sys.exit(cli.main())
"""


def test_a_stop_signal_as_the_command_ends_is_said_in_one_line(tmp_path: Path) -> None:
    """A SIGTERM in the interpreter's last moments (its shutdown can take a second) found the
    default handler: the process died with 143 and said nothing."""
    script = tmp_path / "late.py"
    script.write_text(LATE_SIGNAL)
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, env=env, cwd=ROOT,
                          timeout=120)
    assert done.returncode == 128 + signal.SIGTERM
    assert done.stderr.strip().splitlines()[-1] == (
        "aileen: SIGTERM received as the command ended; what it did is complete")


def test_a_stop_signal_while_the_commands_are_read_is_said_in_one_line(tmp_path: Path) -> None:
    """Reading the commands imports the heavy modules (about a second): a SIGTERM then found
    the default handler, and the process died with 143 and said nothing. A declaration file
    of the user's own (`AILEEN_DOMAIN`, loaded first) sends it at that moment."""
    early = tmp_path / "early.py"
    early.write_text("import os, signal, time\nos.kill(os.getpid(), signal.SIGTERM)\ntime.sleep(0.5)\n")
    env = {**os.environ, "PYTHONPATH": str(ROOT), "AILEEN_DOMAIN": str(early)}
    done = subprocess.run([sys.executable, "-m", "aileen", "asp", "check"], capture_output=True, text=True,
                          env=env, cwd=ROOT, timeout=120)
    assert done.returncode == 128 + signal.SIGTERM
    assert done.stderr.strip().splitlines()[-1].startswith("aileen: stopped by SIGTERM")


# ------------------------------------------------------------------ teach


@pytest.mark.parametrize("sig", [signal.SIGHUP, signal.SIGTERM, signal.SIGQUIT], ids=lambda s: signal.Signals(s).name)
def test_teach_saves_the_session_when_the_terminal_closes_or_it_is_stopped(tmp_path: Path, sig: int) -> None:
    mem = tmp_path / "m.json"
    proc = aileen("teach", "--perception", "truth", "--memory", str(mem), stdin=subprocess.PIPE)
    proc.stdin.write(b"place red box\ninform red box\n")
    proc.stdin.flush()  # the pipe stays open: the session waits for more, as a person typing
    read_until(proc, "learned:")
    proc.send_signal(sig)
    rc, err = finish(proc)
    assert rc == 128 + sig, err
    assert f"stopped by {signal.Signals(sig).name}; what was learned is saved in {mem}" in err
    assert concepts(mem) == {"r_red", "r_box"}


@pytest.mark.parametrize("autosave", [True, False], ids=["autosave", "no-autosave"])
def test_a_killed_teach_session_keeps_every_lesson_it_finished(tmp_path: Path, autosave: bool) -> None:
    """SIGKILL (or the power) cannot be caught: each lesson is saved as it ends (`--autosave`,
    the default); with --no-autosave the session is saved only at its end, so it is lost."""
    mem = tmp_path / "m.json"
    flag = "--autosave" if autosave else "--no-autosave"
    proc = aileen("teach", "--perception", "truth", "--memory", str(mem), flag, stdin=subprocess.PIPE)
    # `help` answers only after the inform and its save are done: the kill comes after both
    proc.stdin.write(b"place red box\ninform red box\nhelp\n")
    proc.stdin.flush()
    read_until(proc, "save the memory")
    proc.kill()
    finish(proc)
    assert concepts(mem) == ({"r_red", "r_box"} if autosave else set())


def test_teach_without_memory_says_nothing_is_kept(tmp_path: Path) -> None:
    proc = aileen("teach", "--perception", "truth", stdin=subprocess.PIPE)
    proc.stdin.write(b"place red box\ninform red box\n")
    proc.stdin.flush()
    read_until(proc, "learned:")
    proc.send_signal(signal.SIGTERM)
    rc, err = finish(proc)
    assert rc == 143 and "stopped by SIGTERM; nothing is kept without --memory" in err


# ------------------------------------------------------------------ serve


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _post(port: int, path: str, body: dict) -> dict:
    req = urllib.request.Request(f"http://127.0.0.1:{port}{path}", data=json.dumps(body).encode(), method="POST",
                                 headers={"Content-Type": "application/json", "Origin": f"http://127.0.0.1:{port}"})
    with urllib.request.urlopen(req, timeout=60) as r:
        return json.loads(r.read())


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGHUP], ids=lambda s: signal.Signals(s).name)
def test_serve_saves_on_a_service_managers_stop_and_a_closed_terminal(tmp_path: Path, sig: int) -> None:
    pytest.importorskip("uvicorn")
    pytest.importorskip("starlette")
    mem, port = tmp_path / "m.json", _free_port()
    proc = aileen("serve", "--memory", str(mem), "--port", str(port))
    try:
        read_until(proc, "aileen serve: open")
        end = time.monotonic() + 60
        while True:  # the server is up a moment after it says so
            try:
                _post(port, "/api/scene", {"op": "add", "object": "red box"})
                break
            except OSError:
                assert time.monotonic() < end
                time.sleep(0.2)
        r = _post(port, "/api/lesson", {"signal": "inform", "content": "red box"})
        assert set(r["created"]) == {"r_red", "r_box"}
        proc.send_signal(sig)
        rc, err = finish(proc)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert rc == 128 + sig, err
    assert f"stopped by {signal.Signals(sig).name}; what was learned is saved in {mem}" in err
    assert concepts(mem) == {"r_red", "r_box"}


# ------------------------------------------------------------------ rules that blow up in clingo


def _blowing_rules(tmp_path: Path, only_relations: bool) -> Path:
    """comprehension.lp plus a rule that never ends once there are objects (or, with
    `only_relations`, once a sentence names a relation: the visual lessons before it run)."""
    rules = tmp_path / "rules"
    rules.mkdir()
    body = "rel_word(R,W)" if only_relations else "obj(O)"
    text = (ROOT / "asp" / "comprehension.lp").read_text()
    (rules / "comprehension.lp").write_text(text + f"\nnn(0,0) :- {body}.\nnn(O,X+1) :- nn(O,X).\n")
    return rules


def test_rules_that_blow_up_on_lesson_facts_stop_the_run_within_the_limit_and_keep_its_learning(tmp_path: Path) -> None:
    mem = tmp_path / "m.json"
    rules = _blowing_rules(tmp_path, only_relations=True)
    t0 = time.monotonic()
    proc = aileen("run", "lessons/visual.toml", "lessons/spatial.toml", "--perception", "truth", "--memory", str(mem),
                  "--rules", str(rules), "--rules-timeout", "3", memory_cap_gb=8)
    rc, err = finish(proc, timeout=90)
    assert rc == 2, err
    assert time.monotonic() - t0 < 60
    line = [ln for ln in err.splitlines() if ln.startswith("aileen:")]
    assert len(line) == 1 and "grounding took longer than 3 s" in line[0] and str(rules) in line[0], err
    assert line[0].endswith(f"what was learned is saved in {mem}")
    assert {"r_red", "r_green", "r_box", "r_cone"} <= concepts(mem)  # the visual lessons before it


def test_the_memory_bound_stops_a_blow_up_before_the_time_limit(tmp_path: Path) -> None:
    mem = tmp_path / "m.json"
    proc = aileen("run", "lessons/visual.toml", "lessons/spatial.toml", "--perception", "truth", "--memory", str(mem),
                  "--rules", str(_blowing_rules(tmp_path, only_relations=True)), "--rules-timeout", "300",
                  "--rules-memory", "150", memory_cap_gb=8)
    rc, err = finish(proc, timeout=200)
    assert rc == 2 and "grounding took more than 150 MB of memory" in err, err
    assert "r_red" in concepts(mem)


def test_a_signal_while_clingo_grounds_is_acted_on_at_once(tmp_path: Path) -> None:
    mem = tmp_path / "m.json"
    proc = aileen("run", "lessons/visual.toml", "lessons/spatial.toml", "--perception", "truth", "--memory", str(mem),
                  "--rules", str(_blowing_rules(tmp_path, only_relations=True)), "--rules-timeout", "300",
                  memory_cap_gb=8)
    read_until(proc, "spatial words")  # the spatial lessons begin: clingo grounds for ever
    time.sleep(1.0)
    t0 = time.monotonic()
    proc.send_signal(signal.SIGINT)
    rc, err = finish(proc, timeout=30)
    assert rc == 130, err
    assert time.monotonic() - t0 < 10
    assert "stopped by SIGINT while clingo was grounding; what was learned is saved in" in err
    assert "r_red" in concepts(mem)


def test_a_huge_rules_timeout_means_no_limit_not_a_traceback(tmp_path: Path) -> None:
    from aileen.cli import main

    a = tmp_path / "a.toml"
    a.write_text('[[lesson]]\nsignal = "inform"\ncontent = "red box"\nobjects = ["red box"]\n')
    assert main(["run", str(a), "--perception", "truth", "--rules-timeout", "1e9"]) == 0
    assert main(["run", str(a), "--perception", "truth", "--rules", str(ROOT / "asp"), "--rules-timeout", "1e300"]) == 0
    assert main(["asp", "check", "--rules-timeout", "1e9"]) == 0


# ------------------------------------------------------------------ a signal during a save


class SlowSaver:
    """An agent whose save takes a while and sends this process a signal midway."""

    def __init__(self, sig: int) -> None:
        self.sig = sig
        self.saves = 0

    def save(self, path: str) -> None:
        self.saves += 1
        os.kill(os.getpid(), self.sig)  # handled at once by Python, inside the save
        time.sleep(0.05)
        mem = ConceptMemory()
        mem.create("r_red", "visual")
        mem.save(path)


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_during_a_save_waits_for_it_and_then_says_it_saved(tmp_path: Path, sig: int) -> None:
    lifecycle.install()
    try:
        mf = MemoryFile.open(tmp_path / "m.json")
        agent = SlowSaver(sig)
        with pytest.raises(lifecycle.Stopped) as caught:
            mf.save(agent)
        mf.close()
    finally:
        lifecycle.uninstall()
    assert agent.saves == 1
    assert caught.value.signum == sig and caught.value.kept == f"what was learned is saved in {tmp_path / 'm.json'}"
    assert concepts(tmp_path / "m.json") == {"r_red"}


def test_a_signal_during_a_failing_save_names_the_recovery_file(tmp_path: Path) -> None:
    folder = tmp_path / "d"
    folder.mkdir()
    lifecycle.install()
    try:
        mf = MemoryFile.open(folder / "m.json")
        (folder / "m.json").mkdir()  # the save cannot replace a directory: a recovery file is written
        with pytest.raises(lifecycle.Stopped) as caught:
            mf.save(SlowSaver(signal.SIGTERM))
        mf.close()
    finally:
        lifecycle.uninstall()
    assert "learned is in" in caught.value.kept
    recovered = Path(caught.value.kept.rsplit("learned is in ", 1)[1])
    assert concepts(recovered) == {"r_red"}


def test_a_second_signal_while_stopping_does_not_cut_the_save_short(tmp_path: Path) -> None:
    """The first signal stops the session; the second arrives while it is being saved."""
    from aileen.cli import main

    a = tmp_path / "a.toml"
    a.write_text('[[lesson]]\nsignal = "inform"\ncontent = "red box"\nobjects = ["red box"]\n')
    mem = tmp_path / "m.json"
    sent = []
    real_save = ConceptMemory.save

    def save(self, path):  # noqa: ANN001
        if not sent:
            sent.append(1)
            os.kill(os.getpid(), signal.SIGTERM)
        return real_save(self, path)

    from aileen.curriculum import interpreter

    real_run = interpreter.Interpreter.run

    def run_then_stop(self, *a, **kw):  # noqa: ANN001
        r = real_run(self, *a, **kw)
        os.kill(os.getpid(), signal.SIGHUP)
        return r

    mp = pytest.MonkeyPatch()
    mp.setattr(ConceptMemory, "save", save)
    mp.setattr(interpreter.Interpreter, "run", run_then_stop)
    try:
        rc = main(["run", str(a), "--perception", "truth", "--memory", str(mem)])
    finally:
        mp.undo()
    assert rc == 128 + signal.SIGHUP
    assert concepts(mem) == {"r_red", "r_box"}


def test_stop_signal_handlers_are_put_back_after_a_command(tmp_path: Path) -> None:
    from aileen.cli import main

    before = {s: signal.getsignal(s) for s in lifecycle.STOP_SIGNALS}
    assert main(["asp", "check"]) == 0
    assert {s: signal.getsignal(s) for s in lifecycle.STOP_SIGNALS} == before


def test_a_save_error_on_the_way_out_is_named_once(tmp_path: Path) -> None:
    """A UserError from the final save names the recovery file; nothing saves it twice."""
    folder = tmp_path / "d"
    folder.mkdir()
    mf = MemoryFile.open(folder / "m.json")
    (folder / "m.json").mkdir()
    with pytest.raises(UserError) as caught:
        mf.save(_Plain())
    mf.close()
    assert lifecycle.kept(caught.value) == ""


class _Plain:
    def save(self, path: str) -> None:
        ConceptMemory().save(path)


# ------------------------------------------------------------------ experiment sweep


def _session_alive(sid: int) -> list[int]:
    """Processes still in session `sid` (the sweep and its workers)."""
    alive = []
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                fields = (d / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            if int(fields[3]) == sid and fields[0] != "Z":
                alive.append(int(d.name))
    return alive


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads /proc")
def test_a_stopped_sweep_ends_its_workers_at_once_and_resumes(tmp_path: Path) -> None:
    grid = tmp_path / "grid.toml"
    grid.write_text('experiment = "visual"\ntrials = 1\nseeds = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9]\nperception = "truth"\n'
                    'lessons = 6\n[params]\nassimilation = [0.01, 0.1]\n')
    out = tmp_path / "out"
    proc = aileen("experiment", "sweep", str(grid), "--out", str(out), "--jobs", "2", "--no-plot", "--quiet")
    csv = out / "sweep.csv"
    end = time.monotonic() + 120
    while not (csv.exists() and len(csv.read_text().splitlines()) >= 2):  # a trial done, most still to run
        assert time.monotonic() < end and proc.poll() is None, proc.stderr.read().decode() if proc.poll() else ""
        time.sleep(0.1)
    proc.send_signal(signal.SIGTERM)
    t0 = time.monotonic()
    rc, err = finish(proc, timeout=60)
    assert rc == 143 and "stopped by SIGTERM" in err, err
    assert time.monotonic() - t0 < 10, "the sweep waited for its trials before stopping"
    end = time.monotonic() + 10
    while _session_alive(proc.pid):
        assert time.monotonic() < end, f"workers left running: {_session_alive(proc.pid)}"
        time.sleep(0.2)
    done = len(csv.read_text().splitlines()) - 1
    assert 1 <= done < 20
    again = aileen("experiment", "sweep", str(grid), "--out", str(out), "--jobs", "2", "--no-plot", "--quiet")
    rc, err = finish(again, timeout=300)
    assert rc == 0, err
    assert len(csv.read_text().splitlines()) - 1 == 20


def test_install_answers_every_stop_signal_not_ignored() -> None:
    """(A first version of `listened` asked whether it was installed while installing, and
    put no handler on any signal: a SIGTERM killed a run without saving.)"""
    if lifecycle.installed():
        pytest.skip("installed by an earlier test in this process")
    before = signal.getsignal(signal.SIGHUP)
    signal.signal(signal.SIGHUP, signal.SIG_IGN)
    try:
        lifecycle.install()
        try:
            assert signal.getsignal(signal.SIGTERM) is not signal.SIG_DFL
            assert signal.getsignal(signal.SIGHUP) == signal.SIG_IGN
            assert signal.SIGTERM in lifecycle.listened() and signal.SIGHUP not in lifecycle.listened()
        finally:
            lifecycle.uninstall()
        assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL
    finally:
        signal.signal(signal.SIGHUP, before)


# ------------------------------------------------------------------ a stop inside a lesson


def _stop_after_first_store(mp: pytest.MonkeyPatch, sig: int = signal.SIGTERM) -> None:
    """Send this process `sig` right after the first concept store: inside an inform lesson,
    between the stores of its two words."""
    real_store = ConceptMemory.store
    sent: list[int] = []

    def store(self, *a, **kw):  # noqa: ANN001, ANN002, ANN003
        r = real_store(self, *a, **kw)
        if not sent:
            sent.append(1)
            os.kill(os.getpid(), sig)
        return r

    mp.setattr(ConceptMemory, "store", store)


def test_a_stop_inside_a_lesson_waits_for_its_end_and_keeps_it_whole(tmp_path: Path, capsys) -> None:
    """A SIGTERM between the two stores of 'red box' kept r_red and not r_box: half a lesson."""
    from aileen.cli import main

    a = tmp_path / "a.toml"
    a.write_text('[[lesson]]\nsignal = "inform"\ncontent = "red box"\nobjects = ["red box"]\n\n'
                 '[[lesson]]\nsignal = "inform"\ncontent = "blue cone"\nobjects = ["blue cone"]\n')
    mem = tmp_path / "m.json"
    mp = pytest.MonkeyPatch()
    _stop_after_first_store(mp)
    try:
        rc = main(["run", str(a), "--perception", "truth", "--memory", str(mem)])
    finally:
        mp.undo()
    cap = capsys.readouterr()
    assert rc == 128 + signal.SIGTERM
    assert concepts(mem) == {"r_red", "r_box"}  # the whole first lesson, and not the second
    assert "SIGTERM received; finishing the lesson first" in cap.err
    assert cap.err.endswith(f"aileen: stopped by SIGTERM; what was learned is saved in {mem}\n")
    assert "created r_red, r_box" in cap.out and "blue cone" not in cap.out  # the lesson kept is reported


def test_a_stop_inside_a_teach_lesson_keeps_it_whole(tmp_path: Path, monkeypatch, capsys) -> None:
    import io

    from aileen.cli import main

    mem = tmp_path / "m.json"
    monkeypatch.setattr("sys.stdin", io.StringIO("place red box\ninform red box\nclear\nplace blue cone\n"
                                                 "inform blue cone\n"))
    _stop_after_first_store(monkeypatch)
    assert main(["teach", "--memory", str(mem), "--perception", "truth"]) == 128 + signal.SIGTERM
    assert concepts(mem) == {"r_red", "r_box"}
    assert "finishing the lesson first" in capsys.readouterr().err


def test_a_lesson_hides_stop_signals_from_the_watchdog_until_it_ends() -> None:
    """Inside clingo the watchdog acts on a stop signal by ending the process, saving what the
    agent holds: half a lesson. Inside a lesson the signal is Python's, at the lesson's end."""
    lifecycle.install()
    try:
        assert lifecycle.wakeup_fd() is not None
        with pytest.raises(lifecycle.Stopped) as caught, lifecycle.lesson():
            assert lifecycle.wakeup_fd() is None
            os.kill(os.getpid(), signal.SIGTERM)
            raise UserError("a lesson's own error")  # an outcome: raised past as the stop
        assert caught.value.signum == signal.SIGTERM and caught.value.kept is None
        assert isinstance(caught.value.__cause__, UserError)
        assert lifecycle.wakeup_fd() is not None
        ready, _, _ = select.select([lifecycle.wakeup_fd()], [], [], 0)
        assert not ready  # the byte of the signal acted on is not left for the watchdog
    finally:
        lifecycle.uninstall()


def test_a_signal_python_cannot_take_inside_a_lesson_is_shown_to_the_watchdog_after_the_grace(monkeypatch) -> None:
    """The main thread stuck in clingo (rules grounding for ever) cannot finish the lesson: the
    watchdog is shown the signal once `LESSON_GRACE` has passed; one Python took is never shown."""
    lifecycle.install()
    try:
        with lifecycle.lesson():
            assert lifecycle.wakeup_fd() is None  # nothing came
            lifecycle._S.wake_w.send(bytes([signal.SIGTERM]))  # as the C-level handler writes it, Python not yet run
            assert lifecycle.wakeup_fd() is None  # within the grace
            monkeypatch.setattr(lifecycle, "LESSON_GRACE", -1.0)  # the grace over
            assert lifecycle.wakeup_fd() is lifecycle._S.wake_r
            lifecycle._S.pending = signal.SIGTERM  # Python took it: the lesson runs on to its end
            assert lifecycle.wakeup_fd() is None
            lifecycle._S.pending = None
            lifecycle._drain_wakeup()
    finally:
        lifecycle.uninstall()
