"""aileen.io: the one atomic writer keeps links and modes and cleans up after killed writers."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from aileen.io import (
    TMP_SUFFIX,
    atomic_path,
    atomic_write_bytes,
    atomic_write_text,
    stale_temp_files,
)


def _dead_pid() -> int:
    """The id of a process that has ended (a child we started and waited for)."""
    proc = subprocess.Popen([sys.executable, "-c", "pass"])
    proc.wait()
    return proc.pid


def test_write_replaces_the_content_and_leaves_no_temporary_file(tmp_path: Path) -> None:
    target = tmp_path / "a.json"
    atomic_write_text(target, "old")
    atomic_write_text(target, "new")
    assert target.read_text() == "new"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.json"]


def test_a_symbolic_link_stays_a_link_and_its_target_is_replaced(tmp_path: Path) -> None:
    real = tmp_path / "real.json"
    real.write_text("old")
    link = tmp_path / "link.json"
    link.symlink_to("real.json")
    atomic_write_text(link, "new")
    assert link.is_symlink()
    assert real.read_text() == "new"


def test_the_file_mode_is_kept(tmp_path: Path) -> None:
    target = tmp_path / "shared.json"
    target.write_text("old")
    os.chmod(target, 0o644)
    atomic_write_bytes(target, b"new")
    assert (target.stat().st_mode & 0o777) == 0o644
    os.chmod(target, 0o640)
    atomic_write_bytes(target, b"newer")
    assert (target.stat().st_mode & 0o777) == 0o640


def test_a_new_file_gets_the_umask_mode_not_0600(tmp_path: Path) -> None:
    old = os.umask(0o022)
    try:
        atomic_write_text(tmp_path / "new.json", "x")
    finally:
        os.umask(old)
    assert ((tmp_path / "new.json").stat().st_mode & 0o777) == 0o644


def test_a_stale_temporary_file_of_a_dead_writer_is_removed_at_the_next_save(tmp_path: Path) -> None:
    stale = tmp_path / f".m.json.{_dead_pid()}.0123abcd{TMP_SUFFIX}"
    stale.write_text("half")
    live = tmp_path / f".m.json.{os.getppid()}.0123abcd{TMP_SUFFIX}"  # a running process's
    live.write_text("being written")
    other = tmp_path / ".notes.tmp"  # not ours: never touched
    other.write_text("x")
    assert stale_temp_files(tmp_path) == [stale]
    atomic_write_text(tmp_path / "m.json", "{}")
    assert not stale.exists()
    assert live.exists() and other.exists()


def test_a_failed_write_leaves_the_old_file_and_no_temporary_file(tmp_path: Path) -> None:
    target = tmp_path / "m.json"
    target.write_text("old")
    with pytest.raises(RuntimeError), atomic_path(target) as tmp:
        tmp.write_text("half")
        raise RuntimeError("killed")
    assert target.read_text() == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.json"]


def test_a_directory_in_the_way_is_an_os_error(tmp_path: Path) -> None:
    (tmp_path / "d").mkdir()
    with pytest.raises(IsADirectoryError):
        atomic_write_text(tmp_path / "d", "x")
