"""Nothing learned is ever lost: the memory file under concurrent runs, kills and failing saves.

The concurrent and SIGKILL cases run the CLI in real child processes, forked from the test
after the imports (a fresh interpreter spends most of a second importing), on tiny lesson
files with `--perception truth`."""

from __future__ import annotations

import io
import os
import signal
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from aileen.cli import main
from aileen.errors import UserError
from aileen.io import TMP_SUFFIX
from aileen.memory.concept import ConceptMemory
from aileen.memory.store import MemoryFile

ROOT = Path(__file__).resolve().parents[1]


def lesson_file(folder: Path, name: str, *contents: str) -> Path:
    """A lesson file teaching each phrase on a table with that one object."""
    body = "".join(f'[[lesson]]\nsignal = "inform"\ncontent = "{c}"\nobjects = ["{c}"]\n\n' for c in contents)
    p = folder / name
    p.write_text(body)
    return p


def fork_cli(err: Path, *args: str) -> int:
    """Run `aileen ARGS` in a forked child (stdout dropped, stderr to `err`); its pid."""
    pid = os.fork()
    if pid == 0:  # pragma: no cover - the child
        rc = 99
        try:
            with open(err, "w") as fh, open(os.devnull, "w") as null:
                sys.stdout, sys.stderr = null, fh
                rc = main(list(args))
                fh.flush()
        finally:
            os._exit(rc)
    return pid


def wait(pid: int) -> int:
    return os.waitstatus_to_exitcode(os.waitpid(pid, 0)[1])


def concepts(path: Path) -> set[str]:
    return {c.symbol for c in ConceptMemory.load(path).concepts()} if path.exists() else set()


def test_memory_concepts_helper_reads_symbols(tmp_path: Path, capsys) -> None:
    a = lesson_file(tmp_path, "a.toml", "red box")
    assert main(["run", str(a), "--perception", "truth", "--memory", str(tmp_path / "m.json")]) == 0
    assert concepts(tmp_path / "m.json") == {"r_red", "r_box"}


def test_two_concurrent_runs_lose_nothing_20_times(tmp_path: Path) -> None:
    a = lesson_file(tmp_path, "a.toml", "red box")
    b = lesson_file(tmp_path, "b.toml", "blue cone")
    taught = {"a": {"r_red", "r_box"}, "b": {"r_blue", "r_cone"}}
    assert main(["run", str(a), "--perception", "truth"]) == 0  # imports done once, before the forks
    refused = 0
    for k in range(20):
        mem = tmp_path / f"m{k}.json"
        errs = {name: tmp_path / f"{name}{k}.err" for name in taught}
        pids = {name: fork_cli(errs[name], "run", str(f), "--perception", "truth", "--memory", str(mem))
                for name, f in (("a", a), ("b", b))}
        outcome = {name: (wait(pid), errs[name].read_text()) for name, pid in pids.items()}
        have = concepts(mem)
        for name, (rc, err) in outcome.items():
            if rc == 0:
                assert taught[name] <= have, f"round {k}: run {name}'s concepts are missing: {have}"
            else:
                assert rc == 2, err
                assert "in use by another aileen run" in err and err.count("\n") == 1
                refused += 1
        assert any(rc == 0 for rc, _ in outcome.values())
    # Both outcomes are allowed; print how often the later run was refused, for the record.
    print(f"refused {refused} of 20 later runs")


def test_sigkill_at_random_moments_leaves_the_old_or_the_new_file_20_times(tmp_path: Path) -> None:
    rng = np.random.default_rng(12)
    a = lesson_file(tmp_path, "a.toml", "red box")
    b = lesson_file(tmp_path, "b.toml", "blue cone", "green sphere")
    mem = tmp_path / "m.json"
    assert main(["run", str(a), "--perception", "truth", "--memory", str(mem)]) == 0
    old = mem.read_bytes()
    t0 = time.perf_counter()
    assert wait(fork_cli(tmp_path / "err", "run", str(b), "--perception", "truth", "--memory", str(mem))) == 0
    full = time.perf_counter() - t0
    new = mem.read_bytes()
    assert old != new
    outcomes = set()
    for k in range(20):
        mem.write_bytes(old)
        pid = fork_cli(tmp_path / "err", "run", str(b), "--perception", "truth", "--memory", str(mem))
        time.sleep(float(rng.uniform(0.0, full * 1.1)))
        os.kill(pid, signal.SIGKILL)
        wait(pid)
        now = mem.read_bytes()
        assert now in (old, new), f"kill {k}: the memory file is neither version"
        outcomes.add("new" if now == new else "old")
        ConceptMemory.load(mem)  # and it loads
    # The next run cleans up whatever temporary file a kill left behind.
    assert main(["run", str(b), "--perception", "truth", "--memory", str(mem)]) == 0
    assert not [f for f in os.listdir(tmp_path) if f.endswith(TMP_SUFFIX) or f.endswith(".tmp")]
    print(f"after kills: {sorted(outcomes)}; a full run takes {full:.2f} s")


