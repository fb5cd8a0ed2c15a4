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
from aileen.terms import Term

__all__ = ["HEAD", "MODIFIER", "POSITIONS", "SECOND_CHANNEL_WORDS", "evidence_of", "named_channels", "positions_in"]

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
