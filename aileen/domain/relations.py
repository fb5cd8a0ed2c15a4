"""The registry of the trainer's relations and the queries over it: the teacher's meaning of its words.

The agent never reads this module. It learns "left of" from examples laid out with it and is
graded against it, so these definitions are the trainer's intent, not the learner's concept.

What a relation is and how each kind is laid out (`TrainerRelation`, `Direction`, `Grain`,
`Distance`, the geometry and the factories `directional`, `next_to`, `distance`,
`comparative`, `on`) live in `relation_kinds.py`; this module declares relations, knows them
by every spelling and answers questions about them. It was split so that each file has one
job; every name of `relation_kinds` is re-exported here, so `relations.X` works as before.

Direction words come in families. A `Direction` is declared with its axis, the word opposite
it and its `Grain` (how wide its family's words are: the four cardinal words are each a quarter
of the circle); `declare_directions` lays each out three ways, plain (`left of`), wide (`left of
wide`) and touching (`left of ec`). What is "a direction word", "the opposite of left of", "the
wide layout of behind" is read from these declarations (`directions`, `direction`), never from
a layout's geometry. A distance word (`distance`) declares its region as a `Distance`, and a
word that is both ("far left of") is their `conjunction`: laid out, accepted and near-missed
through the two declarations (so it is built here, from declared relations by name, as is a
`disjunctive`).

To add a relation: one `declare(...)` of a `TrainerRelation` (the factories cover direction,
contact, distance, size and stacking; `declare_directions` a family of direction words,
`conjunction` a direction at a distance), in a module of your own named in `AILEEN_DOMAIN`
(`extensions.py`); nothing else lists relations.
"""

from __future__ import annotations

import contextlib
import dataclasses
import math
import re
from collections.abc import Iterator
from contextvars import ContextVar

import numpy as np

# Re-exported: the kinds of relation moved to relation_kinds.py, and every name is still
# importable from here (relations.directional, relations.TrainerRelation, relations.gap, ...);
# the table geometry they read is in table_geometry.py.
from aileen.domain.relation_kinds import (
    APART_MIN, CARDINAL, CLEAR_GAP, CLEAR_HALF_ANGLE, FAR_GAP, FAR_LAY, HOLDS_HALF_ANGLE, LAY_TOUCH_GAP,
    NEAR_GAP, NEAR_LAY, PLACE_DISTANCE, PLACE_HALF_ANGLE, TOUCH_GAP, TOUCHING_SUFFIX, WIDE_CLEAR_HALF_ANGLE,
    WIDE_CLEAR_MARGIN, WIDE_HALF_ANGLE, WIDE_LAY_MARGIN, WIDE_SUFFIX, Direction, Distance, Grain, Offset,
    TrainerRelation, comparative, directional, distance, next_to, on,
)
from aileen.domain.table_geometry import OnTable, angle_from, gap, touch_length
from aileen.errors import UserError

# ------------------------------------------------------------------ kinds made of declared relations


def disjunctive(name: str, word: str, variants: tuple[str, ...]) -> TrainerRelation:
    """Any of several layouts of one word, drawn at random for each scene."""
    parts = [RELATIONS[v] for v in variants]

    def offset(rng: np.random.Generator, fa: float, fb: float) -> tuple[float, float]:
        return parts[int(rng.integers(len(parts)))].offset(rng, fa, fb)  # type: ignore[misc]

    first = parts[0]
    return TrainerRelation(name, word, first.accepts, lambda a, b: any(p.clear(a, b) for p in parts), offset,
                           first.near_miss, direction=first.direction)


