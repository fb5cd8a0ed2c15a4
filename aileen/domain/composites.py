"""Composite words: concepts over several objects, as the trainer lays them out and judges them.

A composite is a number of parts (each an object description: "box", or any object) and an
arrangement: relations between parts, `(i, relation, j)` meaning part i stands in `relation`
to part j (relations from `aileen.domain.relations`). "wall": three boxes side by side in a
row, touching; "tower": one object resting on a box. Like the relations, these are the
trainer's meaning, for laying scenes out and grading; the agent learns the word from examples.

To add a composite word: one `Composite` in `COMPOSITES`.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass

from aileen.domain import relations
from aileen.errors import UserError


@dataclass(frozen=True)
class Composite:
    word: str
    parts: tuple[str | None, ...]  # a shape each part must have (None: any object)
    arrangement: tuple[tuple[int, str, int], ...]  # (i, relation, j): part i <relation> part j

    def accepts(self, objects: Sequence[relations.OnTable]) -> bool:
        """Does some choice of distinct objects on the table form this composite (as a person
        judges its relations)?"""
        for combo in itertools.permutations(objects, len(self.parts)):
            if any(shape is not None and getattr(o, "shape", None) != shape for o, shape in zip(combo, self.parts)):
                continue
            if all(relations.get(r).accepts(combo[i], combo[j]) for i, r, j in self.arrangement):
                return True
        return False


COMPOSITES: dict[str, Composite] = {
    c.word: c
    for c in (
        Composite("wall", ("box", "box", "box"), ((1, "right of ec", 0), (2, "right of ec", 1))),
        Composite("tower", ("box", None), ((1, "on", 0),)),  # nothing stays on a sphere or a cone
    )
}


def get(word: str) -> Composite:
    try:
        return COMPOSITES[word.strip().lower()]
    except KeyError:
        raise UserError(f"unknown composite word {word!r}; expected one of: {', '.join(COMPOSITES)}") from None
