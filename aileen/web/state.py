"""The console's table and transcript, kept beside the memory file across restarts.

Why a file of its own: the memory file holds what the agent learned, in a format other
commands read; the console's table and the lessons given are the session's, not the agent's.
They are written together with the memory (the Save button, leaving the server), with the
SHA-256 of the memory file as it was just written. At the next start they are restored only
when the memory file is still that one: a memory that another run changed meanwhile would
not be the memory the transcript taught, so the old state is moved aside (named) and the
console starts with an empty table.

`keep` and `recall` are the session's two calls (moved here from `session`, whose job is
teaching, not files). `m.json` -> `m.console.json` (`path_for`), written atomically (`aileen.io`); any
problem reading it is one `UserError` naming the file.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import shutil
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

from aileen.curriculum import lessonfile, trainer
from aileen.curriculum.lesson import Lesson, Source
from aileen.curriculum.stage import off_table
from aileen.errors import UserError
from aileen.io import atomic_write_text
from aileen.strictjson import deeper_than, no_duplicates
from aileen.web import transcript
from aileen.web.table import MAX_OBJECTS, Placed
from aileen.world.camera import Table
from aileen.domain import channels
from aileen.world.appearance import Appearance

FORMAT = "aileen-console-state"
VERSION = 1
MAX_DEPTH = 12  # document > records > record > referents > phrase > ids, with room to spare


@dataclass
class Saved:
    """What a restart restores: the table, the transcript and the scene's version."""

    version: int
    objects: list[Placed]
    blocks: list[str]  # lesson-file blocks, one per lesson (docs/lessons.md)
    records: list[dict[str, Any]]  # each lesson's and verdict's `aileen run --json` record
    memory_sha256: str | None = None


def path_for(memory_path: str | os.PathLike[str]) -> Path:
    """The state file of a memory file, in its folder: `m.json` -> `m.console.json`; any other
    name, `m.amem` or `m`, -> `m.amem.console-state.json`. One per memory file: `m.json` and
    `m.amem` shared `m.console.json`, and one session's table and transcript were lost. (The
    two forms end differently, so no two memory files share one.)"""
    p = Path(memory_path)
    if p.suffix == ".json":
        return p.with_name(f"{p.stem}.console.json")
    return p.with_name(f"{p.name}.console-state.json")


def start_path_for(memory_path: str | os.PathLike[str]) -> Path:
    """Where the memory a transcript starts from is kept, beside its state file, in the memory
    file's form: `m.json` -> `m.console.start.json`, `m.amem` -> `m.amem.console-state.start.amem`.
    The memory file itself holds the taught memory once the session saves."""
    where = path_for(memory_path)
    return where.with_name(where.name.removesuffix(".json") + ".start" + Path(memory_path).suffix)


def keep_start(memory_path: str | os.PathLike[str], agent: Any) -> Path:
    """At the start of a new transcript: a copy of the memory file as it is now (the agent's
    memory, empty, when there is no file yet), so the downloaded lesson file can say what
    replays it. Returns where it went."""
    start = start_path_for(memory_path)
    part = start.with_name(f".{start.name}.part")
    try:
        if Path(memory_path).is_file():
            shutil.copyfile(memory_path, part)
            os.replace(part, start)
        else:
            agent.save(str(start))
    except OSError as exc:
        raise UserError(f"cannot keep a copy of the memory the session starts from: {exc.strerror or exc}",
                        path=str(start)) from None
    return start


def legacy_path_for(memory_path: str | os.PathLike[str]) -> Path:
    """The name a console before `path_for` gave the state of `m.amem` or `m`: `m.console.json`,
    shared with `m.json`'s (read only when its memory SHA-256 says it is this memory file's)."""
    p = Path(memory_path)
    return p.with_name(f"{p.name[: -len(p.suffix)] if p.suffix else p.name}.console.json")


def aside_path(state_path: Path) -> Path:
    """Where a state that no longer fits the memory file is moved: `m.console.old.json`, or
    when that is taken `m.console.old.2.json`, `.3` ...: a second set-aside overwrote the
    first, and its transcript was lost."""
    base = state_path.name.removesuffix(".json")
    aside, n = state_path.with_name(f"{base}.old.json"), 1
    while aside.exists():
        n += 1
        aside = state_path.with_name(f"{base}.old.{n}.json")
    return aside


