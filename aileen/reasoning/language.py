"""Lesson sentences -> references (object, relation, action): what each word's role is.

What a word *means* is learned (semantic memory maps words to concept symbols); this module
only decides what *role* a word plays. The teacher's grammar is a rule file,
`grammar.lark`, read by `aileen.reasoning.grammar` with the words of the domain declarations
(relation spellings, verbs, the closed class of function words); this module turns its tree
into a `Parse`. It reads (docs/lessons.md, "What the agent reads"):

- noun phrases: `[det] [other] [number] word+ [one]` ("the red box", "two boxes", "the red
  one"), "it", "that one", "the other one"; a plural head is read singular ("boxes" ->
  `box`, `ObjectRef.plural`);
- statements: `X [is|are] [not] REL Y [and [not] REL Z]`, with "A and B" for X or Y, "X is
  red", "this is a red box", "there is a red box", or a noun phrase alone ("red box");
- questions: "is X REL Y?", "is X red?", "is it a red box?", "is there a X?", "are there two
  X?", and "where is X?";
- commands: `[please|now|could you] VERB X [REL Y] [so that it is REL Y]`.

A relation phrase becomes one word joined with underscores (`in front of` -> `in_front_of`;
every declared spelling of a relation, "left-of", "to the left of", "leftof", is its word);
an action's word is verb + relation (`move_right_of`), as the paper's per-verb+relation
action concepts (`r_move_right_of`), while the verb and relation stay available. A sentence
no rule reads raises `NotUnderstood` (a `UserError`), its message in the teacher's words.
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Iterable
from dataclasses import dataclass, field

from lark import Tree

from aileen.domain import words as closed_class
from aileen.reasoning import grammar, typed
from aileen.reasoning.grammar import MAX_WORDS, NotUnderstood, TooLong
from aileen.reasoning.typed import general
from aileen.terms import Term, fn

__all__ = [
    "ARTICLES",
    "FUNCTION_WORDS",
    "MAX_WORDS",
    "MOODS",
    "RELATION_WORDS",
    "VERBS",
    "NotUnderstood",
    "TooLong",
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
#: What a sentence does: says something (inform teaches it, verify checks it), asks a yes/no
#: question (checked, never taught), asks where something is, or asks for an action.
MOODS: tuple[str, ...] = ("statement", "question", "where", "command")


def property_said(word: str) -> str:
    """A property word as the teacher typed it: one word, so an underscore in it was a hyphen
    ("blue-cone", read `blue_cone` because a clingo name has no hyphen), not the space a
    relation's underscore stands for ("left_of")."""
    return word.replace("_", "-")


@dataclass(frozen=True)
class ObjectRef:
    """A noun phrase: its property words in order (articles dropped), and how many things it
    names: `definite` ("the", "this"), `count` (a number said: "two boxes", "one red box"),
    `plural` ("boxes", "these", "two"), `quantifier` ("every", "all", "some", "any", "each",
    "both"). `anaphor` is "it" ("it", "that one") or "other" ("the other one"): what an
    earlier lesson grounded, not a description (its words may narrow it: "it is a red box")."""

    id: str
    words: tuple[str, ...]
    definite: bool = False
    count: int | None = None
    plural: bool = False
    anaphor: str | None = None
    quantifier: str | None = None
    # the head as said, when only its ending made the phrase plural ("klos", read "klo": no
    # number, no "these"): a word of the teacher's own said of one thing may end so
    by_ending: str | None = None
    # "a red box", "one red box": any one that fits will do (an action takes one of several)
    indefinite: bool = False
    # the words said *of* the thing, not to find it ("every box is red", "is the box red?",
    # "is the cone a box?": red, red, box): also among `words` (an inform learns them of what
    # it names), while a verify finds the thing by the others and asks it of each it names
    # (`subject`); `attribute` is how it was said ("red", "a box")
    said_of: tuple[str, ...] = ()
    attribute: str = ""

    @property
    def subject(self) -> tuple[str, ...]:
        """The words that find the thing: `words` less those said of it ("box" of "every box is red")."""
        return tuple(w for w in self.words if w not in self.said_of)

    @property
    def text(self) -> str:
        if self.anaphor is not None and not self.words:
            return "it" if self.anaphor == "it" else "the other one"
        if not self.words:  # "the object", "something": a thing, no word said of it (it said "[ = o1]")
            return "thing"
        return " ".join(map(property_said, self.words))

    @property
    def said(self) -> str:
        """The phrase as the teacher would say it back ("the red box", "two boxes", "it")."""
        if self.anaphor is not None and not self.words:
            return self.text
        head = " ".join(map(property_said, self.words)) if self.words else "one"
        if self.count is not None and self.count != 1:
            return f"{self.count} {plural(head)}"
        if self.plural:
            head = plural(head)
        return f"the {head}" if self.definite else head