def test_a_second_holder_is_refused_while_the_first_holds_the_lock(tmp_path: Path) -> None:
    mem = tmp_path / "m.json"
    with MemoryFile.open(mem):
        with pytest.raises(UserError, match=f"in use by another aileen run \\(process {os.getpid()}\\)"):
            MemoryFile.open(mem)
        link = tmp_path / "link.json"
        link.symlink_to("m.json")
        with pytest.raises(UserError, match="in use"):
            MemoryFile.open(link)  # a link to a held file is the same file
    MemoryFile.open(mem).close()  # released


def test_a_file_changed_behind_the_lock_is_not_overwritten(tmp_path: Path, capsys) -> None:
    mem = tmp_path / "m.json"
    ConceptMemory().save(mem)

    class Saver:
        def save(self, path: str) -> None:
            m = ConceptMemory()
            m.create("r_mine", "visual")
            m.save(path)

    mf = MemoryFile.open(mem)
    other = ConceptMemory()
    other.create("r_theirs", "visual")
    other.save(mem)  # a program that ignores the lock
    with pytest.raises(UserError, match="changed by another program") as exc:
        mf.save(Saver())
    mf.close()
    assert {c.symbol for c in ConceptMemory.load(mem).concepts()} == {"r_theirs"}
    recovered = Path(exc.value.message.rsplit(" ", 1)[1])
    assert recovered.parent == tmp_path and {c.symbol for c in ConceptMemory.load(recovered).concepts()} == {"r_mine"}


def test_a_failing_save_writes_a_recovery_file_and_names_it(tmp_path: Path) -> None:
    mem = tmp_path / "m.json"

    class DiskFull:
        def save(self, path: str) -> None:
            if Path(path).name == "m.json":
                raise OSError(28, "No space left on device")
            m = ConceptMemory()
            m.create("r_red", "visual")
            m.save(path)

    with MemoryFile.open(mem) as mf, pytest.raises(UserError, match="No space left on device") as exc:
        mf.save(DiskFull())
    assert "what was learned is in" in exc.value.message
    recovered = Path(exc.value.message.rsplit(" ", 1)[1])
    assert {c.symbol for c in ConceptMemory.load(recovered).concepts()} == {"r_red"}
    assert not mem.exists()


def test_a_bad_sentence_late_in_a_run_stops_it_before_the_first_lesson(tmp_path: Path, capsys) -> None:
    good = lesson_file(tmp_path, "good.toml", "red box")
    bad = tmp_path / "bad.toml"
    # a sentence the agent cannot read is its answer when its turn comes (not understood);
    # one longer than any it reads is a mistake in the file
    bad.write_text('[[lesson]]\nsignal = "inform"\ncontent = "' + "red " * 201 + '"\nobjects = ["red box"]\n')
    mem = tmp_path / "fresh.json"
    rc = main(["run", str(good), str(bad), "--perception", "truth", "--memory", str(mem)])
    cap = capsys.readouterr()
    assert rc == 2
    assert f"{bad}:3: lesson 1: I cannot read 'red red" in cap.err and "longer than 200 words" in cap.err
    assert "lesson  1" not in cap.out  # nothing ran
    assert not mem.exists()


@pytest.mark.parametrize("where", ["missing-folder", "directory"])
def test_an_unwritable_memory_path_is_refused_before_the_run(tmp_path: Path, capsys, where: str) -> None:
    good = lesson_file(tmp_path, "good.toml", "red box")
    mem = tmp_path / "nope" / "m.json" if where == "missing-folder" else tmp_path
    rc = main(["run", str(good), "--perception", "truth", "--memory", str(mem)])
    cap = capsys.readouterr()
    assert rc == 2 and "lesson  1" not in cap.out
    assert cap.err.startswith("aileen: ") and cap.err.count("\n") == 1


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_a_read_only_memory_folder_is_refused_before_the_run(tmp_path: Path, capsys) -> None:
    good = lesson_file(tmp_path, "good.toml", "red box")
    ro = tmp_path / "ro"
    ro.mkdir()
    os.chmod(ro, 0o555)
    try:
        rc = main(["run", str(good), "--perception", "truth", "--memory", str(ro / "m.json")])
    finally:
        os.chmod(ro, 0o755)
    cap = capsys.readouterr()
    assert rc == 2 and "not writable" in cap.err and "lesson  1" not in cap.out


def test_save_images_pointing_at_a_file_is_refused_before_the_run(tmp_path: Path, capsys) -> None:
    good = lesson_file(tmp_path, "good.toml", "red box")
    f = tmp_path / "afile"
    f.write_text("x")
    rc = main(["run", str(good), "--perception", "truth", "--save-images", str(f)])
    cap = capsys.readouterr()
    assert rc == 2 and "--save-images must be a directory" in cap.err and "lesson  1" not in cap.out


