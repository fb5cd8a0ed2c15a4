"""Two words one slip apart: the typing slips a trainer makes.

The grammar reads "lef of" as "left of" (`aileen.reasoning.grammar`), and the agent takes a new
word one slip from a known one for a typo rather than a new meaning
(`near_spelling`): both ask the same question, here, below both.
"""

from __future__ import annotations

from collections.abc import Iterable

__all__ = ["one_edit", "near_spelling", "swapped", "swap_of", "slip_of", "dropped_or_doubled", "joined_of", "degree_of",
           "TYPO_MIN_LENGTH"]


def one_edit(a: str, b: str) -> bool:
    """Are two different words one edit apart: a letter inserted, deleted or replaced, or two
    neighbouring letters swapped (the slips a typing trainer makes)?"""
    if a == b or abs(len(a) - len(b)) > 1:
        return False
    if len(a) != len(b):
        short, long_ = (a, b) if len(a) < len(b) else (b, a)
        i = next((k for k in range(len(short)) if short[k] != long_[k]), len(short))
        return short[i:] == long_[i + 1:]
    diff = [k for k in range(len(a)) if a[k] != b[k]]
    return len(diff) == 1 or _neighbours_swapped(a, b, diff)


def _neighbours_swapped(a: str, b: str, diff: list[int]) -> bool:
    """Given where two words of one length differ: only in two neighbouring letters, swapped."""
    return len(diff) == 2 and diff[1] == diff[0] + 1 and a[diff[0]] == b[diff[1]] and a[diff[1]] == b[diff[0]]


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


def swapped(a: str, b: str) -> bool:
    """Are two words the same but for two neighbouring letters swapped ("teh", "the")?"""
    if len(a) != len(b):
        return False
    return _neighbours_swapped(a, b, [k for k in range(len(a)) if a[k] != b[k]])


def swap_of(word: str, closed_class: Iterable[str]) -> str | None:
    """The closed-class word (a function word, a relation word of the grammar, a verb: "the",
    "and", "behind", "move") that a new `word` is a slip of by two neighbouring letters
    swapped ("teh", "adn", "behnid", "mvoe"), both at least `TYPO_MIN_LENGTH` letters, or None.
    Such a word is never a new meaning's name, and may not be taught yet ("behind" before its
    first lesson), so `near_spelling` over the known words cannot find it. Only the swap: the
    other slips of short closed-class words are content words a lesson may teach ("one" is a
    letter from "cone", "shall" one from "small"), where a swap rarely is (of the words in the
    lessons, the docs and the original's scripts, only "sin" and "form")."""
    if len(word) < TYPO_MIN_LENGTH:
        return None
    near = sorted(f for f in closed_class if swapped(word, f))
    return near[0] if near else None


def dropped_or_doubled(a: str, b: str) -> bool:
    """Is `a` the word `b` with one letter left out ("th", "nd") or one letter typed twice
    ("tthe", "thee", "annd")?"""
    if len(a) == len(b) - 1:
        return any(b[:i] + b[i + 1:] == a for i in range(len(b)))
    return len(a) == len(b) + 1 and any(a == b[:i] + b[i] + b[i:] for i in range(len(b)))


def slip_of(word: str, closed_class: Iterable[str], frequent: Iterable[str] = ()) -> str | None:
    """The closed-class word a new `word` is a slip of: two neighbouring letters swapped of
    any (`swap_of`), or a letter left out or typed twice of one of the `frequent` ones (the
    articles and "and": "th", "te", "thee", "tthe" were each learned as a word, and "ther"
    was then asked about as "thee"). Only for those: a letter left out of other function
    words makes content words a lesson may teach ("ring" of "bring", "round" of "around",
    "tree" of "three", "hat" of "that")."""
    swap = swap_of(word, closed_class)
    if swap is not None or len(word) < TYPO_MIN_LENGTH - 1:
        return swap
    near = sorted(f for f in frequent if len(f) >= TYPO_MIN_LENGTH and dropped_or_doubled(word, f))
    return near[0] if near else None


def joined_of(word: str, known: Iterable[str]) -> str | None:
    """The two known words a new `word` is written together ("redbox") or hyphenated
    ("blue-cone", read `blue_cone`) from, as "red box", or None: two words run together are
    far more often a slip than a new meaning (both were learned as new words for good). Each
    part at least `TYPO_MIN_LENGTH` letters; where it splits two ways, the first split."""
    words = set(known)
    parts = word.split("_")
    if len(parts) == 2 and all(p in words for p in parts):
        return " ".join(parts)
    if "_" in word:
        return None
    for k in range(TYPO_MIN_LENGTH, len(word) - TYPO_MIN_LENGTH + 1):
        if word[:k] in words and word[k:] in words:
            return f"{word[:k]} {word[k:]}"
    return None


def degree_of(word: str, stems: Iterable[str]) -> tuple[str, str] | None:
    """A comparative or superlative of one of `stems` by its ending: ("bigger", ...) ->
    ("big", "er"), "smallest" -> ("small", "est"), "largest" -> ("large", "est"), "tiniest" ->
    ("tiny", "est"), "leftmost" -> ("left", "most"); None when no ending leaves a stem.

    Why by morphology: a word that compares ("bigger", "the leftmost cone") is no property of
    one thing, and a list of them by hand would miss the next ("redder", "topmost"); a known
    word or a declared one before the ending says what it is. A stem is at least three letters
    ("tower" is no "tow" + "er")."""
    have = frozenset(stems)
    for ending in ("most", "est", "er"):
        if not word.endswith(ending):
            continue
        base = word[: -len(ending)]
        found = [base]
        if ending != "most":
            found += [base + "e", base[:-1] + "y" if base.endswith("i") else ""]
            if len(base) > 1 and base[-1] == base[-2]:
                found.append(base[:-1])  # "bigger": big
        stem = next((s for s in found if len(s) >= TYPO_MIN_LENGTH and s in have), None)
        if stem is not None:
            return stem, ending
    return None