def digest(path: str | os.PathLike[str]) -> str | None:
    """SHA-256 of a file's bytes; None when there is no such file."""
    h = hashlib.sha256()
    try:
        with open(path, "rb") as fh:
            for chunk in iter(lambda: fh.read(1 << 20), b""):
                h.update(chunk)
    except FileNotFoundError:
        return None
    return h.hexdigest()


#: A state file's keys (`write`), every one read back by `read`.
KEYS = ("format", "version", "scene_version", "memory_sha256", "table", "blocks", "records")


def write(path: str | os.PathLike[str], saved: Saved) -> None:
    doc = {"format": FORMAT, "version": VERSION, "scene_version": saved.version,
           "memory_sha256": saved.memory_sha256,
           "table": [{**o.appearance, "x": o.x, "y": o.y, "distractor": o.distractor} for o in saved.objects],
           "blocks": saved.blocks, "records": saved.records}
    atomic_write_text(path, json.dumps(doc, indent=1, ensure_ascii=False) + "\n")


def keep(memory_path: str | os.PathLike[str], version: int, objects: list[Placed], blocks: list[str],
         records: list[dict[str, Any]]) -> None:
    """The table and transcript beside the memory file, marked with the memory file as it
    is now (call it after the memory was saved)."""
    where = path_for(memory_path)
    try:
        write(where, Saved(version, list(objects), list(blocks), list(records), digest(memory_path)))
    except OSError as exc:
        raise UserError(f"saved the memory, but not the table and transcript: {exc.strerror or exc}",
                        path=str(where)) from None


def recall(memory_path: str | os.PathLike[str], table: Table) -> tuple[Saved | None, str | None]:
    """At start: the state saved beside the memory file when it goes with the memory file as
    it is now, and a line to print (None, None: there was none). A state saved with another
    version of the memory file is moved aside (None and a warning); one that holds no object
    and no lesson is restored without a line. `table`: the console's,
    which the saved objects must stand on (`check_table`)."""
    where = path_for(memory_path)
    moved = ""
    if not where.exists():
        legacy = legacy_path_for(memory_path)
        sha = _sha_in(legacy) if legacy != where and legacy.is_file() else None
        if sha is None or sha != digest(memory_path):
            return None, None
        os.replace(legacy, where)  # unambiguous: it was saved with this very memory file
        moved = f" (moved there from {legacy}, the name it had before)"
    saved = read(where)
    check_table(saved.objects, table, where)
    if saved.memory_sha256 != digest(memory_path):
        aside = aside_path(where)
        os.replace(where, aside)
        return None, (f"warning: {where} was saved with another version of {memory_path} (another run "
                      f"changed it); moved it to {aside} and started with an empty table")
    if not saved.objects and not saved.blocks:  # nothing to say: "restored ... 0 objects and 0 lessons"
        return saved, None
    return saved, (f"restored the table ({_counted(len(saved.objects), 'object')}) and "
                   f"{_counted(len(saved.blocks), 'lesson')} from {where}{moved}")


def _counted(n: int, noun: str) -> str:
    """`1 object`, `2 objects`: the line said "(1 objects) and 1 lessons"."""
    return f"{n} {noun}" if n == 1 else f"{n} {noun}s"


def _sha_in(path: Path) -> str | None:
    """The memory SHA-256 a state file records; None when it cannot be read as one."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    sha = data.get("memory_sha256") if isinstance(data, dict) else None
    return sha if isinstance(sha, str) else None


def _malformed(path: str | os.PathLike[str]) -> Callable[[str], UserError]:
    """The one error of a state file that cannot be restored, naming it and what is wrong."""
    def bad(what: str) -> UserError:
        return UserError(f"malformed console state ({what}); move it aside to start with an empty table",
                         path=str(path))
    return bad


def check_table(objects: list[Placed], table: Table, path: str | os.PathLike[str]) -> None:
    """The saved table must be one the console can show: a table with an object off it, or 40
    on one spot, was restored, and then every scene request failed on it (naming table object
    0 `objects[1]`). The checks of a lesson's table (`trainer.layout`), said of the state file."""
    bad = _malformed(path)
    if len(objects) > MAX_OBJECTS:
        raise bad(f"its table has {len(objects)} objects; the console's table holds at most {MAX_OBJECTS}")
    for i, o in enumerate(objects):
        why = off_table(o.x, o.y, o.size, table)
        if why is not None:
            raise bad(f"table object {i} at ({o.x}, {o.y}) is off the table: {why}")
    if objects:
        lesson = Lesson("inform", "", [o.spec() for o in objects], source=Source(str(path)))
        try:
            trainer.layout(lesson, seed=0, table=table)
        except UserError as exc:
            raise bad(f"its table cannot be laid out: {exc.message.removeprefix(str(path) + ': ')}") from None


