"""The memory file while a run uses it: checked first, locked throughout, saved safely.

Why a module of its own: `persist` knows the file's format; this module knows that other
processes exist. The guarantees (docs/concept-memory.md, "Concurrency and crashes"):

- **One run at a time.** `MemoryFile.open` takes an advisory lock (`fcntl.flock`) on a lock
  file beside the memory file (`.<name>.lock`, never deleted: deleting a lock file opens a
  race) before the memory is read, and keeps it until the run ends. A second run on the same
  file is refused at once, with exit 2, before it does any work: nothing it would learn can
  be lost. We refuse rather than merge: two runs that taught the same word differently have
  no right merge (the SAGE generalizations depend on the order of examples), and a refusal
  is predictable. The kernel drops the lock when the process ends, even on SIGKILL, so a
  crashed run never leaves the file locked. The lock file is keyed by the name (links
  resolved), which covers a file not written yet; a file that exists is locked as well
  itself (`flock` on the memory file: keyed by what the file is, its device and inode), so
  a run on a hard link to a held file (another name, the same file) is refused too.
- **Nothing overwritten unseen.** A program that ignores the lock (an old aileen, an editor)
  may still write the file. At save time the file's identity (inode, size, mtime) is
  compared with what was read; if it changed, this run's memory goes to a recovery file
  beside it and the save is refused (exit 2), naming both files.
- **A failed save loses nothing.** When the memory cannot be written (permissions, full
  disk, a directory in the way), it is written to a recovery file (beside the target, else
  in the temporary folder) named in the one-line error.
- **Atomic.** Writes go through `aileen.io`: the file is the old or the new complete version
  whatever moment the process is killed; a link stays a link, the mode stays the mode.

`fcntl` rather than the `filelock` package: it is in the standard library (no new runtime
dependency) and `flock` is released by the kernel on any exit. It is POSIX only; on a
system without it the lock is skipped with a warning and the save-time check still holds.
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Protocol

from aileen import lifecycle
from aileen.errors import UserError
from aileen.io import resolve_target

try:  # pragma: no cover - POSIX has it
    import fcntl
except ImportError:  # pragma: no cover
    fcntl = None  # type: ignore[assignment]

__all__ = ["MemoryFile", "SaveRefused", "check_writable_file", "check_plain_file", "check_output_dir",
           "recovery_path"]


class _Saver(Protocol):
    def save(self, path: str) -> None: ...


class SaveRefused(UserError):
    """A save that did not reach the memory file. Why a class of its own: what comes after
    depends on where the memory went and why. `recovered`: the recovery file that holds it
    (None: no file could be written), so the console keeps its table and transcript beside
    that, not stamped as the memory file's; `conflict`: another program changed or removed
    the file (else writing failed: `errno`, e.g. ENOSPC), which the console answers 409, not
    as a client's error."""

    def __init__(self, message: str, *, path: str | None = None, recovered: Path | None = None,
                 conflict: bool = False, errno: int | None = None) -> None:
        super().__init__(message, path=path)
        self.recovered = recovered
        self.conflict = conflict
        self.errno = errno

    def adding(self, more: str) -> "SaveRefused":
        """The same refusal with `more` said after it (what became of what goes with the memory)."""
        return _kept(SaveRefused(f"{self.message}; {more}", path=self.path, recovered=self.recovered,
                                 conflict=self.conflict, errno=self.errno))


def _kept(exc: UserError) -> UserError:
    """Mark a save's error as already naming where the memory went (no second save on the way out)."""
    lifecycle.set_kept(exc, "")
    return exc


def check_writable_file(path: str | os.PathLike[str], what: str = "memory file") -> Path:
    """Fail now, not after the run, if `path` cannot be written: a name must be given, its
    folder must exist and be writable, and what stands there, if anything, must be a regular
    file (not a directory, a FIFO, a device, a socket, a symbolic link loop) that may be read
    and written. Returns the file a save replaces."""
    if not str(path):
        raise UserError(f"the {what} needs a name (an empty path was given)", path="''")
    check_plain_file(path, what)
    target = resolve_target(path)
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        raise UserError(f"cannot save the {what}: folder {str(folder)!r} does not exist", path=str(path))
    if not os.access(folder, os.W_OK | os.X_OK):
        raise UserError(f"cannot save the {what}: folder {str(folder)!r} is not writable", path=str(path))
    if target.exists():
        if not os.access(target, os.R_OK):
            raise UserError(f"cannot read the {what}: permission denied", path=str(path))
        if not os.access(target, os.W_OK) or not stat.S_IMODE(os.stat(target).st_mode) & 0o222:
            raise UserError(f"the {what} is read-only, so nothing could be saved to it; "
                            "make it writable (chmod u+w) or use another file", path=str(path))
    return target


#: What a path can be instead of a regular file, for the error message.
_KINDS = ((stat.S_ISDIR, "a directory"), (stat.S_ISFIFO, "a FIFO (named pipe)"), (stat.S_ISCHR, "a device"),
          (stat.S_ISBLK, "a device"), (stat.S_ISSOCK, "a socket"))