def conjunction(name: str, direction: str, distance: str, *, aliases: tuple[str, ...] = ()) -> TrainerRelation:
    """a lies in the declared `direction` from b and at the declared `distance` from it ("far
    left of": left of, and far from), as a person judges both words.

    Read from the two declarations: the direction word's axis and grain, the distance word's
    region. Laid out along the axis (within the grain's plain spread) with a gap in the
    distance's layout band; clear when the direction is clear of its edge and the distance
    clearly holds. A near miss is one without the other: along the axis at the distance's
    near-miss gap, or at the distance in the opposite or a perpendicular direction."""
    way, apart_by = get(direction), get(distance)
    if way.direction is None or apart_by.distance is None:
        raise UserError(f"a conjunction joins a direction and a distance; got {direction!r} and {distance!r}")
    d, region = way.direction, apart_by.distance
    spread = d.grain.lay if d.grain is not None else PLACE_HALF_ANGLE
    clear_half = d.grain.clear if d.grain is not None else CLEAR_HALF_ANGLE

    def accepts(a: OnTable, b: OnTable) -> bool:
        return way.accepts(a, b) and apart_by.accepts(a, b)

    def clear(a: OnTable, b: OnTable) -> bool:
        return accepts(a, b) and angle_from(d.radians, a, b) < clear_half and apart_by.clear(a, b)

    def at(rng: np.random.Generator, fa: float, fb: float, axis: float,
           span: tuple[float, float]) -> tuple[float, float]:
        theta = axis + math.radians(rng.uniform(-spread, spread))
        length = touch_length(theta, fa, fb, max(max(fa, fb) * rng.uniform(*span), APART_MIN))
        return length * math.cos(theta), length * math.sin(theta)

    def offset(rng: np.random.Generator, fa: float, fb: float) -> tuple[float, float]:
        return at(rng, fa, fb, d.radians, region.lay)

    def near_miss(rng: np.random.Generator, fa: float, fb: float) -> tuple[float, float]:
        if rng.random() < 0.5:  # the direction, not at the distance
            return at(rng, fa, fb, d.radians, region.miss)
        turn = math.radians(float(rng.choice([90.0, 180.0, 270.0])))  # the distance, another way
        return at(rng, fa, fb, d.radians + turn, region.lay)

    return TrainerRelation(name, name, accepts, clear, offset, near_miss, aliases=aliases, direction=d,
                           distance=region)


RELATIONS: dict[str, TrainerRelation] = {}
_ALIASES: dict[str, str] = {}
# The declared direction words, by word (`declare_directions`): what "a direction word", "its
# opposite" and "its wide layout" mean everywhere.
DIRECTIONS: dict[str, Direction] = {}
# `spellings()`, made again after a declaration (keyed by `version()`)
_SPELLINGS: dict[tuple[int, int, int], dict[str, str]] = {}
_DECLARED = [0]  # declarations so far


_SAID = re.compile(r"[a-z][a-z0-9]*(?: [a-z][a-z0-9]*)*")


def declare(*rels: TrainerRelation) -> None:
    """Add relations the trainer can lay out, examine and grade (with their spellings). A name,
    word or spelling that is not lowercase words of the letters a-z and digits, a letter first,
    separated by single spaces (no hyphen, no underscore: one rule for all three), is a
    `UserError` here: "Aside" reached clingo as a variable, "2 steps from" stopped a run with a
    traceback, and "près de" was never read."""
    from aileen.domain import words as closed_class

    for r in rels:
        for said in (r.name, *r.aliases):
            # one rule for a name and its spellings, written as a sentence says them (an alias
            # "aligned-with" was accepted while the name "aligned-with" was refused)
            if not isinstance(said, str) or not _SAID.fullmatch(said):
                raise UserError(f"relation {said!r}: a relation's name and spellings are lowercase words of the "
                                f"letters a-z and digits, a letter first, separated by single spaces, with no "
                                f"hyphen or underscore (e.g. 'short way from')")
            if _normalise(said) in closed_class.FUNCTION_WORDS | closed_class.VERBS:
                # ("not" stopped a run with a traceback from clingo; "move" stored spatial examples
                # in the verb's concept)
                raise UserError(f"relation {said!r}: a word of the grammar or a verb cannot name a relation")
            from aileen.domain import channels

            if any(_normalise(said) in c.values for c in channels.CHANNELS):
                # ("box" stored spatial examples in the visual concept r_box)
                raise UserError(f"relation {said!r}: it is what an object looks like (a channel's value), "
                                f"not a relation")
            taken = _spelled_by(_normalise(said), r, rels)
            if taken is not None:
                # (an alias "left of" of "east of" took the word from the direction "left of")
                raise UserError(f"relation {r.name!r}: {said!r} already says {taken}; expected a word of the "
                                f"relation's own")
        _check_word(r, rels)
    _DECLARED[0] += 1
    for r in map(_guarded, rels):
        RELATIONS[r.name] = r
        _ALIASES[_normalise(r.name)] = r.name
        _ALIASES[r.name.replace(" ", "_")] = r.name
        for alias in r.aliases:
            _ALIASES[_normalise(alias)] = r.name


