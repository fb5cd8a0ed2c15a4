"""A Soar kernel and one agent, in-process: the only module that imports `soar_sml`.

Everything else in `aileen.soar` talks to Soar through `SoarKernel`: it adds and removes
input-link structures, reads the output-link as plain trees (`WMNode`), is told of new
output commands by Soar's own output events (no polling), marks commands done
(`^status complete`, Soar's convention for output commands), runs decision cycles, and
shuts the kernel down on every exit path (it is a context manager).

With `listen=PORT` the kernel also opens Soar's listener socket, so Soar's debugger or a
remote CLI (`soar_sml.Kernel.CreateRemoteConnection`) can attach to the running agent: the
kernel still runs in the calling thread, and serves the remote side after every decision
cycle and whenever `pump()` is called (between lessons).
"""

from __future__ import annotations

import re
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from aileen.errors import UserError

INSTALL_HINT = 'the Soar agent needs the optional extra: pip install -e ".[soar]" (soar-sml)'

#: How deep an output-link command may nest (command > fact > argument > ...). Deeper, or a
#: cycle, is a malformed command (`WMNode.error`), never a structure cut short.
MAX_DEPTH = 8
#: The print trace keeps this many of the latest messages (a long run must not grow it).
PRINT_LIMIT = 2000

Value = str | int | float


def _sml() -> Any:
    try:
        import soar_sml
    except ImportError:
        raise UserError(INSTALL_HINT) from None
    return soar_sml


@dataclass
class WMNode:
    """An identifier of the output-link as read at one moment: its attributes, each with its
    values (constants or nested nodes). `handle` is the live identifier (for marking it done),
    `tag` the time tag of the WME that holds it. `error` says why the structure cannot be
    read as it stands (a cycle, nested too deep); its attributes are then its constants only."""

    name: str
    tag: int
    handle: Any = None
    attrs: dict[str, list["Value | WMNode"]] = field(default_factory=dict)
    error: str | None = None

    def get(self, attr: str) -> "Value | WMNode | None":
        vals = self.attrs.get(attr)
        return vals[0] if vals else None

    def all(self, attr: str) -> list["Value | WMNode"]:
        return self.attrs.get(attr, [])


@dataclass
class Counts:
    """What Soar's decision trace showed since the kernel started: operator selections
    (`O: O12 (name)`) and impasses (`==>S: S3 (operator no-change)`). Read from the trace at
    its default level 1; a debugger that turns the trace off stops the counting."""

    selections: int = 0
    impasses: int = 0


class _Malformed(Exception):
    pass


