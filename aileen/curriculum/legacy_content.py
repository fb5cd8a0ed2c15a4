"""An original-format lesson's sentence (`content`) held against its `description`.

Why: the trainer lays out the description and says the content, and an inform teaches the
agent that the one is the other. The original's instructor drew whatever its description left
open ("red cone" over a random object, `"color": null` under "red box"), and nothing checked
that "left of" was said over a right-of table: the agent stored "red" of a green cylinder.
Here the sentence fills what the description leaves open (`fill`: the trainer lays out what it
says), and a sentence that contradicts what the description gives (`contradiction`) is a
mistake in the file. Only what the trainer reads counts: a word of the teacher's own ("wug",
"rox") names nothing and contradicts nothing, though the phrases either side of a relation
word of its own are held to their objects ("green sphere wug yellow cylinder" over a red box
and a blue cone is refused). Values come from the declarations (`channels`,
`relations`, `actions`), never written here.
"""

from __future__ import annotations

from aileen.curriculum.lesson import ActionSpec, ObjectSpec
from aileen.curriculum.sentences import ContentInfo, read_content
from aileen.domain import relations

__all__ = ["contradiction", "fill"]


def _word(relation: str) -> str:
    """The word a relation is said by (`left-of-ec` and `left of` are both "left of")."""
    return relations.get(relation).word


def _conflict(objects: list[ObjectSpec], pairs: list[tuple[int, ObjectSpec]]) -> tuple[int, str, str] | None:
    """The first (object index, channel, value said) where a phrase says other than its object."""
    for i, phrase in pairs:
        for name, value in phrase.appearance.items():
            given = objects[i].appearance.get(name)
            if given is not None and given != value:
                return i, name, value
    return None


def _pairs(objects: list[ObjectSpec], relation: str | None, info: ContentInfo) -> list[tuple[int, ObjectSpec]]:
    """Which described object each of the sentence's phrases names: in order when the sentence
    has a phrase per object; swapped when it says the relation from the other side (by its
    converse, `relations.converse`: "blue cone right of red box" over a red box left of a blue
    cone, "blue cone smaller than red box", "blue cone near red box" over a red box near a blue
    cone) and the phrases fit so; none when it cannot tell (more or fewer phrases than objects)."""
    if len(info.phrases) != len(objects):
        return []
    pairs = list(enumerate(info.phrases))
    if _from_other_side(relation, info) and len(objects) == 2:
        if relations.get(relation).symmetric and _conflict(objects, pairs) is None:
            return pairs  # (said either way round: as written, where that fits)
        swapped = _swapped(info)
        if _conflict(objects, swapped) is None:
            return swapped
    return pairs


def _swapped(info: ContentInfo) -> list[tuple[int, ObjectSpec]]:
    return [(1, info.phrases[0]), (0, info.phrases[1])]


def _from_other_side(relation: str | None, info: ContentInfo) -> bool:
    """Does the sentence say the description's relation by its converse word?"""
    return (relation is not None and info.relation is not None
            and _word(info.relation) == relations.converse(relation))


def _reversed(objects: list[ObjectSpec], relation: str | None, info: ContentInfo) -> bool:
    """Does the sentence say the description's own relation word with its objects the other
    way round ("blue cone right of red box" over a red box right of a blue cone)?"""
    return (relation is not None and info.relation is not None and len(objects) == 2 == len(info.phrases)
            and _word(info.relation) == _word(relation) and not relations.get(relation).symmetric
            and _conflict(objects, _swapped(info)) is None)


def _read(content: str, relation: str | None) -> ContentInfo:
    """The trainer's reading of the sentence (`read_content`); where the description relates
    two objects and the sentence's relation is a word of the teacher's own ("green sphere wug
    yellow cylinder": no relation the trainer reads), the phrases either side of that word,
    so that they are held to the objects as a known word's would be."""
    info = read_content(content)
    if info.relation is not None or relation is None or not info.unknown:
        return info
    words = content.split()
    for i in range(1, len(words) - 1):
        j = i
        while j < len(words) - 1 and read_content(words[j]).unknown:
            j += 1
        if j == i:
            continue
        left, right = read_content(" ".join(words[:i])), read_content(" ".join(words[j:]))
        if (len(left.phrases) == len(right.phrases) == 1 and not left.unknown and not right.unknown
                and left.relation is None and right.relation is None and right.verb is None):
            return ContentInfo(left.verb, [*left.phrases, *right.phrases], None, info.unknown)
    return info


def _said_relation(relation: str | None, action: ActionSpec | None) -> str | None:
    """The relation the description lays out or its action brings about."""
    return relation if relation is not None else (action.relation if action is not None else None)


def fill(objects: list[ObjectSpec], relation: str | None, action: ActionSpec | None,
         content: str) -> list[ObjectSpec]:
    """The objects with each channel the description leaves open (no `color`, or `null`) set
    as the sentence says it: "red cone" over an open object lays out a red cone."""
    info = _read(content, _said_relation(relation, action))
    out = list(objects)
    for i, phrase in _pairs(objects, _said_relation(relation, action), info):
        given = {k: v for k, v in phrase.appearance.items() if k not in out[i].appearance}
        if given:
            out[i] = out[i].with_values(**given)
    return out


def contradiction(objects: list[ObjectSpec], relation: str | None, action: ActionSpec | None,
                  content: str, *, whose: str = "the description") -> str | None:
    """Where the sentence says other than the description gives, in one clause naming both
    (`'content' says 'blue' where the description's object 1 has colour 'red' (red box)`),
    else None. A relation said from the other side of its objects ("blue cone right of red
    box" over a red box left of a blue cone) says the same; said not to hold ("the red box is
    not left of the blue cone" over a red box left of a blue cone) it says the opposite: the
    agent learned a near miss of the word from a scene of the word. `whose`: what lays the
    objects out, for the message (a TOML lesson's own `relation`: "the lesson")."""
    rel = _said_relation(relation, action)
    info = _read(content, rel)
    if action is not None and info.verb is not None and info.verb != action.verb:
        return f"'content' says {info.verb!r} where {whose}'s action is {action.name!r}"
    pairs = _pairs(objects, rel, info)
    swapped = bool(pairs) and pairs[0][0] == 1
    if rel is not None and info.relation is not None and _word(info.relation) != _word(rel) and not swapped:
        if info.negated:
            return None  # "the red box is not right of the blue cone" over left of: not false
        what = "relation" if relation is not None else "action"
        return f"'content' says {_word(info.relation)!r} where {whose}'s {what} is {_word(rel)!r}"
    found = _conflict(objects, pairs)
    if found is None:
        if info.negated and rel is not None and info.relation is not None and pairs:
            return (f"'content' says 'not {_word(info.relation)}' where {whose} lays out "
                    f"'{objects[0].describe()} {_word(rel)} {objects[1].describe()}'")
        return None
    if _reversed(objects, rel, info):
        said = f"{info.phrases[0].describe()} {_word(rel)} {info.phrases[1].describe()}"
        return (f"'content' says {said!r}, the relation reversed: {whose} lays out "
                f"'{objects[0].describe()} {_word(rel)} {objects[1].describe()}'")
    i, name, value = found
    return (f"'content' says {value!r} where {whose}'s object {i + 1} has {name} "
            f"{objects[i].appearance[name]!r} ({objects[i].describe()})")
