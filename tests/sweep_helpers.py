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
