"""Indexical comprehension: a parsed sentence + working memory -> referents, relation, goal, failures.

The reasoning itself is `asp/comprehension.lp` (user-editable); this module only builds the
facts and reads the answer back. It is also the one place where the concept memory's
binary concept facts `r_left_of(o1,o2)` become `rel(r_left_of,o1,o2)` on the ASP side (and
QSR facts `w(o1,o2)` become `rel(w,o1,o2)` as well, so a word may also map straight to a
QSR while nothing is learned yet).
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import NamedTuple

from aileen.errors import UserError
from aileen.reasoning.language import Parse
from aileen.reasoning.reify import is_relation, reify
from aileen.terms import Term, TermSyntaxError, fn
from aileen.terms import parse as parse_term

__all__ = ["Failure", "Goal", "Comprehension", "comprehend", "working_memory", "RULE_FILES", "FAILURE_REASONS"]

RULE_FILES: tuple[str, ...] = ("comprehension.lp",)
#: What `_read` takes from the answer set, per rule file (a user's edit must still show it:
#: `rulefiles.check_reads`).
READS: dict[str, tuple[str, ...]] = {"comprehension.lp": ("referent/2", "holds/3", "candidate/2", "goal/4",
                                                          "goal/3", "act_relation/2", "failure/2")}
FAILURE_REASONS: tuple[str, ...] = ("unknown_word", "no_referent", "ambiguous", "relation_false")

_ISA = "isa"


class Failure(NamedTuple):
    """Why comprehension failed: `reason` (one of FAILURE_REASONS) and what it is about."""

    reason: str
    subject: Term


@dataclass(frozen=True)
class Goal:
    """An action reference grounded: concept `concept` applied to `arg1` (and `arg2` for a
    verb with a relation; None for one on one object, "push X")."""

    action: str
    concept: Term
    arg1: Term
    arg2: Term | None
    relation: Term | None = None  # the concept of the relation word, when known

    @property
    def args(self) -> tuple[Term, ...]:
        return (self.arg1,) if self.arg2 is None else (self.arg1, self.arg2)

    def term(self) -> Term:
        """`concept(arg1,arg2)` or `concept(arg1)`, the form the concept memory stores it in."""
        return Term(str(self.concept.name), self.args)


@dataclass
class Comprehension:
    """What comprehension found. `ok` is true when nothing failed."""

    parse: Parse
    referents: dict[str, list[Term]] = field(default_factory=dict)
    # True: holds between some referents; False: referents exist and it holds between none
    # (relation_false); None: no relation reference, or undecided (unknown word, no referent).
    relation_holds: bool | None = None
    pairs: list[tuple[Term, Term]] = field(default_factory=list)  # (O1, O2) the relation holds for
    goal: Goal | None = None
    failures: list[Failure] = field(default_factory=list)
    # Per relation reference, the pairs it holds for (a sentence may have several relations).
    holds_for: dict[str, list[tuple[Term, Term]]] = field(default_factory=dict)
    # Per object reference, the objects its words fit before any relation narrows them ("the"
    # needs one of them, "two" two); a rule file without `candidate/2` leaves it empty.
    candidates: dict[str, list[Term]] = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return not self.failures

    @property
    def unknown_words(self) -> list[str]:
        return [str(f.subject) for f in self.failures if f.reason == "unknown_word"]

    def failed(self, reason: str) -> list[Term]:
        return [f.subject for f in self.failures if f.reason == reason]

    def referent(self, ref_id: str) -> Term | None:
        """The one referent of `ref_id`, or None when it has none or several."""
        objs = self.referents.get(ref_id, [])
        return objs[0] if len(objs) == 1 else None


def _concept(word: str, text: str) -> Term:
    try:
        return parse_term(text)
    except TermSyntaxError as exc:
        raise UserError(f"semantic memory: the concept of {word!r} is not a term: {exc}") from exc


def working_memory(
    parse: Parse,
    *,
    words: Mapping[str, str | Term],
    facts: Iterable[Term],
    inferred: Iterable[Term] = (),
) -> list[Term]:
    """The facts comprehension.lp reads (exposed for tests, the CLI and debugging).

    Objects are the `obj/1` facts plus every first argument of an `isa/2` fact and every
    argument of a binary relation fact.
    """
    out: list[Term] = list(parse.facts())
    objs: dict[Term, None] = {}
    for f in (*facts, *inferred):
        if f.name == "obj" and len(f.args) == 1:
            objs[f.args[0]] = None
            continue
        out.append(f)
        if f.name == _ISA and len(f.args) == 2:
            objs[f.args[0]] = None
        elif f.name == "rel" and len(f.args) == 3:
            objs[f.args[1]] = None
            objs[f.args[2]] = None
        elif is_relation(f):
            objs[f.args[0]] = None
            objs[f.args[1]] = None
            out.append(reify(f))
    out.extend(fn("obj", o) for o in objs)
    for w, c in words.items():
        out.append(fn("word_concept", w, c if isinstance(c, Term) else _concept(w, c)))
    return out


def comprehend(
    parse: Parse,
    *,
    words: Mapping[str, str | Term],
    facts: Iterable[Term],
    inferred: Iterable[Term] = (),
    rules: "str | os.PathLike[str] | None" = None,
) -> Comprehension:
    """Ground `parse` in the scene.

    words: semantic memory, word -> concept symbol (`{"red": "r_red"}`); only the sentence's
      own words are passed on to clingo.
    facts: percepts, QSR facts, `held/1` (anything else is passed through for user rules).
    inferred: concept facts from the concept memory: `isa(o1,r_red)`, `r_left_of(o1,o2)`.
    rules: a user's rule directory overriding the shipped `comprehension.lp`.
    """
    from aileen.reasoning import asp

    needed = set(parse.words)
    if parse.action is not None:  # optional meanings: reported when known, never a failure
        needed |= {parse.action.verb, parse.action.relation}
    relevant = {w: c for w, c in words.items() if w in needed}
    wm = working_memory(parse, words=relevant, facts=facts, inferred=inferred)
    files = asp.rule_paths(RULE_FILES, rules)
    model = asp.solve_once(files, wm)
    if model is None:
        own = asp.own_files(files)
        if own:  # the shipped comprehension always has an answer: the rules, not the lesson, failed
            names = ", ".join(map(str, own))
            raise asp.RulesUnsatisfiable(f"the comprehension program has no answer set with {names}, where the "
                                         f"shipped rules always have one; check your rules",
                                         path=str(rules if rules is not None else own[0].parent))
        raise UserError(f"{files[0]}: comprehension program has no answer set (check your rules)")
    return _read(parse, model)


def _read(parse: Parse, model: Iterable[Term]) -> Comprehension:
    result = Comprehension(parse, referents={o.id: [] for o in parse.objects})
    goal_rel: dict[str, Term] = {}
    goals: list[tuple[str, Term, Term, Term | None]] = []
    for a in model:
        name, args = a.name, a.args
        if name == "referent" and len(args) == 2:
            result.referents.setdefault(str(args[0]), []).append(args[1])
        elif name == "holds" and len(args) == 3:
            result.pairs.append((args[1], args[2]))
            result.holds_for.setdefault(str(args[0]), []).append((args[1], args[2]))
        elif name == "candidate" and len(args) == 2:
            result.candidates.setdefault(str(args[0]), []).append(args[1])
        elif name == "goal" and len(args) == 4:
            goals.append((str(args[0]), args[1], args[2], args[3]))
        elif name == "goal" and len(args) == 3:
            goals.append((str(args[0]), args[1], args[2], None))
        elif name == "act_relation" and len(args) == 2:
            goal_rel[str(args[0])] = args[1]
        elif name == "failure" and len(args) == 2:
            result.failures.append(Failure(str(args[0]), args[1]))
    for objs in (*result.referents.values(), *result.candidates.values()):
        objs.sort()
    result.pairs.sort()
    for pairs in result.holds_for.values():
        pairs.sort()
    result.failures.sort(key=lambda f: (FAILURE_REASONS.index(f.reason) if f.reason in FAILURE_REASONS else 99, f.subject))
    if parse.relation is not None:
        if result.holds_for.get(parse.relation.id):
            result.relation_holds = True
        elif parse.relation.id in {str(f.subject) for f in result.failures if f.reason == "relation_false"}:
            result.relation_holds = False
    if goals:
        goals.sort(key=lambda g: (g[1], g[2], g[3] or Term("")))
        a, c, o1, o2 = goals[0]
        result.goal = Goal(a, c, o1, o2, goal_rel.get(a))
    return result
