"""A pool's workers end with the process that started them, however it ends (SIGKILL too)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pytest

SCRIPT = """
import multiprocessing as mp, os, sys, time
from concurrent.futures import ProcessPoolExecutor
from aileen.experiments.local_backend import pool_worker

def pid_then_wait(_):
    return os.getpid()

if __name__ == "__main__":
    pool = ProcessPoolExecutor(max_workers=1, mp_context=mp.get_context("spawn"), initializer=pool_worker)
    print(pool.submit(pid_then_wait, 0).result(), flush=True)
    time.sleep(60)
"""


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    return True


MANAGER_SCRIPT = """
import multiprocessing as mp, time
from aileen.experiments.local_backend import _manager

if __name__ == "__main__":
    manager = _manager(mp.get_context("spawn"))
    print(manager._process.pid, flush=True)
    time.sleep(60)
"""


def _ends_with_its_parent(script_text: str, tmp_path) -> bool:
    """Run `script_text` (it prints the pid of a process it started, then waits), kill it with
    SIGKILL, and say whether that process ended within 10 s."""
    script = tmp_path / "parent.py"
    script.write_text(script_text)
    proc = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True)
    assert proc.stdout is not None
    child = int(proc.stdout.readline())
    assert _alive(child)
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=10)
    deadline = time.monotonic() + 10
    while _alive(child) and time.monotonic() < deadline:
        time.sleep(0.1)
    return not _alive(child)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="PR_SET_PDEATHSIG is Linux's")
@pytest.mark.parametrize("script_text", [SCRIPT, MANAGER_SCRIPT], ids=["pool-worker", "progress-manager"])
def test_a_process_a_run_starts_ends_when_the_run_is_killed(tmp_path, script_text: str) -> None:
    # a pool's workers (120 MB each) outlived a sweep killed with SIGKILL; the progress queues'
    # managers, one per experiment, outlived `aileen experiment all --jobs 2` the same way
    assert _ends_with_its_parent(script_text, tmp_path)
