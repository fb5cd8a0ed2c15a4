"""A Soar kernel and one agent, in-process: the only module that imports `soar_sml`.

Everything else in `aileen.soar` talks to Soar through `SoarKernel`: it adds and removes
input-link structures, reads the output-link as plain trees (`WMNode`), marks commands done
(`^status complete`, Soar's convention for output commands), runs decision cycles, and
shuts the kernel down on every exit path (it is a context manager).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from aileen.errors import UserError

INSTALL_HINT = 'the Soar agent needs the optional extra: pip install -e ".[soar]" (soar-sml)'

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
    `tag` the time tag of the WME that holds it."""

    name: str
    tag: int
    handle: Any = None
    attrs: dict[str, list["Value | WMNode"]] = field(default_factory=dict)

    def get(self, attr: str) -> "Value | WMNode | None":
        vals = self.attrs.get(attr)
        return vals[0] if vals else None

    def all(self, attr: str) -> list["Value | WMNode"]:
        return self.attrs.get(attr, [])


class SoarKernel:
    """One Soar agent running in the calling thread (so a decision cycle costs microseconds
    of messaging, and Ctrl-C reaches Python between runs)."""

    def __init__(self, name: str = "aileen") -> None:
        sml = _sml()
        # No listener socket: the kernel serves this process only (and two kernels do not
        # fight over a port).
        self._kernel = sml.Kernel.CreateKernelInCurrentThread(True, sml.Kernel.kSuppressListener)
        if self._kernel.HadError():
            raise UserError(f"Soar: cannot create a kernel: {self._kernel.GetLastErrorDescription()}")
        self._agent = self._kernel.CreateAgent(name)
        if self._agent is None:
            msg = self._kernel.GetLastErrorDescription()
            self._kernel.Shutdown()
            raise UserError(f"Soar: cannot create an agent: {msg}")
        self._printed: list[str] = []
        self._agent.RegisterForPrintEvent(sml.smlEVENT_PRINT, self._on_print, None)
        self.input_link = self._agent.GetInputLink()
        self._closed = False

    def _on_print(self, _id: Any, _data: Any, _agent: Any, message: str) -> None:
        self._printed.append(message)

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

    # ------------------------------------------------------------------ commands
    def command(self, line: str) -> str:
        """Run a Soar command line; a failure raises UserError with Soar's own message."""
        out = self._agent.ExecuteCommandLine(line)
        if not self._agent.GetLastCommandLineResult():
            raise UserError(f"Soar: {line.split()[0]}: {_first_error(out)}")
        return out

    def source(self, path: str | Path) -> None:
        """Load a rule file; a syntax error names file:line, as Soar reports it (exit 2)."""
        p = Path(path)
        out = self._agent.ExecuteCommandLine(f"source {{{p}}}")
        if not self._agent.GetLastCommandLineResult() or "Production addition failed" in out:
            where = re.search(r"(\S+\.soar):(\d+)", out)
            msg = _first_error(out)
            if where:
                raise UserError(msg, path=where.group(1), line=int(where.group(2)))
            raise UserError(msg, path=str(p))

    def printed(self) -> list[str]:
        """What the agent wrote (`write`, traces) since the last call."""
        out, self._printed = self._printed, []
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
    def output(self, depth: int = 8, skip: "set[int] | frozenset[int]" = frozenset()) -> list[tuple[str, WMNode]]:
        """The output-link's commands as (attribute, tree), read now; those whose time tag is
        in `skip` (already served) are not read."""
        ol = self._agent.GetOutputLink()
        if ol is None:
            return []
        out = []
        for i in range(ol.GetNumberChildren()):
            w = ol.GetChild(i)
            if w.IsIdentifier() and w.GetTimeTag() not in skip:
                out.append((w.GetAttribute(), _read(w.ConvertToIdentifier(), w.GetTimeTag(), depth)))
        return out

    def tree(self, ident: Any, depth: int = 8) -> WMNode:
        """An input-link identifier (as `add` returned it) read as a tree, as the agent sees it."""
        return _read(ident, 0, depth)

    def mark(self, node: WMNode, status: str = "complete") -> None:
        """Soar's convention for output commands: `^status complete` (or `error`) on the command."""
        if node.handle is not None:
            if status == "complete":
                node.handle.AddStatusComplete()
            else:
                node.handle.AddStatusError()

    # ------------------------------------------------------------------ running
    def run_until_output(self) -> None:
        """Run until the agent changes its output-link (Soar gives up after its
        max-nil-output-cycles, 15 by default, without output)."""
        self._agent.RunSelfTilOutput()

    def run(self, decisions: int = 1) -> None:
        self._agent.RunSelf(decisions)


def _read(ident: Any, tag: int, depth: int) -> WMNode:
    node = WMNode(ident.GetValueAsString(), tag, ident)
    for i in range(ident.GetNumberChildren()):
        w = ident.GetChild(i)
        attr = w.GetAttribute()
        if w.IsIdentifier():
            if depth <= 0:
                continue
            val: Value | WMNode = _read(w.ConvertToIdentifier(), w.GetTimeTag(), depth - 1)
        else:
            kind = w.GetValueType()
            s = w.GetValueAsString()
            val = int(s) if kind == "int" else float(s) if kind == "double" else s
        node.attrs.setdefault(attr, []).append(val)
    return node


def _first_error(out: str) -> str:
    lines = [ln.strip() for ln in out.splitlines() if ln.strip() and not ln.strip().startswith(("*", "Total:"))]
    return lines[0].split("\t")[0] if lines else "failed"
