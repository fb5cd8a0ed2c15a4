"""Where a lesson and its fields stand in an original-format script's text: what a
`UserError` about them names (`file:line: lesson N: ...`).

Why apart: `json` hands back values without their places, and both the lesson reader
(`legacy`) and the description reader (`legacy_description`) name where a value they
refuse stands.
"""

from __future__ import annotations

import json

from aileen.curriculum.lesson import Source
from aileen.errors import UserError

__all__ = ["EXPECT_KEY", "Where", "field", "spans"]

EXPECT_KEY = "is_positive"  # the original scripts' key for what a correct learner answers


def spans(text: str) -> list[tuple[int, int]]:
    """Character spans of the top-level list's elements (the text is known to be valid JSON)."""
    decoder = json.JSONDecoder()
    spans: list[tuple[int, int]] = []
    i = text.index("[") + 1
    n = len(text)
    while True:
        while i < n and text[i] in " \t\r\n,":
            i += 1
        if i >= n or text[i] == "]":
            return spans
        _, end = decoder.raw_decode(text, i)
        spans.append((i, end))
        i = end


class Where:
    """Locates a lesson and the fields inside it in the script text."""

    def __init__(self, text: str, path: str, index: int, span: tuple[int, int] | None) -> None:
        self.text = text
        self.span = span
        line = text.count("\n", 0, span[0]) + 1 if span else None
        self.source = Source(path, line, index + 1, expect_key=EXPECT_KEY)

    def line_of(self, *needles: str) -> int | None:
        """Line of the first needle found (in order, each after the previous) inside the lesson."""
        if self.span is None:
            return None
        pos = self.span[0]
        found = False
        for needle in needles:
            at = self.text.find(needle, pos, self.span[1])
            if at < 0:
                break
            pos, found = at, True
        return self.text.count("\n", 0, pos) + 1 if found else self.source.line

    def error(self, message: str, *needles: str) -> UserError:
        return self.source.error(message, line=self.line_of(*needles) if needles else None)


def field(name: str) -> str:
    """A field's name as it stands in the text (what `Where.line_of` looks for)."""
    return f'"{name}"'
