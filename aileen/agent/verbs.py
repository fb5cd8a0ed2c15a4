"""One verb for every relation: an action concept whose outcome is a slot, and who moved.

Why (DESIGN.md section 14): with one action concept per verb and relation (`move left of`,
`move behind`) the agent cannot carry out "move X behind Y" after seeing "move" only with
"left of" and "right of", although it knows "behind"; and checking that "the sentence's
relation holds at the end" was a rule written in Python. Here the action concept is the
verb's (`r_move`), and its examples say two things the old traces left implicit:

* **the slot.** At the demonstration's last time point, the facts that the sentence's
  relation concept accounts for (its best-matching description, mapped by SME onto the pair)
  are replaced by `h(T, said_rel(a, b))`: "the relation named in the sentence holds between
  the two objects". Comprehension fills the slot from the relation's own concept, so one `move`
  serves every spatial word the agent knows.
* **where it started, by contrast.** At the first time point, the calculus facts between the
  two objects that the action changed (the direction it came from, a distance) are replaced
  by `h(T0, not_said_rel(a, b))`: "the relation was not yet the one named". Where the mover
  started is no part of "move"; without this, one demonstration taught "move" only from
  where that demonstration began (from the west, or from close by), and recognition of a
  move from anywhere else waited for more demonstrations to average the start away.
* **who moved.** Per argument, `moved(o)` when the agent saw it held during the trace, else
  `stayed(o)`.

Recognition then asks that a match keep everything the concept says about its outcome: every
significant fact of the matched description's last time point and every role fact must be in
the mapping. That is a property of action concepts (they are defined by what they bring about),
not of any word; the word-specific part (which direction, who is moved) is learned.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

from aileen.analogy import sme
from aileen.domain import calculi, predicates
from aileen.memory.concept import ConceptMemory
from aileen.memory.projection import time_chain
from aileen.memory.recognition import Inference
from aileen.terms import Term, fn, substitute

# h(T, said_rel(a,b)): the sentence's relation holds between a and b; h(T0, not_said_rel(a,b)):
# at the start it did not (what the move changed); declared with the memory's other predicates
SLOT, NOT_YET, STAYED = predicates.SLOT, predicates.NOT_YET, predicates.STAYED
MOVED = calculi.MOVED
ROLE_FACTS = frozenset({MOVED, STAYED})


def roles(trace: Iterable[Term], args: Sequence[Term]) -> list[Term]:
    """What happened to each argument: `moved(o)` when it was held at some time point of the
    trace (the only way the hand moves things), else `stayed(o)`."""
    held = {f.args[1].args[0] for f in trace
            if f.name == "h" and len(f.args) == 2 and f.args[1].name == "held" and len(f.args[1].args) == 1}
    return [fn(MOVED if a in held else STAYED, a) for a in args]


def last_facts(trace: Sequence[Term]) -> tuple[Term | None, list[Term]]:
    """The trace's last time point and the facts that hold at it."""
    chain = time_chain(trace)
    if not chain:
        return None, []
    t = chain[-1]
    return t, [f.args[1] for f in trace if f.name == "h" and len(f.args) == 2 and f.args[0] is t]


def accounted(memory: ConceptMemory, relation: str, a: Term, b: Term, facts: Sequence[Term],
              percepts: Sequence[Term]) -> list[Term] | None:
    """The facts among `facts` (a state's facts about a and b) that the relation concept's best
    matching description maps onto, when it holds of (a, b); None when it does not hold."""
    best = memory.query(list(percepts) + list(facts), fn(relation, a, b))
    if not best:
        return None
    inf: Inference = best[0]
    wanted = set(facts)
    return [t for t in inf.mapping.pairs.values() if t in wanted]


def slotted(trace: list[Term], explained: Iterable[Term], a: Term, b: Term, *, contrast: bool = True) -> list[Term]:
    """The trace with the explained facts of its last time point replaced by the slot fact,
    and (with `contrast`) the calculus facts between a and b at its first time point that no
    longer hold at its last by the contrast fact (see the module doc)."""
    t, final = last_facts(trace)
    if t is None:
        return list(trace)
    explained = list(explained)
    gone = {fn("h", t, f) for f in explained}
    added = [fn("h", t, fn(SLOT, a, b))]
    chain = time_chain(trace)
    if contrast and len(chain) > 1:
        t0, after = chain[0], set(final)
        changed = [f.args[1] for f in trace if f.name == "h" and len(f.args) == 2 and f.args[0] is t0
                   and len(f.args[1].args) == 2 and set(f.args[1].args) <= {a, b}
                   and calculi.calculus_of(f.args[1].name) is not None and f.args[1] not in after]
        if changed:
            gone |= {fn("h", t0, f) for f in changed}
            added.append(fn("h", t0, fn(NOT_YET, a, b)))
    return [f for f in trace if f not in gone] + added


