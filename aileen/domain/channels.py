"""Perceptual channels: what the visual module reports about each object, declared once.

A channel is one declaration (`Channel`): its values (the world's names for them), the
function that measures it from the camera image, and, for a channel the camera shows beyond
the body, the function that renders it. Each value is seen as a percept symbol (`cv_red`); the
agent knows which channel a percept belongs to (its own senses), never what any word means.
The order of `CHANNELS` is the order of an object's percept facts and of its appearance.

Everything that says what an object looks like reads these declarations through one record,
`aileen.world.appearance.Appearance` (channel name -> value): the world and its camera, the
ground truth and the ground-truth vision, the trainer (the kinds it draws, its distractors),
its sentence reader (`curriculum.sentences`), the lesson readers (TOML and the original JSON),
the teaching console and the data set. Lesson files name a channel by its name (or one of its
`keys`: the original scripts say "color"); sentences name a value by itself or one of its
`spellings` ("cube" is a box).

To add a channel: declare it (`declare`, or `scope` for a while, as a test does) with its
values, its `measure` (`measure(image, detection, camera) -> (value, distance)`, a function or
its dotted path "module:function", so that this module stays free of OpenCV; optionally a
`measure_all_by` that measures all of one image's detections at once) and its `render`
(`render(value, canvas)`, drawing it on one object's patch: `aileen.world.appearance.Canvas`).
To add a shape: declare an `aileen.world.catalog.Shape` (its footprint and its render
function); it becomes a value of the shape channel. docs/architecture.md has both recipes.
"""

from __future__ import annotations

import contextlib
import dataclasses
import importlib
import importlib.util
import itertools
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any

from aileen.errors import UserError
from aileen.terms import DECLARED_NAME
from aileen.world import appearance, catalog
from aileen.world.appearance import Appearance, Render
from aileen.world.catalog import Shape

__all__ = ["Channel", "CHANNELS", "SHAPE", "COLOUR", "SIZE", "Shape", "declare", "scope", "get", "names", "drawn",
           "of_percept", "truth_percepts", "read_value", "key_names", "appearance_of", "kinds", "kind_of"]


@dataclass(frozen=True)
class Channel:
    name: str  # "colour"
    values: tuple[str, ...]  # the world's names: "red", "green", ...
    measure_by: str | Callable[..., tuple[str, float]]  # "module:function", or the function itself
    render: Render | None = None  # for a look the camera shows beyond the body: render(value, canvas)
    # The value an object has unless a lesson says otherwise ("medium"); None: the trainer
    # draws one at random, and distractors differ in it (shape, colour).
    default: str | None = None
    spellings: tuple[tuple[str, str], ...] = ()  # other words for a value: ("cube", "box")
    keys: tuple[str, ...] = ()  # other names lesson files give the channel: ("color",)
    # Optional: the measure of all of one image's detections at once, for a channel whose
    # measure shares work between objects: `(image, detections, camera) -> [(value, distance)]`
    measure_all_by: str | Callable[..., list[tuple[str, float]]] | None = None

    def percept(self, value: str) -> str:
        """The percept symbol the agent sees for a value: `red` -> `cv_red`."""
        return catalog.percept(value)

    @cached_property
    def percepts(self) -> tuple[str, ...]:
        return tuple(self.percept(v) for v in self.values)

    @cached_property
    def measure(self) -> Callable[..., tuple[str, float]]:
        return _function(self.measure_by, f"channel {self.name!r}: its measure")

    @cached_property
    def measure_all(self) -> Callable[..., list[tuple[str, float]]]:
        """The measure of every detection of one image: `measure_all_by` where the channel
        declares one, else `measure` object by object."""
        if self.measure_all_by is not None:
            return _function(self.measure_all_by, f"channel {self.name!r}: its measure_all_by")
        measure = self.measure
        return lambda image, detections, camera: [measure(image, d, camera) for d in detections]

    def truth(self, obj: Any) -> str:
        """The true value of a world object (or its ground-truth record): its appearance's."""
        return str(obj.appearance[self.name])

    def value(self, word: str) -> str | None:
        """The value a word names in this channel ("cube" -> "box"), or None."""
        word = dict(self.spellings).get(word, word)
        return word if word in self.values else None

    def check(self, word: str) -> str:
        """The value a word names (its spellings read), or a `UserError` listing the values."""
        said = word.lower() if isinstance(word, str) else word
        value = self.value(said) if isinstance(said, str) else None
        if value is None:
            raise UserError(f"unknown {self.name} {said!r}; expected one of: {', '.join(self.values)}")
        return value

    @property
    def look(self) -> appearance.Look:
        """The channel as the world holds it (a channel beyond the body)."""
        from aileen.domain import guard

        render = guard.guarded(f"channel {self.name!r}: its render", self.render)
        return appearance.Look(self.name, self.values, self.default or self.values[0], render)