def _check_word(r: TrainerRelation, rels: tuple[TrainerRelation, ...]) -> None:
    """A relation's `word` is what a sentence says for it: its own name, or (a layout variant,
    "left of wide") the name of a relation declared before or with it; lowercase words
    separated by single spaces, as a name is. A word "aligned  with" (two spaces) was accepted
    and could never be said: `spellings()` holds a relation only by its word."""
    if not isinstance(r.word, str) or not _SAID.fullmatch(r.word):
        raise UserError(f"relation {r.name!r}: its word {r.word!r}: expected lowercase words of the letters a-z and "
                        f"digits separated by single spaces, a letter first (e.g. 'short way from')")
    if r.word != r.name and r.word not in RELATIONS and all(r.word != o.name for o in rels):
        raise UserError(f"relation {r.name!r}: its word {r.word!r} is no declared relation's name; expected its own "
                        f"name {r.name!r} or (a layout variant) the name of a relation declared before it")


def _guarded(r: TrainerRelation) -> TrainerRelation:
    """`r` with its functions of one's own guarded (`extensions.guarded`): an error inside a
    user's `accepts` is one line naming it, never a traceback nor "a defect inside aileen"."""
    from aileen.domain import guard

    functions = {f: getattr(r, f) for f in ("accepts", "clear", "offset", "near_miss", "sizes", "near_miss_sizes")}
    # an offset or near miss is where the trainer puts an object: a pair, checked as it returns
    shapes = {"offset": guard.two_numbers, "near_miss": guard.two_numbers}
    checked = {f: guard.guarded(f"relation {r.name!r}: its {f}", fn, shapes.get(f)) for f, fn in functions.items()}
    return r if checked == functions else dataclasses.replace(r, **checked)


def _spelled_by(said: str, r: TrainerRelation, rels: tuple[TrainerRelation, ...]) -> str | None:
    """What already says the spelling `said` of `r`: a declared relation (another, or one of
    the same name: a relation is declared once), another of `rels` declared with it, a
    channel's value or spelling, or a verb; None when nothing does."""
    from aileen.domain import spoken

    name = _ALIASES.get(said)
    if name is not None and RELATIONS.get(name) not in (r, _guarded(r)):
        return f"the relation {name!r}"
    for other in rels:
        if other is not r and said in {_normalise(s) for s in (other.name, *other.aliases)}:
            return f"the relation {other.name!r}, declared with it"
    # each word of the phrase too ("abreast of" beside a channel value "abreast"), but for the
    # grammar's own ("of", "left"), which every relation shares
    from aileen.domain import words as closed_class

    taken = spoken.owner(said, skip="relation")
    if taken is not None:
        return taken
    for w in said.split():
        if w != said and w not in closed_class.CLOSED_CLASS:
            taken = spoken.owner(w, skip="relation")
            if taken is not None:
                return f"{taken} (its word {w!r})"
    return None


