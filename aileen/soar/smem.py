"""Soar's semantic memory on disk: the words the Soar agent has learned, beside the memory file.

Why its own module: the Soar agent's word maps live in Soar's smem (an SQLite database Soar
writes), while the concepts live in aileen's concept memory file; the two must stay a pair.
This module opens a private copy of the saved database (so the file itself changes only when
the agent saves), checks that it is one Soar can read (Soar itself only prints an sqlite error
and goes on), reconciles it with the concept memory, reads the words back, and writes the
backup whole or not at all. It talks to Soar through `SoarKernel.command` only.
"""

from __future__ import annotations

import os
import re
import shutil
import sqlite3
from pathlib import Path

from aileen.errors import UserError
from aileen.io import resolve_target
from aileen.memory.concept import ConceptMemory
from aileen.soar.kernel import SoarKernel

__all__ = ["SMEM_SUFFIX", "smem_path", "open_smem", "words", "backup", "parse_smem_print"]

SMEM_SUFFIX = ".smem"  # Soar's semantic memory database, beside the memory file


def smem_path(memory_path: str | os.PathLike[str]) -> Path:
    """Where the Soar agent keeps its semantic memory for the memory file `memory_path`."""
    target = resolve_target(memory_path)
    return target.with_name(target.name + SMEM_SUFFIX)


def open_smem(kernel: SoarKernel, memory: ConceptMemory, db: Path, saved: Path | None) -> None:
    """smem in `db`, a private copy of the saved database (or empty), reconciled with the
    concept memory: a concept smem does not name yet gets its word; a word whose concept the
    memory lacks means the two files are not a pair (exit 2)."""
    if saved is not None and saved.exists() and not saved.is_file():
        # (it was passed over, and the save at the end failed naming the memory file)
        raise UserError("Soar's semantic memory beside the memory file is not a file; expected a file or none",
                        path=str(saved))
    if saved is not None and saved.is_file():
        try:
            shutil.copyfile(saved, db)
        except OSError as exc:
            raise UserError(f"cannot read Soar's semantic memory: {exc.strerror or exc}", path=str(saved)) from None
        _check_db(db, saved)
        kernel.command("smem --set database file")
        kernel.command(f"smem --set path {{{db}}}")
        kernel.command("smem --set append on")
    kernel.command("smem --enable")
    try:
        known = words(kernel)
    except UserError as exc:
        raise UserError(f"not a semantic memory Soar can read ({exc.message})",
                        path=str(saved) if saved else None) from None
    stray = sorted({c for c, _k in known.values() if not memory.has(c)})
    if stray:
        raise UserError("Soar's semantic memory names concepts the memory file does not have "
                        f"({', '.join(stray[:5])}): "
                        "the two files are not a pair; delete this one to rebuild it from the memory file",
                        path=str(saved))
    have = {c for c, _k in known.values()}
    for c in memory.concepts():  # learned elsewhere (the ASP agent, an older file): into smem
        if c.symbol not in have:
            word = c.symbol[2:] if c.symbol.startswith("r_") else c.symbol
            kernel.command(f"smem --add {{(<w> ^word |{word}| ^concept |{c.symbol}| ^kind |{c.kind}|)}}")


def words(kernel: SoarKernel) -> dict[str, tuple[str, str]]:
    """word -> (concept, kind), as smem holds them now (`print @`)."""
    out: dict[str, tuple[str, str]] = {}
    for attrs in parse_smem_print(kernel.command("print @")):
        w, c, kind = attrs.get("word"), attrs.get("concept"), attrs.get("kind")
        if w is not None and c is not None and kind is not None:
            out[w] = (c, kind)
    return out


def backup(kernel: SoarKernel, target: Path) -> None:
    """Soar's semantic memory to `target`, whole or not at all (a backup beside it, renamed)."""
    tmp = target.with_name(f".{target.name}.{os.getpid()}.tmp")
    try:
        kernel.command(f"smem --backup {{{tmp}}}")
        if not tmp.is_file():
            raise UserError("Soar wrote no semantic memory backup", path=str(target))
        os.replace(tmp, target)
    finally:
        if tmp.exists():
            tmp.unlink()


def _check_db(db: Path, shown: Path) -> None:
    """Is `db` a Soar semantic memory database (SQLite with Soar's smem schema)?"""
    try:
        con = sqlite3.connect(f"file:{db}?mode=ro", uri=True)
        try:
            tables = {r[0] for r in con.execute("SELECT name FROM sqlite_master WHERE type='table'")}
            schema = dict(con.execute("SELECT * FROM versions")) if "versions" in tables else {}
        finally:
            con.close()
    except sqlite3.Error as exc:
        raise UserError(f"not a Soar semantic memory database ({exc})", path=str(shown)) from None
    if "smem_lti" not in tables or "smem_schema" not in schema:
        raise UserError("not a Soar semantic memory database (no smem tables)", path=str(shown))


def parse_smem_print(text: str) -> list[dict[str, str]]:
    """The long-term identifiers Soar's `print @` lists, as attribute -> value (the first
    value of each attribute; `|quoted|` symbols unquoted)."""
    out: list[dict[str, str]] = []
    for m in _SMEM_TOKEN.finditer(text):
        if m.group("lti") is not None:
            out.append({})
        elif out and m.group("attr") is not None:
            v = m.group("value")
            if v.startswith("|") and v.endswith("|") and len(v) >= 2:
                v = v[1:-1].replace("\\|", "|")
            out[-1].setdefault(m.group("attr"), v)
    return out


_SMEM_TOKEN = re.compile(r"\((?P<lti>@\d+)|\^(?P<attr>[^\s|()]+)\s+(?P<value>\|(?:[^|\\]|\\.)*\||[^\s()\[]+)")
