"""A sweep against a Ray cluster of two nodes, started by the test on this machine (`ray start
--head` and a worker node, on the loopback), through `--address`: the same files as the local
backend, from trials that ran on both of the cluster's nodes (each trial notes its node), the
progress bar across the sweep, and a worker that dies mid-task costing only its own trial.
Needs the `ray` extra."""

from __future__ import annotations

import functools
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

pytest.importorskip("ray")

from sweep_helpers import flaky, noting_node  # noqa: E402

from aileen.cli import main  # noqa: E402
from aileen.experiments import ray_backend, sweep  # noqa: E402
from aileen.experiments.grid import parse_grid  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
RAY = str(Path(sys.executable).with_name("ray"))

# 2 points x 3 trials, the first lesson of a visual trial each: 6 trials, cut into tasks of one
# or more for the cluster's 2 CPUs
GRID = """experiment = "visual"
trials = 3
seeds = [0]
perception = "truth"
lessons = 1
[params]
match = [0.5, 0.75]
"""


def _port() -> str:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return str(s.getsockname()[1])


def _node_args() -> list[str]:
    """One CPU, and ports of its own for everything a node listens on (two nodes share the host)."""
    return ["--node-ip-address", "127.0.0.1", "--num-cpus", "1", "--disable-usage-stats",
            "--node-manager-port", _port(), "--object-manager-port", _port(),
            "--dashboard-agent-listen-port", _port(), "--dashboard-agent-grpc-port", _port(),
            "--runtime-env-agent-port", _port(), "--metrics-export-port", _port(), "--block"]


def _descendants(pid: int) -> set[int]:
    """The process and every process below it (read from /proc: the nodes' own processes)."""
    children: dict[int, list[int]] = {}
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                stat = Path(f"/proc/{d}/stat").read_text()
            except OSError:
                continue
            children.setdefault(int(stat.rsplit(")", 1)[1].split()[1]), []).append(int(d))
    out, todo = set(), [pid]
    while todo:
        p = todo.pop()
        out.add(p)
        todo += children.get(p, [])
    return out


def _stop(nodes: list[subprocess.Popen]) -> None:
    """Stop the nodes this test started, and only those: each `ray start --block` is asked to
    end (it stops its node's processes); whatever of theirs still runs after 20 s is killed
    by its process id."""
    pids: set[int] = set()
    for n in nodes:
        pids |= _descendants(n.pid)
    for n in reversed(nodes):
        n.terminate()
    for n in nodes:
        try:
            n.wait(20)
        except subprocess.TimeoutExpired:
            pass
    for p in pids:
        try:
            os.kill(p, signal.SIGKILL)
        except ProcessLookupError:
            pass


@pytest.fixture(scope="module")
def cluster() -> Iterator[str]:
    """The address of a running two-node cluster, 1 CPU a node; its workers import this
    checkout (and tests/, for `sweep_helpers`)."""
    if sys.platform != "linux":
        pytest.skip("the cluster's processes are found through /proc")
    temp = tempfile.mkdtemp(prefix="ray", dir="/tmp")  # short: Ray's socket paths must fit
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), str(ROOT / "tests")]),
           "RAY_AUTH_MODE": "disabled"}  # a throwaway cluster on the loopback
    old_auth = os.environ.get("RAY_AUTH_MODE")
    os.environ["RAY_AUTH_MODE"] = "disabled"  # the driver (this process) alike
    gcs = _port()
    address = f"127.0.0.1:{gcs}"
    log = open(Path(temp) / "nodes.log", "w")  # noqa: SIM115 - closed below
    nodes = [subprocess.Popen([RAY, "start", "--head", "--port", gcs, "--include-dashboard", "false",
                               "--temp-dir", temp, *_node_args()], env=env, stdout=log, stderr=subprocess.STDOUT)]
    try:
        _wait_for(address, 1, env)
        nodes.append(subprocess.Popen([RAY, "start", "--address", address, *_node_args()],
                                      env=env, stdout=log, stderr=subprocess.STDOUT))
        _wait_for(address, 2, env)
        yield address
    finally:
        _stop(nodes)
        log.close()
        shutil.rmtree(temp, ignore_errors=True)
        if old_auth is None:
            os.environ.pop("RAY_AUTH_MODE", None)
        else:
            os.environ["RAY_AUTH_MODE"] = old_auth


