"""Projection: the next state an action concept asks for, given the episodic trace of what
the agent has done so far (the paper's section 4, "project"), and the trace's time points in
order (`time_chain`).

Why a module of its own: projecting reads one action concept's context and the trace, and
nothing else of the memory (neither its index nor its caches, which are recognition's:
`memory/recognition.py`); `ConceptMemory.project` hands the concept it names to `project`.
It scores its mappings as a query does (`recognition.similarity`).

Pure computation on `Term`s.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field, replace

from aileen.analogy import sme
from aileen.analogy.sage import SageParams
from aileen.memory.codec import StoredConcept
from aileen.memory.recognition import has_skolem, similarity
from aileen.terms import Term, as_term

__all__ = ["Projection", "project", "time_chain", "latest_time_point"]


@dataclass
class Projection:
    """The next desired state of an action, projected from the trace so far."""

    facts: list[Term]
    complete: bool
    similarity: float
    time_point: Term | None = None  # the skolem time point the facts hold at
    after: Term | None = None  # the trace's latest time point
    unresolved: list[Term] = field(default_factory=list)  # next-state facts about unknown entities
    source: str | None = None
    index: int | None = None
    mapping: sme.Mapping | None = field(default=None, repr=False)


def project(trace: Iterable[Term | str], concept: StoredConcept, params: SageParams) -> Projection:
    """The state after the trace's latest time point, as the action concept has it.

    The trace is `h(T, Fact)`, `after(T1, T0)` and `isa(t0, start)` facts. Candidate
    inferences `after(S, latest)` name the next time point S (a skolem); the facts are those
    of the inferences `h(S, F)`, with the trace's entities in them. `complete` is true when
    the generalization has no time point after S (or the trace already reached its last).
    `params` are the memory's.
    """
    facts = [as_term(f) for f in trace]
    chain = time_chain(facts)
    latest = chain[-1] if chain else None
    trace_index = {t: i for i, t in enumerate(chain)}
    # Keep every mapping (no cutoff): a weaker one may be the temporally coherent one.
    loose = replace(params, sme=replace(params.sme, cutoff=0.0))
    best: Projection | None = None
    best_key: tuple = ()
    anchors = _anchors(facts, concept.symbol)

    def require(base: list[Term]) -> dict[Term, Term]:
        # The action's start aligns with the trace's start, and its arguments with the
        # trace's when the trace names them (`r_move_right_of(o1,o2)`): otherwise a start
        # state that looks like the end state with the roles swapped can win the match.
        req: dict[Term, Term] = {}
        for key, b in _anchors(base, concept.symbol).items():
            t = anchors.get(key)
            if t is not None and len(t) == len(b):
                req.update((x, y) for x, y in zip(b, t) if sme.is_entity(x) and sme.is_entity(y))
        return req

    for cand in concept.context.match(facts, loose, require=require):
        has_next = {f.args[1] for f in cand.base if f.name == "after" and len(f.args) == 2}
        base_index = {t: i for i, t in enumerate(time_chain(cand.base))}
        for m in cand.mappings:
            sim = similarity(m, cand.base, None, params)
            proj = _project_one(m, latest, has_next, sim)
            if proj is None:
                continue
            # Coherent: every trace time point mapped lies as far from the start as its
            # correspondent in the action (t1 is the action's second state, not its third).
            coherent = all(
                base_index.get(b) == trace_index[t] for b, t in m.pairs.items() if t in trace_index
            )
            proj.source, proj.index, proj.mapping = cand.kind, cand.index, m
            key = (coherent, sim, len(proj.facts))
            if best is None or key > best_key:
                best, best_key = proj, key
    if best is None:
        return Projection(facts=[], complete=False, similarity=0.0, after=latest)
    return best


def _project_one(m: sme.Mapping, latest: Term | None, has_next: set[Term], sim: float) -> Projection | None:
    """What one mapping projects: the facts at the time point it infers after `latest` (a
    skolem), or none when the trace already reached one of the action's time points; None
    when the trace has no time point or the mapping places `latest` nowhere in the action."""
    if latest is None:
        return None
    inv = {t: b for b, t in m.pairs.items()}
    nxt: Term | None = None
    for inf in m.inferences:
        if inf.name == "after" and len(inf.args) == 2 and inf.args[1] is latest and inf.args[0].name == "skolem":
            nxt = inf.args[0]
            break
    if nxt is None:
        base_latest = inv.get(latest)
        if base_latest is None:
            return None
        # The trace reached a time point of the action: complete when it is the last.
        return Projection(facts=[], complete=base_latest not in has_next, similarity=sim, after=latest)
    out: list[Term] = []
    unresolved: list[Term] = []
    for inf in m.inferences:
        if inf.name == "h" and len(inf.args) == 2 and inf.args[0] is nxt:
            f = inf.args[1]
            (unresolved if has_skolem(f) else out).append(f)
    base_tp = nxt.args[0]
    return Projection(facts=out, complete=base_tp not in has_next, similarity=sim,
                      time_point=nxt, after=latest, unresolved=unresolved)


def _anchors(facts: Iterable[Term], concept: str) -> dict[str, tuple[Term, ...]]:
    """The start time point (`isa(T,start)`) and the concept's own fact's arguments."""
    out: dict[str, tuple[Term, ...]] = {}
    for f in facts:
        if f.name == "isa" and len(f.args) == 2 and f.args[1].name == "start" and not f.args[1].args:
            out["start"] = (f.args[0],)
        elif f.name == concept and f.args:
            out["concept"] = f.args
    return out


def time_chain(trace: Iterable[Term]) -> list[Term]:
    """The time points of a trace in order: from the start (`isa(T, start)`, else the first
    time point that follows none) along the `after(T1, T0)` links."""
    nxt: dict[Term, Term] = {}
    later: set[Term] = set()
    points: list[Term] = []
    start: Term | None = None
    for f in trace:
        if f.name == "after" and len(f.args) == 2:
            nxt[f.args[1]] = f.args[0]
            later.add(f.args[0])
            points.extend((f.args[1], f.args[0]))
        elif f.name == "isa" and len(f.args) == 2 and f.args[1].name == "start" and not f.args[1].args:
            start = f.args[0]
            points.append(start)
        elif f.name == "h" and len(f.args) == 2:
            points.append(f.args[0])
    if start is None:
        firsts = [p for p in dict.fromkeys(points) if p not in later]
        if not firsts:
            return []
        start = firsts[0]
    out = [start]
    seen = {start}
    while out[-1] in nxt and nxt[out[-1]] not in seen:
        out.append(nxt[out[-1]])
        seen.add(out[-1])
    return out


def latest_time_point(trace: Iterable[Term]) -> Term | None:
    """The last time point of a trace (see `time_chain`), or None without time points."""
    chain = time_chain(trace)
    return chain[-1] if chain else None
