"""Generation, the inverse problem the paper names: say what is seen in learned words.

Words are chosen by asking the concept memory which learned concepts fit each object (and
each ordered pair): a word is said when its concept's query succeeds, most typical (highest
similarity) first. A property with no learned word is left out; an object with no word at all
is "something". Of two words in the same place of the noun phrase that say the same percepts
(synonyms) only the more typical is said; words in different places are both said even when
the agent cannot yet tell them apart ("red box", taught once together). Words stand in
noun-phrase order as the agent learned it from the trainer's sentences: modifiers first, in
the order they stood (further from the head first), the head last.
"""

from __future__ import annotations

from dataclasses import dataclass

from aileen.agent.directions import band_predicates
from aileen.agent.part import Part
from aileen.agent.records import Answer
from aileen.agent.state import State, id_order
from aileen.reasoning.language import property_said
from aileen.terms import Term

NOTHING = "something"
# How many concepts the retrieval hands on per object or pair (MAC/FAC, `ConceptMemory.fitting`):
# more than the words one object can have (one per channel, and synonyms).
FIT_WIDTH = 8


#: The positions of a word only ever said as the head of a noun phrase.
HEAD_ONLY = frozenset({"head"})


@dataclass(frozen=True)
class Phrase:
    """The words for one object, in noun-phrase order."""

    obj: str
    words: tuple[str, ...]

    @property
    def text(self) -> str:
        return " ".join(map(property_said, self.words)) or NOTHING  # "red-box", not "red_box"


class Generation(Part):
    """The agent's part that speaks: the `generate` signal (`aileen teach`: `describe`), the
    phrase for one object, where an object is (`Reading.where`)."""

    def generate(self, content: str = "") -> Answer:
        """Describe the table in learned words: one object by its words, two by a relation
        that holds between them, more as a list of phrases."""
        assert self.state is not None, "perceive before a lesson"
        state = self.state
        objs = sorted(state.objects, key=id_order)
        answer = Answer("generate", content, "success")
        if not objs:
            answer.result, answer.reason = "failure", "there is nothing on the table to describe"
            return answer
        phrases = {o: self.phrase(o, state) for o in objs}
        answer.referents = {phrases[o].text: [o] for o in objs}
        if len(objs) == 2:
            rel = self._best_relation(objs[0], objs[1], state)
            if rel is not None:
                word, a, b = rel
                answer.said = f"{phrases[a].text} {word} {phrases[b].text}"
                return answer
        if all(not phrases[o].words for o in objs):
            # nothing said, so nothing for the trainer to grade ("something and something" was
            # graded true of the table, "generate 1/1 said something true")
            answer.result, answer.reason = "failure", "I know no word for what I see"
            return answer
        answer.said = " and ".join(phrases[o].text for o in objs)
        return answer

    def phrase(self, obj: str, state: State) -> Phrase:
        """The words for one object: the visual concepts that fit it, most typical first,
        one per set of percepts, in noun-phrase order, and one head noun (syntax: a noun
        phrase has one head; "red box capsule" says two, whatever each means)."""
        fits: list[tuple[float, str]] = []
        ignore = self.lexicon.claimed_by_others if self.params.mutual_exclusivity else None
        for inf in self.memory.fitting(state.percepts(obj), kind="visual", k=FIT_WIDTH, ignore=ignore):
            word = self.semantic.word(inf.concept)
            if word is not None and inf.fact.args[0] == Term(obj):
                fits.append((inf.similarity, word))
        fits.sort(key=lambda x: (-x[0], x[1]))
        meanings = self.lexicon.effective_meanings()
        said: list[tuple[frozenset[str], frozenset[Term]]] = []  # (positions, meaning) of chosen words
        chosen: list[str] = []
        for _sim, word in fits:
            mine = meanings.get(self.semantic.concept(word) or "", frozenset())
            where = frozenset(self.lexicon.positions.get(word, ()))
            if mine and any(pos == where and mine <= theirs for pos, theirs in said):
                continue  # a word in the same place already says these percepts (a synonym)
            if where == HEAD_ONLY and any(pos == HEAD_ONLY for pos, _ in said):
                continue  # the phrase has its head noun, the most typical of those that fit
            chosen.append(word)
            said.append((where, mine))
        # a hyphenated word of the teacher's own whose parts are said too is said once ("red box
        # red-box")
        chosen = [w for w in chosen if "_" not in w or not all(p in chosen for p in w.split("_"))]
        return Phrase(obj, tuple(self.lexicon.noun_phrase_order(chosen)))

    def location(self, obj: str, state: State) -> str | None:
        """Where `obj` is, in learned words: "the red box is left of the blue cone", by the
        relation that fits it best to the nearest object it has a word for (the concept
        memory's retrieval proposes, the agent's own recognition, as a verify would answer,
        confirms); None when no learned relation word holds of it ("where is X?")."""
        x, y = state.objects[obj].centre
        others = sorted((o for o in state.objects if o != obj),
                        key=lambda o: ((state.objects[o].centre[0] - x) ** 2 + (state.objects[o].centre[1] - y) ** 2,
                                       id_order(o)))
        for other in others:  # the nearest object with a word for where obj stands to it
            facts = state.percepts(obj) + state.percepts(other) + state.relations(obj, other)
            best: tuple[float, str] | None = None
            for inf in self.memory.fitting(facts, kind="spatial", k=FIT_WIDTH, ignore_relations=band_predicates()):
                word = self.semantic.word(inf.concept)
                if word is None or tuple(str(t) for t in inf.fact.args) != (obj, other):
                    continue
                if (best is None or inf.similarity > best[0]) \
                        and self.agent.grounding.holds_binary(inf.concept, obj, other, state):
                    best = (inf.similarity, word.replace("_", " "))
            if best is None:
                # none the retrieval proposed holds, yet a verify of another word would say yes
                # (a direction word whose examples lay at other angles and distances: "where is
                # the red box?" said it knew no word, "red box right of blue cone" yes)
                best = next(((0.0, w.replace("_", " ")) for w, c in sorted(self.semantic.words().items())
                             if self.semantic.kind(c) == "spatial"
                             and self.agent.grounding.holds_binary(c, obj, other, state)), None)
            if best is not None:
                return f"{_the(self.phrase(obj, state))} is {best[1]} {_the(self.phrase(other, state))}"
        return None

    def _best_relation(self, a: str, b: str, state: State) -> tuple[str, str, str] | None:
        """The most typical learned relation between the two objects, either way round."""
        best: tuple[float, str, str, str] | None = None
        facts = state.percepts(a) + state.percepts(b) + state.relations(a, b)
        for inf in self.memory.fitting(facts, kind="spatial", k=FIT_WIDTH, ignore_relations=band_predicates()):
            word = self.semantic.word(inf.concept)
            x, y = (str(t) for t in inf.fact.args)
            if word is not None and {x, y} == {a, b} and (best is None or inf.similarity > best[0]):
                best = (inf.similarity, word.replace("_", " "), x, y)
        return None if best is None else best[1:]


def _the(p: Phrase) -> str:
    """A phrase said of one object seen: "the red box" ("something" when it has no words)."""
    return f"the {p.text}" if p.words else NOTHING