def _wait_for(address: str, nodes: int, env: dict, timeout: float = 180.0) -> None:
    """Until `ray status` shows `nodes` nodes with a CPU each (a node takes seconds to start)."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        out = subprocess.run([RAY, "status", "--address", address], env=env, capture_output=True, text=True,
                             timeout=60)
        if out.returncode == 0 and f"0.0/{nodes}.0 CPU" in out.stdout:
            return
        time.sleep(1.0)
    pytest.fail(f"the Ray cluster at {address} did not come up with {nodes} nodes in {timeout:.0f} s")


@pytest.mark.slow  # starts two Ray nodes (10-30 s)
def test_a_sweep_on_a_two_node_cluster_writes_the_local_backends_files(cluster: str, tmp_path, capsys,
                                                                        monkeypatch) -> None:
    import ray

    from aileen.experiments import commands

    monkeypatch.setattr(commands, "_bars", lambda args: not args.quiet)  # as on a terminal: bars go only there
    ran_on = tmp_path / "nodes"  # a file per trial of the Ray sweep: the node that ran it
    ran_on.mkdir()
    # as the cluster's nodes have it, so that a Ray of the sweep's own could run `noting_node` too
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([str(ROOT), str(ROOT / "tests")]))

    local, remote = tmp_path / "local", tmp_path / "ray"
    for out in (local, remote):
        out.mkdir()
        (out / "grid.toml").write_text(GRID)
    assert main(["experiment", "sweep", str(local / "grid.toml"), "--out", str(local), "--no-plot", "--quiet"]) == 0
    capsys.readouterr()
    monkeypatch.setattr(sweep, "run_job", functools.partial(noting_node, str(ran_on)))
    assert main(["experiment", "sweep", str(remote / "grid.toml"), "--out", str(remote), "--no-plot",
                 "--backend", "ray", "--address", cluster]) == 0
    err = capsys.readouterr().err
    assert "6/6" in err  # the progress bar went across the whole sweep
    for name in ("sweep.csv", "sweep-summary.csv"):
        assert (remote / name).read_bytes() == (local / name).read_bytes()
    # the trials ran on the cluster at --address (not on a Ray of the sweep's own), on both its nodes
    ray.init(address=cluster, log_to_driver=False, configure_logging=False)
    try:
        nodes = {n["NodeID"] for n in ray.nodes() if n["Alive"]}
    finally:
        ray.shutdown()
    assert len(nodes) == 2
    assert len(list(ran_on.iterdir())) == 6
    assert {f.read_text() for f in ran_on.iterdir()} == nodes


def _jobs(matches: list[float]) -> list[sweep.Job]:
    grid = parse_grid(f'experiment = "visual"\nperception = "truth"\n[params]\nmatch = {matches}\n')
    return sweep.jobs_of(grid)


@pytest.mark.slow
def test_a_worker_that_dies_costs_its_own_trial_only(cluster: str) -> None:
    # 0.5 raises, 0.6 kills its worker (sweep_helpers.flaky); 18 jobs on 2 CPUs go 3 to a task,
    # so the 0.6 one takes the two others of its task down with it: they must run again and pass
    matches = [0.7, 0.71, 0.72, 0.6, 0.73, 0.74, 0.5, 0.75, 0.76] + [0.8 + i / 100 for i in range(9)]
    jobs = _jobs(matches)
    assert [len(c) for c in ray_backend.chunks(jobs, 2)] == [3] * 6
    done, failed = [], []
    ray_backend.run_jobs(jobs, 1, cluster, flaky, lambda j, r: done.append(r["match"]),
                         lambda j, why: failed.append((j.point.match, why)))
    assert sorted(done) == sorted(repr(m) for m in matches if m not in (0.5, 0.6))
    assert sorted(m for m, _ in failed) == [0.5, 0.6]
    why = dict(failed)
    assert why[0.5] == "RuntimeError: no luck"
    assert why[0.6]  # the worker's death, in Ray's words
