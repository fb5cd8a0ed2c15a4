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

The agent knows its own senses (`aileen.domain.channels`), never what a word means.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from aileen.domain import channels as channel_decl
from aileen.memory import claims
from aileen.reasoning import language
from aileen.reasoning.spelling import one_edit
from aileen.terms import Term

POSITIONS = ("head", "modifier")


class Lexicon:
    def __init__(
        self,
        meaning_of: Callable[[str], frozenset[Term]],
        word_of: Callable[[str], str | None],
        visual_concepts: Callable[[], list[str]],
        *,
        bootstrapping: bool = True,
    ) -> None:
        self._meaning_of = meaning_of
        self._word_of = word_of
        self._visual_concepts = visual_concepts
        self.bootstrapping = bootstrapping
        # Which channel of the visual module each percept symbol belongs to (the agent's senses).
        self.channels: dict[Term, str] = {Term(p): c for p, c in channel_decl.of_percept().items()}
        # Where each taught word has stood in multi-word noun phrases (learned), and how far
        # before the head it stood (summed, with counts), for saying words in their order.
        self.positions: dict[str, set[str]] = {}
        self.distance: dict[str, list[int]] = {}
        self._effective: dict[str, frozenset[Term]] | None = None

    # ---------------------------------------------------------------- persistence
    def to_annotation(self) -> dict:
        return {"positions": {w: sorted(p) for w, p in sorted(self.positions.items())},
                "distance": {w: list(d) for w, d in sorted(self.distance.items())}}

    def load_annotation(self, lex: object) -> None:
        if not isinstance(lex, dict):
            return
        positions = lex.get("positions", {})
        if not isinstance(positions, dict):
            return
        for w, ps in positions.items():
            if isinstance(ps, (list, tuple)):
                self.positions[str(w)] = {str(p) for p in ps if p in POSITIONS}
        distance = lex.get("distance", {})
        if isinstance(distance, dict):
            for w, d in distance.items():
                if isinstance(d, list) and len(d) == 2 and all(isinstance(x, int) and x >= 0 for x in d):
                    self.distance[str(w)] = [d[0], d[1]]

    # ---------------------------------------------------------------- learning positions
    def note_positions(self, parse: language.Parse) -> bool:
        """Remember where each word stood; True when something new was noted."""
        changed = False
        for ref in parse.objects:
            if len(ref.words) < 2:
                continue
            for i, w in enumerate(ref.words):
                pos = "head" if i == len(ref.words) - 1 else "modifier"
                d = self.distance.setdefault(w, [0, 0])
                d[0] += len(ref.words) - 1 - i
                d[1] += 1
                seen = self.positions.setdefault(w, set())
                if pos not in seen:
                    seen.add(pos)
                    changed = True
        if changed:
            self.invalidate()
        return changed

    def noun_phrase_order(self, words: list[str]) -> list[str]:
        """Words in the order the trainer says them: further from the head first (sizes
        before colours before shapes, in the curricula we ship: learned, not built in)."""

        def key(w: str) -> tuple[float, str]:
            total, n = self.distance.get(w, (0, 0))
            mean = total / n if n else (0.0 if "head" in self.positions.get(w, ()) or not self.positions.get(w)
                                        else 1.0)
            return (-mean, w)

        return sorted(words, key=key)

    def invalidate(self) -> None:
        """Forget derived meanings (after a store or a new position)."""
        self._effective = None

    # ---------------------------------------------------------------- meanings
    def effective_meanings(self) -> dict[str, frozenset[Term]]:
        """Each visual concept's meaning once the percepts that other words stand for are
        taken out, repeated until nothing changes; then narrowed to the channels its
        positions name (when bootstrapping is on) and made exclusive again."""
        if self._effective is not None:
            return self._effective
        raw = {c: self._meaning_of(c) for c in self._visual_concepts()}
        flat = self._uninformative(raw)
        m = exclusive(raw, flat)
        if self.bootstrapping:
            by_position = self.position_channels(m)
            if by_position:
                narrowed = {}
                for c, mine in m.items():
                    word = self._word_of(c)
                    positions = self.positions.get(word or "", set())
                    chans: set[str] = set()
                    unknown = not positions
                    for p in positions:
                        if p in by_position:
                            chans |= by_position[p]
                        else:
                            unknown = True
                    keep = frozenset(t for t in mine if self.channels.get(t) in chans)
                    if unknown:
                        # No syntax to go by (a word only ever said alone, "grox"): its
                        # meaning is made again from what it was shown, against the others'
                        # meanings now that syntax has pinned them.
                        narrowed[c] = raw[c]
                    else:
                        narrowed[c] = keep or mine
                m = exclusive(narrowed, flat)
        self._effective = m
        return m

    def uninformative(self) -> frozenset[Term]:
        """Percepts that tell no two things apart as far as the words learned show: the only
        value of their channel that any visual word's meaning holds (`cv_medium` while every
        object seen has been medium-sized). A meaning made of them alone would hold of every
        object: a concept never matches everything."""
        return self._uninformative({c: self._meaning_of(c) for c in self._visual_concepts()})

    def _uninformative(self, raw: dict[str, frozenset[Term]]) -> frozenset[Term]:
        seen: dict[str, set[Term]] = {}
        for mine in raw.values():
            for t in mine:
                chan = self.channels.get(t)
                if chan is not None:
                    seen.setdefault(chan, set()).add(t)
        return frozenset(next(iter(ts)) for ts in seen.values() if len(ts) == 1)

    def claimed_by_others(self, concept: str) -> frozenset[Term]:
        """Mutual exclusivity at query time: percepts of `concept` that other visual words
        stand for."""
        return self._meaning_of(concept) - self.effective_meanings().get(concept, frozenset())

    def position_channels(self, meanings: dict[str, frozenset[Term]]) -> dict[str, set[str]]:
        """Which channels each noun-phrase position names, from the words pinned to one
        percept (a modifier that means `cv_red` is evidence that modifiers name colours; one
        that means `cv_large`, that they name sizes too)."""
        evidence: dict[str, set[str]] = {}
        for c, mine in meanings.items():
            word = self._word_of(c)
            if len(mine) != 1 or word is None:
                continue
            (only,) = mine
            chan = self.channels.get(only)
            if chan is None:
                continue
            for pos in self.positions.get(word, ()):
                evidence.setdefault(pos, set()).add(chan)
        # A position that names every channel tells nothing.
        every = set(self.channels.values())
        return {pos: ch for pos, ch in evidence.items() if ch != every}


