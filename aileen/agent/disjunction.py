"""Disjunctive relation concepts: when SAGE may merge two examples of a relation word.

Why (issue 11): taught over the whole region a person accepts, "left of" has examples in CDC
sectors `w`, `nw` and `sw`. SAGE merges anything that shares a fact at the paper's threshold,
and "left of" at `w` merged with "left of" at `sw` keeps only `dc`: no direction passes the
probability threshold, and the concept accepts every pair of objects apart. No assimilation
threshold fixes it: two such examples score 0.31-0.59, and pairs that should merge as low or
lower ("near" 0.35, "far from" 0.22, "larger than" 0.19, two visual examples 0.50; stop 52,
benchmarks/assimilation.py and docs/results.md, "When relation examples merge").

What tells the two apart is what the merge keeps. Direction and topology are the agent's
exhaustive senses (`calculi.EXHAUSTIVE`: every pair of objects has a fact of each; of the two
direction calculi, the one the agent perceives); the others
report only what stands out (close, far, larger, resting on). A merge that keeps a marked fact
keeps a meaning ("near" is `qd_close` whatever the direction), and so does one that keeps a
direction ("left of" shown apart and touching is `cone_w` either way); a merge that keeps
only what nearly every pair of objects has (`dc`, `Calculus.common`) tells no pairs apart.
Such a merge is refused and the example stays apart: one description per sector, and a
query succeeds when any of them matches.

The same holds of a visual word (`keeps_a_percept`): "zup", said of a red box and then of a
blue cone, merged into a generalization that kept only `cv_medium`, while every object the
agent had been taught on was medium-sized, and was then true of every object on the table;
a `wrong` could not narrow it (the near miss lacked none of what it kept). A merge that keeps
no percept but those most objects taught on have (`seen.COMMON`, read once `seen.MIN_OBJECTS`
objects are counted) is refused where the example had one: "zup" is a red box or a blue cone.
"""

from __future__ import annotations

from aileen.analogy.sage import Generalization
from aileen.domain import calculi
from aileen.terms import Term


def _senses(facts) -> dict[str, set[str]]:  # noqa: ANN001
    """Relation names per calculus among binary facts."""
    out: dict[str, set[str]] = {}
    for f in facts:
        c = calculi.calculus_of(f.name) if len(f.args) == 2 else None
        if c is not None and c not in calculi.FINER:  # a band tells no meaning apart by itself
            out.setdefault(c.name, set()).add(f.name)
    return out


def keeps_a_meaning(merged: Generalization, probability: float, example: list[Term] | None = None) -> bool:
    """May SAGE make this merge of a relation concept's example (see the module doc)?

    Refused when the merged generalization still insists on a value of an exhaustive sense
    that the new example does not have (it would absorb a `se` example into a `ne`
    generalization that does not describe it), or when it keeps no relation fact but those
    nearly every pair has (`dc` alone)."""
    kept = _senses(merged.significant(probability))
    # the exhaustive senses this agent has: those its examples show at all
    exhaustive = calculi.EXHAUSTIVE & set(_senses(merged.counts))
    if example is not None:
        own = _senses(example)
        exhaustive |= calculi.EXHAUSTIVE & set(own)
        for sense in exhaustive:
            if kept.get(sense) and not own.get(sense, set()) <= kept[sense]:
                return False
    # It must keep something that tells pairs apart: a marked fact, a direction, a contact;
    # not only what nearly every pair of objects has (`Calculus.common`: two objects apart).
    return any(r not in calculi.calculus_by_name(sense).common for sense, rs in kept.items() for r in rs)


def keeps_a_percept(merged: Generalization, probability: float, uninformative: frozenset[Term],
                    example: list[Term]) -> bool:
    """May SAGE make this merge of a visual concept's `example`? Refused when the example has
    a percept that tells objects apart (one not in `uninformative`) and the merged
    generalization keeps none (see the module doc). An example mutual exclusivity has
    already left with nothing telling ("rox" said of a red box, "red" and "box" known: the
    word is their conjunction, read at query time) loses nothing by merging."""
    own = merged.concept

    def telling(facts: list[Term]) -> bool:
        return any(f.name == "isa" and len(f.args) == 2 and str(f.args[1]) != own
                   and f.args[1] not in uninformative for f in facts)

    return telling(merged.significant(probability)) or not telling(example)