def _function(by: str | Callable[..., Any], what: str) -> Callable[..., Any]:
    """A function given as itself or by its dotted path "module:function" (`what` it is for, in
    a message): one of one's own guarded (`extensions.guarded`: an error inside it is one line
    naming it), and a path that names none a `UserError` saying so."""
    from aileen.domain import guard

    if callable(by):
        return guard.guarded(what, by)
    module, _, func = by.partition(":") if isinstance(by, str) else ("", "", "")
    try:
        found = getattr(importlib.import_module(module), func, None) if module and func else None
    except Exception as exc:  # noqa: BLE001 - the user's path: named, not a traceback
        raise UserError(f"{what} {by!r}: cannot import {module!r}: {type(exc).__name__}: {exc}") from None
    if not callable(found):
        raise UserError(f"{what} {by!r}: expected 'module:function' naming a function, or the function itself")
    return guard.guarded(what, found)


def _findable(by: object, what: str) -> None:
    """A measure given by its path names a module that can be found (checked when the channel
    is declared, without importing it: "nosuch.module:fn" stopped the first lesson)."""
    if callable(by) or by is None:
        return
    module, _, func = by.partition(":") if isinstance(by, str) else ("", "", "")
    try:
        spec = importlib.util.find_spec(module) if module and func else None
    except (ImportError, ValueError):
        spec = None
    if spec is None:
        raise UserError(f"{what} {by!r}: expected 'module:function' of a module that can be imported, or the "
                        f"function itself")


SHAPE = Channel("shape", catalog.SHAPES, "aileen.perception.detector:measure_shape",
                spellings=(("cube", "box"), ("block", "box"), ("ball", "sphere")))
COLOUR = Channel("colour", catalog.COLOURS, "aileen.perception.color:measure_colour",
                 spellings=(("violet", "purple"),), keys=("color",),
                 measure_all_by="aileen.perception.color:measure_colours")
SIZE = Channel("size", tuple(catalog.SIZES), "aileen.perception.size:measure_size", default=catalog.DEFAULT_SIZE)

# Every channel, in order. Change it only through `declare` and `scope` (they keep the world's
# looks and catalogue in step); it is one list, so every module that imported it sees the change.
CHANNELS: list[Channel] = [SHAPE, COLOUR, SIZE]


def get(name: str) -> Channel:
    """The channel of that name (or of one of its keys); a `UserError` listing them otherwise."""
    for c in CHANNELS:
        if name == c.name or name in c.keys:
            return c
    raise UserError(f"unknown channel {name!r}; expected one of: {', '.join(names())}")


def names() -> tuple[str, ...]:
    return tuple(c.name for c in CHANNELS)


def key_names() -> tuple[str, ...]:
    """Every name a lesson file may give a channel: each channel's name, then its other keys."""
    return tuple(k for c in CHANNELS for k in (c.name, *c.keys))


def drawn() -> tuple[Channel, ...]:
    """The channels the trainer draws at random when a lesson leaves them open (no default):
    an object's kind, in which distractors differ from the described objects."""
    return tuple(c for c in CHANNELS if c.default is None)


def kinds(choose: Callable[[Channel], Sequence[str]] | None = None) -> list[Appearance]:
    """Every kind of object: one value of each drawn channel (`drawn`), the first channel
    varying slowest (shape, then colour: box red, box green, ...). `choose(channel)` narrows a
    channel's values (a lesson's own colour, a shape that can carry)."""
    drawn_now = drawn()
    pools = [tuple(choose(c)) if choose is not None else _drawable(c) for c in drawn_now]
    return [Appearance(zip((c.name for c in drawn_now), combo)) for combo in itertools.product(*pools)]