@dataclass(frozen=True)
class RelationRef:
    """A relation phrase between two object references: `word(arg1, arg2)`; `negated` for
    "X is not REL Y"."""

    id: str
    word: str
    arg1: str
    arg2: str
    negated: bool = False
    said: str | None = field(default=None, compare=False)  # as typed ("touching" for next_to), for answers

    @property
    def spoken(self) -> str:
        """The relation's word ("right of", also for "to the right of"), or what the teacher
        said where that is another word for it ("touching" for next to)."""
        word = self.word.replace("_", " ")
        return word if not self.said or word in self.said.lower() else self.said


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
    """The references in one sentence; `facts()` is their ASP form for comprehension.lp.

    `relation` is the sentence's first relation (the only one in most sentences), `relations`
    all of them ("A and B are left of C" has two); `mood` is one of `MOODS`; `slips` are
    relation spellings and framing words said with a slip, (said, meant): "lef of" for "left
    of", "pleese" for "please"."""

    sentence: str
    objects: tuple[ObjectRef, ...]
    relation: RelationRef | None = None
    action: ActionRef | None = None
    relations: tuple[RelationRef, ...] = ()
    mood: str = "statement"
    slips: tuple[tuple[str, str], ...] = field(default=())

    def __post_init__(self) -> None:
        if not self.relations and self.relation is not None:
            object.__setattr__(self, "relations", (self.relation,))
        elif self.relations and self.relation is None:
            object.__setattr__(self, "relation", self.relations[0])

    def object(self, ref_id: str) -> ObjectRef:
        for o in self.objects:
            if o.id == ref_id:
                return o
        raise KeyError(ref_id)

    def relation_ref(self, ref_id: str) -> RelationRef:
        for r in self.relations:
            if r.id == ref_id:
                return r
        raise KeyError(ref_id)

    @property
    def words(self) -> tuple[str, ...]:
        """Every word that needs a meaning, in sentence order, without repeats."""
        out: list[str] = []
        for o in self.objects:
            out.extend(o.words)
        out.extend(r.word for r in self.relations)
        if self.action is not None:
            out.append(self.action.word)
        return tuple(dict.fromkeys(out))

    @property
    def function_words(self) -> tuple[str, ...]:
        """The words that need a meaning and are function words of the closed class (`and`,
        `is`, `please`): they carry grammar, not a property, and are never learned. The
        grammar gives each function word its role, so none stands where a property does."""
        return tuple(w for w in self.words if closed_class.is_function_word(w))

    @property
    def asks(self) -> bool:
        """Is the sentence a question (checked, never taught)?"""
        return self.mood in ("question", "where")

    def subjects(self) -> "Parse":
        """The sentence with each thing found by its subject's words alone ("every box is
        red": every box), nothing said of it: what a verify asks the attribute of."""
        objects = tuple(dataclasses.replace(o, words=o.subject, said_of=(), attribute="") if o.said_of else o
                        for o in self.objects)
        return dataclasses.replace(self, objects=objects)

    def facts(self) -> list[Term]:
        out: list[Term] = []
        for o in self.objects:
            out.append(fn("ref", o.id))
            out.extend(fn("ref_word", o.id, w) for w in o.words)
            if o.definite:
                out.append(fn("ref_definite", o.id))
        for r in self.relations:
            out += [fn("rel_ref", r.id, r.arg1, r.arg2), fn("rel_word", r.id, r.word)]
        if self.action is not None:
            a = self.action
            out += [fn("act_ref", a.id, *a.args), fn("act_word", a.id, a.word), fn("act_verb", a.id, a.verb)]
            if a.relation is not None:
                out.append(fn("act_rel", a.id, a.relation))
        return out


