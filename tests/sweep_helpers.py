"""A trial function for the sweep's failure tests, in a module light enough for spawned workers
to import (they load it by name to unpickle it)."""

from __future__ import annotations

import os


def flaky(job) -> dict:  # noqa: ANN001 - a sweep.Job
    """match 0.5 raises; match 0.6 kills its process; any other match gives a row."""
    if job.point.match == 0.5:
        raise RuntimeError("no luck")
    if job.point.match == 0.6:
        os._exit(3)
    return {"match": repr(job.point.match)}


def noting_node(folder: str, job) -> dict:  # noqa: ANN001 - a sweep.Job
    """`sweep.run_job`, noting in `folder` (a file per trial) the id of the Ray node that ran
    it: which cluster, and which of its nodes, a sweep's trials ran on."""
    from pathlib import Path

    import ray

    from aileen.experiments.sweep import run_job

    row = run_job(job)
    Path(folder, f"{job.point.match}-{job.trial}").write_text(ray.get_runtime_context().get_node_id())
    return row