def outcome_kept(memory: ConceptMemory, concept: str, inf: Inference) -> bool:
    """Does the match behind `inf` keep the outcome of the action: every role fact and every
    fact at the last time point of the matched description?"""
    base = _description(memory, concept, inf)
    if base is None:
        return False
    chain = time_chain(base)
    last = chain[-1] if chain else None
    mapped = inf.mapping.pairs
    for f in base:
        if f.name in ROLE_FACTS or (last is not None and f.name == "h" and len(f.args) == 2 and f.args[0] is last):
            if f not in mapped:
                return False
    return True


def _description(memory: ConceptMemory, concept: str, inf: Inference) -> list[Term] | None:
    for kind, i, facts in memory.concept(concept).context.descriptions(memory.params):
        if kind == inf.source and i == inf.index:
            return facts
    return None


def fill_slot(memory: ConceptMemory, relation: str, facts: Sequence[Term], *,
              direction: str | None = None, directionless: bool = False, distance: str | None = None) -> list[Term]:
    """Projected next-state facts with each `said_rel(a, b)` replaced by what one description
    of the relation concept says between its two arguments. A disjunctive concept is brought
    about through the disjunct that no other spatial concept also accounts for (where the
    relation holds unambiguously), the best attested first. `direction` (a fine-sector
    relation: a word whose direction is learned as a region, memory/extent.py) replaces the
    description's direction facts: the object goes where the word holds most surely;
    `directionless` (a word whose examples say nothing of direction, "near" once direction
    words are known: `Directions.region` is None) drops them, and the verb's own outcome's
    direction facts between the two: the side its examples (or the verb's demonstrations)
    happened to lie on is no part of the goal, and a goal tied to one fine sector of it can
    leave no room on the table.

    The relation's facts win over what the verb's own outcome says of the same pair in the
    same calculus (a calculus's relations are disjoint): "move" shown only with "near" ends
    with the objects apart (`dc`), which "next to" (`ec`) contradicts; the sentence decides.
    No distance band is a goal (the one the demonstrations ended at is no part of the verb),
    except `distance`: the band a word whose distance is learned as a region holds of most
    surely (`Directions.reach`), for the slot's pair. No fact of a static calculus is a goal
    (`calculi.is_static`: which of the two is larger): "on" shown with a small box on a large
    one asked every "move X on Y" to make X the smaller, which no move does."""
    out: list[Term] = []
    said: set[Term] = set()
    sideless: set[frozenset[Term]] = set()  # slot pairs whose side is no part of the goal
    slots: list[tuple[Term, Term]] = []
    for f in facts:
        if f.name != SLOT or len(f.args) != 2:
            out.append(f)
            continue
        slots.append((f.args[0], f.args[1]))
        if directionless and direction is None:
            sideless.add(frozenset(f.args))
        filled = _relation_facts(memory, relation, f.args[0], f.args[1])
        if direction is not None:
            filled = [g for g in filled if not calculi.is_direction(g.name)] + [fn(direction, f.args[0], f.args[1])]
        elif directionless:
            filled = [g for g in filled if not calculi.is_direction(g.name)]
        said.update(filled)
        out.extend(filled)
    decided = {(_calculus(f), frozenset(f.args)) for f in said if _calculus(f) is not None}
    out = [f for f in out if f in said or (_calculus(f), frozenset(f.args)) not in decided]
    out = [f for f in out if not (calculi.is_direction(f.name) and frozenset(f.args) in sideless)]
    out = [f for f in out if not calculi.is_finer(f.name)]
    # which of the two is larger was so in the examples, and no move changes it: never a goal
    out = [f for f in out if not calculi.is_static(f.name)]
    if distance is not None:
        out += [fn(distance, *pair) for pair in slots]
    return list(dict.fromkeys(out))


def _calculus(f: Term) -> str | None:
    """The calculus of a binary relation fact between two objects, None for anything else."""
    if len(f.args) != 2:
        return None
    calc = calculi.calculus_of(f.name)
    return calc.name if calc is not None else None


def relation_facts(memory: ConceptMemory, relation: str, a: Term, b: Term) -> list[Term]:
    """What one description of the relation concept says between `a` and `b` (the one the
    slot is filled with, static facts included: `fill_slot` drops those)."""
    return _relation_facts(memory, relation, a, b)


def _relation_facts(memory: ConceptMemory, relation: str, a: Term, b: Term) -> list[Term]:
    ctx = memory.concept(relation).context
    sized = [(g.size, facts) for (_k, _i, facts), g in zip(ctx.descriptions(memory.params), ctx.generalizations)]
    sized += [(1, ex) for ex in ctx.examples]
    options: list[list[Term]] = []
    for _size, facts in sorted(sized, key=lambda s: -s[0]):
        member = next((f for f in facts if f.name == relation and len(f.args) == 2), None)
        if member is None:
            continue
        x, y = member.args
        ren = {x: a, y: b}
        options.append([substitute(f, ren) for f in facts
                        if f is not member and f.name != "isa" and len(f.args) == 2 and not calculi.is_finer(f.name)
                        and all(sme.is_entity(t) for t in f.args) and set(f.args) <= {x, y}])
    others = [c.symbol for c in memory.concepts() if c.kind == "spatial" and c.symbol != relation]
    for option in options:
        if not any(memory.query(option, fn(o, a, b)) for o in others):
            return option
    return options[0] if options else []
