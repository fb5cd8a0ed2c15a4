"""Typicality of a recognised instance and the quality of a concept (the paper's D4a and D4c).

Why: a yes/no answer hides how sure the memory is. A scene that matches a concept's main
generalization well is a typical instance; one that only matches a single example kept apart
(a rare disjunct), or that matches weakly, is not. And a concept can be judged without an exam:
how much it has seen, how many descriptions it holds, how many facts it insists on, and whether
the other concepts of its kind would accept its own descriptions (how well it separates).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

from aileen.memory.concept import Concept, ConceptMemory
from aileen.memory.recognition import Inference
from aileen.terms import Term, fn


def _sizes(memory: ConceptMemory, concept: str) -> dict[tuple[str, int], int]:
    ctx = memory.concept(concept).context
    out = {("generalization", i): g.size for i, g in enumerate(ctx.generalizations)}
    out.update({("example", i): 1 for i in range(len(ctx.examples))})
    return out


def seen(memory: ConceptMemory, concept: str) -> int:
    """Examples the concept has taken in (merged or kept apart)."""
    return sum(_sizes(memory, concept).values())


def typicality(memory: ConceptMemory, inf: Inference) -> float:
    """How typical the recognised instance is, in [0, 1]: the match's similarity times the share
    of the concept's examples that the matched description carries."""
    sizes = _sizes(memory, inf.concept)
    total = sum(sizes.values())
    share = sizes.get((inf.source, inf.index), 0) / total if total else 0.0
    return round(inf.similarity * share, 4)


@dataclass
class Quality:
    """One concept's quality figures (`aileen memory show`)."""

    examples_seen: int
    generalizations: int
    examples_apart: int
    significant_facts: int  # distinct facts that count when matching, over all descriptions
    near_misses: int
    separation: float  # share of its descriptions no other concept of its kind accepts (1 = all)
    confused_with: list[str] = field(default_factory=list)

    def to_dict(self) -> dict:
        return asdict(self)


def _member(facts: list[Term], concept: str) -> Term | None:
    for f in facts:
        if f.name == concept or (f.name == "isa" and len(f.args) == 2 and str(f.args[1]) == concept):
            return f
    return None


def _pattern(member: Term, other: str) -> Term:
    """The other concept's fact about the same arguments, in the same roles."""
    if member.name == "isa":
        return fn("isa", member.args[0], other)
    return Term(other, member.args)


#: Up to this many other concepts of its kind, a concept's separation asks every one of them
#: whether it accepts the concept's descriptions; past it, only the `CONFUSERS` the content
#: index finds most alike (`ConceptMemory.fitting`, MAC/FAC): asking every concept for every
#: concept made `aileen memory show` quadratic (32 s at 1,000 concepts, 5 min at 3,000).
EXHAUSTIVE_UP_TO = 64
CONFUSERS = 8


def _accepting(memory: ConceptMemory, scene: list[Term], member: Term, mine: str, others: list[str],
               exhaustive: bool) -> list[str]:
    """The other concepts that accept `scene` in `member`'s place (the same objects, in the
    same roles): every one asked, or those the content index finds most alike."""
    if exhaustive:
        return [o for o in others if memory.query(scene, _pattern(member, o))]
    kind = memory.concept(mine).kind
    out: list[str] = []
    for inf in memory.fitting(scene, kind=kind, k=CONFUSERS + 1):
        if inf.concept != mine and inf.concept not in out and inf.fact == _pattern(member, inf.concept):
            out.append(inf.concept)
    return out


def _more_than(memory: ConceptMemory, c: Concept, n: int) -> bool:
    """Has the memory more than `n` other concepts of `c`'s kind? (Counted until it has.)"""
    found = 0
    for o in memory.concepts():
        if o.kind == c.kind and o.symbol != c.symbol:
            found += 1
            if found > n:
                return True
    return False


def quality(memory: ConceptMemory, concept: str, *, exhaustive: bool | None = None) -> Quality:
    """The concept's quality figures; `exhaustive` (default: when the memory has at most
    `EXHAUSTIVE_UP_TO` other concepts of its kind) asks every other concept of its kind."""
    c = memory.concept(concept)
    ctx = c.context
    descriptions = list(ctx.descriptions(memory.params))
    significant = {f for _k, _i, facts in descriptions for f in facts
                   if f.name != c.symbol and not (f.name == "isa" and len(f.args) == 2 and str(f.args[1]) == c.symbol)}
    every = exhaustive if exhaustive is not None else not _more_than(memory, c, EXHAUSTIVE_UP_TO)
    # (the others of its kind are listed only to be asked: listing them for every concept made
    # `memory show` quadratic, 90 s for 10,000 concepts)
    others = [o.symbol for o in memory.concepts() if o.kind == c.kind and o.symbol != c.symbol] if every else []
    confused: set[str] = set()
    separated = 0
    for _kind, _i, facts in descriptions:
        member = _member(facts, c.symbol)
        scene = [f for f in facts if f is not member]
        hits = _accepting(memory, scene, member, c.symbol, others, every) if scene and member is not None else []
        confused.update(hits)
        separated += not hits
    return Quality(
        examples_seen=seen(memory, concept),
        generalizations=len(ctx.generalizations),
        examples_apart=len(ctx.examples),
        significant_facts=len(significant),
        near_misses=len(c.near_misses),
        separation=round(separated / len(descriptions), 3) if descriptions else 0.0,
        confused_with=sorted(confused),
    )


def quality_line(q: Quality) -> str:
    """One line for `aileen memory show`."""
    text = (f"  quality: {q.examples_seen} examples seen, {q.generalizations} generalizations + "
            f"{q.examples_apart} apart, {q.significant_facts} significant facts, {q.near_misses} near misses, "
            f"separation {q.separation:.2f}")
    if q.confused_with:
        text += " (also accepted by " + ", ".join(q.confused_with) + ")"
    return text
