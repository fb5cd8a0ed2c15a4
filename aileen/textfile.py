"""Reading a text file a person wrote (a lesson file, a grid): its text, or one line saying why not.

Why one helper: a file that is not UTF-8 was "cannot read lesson file: 'utf-8' codec can't
decode byte 0xff in position 45: invalid start byte" (Python's words, a byte offset, no line)
in one reader and something else in the next. Here every reader says where, in the file's
terms (its line), and what was expected. A byte order mark at the start is read past, as
editors on Windows write one.
"""

from __future__ import annotations

from pathlib import Path

from aileen.errors import UserError

__all__ = ["read_text", "decoded"]


def decoded(raw: bytes, path: str, what: str) -> str:
    """`raw` as UTF-8 text, or a `UserError` naming the line of the first byte that is not."""
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = raw[:exc.start].count(b"\n") + 1
        raise UserError(f"not UTF-8 text (byte {exc.start}, 0x{raw[exc.start]:02x}); expected a {what} "
                        "in UTF-8", path=path, line=line) from None


def read_text(path: str | Path, what: str, missing: str) -> str:
    """The text of the file at `path`, a `what` ("lesson file"); `missing` is said when there
    is none. A folder, an unreadable file or bytes that are not UTF-8 are one `UserError`."""
    p = Path(path)
    try:
        raw = p.read_bytes()
    except FileNotFoundError:
        raise UserError(missing, path=str(p)) from None
    except IsADirectoryError:
        raise UserError(f"is a folder, not a {what}", path=str(p)) from None
    except OSError as exc:
        raise UserError(f"cannot read the {what}: {(exc.strerror or str(exc)).lower()}", path=str(p)) from None
    return decoded(raw, str(p), what)
