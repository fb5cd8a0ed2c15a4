"""A console session written as a lesson file (TOML, docs/lessons.md) that `aileen run` replays.

Each lesson is stated with every object's appearance (shape, colour, size, any declared
channel) and exact position, and the
seed it ran with, so the replayed table, camera noise and demonstration are the ones the
session had. The console parses each lesson from this very text before running it, so what
is downloaded is what ran.

`session_file` is the Download button's file (moved here from `session`: writing the session as
a lesson file is this module's one job).
"""

from __future__ import annotations

import json
import shlex
from pathlib import Path

from aileen.curriculum.lesson import ObjectSpec
from aileen.errors import UserError


def _str(text: str) -> str:
    """A TOML basic string: JSON's escapes are valid TOML; TOML also forbids a bare DEL."""
    return json.dumps(text, ensure_ascii=False).replace("\x7f", "\\u007f")


def _object(spec: ObjectSpec) -> str:
    assert spec.position is not None and spec.shape and spec.colour
    x, y = spec.position
    values = ", ".join(f"{name} = {_str(value)}" for name, value in spec.appearance.items())
    return f"{{ {values}, position = [{x!r}, {y!r}] }}"


def lesson_block(signal: str, content: str, objects: list[ObjectSpec], *, seed: int, demonstrate: bool,
                 note: str | None = None, as_said: tuple[str, ...] = ()) -> str:
    """One `[[lesson]]` table. `demonstrate`: the trainer shows the sentence's action first;
    `as_said`: words the trainer means as said (the agent asked about them)."""
    lines = ["[[lesson]]", f"signal = {_str(signal)}", f"content = {_str(content)}"]
    if objects:
        lines.append("objects = [")
        lines.extend(f"  {_object(o)}," for o in objects)
        lines.append("]")
    if demonstrate:
        lines.append('demonstration = "auto"')
    lines.append(f"seed = {int(seed)}")
    if note:
        lines.append(f"note = {_str(note)}")
    if as_said:
        lines.append("as_said = [" + ", ".join(_str(w) for w in as_said) + "]")
    return "\n".join(lines) + "\n"


def document(blocks: list[str], *, title: str, seed: int, description: str) -> str:
    """The whole lesson file."""
    head = [f"title = {_str(title)}", f"description = {_str(description)}", f"seed = {int(seed)}", ""]
    return "\n".join(head) + "\n".join(blocks)


def session_file(blocks: list[str], *, seed: int, start: str | None, known: bool = True,
                 options: tuple[str, ...] = ()) -> str:
    """The console's lessons so far as one lesson file, saying how to replay them to the same
    answers: from `start`, the copy of the memory the session started with (`state.keep_start`;
    None: an empty memory; not `known`: none was kept), with `options`, the command-line
    options the replay needs (`--senses`, `--rules`: no lesson-file key holds them). It said
    to replay from the memory file, which holds the taught memory by then."""
    if not blocks:
        raise UserError("no lessons given yet")
    run = ["aileen", "run", "session.toml", *options]
    if not known:
        how = (f"from the memory the session started with (this console kept no copy of it: the session "
               f"began under an earlier one): `{shlex.join(run)} --memory COPY-OF-IT`")
    elif start is None:
        how = f"from an empty memory: `{shlex.join(run)}`"
    else:
        copy = "replay" + (Path(start).suffix or ".json")
        how = (f"from the memory the session started with, kept as {start} (the memory file holds what "
               f"was taught since): `cp {shlex.quote(start)} {copy} && {shlex.join([*run, '--memory', copy])}`")
    return document(blocks, title="aileen serve session", seed=seed,
                    description=f"Lessons given in the teaching console. Replay them to the same answers {how}.")
