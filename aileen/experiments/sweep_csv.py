"""sweep.csv: its columns, its rows read (an older file's upgraded to today's columns) and
appended as trials finish; one module so that the sweep itself (`sweep.py`) is the grid, the
jobs and the summaries, and the file's versions live in one place.

Why its own module: the file outlives the code that wrote it (a sweep stopped and resumed with
a newer aileen, a folder of an earlier stop's sweep), so each version's header is declared
here, with how its rows gain today's columns.
"""

from __future__ import annotations

import csv
import io
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from aileen.errors import UserError
from aileen.experiments.grid import PARAMS, SWEEP_PROTOCOL

__all__ = ["AXES", "HEADER", "HEADER_BEFORE_BALANCED", "HEADER_BEFORE_PROTOCOL", "KEY", "SUMMARY_HEADER",
           "Appender", "balanced", "csv_text", "first_line", "fmt", "read_rows", "row_key"]

#: Columns of sweep.csv: the axes, the job, then the figures.
AXES = ("experiment", "protocol", "without") + PARAMS
HEADER: tuple[str, ...] = AXES + ("perception", "lessons", "seed", "trial", "area_pct_oracle", "commands",
                                  "min_specificity", "final_generality", "generality_sum", "oracle_sum",
                                  "generality", "specificity", "balanced_pct_oracle", "exam_items")
SUMMARY_HEADER: tuple[str, ...] = AXES + ("trials", "area_pct_oracle", "commands_per_trial",
                                          "lowest_specificity", "final_generality", "balanced_pct_oracle")
KEY = AXES + ("perception", "lessons", "seed", "trial")
#: sweep.csv before the balanced area (stop 46) and before the protocol became an axis (stop
#: 45): read (an old row's exam sizes are its protocol's, its protocol the paper's when it has
#: none), and written again in today's columns before anything is appended to it.
HEADER_BEFORE_BALANCED: tuple[str, ...] = HEADER[:-2]
HEADER_BEFORE_PROTOCOL: tuple[str, ...] = tuple(h for h in HEADER_BEFORE_BALANCED if h != "protocol")


def fmt(x: float) -> str:
    return repr(round(float(x), 4))


def balanced(g: float, s: float, o: float, n_gen: int, n_spec: int) -> float:
    """The balanced curve area, % of the one-shot oracle's (`results.Areas.pct_oracle`): the
    headline, generality and specificity together, from sums over lessons (and trials) and
    the items they asked."""
    from aileen.experiments.results import Areas

    if not (n_gen and n_spec):
        return float("nan")
    return Areas(g / n_gen, s / n_spec, o / n_gen).pct_oracle()


def _exam_items_of_old_row(row: dict) -> tuple[int, int]:
    """An older row's exam sizes: its protocol's (the teacher's 12 and 12, every other 5 and 5)."""
    from aileen.experiments import results, teacher

    if row["protocol"] == "teacher":
        return teacher.GEN_ITEMS, teacher.SPEC_ITEMS
    return results.EXAM_ITEMS, results.EXAM_ITEMS


def _upgraded(row: dict) -> dict:
    """A row of an older sweep.csv with today's columns."""
    ng, ns = _exam_items_of_old_row(row)
    lessons = len(row["generality"].split())
    spec = sum(int(x) for x in row["specificity"].split())
    bal = balanced(int(row["generality_sum"]), spec, int(row["oracle_sum"]), ng * lessons, ns * lessons)
    return {**row, "balanced_pct_oracle": fmt(bal), "exam_items": f"{ng} {ns}"}


def row_key(row: dict) -> tuple:
    """A row's identity, with the numbers compared as numbers (0.6 == 0.60)."""
    out = []
    for k in KEY:
        v = row[k]
        out.append(float(v) if k in PARAMS else v)
    return tuple(out)


# --------------------------------------------------------------------------- the CSV

def read_rows(path: Path) -> list[dict]:
    """The rows of an existing sweep.csv (to resume); a foreign header is a `UserError`."""
    if not path.exists():
        return []
    with path.open(newline="", encoding="utf-8") as fh:
        reader = csv.DictReader(fh)
        if reader.fieldnames is None:
            return []
        before_protocol = tuple(reader.fieldnames) == HEADER_BEFORE_PROTOCOL
        before_balanced = before_protocol or tuple(reader.fieldnames) == HEADER_BEFORE_BALANCED
        if tuple(reader.fieldnames) != HEADER and not before_balanced:
            raise UserError("not a sweep.csv of this version (its columns differ); use another --out",
                            path=str(path), line=1)
        rows = []
        seen: set[tuple] = set()
        for row in reader:
            if None in row or any(v is None for v in row.values()):
                continue  # a line cut short when a run was stopped: that trial runs again
            if before_protocol:
                row = {**row, "protocol": SWEEP_PROTOCOL}
            if before_balanced:
                try:
                    row = _upgraded(row)
                except (ValueError, KeyError):
                    continue  # a row that cannot be read: that trial runs again
            try:
                key = row_key(row)
                _numbers(row)
            except (ValueError, KeyError):
                continue  # a damaged value ("x" for a sum): that trial runs again (it was a traceback)
            if key in seen:
                continue  # one trial written twice (two sweeps into one folder): counted once
            seen.add(key)
            rows.append(row)
        return rows


def _numbers(row: dict) -> None:
    """A `ValueError` where a count the summary adds up is not a whole number."""
    int(row["generality_sum"]), int(row["oracle_sum"])
    [int(x) for x in (*row["specificity"].split(), *row["exam_items"].split())]


def csv_text(rows: Sequence[dict], header: Sequence[str]) -> str:
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=list(header), lineterminator="\n")
    w.writeheader()
    w.writerows(rows)
    return buf.getvalue()


def first_line(path: Path) -> str:
    with path.open(encoding="utf-8") as fh:
        return fh.readline().rstrip("\n")


def _ends_with_newline(path: Path) -> bool:
    """Does the file's last byte end a line? (Read alone: a sweep.csv grows with every trial.)"""
    with path.open("rb") as fh:
        fh.seek(0, io.SEEK_END)
        if fh.tell() == 0:
            return True
        fh.seek(-1, io.SEEK_END)
        return fh.read(1) == b"\n"


class Appender:
    """Appends rows to sweep.csv as trials finish, flushed, so a stopped sweep keeps them.

    The file is opened at the first row, not before: a sweep refused before any trial
    finished (a Ray that would not start) left a sweep.csv of its header alone."""

    def __init__(self, path: Path, existing: bool) -> None:
        self.path, self.existing = path, existing
        self.fh: Any = None
        self.w: Any = None

    def _open(self) -> None:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        cut = self.existing and not _ends_with_newline(self.path)  # a run stopped mid-line
        self.fh = self.path.open("a", newline="", encoding="utf-8")
        if cut:
            self.fh.write("\n")  # the next row on a line of its own (the cut one is skipped on reading)
        self.w = csv.DictWriter(self.fh, fieldnames=list(HEADER), lineterminator="\n")
        if not self.existing:
            self.w.writeheader()

    def add(self, row: dict) -> None:
        if self.fh is None:
            self._open()
        self.w.writerow(row)
        self.fh.flush()

    def close(self) -> None:
        if self.fh is not None:
            self.fh.close()


