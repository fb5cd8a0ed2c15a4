"""Which objects a sentence's references may mean, for learning from an `inform`.

Why a part of its own: grounding answers whether what a sentence says holds; learning needs
more, which object each reference is *taught* on when a known word does not hold of it (it
may not fit this instance yet, `candidates`) and when what the agent knows rules an object
out (`ruled_out`: "purple box" said over a red sphere, with "red" and "sphere" known, names no
object on the table, and teaches nothing).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

from aileen.agent.part import Part
from aileen.agent.state import id_order
from aileen.terms import Term

if TYPE_CHECKING:
    from aileen.agent.grounding import _Grounding

#: Examples a visual word never said in a phrase needs before what it means can rule an object
#: out of an inform (`Referents.ruled_out`): what one example means depends on what other
#: words took from it, and no syntax says which channel it names.
RULE_OUT_MIN = 2


class Referents(Part):
    """The agent's part that says which objects an inform's references may be taught on."""

    def candidates(self, g: "_Grounding", inferred: Iterable[Term]) -> dict[str, list[str]]:
        """Which objects each reference may mean, by the words already known (unknown words
        do not constrain; a known word that holds of none of them is set aside, since it may
        not fit this instance yet, but not for an object it is ruled out of, `ruled_out`), then
        by mutual exclusivity: two references of one sentence do not mean the same object, so
        a reference pinned to one object frees it from the others. A reference that no known
        word of it holds for (set aside or none known) is a guess: it gives way to a reference
        pinned to that object by its words, even when nothing is left for it. "red box left of
        blue cylinder" said with only a red box on the table: "blue cylinder" means nothing
        seen (an empty list), not the red box; nor does "purple box" said over a red sphere."""
        assert self.state is not None
        holds: dict[str, set[str]] = {}
        for f in inferred:
            if f.name == "isa":
                holds.setdefault(str(f.args[1]), set()).add(str(f.args[0]))
        objs = self.state.named()
        cands: dict[str, list[str]] = {}
        guess: set[str] = set()
        for ref in g.parse.objects:
            cs = [g.pins[ref.id]] if ref.id in g.pins else [] if ref.id in g.unresolved else objs
            found = ref.id in g.pins
            for w in ref.words:
                c = self.semantic.concept(w)
                if c is not None and self.semantic.kind(c) == "visual":
                    fit = [o for o in cs if o in holds.get(c, set())]
                    if not fit and self.params.mutual_exclusivity:
                        # as a question finds it (which leaves out what an inform's table shows
                        # to vary): the news is what the lesson shows
                        fit = [o for o in cs if self.agent.grounding.holds_as_asked(c, o)]
                    found = found or bool(fit)
                    cs = fit or [o for o in cs if not self.ruled_out(c, o)]
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

    def ruled_out(self, concept: str, obj: str) -> bool:
        """Does what the agent knows say that the known visual word does not name `obj`, so
        that an inform cannot make `obj` its example? So when, on every channel its meaning
        has (`Lexicon.effective_meanings`: colour for "purple", shape for "box"), `obj` shows
        a value that none of the word's examples showed and that another word stands for,
        while the word alone stands for its own value there: "purple" said of a red sphere
        while "red" is known (mutual exclusivity: a child's "that's not purple, it's red").
        What it leaves to learning: a word that shares a value with the object may widen from
        it ("box" first learned on a red box, then said of a green one); a value no word names
        may be the word's after all (no word for yellow yet: the trainer may call it "red"); a
        word read as a synonym of another (`Lexicon.holders`) may be wrong about its channel
        ("medium" first said of a red box, while every object seen was medium, reads as red),
        and so may a word whose meaning is of a channel its place in a phrase does not name
        (`Lexicon.slot_channels`: "small" first said of a small yellow cone, while every
        yellow object seen was small, read as the shape, which modifiers do not name; a word
        never said in a phrase needs `RULE_OUT_MIN` examples instead); and a value the word's examples did show is no contradiction, whatever the word's
        meaning now says. Those doubts are about which channel the word names, so none of
        them stands where `obj` contradicts every channel of the meaning and the word was said
        in a phrase beside another (it names one of the phrase's properties, not a group of
        things): "red box", "blue cone", "green sphere" and "yellow cylinder", each taught
        once, leave "cylinder" meaning yellow or cylinder, and a green cone is neither (it was
        stored as a "blue cylinder" in "red box left of blue cylinder"). A word said alone may
        still widen to anything ("zup" of a red box, then of a blue cone: a disjunction).
        Without mutual exclusivity nothing is ruled out: every inform of the only object
        teaches."""
        assert self.state is not None
        if not self.params.mutual_exclusivity:
            return False
        # what tells things apart: not `cv_medium` while every object seen was medium
        meaning = self.lexicon.effective_meanings().get(concept, frozenset()) - self.lexicon.uninformative()
        channels = self.lexicon.channels
        wanted: dict[str, set[Term]] = {}
        for p in meaning:
            ch = channels.get(p)
            if ch is None:
                return False  # a meaning beyond the visual channels: nothing to compare by
            wanted.setdefault(ch, set()).add(p)
        if not wanted:
            return False
        n, shown_in_examples = self.memory.class_counts(concept)
        claimed = self.lexicon.claimed_percepts()
        shown: dict[str, set[Term]] = {}
        for f in self.state.percepts(obj):
            p = f.args[1]
            if p in channels:
                shown.setdefault(channels[p], set()).add(p)

        def against(ch: str, ps: set[Term]) -> bool:
            values = shown.get(ch, set())
            return bool(values) and not any(v in ps or shown_in_examples[v] for v in values) \
                and bool(values & claimed)

        if not all(against(ch, ps) for ch, ps in wanted.items()):
            return False
        if len(wanted) > 1 and self.lexicon.positions.get(self.semantic.word(concept) or "", set()):
            return True  # whichever of its channels the word names, `obj` is not it
        if any(self._synonym_of(concept, meaning, p) for p in meaning):
            return False
        slots = self.lexicon.slot_channels(concept)
        # its meaning and its syntax must agree, or it needs examples to go by
        return set(wanted) <= slots if slots is not None else n >= RULE_OUT_MIN

    def _synonym_of(self, concept: str, meaning: frozenset[Term], percept: Term) -> bool:
        """Is there another visual word holding `percept` that says no more than `meaning` (the
        word's own, less what tells nothing apart) says: a synonym, so the word may be read as
        another's ("medium", first said of a red box while every object seen was medium, read
        as red: `Lexicon.holders`)? A word holding more is not one: "kube", said of a red box
        and of a blue cone, means red or blue, and "red" is one of its alternatives, no
        doubt about what "red" names (with the doubt, "red glorp" said of a green box stored
        the green box as "red", while "red" meant red and the modifier's place names colours)."""
        if self.lexicon.holders(percept) < 2:
            return False
        flat = self.lexicon.uninformative()
        return any(c != concept and percept in m and (m - flat) <= meaning
                   for c, m in self.lexicon.effective_meanings().items())