def exclusive(meanings: dict[str, frozenset[Term]],
              uninformative: frozenset[Term] = frozenset()) -> dict[str, frozenset[Term]]:
    """Mutual exclusivity to a fixpoint: a meaning gives up the percepts of any strictly
    smaller meaning, repeated so that a word pinned down frees the words taught with it, and
    never down to nothing, nor to `uninformative` percepts alone (`claims.exclusive`: linear
    in the number of concepts). A word whose every other percept is claimed is thus the
    conjunction (or a synonym) of the words that claim them: "grox", taught on green boxes
    once "green" and "box" are known, means green box, not "medium-sized", which every object
    seen is."""
    return claims.exclusive(meanings, uninformative)


#: Shortest word that a one-letter difference makes a typo of: in two-letter words one edit
#: is half the word, and short words are each other's neighbours by chance.
TYPO_MIN_LENGTH = 3


def near_spelling(word: str, known: Iterable[str]) -> str | None:
    """The known word that a new `word` is a typo of (one edit away; both at least
    `TYPO_MIN_LENGTH` letters, or `word` one shorter, a letter left out: "bx"), or None. A new word next to a known one is far more often a
    slip than a new meaning, and a slip learned as a concept stays for good; when several
    known words are one edit away, the first in alphabetical order is offered."""
    if len(word) < TYPO_MIN_LENGTH - 1:
        return None
    # a two-letter word is a slip only as a letter left out of a known word ("bx" for "box"):
    # two short words are each other's neighbours by chance, a dropped letter is not
    near = sorted(k for k in known if len(k) >= TYPO_MIN_LENGTH and one_edit(word, k)
                  and (len(word) >= TYPO_MIN_LENGTH or len(k) == len(word) + 1))
    return near[0] if near else None
