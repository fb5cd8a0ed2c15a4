"""Running a sweep's trials as Ray tasks: the one module that imports `ray` (the `ray` extra).

Why: a sweep is hundreds of independent trials, past what one small machine does quickly,
and Ray already schedules tasks over a cluster. Each trial runs the same pure function as
the local backend (`sweep.run_job`), so the rows are the same whichever backend ran them.
Without an address a local Ray is started for the run with `workers` CPUs, without the
autoscaler's monitor and the log monitor (`_start_own_node`); with one, the run joins that
cluster (whose workers must have aileen installed).

A task runs several consecutive trials (`chunks`: about four tasks per CPU, at most 8
trials), so what Ray costs per task is shared by them (issue 25); progress and the appended
sweep.csv move as each task ends.
"""

from __future__ import annotations

import contextlib
import math
import os
from collections.abc import Callable, Iterator, Sequence

from aileen import lifecycle
from aileen.errors import UserError


#: Tasks per worker when a sweep is cut into tasks (`chunks`), and the most trials in one task.
CHUNKS_PER_WORKER = 4
MAX_CHUNK = 8


def _ray():  # noqa: ANN202
    try:
        import ray
    except ImportError:
        raise UserError("--backend ray needs Ray: pip install 'aileen[ray]'") from None
    return ray


def preflight(address: str | None) -> None:
    """Before any trial runs: Ray is installed, and the cluster (if one is named) answers."""
    _ray()
    if address is not None:
        check_reachable(address)


def check_reachable(address: str, timeout: float = 5.0) -> None:
    """A clear one-line `UserError` when the address is no address (`nonsense`: Ray refused it
    only once the local sweeps had run, a traceback in the benchmark) or nothing listens
    there (Ray itself would retry for minutes). `auto`, `local` and a Ray client's
    `ray://HOST` without a port are left to Ray."""
    import socket

    if address in ("auto", "local"):
        return
    client = address.startswith("ray://")
    rest = address.split("://", 1)[-1]
    host, sep, port = rest.rpartition(":")
    if not (sep and port.isdigit()):
        if client and rest:
            return
        raise UserError(f"cannot reach the Ray cluster at {address!r}: expected HOST:PORT (the address "
                        "`ray start --head` printed), ray://HOST:PORT, auto or local")
    try:
        conn = socket.create_connection((host or "127.0.0.1", int(port)), timeout=timeout)
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        raise UserError(f"cannot reach the Ray cluster at {address!r}: {reason.lower()}") from None
    with conn:
        if not _speaks_grpc(conn):
            raise UserError(f"cannot reach the Ray cluster at {address!r}: something answers there, but not "
                            "as a Ray cluster's head (its GCS speaks gRPC); expected the address `ray start "
                            "--head` printed") from None


#: HTTP/2's client preface and an empty SETTINGS frame: what a gRPC client says first.
_H2_PREFACE = b"PRI * HTTP/2.0\r\n\r\nSM\r\n\r\n" + b"\x00\x00\x00\x04\x00\x00\x00\x00\x00"


def _speaks_grpc(conn: "socket.socket") -> bool:
    """Does the server on `conn` answer HTTP/2 (its first frame a SETTINGS frame), as Ray's
    GCS does? Ray itself, given another server's port, retried for minutes (a web server on
    the port kept a sweep waiting past 100 s)."""
    try:
        conn.sendall(_H2_PREFACE)
        head = b""
        while len(head) < 9:
            got = conn.recv(9 - len(head))
            if not got:
                return False
            head += got
    except OSError:
        return False
    return head[3] == 0x04  # the frame's type: SETTINGS


@contextlib.contextmanager
def _absolute_pythonpath() -> Iterator[None]:
    """Within the block, $PYTHONPATH (if set) with every entry made absolute."""
    old = os.environ.get("PYTHONPATH")
    if old:
        os.environ["PYTHONPATH"] = os.pathsep.join(os.path.abspath(p) if p else p for p in old.split(os.pathsep))
    try:
        yield
    finally:
        if old:
            os.environ["PYTHONPATH"] = old


