"""What an object looks like, channel by channel: one record for every part that carries it.

An object's appearance is one frozen mapping from channel name to value, `{"shape": "box",
"colour": "red", "size": "medium"}`, in channel order. The world's objects, the camera's
ground truth, the trainer's plans, the lesson's descriptions, the console's table and the data
set's labels all hold one `Appearance` instead of a field per channel, so a channel declared in
`aileen.domain.channels` (its values, its measure and its render function) reaches all of them
without a new field anywhere.

The body (shape, colour and size: `BODY`) is the world's own: the catalogue says what each
value is (`aileen.world.catalog`: footprints, shades, metres), the physics moves it and the
camera draws it. Any other channel is a `Look`: its values, the value an object shows when
nobody says, and the function that paints it on the camera image (`render(value, canvas)`,
on the `Canvas` of one object). The domain's channel declarations put their looks in `LOOKS`
(`aileen.domain.channels.declare`); this module stands below them so that the world, which
the domain reads, never reads the domain.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Mapping
from dataclasses import dataclass
from typing import Any

from aileen.errors import UserError

__all__ = ["Appearance", "BODY", "BodyChannels", "Canvas", "Look", "LOOKS", "complete", "described"]

BODY: tuple[str, ...] = ("shape", "colour", "size")  # the channels the world's catalogue holds


class Appearance(Mapping[str, str]):
    """Channel name -> value, frozen and hashable; the order is the order given.

    Two appearances are equal when they hold the same values (order aside). A description
    may leave channels out (`ObjectSpec`: "red object" says no shape); an object in the world
    has every channel.
    """

    __slots__ = ("_items", "_hash")

    def __init__(self, values: Mapping[str, str] | Iterable[tuple[str, str]] = (), /, **more: str) -> None:
        pairs = list(values.items() if isinstance(values, Mapping) else values) + list(more.items())
        seen: dict[str, str] = {}
        for name, value in pairs:
            if not isinstance(name, str) or not isinstance(value, str):
                raise TypeError(f"an appearance maps channel names to values (strings), got {name!r}: {value!r}")
            seen[name] = value
        self._items: tuple[tuple[str, str], ...] = tuple(seen.items())
        self._hash: int | None = None

    def __getitem__(self, name: str) -> str:
        for k, v in self._items:
            if k == name:
                return v
        raise KeyError(name)

    def __iter__(self) -> Iterator[str]:
        return (k for k, _ in self._items)

    def __len__(self) -> int:
        return len(self._items)

    def __eq__(self, other: object) -> bool:
        if isinstance(other, Appearance):
            return dict(self._items) == dict(other._items)
        if isinstance(other, Mapping):
            return dict(self._items) == dict(other)
        return NotImplemented

    def __hash__(self) -> int:
        if self._hash is None:
            self._hash = hash(frozenset(self._items))
        return self._hash

    def __repr__(self) -> str:
        return f"Appearance({', '.join(f'{k}={v!r}' for k, v in self._items)})"

    def __reduce__(self) -> tuple[Any, ...]:
        return (Appearance, (self._items,))

    def replace(self, **changes: str | None) -> Appearance:
        """A copy with some channels set (a value) or left out (None)."""
        out = dict(self._items)
        for name, value in changes.items():
            if value is None:
                out.pop(name, None)
            else:
                out[name] = value
        return Appearance(out)


class BodyChannels:
    """`shape`, `colour` and `size` read from a record's `appearance` (None where a description
    leaves one open): the body's channels by name, for the code that is about the body (the
    physics, stacking, a comparative's sizes). Code about an object's kind reads the
    appearance, every channel alike."""

    __slots__ = ()
    appearance: Appearance

    @property
    def shape(self) -> str | None:
        return self.appearance.get("shape")

    @property
    def colour(self) -> str | None:
        return self.appearance.get("colour")

    @property
    def size(self) -> str | None:
        return self.appearance.get("size")


def described(shape: str | None = None, colour: str | None = None, size: str | None = None,
              appearance: Mapping[str, str] | None = None, looks: Mapping[str, str | None] | None = None
              ) -> Appearance:
    """The appearance of a description given channel by channel (None: left open); the body's
    channels first, then `appearance`'s and `looks`' (keyword) values."""
    pairs = [("shape", shape), ("colour", colour), ("size", size), *(appearance or {}).items(), *(looks or {}).items()]
    return Appearance([(k, v) for k, v in pairs if v is not None])


@dataclass
class Canvas:
    """One object's patch of the camera image while it is drawn, for a look's render function.

    `X`, `Y` are the pixel centres in units of the footprint's half size, relative to the
    object's centre (X east, Y north); `angle` its rotation (radians), `r_px` the half size in
    pixels, `light` the unit vector toward the light. A render function changes the maps in
    place: `bright` (shading, 1 = flat top under the light), `spec` (specular highlight, or
    None), `rgb` (the surface colour, 0-255, shape (3,) or (H, W, 3)); `alpha` (coverage)
    is the body's silhouette and is best left alone.
    """

    X: Any
    Y: Any
    angle: float
    r_px: float
    light: Any
    alpha: Any
    bright: Any
    spec: Any
    rgb: Any


Render = Callable[[str, Canvas], None]


@dataclass(frozen=True)
class Look:
    """A channel beyond the body, as the world holds it: its values, the value an object shows
    when nobody says (`default`), and how the camera paints it (None: the camera does not
    show it; the ground truth still holds it)."""

    name: str
    values: tuple[str, ...]
    default: str
    render: Render | None = None

    def check(self, value: str) -> str:
        if value not in self.values:
            raise UserError(f"unknown {self.name} {value!r}; expected one of: {', '.join(self.values)}")
        return value


# The looks declared beyond the body, in channel order (filled by `aileen.domain.channels`).
LOOKS: dict[str, Look] = {}


def complete(appearance: Mapping[str, str]) -> Appearance:
    """An object's whole appearance: the body's channels in order, then every declared look
    (its default where the appearance says nothing). Raises `UserError` for a channel no one
    declared or a value the look does not have; the body's values are checked by the world."""
    for name in appearance:
        if name not in BODY and name not in LOOKS:
            known = ", ".join((*BODY, *LOOKS))
            raise UserError(f"unknown channel {name!r}; expected one of: {known}")
    body = [(n, appearance[n]) for n in BODY if n in appearance]
    looks = [(n, look.check(appearance.get(n, look.default))) for n, look in LOOKS.items()]
    return Appearance(body + looks)
