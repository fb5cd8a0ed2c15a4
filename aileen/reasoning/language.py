"""Lesson sentences -> references (object, relation, action), by syntax alone.

What a word *means* is learned (semantic memory maps words to concept symbols); this
parser only decides what *role* a word plays, from its position and a small closed class
of function words. The grammar (see docs/asp.md):

    sentence  := action | np [relation np]
    action    := verb np relation np
    np        := [article] content+
    relation  := relword+          (articles between relation words are dropped)

- `article` is one of `the a an`.
- `relword` is a closed class of spatial function words (prepositions and relational
  nouns/adverbs: `of to in on at behind left right front next near ...`, `RELATION_WORDS`).
- `content` is any other word: property and object-name words (colours, shapes, or words
  nobody taught yet). A function word of the closed class (`and`, `is`, `two`, `please`,
  ...: `FUNCTION_WORDS`) stands where it is said and is reported in `Parse.function_words`:
  the agent does not learn it as a concept.
- The closed class (articles, relation words, verbs, function words) is declared once, in
  `aileen.domain.words`.
- `verb`: the first word when it is followed by an article ("shove the red box ..."), or a
  member of the closed class `VERBS` ("move blue cone ..."), or the caller says the sentence
  is an action (`action=True`).
- A leading `to` before an article inside the relation is dropped: `to the left of` is
  `left_of`, as `left of` (`next to the box` keeps its `to`).
- A relation made of open-class words ("the red box touching the green sphere"): when the
  first noun phrase runs straight into an article, its last word is the relation.

The relation phrase becomes one word joined with underscores (`in front of` -> `in_front_of`);
an action's word is verb + relation (`move_right_of`), as the paper's per-verb+relation
action concepts (`r_move_right_of`), while the verb and relation stay available.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass

from aileen.domain import words as closed_class
from aileen.errors import UserError
from aileen.terms import Term, fn

__all__ = [
    "ARTICLES",
    "FUNCTION_WORDS",
    "MAX_WORDS",
    "RELATION_WORDS",
    "VERBS",
    "ObjectRef",
    "RelationRef",
    "ActionRef",
    "Parse",
    "parse",
]

# The closed class is declared once, in `aileen.domain.words`; the names stay importable here.
ARTICLES: frozenset[str] = closed_class.ARTICLES
RELATION_WORDS: frozenset[str] = closed_class.RELATION_WORDS
VERBS: frozenset[str] = closed_class.VERBS
FUNCTION_WORDS: frozenset[str] = closed_class.FUNCTION_WORDS

_WORD = re.compile(r"[a-z][a-z0-9_]*")
_TOKEN = re.compile(r"\S+")
_TRAILING = ".!?"
_RESERVED = frozenset({"not"})  # an ASP keyword, not a constant
#: Longest sentence accepted, in words: a trainer's sentence is a handful of words; past
#: this it is a mistake (a pasted file), and the per-lesson work should stay small.
MAX_WORDS = 200


@dataclass(frozen=True)
class ObjectRef:
    """A noun phrase: its property words in order (articles dropped)."""

    id: str
    words: tuple[str, ...]
    definite: bool = False

    @property
    def text(self) -> str:
        return " ".join(self.words)


@dataclass(frozen=True)
class RelationRef:
    """A relation phrase between two object references: `word(arg1, arg2)`."""

    id: str
    word: str
    arg1: str
    arg2: str


@dataclass(frozen=True)
class ActionRef:
    """`verb arg1 relation arg2` (`word` is the action concept's word, `move_right_of`), or
    `verb arg1` for a verb on one object (`push`; `relation` and `arg2` are None)."""

    id: str
    word: str
    verb: str
    relation: str | None
    arg1: str
    arg2: str | None = None

    @property
    def args(self) -> tuple[str, ...]:
        return (self.arg1,) if self.arg2 is None else (self.arg1, self.arg2)


@dataclass(frozen=True)
class Parse:
    """The references in one sentence; `facts()` is their ASP form for comprehension.lp."""

    sentence: str
    objects: tuple[ObjectRef, ...]
    relation: RelationRef | None = None
    action: ActionRef | None = None

    def object(self, ref_id: str) -> ObjectRef:
        for o in self.objects:
            if o.id == ref_id:
                return o
        raise KeyError(ref_id)

    @property
    def words(self) -> tuple[str, ...]:
        """Every word that needs a meaning, in sentence order, without repeats."""
        out: list[str] = []
        for o in self.objects:
            out.extend(o.words)
        if self.relation is not None:
            out.append(self.relation.word)
        if self.action is not None:
            out.append(self.action.word)
        return tuple(dict.fromkeys(out))

    @property
    def function_words(self) -> tuple[str, ...]:
        """The words of the sentence that are function words of the closed class (`and`,
        `is`, `please`): they carry grammar, not a property, and are never learned."""
        return tuple(w for w in self.words if closed_class.is_function_word(w))

    def facts(self) -> list[Term]:
        out: list[Term] = []
        for o in self.objects:
            out.append(fn("ref", o.id))
            out.extend(fn("ref_word", o.id, w) for w in o.words)
            if o.definite:
                out.append(fn("ref_definite", o.id))
        if self.relation is not None:
            r = self.relation
            out += [fn("rel_ref", r.id, r.arg1, r.arg2), fn("rel_word", r.id, r.word)]
        if self.action is not None:
            a = self.action
            out += [fn("act_ref", a.id, *a.args), fn("act_word", a.id, a.word), fn("act_verb", a.id, a.verb)]
            if a.relation is not None:
                out.append(fn("act_rel", a.id, a.relation))
        return out


@dataclass(frozen=True)
class _Tok:
    word: str
    index: int  # 1-based word position
    offset: int  # 0-based character offset


def _tokens(sentence: str) -> list[_Tok]:
    out: list[_Tok] = []
    matches = []
    for m in _TOKEN.finditer(sentence):
        matches.append(m)
        if len(matches) > MAX_WORDS:
            head = sentence[:40].strip()
            raise UserError(f"cannot parse {head!r}...: the sentence is longer than {MAX_WORDS} words")
    for i, m in enumerate(matches):
        raw = m.group()
        if i == len(matches) - 1:
            raw = raw.rstrip(_TRAILING)
            if not raw:
                continue
        word = raw.lower().replace("-", "_")
        if not _WORD.fullmatch(word) or word in _RESERVED:
            why = "is an ASP keyword" if word in _RESERVED else "is not a word (letters, digits, '_' or '-', starting with a letter)"
            raise UserError(f"cannot parse {sentence!r}: token {raw!r} at word {i + 1} (character {m.start() + 1}) {why}")
        out.append(_Tok(word, i + 1, m.start()))
    return out


def _error(sentence: str, toks: list[_Tok], i: int, expected: str) -> UserError:
    if i < len(toks):
        t = toks[i]
        return UserError(f"cannot parse {sentence!r}: expected {expected}, found {t.word!r} at word {t.index} (character {t.offset + 1})")
    return UserError(f"cannot parse {sentence!r}: expected {expected}, found the end of the sentence (word {len(toks) + 1})")


def parse(sentence: str, *, action: bool | None = None, verbs: Iterable[str] = VERBS) -> Parse:
    """Parse a lesson sentence; a sentence outside the grammar raises `UserError` naming the token.

    `action=True` forces the first word to be read as a verb, `False` forbids it, `None`
    decides by syntax (followed by an article) or the closed class `verbs`.
    """
    toks = _tokens(sentence)
    if not toks:
        raise UserError(f"cannot parse {sentence!r}: the sentence is empty")
    words = [t.word for t in toks]
    verbset = frozenset(verbs)
    i = 0
    verb: str | None = None
    first = words[0]
    is_verb = action
    if is_verb is None:
        is_verb = first not in ARTICLES and first not in RELATION_WORDS and (
            first in verbset or (len(words) > 1 and words[1] in ARTICLES)
        )
    if is_verb:
        if first in ARTICLES or first in RELATION_WORDS:
            raise _error(sentence, toks, 0, "a verb")
        verb = first
        i = 1

    def noun_phrase(i: int) -> tuple[list[str], bool, int]:
        definite = False
        if i < len(words) and words[i] in ARTICLES:
            definite = words[i] == "the"
            i += 1
        start = i
        while i < len(words) and words[i] not in ARTICLES and words[i] not in RELATION_WORDS:
            i += 1
        if i == start:
            raise _error(sentence, toks, i, "a noun phrase (a property or object word)")
        # A word said twice in one phrase ("red red box") is one word: repeating it adds
        # nothing to what the phrase says, so it must not count twice for learning.
        return list(dict.fromkeys(words[start:i])), definite, i

    np1, def1, i = noun_phrase(i)
    rel: list[str] = []
    if i < len(words):
        if words[i] in ARTICLES and len(np1) >= 2:
            # "the red box touching the green sphere": an open-class relation word.
            rel = [np1.pop()]
        elif words[i] == "than" and len(np1) >= 2:
            # a comparative: "the red box larger than the blue cone"
            rel = [np1.pop()]
        if (
            not rel
            and words[i] == "to"
            and i + 2 < len(words)
            and words[i + 1] in ARTICLES
            and words[i + 2] in RELATION_WORDS
        ):
            i += 1  # "to the left of" says what "left of" says
        while i < len(words) and (
            words[i] in RELATION_WORDS or (words[i] in ARTICLES and i + 1 < len(words) and words[i + 1] in RELATION_WORDS)
        ):
            if words[i] not in ARTICLES:
                rel.append(words[i])
            i += 1
        if not rel:
            raise _error(sentence, toks, i, "a relation phrase (e.g. 'left of') between two noun phrases")
    if not rel:
        r1 = ObjectRef("r1", tuple(np1), def1)
        if verb is not None:  # a verb on one object: "push the red box"
            return Parse(sentence, (r1,), action=ActionRef("a1", verb, verb, None, "r1"))
        return Parse(sentence, (r1,))
    np2, def2, i = noun_phrase(i)
    if i < len(words):
        raise _error(sentence, toks, i, "the end of the sentence (one relation per sentence)")
    r1, r2 = ObjectRef("r1", tuple(np1), def1), ObjectRef("r2", tuple(np2), def2)
    relword = "_".join(rel)
    if verb is not None:
        act = ActionRef("a1", f"{verb}_{relword}", verb, relword, "r1", "r2")
        return Parse(sentence, (r1, r2), action=act)
    return Parse(sentence, (r1, r2), relation=RelationRef("l1", relword, "r1", "r2"))
