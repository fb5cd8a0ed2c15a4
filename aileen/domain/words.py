"""The closed class of words: the words whose role the parser knows before any lesson.

Why here: the parser (`aileen.reasoning.language`) decides what role a word plays from its
position and a small closed class of words; everything else is an open-class word whose
meaning the agent learns. The closed class is a fact of the language the trainer speaks, not
of what any word means, so it is declared once, here, and read by the parser, by the agent
(which refuses to learn a function word) and by whoever builds a grammar on it.

- `ARTICLES` start a noun phrase and are dropped.
- `RELATION_WORDS` are the spatial function words (prepositions and relational nouns and
  adverbs) that make up a relation phrase (`left of`, `in front of`); the phrase, joined, is
  a word the agent learns (`left_of`), each piece alone is not.
- `VERBS` are the verbs the parser recognises without an article after them ("move blue cone
  ..."); the agent learns what they mean.
- `FUNCTION_WORDS` are the words that carry grammar, not a property of the table: articles,
  copulas and auxiliaries, conjunctions, pronouns and demonstratives, quantifiers, numbers,
  negation, question words and politeness words. The parser leaves them where they stand (a
  grammar may give them a role later); the agent never learns one as a concept ("red and
  box" does not make "and" a word for red boxes).

`CLOSED_CLASS` is all of them. Nothing here names a colour, a shape, a size or a relation's
meaning: those are learned.
"""

from __future__ import annotations

from collections.abc import Callable

__all__ = [
    "ANY_SHAPE", "ARTICLES", "CLOSED_CLASS", "CONJUNCTIONS", "COPULAS", "DEFINITE", "DEMONSTRATIVES", "EXISTENTIAL",
    "DEGREE", "DEGREE_PHRASES", "FRAMING", "COMPOUNDING", "FUNCTION_WORDS", "INDEFINITE", "LINKING", "LOCATIVES", "MODALS", "NEGATIONS", "NUMBERS", "OTHER", "PARTICIPLES", "PHRASE_ENDS", "PLURAL_DETERMINERS",
    "PRONOUNS", "PURPOSE", "QUANTIFIERS", "RELATION_WORDS", "SLIPPED", "VERBS", "WHERE", "is_function_word",
]

ARTICLES: frozenset[str] = frozenset({"the", "a", "an"})

RELATION_WORDS: frozenset[str] = frozenset(
    """
    of to in on at by from with into onto over under below above behind beside besides than
    between near far close next front back left right top bottom inside outside within
    across against along around beyond beneath underneath toward towards away ahead
    north south east west up down off out past upon
    """.split()
)

# The relation words that end a relation phrase before the thing it relates to ("left of",
# "apart from", "next to", "level with"): alone they name no relation ("the blue sphere of the
# red box" taught a spatial word "of"), so a relation word that is one of them is not learned.
PHRASE_ENDS: frozenset[str] = frozenset({"of", "from", "to", "with"})

VERBS: frozenset[str] = frozenset({"move", "put", "place", "push", "bring", "set", "take", "slide", "shift"})

_COPULAS_AND_AUXILIARIES = """
    is are was were be been being am isn aren wasn weren
    do does did done has have had can could will would shall should may might must
"""
_CONJUNCTIONS = "and or but nor yet so either neither both also then"
_PRONOUNS_AND_DEMONSTRATIVES = """
    it its this that these those there here they them their he she him her his i me my
    we us our you your one ones
"""
_QUANTIFIERS = "all any some every each no none other another such only just very"
_NUMBERS = """
    zero two three four five six seven eight nine ten eleven twelve thirteen fourteen fifteen
    sixteen seventeen eighteen nineteen twenty thirty forty fifty sixty seventy eighty ninety
    hundred thousand dozen first second third
"""  # "one" is a pronoun above ("the red one") and a number (NUMBERS below)
_NEGATION = "no not nothing never"
_QUESTION_WORDS = "what which who whom whose where when why how whether if"
_POLITENESS = "please thanks thank ok okay yes hello hi hey sorry well now kindly"
_ADVERBS = "really too quite again as same rather fairly still even already always"
_MANNER = """
    sits sit lies lie stands stand located placed positioned situated sitting lying standing
    directly exactly immediately slightly somewhat roughly approximately straight more further somewhere
    correct
"""  # locatives and degree words (below); "correct" as a tag ("..., correct?")
_LINKING = "looks look seems seem appears appear"  # LINKING below
_PARTICIPLES = "coloured colored painted"  # PARTICIPLES below

FUNCTION_WORDS: frozenset[str] = ARTICLES | frozenset(
    " ".join((_COPULAS_AND_AUXILIARIES, _CONJUNCTIONS, _PRONOUNS_AND_DEMONSTRATIVES, _QUANTIFIERS,
              _NUMBERS, _NEGATION, _QUESTION_WORDS, _POLITENESS, _ADVERBS, _MANNER, _LINKING, _PARTICIPLES)).split()
)

CLOSED_CLASS: frozenset[str] = FUNCTION_WORDS | RELATION_WORDS | VERBS

