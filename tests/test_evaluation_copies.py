"""docs/evaluation/'s copies of the paper protocol's run are of today's files: they lacked the
balanced headline (summary.json's balanced_pct_oracle, summary.csv's balanced_mean) and said
8.0 commands per spatial trial where README says 14.5."""

from __future__ import annotations

import csv
import json
from pathlib import Path

from aileen.experiments import tables

EVAL = Path(__file__).resolve().parent.parent / "docs" / "evaluation"


def test_the_paper_protocols_copies_have_todays_columns() -> None:
    data = json.loads((EVAL / "summary.json").read_text())
    for name in ("visual", "spatial", "action"):
        with (EVAL / f"{name}-summary.csv").open(newline="") as fh:
            assert tuple(next(csv.reader(fh))) == tables.SUMMARY_HEADER, name
        assert data[name]["protocol"] == "paper" and data[name]["balanced_pct_oracle"] is not None, name
    # README's figure: the spatial row's "commands per trial" (the paper protocol's)
    readme = (EVAL.parent.parent / "README.md").read_text().splitlines()
    row = next(line for line in readme if line.startswith("| spatial (10 trials) |"))
    assert data["spatial"]["commands_per_trial"] == float(row.split("|")[5].split()[0])
