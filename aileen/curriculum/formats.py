"""Lesson files: `.toml` (our format, `lessonfile`) or `.json` (the original AILEEN scripts,
`legacy`), chosen by extension. Both readers take the file's text from
`lesson.read_lesson_text`."""

from __future__ import annotations

from pathlib import Path

from aileen.curriculum import legacy, lessonfile
from aileen.curriculum.lesson import Curriculum
from aileen.errors import UserError


def load_curriculum(path: str | Path) -> Curriculum:
    """Read a lesson file: `.toml` (our format) or `.json` (the original AILEEN scripts)."""
    p = Path(path)
    suffix = p.suffix.lower()
    if suffix == ".toml":
        return lessonfile.load(p)
    if suffix == ".json":
        return legacy.load(p)
    raise UserError(f"cannot tell the lesson format of {str(p)!r}; expected a .toml or .json file")
