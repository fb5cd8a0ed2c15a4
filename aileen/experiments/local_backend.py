"""Running a sweep's trials in this process or in a pool of spawned processes (`--backend local`).

Why a module of its own: it is the sweep's default backend, beside `ray_backend`, and both
take the same pure trial function (`sweep.run_job`) and report each trial through the same
two callbacks, so a sweep's files do not depend on which one ran it.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator, Sequence
from typing import Any

__all__ = ["run_local", "stop_on_interrupt", "one_thread"]


def one_thread() -> None:
    """The start of every worker process of a pool: OpenCV on one thread. The pool's
    processes are the parallelism; OpenCV's own threads (one per core by default) in each of
    them only contend for the same cores. The detector's output does not depend on it."""
    try:
        import cv2
    except ImportError:  # pragma: no cover - cv2 is a dependency
        return
    cv2.setNumThreads(1)


@contextlib.contextmanager
def stop_on_interrupt(pool: Any) -> Iterator[Any]:
    """On a stop signal (Ctrl-C, SIGTERM, ...: a `KeyboardInterrupt`) inside the block, the
    pool's queued jobs never start and its running workers are ended, so the command stops at
    once instead of after every trial (a pool's own exit waits for them all). A trial cut short
    wrote nothing; a resumed sweep runs it again."""
    try:
        yield pool
    except KeyboardInterrupt:
        workers = list((getattr(pool, "_processes", None) or {}).values())
        pool.shutdown(wait=False, cancel_futures=True)
        for w in workers:
            with contextlib.suppress(Exception):
                w.terminate()
        raise


def run_local(jobs: Sequence[Any], workers: int, func: Callable[[Any], dict],
              on_done: Callable[[Any, dict], None], on_fail: Callable[[Any, str], None]) -> None:
    """`func(job)` for every job, in this process (workers == 1) or in `workers` spawned
    processes; `on_done(job, row)` as each finishes. A trial that raises is reported through
    `on_fail(job, why)` and the rest go on; a worker process that dies breaks the pool, so the
    trials it took down are run again one at a time, each in a fresh process, and the one
    that dies again is reported."""
    if workers == 1:
        for j in jobs:
            try:
                row = func(j)
            except Exception as exc:  # noqa: BLE001 - reported with its trial, the sweep goes on
                on_fail(j, f"{type(exc).__name__}: {exc}")
            else:
                on_done(j, row)
        return
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor, as_completed
    from concurrent.futures.process import BrokenProcessPool

    ctx = mp.get_context("spawn")  # clingo and cv2 hold threads: never fork them
    broken: list[Any] = []
    with ProcessPoolExecutor(max_workers=min(workers, len(jobs)), mp_context=ctx, initializer=one_thread) as pool, \
            stop_on_interrupt(pool):
        futures = {pool.submit(func, j): j for j in jobs}
        for f in as_completed(futures):
            j = futures[f]
            try:
                row = f.result()
            except BrokenProcessPool:
                broken.append(j)
            except Exception as exc:  # noqa: BLE001
                on_fail(j, f"{type(exc).__name__}: {exc}")
            else:
                on_done(j, row)
    for j in sorted(broken, key=jobs.index):
        with ProcessPoolExecutor(max_workers=1, mp_context=ctx, initializer=one_thread) as pool, stop_on_interrupt(pool):
            try:
                row = pool.submit(func, j).result()
            except BrokenProcessPool:
                on_fail(j, "the worker process died")
            except Exception as exc:  # noqa: BLE001
                on_fail(j, f"{type(exc).__name__}: {exc}")
            else:
                on_done(j, row)