def parse(sentence: str, *, action: bool | None = None, verbs: Iterable[str] | None = None,
          as_said: Iterable[str] = (), heads: Iterable[str] = (), named: Iterable[str] = ()) -> Parse:
    """Read a lesson sentence; one no rule of the grammar reads raises `NotUnderstood` (a
    `UserError`) saying what could not be read and what was expected there.

    `action=True` reads the first word (after "please", "could you") as a verb, `False` never,
    `None` by syntax (an article after it) or the closed class `verbs` (default: the declared
    verbs and `VERBS`). `as_said`: relation spellings the teacher has said are meant as
    said (`grammar.words_of`), read as words of their own instead of slips. `heads`, `named`:
    the reader's lexicon, the words it has heard only ending a noun phrase and every word it
    has heard in one (`grammar.words_of`: where a phrase ends when no article says so).
    """
    verbset = frozenset(verbs) if verbs is not None else None
    said = frozenset(as_said)
    lex = (frozenset(heads), frozenset(named))
    if len(sentence) > _CACHED_CHARACTERS:  # a pasted file is refused after 200 words, not hashed whole
        return _parse.__wrapped__(sentence, action, verbset, grammar.version(), said, lex)
    return _parse(sentence, action, verbset, grammar.version(), said, lex)


_CACHED_CHARACTERS = 4096


@functools.lru_cache(maxsize=256)
def _parse(sentence: str, action: bool | None, verbs: frozenset[str] | None,
           version: tuple[int, ...], as_said: frozenset[str] = frozenset(),
           lexicon: tuple[frozenset[str], frozenset[str]] = (frozenset(), frozenset())) -> Parse:  # noqa: ARG001
    """Read once: a lesson reads its sentence more than once (the agent's signals, the trainer's
    checks), and a `Parse` never changes. `version` is the registries' (relation spellings, verbs)."""
    tree, words = grammar.read(sentence, action=action, verbs=verbs, as_said=as_said, heads=lexicon[0],
                               named=lexicon[1])
    return _Reading(sentence, words, lexicon[0], as_said, lexicon[1]).parse(tree)


# ------------------------------------------------------------------ the grammar's tree, read


