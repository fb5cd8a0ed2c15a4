"""The concept memory (and the planner) served on a Soar agent's output-link, as smem/epmem are.

A command is `(<ol> ^concept-memory <cm>)` with `(<cm> ^command create|store|query|project|plan
^concept <symbol> ...)`; its facts are working-memory structures (see `aileen.soar.wm`).
Soar's output event hands every new command to the bridge in the output phase that made it;
after that phase the bridge executes them (creates first, then stores in their `^order`,
then queries, projections and plans), puts each answer on the input-link under
`(<il> ^concept-memory <cmi>)` as `(<cmi> ^result <r>)` with the command's `^tag` echoed, and
marks the command `^status complete` (or `^status error`), as Soar's conventions ask. When
the agent removes a command, its answer is removed with it, so answers never pile up.

Every command is checked in full before anything is executed: a structure nested too deep
or with a cycle, a name the memory file cannot read back (a numeric or empty predicate,
`|o 1|`), a bare `^fact foo`, a concept named for a reserved predicate (`isa`, `h`, a
calculus relation): `^status error ^message |...|`, nothing stored, nothing raised in the
kernel.

    create   ^concept C ^kind visual|spatial|action
    store    ^concept C ^fact F ...                      (the example, membership fact included)
    query    ^concept C ^pattern P ^fact F ...            -> ^inference (^fact ^similarity),
                                                             ^length L (action concepts: time points
                                                             of each description)
    project  ^concept C ^fact F ... (a trace: h/after/isa(t0,start) facts)
                                                          -> ^fact ... (each with its ^order),
                                                             ^size, ^complete, ^similarity
    plan     ^fact F ... (the state) ^goal G ... [^depth D]
                                                          -> ^step (^index ^action ^relation ...)
"""

from __future__ import annotations

import time
from collections import deque
from dataclasses import dataclass
from typing import Any

from aileen.agent import verbs
from aileen.domain import calculi, predicates
from aileen.errors import UserError
from aileen.memory.concept import ConceptMemory
from aileen.memory.projection import time_chain
from aileen.soar import wm
from aileen.soar.kernel import SoarKernel, WMNode
from aileen.terms import Term

COMMANDS = ("create", "store", "query", "project", "plan")
_RANK = {"create": 0, "store": 1, "query": 2, "project": 3, "plan": 4}
#: Names no concept may take: the predicates the memory's facts are made of (a concept `isa`
#: would make `isa(o1,isa)` both a percept and a membership; `w` a direction and a word).
RESERVED: frozenset[str] = frozenset(
    predicates.MEMORY | {"held", "pointed", calculi.MOVED} | verbs.ROLE_FACTS
    | {r for c in calculi.CALCULI for r in c.relations})


def reserved() -> frozenset[str]:
    """`RESERVED` with the relations of calculi declared since (`calculi.declare`)."""
    return RESERVED | {r for c in calculi.CALCULI for r in c.relations}


