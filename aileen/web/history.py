"""Undo in the console: what each lesson, verdict or forget found, so it can be taken back.

Why a module of its own (split out of `session`): a step is all or nothing, so a lesson that
fails half-way is taken back by the same means as one the trainer undoes; keeping the steps
(bounded, newest last) and putting everything back is one job, apart from giving lessons.
The agent is taken back through `Agent.snapshot`/`restore`; an agent without them cannot
be undone, and a step that cannot be undone ends the reach of undo.
"""

from __future__ import annotations

from dataclasses import dataclass

from aileen.errors import UserError
from aileen.web.table import Placed, TableEdit

UNDO_LESSONS = 10  # lessons (and verdicts, forgets) that can be taken back, newest first


@dataclass
class Step:
    """A lesson, verdict or forget that undo can take back: everything as it was before it."""

    what: str  # the record's signal, or "forget"
    agent: object  # Agent.snapshot()
    table: list[Placed]
    blocks: list[str]
    records: int
    undone: dict | None = None  # what undo reports for a step that has no record (a forget)


def before(what: str, agent: object, table: TableEdit, blocks: list[str], records: list[dict]) -> Step | None:
    """What undo needs to take back the step about to be made (None: this agent cannot
    be snapshotted, so the step cannot be undone)."""
    snap = getattr(agent, "snapshot", None)
    if snap is None:
        return None
    return Step(what, snap(), list(table.objects), list(blocks), len(records))


def back(step: Step | None, agent, table: TableEdit, blocks: list[str], records: list[dict]) -> None:
    """Everything as it was before `step` (a failed step, or an undone one), in place."""
    if step is None:
        return
    agent.restore(step.agent)
    table.restore(step.table)
    blocks[:] = step.blocks
    del records[step.records:]


class History:
    """The steps undo can take back, newest last, at most `UNDO_LESSONS`."""

    def __init__(self) -> None:
        self._steps: list[Step] = []

    @property
    def last(self) -> Step | None:
        return self._steps[-1] if self._steps else None

    def push(self, step: Step | None) -> None:
        if step is None:
            self._steps.clear()  # an older step cannot be undone past one that cannot
            return
        self._steps.append(step)
        del self._steps[:-UNDO_LESSONS]

    def pop(self) -> Step:
        if not self._steps:
            raise UserError("no lesson to undo (undo reaches back over the lessons given since the server "
                            f"started, at most {UNDO_LESSONS})")
        return self._steps.pop()
