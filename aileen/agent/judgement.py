"""What a sentence asks of what comprehension found: negation, "and", "the", numbers, plurals.

Why apart from comprehension.lp: the rule file grounds each reference and relation in the
scene (which objects fit the words, which pairs stand in the relation); whether the sentence
is then true needs how many things it names and how its parts go together, which the
sentence's grammar says:

* "X is not REL Y" is true when REL does not hold between them (and false when it does);
* "X is left of A and right of B": one X must do both; "A and B are left of C": each;
* "the X" needs one X on the table: with two, the agent says which it cannot tell apart;
* "every X is P", "the Xs are P", "is the X P?": P of each X (`predicated`), not "every P X";
  "the Xs are P and Q" each X one of them, each said of one ("the boxes are red and blue");
* "two Xs" needs two (exactly two, when nothing else is said of them: "are there two boxes?"),
  "the Xs", "all Xs", "every X" every X, a plural at least two ("any Xs" at least one).

Comprehension's own failures (an unknown word, nothing fits, the relation does not hold) are
kept as they are, but for a relation the sentence negates.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from aileen.reasoning.comprehension import Comprehension, Failure
from aileen.reasoning.language import ObjectRef, Parse, RelationRef, plural, property_said
from aileen.terms import Term

_ALL = frozenset({"every", "each", "all", "both"})


@dataclass(frozen=True)
class Problem:
    """Why the sentence is not true of the scene, beyond comprehension's failures. `kind`:
    "cannot_tell" ("the" with several), "count", "not_all", "holds" (a negated relation
    holds), "not_together" (one object cannot be all the sentence says), "not_said" (what is
    said of the one thing named is not so: "the box is red" of a blue box)."""

    kind: str
    ref: str  # the object or relation reference it is about
    text: str  # in the teacher's words


@dataclass(frozen=True)
class Verdict:
    failures: list[Failure]  # comprehension's, less those a negation turns round
    problems: list[Problem]


def judge(p: Parse, r: Comprehension, where: Callable[[Term], str]) -> Verdict:
    """The sentence `p` against comprehension's result `r`; `where(o)` says where an object
    is ("o2 at (0.31, 0.52)"), for "which one" messages."""
    negated = {rel.id for rel in p.relations if rel.negated}
    # "0 boxes are right of the cone": that none is, not that one is, and none seen is no
    # failure (`_how_many` counts them)
    none_said = {o.id for o in p.objects if o.count == 0}
    negated |= {rel.id for rel in p.relations if rel.arg1 in none_said or rel.arg2 in none_said}
    kept = [f for f in r.failures if not (f.reason == "relation_false" and str(f.subject) in negated)]
    failures = [f for f in kept if not (f.reason == "no_referent" and str(f.subject) in none_said)]
    unknown = {str(f.subject) for f in r.failures if f.reason == "unknown_word"}
    problems: list[Problem] = []
    for rel in p.relations:
        if rel.negated and r.holds_for.get(rel.id):
            problems.append(Problem("holds", rel.id, f"'{_word(rel)}' holds: {_sentence(p, rel)}"))
    failed = {str(f.subject) for f in kept if f.reason != "ambiguous"}  # (none seen of "0 Xs": nothing to judge)
    for ref in p.objects:
        if ref.anaphor is not None or ref.id in failed or any(w in unknown for w in ref.words):
            continue
        cands = r.candidates.get(ref.id, []) if r.candidates else r.referents.get(ref.id, [])
        if _singular(ref) and ref.definite and len(cands) > 1:
            listed = ", ".join(where(o) for o in cands[:-1]) + f" and {where(cands[-1])}"
            problems.append(Problem("cannot_tell", ref.id,
                                    f"I cannot tell which '{ref.text}' you mean: I see {len(cands)}, {listed}"))
            continue
        mine = [rel for rel in p.relations if not rel.negated and ref.id in (rel.arg1, rel.arg2)]
        if any(rel.id in failed or rel.word in unknown for rel in mine):
            continue  # the relation already failed: that is the answer
        fitting = _fitting(ref, mine, r, cands)
        problems += _together(ref, mine, r, fitting)
        problems += _how_many(ref, mine, cands, fitting)
    return Verdict(failures, problems)


def shared_out(ref: ObjectRef) -> bool:
    """May what is said of the thing be shared out among them? "the boxes are red and blue"
    over a red box and a blue box is true as a person says it: each box is one of the things
    said and each is said of some box (the cumulative reading; it read as every box both red
    and blue). Only a plain definite plural with two or more words said of it: "every box is
    red and blue" and "both boxes are ..." say it of each one, and "is the box red and blue?"
    of one."""
    return len(ref.said_of) >= 2 and ref.definite and ref.plural and ref.quantifier is None and ref.count is None


def predicated(p: Parse, whole: Comprehension, subject: Comprehension,
               where: Callable[[Term], str],
               each: dict[str, dict[str, set[Term]]] | None = None) -> tuple[set[str], list[Problem]]:
    """What is said of a thing ("every box is red", "is the box red?", "is the cone a box?")
    holds of each thing its subject names: `subject` grounds the sentence with the subject's
    words alone (`Parse.subjects`), `whole` with every word. Read as one description, "every
    box is red" was "every red box" (yes over a red and a blue box), "the boxes are red" "I see
    1 'red box', not several", "is the box red?" over two red boxes "cannot tell which 'red
    box'". Returned: the references judged here (what `judge` and comprehension say of them
    stands aside, their relations apart) and the problems. An indefinite subject ("a box is
    red", "two boxes are red", "some boxes are blue") says there are such things: left to `judge`.
    `each`: per reference whose words may be shared out (`shared_out`), the things its subject
    names that each word said of it holds of; true when every one is one of them and every word
    holds of one."""
    unknown = {str(f.subject) for f in whole.failures if f.reason == "unknown_word"}
    handled: set[str] = set()
    problems: list[Problem] = []
    for ref in p.objects:
        if not ref.said_of or ref.anaphor is not None or any(w in unknown for w in ref.words):
            continue
        every = ref.quantifier in _ALL or (ref.definite and not _singular(ref))
        if not every and not (ref.definite and _singular(ref)):
            continue
        handled.add(ref.id)
        named = subject.candidates.get(ref.id) or subject.referents.get(ref.id, [])
        fits = set(whole.candidates.get(ref.id) or whole.referents.get(ref.id, []))
        head = " ".join(map(property_said, ref.subject))
        n = len(named)
        heads = head if n == 1 else plural(head)
        if every:
            least = _least(ref)
            want = ref.count if ref.definite and ref.count is not None else 2 if ref.quantifier == "both" else None
            if want is not None and n != want:
                problems.append(Problem("count", ref.id, f"I see {n} '{heads}', not {want if want != 2 else 'two'}"))
            elif n < least:
                problems.append(Problem("count", ref.id, f"I see {n} '{heads}'" + (", not several" if n else "")))
            elif not set(named) <= fits and not _shared_out(named, (each or {}).get(ref.id)):
                problems.append(Problem("not_all", ref.id, f"not every '{head}' is {ref.attribute}"))
        elif n == 0:
            problems.append(Problem("count", ref.id, f"I see no '{head}'"))
        elif n > 1:
            listed = ", ".join(where(o) for o in named[:-1]) + f" and {where(named[-1])}"
            problems.append(Problem("cannot_tell", ref.id, f"I cannot tell which '{head}' you mean: I see {n}, {listed}"))
        elif named[0] not in fits:
            problems.append(Problem("not_said", ref.id, f"'the {head}' is not {ref.attribute}"))
    return handled, problems


def _shared_out(named: list[Term], by_word: dict[str, set[Term]] | None) -> bool:
    """Every thing named is one of the things said, and every one said is so of some thing."""
    if not by_word:
        return False
    return all(any(o in fit for fit in by_word.values()) for o in named) and all(by_word.values())


def _least(ref: ObjectRef) -> int:
    """How many things a plural or a quantifier needs: "both" and a plain plural ("the boxes",
    "red boxes") two; "all", "every", "each" every one, one being enough ("all cones are blue"
    over one blue cone was "I see 1 'blue cone', not several"); "any" at least one ("are there
    any boxes?" asks whether there is one)."""
    if ref.quantifier in ("all", "every", "each", "any"):
        return 1
    return 2 if ref.plural or ref.quantifier == "both" else 1


def _singular(ref: ObjectRef) -> bool:
    return not ref.plural and ref.count in (None, 1) and ref.quantifier is None


def _fitting(ref: ObjectRef, rels: list[RelationRef], r: Comprehension, cands: list[Term]) -> set[Term]:
    """The candidates that stand in every relation the sentence gives the reference."""
    out = set(cands)
    for rel in rels:
        pairs = r.holds_for.get(rel.id, [])
        out &= {a if rel.arg1 == ref.id else b for a, b in pairs}
    return out


def _together(ref: ObjectRef, rels: list[RelationRef], r: Comprehension, fitting: set[Term]) -> list[Problem]:
    if len(rels) < 2 or fitting:
        return []
    # said from the thing's side: "no 'blue cone' I see has 'red box' left of it", not "is
    # left of 'red box'" (the relation turned round) where it is the relations' second argument
    said = " and ".join(f"is {_word(rel)} '{_other(rel, ref.id, r)}'" if rel.arg1 == ref.id
                        else f"has '{_other(rel, ref.id, r)}' {_word(rel)} it" for rel in rels)
    return [Problem("not_together", ref.id, f"no '{ref.text}' I see {said}")]


def _many(n: int, text: str) -> str:
    """The thing's words as many as seen: "2 'boxes'", "1 'box'" (it said "I see 2 'box'")."""
    return text if n == 1 else plural(text)


def _how_many(ref: ObjectRef, rels: list[RelationRef], cands: list[Term], fitting: set[Term]) -> list[Problem]:
    n, text = len(cands), ref.text
    if ref.count == 0:  # "0 red boxes", "zero red boxes": none there (as the sentence says)
        some = len(fitting) if rels else n
        if some:
            return [Problem("count", ref.id, f"I see {some} '{_many(some, text)}'" + (" that " + ("is" if some == 1 else "are")
                                                                          + " as the sentence says" if rels else "")
                            + ", not 0")]
        return []
    if ref.count is not None and ref.count >= 1:
        if rels and not ref.definite:
            if len(fitting) < ref.count:
                some = len(fitting)
                return [Problem("count", ref.id, f"I see {some} '{_many(some, text)}' that {'is' if some == 1 else 'are'}"
                                f" as the sentence says, not {ref.count}")]
            return []
        if n != ref.count:
            return [Problem("count", ref.id, f"I see {n} '{_many(n, text)}', not {ref.count}")]
        if rels and fitting != set(cands):
            return [Problem("not_all", ref.id, f"not every '{text}' is as the sentence says")]
        return []
    if ref.plural or ref.quantifier in _ALL:
        least = _least(ref)
        if n < least:
            return [Problem("count", ref.id, f"I see {n} '{_many(n, text)}'" + (", not several" if n else ""))]
        if ref.quantifier == "both" and n != 2:
            return [Problem("count", ref.id, f"I see {n} '{_many(n, text)}', not two")]
        if rels and (ref.definite or ref.quantifier in _ALL or ref.quantifier is None) and fitting != set(cands):
            return [Problem("not_all", ref.id, f"not every '{text}' is as the sentence says")]
        return []
    return []


def _word(rel: RelationRef) -> str:
    return rel.spoken


def _other(rel: RelationRef, ref_id: str, r: Comprehension) -> str:
    other = rel.arg2 if rel.arg1 == ref_id else rel.arg1
    return r.parse.object(other).text


def _sentence(p: Parse, rel: RelationRef) -> str:
    return f"'{p.object(rel.arg1).text}' is {_word(rel)} '{p.object(rel.arg2).text}'"


def reason_text(reason: str, subject: Term, parse: Parse, *, verb_alone: bool = False,
                knows: Callable[[str], bool] | None = None) -> str:
    """A failure as a person would say it. `verb_alone`: an action's word is its verb (one
    verb for every relation, `agent/verbs.py`): "I do not know the word 'put'", not 'put
    behind' (the relation may be known; the concept made is the verb's). `knows`: whether the
    agent knows a word; where it knows the verb and not the relation, the relation is named
    ("move" known, "right of" never taught: it said 'move')."""
    s = str(subject)
    if reason == "unknown_word":
        act = parse.action
        if verb_alone and act is not None and s == act.word:
            if act.relation is not None and knows is not None and knows(act.verb) and not knows(act.relation):
                said = next((r.spoken for r in parse.relations if r.word == act.relation),
                            act.relation.replace("_", " "))
                return f"I do not know the word '{said}'"
            return f"I do not know the word '{act.verb}'"
        said = next((r.spoken for r in parse.relations if r.word == s),
                    property_said(s) if any(s in o.words for o in parse.objects) else s.replace("_", " "))
        return f"I do not know the word '{said}'"
    if reason in ("no_referent", "ambiguous"):
        try:
            text = parse.object(s).text
        except KeyError:
            text = s
        if reason == "no_referent":
            return f"I see no '{text}'"
        # (an action needs one: "a red box" says any one will do)
        if parse.action is None:
            return f"I see more than one '{text}'"
        try:
            several = parse.object(s).plural or (parse.object(s).count or 1) > 1
        except KeyError:
            several = False
        return (f"I see more than one '{text}'" + (": I move one thing at a time" if several else "")
                + f"; say which, or 'a {text}' for any one")
    if reason == "relation_false":
        try:
            rel = parse.relation_ref(s)
        except KeyError:
            rel = parse.relation
        return f"'{rel.spoken}' does not hold" if rel is not None else "the relation does not hold"
    return f"{reason}: {s}"
