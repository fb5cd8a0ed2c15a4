"""Grounding: which known concepts of a sentence hold in the scene, and what its words refer to.

Each candidate object (or ordered pair) is queried alone with its own facts (DESIGN.md
section 12), so other objects on the table neither dilute the match nor lend it spurious
support; the comprehension program (asp/comprehension.lp) then picks the referents.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable
from dataclasses import dataclass, field

from aileen.agent import directions, judgement, verbs
from aileen.agent.records import Answer
from aileen.agent.state import State, id_order
from aileen.domain import calculi
from aileen.memory import claims, extent, quality
from aileen.memory.concept import time_chain
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


class Grounding:
    """Mixin of `Agent`: comprehension against the concept memory."""

    def _concept_facts(self, p: language.Parse, state: State, demo_start: int | None) -> list[Term]:
        """Ask the concept memory which known concepts of the sentence hold in the scene.

        Each candidate object (or ordered pair) is queried alone with its own facts, so other
        objects on the table neither dilute the match nor lend it spurious support."""
        inferred: list[Term] = []
        objs = sorted(state.objects, key=id_order)
        unary: dict[str, list[str]] = {}
        pins = self.__dict__.get("_pins", {})
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
                            if self._holds_binary(c, a, b, state):
                                inferred.append(fn(c, a, b))
        if p.action is not None and demo_start is not None:
            inferred += self._action_facts(p, unary, demo_start)
        return inferred

    def _holds_unary(self, concept: str, obj: str, state: State) -> bool:
        facts = state.percepts(obj)
        ignore = self.lexicon.claimed_by_others(concept) if self.params.mutual_exclusivity else ()
        return self._note(self.memory.query(facts, fn("isa", obj, concept), ignore=ignore))

    def _visual_concepts(self) -> list[str]:
        return [c.symbol for c in self.memory.concepts() if c.kind == "visual"]

    def _holds_binary(self, concept: str, a: str, b: str, state: State) -> bool:
        facts = state.percepts(a) + state.percepts(b) + state.relations(a, b)
        skip: frozenset[str] = frozenset()
        if self.params.extents and self.semantic.kind(concept) == "spatial":
            # The word's direction is the region its examples support (memory/extent.py); the
            # other facts go to SME as always.
            region = self.directions.region(concept)
            if region is not None:
                k = extent.sector_of(facts, Term(a), Term(b))
                if k is None or region[k] < extent.ACCEPT:
                    return False
                # where the word was found to hold: an inform there that would still move the
                # word's region is learned from (Learning._weakly_recognised)
                self.__dict__.setdefault("_direction_seen", {})[fn(concept, a, b)] = (concept, k)
                if not self.directions.marked_word(concept):
                    # a direction word: its descriptions hold nothing but its direction and
                    # what nearly every pair has (`dc`), so its region decides ("right of" shown
                    # twice apart and once touching is not "apart")
                    return True
            skip = directions.direction_predicates()
        if not self.params.mutual_exclusivity:
            return self._note(self.memory.query(facts, fn(concept, a, b), ignore_relations=skip))
        return self._note(self.memory.query(facts, fn(concept, a, b), ignore=self._percepts_claimed(),
                                            ignore_relations=self._relations_claimed_by_others(concept) | skip))

    def _accounted(self, concept: str, a: str, b: str, facts: list[Term]) -> list[Term] | None:
        """The facts among `facts` (between a and b, in the current state) that the relation
        concept accounts for when it holds of (a, b), None when it does not
        (`verbs.accounted`). With extents, the word holds as `_holds_binary` says, and its
        direction accounts for every direction fact at every grain."""
        assert self.state is not None
        percepts = self.state.percepts(a) + self.state.percepts(b)
        if not (self.params.extents and self.semantic.kind(concept) == "spatial"):
            return verbs.accounted(self.memory, concept, Term(a), Term(b), facts, percepts)
        if not self._holds_binary(concept, a, b, self.state):
            return None
        if self.directions.is_direction_word(concept):
            # a direction word accounts for the pair's direction at every grain and for what
            # nearly every pair has (`dc`): it says nothing else of them
            return [f for f in facts if calculi.is_direction(f.name) or directions.common(f.name)]
        best = self.memory.query(percepts + list(facts), fn(concept, a, b),
                                 ignore_relations=directions.direction_predicates())
        wanted = set(facts)
        out = [t for t in best[0].mapping.pairs.values() if t in wanted] if best else []
        if self.directions.region(concept) is not None:
            out += [f for f in facts if calculi.is_direction(f.name) and f not in out]
        return out

    def _percepts_claimed(self) -> frozenset[Term]:
        """Every percept a visual word stands for ("large": `cv_large`): not what a relation
        word is about either. Made again only when the lexicon's meanings were (after a store
        or a newly noted word position), not on every pair asked about."""
        return self.lexicon.claimed_percepts()

    def _relations_claimed_by_others(self, concept: str) -> frozenset[str]:
        """Mutual exclusivity over relation words, at query time, as for visual words: a
        relation concept's meaning is the set of relations its description requires between
        its two roles (`cone_w(A,B)`, `dc(A,B)`, `qd_close(B,A)`); it gives up those of any
        strictly smaller meaning, to a fixpoint and never down to nothing (`memory.claims`).
        "near" first shown with the objects left of one another means {cone_w(A,B),
        cone_e(B,A), dc, qd_close}; once "left of" means {cone_w(A,B), cone_e(B,A)}, "near"
        is {dc, qd_close}: which side it was shown on is "left of"'s business. Returned: the
        predicates all of whose role forms in the concept are claimed."""
        claims_now = self.__dict__.get("_relation_claims")
        if claims_now is None:
            meanings: dict[str, frozenset[tuple[str, int, int]]] = {}
            skip = directions.direction_predicates() if self.params.extents else frozenset()
            for c in self.memory.concepts():
                descriptions = self.memory.descriptions(c.symbol) if c.kind == "spatial" else []
                if len(descriptions) != 1:  # a disjunctive concept has no one meaning to compare
                    continue
                # with extents, directions are compared as regions, not as facts (`_extent`)
                meanings[c.symbol] = frozenset(f for f in _role_forms(descriptions[0], c.symbol) if f[0] not in skip)
            kept = claims.exclusive(meanings)
            claims_now = {}
            for c, m in meanings.items():
                gone = m - kept.get(c, m)
                claims_now[c] = frozenset(p for p, *_ in gone if all(f in gone for f in m if f[0] == p))
            self._relation_claims = claims_now
        return claims_now.get(concept, frozenset())

    def _forget_derived(self, concept: str | None = None) -> None:
        """The concept memory changed (a store into `concept`; None: near misses, anywhere):
        what comprehension derived from it is made again when next asked (the relation words'
        claims). The one place these caches are reset. The visual words' meanings and their
        exclusivity are the lexicon's, kept up to date from the memory's change log (a store
        is in it; near misses leave the descriptions, so the meanings, as they were)."""
        self._relation_claims = None

    def _note(self, found: list) -> bool:
        """Keep the best evidence for a recognised fact (its typicality goes on the answer)."""
        if found:
            evidence = self.__dict__.setdefault("_evidence", {})
            evidence[found[0].fact] = found[0]
        return bool(found)

    # ------------------------------------------------------------------ referents for learning
    def _candidates(self, g: _Grounding, inferred: Iterable[Term]) -> dict[str, list[str]]:
        """Which objects each reference may mean, by the words already known (unknown words
        do not constrain; a known word that holds of none of them is set aside, since it may
        not fit this instance yet), then by mutual exclusivity: two references of one
        sentence do not mean the same object, so a reference pinned to one object frees it
        from the others. A reference that no known word of it holds for (set aside or none
        known) is a guess: it gives way to a reference pinned to that object by its words,
        even when nothing is left for it. "red box left of blue cylinder" said with only a red
        box on the table: "blue cylinder" means nothing seen (an empty list), not the red box."""
        assert self.state is not None
        holds: dict[str, set[str]] = {}
        for f in inferred:
            if f.name == "isa":
                holds.setdefault(str(f.args[1]), set()).add(str(f.args[0]))
        objs = sorted(self.state.objects, key=id_order)
        cands: dict[str, list[str]] = {}
        guess: set[str] = set()
        for ref in g.parse.objects:
            cs = [g.pins[ref.id]] if ref.id in g.pins else [] if ref.id in g.unresolved else objs
            found = ref.id in g.pins
            for w in ref.words:
                c = self.semantic.concept(w)
                if c is not None and self.semantic.kind(c) == "visual":
                    fit = [o for o in cs if o in holds.get(c, set())]
                    found = found or bool(fit)
                    cs = fit or cs
            cands[ref.id] = list(cs)
            if not found:
                guess.add(ref.id)
        changed = True
        while changed:
            changed = False
            for rid, cs in cands.items():
                if len(cs) == 1:
                    for other, ocs in cands.items():
                        if other != rid and cs[0] in ocs and (len(ocs) > 1 or (other in guess and rid not in guess)):
                            ocs.remove(cs[0])
                            changed = True
        return cands

    def meaning(self, concept: str) -> frozenset[Term]:
        """The percept symbols a visual concept requires (its generalization's significant
        `isa` facts), for mutual exclusivity; the lexicon keeps them, read again only when
        the concept is stored into."""
        return self.lexicon.meaning(concept)

    def _required_percepts(self, concept: str) -> frozenset[Term]:
        """`meaning`, read from the memory now."""
        return self.memory.required_classes(concept)

    def verify(self, content: str, *, demo_start: int | None = None) -> Answer:
        """Does what the content says hold in the scene (or the demonstration just seen)?"""
        assert self.state is not None, "perceive before a lesson"
        read = self._read("verify", content)
        if isinstance(read, Answer):
            return read  # not understood, or a slip asked about
        group = self._composite_answer("verify", content, read)
        if group is not None:
            return group
        if read.mood == "where":
            return self._where("verify", content, read, demo_start)
        g, inferred = self._understand(read, demo_start)
        return self._answer("verify", content, g, inferred, demo_start)

    def comprehend(self, content: str, *, demo_start: int | None = None) -> comprehension.Comprehension:
        """Indexical comprehension of `content` in the current scene (and demonstration)."""
        return self._understand(language.parse(content), demo_start)[0].result

    def _understand(self, p: language.Parse, demo_start: int | None) -> tuple[_Grounding, list[Term]]:
        """Ground the sentence read (`p`: parsed once per lesson, by `_read`) in the scene."""
        assert self.state is not None, "perceive before comprehending"
        self._evidence: dict[Term, object] = {}
        self._direction_seen: dict[Term, tuple[str, int]] = {}
        # "it", "the other one": what the last lesson grounded, found on this table
        pins, unresolved = self._resolve_anaphora(p) if any(o.anaphor for o in p.objects) else ({}, {})
        self._pins = pins
        inferred = self._concept_facts(p, self.state, demo_start)
        words = self._words_for(p)
        named = [fn("ref_is", r, pins.get(r, "nothing")) for r in (*pins, *unresolved)]
        result = comprehension.comprehend(p, words=words, facts=self.state.facts, inferred=inferred + named,
                                          rules=self.rules)
        unknown = [w for w in p.words if w not in words]
        return _Grounding(p, result, unknown, pins, unresolved), inferred

    def _action_facts(self, p: language.Parse, unary: dict[str, list[str]], demo_start: int) -> list[Term]:
        """Which (mover, reference) pairs the demonstration since `demo_start` shows the action
        for. The action concept must match the trace, and, since the sentence also says
        where the mover ends up ("move X right of Y" ends with X right of Y), the relation's
        own concept must hold at the end when it is known: meaning composes."""
        assert self.state is not None and p.action is not None
        c = self._action_concept(p)
        if c is None:
            return []
        rel_c = self.semantic.concept(p.action.relation) if p.action.relation else None
        objs = sorted(self.state.objects, key=id_order)
        out = []
        if self._is_verb_concept(c, p) and p.action.arg2 is not None:
            # one verb for every relation (agent/verbs.py): who moved, and the slot the
            # sentence's relation fills; the match must keep the action's whole outcome
            for a in unary.get(p.action.arg1, objs):
                for b in unary.get(p.action.arg2, objs):
                    if a == b:
                        continue
                    trace = self._verb_trace(demo_start, a, b, rel_c)
                    if not self._as_long_as(c, trace):
                        continue
                    kept = [inf for inf in self.memory.query(trace, fn(c, a, b))
                            if verbs.outcome_kept(self.memory, c, inf)]
                    if self._note(kept):
                        out.append(fn(c, a, b))
            return out
        for args in itertools.product(*(unary.get(r, objs) for r in p.action.args)):
            if len(set(args)) != len(args):
                continue
            trace = self.episodic.trace(demo_start, [Term(o) for o in args])
            if not self._as_long_as(c, trace) or not self.memory.query(trace, fn(c, *args)):
                continue
            if rel_c is not None and not self._holds_binary(rel_c, args[0], args[1], self.state):
                continue
            out.append(fn(c, *args))
        return out

    def _as_long_as(self, concept: str, trace: list[Term]) -> bool:
        """A demonstration shows the whole action and only it: its trace has as many steps as
        some description of the action concept (a pick-up and a place are two steps, a push
        one), so an action that matches part of a longer one is not taken for it."""
        steps = len(time_chain(trace))
        lengths = {len(time_chain(d)) for d in self.memory.descriptions(concept)}
        return not lengths or steps in lengths

    def _answer(self, signal: str, content: str, g: _Grounding, inferred: list[Term],
                demo_start: int | None) -> Answer:
        r = g.result
        referents = {g.parse.object(k).text: [str(o) for o in v] for k, v in r.referents.items()}
        # Two red boxes on the table do not make "red box" false: only acting on one needs
        # it to be unique. "the red box" does (agent/judgement.py), as do numbers, plurals,
        # "not" and "and".
        verdict = judgement.judge(g.parse, r, self._where_is)
        failures = [f for f in verdict.failures if (f.reason != "ambiguous" or signal == "react")
                    and not (f.reason == "no_referent" and str(f.subject) in g.unresolved)]
        said = {str(f.subject) for f in failures if f.reason == "ambiguous"}  # react says it its way
        reasons = [reason_text(f.reason, f.subject, g.parse) for f in failures]
        reasons[:0] = [g.unresolved[o.id] for o in g.parse.objects if o.id in g.unresolved]
        reasons += [pr.text for pr in verdict.problems if not (pr.kind == "cannot_tell" and pr.ref in said)]
        if g.parse.action is not None and not failures and demo_start is not None:
            if not any(f.name == self._action_concept(g.parse) for f in inferred):
                reasons.append(f"the demonstration is not '{g.parse.action.word.replace('_', ' ')}'")
        result = "failure" if reasons else "success"
        self._remember([str(v[0]) for k, v in r.referents.items() if len(v) == 1])
        return Answer(signal, content, result, "; ".join(reasons) or None, referents,
                      typicality=self._typicality(g))

    def _typicality(self, g: _Grounding) -> dict[str, float]:
        """Per recognised fact about the referents: how typical an instance it is (memory/quality.py)."""
        chosen = {o for objs in g.result.referents.values() for o in objs}
        out = {}
        for fact, inf in getattr(self, "_evidence", {}).items():
            if all(a in chosen for a in fact.args if not str(a).startswith("r_") and not str(a).startswith("cv_")):
                out[str(fact)] = quality.typicality(self.memory, inf)
        return dict(sorted(out.items()))

    # ------------------------------------------------------------------ one verb, every relation
    def _action_concept(self, p: language.Parse) -> str | None:
        """The concept an action sentence names: the verb's own (`r_move`, its relation a
        slot) when the agent has one and knows the relation word; else a per-relation concept
        (`r_move_left_of`: the paper's, kept in memories saved before issue 11 and with
        `--without one-verb`), when there is one."""
        if p.action is None:
            return None
        if self.params.one_verb and p.action.relation is not None and p.action.arg2 is not None:
            c = self.semantic.concept(p.action.verb)
            if c is not None and self.semantic.kind(c) == "action" and self.semantic.concept(p.action.relation):
                return c
        return self.semantic.concept(p.action.word)

    def _is_verb_concept(self, concept: str | None, p: language.Parse) -> bool:
        """Is `concept` the verb's own (a slot for the relation), not a per-relation one?"""
        return (concept is not None and p.action is not None and self.params.one_verb
                and p.action.relation is not None and p.action.arg2 is not None
                and concept == self.semantic.concept(p.action.verb))

    def _words_for(self, p: language.Parse) -> dict[str, str]:
        """The semantic memory as comprehension gets it: with one verb for every relation,
        `move_behind` is understood as soon as "move" and "behind" are (composition)."""
        words = self.semantic.words()
        c = self._action_concept(p)
        if c is not None and p.action is not None:
            words[p.action.word] = c
        return words

    def _verb_trace(self, demo_start: int, a: str, b: str, rel_c: str | None) -> list[Term]:
        """The demonstration's trace as a verb's example sees it: who moved, and the slot
        in place of what the sentence's relation accounts for at the end."""
        assert self.state is not None
        ta, tb = Term(a), Term(b)
        trace = self.episodic.trace(demo_start, [ta, tb])
        out = trace + verbs.roles(trace, [ta, tb])
        if rel_c is None:
            return out
        _t, final = verbs.last_facts(trace)
        between = [f for f in final if f.args and set(f.args) <= {ta, tb}]
        explained = self._accounted(rel_c, a, b, between)
        if explained is None:
            return out
        return verbs.slotted(out, explained, ta, tb, contrast=self.params.start_contrast)


