"""Reading and writing the concept memory file: versioned, human-readable JSON.

Why a module of its own: the file outlives the code that wrote it. Writing goes to a
temporary file in the same folder and is renamed over the target, so a crash never leaves a
half-written memory; reading checks the header before anything else and turns every
problem (not JSON, truncated, another format, a newer version, a malformed entry) into one
`UserError` naming the path. Reading never modifies the file.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

from aileen.errors import UserError
from aileen.io import atomic_write_text

__all__ = ["FORMAT", "VERSION", "write_json_atomic", "read_json"]

FORMAT = "aileen-concept-memory"
#: Version of the file layout this code writes; it reads versions 1..VERSION.
VERSION = 1


def write_json_atomic(path: str | os.PathLike[str], data: dict[str, Any]) -> None:
    """Write `data` as indented JSON to `path` atomically (`aileen.io`: temporary file, fsync,
    rename; a symbolic link and the file's mode are kept). Raises `OSError` when it cannot."""
    target = Path(path)
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        raise UserError(f"cannot save: folder {str(folder)!r} does not exist", path=str(target))
    atomic_write_text(target, json.dumps(data, indent=2, ensure_ascii=False) + "\n")


def read_json(path: str | os.PathLike[str]) -> dict[str, Any]:
    """Read and check a memory file's header; returns the whole document."""
    p = str(path)
    try:
        with open(p, encoding="utf-8") as fh:
            text = fh.read()
    except FileNotFoundError:
        raise UserError("no such memory file", path=p) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise UserError(f"cannot read memory file: {exc}", path=p) from None
    if not text.strip():
        raise UserError("memory file is empty", path=p)
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        ends_open = not text.rstrip().endswith("}")
        what = "truncated (not valid JSON)" if ends_open else "not valid JSON"
        raise UserError(f"memory file is {what}: {exc.msg} (column {exc.colno})", path=p, line=exc.lineno) from None
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise UserError(f"not an aileen concept memory (expected \"format\": \"{FORMAT}\")", path=p)
    version = data.get("version")
    if not isinstance(version, int) or isinstance(version, bool) or version < 1:
        raise UserError(f"bad format version {version!r} (expected an integer >= 1)", path=p)
    if version > VERSION:
        raise UserError(
            f"memory file has format version {version}, newer than this aileen reads ({VERSION}); upgrade aileen",
            path=p,
        )
    return data