def check_plain_file(path: str | os.PathLike[str], what: str = "memory file") -> bool:
    """Whether a regular file stands at `path` (links followed); False when nothing does.
    Anything else - a directory, a FIFO (reading it would wait for ever), a device, a
    socket, a symbolic link loop - is a one-line `UserError`."""
    try:
        st = os.stat(path)
    except FileNotFoundError:
        return False
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            raise UserError(f"cannot use the {what}: the path is a loop of symbolic links", path=str(path)) from None
        if exc.errno == errno.ENOTDIR:
            raise UserError(f"cannot use the {what}: a part of the path is not a folder", path=str(path)) from None
        raise UserError(f"cannot use the {what}: {exc.strerror}", path=str(path)) from None
    for test, kind in _KINDS:
        if test(st.st_mode):
            raise UserError(f"cannot use {kind} as the {what}; expected a regular file", path=str(path))
    return True


def check_output_dir(path: str | os.PathLike[str], what: str) -> None:
    """`path` must be a writable directory, or creatable as one."""
    p = Path(path)
    if p.exists() and not p.is_dir():
        raise UserError(f"{what} must be a directory, and this is a file", path=str(p))
    probe = p
    while not probe.exists():
        probe = probe.parent if probe.parent != probe else Path(".")
    if not probe.is_dir():
        raise UserError(f"{what}: {str(probe)!r} is a file, so the directory cannot be created", path=str(p))
    if not os.access(probe, os.W_OK | os.X_OK):
        raise UserError(f"{what}: {str(probe)!r} is not writable", path=str(p))


def recovery_path(path: str | os.PathLike[str]) -> Path:
    """Where a memory that could not be saved to `path` goes: beside it if that folder takes
    files, else the temporary folder. The name carries the process id, so it is never reused."""
    target = resolve_target(path)
    name = f"{target.stem}.recovered-{os.getpid()}{target.suffix or '.json'}"
    folder = target.parent if str(target.parent) else Path(".")
    if folder.is_dir() and os.access(folder, os.W_OK | os.X_OK):
        return folder / name
    return Path(tempfile.gettempdir()) / name


def _stamp(p: Path) -> tuple[int, int, int] | None:
    try:
        st = os.stat(p)
    except FileNotFoundError:
        return None
    return (st.st_ino, st.st_size, st.st_mtime_ns)


_NOWHERE = "no file (nothing could be written)"


def _what_became(target: Path, now: tuple[int, int, int] | None) -> str:
    """What another program did to the memory file, in the refusal's words: a file removed
    was said to be "changed ... left as that program wrote it", which no longer existed."""
    if now is None:
        return "removed by"
    return "changed by" if target.is_file() else "replaced with something that is not a file by"


def _left(now: tuple[int, int, int] | None) -> str:
    return "" if now is None else "it was left as that program wrote it, and "


