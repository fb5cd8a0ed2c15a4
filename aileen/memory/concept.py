"""The analogical concept memory: create, store, query and project (the paper's section 4).

Why: concepts in AILEEN are generalization contexts (SAGE over SME), not rules. The agent
creates a concept when a word is new, stores examples when comprehension fails, queries the
memory to recognise concepts in a scene (candidate inferences that fit a pattern, accepted
when the match is similar enough) and projects an action concept onto the episodic trace of
what it has done so far, to get the next state it should bring about.

The memory's jobs live in three modules, cut where the state each one needs is cut. This one
holds the concepts: creating them, storing into them, the change log, and reading and writing
the memory file. Recognising concepts in a scene (`query`, `fitting`) is
`memory/recognition.py`, with the content index and the caches that spare SME, which nothing
here reads; projecting an action concept onto a trace (`project`) is `memory/projection.py`,
which reads only the one concept. `ConceptMemory` hands those calls on, and the names those
modules define are importable from here as before (`Inference`, `Projection`, `time_chain`,
`CONTEXT_MAC`, ...).

Everything here is pure computation on `Term`s except `save` / `load`.
"""

from __future__ import annotations

import os
from collections import Counter
from collections.abc import Callable, Collection, Iterable
from dataclasses import dataclass
from typing import Any

from aileen.analogy.sage import Generalization, GeneralizationContext, SageParams
from aileen.errors import UserError
from aileen.memory import codec, compact, persist, projection, recognition, retrieval
from aileen.terms import Term, TermSyntaxError, as_term, parse

__all__ = [
    "KINDS",
    "Concept",
    "StoreResult",
    "Inference",
    "Projection",
    "ConceptMemory",
]

#: Concept kinds the agent creates.
from aileen.memory.kinds import KINDS  # noqa: E402  (re-exported)
# What recognition and projection define, importable from here as it was before the split
# (the private names too).
from aileen.memory.projection import Projection, _anchors, latest_time_point, time_chain  # noqa: E402, F401
from aileen.memory.recognition import (  # noqa: E402, F401
    _ANY, CONTEXT_MAC, Inference, _pattern_concept, _skeleton)
from aileen.memory.recognition import has_skolem as _has_skolem  # noqa: E402, F401


class Concept:
    """A concept symbol, its kind and its generalization context, with the scenes the trainer
    said are not this concept although the agent thought so (`near_misses`,
    memory/nearmiss.py).

    A concept loaded from a compact file (`memory/compact.py`) holds only where it lies in
    the file until its context or near misses are first asked for: a memory of 100,000
    concepts loads in a fraction of a second and costs little at rest."""

    __slots__ = ("symbol", "kind", "_context", "_near_misses", "_source", "_at")

    def __init__(self, symbol: str, kind: str, context: GeneralizationContext | None = None,
                 near_misses: list[list[Term]] | None = None, *,
                 source: "compact.Source | None" = None, at: int = 0) -> None:
        self.symbol = symbol
        self.kind = kind
        self._source = source
        self._at = at
        if source is None:
            self._context = context if context is not None else GeneralizationContext(symbol)
            self._near_misses = near_misses if near_misses is not None else []

    def _read(self) -> None:
        assert self._source is not None
        self._context, self._near_misses = self._source.read(self._at, self.symbol)
        self._source = None

    @property
    def loaded(self) -> bool:
        """Whether the context has been made into terms (always, unless read from a compact file)."""
        return self._source is None

    @property
    def context(self) -> GeneralizationContext:
        if self._source is not None:
            self._read()
        return self._context

    @context.setter
    def context(self, value: GeneralizationContext) -> None:
        if self._source is not None:
            self._read()
        self._context = value

    @property
    def near_misses(self) -> list[list[Term]]:
        if self._source is not None:
            self._read()
        return self._near_misses

    @near_misses.setter
    def near_misses(self, value: list[list[Term]]) -> None:
        if self._source is not None:
            self._read()
        self._near_misses = value

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Concept):
            return NotImplemented
        return (self.symbol, self.kind, self.context, self.near_misses) == (
            other.symbol, other.kind, other.context, other.near_misses)

    __hash__ = None  # type: ignore[assignment]  (mutable, as the dataclass it replaces)

    def __repr__(self) -> str:
        if self._source is not None:
            return f"Concept(symbol={self.symbol!r}, kind={self.kind!r}, <not read yet>)"
        return (f"Concept(symbol={self.symbol!r}, kind={self.kind!r}, context={self._context!r}, "
                f"near_misses={self._near_misses!r})")