def test_run_keeps_a_symbolic_link_and_the_mode(tmp_path: Path, capsys) -> None:
    good = lesson_file(tmp_path, "good.toml", "red box")
    real = tmp_path / "real.json"
    ConceptMemory().save(real)
    os.chmod(real, 0o644)
    link = tmp_path / "link.json"
    link.symlink_to("real.json")
    assert main(["run", str(good), "--perception", "truth", "--memory", str(link)]) == 0
    assert link.is_symlink()
    assert concepts(real) == {"r_red", "r_box"}
    assert (real.stat().st_mode & 0o777) == 0o644


def test_teach_save_to_a_directory_is_an_error_and_the_session_goes_on(tmp_path: Path, monkeypatch, capsys) -> None:
    mem = tmp_path / "m.json"
    script = f"place red box\ninform red box\nsave {tmp_path}\nsave {tmp_path / 'other.json'}\n"
    monkeypatch.setattr("sys.stdin", io.StringIO(script))
    rc = main(["teach", "--perception", "truth", "--memory", str(mem)])
    cap = capsys.readouterr()
    assert rc == 2  # one line failed
    assert "<stdin>:3: " in cap.err and "cannot use a directory" in cap.err
    assert f"saved 2 concepts to {tmp_path / 'other.json'}" in cap.out
    assert concepts(tmp_path / "other.json") == {"r_red", "r_box"}
    assert concepts(mem) == {"r_red", "r_box"}  # saved at the end


def test_teach_goes_on_after_a_mistake_and_saves(tmp_path: Path, monkeypatch, capsys) -> None:
    mem = tmp_path / "m.json"
    monkeypatch.setattr("sys.stdin", io.StringIO("frobnicate\nplace red box\ninform red box\nverify red\n"))
    rc = main(["teach", "--perception", "truth", "--memory", str(mem)])
    cap = capsys.readouterr()
    assert rc == 2
    assert "<stdin>:1: unknown command 'frobnicate'" in cap.err
    assert 'verify  "red"' in cap.out  # the lines after the mistake ran
    assert concepts(mem) == {"r_red", "r_box"}


def test_teach_help_lists_every_command(monkeypatch, capsys) -> None:
    from aileen.curriculum.console import COMMANDS

    monkeypatch.setattr("sys.stdin", io.StringIO("help\n"))
    assert main(["teach", "--perception", "truth"]) == 0
    out = capsys.readouterr().out
    for c in COMMANDS:
        assert f"\n    {c}" in out, c


def test_the_readme_teach_session_teaches(tmp_path: Path, monkeypatch, capsys) -> None:
    readme = (ROOT / "README.md").read_text()
    block = readme.split("A teaching session", 1)[1].split("```text\n", 1)[1].split("```", 1)[0]
    assert "#" in block  # as pasted, comments and all
    monkeypatch.setattr("sys.stdin", io.StringIO(block))
    mem = tmp_path / "m.json"
    assert main(["teach", "--perception", "truth", "--memory", str(mem)]) == 0
    out = capsys.readouterr().out
    verify = out.split('verify  "red box left of blue cone"', 1)[1]
    assert "answer:   success" in verify.splitlines()[2]
    assert concepts(mem) == {"r_red", "r_box", "r_blue", "r_cone", "r_left_of"}


def test_a_hard_link_to_a_held_file_is_in_use_too(tmp_path: Path) -> None:
    """Two runs on h.json and its hard link hl.json both went on (the lock file was keyed by
    the name), and the memory split into two files."""
    mem = tmp_path / "h.json"
    ConceptMemory().save(mem)
    os.link(mem, tmp_path / "hl.json")
    with MemoryFile.open(mem) as held:
        with pytest.raises(UserError, match="in use by another aileen run under another name") as e:
            MemoryFile.open(tmp_path / "hl.json")
        assert e.value.format().startswith(f"{tmp_path / 'hl.json'}: ") and "--memory" in e.value.message
        # the save writes a new file; a hard link made to it is held as well
        held.save(ConceptMemory())
        os.link(mem, tmp_path / "hl2.json")
        with pytest.raises(UserError, match="in use"):
            MemoryFile.open(tmp_path / "hl2.json")
        with pytest.raises(UserError, match="in use"):
            MemoryFile.open(tmp_path / "hl.json")  # the file it held when it began
    for name in ("h.json", "hl.json", "hl2.json"):
        MemoryFile.open(tmp_path / name).close()  # released


def test_a_run_on_a_hard_link_to_a_held_file_is_refused(tmp_path: Path) -> None:
    a = lesson_file(tmp_path, "a.toml", "red box")
    mem = tmp_path / "h.json"
    assert main(["run", str(a), "--perception", "truth", "--memory", str(mem)]) == 0
    os.link(mem, tmp_path / "hl.json")
    with MemoryFile.open(mem):
        pid = fork_cli(tmp_path / "err", "run", str(a), "--perception", "truth", "--memory", str(tmp_path / "hl.json"))
        assert wait(pid) == 2
    err = (tmp_path / "err").read_text()
    assert "in use by another aileen run" in err and err.count("\n") == 1