@dataclass
class MemoryFile:
    """A memory file held by this process: locked from `open` until `close`."""

    path: Path
    target: Path
    #: What a run refused because another holds the file may do instead (the command's words).
    instead: str = "use another --memory file"
    _lock_fd: int | None = None
    #: The memory file's own locks: the file found at open, and the one the last save wrote
    #: (those between have no name left that a run could come by, unless linked meanwhile).
    _file_fds: dict[str, int] = field(default_factory=dict, repr=False)
    _stamp: tuple[int, int, int] | None = None
    _closed: bool = field(default=False, repr=False)

    @classmethod
    def open(cls, path: str | os.PathLike[str], *, instead: str | None = None) -> "MemoryFile":
        """Check the path, take the lock (or refuse: another run holds it), note the file's state.
        `instead`: what the refusal advises besides waiting (default: another --memory file)."""
        target = check_writable_file(path)
        mf = cls(Path(path), target) if instead is None else cls(Path(path), target, instead)
        mf._lock()
        try:
            mf._lock_file(refuse=True)
        except UserError:
            mf.close()
            raise
        mf._stamp = _stamp(target)
        return mf

    def _in_use(self, holder: str) -> UserError:
        return UserError(f"the memory file is in use by another aileen run{holder}; "
                         f"wait for it to finish or {self.instead}", path=str(self.path))

    def _lock_file(self, *, refuse: bool) -> None:
        """Lock the memory file itself, when it exists: what it is, not what it is called (a
        run on a hard link to a held file took the other name's lock file and went on, and the
        memory split in two). After a save (a new file, renamed in) the new one is locked too,
        so a hard link made to it later is held as well. `refuse`: a lock held elsewhere is a
        `UserError` (else it is left: the name's lock file still holds the file)."""
        if fcntl is None:  # pragma: no cover
            return
        flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOFOLLOW", 0)
        try:
            fd = os.open(self.target, flags)
        except OSError:
            return  # no file yet (the name's lock holds it), or one that the save will report on
        try:
            if not stat.S_ISREG(os.fstat(fd).st_mode):
                raise OSError(errno.EINVAL, "not a regular file")
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(fd)
            if refuse:
                raise self._in_use(" under another name (a hard link to this file)") from None
            return
        except OSError:
            os.close(fd)
            return
        which = "opened" if refuse else "saved"
        if which in self._file_fds:
            with contextlib.suppress(OSError):
                os.close(self._file_fds[which])
        self._file_fds[which] = fd

    def _lock(self) -> None:
        if fcntl is None:  # pragma: no cover
            print("warning: no fcntl on this system; the memory file is not locked", file=sys.stderr)
            return
        lock = self.target.parent / f".{self.target.name}.lock"
        # Never through a symbolic link (it would truncate whatever it points at), and never
        # waiting on a FIFO put in its place.
        flags = os.O_RDWR | os.O_CREAT | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0)
        try:
            fd = os.open(lock, flags, 0o644)
        except OSError as exc:
            why = ("it is a symbolic link; a lock file must be a plain file: remove the link"
                   if exc.errno == errno.ELOOP or lock.is_symlink() else exc.strerror)
            raise UserError(f"cannot use the lock file {str(lock)!r}: {why}", path=str(self.path)) from None
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode) or st.st_nlink > 1:
            os.close(fd)
            what = "not a regular file" if not stat.S_ISREG(st.st_mode) else "a hard link to another file"
            raise UserError(f"cannot use the lock file {str(lock)!r}: it is {what}; remove it",
                            path=str(self.path))
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = ""
            with contextlib.suppress(OSError, ValueError):
                holder = f" (process {int(os.pread(fd, 32, 0).decode().strip())})"
            os.close(fd)
            raise self._in_use(holder) from None
        os.ftruncate(fd, 0)
        os.pwrite(fd, f"{os.getpid()}\n".encode(), 0)
        self._lock_fd = fd

    def same_file(self, path: str | os.PathLike[str]) -> bool:
        """Whether `path` names the file held here: the same name (links resolved) or the same
        file under another name (a hard link, which the lock holds too)."""
        other = resolve_target(path)
        if other.resolve() == self.target.resolve():
            return True
        try:
            return os.path.samefile(other, self.target)
        except OSError:
            return False

    @property
    def exists(self) -> bool:
        return self._stamp is not None

    def save(self, agent: _Saver) -> None:
        """Save `agent`'s memory here; on any failure write a recovery file and raise a
        one-line `UserError` naming it (the caller exits 2, or the console keeps going).

        No stop signal interrupts it (`lifecycle.deferred`): one that arrives meanwhile is
        raised when the save is done, as a `Stopped` that says where the memory went."""
        with lifecycle.deferred() as block:
            now = _stamp(self.target)
            if now != self._stamp:
                where = self._recover(agent)
                if now is None:  # nothing left to overwrite: the next save writes the file anew
                    self._stamp = None
                raise _kept(SaveRefused(f"the memory file was {_what_became(self.target, now)} another program "
                                        f"while this run held it; {_left(now)}what this run learned is in "
                                        f"{where or _NOWHERE}", path=str(self.path), recovered=where,
                                        conflict=True))
            try:
                agent.save(str(self.path))
            except (OSError, UserError) as exc:
                why = exc.message if isinstance(exc, UserError) else (exc.strerror or str(exc))
                where = self._recover(agent)
                raise _kept(SaveRefused(f"cannot save the memory ({why}); what was learned is in {where or _NOWHERE}",
                                        path=str(self.path), recovered=where,
                                        errno=exc.errno if isinstance(exc, OSError) else None)) from None
            self._stamp = _stamp(self.target)
            self._lock_file(refuse=False)
            block.note = self.saved_note()

    def saved_note(self) -> str:
        return f"what was learned is saved in {self.path}"

    def keep(self, agent: _Saver) -> str:
        """Save, and say in a few words where what was learned went (the file, or the recovery
        file when the save failed); never raises a `UserError`. For the way out of a run."""
        try:
            self.save(agent)
        except UserError as exc:
            return exc.format()
        return self.saved_note()

    def _recover(self, agent: _Saver) -> Path | None:
        """Where the memory went when the file could not take it; None: nowhere."""
        for spot in (recovery_path(self.path), Path(tempfile.gettempdir()) / recovery_path(self.path).name):
            try:
                agent.save(str(spot))
                return spot
            except (OSError, UserError):
                continue
        return None

    def close(self) -> None:
        """Release the lock (the kernel does it too when the process ends)."""
        for fd in self._file_fds.values():
            with contextlib.suppress(OSError):
                os.close(fd)
        self._file_fds = {}
        if self._lock_fd is not None:
            with contextlib.suppress(OSError):
                os.close(self._lock_fd)
            self._lock_fd = None
        self._closed = True

    def __enter__(self) -> "MemoryFile":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
