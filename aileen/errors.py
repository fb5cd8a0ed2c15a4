"""Errors a user can cause, as opposed to bugs.

The CLI prints a `UserError` as one line on stderr and exits 2; anything else is a bug and
keeps its traceback. Messages name the file, line and what was expected where there is one.
"""

from __future__ import annotations


def said_number(v: float) -> str:
    """A position (metres) in a message: to the millimetre on a table's scale, in three digits
    past it (1e308 was printed with 300 digits, twice, in one line)."""
    return f"{v:.3f}" if abs(v) < 1e6 else f"{v:.3g}"


class UserError(Exception):
    """Bad input from a user: a file, a name, a command. Printed as one line, exit code 2."""

    def __init__(self, message: str, *, path: str | None = None, line: int | None = None) -> None:
        self.message = message
        self.path = path
        self.line = line
        super().__init__(self.format())

    def format(self) -> str:
        where = ""
        if self.path is not None:
            where = f"{self.path}:{self.line}: " if self.line is not None else f"{self.path}: "
        return f"{where}{self.message}"


class NoRoom(UserError):
    """The world has no room for this move where the objects stand now (a push that would
    carry an object off the table): where a trainer laid the table out, another layout may
    have room, so a lesson's demonstration that meets it is skipped, not refused."""
