"""The concept memory file's content: a `ConceptMemory` as a versioned JSON object and back,
every entry checked on the way in (a malformed file is one `UserError` naming the file and the
entry, never a traceback or a half-loaded memory). Reading and writing the file itself, with
its lock and recovery, is `persist` and `store`."""

from __future__ import annotations

import contextlib
import gc
import json
import math
from collections.abc import Callable, Iterator, Sequence
from dataclasses import asdict, dataclass
from typing import Any, Protocol, TypeVar

from aileen.analogy import sme
from aileen.analogy.sage import NORMALISATIONS, Generalization, GeneralizationContext, SageParams
from aileen.errors import UserError
from aileen.memory import persist
from aileen.memory.kinds import KINDS
from aileen.terms import Term, TermSyntaxError, parse, variables


class StoredConcept(Protocol):
    """What the file holds of one concept, and all that recognition and projection read of one
    (`aileen.memory.concept.Concept` is one)."""

    symbol: str
    kind: str
    context: GeneralizationContext
    near_misses: list[list[Term]]


class StoredMemory(Protocol):
    """What the codec reads of a memory and fills in (`aileen.memory.concept.ConceptMemory`
    is one). Declared here, so the file's content is defined without the memory's behaviour:
    the memory uses the codec, never the other way round."""

    params: SageParams
    annotations: dict[str, Any]

    def concepts(self) -> Sequence[StoredConcept]: ...

    def has(self, symbol: str) -> bool: ...

    def create(self, symbol: str, kind: str) -> StoredConcept: ...


M = TypeVar("M", bound=StoredMemory)


@contextlib.contextmanager
def gc_paused() -> Iterator[None]:
    """Python's cycle collector paused while a memory is read in bulk. Why: reading 100,000
    concepts makes millions of terms, tuples and dicts, none of them garbage, and the
    collector would walk them again and again (about half of the reading time)."""
    was = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was:
            gc.enable()


def encode_params(p: SageParams) -> dict[str, Any]:
    """The `"params"` object of the file."""
    return {
        "assimilation": p.assimilation,
        "probability": p.probability,
        "match": p.match,
        "normalisation": p.normalisation,
        "sme": asdict(p.sme),
        "functions": sorted(p.functions),
    }