def declare_directions(*dirs: Direction) -> None:
    """Declare direction words, each with its opposite (declared with it or before), its grain
    and spellings, and their layouts: every plain one, then every wide one, then every
    touching one. A `ValueError` when an opposite is missing or does not name the word back,
    lies elsewhere than half a circle away or in another grain, or when two words of one grain
    overlap (a word of a grain must be the only one of its grain that holds)."""
    family = {**DIRECTIONS, **{d.word: d for d in dirs}}
    for d in dirs:
        if d.grain is None or d.opposite is None:
            raise ValueError(f"direction {d.word!r}: a declared direction names its opposite and its grain")
        o = family.get(d.opposite)
        if o is None or o.opposite != d.word:
            raise ValueError(f"direction {d.word!r}: its opposite {d.opposite!r} is not declared with "
                             f"{d.word!r} as its own opposite")
        if abs(math.remainder(o.axis - d.axis - 180.0, 360.0)) > 1e-9 or o.grain != d.grain:
            raise ValueError(f"direction {d.word!r}: its opposite {o.word!r} must lie half a circle away "
                             f"({o.axis} against {d.axis} degrees) in the same grain")
        for other in family.values():
            apart = abs(math.remainder(other.axis - d.axis, 360.0))
            if other is not d and other.grain == d.grain and apart < 2 * d.grain.half_angle - 1e-9:
                raise ValueError(f"directions {d.word!r} and {other.word!r} of grain {d.grain.name!r} overlap: "
                                 f"{apart:g} degrees apart, each {2 * d.grain.half_angle:g} wide")
    layouts = [d.layouts() for d in dirs]
    DIRECTIONS.update((d.word, d) for d in dirs)
    declare(*(lay[k] for k in range(3) for lay in layouts))


@contextlib.contextmanager
def kept() -> Iterator[None]:
    """Within the block, declare freely; on leaving, the registry is as it was (a test that
    declares a relation or a family for itself alone)."""
    saved = dict(RELATIONS), dict(_ALIASES), dict(DIRECTIONS)
    try:
        yield
    finally:
        for live, old in zip((RELATIONS, _ALIASES, DIRECTIONS), saved):
            live.clear()
            live.update(old)  # type: ignore[arg-type]
        _DECLARED[0] += 1  # what was read from the registry inside is stale (`version`)


def _normalise(name: str) -> str:
    return re.sub(r"\s+", " ", re.sub(r"[-_]", " ", name.strip().lower())).strip()


# A trial's own relations (experiments/teacher.py draws a teacher per trial): known to the
# trainer inside `scope(...)` only, where they stand before the registry's (the teacher's
# "left of" is the word "left of" there). The registry itself, which the published protocols
# read, is never changed by them. A ContextVar: per thread, so concurrent runs do not mix.
_SCOPE: ContextVar[tuple[dict[str, TrainerRelation], dict[str, str]]] = ContextVar("relations_scope",
                                                                                  default=({}, {}))


@contextlib.contextmanager
def scope(*rels: TrainerRelation) -> Iterator[None]:
    """Within the block, `rels` are known by their names and aliases (before the registry's)."""
    own, aliases = dict(_SCOPE.get()[0]), dict(_SCOPE.get()[1])
    for r in rels:
        own[r.name] = r
        for spelling in (r.name, *r.aliases):
            aliases[_normalise(spelling)] = r.name
    token = _SCOPE.set((own, aliases))
    try:
        yield
    finally:
        _SCOPE.reset(token)


def scope_now() -> object:
    """The `scope` in force (an object that is the same while it lasts): what is read from the
    registry and a scope may be kept by it and `version`."""
    return _SCOPE.get()


def _lookup(name: str) -> TrainerRelation:
    """The relation of a canonical name: the scope's, else the registry's."""
    own = _SCOPE.get()[0].get(name)
    return own if own is not None else RELATIONS[name]