def chunks(jobs: Sequence, workers: int, per_worker: int = CHUNKS_PER_WORKER) -> list[list]:
    """The jobs cut into runs of consecutive jobs, one Ray task each: about `per_worker`
    tasks per worker (so a slow one does not leave the others idle at the end), never more
    than `MAX_CHUNK` trials in one (so a worker that dies takes few down with it)."""
    n = len(jobs)
    if n == 0:
        return []
    size = max(1, min(MAX_CHUNK, math.ceil(n / (max(1, workers) * per_worker))))
    return [list(jobs[i : i + size]) for i in range(0, n, size)]


def _run_chunk(func: Callable, jobs: Sequence) -> list[tuple[bool, object]]:
    """In a Ray worker: `func(job)` for each job in turn, [(True, result) or (False, why)],
    so a trial that raises does not stop the others. A task holds one CPU: OpenCV runs on
    one thread (`local_backend.one_thread`), as in the local pool."""
    from aileen.domain import extensions
    from aileen.experiments.local_backend import one_thread

    one_thread()
    extensions.load()  # the user's declarations (`AILEEN_DOMAIN`: a local Ray's workers inherit it)
    out: list[tuple[bool, object]] = []
    for job in jobs:
        try:
            out.append((True, func(job)))
        except Exception as exc:  # noqa: BLE001 - reported with its trial, the chunk goes on
            out.append((False, f"{type(exc).__name__}: {exc}".splitlines()[0]))
    return out


def run_jobs(jobs: Sequence, workers: int, address: str | None, func: Callable, on_done: Callable,
             on_fail: Callable) -> None:
    """`func(job)` for every job on Ray, several consecutive jobs to a task (`chunks`);
    `on_done(job, result)` for each trial of a task as the task finishes, `on_fail(job,
    why)` for a trial that raised. The trials of a task whose worker or node died are run
    again, each as a task of its own, and one that dies again is reported.

    (Tasks return their trials' rows at their end: a Ray generator streaming them one by
    one was tried, and a `ray.wait` on a finished generator did not always return.)"""
    ray = _ray()
    own, workers = _connect(ray, address, workers)
    lifecycle.reclaim()  # Ray's driver took SIGTERM for itself: a stop is aileen's again (saves, exit 143)
    try:
        task = ray.remote(num_cpus=1, max_retries=0)(_run_chunk)
        lost = _run_parts(ray, task, chunks(jobs, workers), func, on_done, on_fail)
        # alone, each in a task of its own: the one that took its worker down shows again
        for job, why in _run_parts(ray, task, [[j] for j, _ in lost], func, on_done, on_fail):
            on_fail(job, why)
    finally:
        ray.shutdown()
        _stop_own_node(own)


def _connect(ray, address: str | None, workers: int) -> tuple[object, int]:  # noqa: ANN001 - the ray module
    """Connect this process to Ray: the cluster at `address`, or one started here for the sweep
    (`_start_own_node`). Returns the node started here (None otherwise) and the CPUs to cut
    the sweep for. Whatever stops it half way (a refusal, a stop signal) stops the node too."""
    own = None
    try:
        if address is None:
            # The workers run this checkout's code: the local Ray started here (and its workers)
            # inherit this process's environment, its import path made absolute. (A runtime_env
            # saying so instead keeps Ray's pre-started workers idle and starts others for the
            # first tasks: about a second more per worker.)
            with _absolute_pythonpath():
                own = _start_own_node(workers)
                if own is None:  # a Ray whose internals differ: its own start, every process
                    ray.init(num_cpus=workers, include_dashboard=False, log_to_driver=False,
                             configure_logging=False)
                else:
                    ray.init(address=own.address, log_to_driver=False, configure_logging=False)
        else:
            ray.init(address=address, log_to_driver=False, configure_logging=False)
            workers = max(1, int(ray.cluster_resources().get("CPU", workers)))  # cut for the whole cluster
    except BaseException as exc:
        _stop_own_node(own)
        if not isinstance(exc, (ConnectionError, TimeoutError, RuntimeError, ValueError)):
            raise
        where = f"the Ray cluster at {address!r}" if address else "a local Ray"
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise UserError(f"cannot start or reach {where}: {first}") from None
    return own, workers


