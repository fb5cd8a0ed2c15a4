"""The concept memory served on a Soar agent's output-link, in the manner of smem/epmem.

A command is `(<ol> ^concept-memory <cm>)` with `(<cm> ^command create|store|query|project
^concept <symbol> ...)`; its facts are working-memory structures (see `aileen.soar.wm`).
`ConceptMemory` executes it, the answer goes on the input-link under
`(<il> ^concept-memory <cmi>)` as `(<cmi> ^result <r>)` with the command's `^tag` echoed, and
the command is marked `^status complete` (or `^status error`), as Soar's conventions ask.
A malformed command gets `^status error ^message |...|`; nothing raises in the kernel.

    create   ^concept C ^kind visual|spatial|action
    store    ^concept C ^fact F ...                      (the example, membership fact included)
    query    ^concept C ^pattern P ^fact F ...            -> ^inference (^fact ^similarity)
    project  ^concept C ^fact F ... (a trace: h/after/isa(t0,start) facts)
                                                          -> ^fact ..., ^complete, ^similarity
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any

from aileen.errors import UserError
from aileen.memory.concept import ConceptMemory
from aileen.soar import wm
from aileen.soar.kernel import SoarKernel, WMNode
from aileen.terms import Term

COMMANDS = ("create", "store", "query", "project")
_RANK = {"create": 0, "store": 1, "query": 2, "project": 3}


@dataclass
class Served:
    """One command as the bridge executed it (the agent's learning record and the benchmark's)."""

    command: str
    concept: str
    status: str  # success | failure | error
    message: str = ""
    seconds: float = 0.0


class BadCommand(ValueError):
    pass


class ConceptMemoryBridge:
    """Executes the concept-memory commands a Soar agent puts on its output-link."""

    def __init__(self, kernel: SoarKernel, memory: ConceptMemory) -> None:
        self.kernel = kernel
        self.memory = memory
        self._root = kernel.add(kernel.input_link, "concept-memory")
        self._results: list[Any] = []
        self._done: set[int] = set()  # time tags of commands already served

    def reset(self) -> None:
        """Take every answer off the input-link (a new lesson: the old commands are done)."""
        for r in self._results:
            self.kernel.remove(r)
        self._results.clear()

    def answers(self) -> list[WMNode]:
        """The answers now on the input-link (`^result` structures), oldest first."""
        return [self.kernel.tree(r) for r in self._results]

    def serve(self) -> list[Served]:
        """Execute the new commands on the output-link (creates before stores, stores in
        their `^order`), put the answers on the input-link, mark the commands; commit."""
        todo = [n for a, n in self.kernel.output(skip=self._done) if a == "concept-memory"
                and n.get("status") is None]
        todo.sort(key=lambda n: (_RANK.get(str(n.get("command")), 9), _num(n.get("order")), str(n.get("tag"))))
        served = []
        for node in todo:
            self._done.add(node.tag)
            served.append(self._serve_one(node))
        if served:
            self.kernel.commit()
        return served

    def _serve_one(self, node: WMNode) -> Served:
        t0 = time.perf_counter()
        res = self.kernel.add(self._root, "result")
        self._results.append(res)
        tag = node.get("tag")
        if tag is not None and not isinstance(tag, WMNode):
            self.kernel.add(res, "tag", tag)
        cmd = str(node.get("command"))
        self.kernel.add(res, "command", cmd)
        concept = node.get("concept")
        try:
            if cmd not in COMMANDS:
                raise BadCommand(f"unknown ^command {cmd!r}; expected one of {', '.join(COMMANDS)}")
            if concept is None or isinstance(concept, WMNode):
                raise BadCommand(f"{cmd}: missing ^concept")
            concept = str(concept)
            self.kernel.add(res, "concept", concept)
            status = getattr(self, "_" + cmd)(node, concept, res)
            message = ""
        except (BadCommand, wm.MalformedFact, UserError, ValueError, KeyError) as exc:
            status, message = "error", exc.format() if isinstance(exc, UserError) else str(exc)
            self.kernel.add(res, "message", message)
        self.kernel.add(res, "status", status)
        self.kernel.mark(node, "error" if status == "error" else "complete")
        return Served(cmd, str(concept), status, message, time.perf_counter() - t0)

    # ------------------------------------------------------------------ the four commands
    def _create(self, node: WMNode, concept: str, res: Any) -> str:
        kind = node.get("kind")
        if kind is None or isinstance(kind, WMNode):
            raise BadCommand("create: missing ^kind")
        if self.memory.has(concept):
            self.kernel.add(res, "message", f"{concept} exists")
            return "failure"
        self.memory.create(concept, str(kind))
        return "success"

    def _store(self, node: WMNode, concept: str, res: Any) -> str:
        facts = wm.terms(node.all("fact"))
        if not facts:
            raise BadCommand("store: no ^fact")
        if not self.memory.has(concept):
            raise BadCommand(f"store: no concept {concept} (create it first)")
        self.memory.store(_ordered(facts), concept)
        return "success"

    def _query(self, node: WMNode, concept: str, res: Any) -> str:
        pattern = node.get("pattern")
        if not isinstance(pattern, WMNode):
            raise BadCommand("query: missing ^pattern")
        found = self.memory.query(_ordered(wm.terms(node.all("fact"))), wm.term(pattern), concept)
        for inf in found:
            i = self.kernel.add(res, "inference")
            wm.put(self.kernel, i, "fact", inf.fact)
            self.kernel.add(i, "similarity", float(inf.similarity))
        return "success" if found else "failure"

    def _project(self, node: WMNode, concept: str, res: Any) -> str:
        proj = self.memory.project(_ordered(wm.terms(node.all("fact"))), concept)
        wm.put_all(self.kernel, res, "fact", proj.facts)
        self.kernel.add(res, "complete", "true" if proj.complete else "false")
        self.kernel.add(res, "similarity", float(proj.similarity))
        return "success" if proj.facts else "failure"


def _ordered(facts: list[Term]) -> list[Term]:
    """Working memory is a set: give the memory its facts in one fixed order (percepts of
    each object, then relations), so a run does not depend on time tags."""
    return sorted(set(facts), key=_fact_key)


def _fact_key(f: Term) -> tuple:
    first = str(f.args[0]) if f.args else ""
    digits = first.lstrip("o")
    obj = (int(digits), first) if digits.isdigit() else (1 << 30, first)
    return (0 if f.name == "isa" else 1, obj, str(f))


def _num(v: object) -> float:
    return float(v) if isinstance(v, (int, float)) else float("inf")
