"""Composite words: a word for a group of objects ("wall", "tower").

The agent has no list of composite words. A word is taken to name the group when it is new,
said alone, and the table shows several objects with nothing to tell which one it would name
(the whole-object assumption, applied to what the trainer laid out). Which objects are the
group is what the agent sees as one (`taught_group`): objects in contact (touching or one on
another: `calculi.CONTACT`) are seen as one thing, the rest as things apart. One group of
objects in contact among others is the group; a table with none is taken whole (the trainer
laid out the group alone); with several groups the agent cannot tell which the word names,
says so and learns nothing. The example is the group's percepts and the relations between its
objects, with the membership fact `r_wall(o1,o2,o3)` (objects in id order). To recognise it,
the concept memory is asked to
find the group in the whole scene (SME maps the parts; the similarity is normalised by the
concept's own facts, so distractors around do not dilute it).
"""

from __future__ import annotations

from aileen.agent.part import Part
from aileen.agent.records import Answer
from aileen.agent.state import State, id_order
from aileen.domain import calculi
from aileen.reasoning import language
from aileen.terms import Term, fn

KIND = "composite"


class Composites(Part):
    """The agent's part for words for groups of objects: recognising them, and learning them
    (through the learning part's `learn`)."""

    def _composite_word(self, p: language.Parse) -> str | None:
        """The single word of a one-word sentence, when it is (or could become) a composite: not
        a plural or a number ("two glorps", "the blicks" name things one at a time, and a new
        word is not learned from them; it was learned as a word for the pair)."""
        if p.relation is not None or p.action is not None or len(p.objects) != 1 or len(p.objects[0].words) != 1:
            return None
        ref = p.objects[0]
        if (ref.plural or (ref.count or 1) > 1) and not self._is_composite(ref.words[0]):
            return None
        if ref.anaphor is not None:
            return None  # "it is a blicket": one thing, the one the last lesson found (a word for the table)
        return p.objects[0].words[0]

    def _is_composite(self, word: str) -> bool:
        c = self.semantic.concept(word)
        return c is not None and self.semantic.kind(c) == KIND

    def _arity(self, concept: str) -> int:
        for f in self.memory.significant_facts(concept):
            if f.name == concept:
                return len(f.args)
        for ex in self.memory.examples(concept):
            for f in ex:
                if f.name == concept:
                    return len(f.args)
        return 0

    def _find_group(self, concept: str, state: State) -> list[str] | None:
        """The objects forming the composite in the scene, best match, or None."""
        n = self._arity(concept)
        if n == 0 or n > len(state.objects):
            return None
        pattern = Term(concept, tuple(Term(f"P{i}") for i in range(n)))
        found = self.memory.query(state.facts, pattern)
        return [str(a) for a in found[0].fact.args] if found else None

    def _group_facts(self, objs: list[str], state: State) -> list[Term]:
        facts: list[Term] = []
        for o in objs:
            facts += state.percepts(o)
        for i, a in enumerate(objs):
            for b in objs[i + 1:]:
                facts += state.relations(a, b)
        return facts

    def group_answer(self, signal: str, content: str, p: language.Parse) -> Answer | None:
        """Comprehend (and for inform, learn) a one-word sentence about a group; None when the
        sentence is not about one."""
        word = self._composite_word(p)
        state = self.state
        if word is None or state is None:
            return None
        known = self.semantic.concept(word)
        if known is not None and not self._is_composite(word):
            return None
        objs = sorted(state.objects, key=id_order)
        if known is None and (signal != "inform" or len(objs) < 2):
            return None  # not (yet) a group word: the ordinary path explains what is wrong
        group = self._find_group(known, state) if known is not None else None
        if group is not None:
            return Answer(signal, content, "success", referents={word: group})
        reason = f"I see no '{word}'" if known is not None else f"I do not know the word '{word}'"
        answer = Answer(signal, content, "failure", reason, unknown_words=[] if known is not None else [word])
        if signal == "inform":
            parts, groups = taught_group(objs, state)
            if parts is None:
                answer.add_reason(f"I cannot tell which objects are the '{word}': I see {groups} groups "
                                  "of objects in contact")
                return answer  # nothing is learned of objects the word may not name
            member = lambda c, parts=tuple(parts): fn(c, *parts)  # noqa: E731
            stored = len(answer.stored)
            self.agent.learning.learn(answer, word, KIND, self._group_facts(parts, state), member)
            if len(answer.stored) > stored:  # said, so that a teacher who meant one of them can tell
                said = (f"in contact ({', '.join(parts)})" if groups else
                        f"on the table together ({', '.join(parts)}); show one alone if it names one")
                answer.add_reason(f"I take '{word}' to name the {len(parts)} objects {said}")
        return answer


def contact_groups(objs: list[str], state: State) -> list[list[str]]:
    """The groups of two or more objects in contact (touching or one over another, through
    any chain of them), each in id order, in the order of their first object."""
    root = {o: o for o in objs}

    def find(o: str) -> str:
        while root[o] != o:
            root[o] = root[root[o]]
            o = root[o]
        return o

    for f in state.facts:
        if f.name in calculi.CONTACT and len(f.args) == 2:
            a, b = (str(x) for x in f.args)
            if a in root and b in root and a != b:
                root[find(a)] = find(b)
    groups: dict[str, list[str]] = {}
    for o in objs:
        groups.setdefault(find(o), []).append(o)
    return [g for g in groups.values() if len(g) > 1]


def taught_group(objs: list[str], state: State) -> tuple[list[str] | None, int]:
    """The objects a word for a group is taught on, and how many groups in contact the table
    shows. What is in contact is seen as one thing (Gestalt connectedness): the one group
    among things apart is the group (a wall among distractors was learned as the whole table,
    and a bare wall was then no wall); a table with no group is taken whole (its objects were
    laid out alone); with several groups the word could name any: None."""
    groups = contact_groups(objs, state)
    if not groups:
        return objs, 0
    return (groups[0] if len(groups) == 1 else None), len(groups)