DEFAULT_PLAN_DEPTH = 6
MAX_PLAN_DEPTH = 12
SERVED_LOG = 4096  # the bridge keeps the latest commands it served for `serve()` to hand out


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

    def __init__(self, kernel: SoarKernel, memory: ConceptMemory, *, rules: str | None = None) -> None:
        self.kernel = kernel
        self.memory = memory
        self.rules = rules  # ASP rule files for `plan` (None: the shipped ones)
        self._root = kernel.add(kernel.input_link, "concept-memory")
        self._results: dict[int, Any] = {}  # command time tag -> its answer on the input-link
        self._pending: list[WMNode] = []
        self._log: deque[Served] = deque(maxlen=SERVED_LOG)
        kernel.on_output("concept-memory", self._arrived)
        kernel.on_after_output(self._after_output)

    def reset(self) -> None:
        """Take every answer off the input-link."""
        for r in self._results.values():
            self.kernel.remove(r)
        self._results.clear()
        self.kernel.commit()

    def answers(self) -> list[WMNode]:
        """The answers now on the input-link (`^result` structures), oldest first."""
        return [self.kernel.tree(r) for r in self._results.values()]

    def serve(self) -> list[Served]:
        """The commands served since the last call (Soar's output events serve them as the
        agent runs), after serving any still waiting."""
        self._after_output()
        out = list(self._log)
        self._log.clear()
        return out

    def _arrived(self, node: WMNode) -> None:
        self._pending.append(node)

    def _after_output(self) -> None:
        """After an output phase: drop the answers of commands the agent removed, execute the
        new commands (creates before stores, stores in their `^order`), commit."""
        changed = False
        for tag in self.kernel.removed():
            res = self._results.pop(tag, None)
            if res is not None:
                self.kernel.remove(res)
                changed = True
        todo, self._pending = self._pending, []
        todo = [n for n in todo if n.error or n.get("status") is None]
        todo.sort(key=lambda n: (_RANK.get(str(n.get("command")), 9), _num(n.get("order")), str(n.get("tag"))))
        for node in todo:
            self._log.append(self._serve_one(node))
        if changed or todo:
            self.kernel.commit()

    def _serve_one(self, node: WMNode) -> Served:
        t0 = time.perf_counter()
        res = self.kernel.add(self._root, "result")
        old = self._results.pop(node.tag, None)
        if old is not None:
            self.kernel.remove(old)
        self._results[node.tag] = res
        tag = node.get("tag")
        if tag is not None and not isinstance(tag, WMNode):
            self.kernel.add(res, "tag", tag)
        cmd = str(node.get("command"))
        self.kernel.add(res, "command", cmd)
        concept: str | None = None
        try:
            if node.error:
                raise BadCommand(node.error)
            if cmd not in COMMANDS:
                raise BadCommand(f"unknown ^command {cmd!r}; expected one of {', '.join(COMMANDS)}")
            if cmd != "plan":
                if node.get("concept") is None:
                    raise BadCommand(f"{cmd}: missing ^concept")
                concept = wm.symbol(node.get("concept"), f"{cmd}: ^concept")
                if concept in reserved():
                    raise BadCommand(f"{cmd}: ^concept {concept} is a reserved name (a predicate of the "
                                     "memory's facts)")
                self.kernel.add(res, "concept", concept)
            status = getattr(self, "_" + cmd)(node, concept, res)
            message = ""
        except (BadCommand, wm.MalformedFact, UserError, ValueError, KeyError) as exc:
            status, message = "error", exc.format() if isinstance(exc, UserError) else str(exc)
            self.kernel.add(res, "message", message)
        self.kernel.add(res, "status", status)
        self.kernel.mark(node, "error" if status == "error" else "complete")
        return Served(cmd, str(concept), status, message, time.perf_counter() - t0)

    # ------------------------------------------------------------------ the commands
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
        facts = wm.facts(node.all("fact"))
        if not facts:
            raise BadCommand("store: no ^fact")
        if not self.memory.has(concept):
            raise BadCommand(f"store: no concept {concept} (create it first)")
        if not any(concept in (str(f.name), *map(str, f.args)) for f in facts):
            raise BadCommand(f"store: no ^fact names {concept} (the membership fact)")
        self.memory.store(_ordered(facts), concept)
        return "success"

    def _query(self, node: WMNode, concept: str, res: Any) -> str:
        pattern = node.get("pattern")
        if pattern is None:
            raise BadCommand("query: missing ^pattern")
        pat = wm.fact(pattern)
        scene = _ordered(wm.facts(node.all("fact")))
        if not self.memory.has(concept):
            raise BadCommand(f"query: no concept {concept}")
        found = self.memory.query(scene, pat, concept)
        for inf in found:
            i = self.kernel.add(res, "inference")
            wm.put(self.kernel, i, "fact", inf.fact)
            self.kernel.add(i, "similarity", float(inf.similarity))
        for n in sorted({len(time_chain(d)) for d in self.memory.descriptions(concept)} - {0}):
            self.kernel.add(res, "length", n)
        return "success" if found else "failure"

    def _project(self, node: WMNode, concept: str, res: Any) -> str:
        trace = _ordered(wm.facts(node.all("fact")))
        if not self.memory.has(concept):
            raise BadCommand(f"project: no concept {concept}")
        proj = self.memory.project(trace, concept)
        for k, f in enumerate(proj.facts, 1):  # in the memory's order: the planner ranks a region's relations by it
            node = wm.put(self.kernel, res, "fact", f)
            if f.args:
                self.kernel.add(node, "order", k)
        self.kernel.add(res, "size", len(proj.facts))
        self.kernel.add(res, "complete", "true" if proj.complete else "false")
        self.kernel.add(res, "similarity", float(proj.similarity))
        return "success" if proj.facts else "failure"

    def _plan(self, node: WMNode, _concept: None, res: Any) -> str:
        from aileen.reasoning import planner

        state = _ordered(wm.facts(node.all("fact")))
        goal = _ordered(wm.facts(node.all("goal")))
        if not goal:
            raise BadCommand("plan: no ^goal")
        depth = node.get("depth") if node.get("depth") is not None else DEFAULT_PLAN_DEPTH
        if not isinstance(depth, int) or not 0 <= depth <= MAX_PLAN_DEPTH:
            raise BadCommand(f"plan: ^depth must be an integer in 0..{MAX_PLAN_DEPTH}, found {depth!r}")
        try:
            found = planner.plan(state, goal, max_depth=depth, rules=self.rules)
        except planner.NoPlan as exc:
            self.kernel.add(res, "message", str(exc))
            return "failure"
        self.kernel.add(res, "depth", found.depth)
        for k, step in enumerate(found.steps, 1):
            s = self.kernel.add(res, "step")
            self.kernel.add(s, "index", k)
            wm.put(self.kernel, s, "action", step.action)
            for i, r in enumerate(step.relations, 1):  # in order: the body samples the region by it
                self.kernel.add(wm.put(self.kernel, s, "relation", r), "rank", i)
        return "success"


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
