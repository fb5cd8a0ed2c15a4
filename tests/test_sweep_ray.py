"""The Ray backend gives the same result files as the local one (Ray started locally for the
run, as `--backend ray` without `--address` does). Needs the `ray` extra."""

from __future__ import annotations

import pytest

pytest.importorskip("ray")

from aileen.errors import UserError  # noqa: E402
from aileen.experiments import sweep  # noqa: E402
from aileen.experiments.grid import load_grid  # noqa: E402

# A 2 x 1 grid, one trial each, the smallest protocol: the first lesson of a visual trial.
GRID = """experiment = "visual"
trials = 1
seeds = [0]
perception = "truth"
lessons = 1
[params]
assimilation = [0.01, 0.6]
match = [0.75]
"""


@pytest.mark.slow  # starts a local Ray (a few seconds on an idle machine)
def test_ray_and_local_backends_write_identical_files(tmp_path) -> None:
    files = {}
    for backend, jobs in (("local", 1), ("ray", 2)):
        out = tmp_path / backend
        out.mkdir()
        (out / "grid.toml").write_text(GRID)
        rep = sweep.run_sweep(load_grid(out / "grid.toml"), out, backend=backend, jobs=jobs, plot=False)
        assert rep.ran == 2 and not rep.failures, rep.failures
        files[backend] = [(out / n).read_bytes() for n in ("sweep.csv", "sweep-summary.csv")]
    assert files["ray"] == files["local"]
    assert files["local"][0].count(b"\n") == 3  # header + 2 trials


def test_an_unreachable_cluster_is_one_clear_error(tmp_path) -> None:
    (tmp_path / "grid.toml").write_text(GRID)
    with pytest.raises(UserError, match="cannot reach the Ray cluster at '127.0.0.1:1'"):
        sweep.run_sweep(load_grid(tmp_path / "grid.toml"), tmp_path, backend="ray", address="127.0.0.1:1",
                        plot=False)
    assert not (tmp_path / "sweep.csv").exists()  # nothing ran


@pytest.mark.slow  # starts a local Ray and runs trials until a stop
def test_a_stop_during_a_ray_sweep_keeps_the_rows_and_says_so(tmp_path) -> None:
    """Ray's driver answers SIGTERM with a crash report and exit status 134 (abort); aileen
    takes the stop signals back after starting Ray: one line, exit 143, finished rows kept."""
    import os
    import signal
    import subprocess
    import sys
    import time

    grid = tmp_path / "grid.toml"
    grid.write_text(GRID.replace("trials = 1", "trials = 16").replace("lessons = 1", "lessons = 24"))
    out = tmp_path / "out"
    env = {**os.environ, "RAY_AUTH_MODE": "disabled"}
    proc = subprocess.Popen([sys.executable, "-m", "aileen", "experiment", "sweep", str(grid), "--out", str(out),
                             "--backend", "ray", "--jobs", "2", "--quiet"], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=env)
    csv_path = out / "sweep.csv"
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and proc.poll() is None:
        if csv_path.exists() and csv_path.read_text().count("\n") >= 2:  # a trial has finished
            break
        time.sleep(0.2)
    assert proc.poll() is None, proc.communicate()
    proc.send_signal(signal.SIGTERM)
    _out, err = proc.communicate(timeout=60)
    assert proc.returncode == 143, err[-3000:]
    assert "aileen: stopped by SIGTERM" in err and "SIGTERM received" not in err
    assert csv_path.read_text().count("\n") >= 2


def _children() -> dict[int, str]:
    """This process's child processes, pid -> command line (read from /proc)."""
    import os
    from pathlib import Path

    out = {}
    for d in Path("/proc").iterdir():
        if not d.name.isdigit():
            continue
        try:
            if int((d / "stat").read_text().rsplit(")", 1)[1].split()[1]) == os.getpid():
                out[int(d.name)] = (d / "cmdline").read_bytes().replace(b"\0", b" ").decode()
        except (OSError, ValueError):
            continue
    return out


@pytest.mark.slow  # starts a local Ray
def test_a_sweeps_own_ray_starts_no_process_it_never_uses_and_leaves_none() -> None:
    """A sweep's own Ray (no --address) runs without the autoscaler's monitor (one fixed node)
    and the log monitor (workers' output is not sent to the driver): each was another Python
    process importing Ray on the cores the start needs, and the monitor held every stop for
    Ray's one-second grace. Everything it started has ended when the sweep returns."""
    import os
    import sys

    from aileen.experiments import ray_backend

    if sys.platform != "linux":
        pytest.skip("the processes are read from /proc")
    seen: dict[int, str] = {}
    done: list[int] = []
    # children from before the sweep are not its own (an earlier test's local pool leaves
    # multiprocessing's resource tracker running for the rest of the session)
    before = set(_children())

    def on_done(job: int, result: int) -> None:  # in this process, while Ray runs
        done.append(result)
        seen.update((pid, args) for pid, args in _children().items() if pid not in before)

    ray_backend.run_jobs([-1, -2, -3], 2, None, abs, on_done, lambda job, why: pytest.fail(why))
    assert sorted(done) == [1, 2, 3]
    names = " | ".join(seen.values())
    assert "gcs_server" in names and "raylet" in names  # the node's processes were seen
    # neither ray/autoscaler/_private/monitor.py nor ray/_private/log_monitor.py
    assert sorted({w for a in seen.values() for w in a.split() if w.endswith("monitor.py")}) == []
    alive = []
    for pid in seen:
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            continue
        if pid in _children():  # (a pid taken again by an unrelated process is not ours)
            alive.append(seen[pid])
    assert not alive
