"""An experiment's folder: its trials, summary and areas as CSV, and its learning curve.

The records and their text are `results`', the curve is `plots`'; this module puts them in
one folder per experiment (`aileen experiment ...`).
"""

from __future__ import annotations

import contextlib
import os
import secrets
import sys
import tempfile
from collections.abc import Iterable, Iterator
from pathlib import Path

from aileen.errors import UserError
from aileen.experiments import plots
from aileen.experiments.results import ExperimentResult
from aileen.experiments.tables import areas_csv, summary_csv, trials_csv
from aileen.io import TMP_SUFFIX, mode_for, resolve_target

#: What a run that could not write its files says it left: the line's end.
UNTOUCHED = "nothing of this run was written; the files there are as before"


class Batch:
    """The files of one run, replaced together or not at all. A write error (summary.json
    unwritable) left the new CSVs beside the old summary.json, and the old plot deleted: now
    every file is written to a temporary name first, the old ones are moved aside, the new
    ones renamed in, and only then the old ones (and the stale files `drop` names) removed;
    on an error everything is put back and the temporaries removed."""

    def __init__(self) -> None:
        self.files: dict[Path, bytes] = {}
        self.gone: list[Path] = []

    def put(self, path: Path, data: bytes | str) -> None:
        """Write `path` at `commit` (text as UTF-8)."""
        self.files[Path(path)] = data.encode("utf-8") if isinstance(data, str) else data

    def drop(self, path: Path) -> None:
        """Remove `path` (when there) at `commit`, once every new file is in place."""
        self.gone.append(Path(path))

    def commit(self) -> None:
        """Replace the files together; a `UserError` naming the file that failed, with the
        folder as it was."""
        made: list[Path] = []  # folders made for the new files
        temps: list[tuple[Path, Path]] = []  # (temporary, target)
        aside: list[tuple[Path, Path]] = []  # (target, the old file moved aside)
        placed: list[Path] = []
        current = Path(".")
        try:
            for path, data in self.files.items():
                current = target = resolve_target(path)
                for folder in reversed(target.parents):
                    if not folder.exists():
                        folder.mkdir()
                        made.append(folder)
                tmp = target.with_name(f".{target.name}.{os.getpid()}.{secrets.token_hex(4)}{TMP_SUFFIX}")
                fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
                temps.append((tmp, target))
                with os.fdopen(fd, "wb") as fh:
                    fh.write(data)
                    fh.flush()
                    os.fsync(fh.fileno())
                os.chmod(tmp, mode_for(target))
            for tmp, target in temps:
                current = target
                if target.exists():
                    old = target.with_name(f".{target.name}.{os.getpid()}.{secrets.token_hex(4)}{TMP_SUFFIX}")
                    _replace(target, old)
                    aside.append((target, old))
            for tmp, target in temps:
                current = target
                _replace(tmp, target)
                placed.append(target)
        except OSError as exc:
            for target in placed:
                with contextlib.suppress(OSError):
                    target.unlink()
            for target, old in reversed(aside):
                with contextlib.suppress(OSError):
                    os.replace(old, target)
            for tmp, _ in temps:
                with contextlib.suppress(OSError):
                    tmp.unlink()
            for folder in reversed(made):
                with contextlib.suppress(OSError):
                    folder.rmdir()
            raise UserError(f"cannot write {str(current)!r} ({exc.strerror or type(exc).__name__}): "
                            f"{UNTOUCHED}") from None
        for _, old in aside:
            with contextlib.suppress(OSError):
                old.unlink()
        for path in self.gone:
            with contextlib.suppress(OSError):
                path.unlink()
            for folder in path.parents[:2]:  # its folders that this left empty (baselines/<name>/)
                try:
                    folder.rmdir()
                except OSError:
                    break


def _replace(src: Path, dst: Path) -> None:
    """`os.replace`, apart so that a test can make one rename fail."""
    os.replace(src, dst)