# ------------------------------------------------------------------ roles in the grammar
# The function words the teacher's grammar (`aileen/reasoning/grammar.lark`) gives a role,
# by role. Each is a subset of FUNCTION_WORDS (a test holds them so): a word said in the
# sentence with no role here is read as a mistake, never as a property of the table.
DEFINITE: frozenset[str] = frozenset({"the"})
INDEFINITE: frozenset[str] = frozenset({"a", "an"})
# "this box", "that one", "these boxes": definite, as "the"
DEMONSTRATIVES: frozenset[str] = frozenset({"this", "that", "these", "those"})
# "some boxes", "every box": how many of the things named the sentence is about
QUANTIFIERS: frozenset[str] = frozenset({"some", "any", "every", "each", "all", "both"})
# determiners that say the noun phrase names several things
PLURAL_DETERMINERS: frozenset[str] = frozenset({"these", "those", "all", "both"})
NUMBERS: dict[str, int] = {
    "one": 1, "two": 2, "three": 3, "four": 4, "five": 5, "six": 6, "seven": 7, "eight": 8,
    "nine": 9, "ten": 10, "eleven": 11, "twelve": 12, "thirteen": 13, "fourteen": 14, "fifteen": 15,
    "sixteen": 16, "seventeen": 17, "eighteen": 18, "nineteen": 19, "twenty": 20, "zero": 0,
    "thirty": 30, "forty": 40, "fifty": 50, "sixty": 60, "seventy": 70, "eighty": 80, "ninety": 90,
    "hundred": 100, "thousand": 1000, "dozen": 12,
}
COPULAS: frozenset[str] = frozenset({"is", "are"})
NEGATIONS: frozenset[str] = frozenset({"not"})
CONJUNCTIONS: frozenset[str] = frozenset({"and"})
# "it" and "that one" refer to what the last lesson grounded; "the other one" to the other
PRONOUNS: frozenset[str] = frozenset({"it"})
OTHER: frozenset[str] = frozenset({"other", "another"})
EXISTENTIAL: frozenset[str] = frozenset({"there"})
WHERE: frozenset[str] = frozenset({"where"})
# words around a command or a sentence that carry no content: "please", "now", "could you"
FRAMING: frozenset[str] = frozenset({"please", "now", "then", "ok", "okay", "well", "just", "hey", "hi",
                                     "hello", "thanks"})
MODALS: frozenset[str] = frozenset({"can", "could", "would", "will"})
# "move the red box so that it is left of the blue cone"
PURPOSE: frozenset[str] = frozenset({"so"})
# Verbs that say where a thing is, as "is" does: "the box sits left of the cone", "the box is
# placed left of the cone" (after "is" too)
LOCATIVES: frozenset[str] = frozenset({"sits", "sit", "lies", "lie", "stands", "stand", "located", "placed",
                                       "positioned", "situated", "sitting", "lying", "standing"})
# Verbs that link a thing to what it is, as "is" does: "the box looks crimson", "the box seems
# to be red" say what "the box is crimson" says (read as an unknown word between two things,
# "looks" was learned as a relation and "crimson" as a word for the cone)
LINKING: frozenset[str] = frozenset(_LINKING.split())
# Participles after a copula that say only how the property is had: "the box is coloured
# cherry", "painted crimson" say "the box is cherry" (each was learned as a word, r_coloured)
PARTICIPLES: frozenset[str] = frozenset(_PARTICIPLES.split())
# Words before a relation that say how exactly it holds, not what: "directly left of"
DEGREE: frozenset[str] = frozenset({"directly", "exactly", "immediately", "just", "slightly", "somewhat",
                                    "roughly", "approximately", "straight", "more", "further", "somewhere"})
# Phrases of several words that say what a degree word says, read as one before a relation:
# "a bit left of" is "slightly left of" ("a" was read as an article, and the sentence was not
# understood)
DEGREE_PHRASES: frozenset[tuple[str, ...]] = frozenset({("a", "bit"), ("a", "little"), ("a", "little", "bit"),
                                                         ("a", "tad")})

# The most frequent function words, whose slips a trainer types most ("th", "thee", "annd"):
# a new word that is one of them with a letter left out or typed twice is asked about
# (`reasoning.spelling.slip_of`), as a swap of any closed-class word is
SLIPPED: frozenset[str] = ARTICLES | frozenset({"and"})

# Nouns that name no shape: "red object" is any red thing (the trainer's sentence reader and
# the agent's: "the object is a box" is about the thing, never a word "object" learned), so no
# channel value or verb may be one
ANY_SHAPE: frozenset[str] = frozenset({"object", "thing", "something", "item"})

# Words before a relation that make a word of their own with it, as an adverb in -ly does
# ("due west of", "diagonally behind"): the compound's grain is learned, not the relation's
COMPOUNDING: frozenset[str] = frozenset({"due"})


def is_function_word(word: str) -> bool:
    """A word that carries grammar, not a property of the table: never learned as a concept
    (a preposition that ends a relation phrase, `PHRASE_ENDS`, said alone as the relation,
    neither)."""
    return word in FUNCTION_WORDS or word in PHRASE_ENDS


def said_once(items: list, word: Callable[[object], str], kept: Callable[[str], bool]) -> list:
    """`items` with a word said twice in a row said once ("in front of of", "red red box"), and
    a phrase of two or three words ("left of left of"): a stutter or a slip of the keyboard,
    not a word of its own. `word` reads an item's word; words `kept` stay as said (the agent's
    grammar words: "the the" is a sentence that does not read, and the reader says where).
    The agent's reader and the trainer's read a sentence so alike."""
    out = [x for k, x in enumerate(items) if k == 0 or word(x) != word(items[k - 1]) or kept(word(x))]
    for n in (3, 2):
        k = 0
        while k + 2 * n <= len(out):
            first, again = [word(x) for x in out[k:k + n]], [word(x) for x in out[k + n:k + 2 * n]]
            if first == again and not any(kept(w) for w in first):
                del out[k + n:k + 2 * n]
                continue
            k += 1
    return out
