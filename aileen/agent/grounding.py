"""Grounding: which known concepts of a sentence hold in the scene, and what its words refer to.

Each candidate object (or ordered pair) is queried alone with its own facts (DESIGN.md
section 12), so other objects on the table neither dilute the match nor lend it spurious
support; the comprehension program (asp/comprehension.lp) then picks the referents.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

from aileen.agent import directions, judgement, verbs
from aileen.agent.part import Part
from aileen.agent.records import NOTHING_DONE, Answer
from aileen.agent.state import State, id_order
from aileen.domain import calculi
from aileen.memory import claims_pass, extent, quality, reach
from aileen.reasoning import comprehension, language
from aileen.terms import Term, fn


@dataclass
class _Grounding:
    """Comprehension plus the concept-memory evidence that fed it."""

    parse: language.Parse
    result: comprehension.Comprehension
    unknown: list[str]
    # "it", "the other one": the object each such reference is, or why it is none
    pins: dict[str, str] = field(default_factory=dict)
    unresolved: dict[str, str] = field(default_factory=dict)


class Grounding(Part):
    """The agent's part that comprehends against the concept memory: the `verify` signal,
    grounding a sentence read in the scene (`understand`), whether a relation word holds of a
    pair (`holds_binary`), and the evidence of the last comprehension (`weakly_recognised`)."""

    def __init__(self, agent: Any) -> None:
        super().__init__(agent)
        # the last sentence grounded: the best match of each recognised fact (its typicality
        # goes on the answer), where relation words were found to hold by their direction
        # (`weakly_recognised`), and what "it", "the other one" were found to be
        self._evidence: dict[Term, Any] = {}
        self._direction_seen: dict[Term, tuple[str, int]] = {}
        self._reach_seen: dict[Term, tuple[str, reach.Cells]] = {}
        self._pins: dict[str, str] = {}
        # the relation words' claims under mutual exclusivity (`relations_claimed_by_others`),
        # made again when next asked after the memory changed (`forget_derived`)
        self._relation_claims: dict[str, frozenset[str]] | None = None

    def _begin(self, pins: dict[str, str]) -> None:
        """A new sentence is grounded: its evidence starts empty, its anaphora are `pins`."""
        self._evidence = {}
        self._direction_seen = {}
        self._reach_seen = {}
        self._pins = pins

    def _concept_facts(self, p: language.Parse, state: State, demo_start: int | None) -> list[Term]:
        """Ask the concept memory which known concepts of the sentence hold in the scene.

        Each candidate object (or ordered pair) is queried alone with its own facts, so other
        objects on the table neither dilute the match nor lend it spurious support."""
        inferred: list[Term] = []
        objs = state.named()
        unary: dict[str, list[str]] = {}
        pins = self._pins
        for ref in p.objects:
            cands = [pins[ref.id]] if ref.id in pins else objs
            for word in ref.words:
                c = self.semantic.concept(word)
                if c is None or self.semantic.kind(c) != "visual":
                    continue
                holds = [o for o in cands if self._holds_unary(c, o, state)]
                inferred.extend(fn("isa", o, c) for o in holds)
                cands = holds
            unary[ref.id] = cands
        asked: set[Term] = set()
        for rel in p.relations:
            c = self.semantic.concept(rel.word)
            if c is not None:
                r1, r2 = unary.get(rel.arg1, objs), unary.get(rel.arg2, objs)
                for a in r1:
                    for b in r2:
                        if a != b and fn(c, a, b) not in asked:
                            asked.add(fn(c, a, b))
                            if self.holds_binary(c, a, b, state):
                                inferred.append(fn(c, a, b))
        if p.action is not None and demo_start is not None:
            inferred += self.agent.demonstrations.shown(p, unary, demo_start)
        return inferred

    def holds_as_asked(self, concept: str, obj: str) -> bool:
        """Would a question find `concept` of `obj` (leaving out what a question does, outside
        an inform's lesson: `Lexicon.not_asked`)? The object an inform's words name is the one
        a verify of them would find, though what it shows may be news (a large red box said
        to be a "red box" where every one taught was medium)."""
        assert self.state is not None
        return bool(self._query_unary(concept, obj, self.state))

    def _holds_unary(self, concept: str, obj: str, state: State) -> bool:
        return self.note(self._query_unary(concept, obj, state))

    def _query_unary(self, concept: str, obj: str, state: State) -> list:
        """The memory's answers to "is `obj` a `concept`?", leaving out what a query of the
        word leaves out (`Lexicon.not_asked`, in a lesson or out of one)."""
        ignore = self.lexicon.not_asked(concept) if self.params.mutual_exclusivity else ()
        return self.memory.query(state.percepts(obj), fn("isa", obj, concept), ignore=ignore)

    def holds_binary(self, concept: str, a: str, b: str, state: State) -> bool:
        facts = state.percepts(a) + state.percepts(b) + state.relations(a, b)
        skip: frozenset[str] = frozenset()
        if self.params.extents and self.semantic.kind(concept) == "spatial":
            # The word's direction is the region its examples support (memory/extent.py); the
            # other facts go to SME as always. So is its distance, where distance is what it
            # says (`Directions.reach`: "near" once the direction words say where).
            reading = self.directions.reach(concept)
            if reading is not None:
                at = reach.cells(facts, Term(a), Term(b))
                if at is None or reading.holds(at) < extent.ACCEPT:
                    return False
                self._reach_seen[fn(concept, a, b)] = (concept, at)
            region, by_chance = self.directions.read(concept)
            if by_chance:
                # read as sideless for now: one more example on this side may make its sides no
                # coincidence (`Directions.news`), so where it was found to hold is noted
                k = extent.sector_of(facts, Term(a), Term(b))
                if k is not None:
                    self._direction_seen[fn(concept, a, b)] = (concept, k)
            elif region is not None:
                k = extent.sector_of(facts, Term(a), Term(b))
                if k is None or region[k] < extent.ACCEPT:
                    return False
                # where the word was found to hold: an inform there that would still move the
                # word's region is learned from (`weakly_recognised`)
                self._direction_seen[fn(concept, a, b)] = (concept, k)
                if not self.directions.marked_word(concept):
                    # a direction word: its descriptions hold nothing but its direction and
                    # what nearly every pair has (`dc`), so its region decides ("right of" shown
                    # twice apart and once touching is not "apart")
                    return True
            skip = directions.region_predicates()
            if reading is not None and reading.measure is not reach.MEASURES[0]:
                # its distance is the reading's, in another measure than qdist's: SME asked
                # for `qd_close` too refused a pair 7 cm apart side by side of a word shown
                # 7 cm apart on the diagonals, where qdist's gap is 2 cm (`qd_close` each time)
                skip = skip | frozenset(calculi.QDIST.relations)
        if not self.params.mutual_exclusivity:
            return self.note(self.memory.query(facts, fn(concept, a, b), ignore_relations=skip))
        return self.note(self.memory.query(facts, fn(concept, a, b), ignore=self._percepts_claimed(),
                                            ignore_relations=self.relations_claimed_by_others(concept) | skip))

    def sideless(self, concept: str) -> bool:
        """Does the relation word say nothing of which side (with extents, a spatial word
        whose `Directions.region` is None: "near" once the direction words say where)?"""
        return (self.params.extents and self.semantic.kind(concept) == "spatial"
                and self.directions.region(concept) is None)

    def accounted(self, concept: str, a: str, b: str, facts: list[Term]) -> list[Term] | None:
        """The facts among `facts` (between a and b, in the current state) that the relation
        concept accounts for when it holds of (a, b), None when it does not
        (`verbs.accounted`). With extents, the word holds as `holds_binary` says, and its
        direction accounts for every direction fact at every grain."""
        assert self.state is not None
        percepts = self.state.percepts(a) + self.state.percepts(b)
        if not (self.params.extents and self.semantic.kind(concept) == "spatial"):
            return verbs.accounted(self.memory, concept, Term(a), Term(b), facts, percepts)
        if not self.holds_binary(concept, a, b, self.state):
            return None
        if self.directions.is_direction_word(concept):
            # a direction word accounts for the pair's direction at every grain and for what
            # nearly every pair has (`dc`): it says nothing else of them
            return [f for f in facts if calculi.is_direction(f.name) or directions.common(f.name)]
        best = self.memory.query(percepts + list(facts), fn(concept, a, b),
                                 ignore_relations=directions.region_predicates())
        wanted = set(facts)
        out = [t for t in best[0].mapping.pairs.values() if t in wanted] if best else []
        if self.directions.sided(concept):
            out += [f for f in facts if calculi.is_direction(f.name) and f not in out]
        return out

    def _percepts_claimed(self) -> frozenset[Term]:
        """Every percept a visual word stands for ("large": `cv_large`): not what a relation
        word is about either. Made again only when the lexicon's meanings were (after a store
        or a newly noted word position), not on every pair asked about."""
        return self.lexicon.claimed_percepts()

    def relations_claimed_by_others(self, concept: str) -> frozenset[str]:
        """Mutual exclusivity over relation words, at query time, as for visual words: a
        relation concept's meaning is the set of relations its description requires between
        its two roles (`cone_w(A,B)`, `dc(A,B)`, `qd_close(B,A)`); it gives up those of any
        strictly smaller meaning, to a fixpoint and never down to nothing (`memory.claims_pass`).
        "near" first shown with the objects left of one another means {cone_w(A,B),
        cone_e(B,A), dc, qd_close}; once "left of" means {cone_w(A,B), cone_e(B,A)}, "near"
        is {dc, qd_close}: which side it was shown on is "left of"'s business. Returned: the
        predicates all of whose role forms in the concept are claimed."""
        claims_now = self._relation_claims
        if claims_now is None:
            meanings: dict[str, frozenset[tuple[str, int, int]]] = {}
            skip = directions.region_predicates() if self.params.extents else frozenset()
            for c in self.memory.concepts():
                descriptions = self.memory.descriptions(c.symbol) if c.kind == "spatial" else []
                if len(descriptions) != 1:  # a disjunctive concept has no one meaning to compare
                    continue
                # with extents, directions are compared as regions, not as facts (`holds_binary`)
                meanings[c.symbol] = frozenset(f for f in role_forms(descriptions[0], c.symbol) if f[0] not in skip)
            # what nearly every pair has (`dc`) tells nothing: a word left with only that is a
            # synonym or a conjunction of the words that claim the rest, and keeps their facts
            # ("tinier than" taught with "smaller than" known lost its sizes and held of a large
            # box and a small cone once no direction word's one meaning was `dc` alone)
            common = frozenset(f for m in meanings.values() for f in m if directions.common(f[0]))
            kept = claims_pass.exclusive(meanings, common)
            claims_now = {}
            for c, m in meanings.items():
                gone = m - kept.get(c, m)
                claims_now[c] = frozenset(p for p, *_ in gone if all(f in gone for f in m if f[0] == p))
            self._relation_claims = claims_now
        return claims_now.get(concept, frozenset())

    def forget_derived(self, concept: str | None = None) -> None:
        """The concept memory changed (a store into `concept`; None: near misses, anywhere):
        what comprehension derived from it is made again when next asked (the relation words'
        claims). The one place these caches are reset. The visual words' meanings and their
        exclusivity are the lexicon's, kept up to date from the memory's change log (a store
        is in it; near misses leave the descriptions, so the meanings, as they were)."""
        self._relation_claims = None

    def note(self, found: list) -> bool:
        """Keep the best evidence for a recognised fact (its typicality goes on the answer)."""
        if found:
            self._evidence[found[0].fact] = found[0]
        return bool(found)

    def verify(self, content: str, *, demo_start: int | None = None) -> Answer:
        """Does what the content says hold in the scene (or the demonstration just seen)?"""
        assert self.state is not None, "perceive before a lesson"
        read = self.agent.reading.read("verify", content)
        if isinstance(read, Answer):
            return read  # not understood, or a slip asked about
        group = self.agent.composites.group_answer("verify", content, read)
        if group is not None:
            return group
        if read.mood == "where":
            return self.agent.reading.where("verify", content, read, demo_start)
        g, inferred = self.understand(read, demo_start)
        return self.answer("verify", content, g, inferred, demo_start)

    def comprehend(self, content: str, *, demo_start: int | None = None) -> comprehension.Comprehension:
        """Indexical comprehension of `content` in the current scene (and demonstration)."""
        return self.understand(self.agent.reading.parse(content), demo_start)[0].result

    def understand(self, p: language.Parse, demo_start: int | None,
                   chosen: dict[str, str] | None = None) -> tuple[_Grounding, list[Term]]:
        """Ground the sentence read (`p`: parsed once per lesson, by `Reading.read`) in the scene.
        `chosen`: references already taken to mean one object ("a red box", one of two)."""
        assert self.state is not None, "perceive before comprehending"
        # "it", "the other one": what the last lesson grounded, found on this table
        pins, unresolved = self.agent.reading.resolve_anaphora(p) if any(o.anaphor for o in p.objects) else ({}, {})
        pins = {**pins, **(chosen or {})}
        self._begin(pins)
        inferred = self._concept_facts(p, self.state, demo_start)
        words = self._words_for(p)
        named = [fn("ref_is", r, pins.get(r, "nothing")) for r in (*pins, *unresolved)]
        result = comprehension.comprehend(p, words=words, facts=self.state.facts, inferred=inferred + named,
                                          rules=self.agent.rules)
        unknown = [w for w in p.words if w not in words]
        return _Grounding(p, result, unknown, pins, unresolved), inferred

    def answer(self, signal: str, content: str, g: _Grounding, inferred: list[Term],
               demo_start: int | None) -> Answer:
        """The answer to a sentence grounded (`understand`): its referents, and why not."""
        r = g.result
        referents = {g.parse.object(k).text: [str(o) for o in v] for k, v in r.referents.items()}
        # Two red boxes on the table do not make "red box" false: only acting on one needs
        # it to be unique. "the red box" does (agent/judgement.py), as do numbers, plurals,
        # "not" and "and".
        verdict = judgement.judge(g.parse, r, self.agent.reading.where_is)
        judged, said_of, shared = self._predicated(signal, g, demo_start)
        for ref_id, named in shared.items():  # "the boxes are red and blue": the boxes, by their own words
            if not any(pr.ref == ref_id for pr in said_of):
                ref = g.parse.object(ref_id)
                referents.pop(ref.text, None)
                referents[dataclasses.replace(ref, words=ref.subject).text] = [str(o) for o in named]
        failures = [f for f in verdict.failures if (f.reason != "ambiguous" or signal == "react")
                    and not (f.reason == "no_referent" and str(f.subject) in g.unresolved)
                    and not (f.reason in ("no_referent", "ambiguous") and str(f.subject) in judged)]
        verdict.problems[:] = [pr for pr in verdict.problems if pr.ref not in judged] + said_of
        said = {str(f.subject) for f in failures if f.reason == "ambiguous"}  # react says it its way
        reasons = [judgement.reason_text(f.reason, f.subject, g.parse, verb_alone=self.params.one_verb,
                                          knows=lambda w: self.agent.semantic.concept(w) is not None)
                   for f in failures]
        reasons[:0] = [g.unresolved[o.id] for o in g.parse.objects if o.id in g.unresolved]
        reasons += [pr.text for pr in verdict.problems if not (pr.kind == "cannot_tell" and pr.ref in said)]
        if g.parse.action is not None and not failures and demo_start is not None:
            if not any(f.name == self.agent.demonstrations.action_concept(g.parse) for f in inferred):
                reasons.append(f"the demonstration is not '{g.parse.action.word.replace('_', ' ')}'")
        elif g.parse.action is not None and demo_start is None and signal in ("inform", "verify"):
            # an action is something done: with nothing done, "move the red box left of the
            # blue cone" was "yes" wherever the box stood, and an inform taught nothing, silently
            reasons.append(f"{NOTHING_DONE}: '{g.parse.action.verb}' is learned and checked from a demonstration")
        reasons = list(dict.fromkeys(reasons))  # "red box left of red box" over two: said once
        result = "failure" if reasons else "success"
        self.agent.reading.remember([str(v[0]) for k, v in r.referents.items() if len(v) == 1])
        return Answer(signal, content, result, "; ".join(reasons) or None, referents,
                      typicality=self._typicality(g),
                      unknown_words=sorted({str(f.subject) for f in failures if f.reason == "unknown_word"}))

    def _predicated(self, signal: str, g: _Grounding, demo_start: int | None) -> tuple[
            set[str], list[judgement.Problem], dict[str, list[Term]]]:
        """A verify's things said to be something ("every box is red", "is the box red?"):
        grounded again by their subjects' words alone, what is said asked of each
        (`judgement.predicated`). An inform learns from the sentence as one description, as
        before. Also returned: the things named by each reference whose words were shared out
        among them ("the boxes are red and blue": `_each_word`)."""
        p = g.parse
        if signal == "inform":
            # an inform says it of the things as one description ("the box is red": a red box
            # to learn from), but for what is shared out among them ("the boxes are red and
            # blue", every word known), which is true or not as a verify finds it
            p = dataclasses.replace(p, objects=tuple(
                o if judgement.shared_out(o) and all(self.semantic.concept(w) is not None for w in o.words)
                else dataclasses.replace(o, said_of=()) for o in p.objects))
        elif signal != "verify":
            return set(), [], {}
        if p.action is not None or not any(o.said_of and o.anaphor is None for o in p.objects):
            return set(), [], {}
        kept = (self._evidence, self._direction_seen, self._reach_seen, self._pins)
        try:
            subject, _ = self.understand(p.subjects(), demo_start)
        finally:
            self._evidence, self._direction_seen, self._reach_seen, self._pins = kept
        each = self._each_word(p, subject.result)
        judged, problems = judgement.predicated(p, g.result, subject.result, self.agent.reading.where_is, each)
        named = {k: sorted(set().union(*fits.values()), key=str) for k, fits in each.items()}
        return judged, problems, named

    def _each_word(self, p: language.Parse, subject: comprehension.Comprehension) -> dict[str, dict[str, set]]:
        """For each thing whose words may be shared out among the things it names ("the boxes
        are red and blue": `judgement.shared_out`), the things each word said of it holds of
        (`shared_fits`)."""
        out: dict[str, dict[str, set]] = {}
        for ref in p.objects:
            if judgement.shared_out(ref):
                named = subject.candidates.get(ref.id) or subject.referents.get(ref.id, [])
                fits = self.shared_fits(ref.said_of, named)
                if fits is not None:
                    out[ref.id] = fits
        return out

    def shared_fits(self, words: Iterable[str], named: Iterable[Any]) -> dict[str, set] | None:
        """Per word said of several things, the things of `named` it holds of, as a question
        of the word alone would find them; None where a word is no known thing's word (a
        relation's, a new one) or the words are not alternatives on one channel
        (`Lexicon.alternatives`: "red and large" is said of each thing, not shared out)."""
        concepts = {w: self.semantic.concept(w) for w in words}
        if not concepts or any(c is None or self.semantic.kind(c) != "visual" for c in concepts.values()) \
                or not self.lexicon.alternatives(concepts.values()):
            return None
        named = list(named)
        return {w: {o for o in named if self.holds_as_asked(c, str(o))} for w, c in concepts.items()}

    def _typicality(self, g: _Grounding) -> dict[str, float]:
        """Per recognised fact about the referents: how typical an instance it is (memory/quality.py)."""
        chosen = {o for objs in g.result.referents.values() for o in objs}
        out = {}
        for fact, inf in self._evidence.items():
            if all(a in chosen for a in fact.args if not str(a).startswith("r_") and not str(a).startswith("cv_")):
                out[str(fact)] = quality.typicality(self.memory, inf)
        return dict(sorted(out.items()))

    def _words_for(self, p: language.Parse) -> dict[str, str]:
        """The semantic memory as comprehension gets it: with one verb for every relation,
        `move_behind` is understood as soon as "move" and "behind" are (composition)."""
        words = self.semantic.words()
        c = self.agent.demonstrations.action_concept(p)
        if c is not None and p.action is not None:
            words[p.action.word] = c
        return words

    def weakly_recognised(self) -> set[Term]:
        """Concept facts of the last comprehension whose best match lies within
        `AgentParams.weak_margin` of the match threshold, and (with extents) relation facts
        whose example is news to the word (`extent.news`): it would still change where the
        word's region holds, or lies where the word holds without being sure. Under the size
        principle an example the agent already accepts is evidence too (four examples near
        the axis make a narrow word; one at the edge of what it agreed to keeps the word that
        wide), and it would otherwise never move a word's grain. (No weak
        matches with `--without weak-comprehension`.)"""
        unsure = {f for f, (c, k) in self._direction_seen.items() if self.directions.news(c, k)}
        unsure |= {f for f, (c, k) in self._reach_seen.items() if self.directions.reach_news(c, k)}
        if not self.params.weak_comprehension or self.params.weak_margin <= 0:
            return unsure
        edge = self.memory.params.match + self.params.weak_margin
        return unsure | {f for f, inf in self._evidence.items() if inf.similarity < edge - 1e-12}


def role_forms(description: list[Term], concept: str) -> frozenset[tuple[str, int, int]]:
    """A relation description's calculus facts between its two roles, as (predicate, role of
    the first argument, role of the second): 0 the concept's first argument, 1 its second."""
    member = next((f for f in description if f.name == concept and len(f.args) == 2), None)
    if member is None:
        return frozenset()
    role = {member.args[0]: 0, member.args[1]: 1}
    return frozenset((f.name, role[f.args[0]], role[f.args[1]]) for f in description
                     if len(f.args) == 2 and f.name != concept and calculi.calculus_of(f.name) is not None
                     and f.args[0] in role and f.args[1] in role)

