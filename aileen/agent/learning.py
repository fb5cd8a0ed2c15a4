"""Learning: on a failed `inform`, create concepts for unknown words and store examples.

Active learning (the paper): the agent learns only from what it failed to comprehend. An
example for a visual word is the referent's percepts; for a relation both objects' percepts
and the relations between them; for an action the demonstration trace. Mutual exclusivity
leaves out of an example what the phrase's already known words account for.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from aileen.agent import directions, disjunction, judgement
from aileen.agent.grounding import _Grounding, role_forms
from aileen.agent.part import Part
from aileen.agent.records import Answer
from aileen.agent.state import id_order
from aileen.domain import calculi
from aileen.domain import words as closed_class
from aileen.memory.semantic import concept_symbol, part_of
from aileen.reasoning import language
from aileen.reasoning.spelling import near_spelling
from aileen.terms import Term, fn


class Learning(Part):
    """The agent's part that learns from what it failed to comprehend: the `inform` signal,
    and the examples it stores (`learn`, also for composite words and the trainer's verdicts)."""

    def _explained(self, obj: str, words: Iterable[str], inferred: set[Term]) -> set[Term]:
        """Percept facts of `obj` that the (already known, holding) `words` account for."""
        out: set[Term] = set()
        for w in words:
            c = self.semantic.concept(w)
            if c is None or fn("isa", obj, c) not in inferred:
                continue
            out |= {fn("isa", obj, p) for p in self.lexicon.meaning(c)}
        return out

    # ------------------------------------------------------------------ signals
    def inform(self, content: str, *, demo_start: int | None = None) -> Answer:
        """Comprehend; learn only from what failed. `demo_start` is the episode index where
        a demonstration began (for action lessons: the trace runs from there to now)."""
        assert self.state is not None, "perceive before a lesson"
        read = self.agent.reading.read("inform", content)
        if isinstance(read, Answer):
            return read  # not understood, or a slip asked about: nothing is learned
        return self.inform_read(content, read, demo_start)

    def inform_read(self, content: str, read: language.Parse, demo_start: int | None) -> Answer:
        """`inform` of a sentence read (`Reading.read`: its parse, made once for the lesson)."""
        assert self.state is not None
        grounding = self.agent.grounding
        group = self.agent.composites.group_answer("inform", content, read)
        if group is not None:
            return group
        if read.mood == "where":
            return self.agent.reading.where("inform", content, read, demo_start)
        # its table's objects are taught on: what they share with every earlier one is no
        # contrast yet (`Lexicon.not_asked`), what they do not is
        with self.lexicon.teaching([Term(p) for p in o.percepts] for o in self.state.objects.values()):
            g, inferred = grounding.understand(read, demo_start)
            answer = grounding.answer("inform", content, g, inferred, demo_start)
        if read.asks:
            return answer  # a question is answered, never taught
        if any(o.anaphor is None and o.definite and not o.plural and o.count in (None, 1)
               and len(g.result.candidates.get(o.id, ())) > 1 for o in read.objects):
            return answer  # "the" with several: it said which it cannot tell apart; nothing is stored
        self.agent.note_positions(g.parse)  # part of the lesson: where the trainer put each word
        self.agent.note_seen()  # ... and what the objects it was taught on are like
        weak = grounding.weakly_recognised() if answer.ok else set()
        negated = [r for r in read.relations if r.negated]
        if negated:
            self._told_not(answer, g)
            return answer
        if answer.ok and not weak and self.params.mutual_exclusivity:
            # Counting this table's objects (`note_seen`) can change what a question leaves out
            # (`Lexicon.not_asked`): "medium blue box" said yes before the inform and after
            # it, with nothing stored, "I see no 'medium blue box'" on the same table. What
            # a question would no longer find here is news, and learned from.
            again, inferred_again = grounding.understand(read, demo_start)
            news = not grounding.answer("verify", content, again, inferred_again, demo_start).ok
            if not news:
                return answer
            g, inferred = again, inferred_again
        elif answer.ok and not weak:
            return answer
        state = self.state
        # Facts recognised only weakly (similarity near the match threshold) are learned from
        # as if they had not been recognised: active learning that is honest (DESIGN.md 12).
        inferred_set = set(inferred) - weak
        known_before = {w for w in g.parse.words if self.semantic.concept(w) is not None}
        cands = self.agent.referents.candidates(g, inferred)
        referent: dict[str, str] = {}
        shared = self._one_for_several(g.parse, cands)
        for ref in g.parse.objects:
            cs = cands[ref.id]
            if ref.id in shared:
                answer.add_reason(shared[ref.id])
                continue
            if ref.plural or (ref.count or 1) > 1:
                if self._by_elimination(ref, answer):
                    continue
                if any(self.semantic.concept(w) is None for w in ref.words):
                    answer.add_reason(f"I learn a word from one object at a time, not from '{ref.said}'")
                continue
            if len(cs) != 1:
                # Nothing is learned about a reference that is not grounded in one object:
                # what could not be found is said, and no other object is taught for it.
                # ("another box" by the one box talked about said "I see no 'box'" of the box it saw)
                but = " but the one we talked about" if ref.anaphor == "other" and ref.words else ""
                why = f"I see no '{ref.text}'{but}" if not cs else f"cannot tell which object is '{ref.text}'"
                answer.add_reason(why)
                continue
            obj = referent[ref.id] = cs[0]
            for w in ref.words:
                if self._refused(w, answer):
                    continue
                c = self.semantic.concept(w)
                if c is not None and fn("isa", obj, c) in inferred_set:
                    continue  # known and it holds: nothing to learn
                others = [x for x in ref.words if x != w and x in known_before]
                drop = self._explained(obj, others, inferred_set) if self.params.mutual_exclusivity else set()
                percepts = [f for f in state.percepts(obj) if f not in drop] or state.percepts(obj)
                self.learn(answer, w, "visual", percepts, lambda c, o=obj: fn("isa", o, c))
        if answer.reason and self.params.mutual_exclusivity:
            # found after all, as a question finds it (which leaves out what exclusivity does):
            # what it shows is news, not absent (the paper's learner says as the Soar agent does)
            news = {f"I see no '{ref.text}'": f"I had not seen a '{ref.text}' like this one"
                    for ref in g.parse.objects if ref.id in referent}
            answer.reason = "; ".join(news.get(part, part) for part in answer.reason.split("; "))
        act = g.parse.action
        for rel in g.parse.relations:
            if rel.arg1 not in referent or rel.arg2 not in referent or referent[rel.arg1] == referent[rel.arg2]:
                continue  # never a relation of an object to itself
            a, b = referent[rel.arg1], referent[rel.arg2]
            c = self.semantic.concept(rel.word)
            if (c is None or fn(c, a, b) not in inferred_set) and not self._refused(rel.word, answer):
                facts = self.objects_facts([(a, rel.arg1), (b, rel.arg2)], g, known_before, inferred_set)
                facts += self._unexplained_relations(a, b, rel.word)
                self.learn(answer, rel.word, "spatial", facts, lambda c, a=a, b=b: fn(c, a, b))
        self.agent.reading.remember([referent[o.id] for o in g.parse.objects if o.id in referent])
        if act is not None and any(self._refused(w, answer) for w in (act.verb, act.relation) if w):
            return answer
        relational = act is not None and act.relation is not None and act.arg2 is not None
        if relational and act.arg1 in referent and demo_start is not None \
                and not self.moved_since(demo_start, referent[act.arg1]):
            # "move the red box right of the blue cone" shown by pointing at it: the box stood
            # where it was, and "right of" and "move" were learned from that unmoved scene
            answer.add_reason(f"the demonstration did not move {g.parse.object(act.arg1).said}: nothing to learn "
                         f"of '{act.verb}'")
            return answer
        if relational and self.params.one_verb and act.arg1 in referent and act.arg2 in referent \
                and demo_start is not None:
            # one verb for every relation (agent/verbs.py): the verb's concept, the relation a slot
            a, b = referent[act.arg1], referent[act.arg2]
            c = self.agent.demonstrations.action_concept(g.parse)
            if c is None or fn(c, a, b) not in inferred_set:
                rel_c = self.semantic.concept(act.relation)
                if rel_c is None or not grounding.holds_binary(rel_c, a, b, state):
                    # The sentence says where the mover ends up: an example of the relation
                    # (a new word, or a known one seen where it was not taught yet).
                    facts = self.objects_facts([(a, act.arg1), (b, act.arg2)], g, known_before, inferred_set)
                    facts += self._unexplained_relations(a, b, act.relation)
                    self.learn(answer, act.relation, "spatial", facts, lambda c, a=a, b=b: fn(c, a, b))
                    rel_c = self.semantic.concept(act.relation)
                facts = self.agent.demonstrations.verb_trace(demo_start, a, b, rel_c)
                facts += self.objects_facts([(a, act.arg1), (b, act.arg2)], g, known_before, inferred_set)
                self.learn(answer, act.verb, "action", facts, lambda c, a=a, b=b: fn(c, a, b))
        elif act is not None and all(r in referent for r in act.args) and demo_start is not None:
            args = tuple(referent[r] for r in act.args)
            c = self.semantic.concept(act.word)
            if c is None or fn(c, *args) not in inferred_set:
                facts = self.episodic.trace(demo_start, [Term(o) for o in args])
                facts += self.objects_facts(list(zip(args, act.args)), g, known_before, inferred_set)
                self.learn(answer, act.word, "action", facts, lambda c, args=args: fn(c, *args))
        return answer

    @staticmethod
    def _one_for_several(parse: language.Parse, cands: dict[str, list[str]]) -> dict[str, str]:
        """The phrases of a sentence (not "it", not a plural) whose one candidate is another
        phrase's one candidate too, each with why nothing is learned of it: two phrases name
        two things, so where the agent sees one thing for both it sees only one of them, and
        cannot tell which ("large red box on small blue box" with the small box hidden under
        the large one: "blue" and "small" were learned from the red box, and "box" counted
        twice for one object made a memory file that would not load)."""
        single = [o for o in parse.objects if o.anaphor is None and not o.plural and (o.count or 1) == 1
                  and len(cands.get(o.id, ())) == 1]
        out: dict[str, str] = {}
        for o in single:
            alike = [x for x in single if cands[x.id] == cands[o.id]]
            if len(alike) > 1:
                said = " and ".join(f"'{x.text}'" for x in alike)
                out[o.id] = f"I see one object where the sentence names two ({said}): I cannot tell which it is"
        return out

    def moved_since(self, start: int, obj: str) -> bool:
        """Was `obj` seen moved (or held) in an episode since `start`? (An action that did not
        move its object shows nothing of the verb: a demonstration by pointing, a react that
        found its goal holding already.)"""
        marks = {fn(calculi.MOVED, obj), fn("held", obj)}
        return any(f in marks for i in range(start, self.episodic.now + 1) for f in self.episodic[i].facts)

    def _by_elimination(self, ref: language.ObjectRef, answer: Answer) -> bool:
        """"the boxes are red and glorp", "red" known and "glorp" new, over a red box and a blue
        one: what is said is shared out among the boxes (`judgement.shared_out`), so "glorp" is
        the one box no known word said of them names, and is learned from it alone (learning by
        exclusion, as a child takes a new word for the one thing it has no word for). Nothing
        is learned unless exactly one new word is said, the known ones are alternatives on one
        channel (`Grounding.shared_fits`: "red and large and glorp" is said of each box), the
        subject's words are known, every known word holds of one of the things named, and
        exactly one is left."""
        assert self.state is not None
        if not judgement.shared_out(ref) or not ref.subject:
            return False
        new = [w for w in ref.said_of if self.semantic.concept(w) is None]
        subject = [self.semantic.concept(w) for w in ref.subject]
        if len(new) != 1 or any(c is None or self.semantic.kind(c) != "visual" for c in subject):
            return False
        grounding = self.agent.grounding
        named = [o for o in sorted(self.state.objects, key=id_order)
                 if all(grounding.holds_as_asked(c, o) for c in subject)]
        fits = grounding.shared_fits([w for w in ref.said_of if w not in new], named)
        if fits is None:
            return False
        left = [o for o in named if not any(o in f for f in fits.values())]
        if len(named) < 2 or len(left) != 1 or not all(fits.values()) or self._refused(new[0], answer):
            return False
        obj = left[0]
        drop = {fn("isa", obj, p) for c in subject for p in self.lexicon.meaning(c)}  # all of them are boxes
        percepts = [f for f in self.state.percepts(obj) if f not in drop] or self.state.percepts(obj)
        self.learn(answer, new[0], "visual", percepts, lambda c: fn("isa", obj, c))
        others = " or ".join(f"'{w}'" for w in ref.said_of if w != new[0])
        answer.add_reason(f"I take '{new[0]}' to name {self.agent.reading.where_is(Term(obj))}: the "
                          f"{' '.join(ref.subject)} that {others} does not name")
        return True

    def _told_not(self, answer: Answer, g: _Grounding) -> None:
        """"X is not REL Y": where the agent found REL between them, the scene is a near miss
        of REL (as a verify the trainer marks wrong, `agent/feedback.py`); where it did not,
        it agrees and learns nothing. A relation word it does not know is not learned from
        where it does not hold."""
        assert self.state is not None
        for rel in g.parse.relations:
            if not rel.negated:
                continue
            c = self.semantic.concept(rel.word)
            if c is None:
                answer.add_reason(f"I learn '{rel.word.replace('_', ' ')}' from where it holds, not from where it does not")
                continue
            for a, b in g.result.holds_for.get(rel.id, []):
                x, y = str(a), str(b)
                facts = self.state.percepts(x) + self.state.percepts(y) + self.state.relations(x, y) + [fn(c, a, b)]
                self.memory.store_near_miss(facts, c)
                answer.stored.append(c)
        if answer.stored:
            self.agent.grounding.forget_derived()

    def _refused(self, word: str, answer: Answer) -> bool:
        """A new word the agent will not learn, saying why on `answer`: a function word of
        the closed class ("and", "is", "please": grammar, not a property of the table), or a
        slip of a known word (one edit from it: "bux" for "box"), since a word learned is
        learned for good and a typo learned as a concept would take examples from the word
        meant. Known words are never refused."""
        if self.semantic.concept(word) is not None:
            return False
        if closed_class.is_function_word(word):
            why = f"I do not learn '{word}': it is a function word"
        elif word in self.agent.reading.as_said:
            return False  # the teacher said it is meant as said
        else:
            near = near_spelling(word, self.semantic.words())
            if near is None:
                return False
            why = f"did you mean '{near.replace('_', ' ')}'?"
        if why not in (answer.reason or "").split("; "):
            answer.reason = f"{answer.reason}; {why}" if answer.reason else why
        return True

    def _unexplained_relations(self, a: str, b: str, word: str) -> list[Term]:
        """The relations between a and b, less (mutual exclusivity) those that another known
        spatial word holding of the pair accounts for: "red box near blue cone" said of a box
        that is also left of the cone is not about "left of"'s direction, so a first example
        of "near" does not tie it to one side. All of them when no other word holds, or
        without mutual exclusivity. A word the new one is made of is no other word: "behind
        right of" said where "behind" and "right of" both hold is about what they say, not only
        about what is left (shown close by, it was learned as "close": `semantic.part_of`)."""
        assert self.state is not None
        rels = self.state.relations(a, b)
        if not self.params.mutual_exclusivity:
            return rels
        own = self.semantic.concept(word)
        whole = own or concept_symbol(word)
        drop: set[Term] = set()
        for c in self.memory.concepts():
            if c.kind != "spatial" or c.symbol == own or part_of(c.symbol, whole):
                continue
            # (with extents, a known word whose meaning has a direction accounts for which
            # side the pair is on, at every grain: `Grounding.accounted`)
            explained = self.agent.grounding.accounted(c.symbol, a, b, rels)
            if explained:
                drop.update(explained)
        if drop and own is not None and (shown := self._shown_by_every_example(own)):
            # What every example of the word has shown is not taken from it because another
            # word also says it; and where without what the others say this example would
            # share nothing telling with the earlier ones, it keeps it all: "tinier than",
            # said of pairs on three sides of one another and each time smaller, kept only
            # their sides once "smaller than" was known (`sz_smaller`, what all three had in
            # common, was the other word's), and held of a large box and a small cone. The
            # first example still gives up what the others say ("near" shown left of the
            # cone is not about its side), and so do later ones that agree with the first.
            role = {a: 0, b: 1}

            def form(f: Term) -> tuple[str, int | None, int | None]:
                return (f.name, role.get(str(f.args[0])), role.get(str(f.args[1])))

            agreed = {x for x in shown if _telling_name(x[0])}
            if not any(form(f) in agreed for f in rels if f not in drop):
                drop = set()
            else:
                drop = {f for f in drop if form(f) not in shown}
        kept = [f for f in rels if f not in drop]
        if self.params.extents and not any(_telling(f) for f in kept):
            # Nothing but what every pair has would be left: the word is about what the other
            # words also say ("behind left of" where "left of" holds), so it keeps it all.
            return rels
        if self.params.extents:
            # Which side and how far are read as regions from every example (`Directions`),
            # whose mutual exclusivity weighs how far chance explains the examples' sides:
            # they are kept. Dropped here, a word shown close by and always on the left ("just
            # left of") once "left of" was known never saw a side, and held on every side.
            regions = directions.region_predicates()
            kept = [f for f in rels if f not in drop or f.name in regions]
        return kept or rels

    def _shown_by_every_example(self, concept: str) -> frozenset[tuple[str, int, int]]:
        """The relations between its two roles (`role_forms`) that every description of a
        relation concept holds: what its examples so far agree on."""
        descriptions = self.memory.descriptions(concept)
        if not descriptions:
            return frozenset()
        return frozenset.intersection(*(role_forms(d, concept) for d in descriptions))

    def objects_facts(self, objs: list[tuple[str, str]], g: _Grounding, known: set[str],
                       inferred: set[Term]) -> list[Term]:
        """Percepts of the objects a relation or action is about, leaving out (mutual
        exclusivity) what the known words naming those objects already account for."""
        assert self.state is not None
        out: list[Term] = []
        for obj, ref_id in objs:
            words = [w for w in g.parse.object(ref_id).words if w in known]
            drop = self._explained(obj, words, inferred) if self.params.mutual_exclusivity else set()
            out += [f for f in self.state.percepts(obj) if f not in drop]
        return out

    def learn(self, answer: Answer, word: str, kind: str, facts: list[Term],
               member: Callable[[str], Term]) -> None:
        """`create` the word's concept if it is new, then `store` the example: `facts` plus
        the membership fact `member(concept)` (`isa(o1,r_red)`, `r_left_of(o1,o2)`)."""
        concept = self.semantic.concept(word) or self.semantic.add(word, kind)
        if not self.memory.has(concept):
            self.memory.create(concept, kind)
            answer.created.append(concept)
        accept = None
        if kind == "spatial" and self.params.disjunctive_concepts:  # agent/disjunction.py
            p = self.memory.params.probability
            accept = lambda merged: disjunction.keeps_a_meaning(merged, p, facts)  # noqa: E731
        elif kind == "visual" and self.params.disjunctive_concepts:
            p = self.memory.params.probability
            flat = self.agent.lexicon.seen.common()  # none before `seen.MIN_OBJECTS` objects
            accept = lambda merged: disjunction.keeps_a_percept(merged, p, flat, facts)  # noqa: E731
        if kind == "visual":
            self.agent.lexicon.note_taught(word)  # (its meaning is read again after the store)
        self.memory.store(facts + [member(concept)], concept, accept=accept)
        # Only this concept's meaning changed; the exclusivity pass is redone from the others'.
        self.agent.grounding.forget_derived(concept)
        answer.stored.append(concept)


def _telling(fact: Term) -> bool:
    """Does a relation fact tell pairs apart: a direction, or a marked value (not `dc`, nor a
    distance band: every pair apart has one, `calculi.FINER`)?"""
    return _telling_name(fact.name)


def _telling_name(name: str) -> bool:
    c = calculi.calculus_of(name)
    return c is not None and c not in calculi.FINER and (c.is_direction or name not in c.common)