class SoarKernel:
    """One Soar agent running in the calling thread (so a decision cycle costs microseconds
    of messaging, and Ctrl-C reaches Python between runs)."""

    def __init__(self, name: str = "aileen", *, listen: int | None = None) -> None:
        sml = _sml()
        self._sml = sml
        # Without `listen` no listener socket: the kernel serves this process only (and two
        # kernels do not fight over a port).
        if listen is not None:
            _check_port(int(listen))  # Soar only prints that it could not bind, and goes on
        port = sml.Kernel.kSuppressListener if listen is None else int(listen)
        self._kernel = sml.Kernel.CreateKernelInCurrentThread(True, port)
        if self._kernel.HadError():
            raise UserError(f"Soar: cannot create a kernel: {self._kernel.GetLastErrorDescription()}")
        self._agent = self._kernel.CreateAgent(name)
        if self._agent is None:
            msg = self._kernel.GetLastErrorDescription()
            self._kernel.Shutdown()
            raise UserError(f"Soar: cannot create an agent: {msg}")
        self._printed: deque[str] = deque(maxlen=PRINT_LIMIT)
        self.counts = Counts()  # operator selections and impasses, from the decision trace
        self._agent.RegisterForPrintEvent(sml.smlEVENT_PRINT, self._on_print, None)
        self.input_link = self._agent.GetInputLink()
        self.listening = listen is not None
        self._removed: set[int] = set()
        self._after_output: list[Callable[[], None]] = []
        self._handlers: list[Callable[..., None]] = []
        self._failure: BaseException | None = None
        self._agent.SetOutputLinkChangeTracking(True)
        self._agent.RegisterForRunEvent(sml.smlEVENT_AFTER_OUTPUT_PHASE, self._on_after_output, None)
        if self.listening:  # a remote debugger is answered while the agent runs, too
            self._agent.RegisterForRunEvent(sml.smlEVENT_AFTER_DECISION_CYCLE, self._on_decision, None)
        self._closed = False

    def _on_print(self, _id: Any, _data: Any, _agent: Any, message: str) -> None:
        self._printed.append(message)
        if "O: " in message or "==>S: " in message:  # Soar's decision trace (trace level 1, the default)
            self.counts.selections += len(_SELECTION.findall(message))
            self.counts.impasses += len(_IMPASSE.findall(message))

    # ------------------------------------------------------------------ lifecycle
    def close(self) -> None:
        if not self._closed:
            self._closed = True
            self._kernel.Shutdown()
            del self._kernel

    def __enter__(self) -> "SoarKernel":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __del__(self) -> None:  # a forgotten kernel still goes down with its owner
        try:
            self.close()
        except Exception:  # noqa: BLE001 - interpreter shutdown: nothing left to report to
            pass

    @property
    def port(self) -> int | None:
        """The listener port a debugger attaches to (None: not listening)."""
        return self._kernel.GetListenerPort() if self.listening else None

    def pump(self) -> None:
        """Serve a remote debugger or CLI now (a no-op without a listener)."""
        if self.listening:
            self._kernel.CheckForIncomingCommands()

    def _on_decision(self, *_: Any) -> None:
        self._kernel.CheckForIncomingCommands()

    # ------------------------------------------------------------------ commands
    def command(self, line: str) -> str:
        """Run a Soar command line; a failure raises UserError with Soar's own message."""
        out = self._agent.ExecuteCommandLine(line)
        if not self._agent.GetLastCommandLineResult():
            raise UserError(f"Soar: {line.split()[0]}: {_first_error(out)}")
        return out

    def source(self, path: str | Path) -> None:
        """Load a rule file. A rule Soar refuses, or warns about (it would never fire), stops
        with Soar's own reason at file:line, as Soar reports it (exit 2)."""
        p = Path(path)
        out = self._agent.ExecuteCommandLine(f"source {{{p}}}")
        failed = not self._agent.GetLastCommandLineResult() or "Production addition failed" in out
        if failed or "Warning:" in out:
            where = re.search(r"(\S+\.soar):(\d+)", out)
            msg = _first_error(out)
            if where:
                raise UserError(msg, path=where.group(1), line=int(where.group(2)))
            raise UserError(msg, path=str(p), line=_line_of_production(out, p))

    def chunks(self) -> tuple[int, int]:
        """(rules chunking has learned so far, how often they have fired)."""
        learned = fired = 0
        for m in _FIRING.finditer(self.command("firing-counts")):
            if m.group(2).startswith("chunk"):
                learned += 1
                fired += int(m.group(1))
        return learned, fired

    def printed(self) -> list[str]:
        """What the agent wrote (`write`, traces) since the last call (the latest
        `PRINT_LIMIT` messages)."""
        out = list(self._printed)
        self._printed.clear()
        return out

    # ------------------------------------------------------------------ input-link
    def add(self, parent: Any, attr: str, value: Value | None = None) -> Any:
        """Add `(parent ^attr value)` to the input-link; value None makes a new identifier.
        Returns the WME (pass it to `remove`; for a new identifier it is the identifier)."""
        if value is None:
            return parent.CreateIdWME(attr)
        if isinstance(value, bool):
            value = "true" if value else "false"
        if isinstance(value, int):
            return parent.CreateIntWME(attr, value)
        if isinstance(value, float):
            return parent.CreateFloatWME(attr, value)
        return parent.CreateStringWME(attr, str(value))

    def remove(self, wme: Any) -> None:
        self._agent.DestroyWME(wme)

    def commit(self) -> None:
        self._agent.Commit()

    # ------------------------------------------------------------------ output-link
    def output(self, depth: int = MAX_DEPTH) -> list[tuple[str, WMNode]]:
        """The output-link's commands as (attribute, tree), read now."""
        ol = self._agent.GetOutputLink()
        if ol is None:
            return []
        out = []
        for i in range(ol.GetNumberChildren()):
            w = ol.GetChild(i)
            if w.IsIdentifier():
                out.append((w.GetAttribute(), read(w, depth)))
        return out

    def tree(self, ident: Any, depth: int = MAX_DEPTH) -> WMNode:
        """An input-link identifier (as `add` returned it) read as a tree, as the agent sees it."""
        return _read_checked(ident, 0, depth)

    def mark(self, node: WMNode, status: str = "complete") -> None:
        """Soar's convention for output commands: `^status complete` (or `error`) on the command."""
        if node.handle is not None:
            if status == "complete":
                node.handle.AddStatusComplete()
            else:
                node.handle.AddStatusError()

    def on_output(self, attr: str, handler: Callable[[WMNode], None]) -> None:
        """Call `handler` with each new `(<output-link> ^attr <cmd>)` command, read as a tree,
        in the output phase that added it (Soar's output event)."""

        def call(_data: Any, _agent: Any, _attr: str, wme: Any) -> None:
            if wme.IsIdentifier():
                self._guarded(handler, read(wme))

        self._handlers.append(call)  # SWIG keeps no reference to it
        self._agent.AddOutputHandler(attr, call, None)

    def on_after_output(self, handler: Callable[[], None]) -> None:
        """Call `handler` after every output phase (after the output handlers)."""
        self._after_output.append(handler)

    def _on_after_output(self, *_: Any) -> None:
        agent = self._agent
        for i in range(agent.GetNumberOutputLinkChanges()):
            if not agent.IsOutputLinkChangeAdd(i):
                self._removed.add(agent.GetOutputLinkChange(i).GetTimeTag())
        agent.ClearOutputLinkChanges()
        for h in self._after_output:
            self._guarded(h)

    def _guarded(self, handler: Callable[..., None], *args: Any) -> None:
        """Run a handler inside Soar's event; an exception stops the run and is raised by
        `run` (SWIG would print and drop it)."""
        if self._failure is not None:
            return
        try:
            handler(*args)
        except BaseException as exc:  # noqa: BLE001 - re-raised in run()
            self._failure = exc
            self._agent.StopSelf()

    def removed(self) -> set[int]:
        """Time tags of output-link WMEs the agent removed since the last call."""
        out, self._removed = self._removed, set()
        return out

    # ------------------------------------------------------------------ running
    def run(self, decisions: int = 1) -> None:
        """Run up to `decisions` decision cycles (fewer when a handler calls `stop`); an
        exception a handler raised comes out here."""
        self._agent.RunSelf(decisions)
        self._raise()

    def run_until_output(self) -> None:
        """Run until the agent changes its output-link (Soar gives up after its
        max-nil-output-cycles, 15 by default, without output)."""
        self._agent.RunSelfTilOutput()
        self._raise()

    def _raise(self) -> None:
        exc, self._failure = self._failure, None
        if exc is not None:
            raise exc

    def stop(self) -> None:
        """Stop the current run after this phase (from an output handler)."""
        self._agent.StopSelf()


