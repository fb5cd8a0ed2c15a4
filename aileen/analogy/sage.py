"""SAGE, the Sequential Analogical Generalization Engine (McLure et al. 2015), over our SME.

Why: AILEEN learns a concept from a handful of examples, one at a time. SAGE keeps, per
concept, a *generalization context*: generalizations (facts with per-fact probabilities over
the examples merged into them, with generalized entities in place of the example objects)
and examples that have not yet been merged. A new example is compared with each of them;
if the best SME similarity reaches the assimilation threshold it is merged (an example plus
an example makes a new generalization), otherwise it is kept as an example.

Entity naming: merging replaces non-identical aligned entities by `gen_ent(N, Concept)`
(N counts within one generalization) and keeps identical ones; entities of a new example that
align with nothing get fresh generalized entities, so names from different scenes never
collide. Per fact we keep a count; its probability is count / examples merged. Only facts
with probability >= `SageParams.probability` take part when a generalization is matched.

Pure functions of data in and data out; no I/O.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterable, Iterator
from dataclasses import dataclass, field

from aileen.analogy import sme
from aileen.terms import Term, as_term, sort_key, substitute

__all__ = [
    "NORMALISATIONS",
    "SageParams",
    "Generalization",
    "GeneralizationContext",
    "AddResult",
    "Candidate",
    "Bound",
    "gen_ent",
    "entities_of",
]

#: How a match score becomes a similarity for the match threshold (see `SageParams`).
NORMALISATIONS = ("significant", "paper")


@dataclass(frozen=True)
class SageParams:
    """SAGE's thresholds (defaults: the paper's Table 2) and how matches are normalised.

    - `assimilation`: SME similarity a new example needs to be merged (0.01).
    - `probability`: facts below this probability do not count when matching (0.6).
    - `match`: similarity an inference needs to be accepted by a query (0.75).
    - `normalisation`: `"significant"` (default) scores a query match against the
      generalization's own significant facts, leaving out the facts the query asks about:
      `score / self(significant base facts not fitting the pattern)`. Distractors in the scene
      cannot dilute it. `"paper"` is SME's symmetric normalised similarity
      `2 score / (self(base) + self(scene))`, where the whole scene counts.
    - `sme`: the SME parameters; `functions`: function predicates (none in AILEEN's facts).
    """

    assimilation: float = 0.01
    probability: float = 0.6
    match: float = 0.75
    normalisation: str = "significant"
    sme: sme.Params = field(default_factory=sme.Params)
    functions: frozenset[str] = frozenset()
    def __post_init__(self) -> None:
        if self.normalisation not in NORMALISATIONS:
            raise ValueError(f"normalisation must be one of {NORMALISATIONS}, not {self.normalisation!r}")
        for name in ("assimilation", "probability", "match"):
            v = getattr(self, name)
            if not 0.0 <= v <= 1.0:
                raise ValueError(f"{name} threshold must be in [0, 1], not {v}")


def gen_ent(n: int, concept: str) -> Term:
    """The n-th generalized entity of a generalization of `concept`."""
    return Term("gen_ent", (Term(n), Term(concept)))


def entities_of(facts: Iterable[Term]) -> list[Term]:
    """The entities mentioned in facts, in first-seen order (SME's notion of entity)."""
    seen: dict[Term, None] = {}

    def walk(t: Term) -> None:
        for a in t.args:
            if sme.is_entity(a):
                seen.setdefault(a, None)
            else:
                walk(a)

    for f in facts:
        if not sme.is_entity(f):
            walk(sme._to_sme(f))
    return list(seen)


def _is_gen_ent(t: Term) -> bool:
    return t.name == "gen_ent" and len(t.args) == 2


@dataclass
class Generalization:
    """Facts over generalized entities, each with the number of examples it held in."""

    concept: str
    counts: dict[Term, int]
    size: int
    next_entity: int = 0

    def probability(self, fact: Term) -> float:
        return self.counts.get(fact, 0) / self.size if self.size else 0.0

    def probabilities(self) -> dict[Term, float]:
        """Every fact with its probability, most probable first, then by text."""
        items = sorted(self.counts.items(), key=lambda kv: (-kv[1], sort_key(kv[0])))
        return {f: c / self.size for f, c in items}

    def significant(self, threshold: float) -> list[Term]:
        """The facts that count when matching: probability >= threshold (stable order)."""
        return [f for f, p in self.probabilities().items() if p >= threshold - 1e-12]

    def _fresh(self) -> Term:
        e = gen_ent(self.next_entity, self.concept)
        self.next_entity += 1
        while e in self._entities():
            e = gen_ent(self.next_entity, self.concept)
            self.next_entity += 1
        return e

    def _entities(self) -> set[Term]:
        return set(entities_of(self.counts))

    def _rename(self, mapping: dict[Term, Term]) -> None:
        if not mapping:
            return
        new: dict[Term, int] = {}
        for f, c in self.counts.items():
            g = substitute(f, mapping)
            new[g] = new.get(g, 0) + c
        self.counts = new

    def merge(self, example: Iterable[Term], entity_map: dict[Term, Term]) -> None:
        """Add an example, given its entities' correspondents in this generalization.

        `entity_map`: example entity -> generalization entity (from an SME mapping whose base
        is this generalization). Non-identical concrete correspondents are generalized.
        """
        facts = list(dict.fromkeys(example))
        renames: dict[Term, Term] = {}  # generalization entity -> new generalized entity
        ex_map: dict[Term, Term] = {}
        for y in entities_of(facts):
            x = entity_map.get(y)
            if x is None:
                ex_map[y] = self._fresh()
            elif x is y or _is_gen_ent(x):
                ex_map[y] = x
            else:
                g = renames.get(x)
                if g is None:
                    g = self._fresh()
                    renames[x] = g
                ex_map[y] = g
        self._rename(renames)
        seen: set[Term] = set()
        for f in facts:
            g = substitute(f, ex_map)
            if g in seen:
                continue
            seen.add(g)
            self.counts[g] = self.counts.get(g, 0) + 1
        self.size += 1

    @classmethod
    def from_pair(cls, concept: str, first: Iterable[Term], second: Iterable[Term],
                  entity_map: dict[Term, Term]) -> "Generalization":
        """A generalization of two examples; `entity_map`: second's entity -> first's entity."""
        first = list(dict.fromkeys(first))
        keep = {x for y, x in entity_map.items() if x is y}
        gen = cls(concept=concept, counts={}, size=0)
        ren: dict[Term, Term] = {}
        for x in entities_of(first):
            if x not in keep:
                ren[x] = gen_ent(gen.next_entity, concept)
                gen.next_entity += 1
        gen.counts = {substitute(f, ren): 1 for f in first}
        gen.size = 1
        gen.merge(second, {y: ren.get(x, x) for y, x in entity_map.items()})
        return gen


@dataclass
class AddResult:
    """What `GeneralizationContext.add` did with an example."""

    action: str  # "merged", "new_generalization" or "kept"
    index: int  # generalization index (merged / new_generalization) or example index (kept)
    similarity: float  # best similarity found (0.0 when the context was empty)


@dataclass
class Candidate:
    """One description of a context matched against a target."""

    kind: str  # "generalization" or "example"
    index: int
    base: list[Term]  # the facts matched (significant facts of a generalization)
    mappings: list[sme.Mapping]


def _grade(similarity: float) -> int:
    """A similarity to 1e-9, as SAGE's store compares them: two descriptions that match an
    example equally well (up to the rounding of summing scores in a different order) tie,
    and the earlier description wins, whichever way the rounding fell."""
    return round(similarity * 1e9)


@dataclass(frozen=True)
class Bound:
    """An upper bound on the SME similarity of one description (its facts that count) with
    an example, for `GeneralizationContext.add`'s content filter."""

    similarity: float
    kind: str  # "generalization" or "example"
    index: int
    facts: list[Term]


@dataclass
class GeneralizationContext:
    """All SAGE knows about one concept: generalizations and kept examples."""

    concept: str
    generalizations: list[Generalization] = field(default_factory=list)
    examples: list[list[Term]] = field(default_factory=list)

    def descriptions(self, params: SageParams) -> Iterator[tuple[str, int, list[Term]]]:
        """(kind, index, facts that count) for every generalization, then every example."""
        for i, g in enumerate(self.generalizations):
            yield "generalization", i, g.significant(params.probability)
        for i, ex in enumerate(self.examples):
            yield "example", i, ex

    def match(self, target: Iterable[Term | str], params: SageParams, *,
              drop: "Callable[[Term], bool] | None" = None,
              require: "Callable[[list[Term]], dict[Term, Term]] | None" = None,
              only: "Collection[tuple[str, int]] | None" = None) -> list[Candidate]:
        """Match every description (as base) against `target`; descriptions with no mapping are
        left out. `drop` removes facts from the descriptions first (facts another concept
        already accounts for: see `ConceptMemory.query`); `require(description)` gives the
        entity correspondences each mapping must keep (see `sme.analyze`); `only` names the
        (kind, index) descriptions to match (a MAC pre-filter), all when None."""
        tgt = [as_term(t) for t in target]
        out: list[Candidate] = []
        for kind, i, facts in self.descriptions(params):
            if only is not None and (kind, i) not in only:
                continue
            if drop is not None:
                facts = [f for f in facts if not drop(f)]
            if not facts:
                continue
            req = require(facts) if require is not None else None
            ms = sme.match(facts, tgt, functions=params.functions, params=params.sme, require=req)
            if ms:
                out.append(Candidate(kind, i, facts, ms))
        return out

    def membership(self, facts: list[Term]) -> tuple[Term, ...] | None:
        """The entities a description is an example *of* the concept for: the arguments of
        `concept(a, b, ...)`, or the object of `isa(o, concept)`."""
        for f in facts:
            if f.name == self.concept:
                return f.args
            if f.name == "isa" and len(f.args) == 2 and str(f.args[1]) == self.concept:
                return f.args[:1]
        return None

    def _best_bounded(self, facts: list[Term], params: SageParams,
                      require: "Callable[[list[Term]], dict[Term, Term]]",
                      ranked: "Iterable[Bound]") -> "tuple[float, str, int, sme.Mapping] | None":
        """The exhaustive store's best (similarity, kind, index, mapping): the highest graded
        similarity, ties to the earlier description, running SME only on descriptions whose
        bound can still reach it."""
        best: tuple[float, str, int, sme.Mapping] | None = None
        best_key = (-1, 0)
        for b in ranked:
            # The bound, a hair up against rounding, graded: a description under the best
            # grade cannot win, nor can one level with it that comes later.
            top = _grade(b.similarity * (1.0 + 1e-12) + 1e-15)
            pos = b.index if b.kind == "generalization" else len(self.generalizations) + b.index
            if top < best_key[0]:
                break  # the rest have lower bounds still
            if top == best_key[0] and -pos < best_key[1]:
                continue
            ms = sme.match(b.facts, facts, functions=params.functions, params=params.sme,
                           require=require(b.facts))
            if not ms:
                continue
            m = ms[0]
            key = (_grade(m.similarity), -pos)
            if key > best_key:
                best, best_key = (m.similarity, b.kind, b.index, m), key
        return best

    def add(self, example: Iterable[Term | str], params: SageParams,
            accept: "Callable[[Generalization], bool] | None" = None, *,
            bounds: "Callable[[list[Term]], Iterable[Bound]] | None" = None) -> AddResult:
        """SAGE's store: merge the example into the most similar description, or keep it.
        `accept(merged)` may refuse a merge (the example is then kept apart).

        `bounds(example)` (a MAC-style content filter, `retrieval.StoreFilter`) gives an upper
        bound on the SME similarity of each description that could match at all, highest
        first; SME then runs in that order only until no bound left can reach the best
        similarity found. The result is the exhaustive store's (same description, same
        similarity graded to 1e-9, ties to the earlier description), as long as the bounds are true bounds
        and every description left out has no mapping."""
        facts = list(dict.fromkeys(as_term(f) for f in example))
        mine = self.membership(facts)

        def require(base: list[Term]) -> dict[Term, Term]:
            # The example's roles align with the description's: in `r_next_to(o1,o2)` o1 is the
            # one that is next to o2, whatever a role-swapped mapping of the rest would score.
            theirs = self.membership(base)
            if mine is None or theirs is None or len(theirs) != len(mine):
                return {}
            return {x: y for x, y in zip(theirs, mine) if sme.is_entity(x) and sme.is_entity(y)}

        best: tuple[float, str, int, sme.Mapping] | None = None
        if bounds is None:
            for cand in self.match(facts, params, require=require):
                m = cand.mappings[0]
                if best is None or _grade(m.similarity) > _grade(best[0]):
                    best = (m.similarity, cand.kind, cand.index, m)
        else:
            best = self._best_bounded(facts, params, require, bounds(facts))
        if best is None or best[0] < params.assimilation:
            self.examples.append(facts)
            return AddResult("kept", len(self.examples) - 1, 0.0 if best is None else best[0])
        sim, kind, i, m = best
        entity_map = {t: b for b, t in m.pairs.items() if sme.is_entity(b)}
        if kind == "generalization":
            g = self.generalizations[i]
            merged = Generalization(g.concept, dict(g.counts), g.size, g.next_entity)
            merged.merge(facts, entity_map)
        else:
            merged = Generalization.from_pair(self.concept, self.examples[i], facts, entity_map)
        if accept is not None and not accept(merged):
            self.examples.append(facts)
            return AddResult("kept", len(self.examples) - 1, sim)
        if kind == "generalization":
            self.generalizations[i] = merged
            return AddResult("merged", i, sim)
        self.examples.pop(i)
        self.generalizations.append(merged)
        return AddResult("new_generalization", len(self.generalizations) - 1, sim)
