"""The teacher's grammar, read: a sentence as typed -> its words by role -> a parse tree.

Why a grammar file: what a trainer types ("is the red box left of the blue cone?", "please
move it so that it is behind the cone", "the red box and the green sphere are left of the
cone") is more than one phrase pattern, and each construction should be one readable,
editable rule, not a branch in code. The rules are `grammar.lark` (Lark's LALR parser: a
small pure-Python library), run here on the words `tagging.words_of` gives each its role
(what a grammar file cannot do: the words from the domain declarations, the roles that need
the sentence around a word, the reader's lexicon; see that module). `language` turns the
tree into a `Parse`, reading a plural head as its singular ("boxes" -> "box").

A sentence no rule reads: `NotUnderstood`, a `UserError` whose message says, in the
teacher's words, what could not be read and what was expected there (`_explain`).

Every sentence the earlier hand-written parser read (the lesson files, the original AILEEN's
scripts, the experiments' protocols) is read to the same references
(`tests/test_teacher_sentences.py` holds them to a record of that parser's readings).
"""

from __future__ import annotations

import functools
import re
from pathlib import Path

from lark import Lark, Token, Tree
from lark.exceptions import UnexpectedEOF, UnexpectedInput, UnexpectedToken
from lark.lexer import Lexer

from aileen.reasoning.tagging import MAX_WORDS, NotUnderstood, TooLong, Word, version, words_of

__all__ = ["GRAMMAR", "MAX_WORDS", "NotUnderstood", "TooLong", "Word", "read", "version", "words_of"]

GRAMMAR = Path(__file__).with_name("grammar.lark")

# terminals that start a noun phrase (what `_explain` offers as "a thing")
_NP_START = frozenset({"DEF", "INDEF", "DEM", "QUANT", "NUM", "ONE", "WORD", "IT", "OTHER"})


# ------------------------------------------------------------------ the parser


class _Words(Lexer):
    """Hands Lark the words already read (`words_of`)."""

    def __init__(self, lexer_conf) -> None:  # noqa: ANN001 - Lark's
        pass

    def lex(self, data):  # noqa: ANN001, ANN201 - Lark's (interface 0: the input as given)
        for w in data:
            yield Token(w.kind, w, start_pos=w.index, line=1, column=w.index)


@functools.lru_cache(maxsize=1)
def _parser() -> Lark:
    return Lark(GRAMMAR.read_text(), parser="lalr", lexer=_Words, propagate_positions=False,
                maybe_placeholders=False)


def read(sentence: str, *, action: bool | None = None, verbs: frozenset[str] | None = None,
         as_said: frozenset[str] = frozenset(), heads: frozenset[str] = frozenset(),
         named: frozenset[str] = frozenset()) -> tuple[Tree, list[Word]]:
    """The sentence's parse tree (grammar.lark) and its words; `NotUnderstood` when no rule
    reads it. `heads`, `named`: what the reader's lexicon knows (`words_of`)."""
    def words(text: str) -> list[Word]:
        return words_of(text, action=action, verbs=verbs, as_said=as_said, heads=heads, named=named)

    said = words(sentence)
    try:
        return _parser().parse(said), said
    except UnexpectedInput as exc:
        raise NotUnderstood(_explain(sentence.strip(), said, exc) + _two_lessons(sentence, words)) from None


_CLAUSE_AND = re.compile(r"\s*,?\s+and\s+", re.IGNORECASE)


def _two_lessons(sentence: str, words) -> str:  # noqa: ANN001 - words_of with read's arguments
    """A hint where the sentence is two the grammar reads, joined by "and" ("the red box is
    left of the blue cone and the blue cone is right of the red box"): a lesson is one
    sentence, and the trainer gives the two as two lessons. Empty otherwise."""
    for cut in _CLAUSE_AND.finditer(sentence):
        first, second = sentence[:cut.start()].strip(), sentence[cut.end():].strip()
        try:
            head = _parser().parse(words(first))
            _parser().parse(words(second))
        except (UnexpectedInput, NotUnderstood):
            continue
        if head.children and getattr(head.children[0], "data", None) == "where":
            # "where are the red box and the blue cone?": its second half is no question of where
            one = re.sub(r"^where\s+are\b", "where is", first.strip(), flags=re.IGNORECASE).rstrip("?")
            return f" (ask where one thing is at a time: {one + '?'!r})"
        return f" (it reads as two sentences: give {first!r} and {second!r} as two lessons)"
    return ""


# ------------------------------------------------------------------ what could not be read

_EXPECTED = [  # (terminals, how a teacher would say it), in the order offered
    (_NP_START, "a thing (e.g. 'the blue cone')"),
    (frozenset({"REL"}), "a relation (e.g. 'left of')"),
    (frozenset({"_COP"}), "'is' or 'are'"),
    (frozenset({"_AND"}), "'and'"),
    (frozenset({"VERB"}), "what to do (e.g. 'move')"),
    (frozenset({"$END"}), "the end of the sentence"),
]


def _explain(sentence: str, words: list[Word], exc: UnexpectedInput) -> str:
    """What could not be read and what was expected there, as a teacher would say it."""
    expected = set(getattr(exc, "expected", None) or ())
    stops = f"it stops after {_typed(words)!r} (word {len(sentence.split())})"
    if isinstance(exc, UnexpectedEOF):
        where, found = stops, None
    else:
        tok = exc.token if isinstance(exc, UnexpectedToken) else None
        at = next((k for k, w in enumerate(words) if tok is not None and w is tok.value), None)
        if at is None:  # the end of the sentence
            where, found = stops, None
        else:
            if words[at].value == "," and at + 1 < len(words):
                at += 1  # a pause read as "and" ("..., will you?"): what follows it was not expected
            w = words[at]
            found = w.text
            before = _typed([x for x in words[:at] if x.index != w.index])  # not "'isn't' after 'isn't'"
            where = (f"I did not expect {found!r} (word {w.index})" +
                     (f" after {before!r}" if before else " at the start"))
            if w.kind == "FUNC":
                where += f": '{w.value}' has no place in the sentences I read"
    wanted = [say for names, say in _EXPECTED if names & expected]
    if not wanted:
        wanted = ["a sentence such as 'the red box is left of the blue cone' or 'move the red box left of the blue cone'"]
    text = f"I could not read {sentence!r}: {where}"
    if found is not None or wanted:
        text += "; I expected " + _either(wanted)
    return text


def _typed(words: list[Word]) -> str:
    """The words as typed, each typed word once ("isn't" is two words of one typed word);
    a word typed twice is said twice ("the red box and the blue cone" lost its second "the")."""
    return " ".join(text for _index, text in dict.fromkeys((w.index, w.text) for w in words if w.kind != "_COMMA"))


def _either(items: list[str]) -> str:
    items = items[:4]
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " or " + items[-1]