# The four cardinal words, each laid out plain (within 10 degrees of its axis), wide (anywhere
# a person still says it: up to 40 degrees off the axis) and touching (in contact).
declare_directions(
    Direction("left of", 180.0, "right of", CARDINAL, aliases=("left", "to the left of", "leftof")),
    Direction("right of", 0.0, "left of", CARDINAL, aliases=("right", "to the right of", "rightof")),
    Direction("in front of", 270.0, "behind", CARDINAL, aliases=("front of", "in front", "infrontof", "frontof")),
    Direction("behind", 90.0, "in front of", CARDINAL, aliases=("behind of", "in back of", "back of")),
)
declare(
    # numbered layouts of one word (the original's behind1/2/3): straight, to the left, to the right
    directional("behind1", 90.0, direction=DIRECTIONS["behind"]),
    directional("behind2", 120.0, direction=DIRECTIONS["behind"], lay_half_angle=5.0),
    directional("behind3", 60.0, direction=DIRECTIONS["behind"], lay_half_angle=5.0),
    next_to(),
    distance("near", 0.0, NEAR_GAP, NEAR_LAY, (1.2, 2.0), aliases=("close to", "near to")),
    distance("far from", FAR_GAP, math.inf, FAR_LAY, (1.2, 2.0), aliases=("distant", "far away from", "far")),
    comparative("larger than", True, aliases=("bigger than", "larger"), converse="smaller than"),
    comparative("smaller than", False, aliases=("smaller",), converse="larger than"),
    on(),
)
declare(disjunctive("behind disjunctive", "behind", ("behind1", "behind2", "behind3")))


# ------------------------------------------------------------------ names


def known() -> tuple[str, ...]:
    """Canonical names of the layouts the trainer can lay out and demonstrate."""
    return tuple(RELATIONS)


def words() -> tuple[str, ...]:
    """The relation words the trainer says (one per meaning; layouts share them)."""
    return tuple(dict.fromkeys(r.word for r in RELATIONS.values()))


def directions(grain: str | None = None) -> tuple[str, ...]:
    """The declared direction words (`declare_directions`), or those of one grain
    (`directions("cardinal")`: left of, right of, in front of, behind), in declaration order.
    Words of one grain never both hold of a pair; words of different grains may."""
    return tuple(w for w, d in DIRECTIONS.items() if grain is None or (d.grain is not None and d.grain.name == grain))


def direction(word: str) -> Direction:
    """The declared direction of a direction word (any spelling): its axis, opposite, grain and
    layouts; a `UserError` for a word that is not a declared direction."""
    found = find(word)
    if found is None or found not in DIRECTIONS:
        raise UserError(f"{word!r} is not a declared direction; expected one of: {', '.join(DIRECTIONS)}")
    return DIRECTIONS[found]


def converse(name: str) -> str | None:
    """The word that says a relation from its other side (b <it> a whenever a <name> b): a
    direction's opposite ("right of" for "left of"), a symmetric word itself ("near"), a
    comparative's declared converse ("smaller than" for "larger than"); None when no word does
    ("on"). Read from the declarations, as everything about a relation is."""
    rel = get(name)
    if rel.word in DIRECTIONS:
        return DIRECTIONS[rel.word].opposite
    if rel.symmetric:
        return rel.word
    return rel.converse


def protocol_words() -> tuple[str, ...]:
    """The relation words the wide protocol teaches and examines: every word whose plain
    layout puts two objects side by side on the table (all but stacking)."""
    return tuple(w for w in words() if not of_word(w).stacked)


def wide(word: str) -> str:
    """The wide layout of a directional word (`left of` -> `left of wide`): the whole region
    a person accepts; the word itself when it has none."""
    return DIRECTIONS[word].wide if word in DIRECTIONS else word


def placeable() -> tuple[str, ...]:
    """Layouts that say where an object stands (what `move X <r> Y` can bring about)."""
    return tuple(n for n, r in RELATIONS.items() if r.offset is not None and r.positional)


def find(name: str) -> str | None:
    """Canonical name for a spelling (`left-of`, `Left_Of`, `to the left of`), or None."""
    key = _normalise(name)
    return _SCOPE.get()[1].get(key) or _ALIASES.get(key)


