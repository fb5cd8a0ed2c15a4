"""A sentence as typed -> its words, before any word has a role (`tagging` gives roles).

Why apart: what a teacher types is untidy in ways that have nothing to do with what a word
means -- quotes and brackets, end punctuation, a pause (","), contractions ("isn't", "it's"),
a question tag at the end ("..., right?"), a relation written with hyphens ("left-of") --
and a sentence too long for any reader is refused here, before any rule is tried (`TooLong`).
`tagging` reads the words this gives by role (and refuses what is left empty).
"""

from __future__ import annotations

import functools
import re
from dataclasses import dataclass

from aileen.domain import channels, relations
from aileen.domain import words as closed
from aileen.errors import UserError

__all__ = ["MAX_WORDS", "MAX_WORD_LENGTH", "NotUnderstood", "TooLong", "WORD", "FILLERS", "Spellings", "spellings", "numeral",
           "asked", "general", "raw_words", "untagged"]

#: Longest sentence accepted, in words: a trainer's sentence is a handful of words; past
#: this it is a mistake (a pasted file), and the per-lesson work should stay small.
MAX_WORDS = 200
#: Longest word accepted, in characters: no word of a language runs past a few dozen letters;
#: a longer one is a slip (a pasted block), and learned it would be a concept for good.
MAX_WORD_LENGTH = 48


class NotUnderstood(UserError):
    """A sentence the agent cannot read. Never an answer "no": the lesson's record says it
    was not understood, and nothing is learned from it. The message is in the teacher's words."""


class TooLong(NotUnderstood):
    """A sentence past `MAX_WORDS` words (a lesson file refuses it when it is read)."""


# a word as the reader takes it: letters and digits, a letter first ("_" joins a relation's words)
WORD = re.compile(r"[a-z][a-z0-9_]*")


def numeral(word: str) -> bool:
    """A number written in ASCII digits ("2"; not "²", which `str.isdigit` also takes)."""
    return word.isascii() and word.isdigit()


_QUOTES = "\"'`\u2018\u2019\u201c\u201d()[]"
_END = ".!?"
_PAUSE = ",;:"
_DASHES = "-\u2013\u2014"  # a dash typed alone is a pause
_CONTRACTIONS = {"can't": ("can", "not"), "cannot": ("can", "not"), "won't": ("will", "not"),
                 "don't": ("do", "not"), "doesn't": ("does", "not")}
_IS_AFTER = frozenset({"it", "that", "there", "where", "what", "this", "here"})
FILLERS = frozenset({"side", "hand"})  # "on the left side of", "on the right-hand side of"
# question tags at the end: "..., right?", "..., isn't it?", "... or not?"
_TAGS = ((",", "right"), (",", "correct"), (",", "yes"), ("is", "not", "it"), ("are", "not", "they"),
         ("is", "it", "not"), ("or", "not"), (",", "is", "not", "it"))
_ASKED_TAGS = frozenset({(",", "right"), (",", "correct"), (",", "yes")})  # only with a question mark


@dataclass(frozen=True)
class Spellings:
    """The declared spellings of relation words, indexed for reading a sentence."""

    spaced: dict[str, str]  # "to the left of" -> "left of"
    joined: dict[str, str]  # "totheleftof" -> "left of" (also "leftof", "infrontof")
    longest: int  # words in the longest spelling
    tails: dict[tuple[str, ...], list[tuple[str, str]]]  # ("of",) -> [("left", "left of"), ...]
    words: frozenset[str]  # every word of a spelling


@functools.lru_cache(maxsize=4)
def _index(key: tuple[int, int, int]) -> Spellings:  # noqa: ARG001 - the registry's version
    table = relations.spellings()
    joined = {k.replace(" ", ""): v for k, v in table.items()}
    tails: dict[tuple[str, ...], list[tuple[str, str]]] = {}
    for k, v in table.items():
        parts = k.split()
        if len(parts) >= 2:
            tails.setdefault(tuple(parts[1:]), []).append((parts[0], v))
    return Spellings(dict(table), joined, max((len(k.split()) for k in table), default=1), tails,
                     frozenset(w for k in table for w in k.split()))


def spellings() -> Spellings:
    """The declared relation spellings, indexed (again only when a relation is declared)."""
    return _index(relations.version())


def general(word: str) -> bool:
    """A noun that names a thing but no property of it: "object", "thing", "item"
    (`words.ANY_SHAPE`) and a channel's name ("the colour is red", "the shape is a box": what
    a thing is, said of the thing). Read as no word at all where it ends a noun phrase ("the
    red object" finds red things), never learned: a word "object" learned of one box said no
    to "is the cone an object?"."""
    return word in closed.ANY_SHAPE or word in channels.key_names()