def read(path: str | os.PathLike[str]) -> Saved:
    """Read and check a state file; every problem is one `UserError` naming it."""
    p = str(path)
    bad = _malformed(p)

    try:
        text = Path(p).read_text(encoding="utf-8")
        data = json.loads(text, object_pairs_hook=no_duplicates)
    except (OSError, UnicodeDecodeError) as exc:
        raise UserError(f"cannot read the console state: {exc}", path=p) from None
    except RecursionError:
        raise bad("nested too deeply") from None
    except ValueError as exc:  # not JSON, a duplicate key, an integer too long
        raise bad(str(exc)) from None
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise bad(f'expected "format": "{FORMAT}"')
    if data.get("version") != VERSION:
        raise bad(f"format version {data.get('version')!r}, expected {VERSION}")
    if deeper_than(data, MAX_DEPTH):
        raise bad(f"nested deeper than {MAX_DEPTH} levels")
    unknown = sorted(set(data) - set(KEYS))
    if unknown:  # the next save would drop it without a word (the memory file refuses them too)
        raise bad(f"unknown key {unknown[0]!r}; expected {', '.join(KEYS)}")
    version = data.get("scene_version")
    if not isinstance(version, int) or isinstance(version, bool) or version < 0:
        raise bad('"scene_version" must be a whole number >= 0')
    sha = data.get("memory_sha256")
    if sha is not None and not (isinstance(sha, str) and len(sha) == 64):
        raise bad('"memory_sha256" must be a SHA-256 in hex')
    objects = [_placed(o, i, bad) for i, o in enumerate(_list(data, "table", bad))]
    blocks = _list(data, "blocks", bad)
    if not all(isinstance(b, str) for b in blocks):
        raise bad('"blocks" must be lesson-file text')
    if blocks:
        try:
            lessons = lessonfile.loads(transcript.document(blocks, title="t", seed=0, description="d"),
                                       path=p).lessons
        except UserError as exc:
            raise bad(f"its lessons do not read back: {exc.message}") from None
        if len(lessons) != len(blocks):
            raise bad("a lesson block holds other than one lesson")
    records = _list(data, "records", bad)
    if not all(isinstance(r, dict) and isinstance(r.get("signal"), str) for r in records):
        raise bad('"records" must be lesson records with a "signal"')
    if len(records) < len(blocks):
        raise bad("fewer records than lessons")
    return Saved(version, objects, blocks, records, sha)


def _list(data: dict, key: str, bad) -> list:
    value = data.get(key)
    if not isinstance(value, list):
        raise bad(f'"{key}" must be a list')
    return value


def _placed(o: object, i: int, bad) -> Placed:
    names = channels.names()  # one key per channel: shape, colour, size (and any declared one)
    if not isinstance(o, dict) or set(o) != {*names, "x", "y", "distractor"}:
        raise bad(f"table object {i} must have {', '.join(names)}, x, y and distractor")
    if any(o[c.name] not in c.values for c in channels.CHANNELS):
        raise bad(f"table object {i}: unknown {', '.join(names[:-1])} or {names[-1]}")
    xy = (o["x"], o["y"])
    if not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in xy):
        raise bad(f"table object {i}: x and y must be finite numbers")
    if not isinstance(o["distractor"], bool):
        raise bad(f"table object {i}: distractor must be true or false")
    return Placed(Appearance((n, o[n]) for n in names), float(o["x"]), float(o["y"]), o["distractor"])
