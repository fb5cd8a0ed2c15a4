"""Syntactic bootstrapping's evidence: where each word stood in a noun phrase, and which
perceptual channels each position names.

A multi-word noun phrase has its head last and its modifiers before it (syntax, not
meaning). A word pinned to one percept is evidence that every position it stood at names
that percept's channel ("red" pinned to `cv_red` and said as a modifier: modifiers name
colours). `Lexicon` keeps these counts up to date and narrows each word's meaning to the
channels of its positions; this module says what counts and what the counts mean.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence

from aileen.memory.persist import POSITIONS  # the memory file's lexicon annotation declares them
from aileen.reasoning import language
from aileen.terms import Term

__all__ = ["HEAD", "MODIFIER", "POSITIONS", "SECOND_CHANNEL_WORDS", "WordPositions", "evidence_of", "named_channels",
           "positions_in"]

HEAD, MODIFIER = POSITIONS


def positions_in(words: Sequence[str]) -> list[tuple[str, str, int]]:
    """(word, position, how many words it stood before the head) for each word of a noun
    phrase of two words or more; none for one word alone (it tells no position apart)."""
    if len(words) < 2:
        return []
    last = len(words) - 1
    return [(w, HEAD if i == last else MODIFIER, last - i) for i, w in enumerate(words)]


def evidence_of(positions: Iterable[str], meaning: frozenset[Term], channels: Mapping[Term, str]) -> frozenset[tuple[str, str]]:
    """The (position, channel) evidence of a word that stood at `positions` and means
    `meaning`: one pair per position when the meaning is one percept of a known channel,
    none otherwise."""
    if len(meaning) != 1:
        return frozenset()
    (only,) = meaning
    chan = channels.get(only)
    return frozenset() if chan is None else frozenset((pos, chan) for pos in positions)


#: How many pinned words must show a channel at a position before it names that channel
#: beside the position's main one (the channel most of its pinned words show).
SECOND_CHANNEL_WORDS = 2


def named_channels(evidence: Mapping[tuple[str, str], int], every: set[str], *,
                   weak: bool = False) -> dict[str, set[str]]:
    """Which channels each noun-phrase position names, from how many words pinned to one
    percept of a channel stood there: the channel most of them show, and any other that at
    least `SECOND_CHANNEL_WORDS` of them show. Why not every channel one word shows: a word
    taught on a misperceived object (a capsule the eyes read as a small sphere: "capsule"
    pinned to `cv_small`, since "sphere" claims the shape) would make head nouns name sizes,
    and "cone", shown once large, would then refuse every medium cone. A channel shown by
    fewer words is *weak* there (`weak=True` gives those instead): it counts only for a word
    that has nothing of its own in the others (`Lexicon._narrowed`). A position that names
    every channel tells nothing."""
    counts: dict[str, dict[str, int]] = {}
    for (pos, chan), n in evidence.items():
        if n > 0:
            counts.setdefault(pos, {})[chan] = n
    out: dict[str, set[str]] = {}
    for pos, by_chan in counts.items():
        top = max(by_chan.values())
        named = {c for c, n in by_chan.items() if n == top or n >= SECOND_CHANNEL_WORDS}
        if weak:
            if set(by_chan) - named and set(by_chan) != every:
                out[pos] = set(by_chan) - named
        elif named != every:
            out[pos] = named
    return out


class WordPositions:
    """Where each taught word has stood in multi-word noun phrases (`positions`), and how far
    before the head (`distance`: [total, count]): what the trainer's sentences showed of word
    order, learned, kept in the memory file's lexicon annotation."""

    def __init__(self) -> None:
        self.positions: dict[str, set[str]] = {}
        self.distance: dict[str, list[int]] = {}

    def note(self, parse: language.Parse) -> set[str]:
        """Remember where each word of the sentence stood; the words seen at a new position."""
        grown: set[str] = set()
        for ref in parse.objects:
            for w, pos, far in positions_in(ref.words):
                d = self.distance.setdefault(w, [0, 0])
                d[0] += far
                d[1] += 1
                seen = self.positions.setdefault(w, set())
                if pos not in seen:
                    seen.add(pos)
                    grown.add(w)
        return grown

    def order(self, words: list[str]) -> list[str]:
        """Words in the order the trainer says them: further from the head first (sizes
        before colours before shapes, in the curricula we ship: learned, not built in)."""

        def key(w: str) -> tuple[float, str]:
            total, n = self.distance.get(w, (0, 0))
            mean = total / n if n else (0.0 if HEAD in self.positions.get(w, ()) or not self.positions.get(w)
                                        else 1.0)
            return (-mean, w)

        return sorted(words, key=key)

    def to_annotation(self) -> dict:
        return {"positions": {w: sorted(p) for w, p in sorted(self.positions.items())},
                "distance": {w: list(d) for w, d in sorted(self.distance.items())}}

    def load_annotation(self, lex: dict) -> None:
        """Read what `to_annotation` wrote, keeping what is well formed."""
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
