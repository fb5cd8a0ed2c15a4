"""The agent's lexicon: what each visual word stands for once the other words have had their say.

Two word-learning mechanisms live here (DESIGN.md section 12):

- **Mutual exclusivity.** A visual concept's meaning is the set of percepts its
  generalization requires; a meaning gives up the percepts of any strictly smaller meaning,
  to a fixpoint, so a word pinned down frees the words it was taught with ("green cone", both
  new, then "red cone": `cone` is `cv_cone`, so `green` stops requiring it).
- **Syntactic bootstrapping.** Where each word stood in multi-word noun phrases (the last word
  is the head, the others modifiers: syntax, not meaning), and which perceptual channels each
  position names, learned from the words already pinned to one percept. A word's meaning is
  narrowed to the channels of its positions. Modifiers may name several channels ("large red
  box": size and colour), so a position names the *set* of channels its evidence shows.
  What counts as evidence and what the counts mean: `aileen.agent.positions`; this module
  keeps them up to date.

The agent knows its own senses (`aileen.domain.channels`), never what a word means.
"""

from __future__ import annotations

import contextlib
from collections import Counter
from collections.abc import Callable, Iterable, Iterator, Mapping

from aileen.agent.positions import POSITIONS, WordPositions, evidence_of, named_channels  # noqa: F401 - POSITIONS re-exported
from aileen.agent.seen import SeenPercepts
from aileen.domain import channels as channel_decl
from aileen.memory import claims, claims_pass
from aileen.reasoning import language
from aileen.reasoning.spelling import near_spelling, one_edit  # noqa: F401 - re-exported (callers that import them from here)
from aileen.terms import Term


#: What a concept memory says changed since a mark: (the next mark, {concept: kind}), or None
#: in place of the concepts when everything must be read again (`ConceptMemory.changes_since`).
Changes = Callable[[int | None], tuple[int, Mapping[str, str] | None]]


