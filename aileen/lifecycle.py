"""Stopping on a signal without losing what was learned.

Why a module of its own: `run`, `teach` and `serve` hold a memory for minutes or hours, and a
person or a service manager ends them with any of four signals: Ctrl-C (SIGINT), a stop
(SIGTERM, what `kill`, `timeout` and systemd send), a closed terminal (SIGHUP) or Ctrl-\\
(SIGQUIT). Python turns only the first into an exception; the others kill the process where
it stands, and the session with it. The rules here, installed by `aileen.cli.main` for every
command:

- **Every stop signal is a `Stopped`** (a `KeyboardInterrupt`, raised in the main thread), so
  every path that keeps its work on Ctrl-C keeps it on all four. The command line says in one
  line what was kept and exits with 128 + the signal's number (130, 143, 129, 131).
- **Once stopping, the way out is not cut short.** Only the first signal raises; later ones
  are noted on stderr while what was learned is saved (SIGKILL still ends it at once).
- **A save is never interrupted** (`deferred`): a signal that arrives inside the block is
  acted on when the block ends, carrying a note of what the block did (saved, or the recovery
  file it wrote), so the file is never half-written and the session never silently dropped.
- **Nor is a lesson** (`lesson`): a stop in the middle of one waits for it to end ("finishing
  the lesson first"; a react can take seconds), so what is saved holds only whole lessons (a
  stop between the two stores of an inform kept `r_red` and not `r_box`). The watchdog is not
  shown the signal meanwhile (`wakeup_fd`): it would end the process inside clingo, saving
  the half lesson; its time and memory limits still hold. Only when Python has not been able
  to take the signal `LESSON_GRACE` seconds after it came (the main thread inside a clingo
  call that does not return: grounding for ever) is it shown, and it ends the process as
  before (what is saved then holds the lesson as far as it went).
- **After the command has returned** (`ended`), while the interpreter shuts down, a stop
  signal is said in one line too, and the process exits with 128 + its number at once.
- **When the main thread cannot run Python** (it is inside a C call that no signal
  interrupts: clingo's grounding), another thread ends the process (`emergency`): it runs the
  registered keepers (`keeper`: save what was learned), prints one line and exits. The C-level
  signal handler writes each signal to a wake-up socket (`wakeup_fd`) that such a thread can
  watch (`aileen.reasoning.watchdog`).

Forked children (none of ours fork, but a library may) get the default behaviour back.
"""

from __future__ import annotations

import contextlib
import os
import signal
import socket
import sys
import threading
import time
from collections.abc import Callable, Iterator
from types import FrameType
from typing import Any

__all__ = ["STOP_SIGNALS", "Stopped", "install", "listened", "uninstall", "installed", "deferred", "lesson", "keeper",
           "ended", "emergency", "wakeup_fd", "exit_status", "signal_name", "kept", "set_kept"]

#: The signals that stop a command cleanly (those this system has).
STOP_SIGNALS: tuple[int, ...] = tuple(getattr(signal, n) for n in ("SIGINT", "SIGTERM", "SIGHUP", "SIGQUIT")
                                      if hasattr(signal, n))


#: Seconds a stop signal waits for the lesson under way to end while the main thread cannot
#: run Python (inside a clingo call) before the watchdog acts on it: a react's calls take
#: a second or two; rules that ground for ever never return.
LESSON_GRACE = 3.0


class Stopped(KeyboardInterrupt):
    """A stop signal arrived. `kept`: where what was learned went (a note for the one line), or
    None while nobody has saved it yet."""

    def __init__(self, signum: int, kept: str | None = None) -> None:
        super().__init__(signal_name(signum))
        self.signum = signum
        self.kept = kept


def signal_name(signum: int) -> str:
    try:
        return signal.Signals(signum).name
    except ValueError:
        return f"signal {signum}"


def exit_status(signum: int) -> int:
    """The shell's convention for a process ended by a signal: 128 + its number."""
    return 128 + signum


def kept(exc: BaseException) -> str | None:
    """The note of where `exc`'s session went ("" : the message already says), or None."""
    return getattr(exc, "kept", None)


def set_kept(exc: BaseException, note: str | None) -> None:
    with contextlib.suppress(AttributeError):
        exc.kept = note  # type: ignore[attr-defined]


def _say(line: str) -> None:
    """One line on stderr; a closed terminal (SIGHUP) must not turn it into a new error."""
    with contextlib.suppress(OSError, ValueError):
        print(line, file=sys.stderr, flush=True)


class _State:
    def __init__(self) -> None:
        self.pid: int | None = None  # the process that installed the handlers
        self.old: dict[int, Any] = {}
        self.stopping: int | None = None
        self.deferring = 0
        self.holding: list[str] = []  # what the open deferred blocks finish, the outermost first
        self.lessons = 0  # open `lesson` blocks
        self.signalled_at: float | None = None  # when a signal Python has not taken was first seen in a lesson
        self.pending: int | None = None
        self.keepers: list[Callable[[], str | None]] = []
        self.wake_r: socket.socket | None = None
        self.wake_w: socket.socket | None = None
        self.old_wakeup = -1
        self.ending = threading.Lock()