@dataclass(frozen=True)
class StoreResult:
    """Counts in the concept's context after a store, and what happened to the example."""

    generalizations: int
    examples: int
    action: str = "kept"  # "kept", "merged" or "new_generalization"
    similarity: float = 0.0


#: How many changes the memory remembers for `changes_since`; a reader further behind than
#: this is told to read everything again.
CHANGE_LOG = 4096


class ConceptMemory:
    """Named concepts, each a SAGE generalization context, sharing one `SageParams`."""

    def __init__(self, params: SageParams | None = None) -> None:
        self.params = params or SageParams()
        self._concepts: dict[str, Concept] = {}
        self._order: dict[str, int] = {}  # each concept's place in the order of creation
        # JSON data that other memories keep in the same file (the agent's lexicon: where
        # words stood in phrases, which sense each percept comes from); opaque here.
        self.annotations: dict[str, Any] = {}
        # `query` and `fitting`: the content index of every description and the query caches,
        # told of every concept created or stored into (`Recognition.touch`).
        self._recognition = recognition.Recognition(self._concepts, self._order, self.params)
        # SAGE's store: per description, what its exact content filter needs (`store`).
        self._store_filter = retrieval.StoreFilter()
        # The concepts created or stored into, in order (`changes_since`), from change number
        # `_log_start` on.
        self._log: list[str] = []
        self._log_start = 0

    # ------------------------------------------------------------------ contents
    def __contains__(self, symbol: object) -> bool:
        return str(symbol) in self._concepts

    def __len__(self) -> int:
        return len(self._concepts)

    def concepts(self) -> list[Concept]:
        return list(self._concepts.values())

    def has(self, symbol: str | Term) -> bool:
        """Whether the concept has been created."""
        return str(symbol) in self._concepts

    def changes_since(self, mark: int | None) -> tuple[int, dict[str, str] | None]:
        """The concepts created or stored into since `mark` (a number this method returned
        before), each with its kind, in the order they were first touched, and the mark to ask
        with next time. `None` in place of the concepts when `mark` is None or too far behind
        (the memory keeps the last `CHANGE_LOG` changes): read every concept again.

        Why: what is derived from every concept's descriptions (the agent's lexicon) is kept
        up to date from the concepts that changed, whoever stored into them, instead of being
        made again after every store."""
        now = self._log_start + len(self._log)
        if mark is None or not self._log_start <= mark <= now:
            return now, None
        touched = dict.fromkeys(self._log[mark - self._log_start:])
        return now, {s: self._concepts[s].kind for s in touched if s in self._concepts}

    def _changed(self, symbol: str) -> None:
        self._log.append(symbol)
        if len(self._log) > CHANGE_LOG:
            drop = len(self._log) // 2
            del self._log[:drop]
            self._log_start += drop

    def significant_facts(self, concept: str | Term) -> list[Term]:
        """What the concept's descriptions hold with probability >= the probability threshold:
        each generalization's significant facts, then every kept example's facts (an example
        is a description of probability 1), without repeats."""
        c = self.concept(concept)
        out: dict[Term, None] = {}
        for _kind, _i, facts in c.context.descriptions(self.params):
            out.update(dict.fromkeys(facts))
        return list(out)

    def required_classes(self, concept: str | Term) -> frozenset[Term]:
        """The class symbols (`cv_red` of `isa(X, cv_red)`) that the concept's descriptions
        hold with probability >= the probability threshold, the concept's own left out: as
        `significant_facts` has them, without putting the facts in order (the lexicon reads
        this for every visual concept)."""
        c = self.concept(concept)
        own = Term(str(concept))
        low = self.params.probability - 1e-12
        out: set[Term] = set()
        for g in c.context.generalizations:
            size = g.size
            out.update(f.args[1] for f, n in g.counts.items()
                       if f.name == "isa" and len(f.args) == 2 and size and n / size >= low)
        for ex in c.context.examples:
            out.update(f.args[1] for f in ex if f.name == "isa" and len(f.args) == 2)
        out.discard(own)
        return frozenset(out)

    def class_counts(self, concept: str | Term) -> tuple[int, Counter[Term]]:
        """How many examples the concept has stored, and in how many of them each class
        symbol (`cv_red` of `isa(X, cv_red)`) was seen: what its examples showed, whatever
        the probability threshold keeps (the agent asks whether a word was ever shown on a
        value before it rules an object out, `Referents.ruled_out`)."""
        c = self.concept(concept)
        counts: Counter[Term] = Counter()
        n = 0
        for g in c.context.generalizations:
            n += g.size
            for f, k in g.counts.items():
                if f.name == "isa" and len(f.args) == 2:
                    counts[f.args[1]] += k
        for ex in c.context.examples:
            n += 1
            counts.update({f.args[1] for f in ex if f.name == "isa" and len(f.args) == 2})
        return n, counts

    def descriptions(self, concept: str | Term) -> list[list[Term]]:
        """The facts that count of each generalization (its significant facts) and each kept
        example, as queries match them."""
        c = self.concept(concept)
        return [facts for _kind, _i, facts in c.context.descriptions(self.params)]

    def concept(self, symbol: str | Term) -> Concept:
        c = self._concepts.get(str(symbol))
        if c is None:
            raise UserError(f"unknown concept {str(symbol)!r}")
        return c

    def generalizations(self, concept: str | Term) -> list[dict[str, float]]:
        """Each generalization's facts, printed, with their probabilities (most probable first)."""
        return [
            {str(f): p for f, p in g.probabilities().items()}
            for g in self.concept(concept).context.generalizations
        ]

    def examples(self, concept: str | Term) -> list[list[str]]:
        return [[str(f) for f in ex] for ex in self.concept(concept).context.examples]

    # ------------------------------------------------------------------ create / store
    def create(self, symbol: str | Term, kind: str) -> Concept:
        """Create a concept and its empty context; creating an existing one returns it."""
        name = str(symbol)
        try:
            t = parse(name)
        except TermSyntaxError:
            t = None
        if t is None or t.args or t.is_variable or t.is_number or name.startswith('"'):
            raise UserError(f"concept symbol {name!r} is not a lowercase ASP constant")
        if kind not in KINDS:
            raise UserError(f"concept kind {kind!r} is not one of {', '.join(KINDS)}")
        c = self._concepts.get(name)
        if c is not None:
            if c.kind != kind:
                raise UserError(f"concept {name!r} already exists as a {c.kind} concept, not {kind}")
            return c
        c = Concept(name, kind)
        self._concepts[name] = c
        self._order[name] = len(self._order)
        self._recognition.touch(name, kind, c.context)
        self._changed(name)
        return c

    def store(self, facts: Iterable[Term | str], concept: str | Term, *,
              accept: "Callable[[Generalization], bool] | None" = None,
              exhaustive: bool = False) -> StoreResult:
        """Add an example (facts) to a concept's context; it must have been created. `accept`
        may refuse the merge SAGE would make (the example is then kept apart).

        SAGE's comparison with the concept's descriptions goes through an exact content
        filter (`retrieval.StoreFilter`): SME runs only on descriptions whose similarity
        bound can reach the best found, with the same result as matching every description,
        which `exhaustive=True` does."""
        c = self.concept(concept)
        ex = [as_term(f) for f in facts]
        if not ex:
            raise UserError(f"cannot store an empty example for {c.symbol!r}")
        bounds = None if exhaustive else self._store_filter.bounds(c.symbol, c.context, self.params)
        r = c.context.add(ex, self.params, accept, bounds=bounds)
        self._recognition.touch(c.symbol, c.kind, c.context)
        self._changed(c.symbol)
        return StoreResult(len(c.context.generalizations), len(c.context.examples), r.action, r.similarity)

    def store_near_miss(self, facts: Iterable[Term | str], concept: str | Term) -> int:
        """Keep a near miss (a scene the concept wrongly accepted) for the concept; it narrows
        every description it matches (memory/nearmiss.py). Returns the number kept."""
        c = self.concept(concept)
        nm = list(dict.fromkeys(as_term(f) for f in facts))
        if not nm:
            raise UserError(f"cannot store an empty near miss for {c.symbol!r}")
        c.near_misses.append(nm)
        return len(c.near_misses)

    # ------------------------------------------------------------------ query (memory/recognition.py)
    def query(self, scene: Iterable[Term | str], pattern: Term | str,
              concept: str | Term | None = None, *, ignore: Collection[Term] = (),
              ignore_relations: Collection[str] = (), exhaustive: bool = False) -> list[Inference]:
        """Facts fitting `pattern` that the memory infers about `scene`, best first, each
        reaching the match threshold (`Recognition.query`)."""
        return self._recognition.query(scene, pattern, concept, ignore=ignore,
                                       ignore_relations=ignore_relations, exhaustive=exhaustive)

    def forget_answers(self) -> None:
        """Drop the answers `query` keeps until a concept's next store (`Recognition`): a
        benchmark asking a question again times the work, not the lookup."""
        self._recognition.forget_answers()

    def fitting(self, facts: Iterable[Term | str], *, kind: str | None = None, k: int = 5,
                exhaustive: bool = False,
                ignore: "Callable[[str], Collection[Term]] | None" = None,
                ignore_relations: Collection[str] = ()) -> list[Inference]:
        """Which concepts fit these facts: the membership inferences of the `k` concepts whose
        best inference is most similar, best first (`Recognition.fitting`)."""
        return self._recognition.fitting(facts, kind=kind, k=k, exhaustive=exhaustive, ignore=ignore,
                                         ignore_relations=ignore_relations)

    # ------------------------------------------------------------------ project (memory/projection.py)
    def project(self, trace: Iterable[Term | str], concept: str | Term) -> Projection:
        """The state after the trace's latest time point, as the action concept has it
        (`projection.project`)."""
        return projection.project(trace, self.concept(concept), self.params)

    # ------------------------------------------------------------------ persistence (memory/codec.py)
    def to_dict(self) -> dict[str, Any]:
        self.read_all()
        return codec.encode(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any], path: str = "<memory>") -> "ConceptMemory":
        """Rebuild a memory from `to_dict` output; malformed entries raise `UserError`."""
        return codec.decode(cls, data, path)

    def adopt(self, symbol: str, kind: str, source: compact.Source, index: int) -> None:
        """Take in a concept of a compact file, read from it when first used (`compact.decode`)."""
        self._concepts[symbol] = Concept(symbol, kind, source=source, at=index)
        self._order[symbol] = len(self._order)
        self._recognition.touch_all(self.read_all)

    def read_all(self) -> None:
        """Read every concept not read yet (of a memory loaded from a compact file) at once:
        what a retrieval over every concept or a save needs, faster than one at a time."""
        lazy = [c for c in self._concepts.values() if not c.loaded]
        if not lazy:
            return
        with codec.gc_paused():
            for c in lazy:
                c.context  # noqa: B018 - reads it

    def save(self, path: str | os.PathLike[str], form: str | None = None) -> None:
        """Write the memory (temporary file, then rename): as versioned JSON, or in the
        compact form (`form="compact"`, or a path ending in `compact.SUFFIX`, `.amem`)."""
        self.read_all()
        if (form or file_form(path)) == "compact":
            persist.write_bytes_atomic(path, compact.encode(self))
        else:
            persist.write_json_atomic(path, self.to_dict())

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> "ConceptMemory":
        """Read a memory saved by `save`, in either form (told apart by the file's first
        bytes, not its name); any problem is a `UserError` naming the path."""
        raw = persist.read_bytes(path)
        if compact.is_compact(raw, named_json=str(path).endswith(".json")):
            return compact.decode(cls, raw, str(path))
        return cls.from_dict(persist.parse_json(raw, str(path)), str(path))


#: The forms a memory file can take (`ConceptMemory.save`).
FORMS = ("json", "compact")


def file_form(path: str | os.PathLike[str]) -> str:
    """The form `save` writes at `path` by default: compact for a name ending in `.amem`."""
    return "compact" if str(path).endswith(compact.SUFFIX) else "json"
