"""Reading a teacher's sentence before answering it: what cannot be read, slips, "it", "where".

Why one place: every signal (inform, verify, react) first reads the sentence the same way.

* A sentence the grammar cannot read (`language.NotUnderstood`) is answered "not understood"
  with what could not be read and what was expected: never "no", and nothing is learned.
* A word the agent does not know that is one edit from one it does ("bx" for "box"), or a
  relation it knows said with a slip ("lef of" once "left of" is taught), is asked about ("did you mean 'box'?"), not learned
  and not answered: a slip learned as a concept stays for good. A teacher who answers "no,
  as said" (`Agent.take_as_said`: "rox", a word of its own for red boxes) is taken at its
  word: that spelling is read as said from then on, and learned.
* "it", "that one" and "the other one" are found among the objects now seen
  (`agent/discourse.py`), and the objects each lesson grounds are remembered for the next.
* "where is X?" is answered with a relation the agent knows, said in its own words
  (`Generation.location`).
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from typing import Any

from aileen.agent import discourse
from aileen.agent.part import Part
from aileen.agent.records import Answer, not_understood
from aileen.domain import channels, relations
from aileen.domain import words as closed_class
from aileen.reasoning import language
from aileen.reasoning.spelling import degree_of, joined_of, near_spelling, slip_of
from aileen.terms import Term


_WORD = re.compile(r"[a-z0-9_]+")


class Reading(Part):
    """The agent's part that reads the teacher's sentences: the sentence read (`read`), its
    slips, its anaphora, "where"."""

    def __init__(self, agent: Any) -> None:
        super().__init__(agent)
        self._discourse: tuple[discourse.Mention, ...] = ()  # what the last lesson grounded
        self._grounded: tuple[str, ...] = ()  # ... by the ids of the table it was grounded on
        self._said: tuple[str, language.Parse] | None = None  # the last sentence read, and its parse
        # spellings the teacher said are meant as said, not slips (words joined with "_")
        self.as_said: set[str] = set()

    def take_as_said(self, word: str) -> None:
        """The teacher's "no" to "did you mean ...?": `word` ("rox", "nleft of") is meant as said."""
        self.as_said.add("_".join(word.lower().replace("-", " ").split()))  # "blue-cone" is read blue_cone

    def parse(self, content: str) -> "language.Parse":
        """The sentence parsed with the spellings meant as said: those the teacher said are
        (`take_as_said`), a relation spelled like a slip of another that is a word the agent
        knows ("nleft of", learned in an earlier run), and one spelled like a slip of a
        relation the agent was never taught: a slip is of a word it knows (its lexicon, or a
        function word: "pleese"), never of the trainer's declared relations (on an empty memory
        it asked "did you mean 'left of'?" about "nleft of"); `language.NotUnderstood` when it
        cannot be read."""
        heads, named = self._phrase_words(content)
        p = language.parse(content, as_said=self.as_said, heads=heads, named=named)
        if p.slips:
            known = self.semantic.words()
            joined = [("_".join(s.split()), "_".join(m.split())) for s, m in p.slips]
            mine = frozenset(said for said, meant in joined
                             if said in known or not (meant in known or closed_class.is_function_word(meant)))
            if mine:
                p = language.parse(content, as_said=self.as_said | mine, heads=heads, named=named)
        return p

    def _phrase_words(self, content: str) -> tuple[frozenset[str], frozenset[str]]:
        """Of the sentence's words, those the lexicon has heard only ending a noun phrase
        ("box") and those it has heard in one: where a phrase ends when no article says so
        ("red box zorp blue cone"). A plural said is its singular's ("the red and blue boxes":
        "box" is a head, so "red" alone shares it)."""
        positions = self.lexicon.positions
        typed = _WORD.findall(content.lower())
        said = [w for w in (*typed, *(language.singular(w)[0] for w in typed)) if w in positions]
        return frozenset(w for w in said if positions[w] == {"head"}), frozenset(said)

    def last_read(self, content: str) -> "language.Parse | None":
        """The parse of `content` when it is the last sentence read (the trainer's verdict on
        the answer reads the same parse), else None."""
        said = self._said
        return said[1] if said is not None and said[0] == content else None

    def read(self, signal: str, content: str) -> "language.Parse | Answer":
        """The sentence's parse, or the answer when the agent cannot read it or asks about it."""
        try:
            p = self.parse(content)
        except language.NotUnderstood as exc:
            self._said = None
            return not_understood(signal, content, exc.message)
        known = self.semantic.words()
        self._said = (content, p)  # the trainer's verdict on the answer reads the same parse
        for said, meant in p.slips:
            return not_understood(signal, content, f"I do not know '{said}': did you mean '{meant}'?",
                                  question=f"did you mean '{meant}'?", asked_about=said)
        one_thing = self.state is not None and len(self.state.objects) == 1
        for o in p.objects:
            # "klos", "lens" said of the one thing on the table: read as a plural by its ending
            # alone, it was refused ("I learn a word from one object at a time, not from 'klo'")
            if one_thing and o.by_ending and o.words and o.words[-1] not in known and o.by_ending not in known:
                q = f"did you mean more than one '{o.words[-1]}'?"
                return not_understood(signal, content, f"I see one thing: is '{o.by_ending}' a word of its own, "
                                      f"or {q}", question=q, asked_about=o.by_ending)
        for word in self._open_words(p):
            if word in known or word in self.as_said or closed_class.is_function_word(word):
                continue
            compares = self._compares(word, known)
            if compares is not None:
                return not_understood(signal, content, compares)
            near = (near_spelling(word, known) or slip_of(word, closed_class.CLOSED_CLASS, closed_class.SLIPPED)
                    or joined_of(word, [k for k in known if "_" not in k]))
            if near is not None:
                meant, said = near.replace("_", " "), word.replace("_", " ")
                if word.replace("_", "-") in content.lower():  # as typed: "blue-cone"
                    said = word.replace("_", "-")
                return not_understood(signal, content, f"I do not know '{said}': did you mean "
                                      f"'{meant}'?", question=f"did you mean '{meant}'?", asked_about=said)
        return p

    @staticmethod
    def _compares(word: str, known: Iterable[str]) -> str | None:
        """Why a new word that compares is not learned, or None: a comparative or superlative
        by its ending of a word the agent knows, a channel's value or a relation word ("bigger",
        "smallest", "leftmost"), or of a relation declared with "than" ("bigger than"). Said of
        one thing it was learned as a property of it ("the leftmost cone is green" then held
        of the rightmost)."""
        than = {k[: -len(" than")] for k in relations.spellings() if k.endswith(" than")}
        stems = {*known, *(v for c in channels.CHANNELS for v in c.values), *closed_class.RELATION_WORDS}
        degree = degree_of(word, stems)
        if word in than or (degree is not None and degree[1] == "er"):
            return f"'{word}' compares two things: say what it is {word} than (e.g. 'the box is {word} than the cone')"
        if degree is None and not (word.endswith("est") and word[:-3] + "er" in than):
            return None
        pair = f"{degree[0]} of" if degree is not None and degree[1] == "most" else f"{word[:-3]}er than"
        return (f"'{word}' picks one of several by comparing them: say how it stands to another (e.g. 'the box "
                f"is {pair} the cone')")

    @staticmethod
    def _open_words(p: language.Parse) -> list[str]:
        """The words said that need a meaning of their own (the verb and relation of an action,
        not their compound)."""
        out = [w for o in p.objects for w in o.words] + [r.word for r in p.relations]
        if p.action is not None:
            out += [p.action.verb] + ([p.action.relation] if p.action.relation else [])
        return list(dict.fromkeys(out))

    # ------------------------------------------------------------------ "it", "the other one"
    def resolve_anaphora(self, p: language.Parse) -> tuple[dict[str, str], dict[str, str]]:
        """(reference -> the object it is, reference -> why it is none) for the sentence's
        "it", "that one", "the other one"."""
        assert self.state is not None
        pins: dict[str, str] = {}
        why: dict[str, str] = {}
        for ref in p.objects:
            if ref.anaphor is None:
                continue
            found, reason = discourse.resolve(ref.anaphor, self._discourse, self.state, set(pins.values()))
            if found is not None:
                pins[ref.id] = found
            else:
                why[ref.id] = reason or "I do not know what it refers to"
        return pins, why

    def remember(self, objs: list[str]) -> None:
        """The objects this lesson grounded, for "it" in the next (nothing: the last stays)."""
        if objs and self.state is not None:
            self._discourse = discourse.mentions(self.state, objs)
            self._grounded = tuple(dict.fromkeys(objs))

    def acted(self) -> None:
        """After the agent's own acting, the things it talked about stand where it put them:
        "it" is found by where they are now (it was found by where the moved object had
        stood, and "move it behind the cone" after "move a red box right of the cone" moved
        the other red box)."""
        if self._grounded and self.state is not None and all(o in self.state.objects for o in self._grounded):
            self._discourse = discourse.mentions(self.state, list(self._grounded))

    def where_is(self, obj: Term) -> str:
        """Where an object is, as the trainer can check it: its id and table position."""
        assert self.state is not None
        seen = self.state.objects.get(str(obj))
        if seen is None:
            return str(obj)
        x, y = seen.centre
        return f"{obj} at ({x:.2f}, {y:.2f})"

    # ------------------------------------------------------------------ "where is X?"
    def where(self, signal: str, content: str, p: language.Parse, demo_start: int | None = None) -> Answer:
        """Find the one object the question names, then say where it is with the relation the
        agent knows that fits it best (`Generation.location`)."""
        g, inferred = self.agent.grounding.understand(p, demo_start)
        answer = self.agent.grounding.answer(signal, content, g, inferred, demo_start)
        if not answer.ok:
            return answer
        ref = g.parse.objects[0]
        found = g.result.referents.get(ref.id, [])
        if len(found) != 1:
            answer.result, answer.reason = "failure", f"I cannot tell which '{ref.text}' you mean"
            return answer
        assert self.state is not None
        if str(found[0]) not in self.state.objects:  # in the hand (`State.named`): on no table spot
            answer.result, answer.reason = "failure", f"'{ref.text}' is in my hand, not on the table"
            return answer
        said = self.agent.generation.location(str(found[0]), self.state)
        if said is None:
            answer.result, answer.reason = "failure", f"I know no word for where '{ref.text}' is"
        answer.said = said
        return answer
