"""The text of the files an experiment writes: trials.csv, summary.csv, areas.csv (one row
per headline area) and summary.json (every experiment's headline, merged), each written
whole or not at all.

Apart from `results` (the records and the figures made of them) so that a change to a
file's columns is one module's, and so that a reader of the figures need not read the CSV
code. `output` puts an experiment's files in its folder; `plots` draws the curve.
"""

from __future__ import annotations

import csv
import io
import json
import math
from collections.abc import Sequence
from dataclasses import asdict
from pathlib import Path

from aileen.experiments.results import ExperimentResult, Headline
from aileen.io import atomic_write_bytes, atomic_write_text

__all__ = ["AREAS_HEADER", "SUMMARY_HEADER", "TRIALS_HEADER", "areas_csv", "headline_dict", "summary_csv",
           "read_summary_json", "summary_json_text", "trials_csv", "update_summary_json", "write_bytes", "write_text"]


def write_text(path: Path, text: str) -> None:
    """Write via a temporary file and a rename (`aileen.io`), so readers never see half a file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    atomic_write_text(path, text)


def write_bytes(path: Path, data: bytes) -> None:
    """Binary twin of `write_text` (`aileen.io`)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    atomic_write_bytes(path, data)


def _csv(rows: Sequence[Sequence], header: Sequence[str]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    w.writerows(rows)
    return buf.getvalue()


TRIALS_HEADER = ("trial", "lesson", "commands", "generality", "specificity", "oracle", "ideal_generality",
                 "ideal_specificity", "sector_ceiling")
SUMMARY_HEADER = ("lesson", "trials", "commands_mean", "commands_std", "generality_mean", "generality_std",
                  "specificity_mean", "specificity_std", "oracle_mean", "oracle_std", "ceiling_mean", "ceiling_std",
                  "balanced_mean", "ideal_generality_mean", "ideal_specificity_mean")
AREAS_HEADER = ("group", "generality_items", "specificity_items", "area_pct_of_oracle", "specificity_pct",
                "balanced_pct_oracle", "balanced_pct_ideal", "ideal_balanced_pct_oracle", "near_miss_edge_final",
                "ideal_near_miss_edge_final")


def _r(x: float) -> float:
    return round(x, 4)


def _blank(x: float | int) -> float | int | str:
    """A figure for a CSV cell: empty where the protocol has none (nan, -1)."""
    if isinstance(x, float):
        return "" if math.isnan(x) else _r(x)
    return "" if x < 0 else x


def trials_csv(res: ExperimentResult) -> str:
    # sector_ceiling: what an ideal 8-sector learner passes of the generality exam (wide
    # protocol, directions): summary.json's area_pct_of_sector_ceiling is read from it
    rows = [(r.trial + 1, r.lesson, r.commands, r.generality, r.specificity, r.oracle, _blank(r.ideal_generality),
             _blank(r.ideal_specificity), _blank(r.sector_ceiling)) for t in res.trials for r in t.records]
    return _csv(rows, TRIALS_HEADER)


def summary_csv(res: ExperimentResult) -> str:
    rows = [(s.lesson, s.trials, _r(s.commands_mean), _r(s.commands_std), _r(s.generality_mean),
             _r(s.generality_std), _r(s.specificity_mean), _r(s.specificity_std), _r(s.oracle_mean),
             _r(s.oracle_std), _r(s.ceiling_mean), _r(s.ceiling_std), _r(s.balanced_mean),
             _blank(s.ideal_generality_mean), _blank(s.ideal_specificity_mean)) for s in res.summary]
    return _csv(rows, SUMMARY_HEADER)


def areas_csv(res: ExperimentResult) -> str:
    """The headline areas: one row for all the exam items, one per group (the teacher
    protocol's families of words)."""
    h = res.headline
    if h is None:
        return _csv([], AREAS_HEADER)
    edge = [v for k, v in h.near_miss_final.items() if k.startswith("near miss: just outside")]
    ideal_edge = [v for k, v in h.ideal_near_miss_final.items() if k.startswith("near miss: just outside")]
    rows = [("all", h.exam_items[0] * h.trials, h.exam_items[1] * h.trials, _blank(h.area_pct_of_oracle), _blank(h.specificity_pct),
             _blank(h.balanced_pct_oracle), _blank(h.balanced_pct_ideal), _blank(h.ideal_balanced_pct_oracle),
             _blank(edge[0]) if edge else "", _blank(ideal_edge[0]) if ideal_edge else "")]
    for name, f in h.by_family.items():
        rows.append((name,) + tuple(_blank(f[k]) if isinstance(f[k], float) else f[k] for k in AREAS_HEADER[1:]))
    return _csv(rows, AREAS_HEADER)


def headline_dict(h: Headline) -> dict:
    d = asdict(h)
    d["without"] = list(h.without)
    d["exam_items"] = list(h.exam_items)

    def clean(v):  # noqa: ANN001, ANN202
        if isinstance(v, float):
            return None if math.isnan(v) else round(v, 3)
        if isinstance(v, dict):
            return {k: clean(x) for k, x in v.items()}
        return v

    return {k: clean(v) for k, v in d.items()}


def read_summary_json(out: Path) -> tuple[dict, bytes | None]:
    """DIR/summary.json's figures, to merge a run's into; and the file's bytes when it is not
    a summary this command wrote (not valid JSON, not an object): the caller keeps a copy
    (it was replaced without a word). No file: nothing."""
    path = Path(out) / "summary.json"
    try:
        raw = path.read_bytes()
    except FileNotFoundError:
        return {}, None
    try:
        data = json.loads(raw.decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError):
        return {}, raw
    return (data, None) if isinstance(data, dict) else ({}, raw)


def summary_json_text(data: dict) -> str:
    """summary.json's text: sorted keys, indented."""
    return json.dumps(data, indent=2, sort_keys=True) + "\n"


def update_summary_json(out: Path, key: str, value: dict) -> None:
    """Merge one experiment's headline into DIR/summary.json (other experiments' stay)."""
    path = Path(out) / "summary.json"
    data: dict = {}
    if path.exists():
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, json.JSONDecodeError):
            data = {}
        if not isinstance(data, dict):
            data = {}  # not a summary this command wrote ("[1, 2]" was a TypeError): written anew
    data[key] = value
    write_text(path, json.dumps(data, indent=2, sort_keys=True) + "\n")