def _check_port(port: int) -> None:
    """Can Soar's listener bind `port` (on every interface, as it does)?"""
    import socket

    if not 0 < port < 65536:
        raise UserError(f"--soar-listen: {port} is not a port number (1-65535)")
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)  # as a listener does: a closed one's port is free
        try:
            s.bind(("", port))
        except OSError as exc:
            raise UserError(f"Soar: cannot listen on port {port}: {exc.strerror or exc}") from None


def read(wme: Any, depth: int = MAX_DEPTH) -> WMNode:
    """The identifier `wme` holds, read as a tree; a cycle or a structure nested deeper than
    `depth` gives a node with `error` set (and no attributes)."""
    return _read_checked(wme.ConvertToIdentifier(), wme.GetTimeTag(), depth)


def _read_checked(ident: Any, tag: int, depth: int) -> WMNode:
    try:
        return _read(ident, tag, depth, frozenset())
    except _Malformed as exc:  # what can still be said of it: its constants (^command, ^tag, ^status)
        node = WMNode(ident.GetValueAsString(), tag, ident, {}, str(exc))
        for i in range(ident.GetNumberChildren()):
            w = ident.GetChild(i)
            if not w.IsIdentifier():
                node.attrs.setdefault(w.GetAttribute(), []).append(_value(w))
        return node


def _read(ident: Any, tag: int, depth: int, path: frozenset[str]) -> WMNode:
    name = ident.GetValueAsString()
    if name in path:
        raise _Malformed(f"a cycle: {name} contains itself")
    path = path | {name}
    node = WMNode(name, tag, ident)
    for i in range(ident.GetNumberChildren()):
        w = ident.GetChild(i)
        attr = w.GetAttribute()
        if w.IsIdentifier():
            if depth <= 0:
                raise _Malformed(f"nested deeper than {MAX_DEPTH} levels (at {name} ^{attr})")
            val: Value | WMNode = _read(w.ConvertToIdentifier(), w.GetTimeTag(), depth - 1, path)
        else:
            val = _value(w)
        node.attrs.setdefault(attr, []).append(val)
    return node


def _value(w: Any) -> Value:
    kind = w.GetValueType()
    s = w.GetValueAsString()
    return int(s) if kind == "int" else float(s) if kind == "double" else s


_FIRING = re.compile(r"^\s*(\d+):\s+(\S+)", re.M)
_SELECTION = re.compile(r"\d+:\s+O: ")
_IMPASSE = re.compile(r"==>S: ")
_NOISE = ("(Ignoring production", "Production addition failed", "Total:", "Error while sourcing file")


def _first_error(out: str) -> str:
    """Soar's reason in its output: the first line that is not a progress mark (`*`, `#`)
    nor Soar's bookkeeping ("(Ignoring production x)", "Total: ...")."""
    for ln in out.splitlines():
        text = ln.strip().lstrip("*#").strip()
        if text and not text.startswith(_NOISE):
            return text.split("\t")[0].strip()
    return "failed"


def _line_of_production(out: str, path: Path) -> int | None:
    """The line of the rule a Soar warning names ("On the LHS of production warn*rule, ..."):
    Soar says no line for a warning, where it does for an error."""
    m = re.search(r"production ([^\s,]+)", out)
    if m is None:
        return None
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return None
    at = re.search(r"^[ \t]*sp\s*\{\s*" + re.escape(m.group(1)) + r"(?![\w*-])", text, re.MULTILINE)
    return text.count("\n", 0, at.start()) + 1 if at else None
