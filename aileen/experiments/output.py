"""An experiment's folder: its trials, summary and areas as CSV, and its learning curve.

The records and their text are `results`', the curve is `plots`'; this module puts them in
one folder per experiment (`aileen experiment ...`).
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterable
from pathlib import Path

from aileen.errors import UserError
from aileen.experiments import plots
from aileen.experiments.results import ExperimentResult
from aileen.experiments.tables import areas_csv, summary_csv, trials_csv, write_text

__all__ = ["write_experiment", "out_folder", "experiment_paths", "check_writable"]


def out_folder(out: str) -> Path:
    """`--out` as a folder that exists, made when missing; a file there, or a path no folder
    can be made at, is a one-line `UserError` (not a traceback)."""
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


def experiment_paths(out: Path, name: str, *, plot: bool, baselines: Iterable[str] = ()) -> list[Path]:
    """Every file `write_experiment` writes for one experiment (for `check_writable`)."""
    d = Path(out) / name
    paths = [d / f for f in _OWN_CSVS] + ([d / "curve.png"] if plot else [])
    return paths + [d / "baselines" / b / f for b in baselines for f in _OWN_CSVS]


def check_writable(paths: Iterable[Path]) -> None:
    """Refuse, before any work, a run whose files cannot be written: a file where one of their
    folders goes, a folder where one of them goes, or a folder nothing can be created in (tried:
    a probe file made and removed). A `UserError` naming the path; the check came only after
    every trial had run, as a traceback. Nothing is created but the probe."""
    probed: set[Path] = set()
    for path in paths:
        if path.is_dir():
            raise UserError(f"cannot write {str(path)!r}: it is a folder; expected a file there, or none")
        for folder in path.parents:
            if folder.is_dir():
                break
            if folder.exists() or folder.is_symlink():
                raise UserError(f"cannot write {str(path)!r}: {str(folder)!r} is a file; expected a folder there")
        else:  # (a relative path: the current folder)
            folder = Path(".")
        if folder in probed:
            continue
        try:
            fd, probe = tempfile.mkstemp(dir=folder, prefix=".aileen-probe-")
            os.close(fd)
            os.unlink(probe)
        except OSError as exc:
            raise UserError(f"cannot write {str(path)!r}: nothing can be created in {str(folder)!r} "
                            f"({exc.strerror or type(exc).__name__})") from None
        probed.add(folder)


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
