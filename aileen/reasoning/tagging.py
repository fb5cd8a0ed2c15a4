"""A teacher's sentence as typed -> its words by role: the terminals `grammar.lark` parses.

Why apart from the grammar: the rules that read a sentence are in `grammar.lark` and
`grammar.py` runs them; what a grammar file cannot do is here, and it is most of the work
(the split keeps each module to one job):

* **the words, from the domain declarations.** Every declared spelling of a relation word
  (`relations.spellings()`: "left of", "left-of", "leftof", "to the left of", "beside") and
  the relation words of the closed class become one `REL` word whose value is the relation's
  word as the agent learns it (`left_of`); verbs come from `actions.VERBS` (every declared
  spelling is its verb's word) and `words.VERBS`; the function words from `words.py`, one
  terminal per role. A function word with no role in the grammar ("very", "what") is no
  property of the table: a sentence that holds one where no rule takes it is not read.
* **what needs the sentence around a word:** "one" before a word is a number, elsewhere a
  noun ("the red one"); the first word of a command is a verb when an article follows it
  ("shove the box ..."); an open-class word between two noun phrases is a relation ("the box
  touching the cone", "heavier than", "northeast of", "to the northeast of"), and so is an
  adverb with the relation after it ("diagonally behind": a word of its own); where no article
  says where a noun phrase ends, the reader's lexicon may ("red box zorp blue cone"); a
  misspelt relation ("lef of") is a slip, kept on the parse for the agent to ask about.
* **a sentence it cannot read** before any rule is tried (a word not of the letters a-z and digits,
  too long, empty): `NotUnderstood`, a `UserError` in the teacher's words.

What typing leaves untidy (quotes, end punctuation, contractions, a question tag, a
hyphenated relation) is tidied first, in `typed`.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

from aileen.domain import actions, relations
from aileen.domain import words as closed
from aileen.reasoning.spelling import one_edit
from aileen.reasoning.typed import (FILLERS, MAX_WORDS, WORD, NotUnderstood, Spellings, TooLong, numeral, raw_words,
                                    spellings, untagged)

__all__ = ["MAX_WORDS", "NotUnderstood", "TooLong", "Word", "version", "words_of"]


@dataclass(frozen=True)
class Word:
    """One word of the sentence as the grammar sees it: its role (`kind`, a terminal of
    grammar.lark), what it says (`value`: a relation's word joined with "_", a number's
    digits, a singular noun), where it stands (1-based, its first word) and what was typed."""

    kind: str
    value: str
    index: int
    text: str
    meant: str | None = None  # a slip's spelling ("lef of" said, "left of" meant)


# "on the left of", "right behind", "towards the left of": a relation's spelling after a word
# that adds nothing to it ("towards the left of" was a word of its own, "towards left of")
_PREPOSITIONS = frozenset({"on", "to", "at", "in", "right", "toward", "towards"})
_LOCATIVE_VERBS = frozenset({"sits", "sit", "lies", "lie", "stands", "stand"})
_PLURAL_KEEP = ("ss", "us", "is")
# a first word shorter than this before an article is no verb by syntax ("uh the box"; "go",
# "do" and the declared verbs are verbs by the closed class)
_SHORTEST_VERB = 3
# the roles a noun phrase ends with: a word, "it", "one" ("the red one", "that one")
_ENDS_PHRASE = frozenset({"WORD", "IT", "ONE"})  # "glass", "bus", "axis" are no plurals
_ROLE = {
    **{w: "DEF" for w in closed.DEFINITE}, **{w: "INDEF" for w in closed.INDEFINITE},
    **{w: "DEM" for w in closed.DEMONSTRATIVES}, **{w: "QUANT" for w in closed.QUANTIFIERS},
    **{w: "_COP" for w in closed.COPULAS}, **{w: "NOT" for w in closed.NEGATIONS},
    **{w: "_AND" for w in closed.CONJUNCTIONS}, **{w: "IT" for w in closed.PRONOUNS},
    **{w: "OTHER" for w in closed.OTHER}, **{w: "_THERE" for w in closed.EXISTENTIAL},
    **{w: "_WHERE" for w in closed.WHERE}, **{w: "_FRAME" for w in closed.FRAMING},
    **{w: "_MODAL" for w in closed.MODALS}, **{w: "_SO" for w in closed.PURPOSE}, "you": "_YOU",
}


def version() -> tuple[int, ...]:
    """Which declarations the words are read from (changes when a relation or a verb is declared)."""
    return (*relations.version(), actions.version())


def words_of(sentence: str, *, action: bool | None = None, verbs: frozenset[str] | None = None,
             as_said: frozenset[str] = frozenset(), heads: frozenset[str] = frozenset(),
             named: frozenset[str] = frozenset()) -> list[Word]:
    """The sentence's words by role (the terminals of grammar.lark). `action=True`: the first
    word (after "please", "could you") is a verb; False: never; None: by the closed class of
    verbs or an article after it. `as_said`: relation spellings (words joined with "_") the
    teacher has said are meant as said, not slips ("nleft of" is a word of its own, not
    "left of" mistyped). `heads` and `named`: what the reader has learned of noun phrases,
    the words it has heard only at a phrase's end ("box") and every word it has heard in one;
    a word it has never heard in one, after a head and before another phrase, is a relation
    ("red box zorp blue cone": with no article around it, nothing else in the sentence says
    where the first phrase ends)."""
    raw = untagged(raw_words(sentence), sentence.rstrip().endswith("?"))
    if not raw:
        raise NotUnderstood(f"I cannot read {sentence.strip()!r}: the sentence is empty")
    verbset = verbs if verbs is not None else _verbs()
    sp = spellings()
    raw = _once(raw)
    ws = [w for w, _, _ in raw]
    for w, i, typed in raw:
        if w != "," and not WORD.fullmatch(w) and not numeral(w):
            raise NotUnderstood(f"I cannot read {typed!r} (word {i} of {sentence.strip()!r}): "
                                f"I read words of the letters a-z and the digits 0-9, a letter first")
    out: list[Word] = []
    n = len(ws)
    i = 0
    lead = True  # still in the framing before the sentence proper ("please", "could you")
    while i < n:
        w, index, typed = raw[i]
        if w == ",":
            out.append(Word("_COMMA", w, index, typed))
            i += 1
            continue
        if (w == "to" and i + 4 < n and ws[i + 1] in closed.ARTICLES and _open(ws[i + 2], sp)
                and ws[i + 3] == "of" and _after_subject(out)):
            # "to the northeast of": a word of the teacher's own said as "to the left of" is
            out.append(Word("REL", f"{ws[i + 2]}_of", index, " ".join(t for _, _, t in raw[i:i + 4])))
            i += 4
            lead = False
            continue
        if ws[i] in closed.ARTICLES and _degree(ws, i) and _after_subject(out):
            # "a bit northwest of", "a little due north of": a degree before a relation of the
            # teacher's own, not a phrase of its own with "bit" in it (`_phrase_at` reads from
            # an article)
            if (own_of := _own_relation_of(ws, i, sp, out, heads, named)) is not None:
                k, word = own_of
                out.append(Word("REL", word, index, " ".join(t for _, _, t in raw[i:i + k])))
                i += k
                lead = False
                continue
            if (k := _degree_before_relation(ws, i, sp)) and _relation_at(ws, i + k, sp) is None:
                i += k  # before an adverb that makes the relation ("a bit diagonally behind");
                continue  # "a bit away from" stays a phrase of its own
        rel = _relation_at(ws, i, sp)
        if (_after_subject(out) and any(x.kind == "WORD" for x in out)  # a thing named before it
                and (own := _phrase_at(ws, i, sp)) is not None and (rel is None or own[0] > rel[0])):
            rel = own  # "within reach of", "a bit away from": a phrase of the teacher's own
        if rel is not None:
            k, word, slip = rel
            if slip is not None and "_".join(ws[i:i + k]) in as_said:
                word, slip = "_".join(ws[i:i + k]), None
            text = " ".join(dict.fromkeys(t for _, _, t in raw[i:i + k]))
            out.append(Word("REL", word.replace(" ", "_"), index, text, slip))
            i += k
            lead = False
            continue
        kind = _ROLE.get(w)
        nxt = ws[i + 1] if i + 1 < n else None
        if w in closed.LOCATIVES and not lead:
            # "sits left of" says what "is left of" says; "is located left of" what "is" does
            if w in _LOCATIVE_VERBS and not (out and out[-1].kind == "_COP"):
                out.append(Word("_COP", w, index, typed))
            i += 1
            continue
        if w in closed.LINKING and out and out[-1].kind in _ENDS_PHRASE:
            # "the box looks crimson", "the box seems to be red": what "is" says (an unknown
            # word after a head, "looks" was a relation, and "crimson" a word for the cone)
            out.append(Word("_COP", w, index, typed))
            i += 3 if ws[i + 1:i + 3] == ["to", "be"] else 1
            lead = False
            continue
        if w in closed.PARTICIPLES and i + 1 < n and out and (
                out[-1].kind == "_COP" or (out[-1].kind in _ENDS_PHRASE and any(x.kind == "_COP" for x in out))):
            i += 1  # "the box is coloured cherry": "is cherry"; "is the box painted red?"
            continue
        if (k := _degree_before_relation(ws, i, sp)):
            i += k  # "directly left of", "a bit left of": how exactly, not what
            continue
        if _after_subject(out) and (own_of := _own_relation_of(ws, i, sp, out, heads, named)) is not None:
            k, word = own_of  # "exactly northwest of", "due northwest of", "sharp northwest of"
            out.append(Word("REL", word, index, " ".join(t for _, _, t in raw[i:i + k])))
            i += k
            lead = False
            continue
        if lead and kind in ("_FRAME", "_MODAL", "_YOU"):
            out.append(Word(kind, w, index, typed))
            i += 1
            continue
        if lead and kind is None and action is not True and w not in verbset and w not in as_said:
            meant = _framing_slip(w)
            if meant is not None or (nxt == "," and w not in named and (_open(w, sp) or w in closed.LINKING) and i + 2 < n
                                     and ws[i + 2] in closed.ARTICLES | closed.DEMONSTRATIVES | closed.PRONOUNS):
                # "pleese the green box": a slip of "please", asked about; "look, a green box":
                # a word before a pause that opens the sentence (each was a verb, "learned and
                # checked from a demonstration", or "I see no 'look'")
                out.append(Word(_ROLE.get(meant or "", "_FRAME"), meant or w, index, typed, meant))
                i += 1
                continue
        first = lead
        lead = False
        if first and action is not False and kind is None and (
                action or w in verbset or (nxt in closed.ARTICLES and w not in closed.FUNCTION_WORDS
                                           and len(w) >= _SHORTEST_VERB)):  # not "uh the green box"
            out.append(Word("VERB", actions.verb_words().get(w, w), index, typed))  # a spelling: its verb
        elif first and action and kind is not None:
            raise NotUnderstood(f"I cannot read {sentence.strip()!r}: it should start with what to do "
                                f"(e.g. 'move'), not {typed!r}")
        elif w == "one":
            # a number before a word ("one red box"), but a noun after a word or a demonstrative
            # ("is the red one red?", "is that one blue?" read "that 1 blue": the blue thing)
            role = "NUM" if nxt is not None and _open(nxt, sp) and not (out and out[-1].kind in ("WORD", "DEM")) \
                else "ONE"
            out.append(Word(role, "1", index, typed) if role == "NUM" else Word("ONE", w, index, typed))
        elif w in closed.NUMBERS or numeral(w):
            out.append(Word("NUM", str(closed.NUMBERS.get(w, w)), index, typed))
        elif w in closed.DEMONSTRATIVES and w == "that" and out and out[-1].kind == "_SO":
            out.append(Word("_THAT", w, index, typed))
        elif (kind == "DEM" and w in ("this", "that") and len(out) == 1 and out[0].kind == "_COP" and i + 1 < n
              and all(x in named and x not in heads for x in ws[i + 1:])):
            # "is this blue?": what the last lesson grounded, as "is it blue?" (it read "the
            # blue thing": yes of a red box after "the red box"), where the reader knows every
            # word after it, none a head ("is this box red?" is about a box)
            out.append(Word("IT", w, index, typed))
        elif kind is not None:
            out.append(Word(kind, w, index, typed))
        elif w in closed.FUNCTION_WORDS or w in closed.RELATION_WORDS:
            out.append(Word("FUNC", w, index, typed))
        elif _between(out, nxt) and _phrase_at(ws, i + 1, sp) is None and w not in heads \
                and _relation_at(ws, i + 1, sp) is None and not _degree_before_relation(ws, i + 1, sp):
            # ("red box a short way from ...": a spelling; "red box a bit left of ...": a degree)
            # (not a head the reader knows: "is the red box a box?" read "box" as a relation)
            # an open-class relation word between two noun phrases: "the box touching the cone"
            # (not the head of a thing a teacher's phrase follows: "the green sphere a hand
            # apart from the cone")
            out.append(Word("REL", w, index, typed))
        elif (out and out[-1].kind == "WORD" and out[-1].value in heads and w not in named
              and nxt is not None and nxt != "," and _open(nxt, sp)):
            # the reader's lexicon ends the phrase at a word it knows as a head ("box"): the
            # new word after it, before another phrase, is a relation ("red box zorp blue cone")
            out.append(Word("REL", w, index, typed))
        elif nxt == "than" and out and out[-1].kind in ("WORD", "NOT") and i + 2 < n:
            out.append(Word("REL", f"{w}_than", index, f"{typed} {raw[i + 1][2]}"))
            i += 2
            continue
        elif nxt == "of" and _after_subject(out) and i + 2 < n and _relation_at(ws, i + 1, sp) in (None, (1, "of", None)):
            # a word of the teacher's own before "of": "northeast of", "kitty_corner of"; a
            # bare "of" is no relation, and the word is no property of the thing before it
            out.append(Word("REL", f"{w}_of", index, f"{typed} {raw[i + 1][2]}"))
            i += 2
            continue
        elif nxt in ("from", "with") and w not in heads and _after_subject(out) and i + 2 < n \
                and _relation_at(ws, i + 1, sp) in (None, (1, nxt, None)):
            # the same before "from" and "with": "apart from", "miles from", "flush with",
            # "level with" (they taught a property "apart" of the box and a relation "from")
            out.append(Word("REL", f"{w}_{nxt}", index, f"{typed} {raw[i + 1][2]}"))
            i += 2
            continue
        elif _adverb(w) and _after_subject(out) and (rel := _relation_at(ws, i + 1, sp)) is not None:
            # an adverb of the teacher's own before a relation: "diagonally behind" is a word of
            # its own (its grain is learned), not "behind" said of a "diagonally" box
            k, word, _ = rel
            text = " ".join(dict.fromkeys(t for _, _, t in raw[i:i + 1 + k]))
            out.append(Word("REL", f"{w}_{word.replace(' ', '_')}", index, text))
            i += 1 + k
            lead = False
            continue
        elif _possessive(typed, w):
            # "the box's lid": no reading of a possessive ("the box's colour" is the box's);
            # it asked "did you mean 'box'?" of a word "boxs" nobody typed, and learned it
            raise NotUnderstood(f"I cannot read {typed!r} (word {index} of {sentence.strip()!r}): I do not read "
                                f"what belongs to a thing; say what it is ('the {w[:-1]} is ...')")
        else:
            out.append(Word("WORD", w, index, typed))
        i += 1
    return _separators(out)


def _possessive(typed: str, word: str) -> bool:
    """Is `word` a possessive typed ("box's", "box’s," read "boxs"; not "box's" unfolded
    to "box" before a channel's name, nor "box is" before a relation)?"""
    said = typed.lower().replace("’", "'").rstrip(".,;:!?\"')")
    return said.endswith("'s") and word == said[:-2].lstrip("\"'(") + "s"


def _once(raw: list[tuple[str, int, str]]) -> list[tuple[str, int, str]]:
    """A word or a short phrase said twice in a row, once (`words.said_once`); the grammar's
    own words and commas stay as said."""
    return closed.said_once(raw, lambda r: r[0], lambda w: w == "," or w in _ROLE)


def _separators(words: list[Word]) -> list[Word]:
    """Commas around the sentence ("please, ...", "..., please", ", so that") are dropped; a
    run of commas and "and" between two parts is one separator: `_ALSO` before a relation
    ("X is left of A, and right of B"), else `_AND` ("A, B and C")."""
    start = next((k for k, w in enumerate(words) if w.kind not in ("_COMMA", "_FRAME", "_MODAL", "_YOU")), len(words))
    end = len(words)
    while end > start and words[end - 1].kind in ("_COMMA", "_FRAME"):
        end -= 1
    out: list[Word] = [w for w in words[:start] if w.kind != "_COMMA"]
    k = start
    while k < end:
        w = words[k]
        if w.kind not in ("_COMMA", "_AND"):
            out.append(w)
            k += 1
            continue
        j = k
        while j < end and words[j].kind in ("_COMMA", "_AND"):
            j += 1
        nxt = words[j].kind if j < end else None
        if nxt == "_SO" and all(x.kind == "_COMMA" for x in words[k:j]):
            k = j
            continue
        said = next((x for x in words[k:j] if x.kind == "_AND"), w)
        out.append(Word("_ALSO" if nxt in ("REL", "NOT") else "_AND", said.value, said.index, said.text))
        k = j
    out.extend(x for x in words[end:] if x.kind != "_COMMA")
    return out


def _framing_slip(word: str) -> str | None:
    """The framing word ("please", "thanks", "could") a sentence's first word is a slip of
    ("pleese", "plaese"), or None: a word of five letters or more, one edit from it."""
    if len(word) < 5:
        return None
    return next((f for f in sorted(closed.FRAMING | closed.MODALS) if len(f) >= 5 and one_edit(word, f)), None)


def _open(word: str, sp: Spellings) -> bool:
    """Is the word an open-class word (a property or a thing)?"""
    return word not in closed.CLOSED_CLASS and word not in sp.words and word != "," and not numeral(word)


def _own_relation_of(ws: list[str], i: int, sp: Spellings, out: list[Word], heads: frozenset[str],
                     named: frozenset[str]) -> tuple[int, str] | None:
    """A relation of the teacher's own of several words ending in "of", at word i after a
    thing: (words it takes, its word), or None. A degree word first says how exactly, not
    what, and is left out ("exactly northwest of" is "northwest of"); a compounding one is part
    of it ("due northwest of"); two open words are one relation where the phrase before ends
    at a word the reader knows as a head ("red box sharp northwest of": "box" ends the thing).
    One open word before "of" is read where it stands (`words_of`)."""
    parts: list[str] = []
    j, n = i, len(ws)
    lead = 0
    while j < n and ws[j] != "of" and j - i < 3 + max(lead, 1):
        w = ws[j]
        if not parts and not lead and (k := _degree(ws, j)):
            lead = k  # "exactly northwest of", "a bit northwest of"
            j += k
            continue
        if w in closed.COMPOUNDING or (_open(w, sp) and w not in named):
            parts.append(w)
        else:
            return None
        j += 1
    if j + 1 >= n or ws[j] != "of" or not parts or _relation_at(ws, j, sp) not in (None, (1, "of", None)):
        return None
    if not lead and len(parts) == 1:
        return None  # one word before "of": `words_of` reads it where it stands
    if not lead and parts[0] not in closed.COMPOUNDING and not (out and out[-1].kind == "WORD" and out[-1].value in heads):
        return None  # nothing says the thing before ended: "red box northwest of" has "box" in it
    return j + 1 - i, "_".join(parts) + "_of"


def _degree(ws: list[str], i: int) -> int:
    """How many words a degree word or phrase at word i takes ("directly": 1, "a bit": 2;
    `words.DEGREE`, `words.DEGREE_PHRASES`), 0 where none starts there."""
    if i < len(ws) and ws[i] in closed.DEGREE:
        return 1
    return max((len(p) for p in closed.DEGREE_PHRASES if tuple(ws[i:i + len(p)]) == p), default=0)


def _degree_before_relation(ws: list[str], i: int, sp: Spellings) -> int:
    """How many words a degree word or phrase at word i takes when a relation follows it
    ("directly left of": 1, "a bit left of": 2), or an adverb that makes a relation of the
    teacher's own with one ("slightly diagonally behind", "a bit due north of": they were not
    understood), else 0."""
    k = _degree(ws, i)
    if not k or i + k >= len(ws):
        return 0
    if _relation_at(ws, i + k, sp) is not None:
        return k
    return k if _adverb(ws[i + k]) and _relation_at(ws, i + k + 1, sp) is not None else 0


def _after_subject(out: list[Word]) -> bool:
    """Whether a relation may start here: after a noun phrase's word, "it" or "one", or after
    "is" / "not" that follow one ("the box is northeast of the cone", "is it dax of the cone?":
    after "it" it was unreadable where "is it left of" read)."""
    return bool(out) and (out[-1].kind in _ENDS_PHRASE or (out[-1].kind in ("_COP", "NOT") and len(out) > 1))


def _adverb(word: str) -> bool:
    """An adverb that makes a relation word of its own with the relation after it: "due"
    (`words.COMPOUNDING`), or an open-class one by its form ("diagonally", "partially"): -ly,
    and long enough not to be a noun such as "jelly" or "lily"."""
    return word in closed.COMPOUNDING or (len(word) >= 6 and word.endswith("ly"))


def _between(out: list[Word], nxt: str | None) -> bool:
    """An open-class word that follows a noun phrase's word (or "is") and stands before an
    article is a relation between two noun phrases ("the red box touching the green sphere")."""
    return nxt in closed.ARTICLES and _after_subject(out)


def _relation_at(ws: list[str], i: int, sp: Spellings) -> tuple[int, str, str | None] | None:
    """A relation phrase starting at word i: (words it takes, the relation's word, the
    spelling meant when the first word is a slip of it), or None.

    Two readings, the longer wins: a declared spelling, its words said with or without spaces
    ("to the left of", "leftof", "infront of"); or, as the earlier parser read it, a run of
    closed-class relation words with articles between them ("on the top of"), a leading "to"
    before an article dropped, and named by the declared spelling it is ("on the left of" is
    "left of") or else by its words ("under", "on_top_of" when nothing declares it)."""
    if i >= len(ws):  # nothing after ("red box slowly": an adverb ends the sentence)
        return None
    best: tuple[int, str, str | None] | None = None
    run = ""
    for k in range(1, min(sp.longest + 1, len(ws) - i + 1)):
        if ws[i + k - 1] == ",":
            break
        run += ws[i + k - 1]
        if run in sp.joined:
            best = (k, sp.joined[run], None)
    old = _closed_run(ws, i, sp)
    if old is not None and (best is None or old[0] > best[0]):
        best = old
    if best is None and _open(ws[i], sp) and len(ws[i]) >= 3:
        best = _slip(ws, i, sp)
    return best


def _closed_run(ws: list[str], i: int, sp: Spellings) -> tuple[int, str, None] | None:
    rw = closed.RELATION_WORDS
    n = len(ws)
    j = i
    if j + 2 < n and ws[j] == "to" and ws[j + 1] in closed.ARTICLES and ws[j + 2] in rw:
        j += 1  # "to the left of" says what "left of" says
    said: list[str] = []
    while j < n and (ws[j] in rw or (ws[j] in closed.ARTICLES and j + 1 < n and ws[j + 1] in rw)
                     or (said and ws[j] in FILLERS and _then_relation(ws, j + 1))):
        if ws[j] not in closed.ARTICLES and ws[j] not in FILLERS:
            said.append(ws[j])
        j += 1
    if not said:
        return None
    phrase = " ".join(said)
    if phrase in sp.spaced:
        return j - i, sp.spaced[phrase], None
    rest = " ".join(said[1:])
    if said[0] in _PREPOSITIONS and rest in sp.spaced:
        return j - i, sp.spaced[rest], None
    return j - i, "_".join(said), None


# The words that end a relation phrase before the thing it relates to ("within reach of the
# cone", "a bit away from the cone", "at a distance from the cone")
_PHRASE_ENDS = closed.PHRASE_ENDS
_PHRASE_LONGEST = 5


def _phrase_at(ws: list[str], i: int, sp: Spellings) -> tuple[int, str, None] | None:
    """A relation phrase of the teacher's own with open-class words inside it, starting at word
    i: it starts with a relation word or an article ("within reach of", "at a distance from",
    "a bit away from"), holds at least one open-class word, ends with "of", "from", "to" or
    "with", and a thing follows it (a word that is no verb, copula or conjunction). Named by
    its words less the articles ("within_reach_of"). Not when a declared spelling ends it ("a
    red box left of": the open words before "left of" are a noun phrase's), nor when it starts
    with an open-class word (a noun phrase's, or the rules for "northeast of")."""
    n = len(ws)
    if i >= n or not (ws[i] in closed.RELATION_WORDS or ws[i] in closed.ARTICLES):
        return None
    said: list[str] = []
    opened = False
    for j in range(i, min(n - 1, i + _PHRASE_LONGEST)):
        w = ws[j]
        if w in _PHRASE_ENDS and opened and j > i:
            nxt = ws[j + 1]
            if nxt in closed.COPULAS or nxt in closed.CONJUNCTIONS or nxt == "," or nxt in _verbs():
                return None
            tail = [x for x in ws[i:j + 1] if x not in closed.ARTICLES]
            if any(" ".join(tail[k:]) in sp.spaced for k in range(len(tail))):
                return None
            return j + 1 - i, "_".join([*said, w]), None
        if w in closed.ARTICLES:
            continue
        if j > i and any(ws[j:j + k] and "".join(ws[j:j + k]) in sp.joined for k in range(1, sp.longest + 1)):
            return None  # a declared relation starts inside: "the red box to the left of" is a thing, then it
        if _open(w, sp):
            opened = True
        elif w not in closed.RELATION_WORDS and w not in FILLERS:
            return None
        said.append(w)
    return None


def _then_relation(ws: list[str], j: int) -> bool:
    """Do fillers ("side", "hand") from word j lead on to a relation word?"""
    while j < len(ws) and ws[j] in FILLERS:
        j += 1
    return j < len(ws) and ws[j] in closed.RELATION_WORDS


def _slip(ws: list[str], i: int, sp: Spellings) -> tuple[int, str, str | None] | None:
    """"lef of", "rigth of": a word one edit from the first word of a declared spelling whose
    other words follow it as declared."""
    for length in range(sp.longest - 1, 0, -1):
        tail = tuple(ws[i + 1:i + 1 + length])
        if len(tail) < length:
            continue
        for first, word in sp.tails.get(tail, ()):
            if len(first) >= 3 and one_edit(ws[i], first):
                return length + 1, word, " ".join((first, *tail))
    return None


def _verbs() -> frozenset[str]:
    return _verbs_at(actions.version())


@functools.lru_cache(maxsize=4)
def _verbs_at(key: int) -> frozenset[str]:  # noqa: ARG001 - the action registry's version
    """The closed class's verbs and every spelling of a declared verb."""
    return closed.VERBS | frozenset(actions.verb_words())
