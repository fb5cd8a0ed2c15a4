"""What a lesson describes: an object (`ObjectSpec`) and an action word (`ActionSpec`).

Both the lesson records (`curriculum.lesson`) and the trainer's reading of its sentences
(`curriculum.sentences`, which makes these from "large red box" and "move right of") use
them, so they stand below both.
"""

from __future__ import annotations

from dataclasses import dataclass

from aileen.domain import relations

__all__ = ["ActionSpec", "ObjectSpec"]


@dataclass(frozen=True)
class ObjectSpec:
    """One described object. `None` shape, colour or size means "any": the trainer chooses
    (a shape or colour at random; a size as the lesson's relation needs, else the default)."""

    shape: str | None = None
    colour: str | None = None
    size: str | None = None
    position: tuple[float, float] | None = None  # table metres; None = the trainer chooses

    def describe(self) -> str:
        words = [self.size or "", self.colour or "", self.shape or "object"]
        return " ".join(w for w in words if w)

    def matches(self, shape: str, colour: str, size: str | None = None) -> bool:
        """Would an object of this shape, colour (and size, when given) fit this description?"""
        return ((self.shape is None or self.shape == shape) and (self.colour is None or self.colour == colour)
                and (self.size is None or size is None or self.size == size))


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