def _drawable(c: Channel) -> tuple[str, ...]:
    """A channel's values that random draws take (of the shapes, `catalog.drawn_shapes()`)."""
    return catalog.drawable(c.values)


def kind_of(values: Mapping[str, str]) -> Appearance | None:
    """The kind of an object or description (its drawn channels' values); None when a
    description leaves one of them open."""
    names_now = [c.name for c in drawn()]
    if any(n not in values for n in names_now):
        return None
    return Appearance((n, values[n]) for n in names_now)


def read_value(word: str, filled: Mapping[str, str]) -> tuple[str, str] | None:
    """(channel, value) for the first channel, in order, whose value the word names and that
    `filled` does not hold yet; None when it names none. The trainer's sentence filler."""
    for c in CHANNELS:
        if c.name not in filled:
            value = c.value(word)
            if value is not None:
                return c.name, value
    return None


def appearance_of(values: Mapping[str, str | None]) -> Appearance:
    """The values given (None: left open), in channel order."""
    order = {n: i for i, n in enumerate(names())}
    return Appearance(sorted(((k, v) for k, v in values.items() if v is not None), key=lambda kv: order.get(kv[0], 99)))


def of_percept() -> dict[str, str]:
    """Percept symbol -> channel name, for every channel: the agent's knowledge of its senses."""
    return {p: c.name for c in CHANNELS for p in c.percepts}


def truth_percepts(obj: Any) -> tuple[str, ...]:
    """An object's percept symbols from ground truth, in channel order."""
    return tuple(c.percept(c.truth(obj)) for c in CHANNELS)


def _set_shape_channel() -> None:
    global SHAPE
    new = dataclasses.replace(SHAPE, values=catalog.SHAPES)
    CHANNELS[CHANNELS.index(SHAPE)] = new
    SHAPE = new


# The keys the lesson readers give to something other than a channel ("position", "signal",
# "rgb"), by key -> the reader: each reader says its own when it is imported (`reserve_keys`).
_OTHER_KEYS: dict[str, str] = {}


def reserve_keys(reader: str, keys: Iterable[str]) -> None:
    """Keys a lesson reader reads beside a channel's, which no channel may take. A channel
    already named so is refused now, whichever was declared first (the readers are imported
    after `AILEEN_DOMAIN`'s modules, before any lesson)."""
    keys = tuple(keys)
    taken = next((k for k in keys if k in key_names()), None)
    if taken is not None:
        raise UserError(f"channel {get(taken).name!r}: {taken!r} is a key {reader} gives to something else; "
                        f"expected a name of its own")
    _OTHER_KEYS.update((k, reader) for k in keys)


def _said_alone(what: str, word: str) -> None:
    """A value or spelling of a channel is a lowercase name (its percept `cv_<value>` is a
    clingo name) that no relation, verb or other channel's value or spelling says already: a
    sentence reads each word as one thing ("cube" is a box; "red" a colour)."""
    from aileen.domain import spoken, words as closed_class

    if not isinstance(word, str) or not DECLARED_NAME.fullmatch(word):
        raise UserError(f"{what}: {word!r}: expected lowercase letters a-z, digits and '_', a letter first")
    if word in closed_class.CLOSED_CLASS or word in closed_class.NUMBERS:  # ("two red box" read as two boxes)
        raise UserError(f"{what}: {word!r} is a word of the grammar (a function word, a relation word, a verb or "
                        f"a number), which the readers read as such")
    taken = spoken.owner(word) or ("an object of any shape" if word in closed_class.ANY_SHAPE else None)
    if taken is not None:
        raise UserError(f"{what}: {word!r} already says {taken}; expected a word of its own")


