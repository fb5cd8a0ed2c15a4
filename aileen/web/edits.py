"""The page's table requests, checked and made edits of the trainer's table (`table.TableEdit`).

Why a module of its own (split out of `session`): what a request may say (which fields, one-line
descriptions, finite numbers, a spot in metres or in the pixels the page was clicked at) is a
job apart from running lessons. The session calls these, then redraws; a request that is
refused here changes nothing. The checks on a sentence (`text`) are shared with the lessons.
"""

from __future__ import annotations

import numpy as np

from aileen.domain import channels, relations
from aileen.errors import UserError
from aileen.web.table import LAID_OUT_DISTRACTORS, TableEdit
from aileen.world.camera import Camera

# Scene edits and the fields each takes.
EDITS: dict[str, set[str]] = {"add": {"object", "at", "px", "relation", "of"}, "move": {"index", "at", "px"},
                              "remove": {"index"}, "clear": set(), "shuffle": {"distractors"},
                              "layout": {"content", "distractors"}, "undo": set()}


def set_table(table: TableEdit, camera: Camera, objects: object, relation: object = None,
              distractors: object = 0) -> None:
    """The whole table in one call: `objects` a list of descriptions ('large red box') or
    of {"object": description, "at": [x, y] | "px": [u, v]}; `relation` lays out two."""
    if not isinstance(objects, list) or not objects:
        raise UserError("'objects' must be a non-empty list of object descriptions")
    items = []
    for o in objects:
        if isinstance(o, str):
            items.append((text(o, "object"), None))
        elif isinstance(o, dict):
            extra = sorted(set(o) - {"object", "at", "px"})
            if extra:
                raise UserError(f"unexpected field(s) in an object: {', '.join(map(str, extra))}; "
                                "expected object and at or px")
            kw = dict(o)
            items.append((text(kw.pop("object", None), "object"), spot(camera, kw)))
        else:
            raise UserError("each of 'objects' is a description or {\"object\": ..., \"at\": [x, y]}")
    if not isinstance(distractors, int) or isinstance(distractors, bool):
        raise UserError(f"distractors must be a whole number from 0 to {LAID_OUT_DISTRACTORS}")
    table.set_table(items, relation=opt_text(relation), distractors=distractors)


def edit(table: TableEdit, camera: Camera, op: str, kw: dict) -> None:
    """One edit of the table: add, move, remove, clear, shuffle, layout, undo. `kw`: the
    request's other fields (used up)."""
    t = table
    if op not in EDITS:
        raise UserError(f"unknown scene op {op!r}; expected one of: {', '.join(EDITS)}")
    extra = sorted(set(kw) - EDITS[op])
    if extra:
        raise UserError(f"unexpected field(s) for {op!r}: {', '.join(extra)}")
    if op == "add":
        if ("at" in kw or "px" in kw) and ("relation" in kw or "of" in kw):
            # one or the other says where it goes: the relation was dropped silently
            raise UserError("give 'at' or 'px', or 'relation' and 'of', not both")
        t.add(text(kw.pop("object", None), "object"), at=spot(camera, kw), relation=opt_text(kw.pop("relation", None)),
              of=opt_text(kw.pop("of", None)))
    elif op == "move":
        at = spot(camera, kw)
        if at is None:
            raise UserError("move needs 'at': [x, y] metres, or 'px': [u, v] camera pixels")
        t.move(kw.pop("index", None), at)
    elif op == "remove":
        t.remove(kw.pop("index", None))
    elif op == "clear":
        t.clear()
    elif op == "shuffle":
        t.shuffle_distractors(kw.pop("distractors", 2))
    elif op == "layout":
        d = kw.pop("distractors", 0)
        if not isinstance(d, int) or isinstance(d, bool) or not 0 <= d <= LAID_OUT_DISTRACTORS:
            raise UserError(f"distractors must be a whole number from 0 to {LAID_OUT_DISTRACTORS}")
        t.lay_out(text(kw.pop("content", None), "content"), distractors=d)
    else:
        t.undo()


def words() -> dict:
    """The words the page offers, read from the declarations: each channel with its values
    and default (what an object description may say), and the relation words the table
    can lay an object out in (a place beside another object; not stacking, not a size)."""
    placing = [w for w in relations.words()
               if (r := relations.of_word(w)).offset is not None and not r.stacked and r.sizes is None]
    return {"channels": [{"name": c.name, "values": list(c.values), "default": c.default}
                         for c in channels.CHANNELS],
            "relations": placing}


def text(value: object, name: str) -> str:
    """A request's sentence or description: a non-empty string on one line, its spaces as
    the lesson-file reader reads them."""
    if not isinstance(value, str) or not value.strip():
        raise UserError(f"'{name}' must be a non-empty string")
    if "\n" in value or "\r" in value:
        raise UserError(f"'{name}' must be one line")
    return " ".join(value.split())  # as the lesson-file reader reads it


def opt_text(value: object) -> str | None:
    return None if value is None else text(value, "relation/of")


BOUND = 1e6  # past this no position is on any table: refused here, not printed with 300 digits


def number(v: object) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v) or abs(v) > BOUND:
        raise UserError("a position must be two finite numbers (metres on the table, or camera pixels)")
    return float(v)


def spot(camera: Camera, kw: dict) -> tuple[float, float] | None:
    """A spot from 'at' (metres) or 'px' (camera pixels, as clicked on the page); both are
    taken out of `kw`."""
    at, px = kw.pop("at", None), kw.pop("px", None)
    if at is not None and px is not None:
        raise UserError("give 'at' or 'px', not both")
    pair = at if at is not None else px
    if pair is None:
        return None
    if not isinstance(pair, list) or len(pair) != 2:
        raise UserError("a position is a list of two numbers")
    a, b = number(pair[0]), number(pair[1])
    return (a, b) if at is not None else camera.to_metres(a, b)