__all__ = ["Batch", "LOCK_NAME", "locked", "write_experiment", "out_folder", "experiment_paths", "check_writable"]


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


#: The lock file a run holds in its --out folder (never deleted: see aileen/memory/store.py).
LOCK_NAME = ".aileen-out.lock"


@contextlib.contextmanager
def locked(folder: Path, what: str) -> Iterator[None]:
    """Hold `folder` for one run (`what`: its command, for the refusal): two sweeps into one
    --out each rewrote sweep.csv from their own rows and the first's vanished without a word,
    and two experiments' files were mixed. A second run is refused in one line naming the
    holder (`UserError`, exit 2), as a memory file is. An advisory `flock`, which the kernel
    drops when the process ends (SIGKILL too); no `fcntl`: a warning and no lock."""
    try:
        import fcntl
    except ImportError:  # pragma: no cover
        print("warning: no fcntl on this system; the --out folder is not locked", file=sys.stderr)
        yield
        return
    lock = Path(folder) / LOCK_NAME
    flags = os.O_RDWR | os.O_CREAT | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0)
    try:
        fd = os.open(lock, flags, 0o644)
    except OSError as exc:
        raise UserError(f"cannot use the lock file {str(lock)!r} ({exc.strerror or type(exc).__name__}); "
                        "expected a plain file there, or none") from None
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = os.pread(fd, 200, 0).decode("utf-8", "replace").strip() or "another process"
            raise UserError(f"--out {str(folder)!r} is in use by another run ({holder}); wait for it to end, "
                            "or give another --out") from None
        os.ftruncate(fd, 0)
        os.pwrite(fd, f"process {os.getpid()}: {what}\n".encode(), 0)
        yield
    finally:
        os.close(fd)


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


def _drop_stale(d: Path, batch: Batch, *, plot: bool, baselines: set[str]) -> None:
    """An earlier run's files in the folder that this run does not write again (its plot, a
    baseline's CSVs): left there, they disagreed with the CSVs beside them (a seed-0 curve
    beside seed-5 figures). Only files of these names go (with the folders they leave empty);
    anything else stays."""
    if not plot:
        batch.drop(d / "curve.png")
    for sub in sorted((d / "baselines").glob("*")) if (d / "baselines").is_dir() else ():
        if sub.is_dir() and sub.name not in baselines:
            for f in _OWN_CSVS:
                batch.drop(sub / f)


def write_experiment(res: ExperimentResult, out: Path, *, plot: bool = True,
                     baselines: "dict[str, ExperimentResult] | None" = None, name: str | None = None,
                     batch: Batch | None = None) -> list[str]:
    """DIR/<experiment>/trials.csv, summary.csv, areas.csv and curve.png (with the baselines'
    curves); each baseline's CSVs under DIR/<experiment>/baselines/<name>/. `name` replaces
    <experiment> (`aileen experiment all` writes the teacher protocol's spatial experiment as
    `teacher-spatial`). Into `batch` when given (the caller commits it with the run's other
    files), else written at once. Returns notes for the user (e.g. why there is no plot)."""
    own = batch if batch is not None else Batch()
    d = Path(out) / (name or res.experiment)
    _drop_stale(d, own, plot=plot, baselines=set(baselines or {}))
    own.put(d / "trials.csv", trials_csv(res))
    own.put(d / "summary.csv", summary_csv(res))
    own.put(d / "areas.csv", areas_csv(res))
    for bname, other in (baselines or {}).items():
        own.put(d / "baselines" / bname / "trials.csv", trials_csv(other))
        own.put(d / "baselines" / bname / "summary.csv", summary_csv(other))
        own.put(d / "baselines" / bname / "areas.csv", areas_csv(other))
    notes: list[str] = []
    if plot:
        png, notes = plots.curve_png(res, baselines=baselines)
        own.put(d / "curve.png", png)
    if batch is None:
        own.commit()
    return notes
