"""An experiment's folder: its trials, summary and areas as CSV, and its learning curve.

The records and their text are `results`', the curve is `plots`'; this module puts them in
one folder per experiment (`aileen experiment ...`).
"""

from __future__ import annotations

from pathlib import Path

from aileen.experiments import plots
from aileen.experiments.results import ExperimentResult
from aileen.experiments.tables import areas_csv, summary_csv, trials_csv, write_text

__all__ = ["write_experiment", "out_folder"]


def out_folder(out: str) -> Path:
    """`--out` as a folder that exists, made when missing; a file there, or a path no folder
    can be made at, is a one-line `UserError` (not a traceback)."""
    from aileen.errors import UserError

    if not out:  # ('' wrote summary.json and the experiments' folders into the current folder)
        raise UserError("--out: expected a folder, got an empty name")
    path = Path(out)
    if path.exists() and not path.is_dir():
        raise UserError(f"--out {out!r}: expected a folder, found a file")
    if (path / "summary.json").is_dir():  # (found only once every trial had run)
        raise UserError(f"--out {out!r}: its summary.json is a folder; expected a file, or none")
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise UserError(f"--out {out!r}: cannot create the folder ({exc.strerror or type(exc).__name__})") from None
    return path


#: What `write_experiment` writes in an experiment's folder, and so may take away again.
_OWN_CSVS = ("trials.csv", "summary.csv", "areas.csv")


def _drop_stale(d: Path, *, plot: bool, baselines: set[str]) -> None:
    """An earlier run's files in the folder that this run does not write again (its plot, a
    baseline's CSVs): left there, they disagreed with the CSVs beside them (a seed-0 curve
    beside seed-5 figures). Only files of these names go; anything else stays."""
    if not plot:
        (d / "curve.png").unlink(missing_ok=True)
    for sub in sorted((d / "baselines").glob("*")) if (d / "baselines").is_dir() else ():
        if sub.is_dir() and sub.name not in baselines:
            for f in _OWN_CSVS:
                (sub / f).unlink(missing_ok=True)
            if not any(sub.iterdir()):
                sub.rmdir()
    if (d / "baselines").is_dir() and not any((d / "baselines").iterdir()):
        (d / "baselines").rmdir()


def write_experiment(res: ExperimentResult, out: Path, *, plot: bool = True,
                     baselines: "dict[str, ExperimentResult] | None" = None, name: str | None = None) -> list[str]:
    """DIR/<experiment>/trials.csv, summary.csv, areas.csv and curve.png (with the baselines'
    curves); each baseline's CSVs under DIR/<experiment>/baselines/<name>/. `name` replaces
    <experiment> (`aileen experiment all` writes the teacher protocol's spatial experiment as
    `teacher-spatial`). Returns notes for the user (e.g. why there is no plot)."""
    d = Path(out) / (name or res.experiment)
    _drop_stale(d, plot=plot, baselines=set(baselines or {}))
    write_text(d / "trials.csv", trials_csv(res))
    write_text(d / "summary.csv", summary_csv(res))
    write_text(d / "areas.csv", areas_csv(res))
    for bname, other in (baselines or {}).items():
        write_text(d / "baselines" / bname / "trials.csv", trials_csv(other))
        write_text(d / "baselines" / bname / "summary.csv", summary_csv(other))
        write_text(d / "baselines" / bname / "areas.csv", areas_csv(other))
    notes: list[str] = []
    if plot:
        notes += plots.plot_curve(res, d / "curve.png", baselines=baselines)
    return notes
