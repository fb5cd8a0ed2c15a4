"""Running trials in this process or in a pool of spawned processes: a sweep's (`--backend
local`) and an experiment's (`runner.run_experiment`, the react benchmark).

Why a module of its own: it is the sweep's default backend, beside `ray_backend`, and both
take the same pure trial function (`sweep.run_job`) and report each trial through the same
two callbacks, so a sweep's files do not depend on which one ran it. The experiments' pool
(`shared_pool`, `pool_map`: results in input order, progress sent back from the workers)
came here from `runner` because it is the same job: spawned workers (never forked), OpenCV on
one thread in each (`one_thread`), stopped at once on a stop signal (`stop_on_interrupt`).
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
from collections.abc import Callable, Iterator, Sequence
from typing import Any

__all__ = ["run_local", "stop_on_interrupt", "one_thread", "pool_worker", "shared_pool", "pool_map",
           "HASH_ORDER_SENSITIVE", "fixed_hash_seed"]


def _die_with_parent() -> None:
    """Linux: this process gets SIGTERM when the process that started it ends, however it
    ends. A pool's workers outlived a sweep killed with SIGKILL (120 MB each, adopted by
    init); elsewhere nothing is done."""
    if not sys.platform.startswith("linux"):
        return
    import ctypes

    with contextlib.suppress(OSError, AttributeError):
        ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, int(signal.SIGTERM))  # PR_SET_PDEATHSIG
        if os.getppid() == 1:  # the parent was gone before the call took effect
            os.kill(os.getpid(), signal.SIGTERM)


def pool_worker() -> None:
    """The start of every worker process of a local pool: it ends with the process that
    started it (`_die_with_parent`), leaves Ctrl-C to that process (which stops the pool: a
    Ctrl-C to the terminal's process group printed each worker's traceback), runs OpenCV
    on one thread (`one_thread`) and loads the user's declarations (`AILEEN_DOMAIN`)."""
    _die_with_parent()
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    one_thread()
    from aileen.domain import extensions

    extensions.load()  # the user's declarations, as the process that started it has them


def one_thread() -> None:
    """OpenCV on one thread, in a worker of a pool or a Ray task. The pool's processes are the
    parallelism; OpenCV's own threads (one per core by default) in each of them only contend
    for the same cores. The detector's output does not depend on it."""
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
    with ProcessPoolExecutor(max_workers=min(workers, len(jobs)), mp_context=ctx, initializer=pool_worker) as pool, \
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
        with ProcessPoolExecutor(max_workers=1, mp_context=ctx, initializer=pool_worker) as pool, stop_on_interrupt(pool):
            try:
                row = pool.submit(func, j).result()
            except BrokenProcessPool:
                on_fail(j, "the worker process died")
            except Exception as exc:  # noqa: BLE001
                on_fail(j, f"{type(exc).__name__}: {exc}")
            else:
                on_done(j, row)


_SHARED_POOL: list = []  # the pool `shared_pool` holds open, if any
# Learners whose results depend on the order Python iterates sets of strings (COBWEB in
# concept_formation): their trials always run in worker processes started with a fixed
# PYTHONHASHSEED, so the same seed gives the same numbers in every run and for any --jobs.
HASH_ORDER_SENSITIVE = frozenset({"cobweb", "trestle"})


def fixed_hash_seed() -> None:
    """Spawned workers inherit the environment: fix their string hashing (see above)."""
    os.environ.setdefault("PYTHONHASHSEED", "0")


@contextlib.contextmanager
def shared_pool(jobs: int) -> Iterator[None]:
    """Run every `pool_map` inside on one pool of `jobs` worker processes: `aileen experiment
    all` starts (and loads vision in) its workers once, not once per experiment and baseline,
    and they share what vision saw (`vision_cache`: every learner sees a trial's images)."""
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor

    if jobs <= 1:
        yield
        return
    fixed_hash_seed()
    from aileen.experiments import vision_cache

    with vision_cache.shared(), ProcessPoolExecutor(max_workers=jobs, mp_context=mp.get_context("spawn"),
                                                    initializer=pool_worker) as pool, stop_on_interrupt(pool):
        _SHARED_POOL.append(pool)
        try:
            yield
        finally:
            _SHARED_POOL.remove(pool)


def _manager(ctx):  # noqa: ANN001, ANN202 - a multiprocessing context, its SyncManager
    """A started manager (the progress queue's server process) that ends with this process
    (`_die_with_parent`): one per experiment, they outlived `aileen experiment all` killed
    with SIGKILL, as the pool's workers had."""
    from multiprocessing.managers import SyncManager

    manager = SyncManager(ctx=ctx)
    manager.start(_die_with_parent)
    return manager


def pool_map(func: Callable, jobs_args: Sequence[tuple], jobs: int, bar) -> list:  # noqa: ANN001
    """`func(args + (queue,))` for each args tuple in `jobs` spawned processes, results in
    input order. Workers put what they finished (lessons, react tasks) on the queue; this
    process moves the bar."""
    import multiprocessing as mp
    import queue as queue_mod
    from concurrent.futures import ProcessPoolExecutor, wait

    ctx = mp.get_context("spawn")  # clingo and cv2 hold threads: never fork them
    fixed_hash_seed()
    with contextlib.ExitStack() as stack:
        manager = stack.enter_context(_manager(ctx)) if bar is not None else None
        q = manager.Queue() if manager is not None else None
        pool = _SHARED_POOL[-1] if _SHARED_POOL else stack.enter_context(
            ProcessPoolExecutor(max_workers=min(jobs, len(jobs_args)), mp_context=ctx, initializer=pool_worker))
        if not _SHARED_POOL:  # a stop signal ends our own pool's workers at once
            stack.enter_context(stop_on_interrupt(pool))
        futures = [pool.submit(func, tuple(a) + (q,)) for a in jobs_args]
        if q is None:
            wait(futures)
            return [f.result() for f in futures]
        pending = set(futures)
        while pending:
            pending = {f for f in pending if not f.done()}
            try:
                while True:
                    bar.update(q.get(timeout=0.2))
            except queue_mod.Empty:
                pass
        while not q.empty():
            bar.update(q.get())
        return [f.result() for f in futures]