_S = _State()


def _on_signal(signum: int, frame: FrameType | None) -> None:
    if os.getpid() != _S.pid:  # a forked child: what it would have done without us
        if signum == signal.SIGINT:
            raise KeyboardInterrupt
        signal.signal(signum, signal.SIG_DFL)
        os.kill(os.getpid(), signum)
        return
    if _S.deferring and _S.pending is None and _S.stopping is None:
        _S.pending = signum
        _say(f"aileen: {signal_name(signum)} received; finishing {_finishing()} first")
        return
    if _S.deferring and _S.lessons and _S.stopping is None:
        _say(f"aileen: {signal_name(signum)} received; still finishing the lesson, then saving what was learned "
             "(SIGKILL ends at once, losing it)")
        return
    if _S.deferring or _S.stopping is not None:
        _say(f"aileen: {signal_name(signum)} received; still saving what was learned "
             "(SIGKILL ends at once, losing it)")
        return
    _S.stopping = signum
    raise Stopped(signum)


def _finishing() -> str:
    """What a stop waits for: the outermost block open (a save inside a lesson waits for the lesson)."""
    return _S.holding[0] if _S.holding else "the save"


def stopping() -> int | None:
    """The stop signal being acted on, if any: the signal a `KeyboardInterrupt` stands for when
    a library raised its own in place of our `Stopped` (Ray's `wait` does)."""
    return _S.stopping if installed() else None


def installed() -> bool:
    return _S.pid == os.getpid()


def install() -> None:
    """Make the stop signals raise `Stopped` (main thread only; elsewhere a no-op)."""
    if threading.current_thread() is not threading.main_thread() or installed():
        return
    _S.pid = os.getpid()
    _S.stopping = _S.pending = _S.signalled_at = None
    _S.deferring = _S.lessons = 0
    _S.holding = []
    _S.old = {s: signal.signal(s, _on_signal) for s in _not_ignored()}
    with contextlib.suppress(OSError, ValueError):
        r, w = socket.socketpair()
        r.setblocking(False)
        w.setblocking(False)
        _S.old_wakeup = signal.set_wakeup_fd(w.fileno(), warn_on_full_buffer=False)
        _S.wake_r, _S.wake_w = r, w


def reclaim() -> None:
    """The stop signals raise `Stopped` again, after a library put its own handlers on them at
    the C level, where Python does not see them (Ray's driver answers SIGTERM with a crash
    report and exit status 15); a no-op unless `install` ran in this process's main thread."""
    if not installed() or threading.current_thread() is not threading.main_thread():
        return
    for s in _S.old:
        signal.signal(s, _on_signal)


def listened() -> tuple[int, ...]:
    """The stop signals this process answers: `STOP_SIGNALS` less those it was started
    ignoring. `nohup aileen run ...` starts it ignoring SIGHUP, and a shell's `cmd &` ignoring
    SIGINT and SIGQUIT; a handler put on them undid that (the run stopped when the terminal
    closed, or at a Ctrl-C meant for the script that started it)."""
    return tuple(_S.old) if installed() else _not_ignored()


def _not_ignored() -> tuple[int, ...]:
    return tuple(s for s in STOP_SIGNALS if signal.getsignal(s) != signal.SIG_IGN)


def uninstall() -> None:
    """Put back the handlers `install` replaced (tests run many commands in one process)."""
    if not installed() or threading.current_thread() is not threading.main_thread():
        return
    for s, h in _S.old.items():
        signal.signal(s, h)
    if _S.wake_w is not None:
        with contextlib.suppress(OSError, ValueError):
            signal.set_wakeup_fd(_S.old_wakeup)
        for sock in (_S.wake_r, _S.wake_w):
            with contextlib.suppress(OSError):
                sock.close()  # type: ignore[union-attr]
        _S.wake_r = _S.wake_w = None
    _S.old, _S.pid = {}, None


def ended(listening: tuple[int, ...]) -> None:
    """The command has returned and the process is about to exit (the interpreter's shutdown
    can take a second: threads, a Ray driver, large modules): a stop signal now finds nothing
    to stop. It used to find the default handler, and the process died with 128 + the signal
    and no line; now it says so in one line and exits so. Only for a process that ends here
    (the `aileen` command), never in a test that goes on."""
    if threading.current_thread() is not threading.main_thread():
        return
    for s in listening:
        signal.signal(s, _on_late)


def _on_late(signum: int, frame: FrameType | None) -> None:
    _say(f"aileen: {signal_name(signum)} received as the command ended; what it did is complete")
    with contextlib.suppress(Exception):
        sys.stdout.flush()
    os._exit(exit_status(signum))


def wakeup_fd() -> socket.socket | None:
    """The read end of the wake-up socket: one byte per signal, written by the C-level
    handler even while the main thread is inside C code (None when not installed, and while
    a lesson runs: a stop then waits for the lesson's end, clingo's calls in it included)."""
    if not installed() or (_S.lessons and not _lesson_overdue()):
        return None
    return _S.wake_r


