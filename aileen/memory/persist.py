"""Reading and writing the concept memory file: versioned, human-readable JSON.

Why a module of its own: the file outlives the code that wrote it. Writing goes to a
temporary file in the same folder and is renamed over the target, so a crash never leaves a
half-written memory; reading checks the header before anything else and turns every
problem (not JSON, truncated, another format, a newer version, a malformed entry) into one
`UserError` naming the path. Reading never modifies the file.
"""

from __future__ import annotations

import errno
import json
import os
import stat
from pathlib import Path
from typing import Any

from aileen import textfile
from aileen.errors import UserError
from aileen.io import atomic_write_bytes, atomic_write_text
from aileen.strictjson import deeper_than, duplicate_key_line, no_duplicates

__all__ = ["FORMAT", "VERSION", "MAX_DEPTH", "write_json_atomic", "write_bytes_atomic", "read_json", "read_bytes",
           "parse_json", "check_annotations", "is_whole", "version_problem"]

FORMAT = "aileen-concept-memory"
#: Version of the file layout this code writes; it reads versions 1..VERSION.
VERSION = 1
#: The deepest nesting a memory file needs (document > concepts > concept > generalizations >
#: generalization > facts > fact): anything deeper is malformed, and very deep nesting would
#: exhaust Python's stack in the JSON reader.
MAX_DEPTH = 8
#: Where a word may stand in a noun phrase (the agent's lexicon, kept in the annotations).
POSITIONS = ("head", "modifier")


def check_annotations(notes: dict[str, Any]) -> str | None:
    """What is wrong with the annotations' known entries (the agent's lexicon), or None."""
    lex = notes.get("lexicon")
    if lex is None:
        return None
    if not isinstance(lex, dict) or set(lex) - {"positions", "distance", "seen"}:
        return "\"annotations\".\"lexicon\" must be an object with \"positions\", \"distance\" and \"seen\" only"
    positions = lex.get("positions", {})
    if not isinstance(positions, dict):
        return "\"annotations\".\"lexicon\".\"positions\" must map words to lists of positions"
    for word, ps in positions.items():
        if not isinstance(ps, list) or not all(p in POSITIONS for p in ps):
            return (f"\"annotations\".\"lexicon\".\"positions\".{json.dumps(word)} must be a list of "
                    f"{' / '.join(POSITIONS)}, found {json.dumps(ps)[:80]}")
    distance = lex.get("distance", {})
    if not isinstance(distance, dict):
        return "\"annotations\".\"lexicon\".\"distance\" must map words to [total, count]"
    for word, d in distance.items():
        if not (isinstance(d, list) and len(d) == 2 and all(is_whole(x) for x in d)):
            return (f"\"annotations\".\"lexicon\".\"distance\".{json.dumps(word)} must be [total, count], "
                    f"two whole numbers >= 0, found {json.dumps(d)[:80]}")
    return _check_seen(lex.get("seen"))


def is_whole(x: object) -> bool:
    """A whole number >= 0 (not a bool): what a count in a memory file must be."""
    return isinstance(x, int) and not isinstance(x, bool) and x >= 0


def _check_seen(seen: object) -> str | None:
    """What is wrong with the lexicon's counts of the objects taught on (`agent/seen.py`), or None."""
    if seen is None:
        return None
    where = "\"annotations\".\"lexicon\".\"seen\""
    if not (isinstance(seen, dict) and not set(seen) - {"objects", "percepts", "runs", "unbroken", "taught", "said"}
            and is_whole(seen.get("objects")) and isinstance(seen.get("percepts"), dict)
            and isinstance(seen.get("runs", {}), dict) and isinstance(seen.get("taught", {}), dict)
            and isinstance(seen.get("said", {}), dict)
            and isinstance(seen.get("unbroken", []), list) and all(isinstance(p, str) for p in seen.get("unbroken", []))):
        return (f"{where} must be {{\"objects\": a whole number, \"percepts\": {{percept: count}}}}, and may have "
                f"\"runs\": {{percept: count}}, \"unbroken\": [percept], \"taught\", \"said\": {{word: count}}")
    for part in ("percepts", "runs", "taught", "said"):
        for p, n in seen.get(part, {}).items():
            if not (is_whole(n) and n <= seen["objects"]):
                return (f"{where}.{json.dumps(part)}.{json.dumps(p)} must be a whole number from 0 to \"objects\" "
                        f"({seen['objects']}), found {json.dumps(n)[:80]}")
    return None