class _Reading:
    """The tree of grammar.lark -> a `Parse`: one method per rule that makes a sentence."""

    def __init__(self, sentence: str, words: list[grammar.Word], heads: frozenset[str] = frozenset(),
                 as_said: frozenset[str] = frozenset(), named: frozenset[str] = frozenset()) -> None:
        self.sentence = sentence
        self.heads = heads
        self.named = named  # every word the reader has heard in a noun phrase
        self.as_said = as_said  # words meant as said: a head among them is not read as a plural
        self.objects: list[ObjectRef] = []
        self.relations: list[RelationRef] = []
        self.slips = tuple((w.text, w.meant) for w in words if w.meant is not None)

    def parse(self, tree) -> Parse:  # noqa: ANN001 - a lark Tree
        clause = tree.children[0]
        kind = clause.data
        if kind == "command":
            return self._command(clause)
        if kind == "where":
            self._np(clause.children[0])
            return self._made("where")
        mood = "question" if kind.startswith("ask") or typed.asked(self.sentence) else "statement"
        kids = clause.children
        if kind in ("say", "ask"):
            said_of = self._said_after(kids[1])
            subjects = self._nps(kids[0])
            if said_of:
                self._said_of(subjects, said_of, " ".join(map(property_said, said_of)))
            for pred in kids[1].children:
                negated = pred.children[0].type == "NOT" if _is_token(pred.children[0]) else False
                rel = pred.children[1 if negated else 0].value
                objects = self._nps(pred.children[-1])
                for s in subjects:
                    for o in objects:
                        self.relations.append(RelationRef(f"l{len(self.relations) + 1}", rel.value, s, o, negated,
                                                          said=rel.text))
            self._it_said_before()
        elif kind in ("say_thing", "ask_thing", "say_there", "ask_there"):
            more = self._more_said(kids[-1]) if kind == "ask_thing" else ()
            ids = self._nps(kids[-1])
            if kind == "ask_thing":
                self._predicate_before_head(ids)
                first = self.objects[0]
                if more and first.said_of:  # "is the box green and blue?"
                    self.objects[0] = dataclasses.replace(first, words=first.subject, said_of=())
                    self._said_of([first.id], (*first.said_of, *more), " and ".join((first.attribute, *more)))
        elif kind in ("say_attribute", "ask_attribute"):
            noun = (any(_is_token(k) and k.type in ("INDEF", "DEF") for k in kids)  # "a box": a head,
                    and not any(_is_token(k) and k.type == "ONE" for k in kids[-1].children))  # not "a red one"
            self._attribute(kids[0], kids[-1], noun=noun)
        else:  # pragma: no cover - a rule added to grammar.lark without its reading here
            raise NotUnderstood(f"I have no reading for the rule {kind!r} of the grammar")
        return self._made(mood)

    def _made(self, mood: str, action: ActionRef | None = None) -> Parse:
        return Parse(self.sentence, tuple(self.objects), action=action, relations=tuple(self.relations),
                     mood=mood, slips=self.slips)

    def _command(self, clause) -> Parse:  # noqa: ANN001
        kids = clause.children
        verb = kids[0].value.value
        mover = self._np(kids[1])
        relation: str | None = None
        reference: str | None = None
        rest = kids[2:]
        if rest and _is_token(rest[0]) and rest[0].type == "REL":
            relation, reference = rest[0].value.value, self._np(rest[1])
            rest = rest[2:]
        if rest and not _is_token(rest[0]) and rest[0].data == "purpose" and relation is None:
            # "so that it is left of the cone": the mover (said again, or "it") ends up there
            purpose = rest[0].children
            relation, reference = purpose[-2].value.value, self._np(purpose[-1])
        if relation is None:
            return self._made("command", ActionRef("a1", verb, verb, None, mover))
        assert reference is not None
        return self._made("command", ActionRef("a1", f"{verb}_{relation}", verb, relation, mover, reference))

    def _it_said_before(self) -> None:
        """"the red box is left of the blue cone, not right of it": an "it" after a thing named
        in the same sentence is that thing, as a person reads it: the nearest one before it
        that is not what the relation relates it to (it was found among what the last lesson
        grounded: the sphere of the lesson before). The "it" takes the thing's words, so that
        it is found as the thing is."""
        for k, ref in enumerate(self.objects):
            if ref.anaphor != "it" or ref.words:
                continue
            others = {r.arg1 if r.arg2 == ref.id else r.arg2 for r in self.relations if ref.id in (r.arg1, r.arg2)}
            before = [o for o in self.objects[:k] if o.anaphor is None and o.words and o.id not in others]
            if before:
                self.objects[k] = dataclasses.replace(before[-1], id=ref.id)

    def _said_after(self, preds) -> tuple[str, ...]:  # noqa: ANN001
        """Words said of the subject after its relation, taken off the relation's last thing:
        "the box is left of the cone and red" (read as a thing "red": "'left of' does not
        hold"), "is the box left of the cone red?" ("I see no 'cone red'"). The reader's
        lexicon says so: words it knows, none of them a head, after a head or "and"."""
        if not self.heads:
            return ()
        nps = preds.children[-1].children[-1]
        last = nps.children[-1]
        inner = last.children[0] if last.data == "np" else last
        if inner.data != "things":
            return ()
        toks = inner.children
        words = [t.value.value for t in toks if _is_token(t) and t.type == "WORD"]
        if len(nps.children) > 1 and len(toks) == len(words) and not any(w in self.heads for w in words) \
                and all(w in self.named for w in words):
            nps.children.pop()  # "... and red"
            return tuple(words)
        k = max((i for i, t in enumerate(toks) if _is_token(t) and t.type == "WORD" and t.value.value in self.heads),
                default=None)
        after = toks[k + 1:] if k is not None else []
        if after and all(_is_token(t) and t.type == "WORD" and t.value.value in self.named
                         and t.value.value not in self.heads for t in after):
            del inner.children[k + 1:]  # "the cone red"
            return tuple(t.value.value for t in after)
        return ()

    def _more_said(self, nps) -> tuple[str, ...]:  # noqa: ANN001
        """"is the box green and blue?": the bare words after the first thing, known to the
        reader and none a head, are said of it too (taken off `nps`; they were things of their
        own, "blue" any blue thing)."""
        rest = nps.children[1:]
        words: list[str] = []
        for np in rest:
            inner = np.children[0] if np.data == "np" else np
            toks = inner.children
            said = [t.value.value for t in toks if _is_token(t) and t.type == "WORD"]
            if inner.data != "things" or len(said) != len(toks) or not all(
                    w in self.named and w not in self.heads for w in said):
                return ()
            words += said
        del nps.children[1:]
        return tuple(words)

    def _said_of(self, ids: list[str], said: tuple[str, ...], attribute: str) -> None:
        """The subjects `ids` with `said` said of them (`ObjectRef.said_of`), as `attribute`."""
        for k, ref in enumerate(self.objects):
            if ref.id in ids:
                of = tuple(w for w in said if w not in ref.words)
                self.objects[k] = dataclasses.replace(ref, words=tuple(dict.fromkeys((*said, *ref.words))),
                                                      said_of=of if ref.anaphor is None and ref.words else (),
                                                      attribute=attribute)

    def _predicate_before_head(self, ids: list[str]) -> None:
        """"is the box red?": the words after a known head are said of the thing, and stand
        before the head as a person would put them ("red box"; the answer said "box red").
        A plural head is one too ("are the boxes red?": "I do not know the word 'boxes'")."""
        for k, ref in enumerate(self.objects):
            if ref.id not in ids or len(ref.words) < 2 or ref.words[-1] in self.heads:
                continue
            w = ref.words
            last = max((i for i, x in enumerate(w[:-1]) if x in self.heads), default=None)
            plural = False
            if last is None:
                last = max((i for i, x in enumerate(w[:-1]) if x not in self.as_said and singular(x)[1]), default=None)
                plural = last is not None
            if last is not None:
                head = singular(w[last])[0] if plural else w[last]
                said = w[last + 1:]
                self.objects[k] = dataclasses.replace(
                    ref, words=tuple(dict.fromkeys(w[:last] + said + (head,))), said_of=said,
                    attribute=" ".join(map(property_said, said)),
                    plural=ref.plural or (plural and ref.count != 1), by_ending=None)

    def _nps(self, tree) -> list[str]:  # noqa: ANN001
        """The ids of the things of "A and B ..." (`_shared_head`: "the red and blue boxes")."""
        kids = [np.children[0] if np.data == "np" else np for np in tree.children]
        ids: list[str] = []
        i = 0
        while i < len(kids):
            j = i
            while j < len(kids) and self._modifiers_only(kids[j]):
                j += 1
            if i < j < len(kids) and self._headed(kids[j]):
                ids += self._shared_head(kids[i:j + 1])
                i = j + 1
            else:
                ids.append(self._np(kids[i]))
                i += 1
        return ids

    def _modifiers_only(self, inner) -> bool:  # noqa: ANN001
        """A phrase of words the reader's lexicon has heard in noun phrases, none of them ever
        a head, after at most an article ("the red" of "the red and blue boxes")."""
        words = [k for k in inner.children if _is_token(k)]
        return (bool(self.heads) and inner.data == "things" and bool(words)
                and all(k.type == "WORD" and k.value.value in self.named and k.value.value not in self.heads
                        for k in words))

    def _headed(self, inner) -> bool:  # noqa: ANN001
        """A phrase of words after at most an article, whose last word is a head the lexicon
        knows, said as it is or as its plural ("blue boxes")."""
        words = [k for k in inner.children if _is_token(k)]
        return (inner.data == "things" and bool(words) and all(k.type == "WORD" for k in words)
                and (words[-1].value.value in self.heads or singular(words[-1].value.value)[0] in self.heads))

    def _shared_head(self, phrases: list) -> list[str]:
        """Phrases of modifiers only before one with a head share that head, as a person reads
        them: "the red and blue boxes", "a red and a blue box" are a red box and a blue box
        (they were read "red", any red thing, and "blue boxes": "I see 1 'blue box', not
        several"). The plural said of the two is not said of each: each is one thing. With
        one article and a head said singular ("the red and blue box") it is one thing, both.
        A modifier phrase with no article of its own takes the first one's."""
        head = [k for k in phrases[-1].children if _is_token(k)][-1]
        first_det = [k for k in phrases[0].children if not _is_token(k)]
        own_det = any(not _is_token(k) for k in phrases[-1].children)
        word, plural = singular(head.value.value)
        if not own_det and not plural and head.value.value not in self.as_said:
            words = [k for p in phrases for k in p.children if _is_token(k)]
            return [self._np(Tree("things", first_det + words))]
        ids = []
        for p in phrases:
            dets = [k for k in p.children if not _is_token(k)] or first_det
            words = [k for k in p.children if _is_token(k)]
            if p is not phrases[-1]:
                words.append(head)
            ids.append(self._np(Tree("things", dets + words), single=plural))
        return ids

    def _np(self, tree, extra: tuple[str, ...] = (), after: tuple[str, ...] = (), *,  # noqa: ANN001
            single: bool = False) -> str:
        """Add the object reference of a noun phrase; its id. `single`: the phrase is one thing
        though its head was said plural (its plural was said of phrases that share it)."""
        if tree.data == "np":
            tree = tree.children[0]
        ref = f"r{len(self.objects) + 1}"
        if tree.data in ("it", "this"):
            anaphor = "it" if tree.data == "it" else None
            words = tuple(dict.fromkeys(extra))
            said = tree.children[0].value if tree.children else ""
            # "these are groxes": several things, and a new word is not learned from a plural
            # (it was learned as a word for the pair)
            several = str(getattr(said, "value", said)).lower() in closed_class.PLURAL_DETERMINERS
            self.objects.append(ObjectRef(ref, words, definite=False, plural=several, anaphor=anaphor))
            return ref
        det = quantifier = anaphor = None
        count: int | None = None
        said: list[str] = []
        one = False
        for kid in tree.children:
            if not _is_token(kid):  # det
                tok = kid.children[0]
                det = tok.value.value
                if tok.type == "QUANT":
                    quantifier = det
                continue
            w = kid.value
            if kid.type == "OTHER":
                anaphor = "other"
            elif kid.type == "NUM":
                count = int(w.value)
            elif kid.type == "ONE":
                one = True
            else:
                said.append(w.value)
        plural = False
        as_said = None
        if said and not one and said[-1] not in self.as_said:
            head, plural = singular(said[-1])
            as_said, said[-1] = said[-1], head
            if general(head):
                said.pop()  # "the object", "a red thing", "the colour": any thing, "red" ones
        plural = plural and not single
        by_ending = as_said if plural and count in (None, 1) and det not in closed_class.PLURAL_DETERMINERS else None
        plural = (plural and count != 1) or (count is not None and count >= 2) or det in closed_class.PLURAL_DETERMINERS
        definite = det in closed_class.DEFINITE or det in closed_class.DEMONSTRATIVES
        if one and not said and anaphor is None and definite:
            anaphor = "it"  # "that one", "the one"
        if one and not said and not extra and anaphor is None:
            # "one", "a one": no word says what it is and no earlier thing is meant
            raise NotUnderstood(f"I could not read {self.sentence.strip()!r}: 'one' needs a word before it "
                                f"('the red one') or points back ('that one', 'the other one')")
        # A word said twice in one phrase ("red red box") is one word: repeating it adds
        # nothing to what the phrase says, so it must not count twice for learning.
        words = tuple(dict.fromkeys((*extra, *(w for w in said if w not in after), *after)))
        indefinite = anaphor is None and not plural and (det in closed_class.INDEFINITE or count == 1)
        self.objects.append(ObjectRef(ref, words, definite and anaphor is None, count, plural, anaphor, quantifier,
                                      by_ending, indefinite))
        return ref

    def _attribute(self, subject, attribute, *, noun: bool = False) -> None:  # noqa: ANN001
        """"the box is red", "it is a red box", "this is a red box": the subject's words with
        the attribute's, the attribute's first (a head said as the attribute stays last); an
        attribute said with an article is a noun phrase, whose last word is the head: "is the
        red box a box?" is about a red box (it was read "box red", and "I see no")."""
        said = [k.value.value for k in attribute.children if _is_token(k) and k.type == "WORD"]
        toks = [k.value for k in attribute.children if _is_token(k)]
        # "green and blue": an "and" stood where a typed word is skipped
        typed = "".join((" and " if k and t.index > toks[k - 1].index + 1 else " " if k else "") + t.value
                        for k, t in enumerate(toks))
        if noun:
            typed = ("an " if typed[:1] in "aeiou" else "a ") + typed
        if said and not any(_is_token(k) and k.type == "ONE" for k in attribute.children) \
                and said[-1] not in self.as_said:
            said[-1] = singular(said[-1])[0]
            if general(said[-1]):
                said.pop()  # "is the cone an object?", "this is a red object"
        if subject.data in ("it", "this"):
            self._np(subject, tuple(said))
            return
        for np in subject.children:
            inner = np.children[0] if np.data == "np" else np
            if inner.data == "it":
                self._np(inner, tuple(said))
                continue
            ref = self._np(np, after=tuple(said)) if noun else self._np(np, tuple(said))
            k, made = next((k, o) for k, o in enumerate(self.objects) if o.id == ref)
            own = {v for t in np.scan_values(lambda v: _is_token(v) and v.type == "WORD")
                   for v in (t.value.value, singular(t.value.value)[0])}
            of = tuple(w for w in said if w not in own)
            if made.anaphor is None and of and any(w not in of for w in made.words):
                # a thing said with words of its own ("every box", not "that one"): what is
                # said of it is not what finds it ("every red box is red" finds red boxes)
                self.objects[k] = dataclasses.replace(made, said_of=of, attribute=typed)


def _is_token(x) -> bool:  # noqa: ANN001
    return hasattr(x, "type")


def plural(phrase: str) -> str:
    """The phrase with its last word made plural, the inverse of `singular` as said back
    ("2 glorps", "the boxes"; it said "2 glorp")."""
    if phrase == "one":
        return "ones"
    head = phrase.rsplit(" ", 1)[-1]
    if head.endswith(("s", "x", "ch", "sh", "z")):
        more = head + "es"
    elif head.endswith("y") and len(head) > 2 and head[-2] not in "aeiou":
        more = head[:-1] + "ies"
    else:
        more = head + "s"
    return phrase[: len(phrase) - len(head)] + more


def singular(word: str) -> tuple[str, bool]:
    """A noun's singular by simple morphology, and whether `word` was its plural: "boxes" ->
    box, "spheres" -> sphere, "bodies" -> body; "glass", "bus" and "axis" stay."""
    if len(word) <= 3 or not word.endswith("s") or word.endswith(("ss", "us", "is")):
        return word, False
    if word.endswith("ies") and len(word) > 4:
        return word[:-3] + "y", True
    if word.endswith(("xes", "ches", "shes", "sses", "zes")):
        return word[:-2], True
    return word[:-1], True
