"""The concept memory file's content: a `ConceptMemory` as a versioned JSON object and back,
every entry checked on the way in (a malformed file is one `UserError` naming the file and the
entry, never a traceback or a half-loaded memory). Reading and writing the file itself, with
its lock and recovery, is `persist` and `store`."""

from __future__ import annotations

from dataclasses import asdict
from typing import TYPE_CHECKING, Any

from aileen.analogy import sme
from aileen.analogy.sage import Generalization, SageParams
from aileen.errors import UserError
from aileen.memory import persist
from aileen.memory.kinds import KINDS
from aileen.terms import Term, TermSyntaxError, parse

if TYPE_CHECKING:
    from aileen.memory.concept import ConceptMemory


def encode(mem: "ConceptMemory") -> dict[str, Any]:
    """A memory as the versioned JSON object `save` writes."""
    p = mem.params
    return {
        "format": persist.FORMAT,
        "version": persist.VERSION,
        "params": {
            "assimilation": p.assimilation,
            "probability": p.probability,
            "match": p.match,
            "normalisation": p.normalisation,
            "sme": asdict(p.sme),
            "functions": sorted(p.functions),
        },
        "concepts": [
            {
                "symbol": c.symbol,
                "kind": c.kind,
                "generalizations": [
                    {
                        "examples": g.size,
                        "next_entity": g.next_entity,
                        "facts": [{"fact": str(f), "count": g.counts[f]} for f in g.probabilities()],
                    }
                    for g in c.context.generalizations
                ],
                "examples": [[str(f) for f in ex] for ex in c.context.examples],
                **({"near_misses": [[str(f) for f in nm] for nm in c.near_misses]} if c.near_misses else {}),
            }
            for c in mem.concepts()
        ],
        **({"annotations": mem.annotations} if mem.annotations else {}),
    }


def decode(cls: "type[ConceptMemory]", data: dict[str, Any], path: str = "<memory>") -> "ConceptMemory":
    """Rebuild a memory from `encode` output; malformed entries raise `UserError` naming `path`."""

    def bad(what: str) -> UserError:
        return UserError(f"malformed memory file: {what}", path=path)

    def fact(text: Any, where: str) -> Term:
        if not isinstance(text, str):
            raise bad(f"{where}: expected a fact as a string, found {text!r}")
        try:
            return parse(text)
        except TermSyntaxError as exc:
            raise bad(f"{where}: {exc}") from None

    pd = data.get("params", {})
    if not isinstance(pd, dict) or not isinstance(pd.get("sme", {}), dict):
        raise bad("expected an object under \"params\" (and under \"params\".\"sme\")")
    if not isinstance(pd.get("functions", []), list) or not all(isinstance(f, str) for f in pd.get("functions", [])):
        raise bad("\"params\".\"functions\" must be a list of names")
    try:
        params = SageParams(
            assimilation=float(pd.get("assimilation", 0.01)),
            probability=float(pd.get("probability", 0.6)),
            match=float(pd.get("match", 0.75)),
            normalisation=str(pd.get("normalisation", "significant")),
            sme=sme.Params(**pd.get("sme", {})),
            functions=frozenset(pd.get("functions", ())),
        )
    except (TypeError, ValueError, AttributeError) as exc:
        raise bad(f"params: {exc}") from None
    mem = cls(params)
    concepts = data.get("concepts")
    if not isinstance(concepts, list):
        raise bad("expected a list under \"concepts\"")
    for ci, cd in enumerate(concepts):
        where = f"concept {ci + 1}"
        if not isinstance(cd, dict) or not isinstance(cd.get("symbol"), str):
            raise bad(f"{where}: expected an object with a \"symbol\"")
        where = f"concept {cd['symbol']!r}"
        if mem.has(cd["symbol"]):
            raise bad(f"{where} appears twice (concept {ci + 1})")
        if not isinstance(cd.get("kind", "visual"), str):
            raise bad(f"{where}: \"kind\" must be one of {', '.join(KINDS)}")
        for key in ("generalizations", "examples"):
            if not isinstance(cd.get(key, []), list):
                raise bad(f"{where}: expected a list under \"{key}\"")
        try:
            c = mem.create(cd["symbol"], cd.get("kind", "visual"))
        except UserError as exc:
            raise bad(f"{where}: {exc.message}") from None
        for gi, gd in enumerate(cd.get("generalizations", [])):
            gw = f"{where}, generalization {gi}"
            if not isinstance(gd, dict) or not isinstance(gd.get("facts"), list):
                raise bad(f"{gw}: expected an object with \"facts\"")
            size = gd.get("examples")
            if not isinstance(size, int) or size < 1:
                raise bad(f"{gw}: \"examples\" must be a positive integer")
            counts: dict[Term, int] = {}
            for fd in gd["facts"]:
                if not isinstance(fd, dict):
                    raise bad(f"{gw}: expected {{\"fact\": ..., \"count\": ...}}, found {fd!r}")
                f = fact(fd.get("fact"), gw)
                n = fd.get("count")
                if not isinstance(n, int) or not 1 <= n <= size:
                    raise bad(f"{gw}: count of {f} must be an integer in 1..{size}")
                counts[f] = n
            nxt = gd.get("next_entity", 0)
            if not isinstance(nxt, int) or nxt < 0:
                raise bad(f"{gw}: \"next_entity\" must be a non-negative integer")
            c.context.generalizations.append(Generalization(c.symbol, counts, size, nxt))
        for ei, ed in enumerate(cd.get("examples", [])):
            if not isinstance(ed, list):
                raise bad(f"{where}, example {ei}: expected a list of facts")
            c.context.examples.append([fact(x, f"{where}, example {ei}") for x in ed])
        if not isinstance(cd.get("near_misses", []), list):
            raise bad(f"{where}: expected a list under \"near_misses\"")
        for ni, nd in enumerate(cd.get("near_misses", [])):
            if not isinstance(nd, list) or not nd:
                raise bad(f"{where}, near miss {ni}: expected a non-empty list of facts")
            c.near_misses.append([fact(x, f"{where}, near miss {ni}") for x in nd])
    notes = data.get("annotations", {})
    if not isinstance(notes, dict):
        raise bad("expected an object under \"annotations\"")
    why = persist.check_annotations(notes)
    if why:
        raise bad(why)
    mem.annotations = notes
    return mem