def write_json_atomic(path: str | os.PathLike[str], data: dict[str, Any]) -> None:
    """Write `data` as indented JSON to `path` atomically (`aileen.io`: temporary file, fsync,
    rename; a symbolic link and the file's mode are kept). Raises `OSError` when it cannot."""
    target = Path(path)
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        raise UserError(f"cannot save: folder {str(folder)!r} does not exist", path=str(target))
    atomic_write_text(target, json.dumps(data, indent=2, ensure_ascii=False) + "\n")


def write_bytes_atomic(path: str | os.PathLike[str], data: bytes) -> None:
    """`write_json_atomic` for a file's bytes (the compact form)."""
    target = Path(path)
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        raise UserError(f"cannot save: folder {str(folder)!r} does not exist", path=str(target))
    atomic_write_bytes(target, data)


def read_bytes(path: str | os.PathLike[str]) -> bytes:
    """The memory file's bytes. Opened without waiting (a FIFO would block the open until a
    writer came) and checked to be a regular file before a byte is read."""
    p = str(path)
    if not p:
        raise UserError("the memory file needs a name (an empty path was given)", path="''")
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0)
    try:
        fd = os.open(p, flags)
    except FileNotFoundError:
        raise UserError("no such memory file", path=p) from None
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            raise UserError("cannot read the memory file: the path is a loop of symbolic links", path=p) from None
        raise UserError(f"cannot read the memory file: {exc.strerror}", path=p) from None
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            kind = ("a directory" if stat.S_ISDIR(mode) else "a FIFO (named pipe)" if stat.S_ISFIFO(mode)
                    else "a device" if stat.S_ISCHR(mode) or stat.S_ISBLK(mode) else "not a regular file")
            raise UserError(f"cannot read the memory file: it is {kind}; expected a regular file", path=p)
        with os.fdopen(os.dup(fd), "rb") as fh:
            data = fh.read()
    except OSError as exc:
        raise UserError(f"cannot read the memory file: {exc.strerror or exc}", path=p) from None
    finally:
        os.close(fd)
    return data


def read_json(path: str | os.PathLike[str]) -> dict[str, Any]:
    """Read and check a memory file's header; returns the whole document."""
    return parse_json(read_bytes(path), str(path))


def parse_json(raw: bytes, p: str) -> dict[str, Any]:
    """A JSON memory file's bytes (read from `p`), its header checked; the whole document."""
    text = textfile.decoded(raw, p, "memory file")  # an editor's byte order mark is read past, as in lesson files
    if not text.strip():
        raise UserError("memory file is empty", path=p)
    if "\x00" in text:  # no JSON text has one: a file zero-filled by a crash, or binary bytes
        at = text.index("\x00")
        line = text.count("\n", 0, at) + 1
        column = at - (text.rfind("\n", 0, at) + 1) + 1
        raise UserError(f"memory file is damaged: it holds NUL bytes from column {column} on (zeros where "
                        "text should be, as a crash can leave a file), so it is not JSON", path=p, line=line)
    try:
        data = json.loads(text, object_pairs_hook=no_duplicates)
    except json.JSONDecodeError as exc:
        if not text.lstrip().startswith("{"):  # not a cut-off memory: something else (a lesson file)
            raise UserError("not an aileen concept memory: a memory file is a JSON object ({...}); "
                            "lesson files are run with 'aileen run'", path=p, line=exc.lineno) from None
        ends_open = not text.rstrip().endswith("}")
        what = "truncated (not valid JSON)" if ends_open else "not valid JSON"
        raise UserError(f"memory file is {what}: {exc.msg} (column {exc.colno})", path=p, line=exc.lineno) from None
    except RecursionError:
        raise UserError(f"malformed memory file: nested deeper than {MAX_DEPTH} levels", path=p) from None
    except ValueError as exc:  # a duplicate key
        raise UserError(f"malformed memory file: {exc}", path=p, line=duplicate_key_line(text)) from None
    if deeper_than(data, MAX_DEPTH):
        raise UserError(f"malformed memory file: nested deeper than {MAX_DEPTH} levels", path=p)
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise UserError(f"not an aileen concept memory (expected \"format\": \"{FORMAT}\")", path=p)
    problem = version_problem(data)
    if problem is not None:
        raise UserError(problem, path=p)
    return data


def version_problem(header: dict[str, Any]) -> str | None:
    """What is wrong with a memory file's "version" (either form's header), or None. Said as
    the file says it (`true`, `"1"`, or missing), not in Python's spelling (`True`, `None`)."""
    if "version" not in header:
        return "the format version is missing (expected \"version\": an integer >= 1)"
    version = header["version"]
    if not is_whole(version) or version < 1:
        return f"bad format version {json.dumps(version)[:80]} (expected an integer >= 1)"
    if version > VERSION:
        return f"memory file has format version {version}, newer than this aileen reads ({VERSION}); upgrade aileen"
    return None
