"""The one way aileen writes a file: atomically, keeping what the file is.

Why one helper: a reader (another run, a person's editor, a crash) must only ever see the
old or the new complete file. Every writer in the package goes through here, so the
guarantees below hold for memory files, images, CSVs, models and their metadata alike:

- the bytes go to a temporary file in the target's own folder (same file system, so the
  rename is atomic), are flushed and fsync'ed, then renamed over the target, and the folder
  is fsync'ed so the rename itself survives a power cut;
- a symbolic link is kept: the file it points to is replaced, not the link;
- the target's permission bits are kept (a new file gets the usual `0666 & ~umask`, not
  the `0600` of `tempfile.mkstemp`);
- temporary files are named `.<name>.<pid>.<random>.aileen-tmp`; one left by a process that
  no longer runs (killed mid-write) is removed at the next save into that folder. Files of
  live processes are left alone, so two writers never delete each other's work.
"""

from __future__ import annotations

import contextlib
import os
import re
import secrets
import stat
from collections.abc import Iterator
from pathlib import Path

__all__ = ["TMP_SUFFIX", "mode_for", "atomic_write_bytes", "atomic_write_text", "atomic_path", "resolve_target",
           "stale_temp_files"]

TMP_SUFFIX = ".aileen-tmp"
_TMP = re.compile(r"^\.(?P<name>.+)\.(?P<pid>\d+)\.[0-9a-f]{8}" + re.escape(TMP_SUFFIX) + "$")


def resolve_target(path: str | os.PathLike[str]) -> Path:
    """The file a write to `path` must replace: symbolic links followed (even dangling ones)."""
    p = Path(path)
    seen = 0
    while p.is_symlink() and seen < 40:
        link = Path(os.readlink(p))
        p = link if link.is_absolute() else p.parent / link
        seen += 1
    return p


def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # someone else's live process
        return True
    return True


def stale_temp_files(folder: str | os.PathLike[str]) -> list[Path]:
    """Temporary files of ours in `folder` whose writing process is gone."""
    out = []
    try:
        names = os.listdir(folder)
    except OSError:
        return []
    for name in names:
        m = _TMP.match(name)
        if m and not _alive(int(m.group("pid"))):
            out.append(Path(folder) / name)
    return out


def _clean(folder: Path) -> None:
    for p in stale_temp_files(folder):
        with contextlib.suppress(OSError):
            p.unlink()


def mode_for(target: Path) -> int:
    """The permission bits an existing file had (a replacement keeps them), else `0666 & ~umask`."""
    try:
        return stat.S_IMODE(os.stat(target).st_mode)
    except FileNotFoundError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


def _fsync_dir(folder: Path) -> None:
    with contextlib.suppress(OSError):
        fd = os.open(folder, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str]) -> Iterator[Path]:
    """A temporary path to write to (for writers that want a file name: OpenCV, ONNX, NumPy);
    on leaving the block without an error it replaces `path` atomically, else it is removed.

    Raises `OSError` (the folder missing or not writable, a directory in the way); the
    caller turns it into a user-facing message.
    """
    target = resolve_target(path)
    folder = target.parent if str(target.parent) else Path(".")
    if target.is_dir():
        raise IsADirectoryError(21, "a directory is in the way", str(target))
    _clean(folder)
    tmp = folder / f".{target.name}.{os.getpid()}.{secrets.token_hex(4)}{TMP_SUFFIX}"
    mode = mode_for(target)
    try:
        yield tmp
        fd = os.open(tmp, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)
        os.chmod(tmp, mode)
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    _fsync_dir(folder)


def atomic_write_bytes(path: str | os.PathLike[str], data: bytes) -> None:
    """Replace `path` by `data` atomically (see the module's guarantees)."""
    with atomic_path(path) as tmp:
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())


def atomic_write_text(path: str | os.PathLike[str], text: str) -> None:
    """`atomic_write_bytes` for UTF-8 text."""
    atomic_write_bytes(path, text.encode("utf-8"))