class Lexicon:
    """The visual words' meanings once the other words have had their say, kept up to date.

    Why kept up to date rather than made again: the lexicon is asked after every store, and
    a learner's lexicon has tens of thousands of words. Each stage is kept from the previous
    one by what changed: the concepts stored into (from the memory's change log, `changes`,
    or `invalidate(concept)`), their exclusive meanings (`claims.Exclusivity`), the positions'
    evidence (counts, so a word adds or takes back its own), each word's narrowed meaning
    (made again for every word only when what a position names changes), and the exclusive
    pass after narrowing. The answers are those of making everything again from every
    meaning (tests/test_lexicon_incremental.py holds them equal over random store sequences).
    """

    def __init__(
        self,
        meaning_of: Callable[[str], frozenset[Term]],
        word_of: Callable[[str], str | None],
        visual_concepts: Callable[[], list[str]],
        *,
        bootstrapping: bool = True,
        changes: Changes | None = None,
    ) -> None:
        self._meaning_of = meaning_of
        self._word_of = word_of
        self._visual_concepts = visual_concepts
        self._changes = changes
        self.bootstrapping = bootstrapping
        # Which channel of the visual module each percept symbol belongs to (the agent's senses).
        self.channels: dict[Term, str] = {Term(p): c for p, c in channel_decl.of_percept().items()}
        # Where each taught word has stood in multi-word noun phrases (learned), and how far
        # before the head it stood (summed, with counts), for saying words in their order.
        self.phrases = WordPositions()
        # How common each percept is among the objects taught on (`seen.py`): no meaning is
        # made of percepts most objects have, of a channel no phrase position names.
        self.seen = SeenPercepts()
        self._teaching: list[frozenset[Term]] = []  # an inform's objects, while it is grounded
        self._reset()

    def _reset(self) -> None:
        """Forget everything derived: the next question reads every visual concept again."""
        self._mark: int | None = None  # where in the memory's change log the lexicon is
        self._stale_all = True
        self._stale: dict[str, None] = {}  # concepts to read again (invalidate(concept))
        self._stale_words: set[str] = set()  # words whose positions changed
        self._built_with = self.bootstrapping
        self._raw: dict[str, frozenset[Term]] = {}  # each visual concept's meaning, in memory order
        self._word: dict[str, str | None] = {}
        self._concept_of: dict[str, str] = {}
        self._values: dict[str, Counter[Term]] = {}  # channel -> percept -> meanings holding it
        self._flat: frozenset[Term] = frozenset()
        self._common: frozenset[Term] = frozenset()  # `seen.common()` as the second stage read it
        self._flat2: frozenset[Term] = frozenset()  # the second stage's uninformative percepts
        self._first: claims.Exclusivity[str, Term] = claims.Exclusivity()
        self._second: claims.Exclusivity[str, Term] = claims.Exclusivity()  # the words said in phrases
        self._third: claims.Exclusivity[str, Term] = claims.Exclusivity()  # every word (`_apply_second`)
        self._evidence: Counter[tuple[str, str]] = Counter()  # (position, channel) -> pinned words
        self._evidence_of: dict[str, frozenset[tuple[str, str]]] = {}
        self._by_position: dict[str, set[str]] = {}
        self._weak: dict[str, set[str]] = {}  # position -> channels one pinned word alone shows there
        self._pinned: Counter[Term] = Counter()  # percept -> words whose first-stage meaning is that percept alone
        self._pinned_touched: set[Term] = set()  # percepts whose count of words pinned to them changed
        self._first_holders: dict[Term, set[str]] = {}  # percept -> concepts whose first-stage meaning holds it
        self._held: Counter[Term] = Counter()  # percept -> effective meanings holding it
        self._claimed: frozenset[Term] | None = frozenset()

    # ---------------------------------------------------------------- persistence
    def to_annotation(self) -> dict:
        return {**self.phrases.to_annotation(), "seen": self.seen.to_annotation()}

    def load_annotation(self, lex: object) -> None:
        if not isinstance(lex, dict):
            return
        self.seen.load_annotation(lex.get("seen"))
        self.phrases.load_annotation(lex)
        self._stale_words.update(self.positions)

    # ---------------------------------------------------------------- learning positions
    @property
    def positions(self) -> dict[str, set[str]]:
        """Where each taught word has stood in multi-word noun phrases (`WordPositions`)."""
        return self.phrases.positions

    @positions.setter
    def positions(self, value: dict[str, set[str]]) -> None:
        self.phrases.positions = value

    @property
    def distance(self) -> dict[str, list[int]]:
        """How far before the head each word stood: [total, count] (`WordPositions`)."""
        return self.phrases.distance

    @distance.setter
    def distance(self, value: dict[str, list[int]]) -> None:
        self.phrases.distance = value

    def note_positions(self, parse: language.Parse) -> bool:
        """Remember where each word stood; True when something new was noted."""
        grown = self.phrases.note(parse)
        self._stale_words |= grown
        return bool(grown)

    def note_seen(self, objects: "Iterable[Iterable[str]]") -> None:
        """Count the percepts of the objects on the table of a lesson taught (`seen.py`)."""
        before = self.seen.objects
        self.seen.note(objects)
        if before < 2 <= self.seen.objects:
            self.invalidate()  # the first words' unmarked percepts are known from the second object on

    def note_taught(self, word: str) -> bool:
        """An example of a visual word is stored now (`SeenPercepts.unmarked`); True when what
        is unmarked for it changed (its meaning is read again)."""
        changed = self.seen.note_taught(word)
        c = self._concept_of.get(word)
        if changed and c is not None:
            self.invalidate(c)
        return changed

    def noun_phrase_order(self, words: list[str]) -> list[str]:
        """Words in the order the trainer says them (`WordPositions.order`)."""
        return self.phrases.order(words)

    def invalidate(self, concept: str | None = None) -> None:
        """A concept's meaning may have changed (a store that bypassed the memory's change
        log, or a lexicon without one); without a concept, anything may have (the positions
        were edited by hand): everything is read again at the next question."""
        if concept is None:
            self._stale_all = True
        else:
            self._stale[concept] = None

    # ---------------------------------------------------------------- meanings
    def effective_meanings(self) -> Mapping[str, frozenset[Term]]:
        """Each visual concept's meaning once the percepts that other words stand for are
        taken out, repeated until nothing changes; then narrowed to the channels its
        positions name (when bootstrapping is on) and made exclusive again. A live,
        read-only view, in the memory's order."""
        self._sync()
        return self._third.meanings() if self.bootstrapping else self._first.meanings()

    def meaning(self, concept: str) -> frozenset[Term]:
        """The percepts a concept requires (`meaning_of`), read once per change of the concept."""
        self._sync()
        m = self._raw.get(concept)
        return m if m is not None else self._meaning_of(concept)

    def alternatives(self, concepts: Iterable[str]) -> bool:
        """Do these visual concepts all name values of one channel, the same one ("red",
        "blue": colours), so that a thing is one of them at most? Read from what each names
        (`effective_meanings`) and the agent's knowledge of its senses (each percept's
        channel); "red" and "large" are not ("the boxes are red and large" is said of each)."""
        named = self.effective_meanings()
        seen: set[str] = set()
        for c in concepts:
            chans = {self.channels[p] for p in named.get(c, ()) if p in self.channels}
            if not chans:
                return False
            seen |= chans
        return len(seen) == 1

    def claimed_percepts(self) -> frozenset[Term]:
        """Every percept some visual word's effective meaning holds."""
        self._sync()
        if self._claimed is None:
            self._claimed = frozenset(self._held)
        return self._claimed

    def holders(self, percept: Term) -> int:
        """How many visual words' effective meanings hold `percept`: one for a word that
        alone stands for it, two or more for synonyms, or for a word read as another's
        ("medium", first said of a red box while every object seen was medium, read in the
        colour slot as red)."""
        self._sync()
        return self._held.get(percept, 0)

    def slot_channels(self, concept: str) -> set[str] | None:
        """The channels the noun-phrase positions a visual word has stood in surely name
        (colour for a modifier once modifiers were shown naming colours), None when the word
        was never said in a phrase or stood where nothing is known yet: what its syntax
        says it may name."""
        self._sync()
        positions = self.positions.get(self._word.get(concept) or "", set())
        if not positions or any(p not in self._by_position for p in positions):
            return None
        return set().union(*(self._by_position[p] for p in positions))

    def uninformative(self) -> frozenset[Term]:
        """Percepts that tell no two things apart as far as the words learned show: the only
        value of their channel that any visual word's meaning holds (`cv_medium` while every
        object seen has been medium-sized); with syntactic bootstrapping, also those most
        objects taught on have (`seen.py`) of a channel no noun-phrase position names. A
        meaning made of them alone would hold of every object, or nearly: a concept never
        matches everything."""
        self._sync()
        return self._flat2 if self.bootstrapping else self._flat

    def claimed_by_others(self, concept: str) -> frozenset[Term]:
        """Mutual exclusivity at query time: percepts of `concept` that other visual words
        stand for."""
        return self.meaning(concept) - self.effective_meanings().get(concept, frozenset())

    @contextlib.contextmanager
    def teaching(self, objects: Iterable[Iterable[Term]]) -> Iterator[None]:
        """While an inform is grounded: its table's objects count as taught on for `not_asked`
        (a large box taught while every earlier object was medium shows that size varies, so
        the word's medium examples count again, and the inform is news to store)."""
        self._teaching = [frozenset(o) for o in objects]
        try:
            yield
        finally:
            self._teaching = []

    def not_asked(self, concept: str) -> frozenset[Term]:
        """What a query of `concept` leaves out: the percepts other visual words stand for
        (`claimed_by_others`), and those every object taught on has had (`seen.constant`:
        `cv_medium` while every word was taught on medium objects: no example has shown a
        contrast there), as long as the meaning keeps something else. "red box" and "green
        sphere", each taught once on a medium object, named no large red box (2 of 3 facts,
        under the match threshold). Once an object of another size is taught on, the size a
        word's examples showed counts again in an inform (a large red box said to be a "red
        box" is news, and stored); a question still leaves out what no word's meaning tells
        apart (`uninformative`: medium while no word holds another size), nor what every
        object had until the word was taught (`seen.unmarked`): "red sphere" and "blue
        cone" taught on medium objects, and "sphere" on a small one, named no small red
        sphere; "yellow cylinder" taught on a medium one named no large one once "large" and
        "small" were known.

        What every object taught on had is no contrast only where some of them were no
        example of the word: a word taught on every object so far ("crate" on a red, a blue
        and a small yellow box, from an empty memory) names what they share, and was
        otherwise left with the usual size alone (yes to a red sphere).

        Left out in two tiers, each only where the meaning keeps something besides: first what
        no object ever showed a contrast in (`constant`, `unmarked`), then what merely tells
        little (`uninformative`). Together in one tier, "wood" (a channel's default, on most
        objects, so common) taught on medium objects kept both `cv_wood` and `cv_medium`, since
        nothing else was left, and refused a small wood box while "metal" held of any size."""
        ignore = self.claimed_by_others(concept)
        meaning = self.meaning(concept)
        word = self._word.get(concept) or ""
        no_contrast = (frozenset() if self.seen.all_examples_of(word)
                       else meaning & self.seen.constant(self._teaching))
        tiers = [no_contrast]
        if not self._teaching:
            tiers = [no_contrast | (meaning & self.seen.unmarked(self._word.get(concept) or "")),
                     meaning & self.uninformative()]
        for tier in tiers:
            flat = tier - ignore
            if flat and meaning - ignore - flat:
                ignore = ignore | flat
        return ignore

    # ---------------------------------------------------------------- keeping up to date
    def _sync(self) -> None:
        """Bring every stage up to date with what changed since the last question."""
        if self._built_with != self.bootstrapping:
            self._reset()
        full = self._stale_all
        touched: dict[str, None] = {}
        if self._changes is not None:
            self._mark, got = self._changes(self._mark)
            if got is None:
                full = True
            else:
                touched.update((c, None) for c, kind in got.items() if kind == "visual")
        for c in self._stale:
            if c in self._raw:
                touched[c] = None
            elif self._changes is None:
                full = True  # a concept it has not seen: only the full list says where it goes
        self._stale = {}
        if not full and not touched and not self._stale_words and self._common == self.seen.common():
            return
        self._stale_all = False
        if full:
            order = self._visual_concepts()
            keep = set(order)
            known = [c for c in self._raw if c in keep]
            if order[:len(known)] != known:  # not the order it has: built again from nothing
                mark = self._mark
                self._reset()
                self._stale_all, self._mark = False, mark
            changes: dict[str, frozenset[Term] | None] = {c: None for c in self._raw if c not in keep}
            for c in order:
                m = self._meaning_of(c)
                if self._raw.get(c) != m:
                    changes[c] = m
        else:
            changes = {}
            for c in touched:
                m = self._meaning_of(c)
                if self._raw.get(c) != m:
                    changes[c] = m
        self._apply(changes, full)

    def _apply(self, changes: dict[str, frozenset[Term] | None], everything: bool) -> None:
        """Carry `changes` (a concept's new meaning, None when it is gone) through every
        stage; with `everything`, every word's evidence and narrowing is looked at again."""
        for c, m in changes.items():
            old = self._raw.pop(c, None) if m is None else self._raw.get(c)
            for t in old or ():
                self._count_value(t, -1)
            if m is None:
                w = self._word.pop(c, None)
                if w is not None and self._concept_of.get(w) == c:
                    del self._concept_of[w]
                continue
            self._raw[c] = m
            for t in m:
                self._count_value(t, +1)
            if c not in self._word:
                w = self._word[c] = self._word_of(c)
                if w is not None:
                    self._concept_of[w] = c
        self._flat = frozenset(next(iter(vs)) for vs in self._values.values() if len(vs) == 1)
        first = self._first.update(changes, self._flat)
        if not self.bootstrapping:
            self._note_effective(first, self._first.meanings())
            return
        # the positions' evidence: words pinned to one percept, by where they stood
        words = self._raw if everything else {self._concept_of[w] for w in self._stale_words
                                              if w in self._concept_of}
        self._stale_words = set()
        dirty = [*changes, *(c for c in {**first, **dict.fromkeys(words)} if c not in changes)]
        m1 = self._first.meanings()
        self._note_first(first, m1)
        for c in dirty:
            self._note_evidence(c, m1.get(c))
        by_position = self._positions_now()
        weak = named_channels(self._evidence, set(self.channels.values()), weak=True)
        common = self.seen.common()
        if by_position != self._by_position or weak != self._weak or common != self._common:
            # a word's narrowing reads the positions and what is common (`_narrowed`)
            self._by_position, self._weak, self._common = by_position, weak, common
            dirty = [*changes, *(c for c in self._raw if c not in changes)]
        elif weak and self._pinned_touched:
            # ... and, where a position has a weak channel, which percepts words are pinned
            # to: the words holding a percept whose pinned words changed are read again
            seen = set(dirty)
            for t in self._pinned_touched:
                for c in sorted(self._first_holders.get(t, ())):
                    if c not in seen:
                        seen.add(c)
                        dirty.append(c)
        self._pinned_touched = set()
        narrowed: dict[str, frozenset[Term] | None] = {}
        for c in dirty:
            narrowed[c] = self._narrowed(c, m1[c]) if c in self._raw else None
        # What most objects taught on have names nothing, unless a position names its channel
        # (modifiers name sizes once "small" and "large" are pinned: "medium red box" then
        # means medium, however common): `seen.py`.
        self._common = self.seen.common()
        # (a channel one pinned word shows a position to name counts: "small" and "large" at
        # the modifier's place, and "medium" then meant red or blue, cv_medium being common)
        named = set().union(*self._by_position.values(), *self._weak.values())
        self._flat2 = self._flat | frozenset(t for t in self._common if self.channels.get(t) not in named)
        self._apply_second(narrowed)

    def _said_alone(self, c: str) -> bool:
        """Whether the concept's word was never said in a noun phrase ("grox", said as a whole
        sentence): nothing of syntax says what it names (`_apply_second`)."""
        word = self._word.get(c)
        return word is not None and not self.positions.get(word)

    def _apply_second(self, narrowed: dict[str, frozenset[Term] | None]) -> None:
        """The second exclusive pass, in two steps: the words said in noun phrases settle
        among themselves (`_second`); then every word, those with the meanings they settled
        on and the words said alone with theirs (`_third`).

        Why two steps (issue 20, defect (a)): in one pass, "grox", said alone of green boxes
        of three sizes once "green" (taught on a medium green cone, so at first {green,
        medium}) and "box" were known, gave up `cv_box` before "green" had given up
        `cv_medium` to "medium"; "green" could then give up neither (that would leave it
        nothing), so "grox" meant green, true of a green cylinder, and "green" meant medium
        green, false of a large green sphere. With the phrase words settled first, "grox"
        keeps what "green" and "box" claim: their conjunction."""
        moved = [c for c, m in narrowed.items()
                 if m is not None and c in self._second.given() and self._said_alone(c)]
        joined = [c for c, m in narrowed.items()
                  if m is not None and c in self._third.given() and c not in self._second.given()
                  and not self._said_alone(c)]
        if joined:  # said in a phrase at last: the phrase words made again, in memory order
            self._second = claims.Exclusivity()
            gone = {c: None for c, m in narrowed.items() if m is None}
            narrowed = {**{c: (narrowed[c] if c in narrowed else self._narrowed(c, self._first.meanings()[c]))
                           for c in self._raw}, **gone}
        to_second: dict[str, frozenset[Term] | None] = {}
        for c, m in narrowed.items():
            alone = m is not None and self._said_alone(c)
            if not alone or c in moved:
                to_second[c] = None if alone else m
        settled = self._second.update(to_second, self._flat2)
        now2 = self._second.meanings()
        to_third: dict[str, frozenset[Term] | None] = {}
        for c in [*narrowed, *(c for c in settled if c not in narrowed)]:
            if c not in self._raw:
                to_third[c] = None
            elif c in now2:
                to_third[c] = now2[c]
            elif c in narrowed:
                to_third[c] = narrowed[c]
            else:
                to_third[c] = self._third.given().get(c)
        third = self._third.update(to_third, self._flat2)
        self._note_effective(third, self._third.meanings())

    def _count_value(self, t: Term, n: int) -> None:
        chan = self.channels.get(t)
        if chan is None:
            return
        values = self._values.setdefault(chan, Counter())
        values[t] += n
        if values[t] <= 0:
            del values[t]
            if not values:
                del self._values[chan]

    def _note_evidence(self, c: str, mine: frozenset[Term] | None) -> None:
        word = self._word.get(c)
        ev = frozenset() if mine is None or word is None else evidence_of(self.positions.get(word, ()), mine, self.channels)
        old = self._evidence_of.get(c, frozenset())
        if ev == old:
            return
        self._evidence.subtract(old)
        self._evidence.update(ev)
        for k in old - ev:
            if self._evidence[k] <= 0:
                del self._evidence[k]
        if ev:
            self._evidence_of[c] = ev
        else:
            self._evidence_of.pop(c, None)

    def _positions_now(self) -> dict[str, set[str]]:
        return named_channels(self._evidence, set(self.channels.values()))

    def _narrowed(self, c: str, mine: frozenset[Term]) -> frozenset[Term]:
        """The concept's meaning narrowed to the channels its positions name."""
        if not self._by_position:
            return self._raw[c]
        positions = self.positions.get(self._word.get(c) or "", set())
        chans: set[str] = set()
        unknown = not positions
        for p in positions:
            if p in self._by_position:
                chans |= self._by_position[p]
            else:
                unknown = True
        if unknown:
            # No syntax to go by (a word only ever said alone, "grox"): its meaning is made
            # again from what it was shown, against the others' meanings now that syntax has
            # pinned them.
            return self._raw[c]
        keep = frozenset(t for t in mine if self.channels.get(t) in chans)
        if keep and all(self._pinned_elsewhere(t, mine) for t in keep):
            # All it keeps in the channels its positions surely name is what words pinned
            # down stand for ("small", shown on a red object, would mean what "red" means,
            # where one size word alone has shown that modifiers name sizes): mutual
            # exclusivity says a word names something else, so the channels a single word
            # has shown at its positions count for it.
            weak: set[str] = set()
            for p in positions:
                weak |= self._weak.get(p, set())
            keep |= frozenset(t for t in mine if self.channels.get(t) in weak and not self._pinned_elsewhere(t, mine))
        if keep and mine - keep and keep <= self.seen.unmarked(self._word.get(c) or ""):
            # All it keeps is what every object had until it was taught (`seen.unmarked`:
            # "green", said of a medium green sphere while every object shown was medium): no
            # contrast was there to name, so its positions say nothing of it.
            return self._raw[c]
        if keep and keep <= self._common and mine - keep:
            # All it keeps is what most objects taught on have (`seen.COMMON`: "red", said of
            # a medium red box at the console, where every object put down is medium, then
            # "large" and "small" showed that modifiers name sizes: "red" would mean medium,
            # and so would "blue"): a speaker names what stands out, not the usual size, so
            # its positions say nothing of it yet.
            return self._raw[c]
        return keep or mine

    def _pinned_elsewhere(self, t: Term, mine: frozenset[Term]) -> bool:
        """Whether a word other than the one meaning `mine` is pinned to the percept `t` alone
        (first stage)."""
        return self._pinned.get(t, 0) > (1 if mine == frozenset((t,)) else 0)

    def _note_first(self, changed: Mapping[str, frozenset[Term] | None], now: Mapping[str, frozenset[Term]]) -> None:
        """Keep `_pinned` and `_first_holders` up to date (`_narrowed` reads the first where
        a position has a weak channel), and note the percepts whose pinned words changed."""
        for c, was in changed.items():
            is_ = now.get(c)
            for t in was or ():
                holders = self._first_holders.get(t)
                if holders is not None:
                    holders.discard(c)
                    if not holders:
                        del self._first_holders[t]
            for t in is_ or ():
                self._first_holders.setdefault(t, set()).add(c)
            for m, d in ((was, -1), (is_, +1)):
                if m is not None and len(m) == 1:
                    (t,) = m
                    self._pinned[t] += d
                    if self._pinned[t] <= 0:
                        del self._pinned[t]
                    self._pinned_touched.add(t)

    def _note_effective(self, changed: Mapping[str, frozenset[Term] | None],
                        now: Mapping[str, frozenset[Term]]) -> None:
        for c, was in changed.items():
            for t in was or ():
                self._held[t] -= 1
                if self._held[t] <= 0:
                    del self._held[t]
            for t in now.get(c, ()):
                self._held[t] += 1
        if changed:
            self._claimed = None

    def position_channels(self, meanings: dict[str, frozenset[Term]]) -> dict[str, set[str]]:
        """Which channels each noun-phrase position names, from the words pinned to one
        percept (a modifier that means `cv_red` is evidence that modifiers name colours; one
        that means `cv_large`, that they name sizes too)."""
        evidence: Counter[tuple[str, str]] = Counter()
        for c, mine in meanings.items():
            word = self._word_of(c)
            if word is not None:
                evidence.update(evidence_of(self.positions.get(word, ()), mine, self.channels))
        return named_channels(evidence, set(self.channels.values()))


def exclusive(meanings: dict[str, frozenset[Term]],
              uninformative: frozenset[Term] = frozenset()) -> dict[str, frozenset[Term]]:
    """Mutual exclusivity to a fixpoint: a meaning gives up the percepts of any strictly
    smaller meaning, repeated so that a word pinned down frees the words taught with it, and
    never down to nothing, nor to `uninformative` percepts alone (`claims_pass.exclusive`: linear
    in the number of concepts). A word whose every other percept is claimed is thus the
    conjunction (or a synonym) of the words that claim them: "grox", taught on green boxes
    once "green" and "box" are known, means green box, not "medium-sized", which every object
    seen is."""
    return claims_pass.exclusive(meanings, uninformative)