def canonical(name: str) -> str:
    """Like `find`, but an unknown name is a `UserError` that lists the known relations."""
    found = find(name)
    if found is None:
        import difflib

        plain = words()
        layouts = [n for n in known() if n not in plain]
        close = difflib.get_close_matches(name.lower(), list(known()), n=1, cutoff=0.75)
        raise UserError(f"unknown relation {name!r}" + (f" (did you mean {close[0]!r}?)" if close else "")
                        + f"; expected a relation word: {', '.join(plain)}"
                        + (f"; or a layout of one: {', '.join(layouts)}" if layouts else ""))
    return found


def get(name: str) -> TrainerRelation:
    return _lookup(canonical(name))


def of_word(word: str) -> TrainerRelation:
    """The plain layout of a relation word (the one named like it)."""
    return _lookup(word)


def phrases() -> list[tuple[str, str]]:
    """(spelling, word) pairs with spaces, longest first: for finding relation words in the
    trainer's own sentences (only spellings of words, not of layout variants; a `scope`'s
    words too)."""
    global _PHRASES
    scope, ver = _SCOPE.get(), version()
    last = _PHRASES
    if last is not None and last[0] == ver and last[1] is scope:
        return list(last[2])  # the trainer reads every sentence through this: kept per registry and scope
    own, own_aliases = scope
    found = {k: _lookup(v).word for k, v in _ALIASES.items()
             if "_" not in k and _lookup(v).name == _lookup(v).word}
    found.update({k: own[v].word for k, v in own_aliases.items() if own[v].name == own[v].word})
    out = sorted(found.items(), key=lambda kv: -len(kv[0]))
    _PHRASES = (ver, scope, out)
    return list(out)


# `phrases`' last answer: (registry version, the scope it was for, the pairs)
_PHRASES: tuple | None = None


def version() -> tuple[int, int, int]:
    """Which registry this is: changes with every declaration, and when the registry is put
    back by hand (tests do), so what is read from it can be cached by it."""
    return (_DECLARED[0], len(RELATIONS), len(_ALIASES))


def spellings() -> dict[str, str]:
    """Every declared spelling of a relation word in the registry -> the word it spells
    (`"to the left of"`, `"left"`, `"leftof"` -> `"left of"`; as `phrases`, the spellings of
    words, not of layout variants such as `"left of ec"`), words separated by one space. The teacher's grammar reads the
    words of its sentences with it (`aileen/reasoning/grammar.py`); the registry only, so what a
    sentence says does not depend on a trial's teacher (`scope`)."""
    key = version()
    if _SPELLINGS.get(key) is None:
        _SPELLINGS.clear()
        _SPELLINGS[key] = {k.replace("_", " "): RELATIONS[v].word for k, v in _ALIASES.items()
                           if RELATIONS[v].name == RELATIONS[v].word}
    return _SPELLINGS[key]


def angle_off(relation: str, a: OnTable, b: OnTable) -> float:
    """Degrees between the axis of the direction a relation says (`TrainerRelation.direction`:
    "behind" for `behind2` too) and the direction from b's centre to a's (180 when the centres
    coincide)."""
    rel = get(relation)
    if rel.direction is None:
        raise UserError(f"relation {relation!r} has no direction")
    return angle_from(rel.direction.radians, a, b)


def holds(relation: str, a: OnTable, b: OnTable) -> bool:
    """Ground truth as a person judges it: does `a <relation> b` hold?"""
    return get(relation).accepts(a, b)


def clearly_holds(relation: str, a: OnTable, b: OnTable) -> bool:
    """The trainer's standard for its own scenes."""
    return get(relation).clear(a, b)


def which(a: OnTable, b: OnTable) -> list[str]:
    """Every relation word that holds of `a` to `b`, as a person judges it."""
    return [w for w in words() if of_word(w).accepts(a, b)]


def sample_offset(relation: str, fa: float, fb: float | None, rng: np.random.Generator) -> tuple[float, float]:
    """A displacement (dx, dy) that puts an object (footprint fa) clearly in `relation` to one
    (footprint fb) at the origin."""
    rel = get(relation)
    if rel.offset is None:
        raise UserError(f"relation {relation!r} does not depend on where the objects stand")
    return rel.offset(rng, fa, fa if fb is None else fb)
