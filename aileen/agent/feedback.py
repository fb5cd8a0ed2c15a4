"""Learning from use and from near misses: the trainer's feedback after an answer.

Why (the paper's future work; DESIGN.md section 14): the agent learned only from inform
lessons it failed to understand. Two more teachers are at hand:

* **a confirmed react.** When the trainer confirms that the agent's own action reached the goal,
  the executed trace is an example of the action like a demonstration (one store).
* **"wrong".** When the trainer says a verify answer was wrong: a "yes" that should have been
  "no" makes the scene a near miss for the concepts the answer turned on
  (`ConceptMemory.store_near_miss`: the facts the near miss lacks become required, so the next
  scene of the same kind is rejected); a "no" that should have been "yes" is an inform lesson
  on the same scene (the agent learns from what it failed to understand). The answer turned
  on the sentence's relation or action when it has one: its noun phrases only picked out the
  objects ("red box left of blue cylinder" marked wrong says nothing against "red" or "box",
  and a near miss on "box", first taught on a blue box, would make it require blue). A
  sentence that is one noun phrase ("grox") turns on its own words. A "yes" to a denied
  relation ("the red box is not left of the blue cone") marked wrong says the relation holds:
  an example of it, as an inform of "the red box is left of the blue cone".

* **an answer let stand.** In a lesson where the trainer grades the answer (`feedback =
  "wrong"`), a "no" to a relation sentence that the trainer does not correct is the trainer's
  verdict too: the scene is a near miss of the relation word (`told_right`). The ideal
  observer of the teacher protocol reads the trainer's verdict either way; so may the agent.
  A "yes" let stand is not stored (an example inside the region the word already holds
  would only narrow it by the size principle).

The agent remembers its last verify or react answer for this, with the scene it answered
about; a verdict on any other scene is refused.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

from aileen.agent.part import Part
from aileen.agent.records import NOT_UNDERSTOOD, NOTHING_DONE, Answer
from aileen.reasoning import language
from aileen.terms import Term, fn

@dataclass(frozen=True)
class _Asked:
    signal: str
    content: str
    demo_start: int | None  # verify: where the demonstration began; react: the agent's first look
    result: str
    parse: "language.Parse | None"  # the sentence as read for the answer (None: not read)
    state: object  # the agent's State when it answered: a verdict is about that scene only


class Feedback(Part):
    """The agent's part that hears the trainer's verdicts: it keeps the last verify and react
    answered (`answered`), and learns from the verdict on them."""

    def __init__(self, agent: Any) -> None:
        super().__init__(agent)
        self._asked: _Asked | None = None

    def _last(self, signal: str, verdict: str | None = None) -> _Asked:
        """The answer a verdict (`verdict`: its word) is about, taken: one verdict per answer
        (a second `wrong` on the same answer learned the same near miss again, each time)."""
        asked = self._asked
        if asked is None or asked.signal != signal or asked.state is not self.state:
            what = "a verify answer" if signal == "verify" else "a react"
            said = verdict or ("wrong" if signal == "verify" else "confirm")
            raise ValueError(f"'{said}' needs {what} on the scene now seen, and one verdict per answer")
        self._asked = None
        return asked

    def answered(self, signal: str, content: str, demo_start: int | None, answer: Answer) -> None:
        """The agent answered a verify (`demo_start`: where the demonstration began) or a react
        (`demo_start`: its first look): a verdict may come on it, on this scene only."""
        self._asked = _Asked(signal, content, demo_start, answer.result, self._parse_of(content), self.state)

    def _parse_of(self, content: str) -> "language.Parse | None":
        """The parse the answer to `content` was made from (`Reading.read`), not made again."""
        return self.agent.reading.last_read(content)

    def _parsed(self, asked: _Asked) -> "language.Parse":
        """The sentence of the answer a verdict is about, as it was read (parsed now only when
        it could not be read then: `language.NotUnderstood` says why, as it did then)."""
        return asked.parse if asked.parse is not None else self.agent.reading.parse(asked.content)

    def _inform_again(self, asked: _Asked) -> Answer:
        """The verified sentence as an inform lesson (its parse as it was read; `inform`
        when the answer's parse is not at hand). A yes/no question the trainer says was
        answered wrong is said as its statement ("is the red box behind the blue cone?" with
        `wrong`: it is), which a question never teaches ("noted; nothing to learn")."""
        parse = asked.parse if asked.parse is not None else self.agent.reading.parse(asked.content)
        if parse.mood == "question":
            parse = dataclasses.replace(parse, mood="statement")
        return self.agent.learning.inform_read(asked.content, parse, asked.demo_start)

    # ------------------------------------------------------------------ the trainer's verdicts
    def told_wrong(self, answer: Answer) -> None:
        """The trainer says the last verify answer was wrong; learn from it (stores go on
        `answer`)."""
        asked = self._last("verify")
        if asked.result == NOT_UNDERSTOOD:
            return  # nothing was answered, so nothing was wrong: nothing to learn
        if asked.parse is not None and asked.parse.mood == "where":
            # the answer said where in words of its own choosing, and which of them was wrong
            # the verdict does not say (it stored near misses of "red" and "box")
            thing = asked.parse.objects[0].said if asked.parse.objects else "it"
            answer.reason = f"a 'where' answer is said in my words: say where it is instead ('{thing} is <where> <what>')"
            return
        if asked.result == "failure":  # it holds after all: learn as from an inform lesson
            taught = self._inform_again(asked)
            answer.created += taught.created
            answer.stored += taught.stored
            if not (taught.created or taught.stored):
                # why nothing was learned ("I see no 'red glorp'" of a green box): it said
                # "noted; nothing to learn from it" and no more
                answer.reason = taught.reason
            return
        denied = self._denied(asked)
        if denied is not None:  # "X is not REL Y" said yes, and wrong: REL holds here after all
            taught = self.agent.learning.inform_read(asked.content, denied, asked.demo_start)
            answer.created += taught.created
            answer.stored += taught.stored
            return
        near_misses, untold = self._near_misses(asked)
        for facts, concept in near_misses:
            self.memory.store_near_miss(facts, concept)
            answer.stored.append(concept)
        self.agent.grounding.forget_derived()
        if untold:
            answer.reason = untold
        if answer.stored and self._still_yes(asked):
            # a near miss where examples lie does not outweigh them: say so, not only "stored"
            answer.reason = ("the answer would still be yes here: the examples taught outweigh one near "
                             "miss; more `wrong`s here, or examples elsewhere, may move it")

    def _denied(self, asked: _Asked) -> "language.Parse | None":
        """The statement a "yes" marked wrong says holds, when the sentence denied one
        relation and said nothing else of it ("the red box is not left of the blue cone": the
        trainer says it is, an example of "left of", as an inform of it teaches); None for
        anything else. Before, the negated relation held for no pair, so `wrong` was "noted;
        nothing to learn from it" and the word kept refusing the scene the trainer names by it."""
        parse = self._parsed(asked)
        if parse.action is not None or len(parse.relations) != 1 or not parse.relations[0].negated:
            return None
        rel = dataclasses.replace(parse.relations[0], negated=False)
        return dataclasses.replace(parse, relation=rel, relations=(rel,), mood="statement")

    def _still_yes(self, asked: _Asked) -> bool:
        """Would the verify just told `wrong` be answered yes again, on its own scene?"""
        g, inferred = self.agent.grounding.understand(self._parsed(asked), asked.demo_start)
        again = self.agent.grounding.answer("verify", asked.content, g, inferred, asked.demo_start)
        self.agent.grounding.forget_derived()
        return again.ok

    def told_right(self, answer: Answer) -> None:
        """The trainer, grading the last verify, lets its answer stand. A "no" to a relation
        sentence whose two noun phrases each picked out one object here, refused by the
        relation word alone, makes the scene a near miss of that word (a store on `answer`).
        Anything else teaches nothing: the agent already answered as it knew."""
        asked = self._last("verify", "right")
        if asked.result != "failure" or not self.params.answers_let_stand:
            return
        g, _inferred = self.agent.grounding.understand(self._parsed(asked), asked.demo_start)
        rel = g.parse.relation
        if rel is None or rel.negated or g.parse.action is not None or len(g.parse.relations) > 1:
            return
        c = self.semantic.concept(rel.word)
        refs = g.result.referents
        if c is None or len(refs.get(rel.arg1, [])) != 1 or len(refs.get(rel.arg2, [])) != 1:
            return
        a, b = refs[rel.arg1][0], refs[rel.arg2][0]
        if a == b:
            return
        self.memory.store_near_miss(self._pair_near_miss(c, a, b), c)
        answer.stored.append(c)
        self.agent.grounding.forget_derived()

    def _pair_near_miss(self, concept: str, a: Term, b: Term) -> list[Term]:
        """A relation word's near miss between a and b: both objects' percepts, their
        relations and the word's membership fact, so the near miss says who played which
        role (memory/extent.py reads its direction between the roles)."""
        state = self.state
        return state.percepts(str(a)) + state.percepts(str(b)) + state.relations(str(a), str(b)) + [fn(concept, a, b)]

    def _near_misses(self, asked: _Asked) -> tuple[list[tuple[list[Term], str]], str | None]:
        """(scene facts, concept) for each concept the answer turned on that the agent found
        here: each relation word of a sentence that has them (on the pairs that word held
        for) or its action, else the words of its noun phrases (`_phrase_near_misses`); and,
        when the verdict cannot say which phrase was wrong, why nothing was blamed."""
        g, inferred = self.agent.grounding.understand(self._parsed(asked), asked.demo_start)
        out: list[tuple[list[Term], str]] = []
        untold = None
        if g.parse.relation is None and g.parse.action is None:
            out, untold = self._phrase_near_misses(g, set(inferred))
        for rel in g.parse.relations:
            # each relation word on the pairs it held for: "X is left of A and right of B"
            # marked wrong stored two near misses of "left of", one on the pair "right of"
            # held for, and none of "right of"; a negated one held for none
            c = self.semantic.concept(rel.word)
            if c is None or rel.negated:
                continue
            out.extend((self._pair_near_miss(c, a, b), c) for a, b in g.result.holds_for.get(rel.id, []))
        if g.parse.action is not None and asked.demo_start is not None:
            c = self.agent.demonstrations.action_concept(g.parse)
            rel_c = self.semantic.concept(g.parse.action.relation)
            verb = self.agent.demonstrations.is_verb_concept(c, g.parse)
            for f in inferred:
                if c is not None and f.name == c and len(f.args) == 2:
                    a, b = str(f.args[0]), str(f.args[1])
                    trace = (self.agent.demonstrations.verb_trace(asked.demo_start, a, b, rel_c) if verb
                             else self.episodic.trace(asked.demo_start, [Term(a), Term(b)]))
                    out.append((trace, c))
        return out, untold

    def _phrase_near_misses(self, g: Any, have: set[Term]) -> tuple[list[tuple[list[Term], str]], str | None]:
        """The near misses of a sentence of noun phrases only. The answer turned on the words
        that hold here by a value none of their examples showed ("medium" of a small red
        sphere); the others hold as taught (a `wrong` after "medium red sphere" made "red" and
        "sphere" forget it). One phrase with no such word: all its words, as before. Of
        several phrases, the words that were new here, else those found on the weakest
        evidence (`Grounding.weakly_recognised`), else none: "the red box and the blue cone",
        each as taught, marked wrong stored near misses of all four words, and "red", first
        taught on this very red box, then required what it lacks elsewhere; which of the two
        the trainer denies the verdict does not say (the reason says so)."""
        state = self.state
        found: list[tuple[Term, list[str]]] = []  # (object, the words of its phrase that held of it)
        for ref in g.parse.objects:
            for obj in g.result.referents.get(ref.id, []):
                held = [c for c in map(self.semantic.concept, ref.words) if c is not None and fn("isa", obj, c) in have]
                found.append((obj, held))
        novel = [(obj, [c for c in held if self._novel_here(c, str(obj))]) for obj, held in found]
        if len(g.parse.objects) <= 1:
            blamed = [(obj, new or held) for (obj, held), (_o, new) in zip(found, novel)]
            return [(state.percepts(str(obj)), c) for obj, cs in blamed for c in cs], None
        if not any(new for _o, new in novel):
            weak = self.agent.grounding.weakly_recognised()
            novel = [(obj, [c for c in held if fn("isa", obj, c) in weak]) for obj, held in found]
        out = [(state.percepts(str(obj)), c) for obj, cs in novel for c in cs]
        if out:
            return out, None
        said = ", ".join(f"'{ref.said}'" for ref in g.parse.objects)
        return [], (f"each of {said} is here as I was taught it, and the verdict does not say which is not: "
                    "verify one of them alone and say `wrong` to that")

    def _novel_here(self, concept: str, obj: str) -> bool:
        """Does `obj` show, on a channel of the concept's meaning, a value none of the
        concept's examples showed?"""
        lexicon = self.agent.lexicon
        meaning = lexicon.effective_meanings().get(concept, frozenset()) or lexicon.meaning(concept)
        channels = {lexicon.channels.get(p) for p in meaning} - {None}
        _n, shown = self.memory.class_counts(concept)
        seen = [f.args[1] for f in self.state.percepts(obj)]
        return any(lexicon.channels.get(p) in channels and not shown[p] for p in seen)

    def confirmed(self, answer: Answer) -> None:
        """The trainer confirms the last react reached its goal: its trace is an example of
        the action (one store, on `answer`)."""
        asked = self._last("react")
        assert asked.demo_start is not None
        g, inferred = self.agent.grounding.understand(self._parsed(asked), None)
        act = g.parse.action
        refs = g.result.referents
        if act is None or len(refs.get(act.arg1, [])) != 1 or len(refs.get(act.arg2, [])) != 1:
            return
        a, b = str(refs[act.arg1][0]), str(refs[act.arg2][0])
        if not self.agent.learning.moved_since(asked.demo_start, a):
            # the goal held already and nothing was done: an empty trace merged into the verb
            # took `moved` and `held` out of it, and every later move projected no next state
            answer.add_reason(f"{NOTHING_DONE}: nothing to learn of '{act.verb}'")
            return
        known = {w for w in g.parse.words if self.semantic.concept(w) is not None}
        if self.params.one_verb:
            facts = self.agent.demonstrations.verb_trace(asked.demo_start, a, b, self.semantic.concept(act.relation))
            word = act.verb
        else:
            facts, word = self.episodic.trace(asked.demo_start, [Term(a), Term(b)]), act.word
        facts += self.agent.learning.objects_facts([(a, act.arg1), (b, act.arg2)], g, known, set(inferred))
        self.agent.learning.learn(answer, word, "action", facts, lambda c: fn(c, a, b))