def raw_words(sentence: str) -> list[tuple[str, int, str]]:
    """(word, position, typed) for each word, punctuation apart: a pause (",") is the word
    ","; end punctuation is dropped; "isn't" is "is not", "it's" "it is"; a hyphenated or
    underscored relation ("left-of") is its words, any other ("light-blue") one word."""
    matches = []
    for m in re.finditer(r"\S+", sentence):
        matches.append(m.group())
        if len(matches) > MAX_WORDS:
            head = sentence[:40].strip()
            raise TooLong(f"I cannot read {head!r}...: the sentence is longer than {MAX_WORDS} words")
        if len(m.group()) > MAX_WORD_LENGTH:
            raise TooLong(f"I cannot read {m.group()[:20]!r}... (word {len(matches)}): it is {len(m.group())} "
                          f"characters long; I read words of at most {MAX_WORD_LENGTH}")
    sp = spellings()
    out: list[tuple[str, int, str]] = []
    tidy = [_tidy(raw, i == len(matches)) for i, raw in enumerate(matches, 1)]
    owned = 0  # a channel's name after a possessive, left out: "the box's colour is ruby"
    for i, raw in enumerate(matches, 1):
        word, pause = tidy[i - 1]
        if word and not word.strip(_DASHES):  # "the red box - left of the blue cone": a pause
            word, pause = "", i < len(matches)
        if i == owned:
            continue
        if (word.endswith("'s") and WORD.fullmatch(word[:-2]) and not pause and i < len(matches)
                and general(tidy[i][0])):
            # what a thing's colour (shape, ...) is, the thing is: "the box is ruby" (it read
            # "boxs", asked "did you mean 'box'?" of a word nobody typed, and learned it)
            word, owned = word[:-2], i + 1
            pause = tidy[i][1]
        for part in _unfold(word, [w for w, _ in tidy[i:i + sp.longest]], sp, i == 1):
            if "-" in part or "_" in part:
                pieces = [p for p in re.split(r"[-_]+", part) if p]
                if pieces and (" ".join(pieces) in sp.spaced
                               or all(p in closed.RELATION_WORDS or p in FILLERS or p in sp.words for p in pieces)):
                    out.extend((p, i, raw) for p in pieces)
                    continue
                part = part.replace("-", "_")
            out.append((part, i, raw))
        if pause:
            out.append((",", i, raw))
    return out


def _tidy(raw: str, last: bool) -> tuple[str, bool]:
    """A typed word lower case, without quotes and end punctuation ("..." and "\u2026" alike),
    and whether a pause (",") follows it."""
    word = raw.lower().replace("\u2019", "'").replace("\u2026", "...").strip(_QUOTES)
    pause = False
    while word and word[-1] in _END + _PAUSE + _QUOTES:
        pause = pause or word[-1] in _PAUSE or (word[-1] in _END and not last)
        word = word[:-1].rstrip(_QUOTES)
    return word.lstrip(_QUOTES + _PAUSE), pause


def untagged(raw: list[tuple[str, int, str]], asked: bool) -> list[tuple[str, int, str]]:
    """The words without a question tag at the end ("..., right?", "..., isn't it?"), and a
    question that opens negated ("isn't the red box left of the blue cone?") as the plain one:
    it asks the same, expecting yes (it was "I did not expect 'isn't' (word 1) after 'isn't'")."""
    if asked and len(raw) > 2 and raw[0][0] in ("is", "are") and raw[1][0] == "not" and raw[0][1] == raw[1][1]:
        raw = [raw[0], *raw[2:]]
    words = tuple(w for w, _, _ in raw)
    for tag in sorted(_TAGS, key=len, reverse=True):
        if len(words) > len(tag) + 1 and words[-len(tag):] == tag and (asked or tag not in _ASKED_TAGS):
            raw = raw[:-len(tag)]
            while raw and raw[-1][0] == ",":
                raw = raw[:-1]
            return raw
    return raw


def asked(sentence: str) -> bool:
    """Does the sentence ask, though its words say it ("the red box is left of the blue cone?",
    "..., isn't it?")? A question is answered, never taught: such an inform taught what it
    asked (and "this is a wug?" created the word)."""
    if sentence.rstrip().endswith(("?", "？")):
        return True
    raw = raw_words(sentence)
    return len(untagged(raw, False)) < len(raw)


def _unfold(word: str, after: list[str], sp: Spellings, first: bool = False) -> list[str]:
    """A contraction's words ("isn't" -> is not, "where's" -> where is, "box's left of" -> box
    is left of: a noun's "'s" before a relation is "is"), and a possessive one word ("a hand's
    breadth from" -> "hands": a word of the teacher's own relation phrase, said back as typed;
    it was unreadable). `after`: the words typed after it, tidied; `first`: it opens the
    sentence, where "thats", "theres", "wheres" are "that's", "there's", "where's" (they were
    read as verbs: "'thats' is learned and checked from a demonstration")."""
    if not word:
        return []
    if word in _CONTRACTIONS:
        return list(_CONTRACTIONS[word])
    if word.endswith("n't"):
        return [word[:-3], "not"]
    if word.endswith("'s") and (word[:-2] in _IS_AFTER or _relation_starts(after, sp)):
        return [word[:-2], "is"]
    if first and word.endswith("s") and word[:-1] in _IS_AFTER - {"it"}:
        return [word[:-1], "is"]  # "thats a green box", "theres a box": "'s" typed without its "'"
    if word.endswith("'s") and WORD.fullmatch(word[:-2]):
        return [word[:-2] + "s"]
    if word.endswith("'re"):
        return [word[:-3], "are"]
    return [word]


def _relation_starts(after: list[str], sp: Spellings) -> bool:
    """Do the words start with a relation (a declared spelling, said with or without spaces,
    or a relation word of the closed class: "left of", "to the left of", "under")?"""
    if after and after[0] in closed.RELATION_WORDS:
        return True
    return any(" ".join(after[:k]) in sp.spaced or "".join(after[:k]) in sp.joined for k in range(1, len(after) + 1))