def _role_forms(description: list[Term], concept: str) -> frozenset[tuple[str, int, int]]:
    """A relation description's calculus facts between its two roles, as (predicate, role of
    the first argument, role of the second): 0 the concept's first argument, 1 its second."""
    member = next((f for f in description if f.name == concept and len(f.args) == 2), None)
    if member is None:
        return frozenset()
    role = {member.args[0]: 0, member.args[1]: 1}
    return frozenset((f.name, role[f.args[0]], role[f.args[1]]) for f in description
                     if len(f.args) == 2 and f.name != concept and calculi.calculus_of(f.name) is not None
                     and f.args[0] in role and f.args[1] in role)


def reason_text(reason: str, subject: Term, parse: language.Parse) -> str:
    """A failure as a person would say it."""
    s = str(subject)
    if reason == "unknown_word":
        return f"I do not know the word '{s.replace('_', ' ')}'"
    if reason in ("no_referent", "ambiguous"):
        try:
            text = parse.object(s).text
        except KeyError:
            text = s
        return f"I see no '{text}'" if reason == "no_referent" else f"I see more than one '{text}'"
    if reason == "relation_false":
        try:
            rel = parse.relation_ref(s)
        except KeyError:
            rel = parse.relation
        return f"'{rel.word.replace('_', ' ')}' does not hold" if rel is not None else "the relation does not hold"
    return f"{reason}: {s}"
