"""What a lesson describes: an object (`ObjectSpec`) and an action word (`ActionSpec`).

Both the lesson records (`curriculum.lesson`) and the trainer's reading of its sentences
(`curriculum.sentences`, which makes these from "large red box" and "move right of") use
them, so they stand below both.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from aileen.domain import channels, relations
from aileen.world.appearance import Appearance, BodyChannels, described

__all__ = ["ActionSpec", "ObjectSpec"]


@dataclass(frozen=True, init=False, repr=False)
class ObjectSpec(BodyChannels):
    """One described object: what it looks like, channel by channel, and where it stands. A
    channel the appearance leaves out means "any": the trainer chooses (a shape, a colour or
    any other channel without a default at random; a size as the lesson's relation needs, else
    the default; any other channel its default).

    Written channel by channel, `ObjectSpec("box", "red")`, `ObjectSpec(shape="box",
    texture="striped")`, or from an appearance, `ObjectSpec(appearance=...)`; the values are
    kept in channel order. `shape`, `colour` and `size` read the appearance (None when open)."""

    appearance: Appearance
    position: tuple[float, float] | None = None  # table metres; None = the trainer chooses

    def __init__(self, shape: str | None = None, colour: str | None = None, size: str | None = None,
                 position: tuple[float, float] | None = None, *, appearance: Mapping[str, str] | None = None,
                 **looks: str | None) -> None:
        given = described(shape, colour, size, appearance, looks)
        object.__setattr__(self, "appearance", channels.appearance_of(given))
        object.__setattr__(self, "position", position)

    def __repr__(self) -> str:
        """As written channel by channel: the body's three, the position, then any other."""
        rest = "".join(f", {k}={v!r}" for k, v in self.appearance.items() if k not in ("shape", "colour", "size"))
        return (f"ObjectSpec(shape={self.shape!r}, colour={self.colour!r}, size={self.size!r}, "
                f"position={self.position!r}{rest})")

    def describe(self) -> str:
        """The trainer's words for it: its values, the shape last ("large red box"), or "object"."""
        words = [v for k, v in self.appearance.items() if k != "shape"]
        return " ".join([*reversed(words), self.shape or "object"])

    def fits(self, kind: Mapping[str, str]) -> bool:
        """Would an object of this kind (channel -> value) fit this description? A channel the
        kind does not say (a size, when only shape and colour are known) is not checked."""
        return all(kind.get(name, value) == value for name, value in self.appearance.items())

    def matches(self, shape: str, colour: str, size: str | None = None) -> bool:
        """Would an object of this shape, colour (and size, when given) fit this description?"""
        return self.fits(described(shape, colour, size))

    def with_values(self, **values: str | None) -> ObjectSpec:
        """A copy with some channels set (or left open: None)."""
        return ObjectSpec(appearance=self.appearance.replace(**values), position=self.position)


@dataclass(frozen=True)
class ActionSpec:
    """An action word as the trainer means it: `move X <relation> Y`, or `push X`."""

    verb: str
    relation: str | None = None  # canonical relation name, for verbs that take one

    @property
    def name(self) -> str:
        return f"{self.verb} {self.relation}" if self.relation else self.verb

    @property
    def symbol(self) -> str:
        """`move_right_of`, `push`; the agent's concept is `r_move_right_of`, `r_push`."""
        return f"{self.verb}_{relations.get(self.relation).symbol}" if self.relation else self.verb

    @property
    def n_objects(self) -> int:
        return 2 if self.relation else 1
