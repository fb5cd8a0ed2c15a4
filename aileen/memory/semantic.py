"""Semantic memory: the maps between words and concept symbols, queried both ways.

In the paper these are Soar's map nodes (M1..M6). A concept symbol is made from its word
(`red` -> `r_red`, `left of` -> `r_left_of`), which keeps memory files readable; the kind
(visual, spatial, action) records which syntactic role taught the word.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from aileen.domain import predicates
from aileen.memory.kinds import KINDS

_SAFE = re.compile(r"[^a-z0-9_]+")


def concept_symbol(word: str) -> str:
    """The concept symbol for a word: lowercase, ASP-safe, prefixed `r_`."""
    core = _SAFE.sub("_", word.strip().lower()).strip("_")
    if not core:
        raise ValueError(f"cannot make a concept symbol from {word!r}")
    return f"{predicates.CONCEPT_PREFIX}{core}"


def word_of(symbol: str) -> str:
    """The word a concept symbol was made from (`concept_symbol`): `r_left_of` -> "left of"."""
    return symbol.removeprefix(predicates.CONCEPT_PREFIX).replace("_", " ")


def part_of(part: str, whole: str) -> bool:
    """Is the word of concept `part` a run of the words concept `whole`'s word is said with
    ("right of" in "behind right of", "left of" in "far left of"; not "of", nor the word
    itself)? Read from the symbols, which are made from the words (`concept_symbol`)."""
    a, b = part.removeprefix("r_").split("_"), whole.removeprefix("r_").split("_")
    return len(a) < len(b) and any(b[i:i + len(a)] == a for i in range(len(b) - len(a) + 1))


@dataclass
class SemanticMemory:
    """word <-> concept symbol, with the concept's kind."""

    _concepts: dict[str, str] = field(default_factory=dict)  # word -> concept
    _words: dict[str, str] = field(default_factory=dict)  # concept -> word
    _kinds: dict[str, str] = field(default_factory=dict)  # concept -> kind

    def concept(self, word: str) -> str | None:
        return self._concepts.get(word)

    def word(self, concept: str) -> str | None:
        return self._words.get(concept)

    def kind(self, concept: str) -> str | None:
        return self._kinds.get(concept)

    def add(self, word: str, kind: str) -> str:
        if kind not in KINDS:
            raise ValueError(f"unknown concept kind {kind!r}; expected one of {KINDS}")
        symbol = self._concepts.get(word)
        if symbol is None:
            symbol = concept_symbol(word)
            self._concepts[word] = symbol
            self._words[symbol] = word
            self._kinds[symbol] = kind
        return symbol

    def words(self) -> dict[str, str]:
        """A copy of the word -> concept map (what comprehension receives)."""
        return dict(self._concepts)

    def __len__(self) -> int:
        return len(self._concepts)

    def to_dict(self) -> dict[str, dict[str, str]]:
        return {w: {"concept": c, "kind": self._kinds[c]} for w, c in sorted(self._concepts.items())}

    @classmethod
    def from_dict(cls, data: dict[str, dict[str, str]]) -> "SemanticMemory":
        mem = cls()
        for word, entry in data.items():
            concept, kind = entry["concept"], entry["kind"]
            if kind not in KINDS:
                raise ValueError(f"word {word!r}: unknown kind {kind!r}")
            mem._concepts[word] = concept
            mem._words[concept] = word
            mem._kinds[concept] = kind
        return mem


def from_concepts(memory: "ConceptMemory") -> SemanticMemory:  # noqa: F821 - typing only
    """Rebuild the word maps from a concept memory: every concept symbol is `r_` + its word
    (see `concept_symbol`), so a saved concept memory carries the semantic memory with it."""
    sem = SemanticMemory()
    for c in memory.concepts():
        if not c.symbol.startswith("r_"):
            continue
        word = c.symbol[2:]
        sem._concepts[word] = c.symbol
        sem._words[c.symbol] = word
        sem._kinds[c.symbol] = c.kind
    return sem