def _lesson_overdue() -> bool:
    """Whether a signal came inside the lesson under way more than `LESSON_GRACE` seconds ago
    and Python has not taken it yet (its byte is in the wake-up socket, nothing is pending):
    the main thread is stuck in a C call. Once Python has it, the lesson runs on to its end
    (a call stuck after that ends at its time limit). Called by the watchdog's thread."""
    if _S.pending is not None or not _has_wakeup_bytes():
        _S.signalled_at = None
        return False
    now = time.monotonic()
    if _S.signalled_at is None:
        _S.signalled_at = now
    return now - _S.signalled_at > LESSON_GRACE


def _has_wakeup_bytes() -> bool:
    if _S.wake_r is None:
        return False
    try:
        return bool(_S.wake_r.recv(1, socket.MSG_PEEK))
    except (OSError, ValueError):  # nothing there (it does not wait), or closed
        return False


def _drain_wakeup() -> None:
    """Read past the bytes of signals a lesson held back, now acted on by Python: the
    watchdog would take them for a signal arriving inside the next clingo call."""
    if _S.wake_r is None:
        return
    with contextlib.suppress(OSError, ValueError):
        while _S.wake_r.recv(64):
            pass


class deferred:
    """A block no stop signal interrupts (a save). One that arrives inside is raised when the
    block ends, as `Stopped` with `kept` = `note` (set by the block: what it did) or, if the
    block failed with a `UserError`, that error's message (which names the recovery file).
    Outside the main thread, or without `install`, it does nothing."""

    #: What a stop inside the block waits for, in the line it is answered with.
    what = "the save"

    def __init__(self) -> None:
        self.note: str | None = None
        self._on = False

    def __enter__(self) -> "deferred":
        self._on = installed() and threading.current_thread() is threading.main_thread()
        if self._on:
            _S.deferring += 1
            _S.holding.append(self.what)
        return self

    def __exit__(self, et: type[BaseException] | None, exc: BaseException | None, tb: object) -> bool:
        if not self._on:
            return False
        _S.deferring -= 1
        if _S.holding:
            _S.holding.pop()
        if _S.deferring or _S.pending is None:
            return False
        signum, _S.pending = _S.pending, None
        _S.stopping = signum
        return self._stop(signum, exc)

    def _stop(self, signum: int, exc: BaseException | None) -> bool:
        """Act on the signal held back, the block having ended (with `exc`, or None)."""
        from aileen.errors import UserError

        if exc is None:
            raise Stopped(signum, self.note)
        if isinstance(exc, UserError):
            raise Stopped(signum, exc.format()) from exc
        return False  # a bug: its traceback matters more; the signal is spent


class lesson(deferred):
    """One lesson (or console command), which no stop signal cuts in half: one that arrives
    inside is raised as `Stopped` when the lesson ends, with nothing kept yet (`kept` None),
    so the session then saves what was learned, whole lessons only. `outcomes`: exceptions
    that end a lesson as its outcome (a `UserError`, the planner's `NoPlan`), raised past as
    the stop (the console would report them and go on, the stop lost)."""

    what = "the lesson"

    def __init__(self, outcomes: tuple[type[BaseException], ...] = ()) -> None:
        super().__init__()
        self.outcomes = outcomes

    def __enter__(self) -> "lesson":
        super().__enter__()
        if self._on:
            _S.lessons += 1
        return self

    def __exit__(self, et: type[BaseException] | None, exc: BaseException | None, tb: object) -> bool:
        if self._on:
            _S.lessons -= 1
            if not _S.lessons:
                if _S.pending is not None:
                    _drain_wakeup()
                _S.signalled_at = None
        return super().__exit__(et, exc, tb)

    def _stop(self, signum: int, exc: BaseException | None) -> bool:
        from aileen.errors import UserError

        if exc is None:
            raise Stopped(signum)
        if isinstance(exc, (UserError, *self.outcomes)):
            raise Stopped(signum) from exc
        return False  # a bug: its traceback matters more; the signal is spent


@contextlib.contextmanager
def keeper(save: Callable[[], str | None]) -> Iterator[None]:
    """While the block runs, `emergency` calls `save` (which returns a note of where what was
    learned went) before it ends the process."""
    _S.keepers.append(save)
    try:
        yield
    finally:
        with contextlib.suppress(ValueError):
            _S.keepers.remove(save)


def emergency(message: str, status: int) -> None:
    """End the process from a thread other than a stuck main thread: save what was learned
    (every keeper, newest first), print `aileen: message; note` and exit with `status`.
    Never returns; a second caller waits for the first to finish."""
    _S.ending.acquire()
    notes = []
    for save in reversed(list(_S.keepers)):
        try:
            note = save()
        except BaseException as exc:  # noqa: BLE001 - the process ends either way; say why
            note = f"could not save what was learned ({type(exc).__name__}: {exc})"
        if note:
            notes.append(note)
    _say("aileen: " + "; ".join([message, *notes]))
    with contextlib.suppress(Exception):
        sys.stdout.flush()
    os._exit(status)