def encode(mem: StoredMemory) -> dict[str, Any]:
    """A memory as the versioned JSON object `save` writes."""
    return {
        "format": persist.FORMAT,
        "version": persist.VERSION,
        "params": encode_params(mem.params),
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


#: The keys each object of the file may have. Anything else is refused with its name rather
#: than dropped at the next save; "annotations" is the place for a person's own entries.
TOP_KEYS = ("format", "version", "params", "concepts", "annotations")
CONCEPT_KEYS = ("symbol", "kind", "generalizations", "examples", "near_misses")
GENERALIZATION_KEYS = ("examples", "next_entity", "facts")
FACT_KEYS = ("fact", "count")
PARAM_KEYS = ("assimilation", "probability", "match", "normalisation", "sme", "functions")


@dataclass(frozen=True)
class Range:
    """What a numeric parameter may be: a whole number or any number, between `low` and
    `high` (each end included unless `open_low` / `open_high`)."""

    low: float
    high: float
    whole: bool = False
    open_low: bool = False

    def describe(self) -> str:
        kind = "a whole number" if self.whole else "a number"
        low = f"> {self.low:g}" if self.open_low else f">= {self.low:g}"
        return f"{kind} {low} and <= {self.high:g}"

    def holds(self, v: Any) -> bool:
        if isinstance(v, bool) or not isinstance(v, (int, float)) or (self.whole and not isinstance(v, int)):
            return False
        if not math.isfinite(v):
            return False
        return (v > self.low if self.open_low else v >= self.low) and v <= self.high


#: Each parameter's range. The thresholds are similarities or probabilities; SME's scores are
#: small positive numbers (the match score is their sum, trickled down the structure); at
#: least one mapping must be kept; `cutoff` is a fraction of the best mapping's score.
SAGE_RANGES: dict[str, Range] = {"assimilation": Range(0, 1), "probability": Range(0, 1), "match": Range(0, 1)}
SME_RANGES: dict[str, Range] = {
    "same_functor": Range(0, 1, open_low=True),
    "same_function": Range(0, 1),
    "trickle_down": Range(0, 1000),
    "max_mappings": Range(1, 1000, whole=True),
    "cutoff": Range(0, 1),
}


def _known_keys(obj: dict[str, Any], known: tuple[str, ...], where: str, bad: Any) -> None:
    extra = [k for k in obj if k not in known]
    if extra:
        raise bad(f"{where}: unknown key {json.dumps(extra[0])} (expected {', '.join(known)}); "
                  "a note of your own belongs under \"annotations\"")


def decode_annotations(data: dict, bad: Any) -> dict:
    """A memory file's `annotations` (the console's notes on concepts), checked; `bad(text)`
    makes the error to raise. Both file forms read them through here."""
    notes = data.get("annotations", {})
    if not isinstance(notes, dict):
        raise bad("expected an object under \"annotations\"")
    why = persist.check_annotations(notes)
    if why:
        raise bad(why)
    return notes


def decode_params(pd: Any, bad: Any = None) -> SageParams:
    """The `"params"` object as `SageParams`, every field checked for type and range; `bad`
    makes the error (a `UserError` naming the field, e.g. `"params"."sme"."cutoff" must be
    a number >= 0 and <= 1, found 5`)."""
    if bad is None:
        def bad(what: str) -> UserError:
            return UserError(f"malformed memory file: {what}")

    if not isinstance(pd, dict):
        raise bad("expected an object under \"params\"")
    _known_keys(pd, PARAM_KEYS, "\"params\"", bad)
    values: dict[str, Any] = {}
    for name, rng in SAGE_RANGES.items():
        if name in pd:
            if not rng.holds(pd[name]):
                raise bad(f"\"params\".\"{name}\" must be {rng.describe()}, found {json.dumps(pd[name])[:40]}")
            values[name] = float(pd[name])
    if "normalisation" in pd:
        if pd["normalisation"] not in NORMALISATIONS:
            raise bad(f"\"params\".\"normalisation\" must be one of {', '.join(NORMALISATIONS)}, "
                      f"found {json.dumps(pd['normalisation'])[:40]}")
        values["normalisation"] = pd["normalisation"]
    functions = pd.get("functions", [])
    if not isinstance(functions, list) or not all(isinstance(f, str) for f in functions):
        raise bad("\"params\".\"functions\" must be a list of names")
    sd = pd.get("sme", {})
    if not isinstance(sd, dict):
        raise bad("expected an object under \"params\".\"sme\"")
    _known_keys(sd, tuple(SME_RANGES), "\"params\".\"sme\"", bad)
    sme_values: dict[str, Any] = {}
    for name, rng in SME_RANGES.items():
        if name in sd:
            if not rng.holds(sd[name]):
                raise bad(f"\"params\".\"sme\".\"{name}\" must be {rng.describe()}, found {json.dumps(sd[name])[:40]}")
            sme_values[name] = sd[name] if rng.whole else float(sd[name])
    return SageParams(**values, sme=sme.Params(**sme_values), functions=frozenset(functions))


def decode(cls: Callable[[SageParams], M], data: dict[str, Any], path: str = "<memory>") -> M:
    """Rebuild a memory from `encode` output; malformed entries raise `UserError` naming `path`.
    `cls` makes an empty memory with the file's parameters (`ConceptMemory`)."""
    with gc_paused():
        return _decode(cls, data, path)


def _decode(cls: Callable[[SageParams], M], data: dict[str, Any], path: str) -> M:

    def bad(what: str) -> UserError:
        return UserError(f"malformed memory file: {what}", path=path)

    def fact(text: Any, where: str) -> Term:
        if not isinstance(text, str):
            raise bad(f"{where}: expected a fact as a string, found {text!r}")
        try:
            f = parse(text)
        except TermSyntaxError as exc:
            raise bad(f"{where}: {exc}") from None
        var = next(variables(f), None)
        if var is not None:  # a stored fact is of one scene: it loaded, and the word went unrecognised
            raise bad(f"{where}: fact {f} holds the variable {var}; a stored fact names objects (o1, gen_ent(0,r_red))")
        return f

    _known_keys(data, TOP_KEYS, "the top level", bad)
    params = decode_params(data.get("params", {}), bad)
    mem = cls(params)
    concepts = data.get("concepts")
    if not isinstance(concepts, list):
        raise bad("expected a list under \"concepts\"")
    for ci, cd in enumerate(concepts):
        where = f"concept {ci + 1}"
        if not isinstance(cd, dict) or not isinstance(cd.get("symbol"), str):
            raise bad(f"{where}: expected an object with a \"symbol\"")
        where = f"concept {cd['symbol']!r}"
        _known_keys(cd, CONCEPT_KEYS, where, bad)
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
            _known_keys(gd, GENERALIZATION_KEYS, gw, bad)
            size = gd.get("examples")
            if not isinstance(size, int) or size < 1:
                raise bad(f"{gw}: \"examples\" must be a positive integer")
            counts: dict[Term, int] = {}
            for fd in gd["facts"]:
                if not isinstance(fd, dict):
                    raise bad(f"{gw}: expected {{\"fact\": ..., \"count\": ...}}, found {fd!r}")
                _known_keys(fd, FACT_KEYS, gw, bad)
                f = fact(fd.get("fact"), gw)
                n = fd.get("count")
                if not isinstance(n, int) or not 1 <= n <= size:
                    raise bad(f"{gw}: count of {f} must be an integer in 1..{size}")
                if f in counts:  # (merged silently, the next save dropped one: as a repeated key)
                    raise bad(f"{gw}: fact {f} appears twice")
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
    mem.annotations = decode_annotations(data, bad)
    return mem