def _start_own_node(workers: int):  # noqa: ANN202 - a ray._private.node.Node, or None
    """A one-machine Ray for this sweep alone, started as `ray.init()` starts one but without
    the two processes such a Ray never uses, or None where this Ray's internals differ (then
    `ray.init` starts its own, every process).

    Why (issue 25): a sweep that started its own Ray cost 1.5-2.7x the local pool, nearly all
    of it Ray's start and stop. `ray.init` always starts the autoscaler's monitor (a fixed
    node has nothing to scale) and the log monitor (which streams workers' output to the
    driver: `log_to_driver=False` here), two more Python processes importing Ray while the
    two cores start the rest; and at `ray.shutdown` the monitor, asleep between its rounds,
    did not answer SIGTERM within Ray's one-second grace: every stop waited 1.0 s on it.
    The rest is `ray.init`'s own head start: token authentication as it would set it up, no
    usage statistics, the node's CPUs `workers`, no dashboard."""
    try:
        from ray._common.usage import usage_lib
        from ray._private.authentication.authentication_token_setup import (
            enable_token_auth_by_default,
            ensure_token_if_auth_enabled,
        )
        from ray._private.node import Node
        from ray._private.parameter import RayParams
    except ImportError:
        return None
    try:
        params = RayParams(num_cpus=workers, include_dashboard=False, no_monitor=True, include_log_monitor=False)
    except TypeError:
        return None
    import logging

    logging.getLogger("ray").handlers.clear()  # what ray.init(configure_logging=False) does, done first
    enable_token_auth_by_default()  # what `ray.init` does before it starts a cluster of its own
    ensure_token_if_auth_enabled({}, create_token_if_missing=True)
    usage_lib.set_usage_stats_enabled_via_env_var(False)
    return Node(params, head=True, shutdown_at_exit=False, spawn_reaper=True, ray_init_cluster=True)


def _stop_own_node(node) -> None:  # noqa: ANN001 - a ray._private.node.Node, or None
    """Stop the node `_start_own_node` started, as `ray.shutdown` stops the one `ray.init`
    started (the driver disconnected first: `ray.shutdown`)."""
    if node is not None:
        node.destroy_external_storage()  # objects spilled to disk, if any
        node.kill_all_processes(check_alive=False, allow_graceful=True)


def _run_parts(ray, task, parts: list[list], func: Callable, on_done: Callable,  # noqa: ANN001
               on_fail: Callable) -> list[tuple[object, str]]:
    """Run each part as one task, reporting its trials as each task ends. Returns (job, why)
    for the trials of tasks that broke off (their worker or node died)."""
    refs = {task.remote(func, part): k for k, part in enumerate(parts)}
    lost: list[tuple[object, str]] = []
    pending = list(refs)
    while pending:
        ready, pending = ray.wait(pending, num_returns=1)
        for ref in ready:
            part = parts[refs[ref]]
            try:
                results = ray.get(ref)
            except ray.exceptions.RayError as exc:  # the worker or node died mid-task
                cause = exc.cause if getattr(exc, "cause", None) is not None else exc
                text = str(cause).strip()
                why = f"{type(cause).__name__}: {text.splitlines()[0] if text else ''}"
                lost += [(job, why) for job in part]
                continue
            for job, (ok, value) in zip(part, results, strict=True):
                (on_done if ok else on_fail)(job, value)
    return lost