def _declare_one(decl: Channel | Shape) -> None:
    if not isinstance(decl, (Channel, Shape)):
        raise UserError(f"{decl!r}: expected a channels.Channel or a catalog.Shape")
    taken = of_percept()
    if isinstance(decl, Shape):
        if catalog.percept(decl.name) in taken:
            raise UserError(f"shape {decl.name!r}: its percept {catalog.percept(decl.name)} is already a "
                            f"{taken[catalog.percept(decl.name)]}")
        _said_alone(f"shape {decl.name!r}", decl.name)
        from aileen.domain import guard

        catalog.add_shape(dataclasses.replace(decl, render=guard.guarded(f"shape {decl.name!r}: its render",
                                                                         decl.render)))
        _set_shape_channel()
        return
    if any(k in key_names() for k in (decl.name, *decl.keys)):  # ("color" is the colour's)
        raise UserError(f"channel {decl.name!r} is already declared")
    if not isinstance(decl.values, tuple) or not all(isinstance(v, str) for v in decl.values):
        raise UserError(f"channel {decl.name!r}: values {decl.values!r}: expected a tuple of names")
    if not decl.values or len(set(decl.values)) != len(decl.values):
        raise UserError(f"channel {decl.name!r}: its values must be distinct, and at least one")
    odd = [v for v in (decl.name, *decl.values) if not DECLARED_NAME.fullmatch(v)]
    if odd:  # a percept is `cv_<value>`, a clingo name ("Glossy" was refused as "not one of ... Glossy")
        raise UserError(f"channel {decl.name!r}: {odd[0]!r} must be lowercase letters a-z, digits and '_', "
                        f"a letter first")
    reserved = [k for k in (decl.name, *decl.keys) if k in _OTHER_KEYS]
    if reserved:  # ("position" was read as where the object stands, "signal" as the lesson's)
        raise UserError(f"channel {decl.name!r}: {reserved[0]!r} is a key {_OTHER_KEYS[reserved[0]]} gives to "
                        f"something else; expected a name of its own")
    clash = [p for p in decl.percepts if p in taken]
    if clash:
        raise UserError(f"channel {decl.name!r}: percept {clash[0]} is already a {taken[clash[0]]}")
    for v in decl.values:
        _said_alone(f"channel {decl.name!r}", v)
    for spelled in decl.spellings:
        if not isinstance(spelled, tuple) or len(spelled) != 2 or spelled[1] not in decl.values:
            raise UserError(f"channel {decl.name!r}: spelling {spelled!r}: expected (word, value) with value one "
                            f"of {', '.join(decl.values)}")
        if spelled[0] in decl.values or [s for s, _ in decl.spellings].count(spelled[0]) > 1:
            raise UserError(f"channel {decl.name!r}: spelling {spelled[0]!r} already says a value of it")
        _said_alone(f"channel {decl.name!r}", spelled[0])
    _findable(decl.measure_by, f"channel {decl.name!r}: its measure")
    _findable(decl.measure_all_by, f"channel {decl.name!r}: its measure_all_by")
    if decl.default is not None and decl.default not in decl.values:
        raise UserError(f"channel {decl.name!r}: default {decl.default!r} is not one of its values")
    CHANNELS.append(decl)
    appearance.LOOKS[decl.name] = decl.look


def declare(*decls: Channel | Shape) -> None:
    """Add channels (and shapes) for good: the agent's senses, the world's looks, the
    catalogue. A name or percept already taken is a `UserError`."""
    for decl in decls:
        _declare_one(decl)


@contextlib.contextmanager
def scope(*decls: Channel | Shape) -> Iterator[None]:
    """The declarations hold inside the `with` block only (a test's own channel or shape);
    afterwards the channels, the world's looks and the catalogue are as they were."""
    saved_channels, saved_looks = list(CHANNELS), dict(appearance.LOOKS)
    added_shapes: list[str] = []
    try:
        for decl in decls:
            _declare_one(decl)
            if isinstance(decl, Shape):
                added_shapes.append(decl.name)
        yield
    finally:
        global SHAPE
        for name in added_shapes:
            catalog.remove_shape(name)
        CHANNELS[:] = saved_channels
        SHAPE = next(c for c in CHANNELS if c.name == "shape")
        appearance.LOOKS.clear()
        appearance.LOOKS.update(saved_looks)
