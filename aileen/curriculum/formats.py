"""Lesson files: `.toml` (our format, `lessonfile`) or `.json` (the original AILEEN scripts,
`legacy`), chosen by extension."""

from __future__ import annotations

from pathlib import Path

from aileen.curriculum.lesson import Curriculum
from aileen.errors import UserError


def read_lesson_text(path: str | Path) -> str:
    """A lesson file's text; a missing or unreadable file is a `UserError` naming it."""
    p = Path(path)
    try:
        return p.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise UserError("no such lesson file", path=str(p)) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise UserError(f"cannot read lesson file: {exc}", path=str(p)) from None


def load_curriculum(path: str | Path) -> Curriculum:
    """Read a lesson file: `.toml` (our format) or `.json` (the original AILEEN scripts)."""
    p = Path(path)
    suffix = p.suffix.lower()
    if suffix == ".toml":
        from aileen.curriculum.lessonfile import load

        return load(p)
    if suffix == ".json":
        from aileen.curriculum.legacy import load

        return load(p)
    raise UserError(f"cannot tell the lesson format of {str(p)!r}; expected a .toml or .json file")
