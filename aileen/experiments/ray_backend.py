"""Running a sweep's trials as Ray tasks: the one module that imports `ray` (the `ray` extra).

Why: a sweep is hundreds of independent trials, past what one small machine does quickly,
and Ray already schedules tasks over a cluster. Each trial is one task running the same
pure function as the local backend (`sweep.run_job`), so the rows are the same whichever
backend ran them. Without an address a local Ray is started for the run with `workers`
CPUs; with one, the run joins that cluster (whose workers must have aileen installed).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from aileen.errors import UserError


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
    """A clear one-line `UserError` when nothing listens at the cluster's address (Ray itself
    would retry for minutes). `auto` and addresses without a port are left to Ray."""
    import socket

    rest = address.split("://", 1)[-1]
    host, sep, port = rest.rpartition(":")
    if address == "auto" or not sep or not port.isdigit():
        return
    try:
        socket.create_connection((host or "127.0.0.1", int(port)), timeout=timeout).close()
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        raise UserError(f"cannot reach the Ray cluster at {address!r}: {reason.lower()}") from None


def run_jobs(jobs: Sequence, workers: int, address: str | None, func: Callable, on_done: Callable,
             on_fail: Callable) -> None:
    """`func(job)` for every job as a Ray task; `on_done(job, result)` as each finishes,
    `on_fail(job, why)` for a task that raised or whose worker died (the rest go on)."""
    ray = _ray()
    import os

    try:
        if address is None:
            # The workers run this checkout's code: pass its import path on.
            env = {"PYTHONPATH": os.environ["PYTHONPATH"]} if os.environ.get("PYTHONPATH") else {}
            ray.init(num_cpus=workers, include_dashboard=False, log_to_driver=False, configure_logging=False,
                     runtime_env={"env_vars": env} if env else None)
        else:
            ray.init(address=address, log_to_driver=False, configure_logging=False)
    except (ConnectionError, TimeoutError, RuntimeError, ValueError) as exc:
        where = f"the Ray cluster at {address!r}" if address else "a local Ray"
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise UserError(f"cannot start or reach {where}: {first}") from None
    try:
        task = ray.remote(num_cpus=1, max_retries=0)(func)
        refs = {task.remote(j): j for j in jobs}
        pending = list(refs)
        while pending:
            ready, pending = ray.wait(pending, num_returns=1)
            for ref in ready:
                job = refs[ref]
                try:
                    result = ray.get(ref)
                except ray.exceptions.RayTaskError as exc:
                    cause = exc.cause if getattr(exc, "cause", None) is not None else exc
                    on_fail(job, f"{type(cause).__name__}: {cause}".splitlines()[0])
                except ray.exceptions.RayError as exc:  # a worker or node that died
                    on_fail(job, f"{type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}")
                else:
                    on_done(job, result)
    finally:
        ray.shutdown()
