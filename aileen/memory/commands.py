"""`aileen memory show PATH [--concept C] [--json]`: what the concept memory has learned;
`aileen memory list PATH`: its concepts, one line each;
`aileen memory convert IN OUT [--to json|compact]`: the memory file in the other form.

`show` prints each generalization context like the paper's Figure 3: the generalizations
with their facts and probabilities, and the examples kept apart, with counts; and per
concept its quality (examples seen, descriptions, significant facts, near misses, how well
it separates from the other concepts of its kind: memory/quality.py).

`convert` reads either form (JSON, or compact: memory/compact.py) and writes OUT in the
form `--to` names, else the one OUT's name says (`.amem`: compact; anything else: JSON).
OUT is written as a run saves its memory: under OUT's lock (refused while a run holds it),
atomically, and never over a file another program changed meanwhile (memory/store.py). An
OUT that exists must be a memory file (either form, damaged or not) or empty: anything else
(notes, a lesson file) is refused, never replaced.
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from collections.abc import Iterable, Iterator
from typing import Any

from aileen.errors import UserError
from aileen.memory import persist

__all__ = ["json_chunks", "list_lines", "register", "render_json", "render_text", "resolve_concept", "text_blocks"]


def register(subparsers: Any) -> None:
    mem = subparsers.add_parser("memory", help="inspect a saved concept memory")
    sub = mem.add_subparsers(dest="memory_command", metavar="ACTION")
    show = sub.add_parser("show", help="print generalizations (facts with probabilities) and examples")
    show.add_argument("path", metavar="PATH", help="memory file written by the agent (JSON or compact)")
    show.add_argument("--concept", metavar="C", help="only this concept: its symbol (r_red, r_left_of) or its "
                      "word (red, \"left of\")")
    show.add_argument("--json", action="store_true", help="machine-readable output")
    show.set_defaults(handler=_show, closed_output="so the rest of the memory was not shown")
    lst = sub.add_parser("list", help="one line per concept: symbol, kind, word, counts (fast on any size)")
    lst.add_argument("path", metavar="PATH", help="memory file written by the agent (JSON or compact)")
    lst.set_defaults(handler=_list, closed_output="so the rest of the concepts were not listed")
    conv = sub.add_parser("convert", help="write a memory file in the other form: readable JSON, or compact "
                          "(.amem: loads lazily, a fraction of the memory)")
    conv.add_argument("source", metavar="IN", help="memory file to read (JSON or compact)")
    conv.add_argument("target", metavar="OUT", help="memory file to write: a new file, or a memory file replaced atomically "
                      "(anything else is refused)")
    conv.add_argument("--to", choices=("json", "compact"), default=None,
                      help="the form to write (default: compact when OUT ends in .amem, else JSON)")
    conv.set_defaults(handler=_convert)
    mem.set_defaults(handler=lambda _args: (mem.print_help(), 0)[1])


def resolve_concept(memory: Any, name: str, path: str | None = None) -> str:
    """The concept `name` means: a symbol in the memory (`r_red`), or a word whose concept it
    holds (`red` -> `r_red`, `left of` -> `r_left_of`); else a `UserError` listing what it has."""
    from aileen.memory.semantic import concept_symbol, word_of

    if name in memory:
        return name
    try:
        symbol = concept_symbol(name)
    except ValueError:
        symbol = None
    if symbol is not None and symbol in memory:
        return symbol
    # a declared spelling of a relation word ("touching", "bigger than") is that word
    from aileen.domain import relations

    spelled = relations.spellings().get(" ".join(name.lower().replace("_", " ").split()))
    if spelled is not None and concept_symbol(spelled) in memory:
        return concept_symbol(spelled)
    # the first words of one word it holds ("northeast" for "northeast of"), or a slip
    import difflib

    symbols = [c.symbol for c in memory.concepts()]
    said = " ".join(name.lower().replace("_", " ").split())
    words = {s: word_of(s) for s in symbols}
    starting = [s for s, w in words.items() if w.startswith(said + " ")]
    if said and len(starting) == 1:
        return starting[0]
    close = starting or difflib.get_close_matches(said, list(words.values()), n=3, cutoff=0.7)
    hint = f"; did you mean {' or '.join(repr(w) for w in close)}?" if close else ""
    raise UserError(f"no concept {name!r} in the memory{hint} ({_known(symbols)})", path=path)


#: How many of the memory's concepts an unknown `--concept` error names (a memory of 10,000
#: named them all, on one line of 109 KB).
KNOWN_SHOWN = 8


def _known(symbols: list[str]) -> str:
    """The concepts the memory holds, for the error: all of a few, else the first few and the count."""
    if not symbols:
        return "it holds none"
    if len(symbols) <= KNOWN_SHOWN:
        return "known: " + ", ".join(symbols)
    return (f"it holds {len(symbols)} concepts: {', '.join(symbols[:KNOWN_SHOWN])} and "
            f"{len(symbols) - KNOWN_SHOWN} more; 'aileen memory list' lists them")


def text_blocks(memory: Any, concept: str | None = None) -> Iterator[str]:
    """The text `render_text` joins with newlines, a block at a time: the thresholds, then
    one block per concept (a blank line, its header, its quality, its regions, its contexts).

    Why blocks: a concept's quality asks the rest of the memory (memory/quality.py), so a
    memory of 10,000 concepts took two minutes to render; made and written one concept at a
    time, the output starts at once and `| head` stops it early."""
    from aileen.memory import quality, regions

    p = memory.params
    yield (f"thresholds: assimilation {p.assimilation:g}, probability {p.probability:g}, "
           f"match {p.match:g} (normalisation: {p.normalisation})")
    concepts = [memory.concept(concept)] if concept else memory.concepts()
    if not concepts:
        yield "(no concepts)"
    for c in concepts:
        ctx = c.context
        ng, ne = len(ctx.generalizations), len(ctx.examples)
        lines = [""]
        lines.append(
            f"{c.symbol} ({c.kind}): {ng} generalization{'s' if ng != 1 else ''}, "
            f"{ne} example{'s' if ne != 1 else ''}"
        )
        lines.append(quality.quality_line(quality.quality(memory, c.symbol)))
        lines += regions.text_lines(c, memory.params)
        for i, g in enumerate(ctx.generalizations):
            lines.append(f"  generalization {i} ({g.size} examples)")
            lines.append("    P     fact")
            for f, prob in g.probabilities().items():
                mark = "" if prob >= p.probability - 1e-12 else "   (below probability threshold)"
                lines.append(f"    {prob:.2f}  {f}{mark}")
        for i, ex in enumerate(ctx.examples):
            lines.append(f"  example {i} ({len(ex)} facts)")
            for f in ex:
                lines.append(f"          {f}")
        yield "\n".join(lines)


def render_text(memory: Any, concept: str | None = None) -> str:
    """The contexts as text, one block per concept, each with its quality (memory/quality.py)."""
    return "\n".join(text_blocks(memory, concept))


def concept_json(memory: Any, c: Any) -> dict[str, Any]:
    """One concept's entry of `render_json`."""
    from aileen.memory import quality, regions

    return {
        "kind": c.kind,
        "generalizations": [
            {"examples": g.size, "facts": {str(f): round(pr, 6) for f, pr in g.probabilities().items()}}
            for g in c.context.generalizations
        ],
        "examples": [[str(f) for f in ex] for ex in c.context.examples],
        "near_misses": [[str(f) for f in nm] for nm in c.near_misses],
        "quality": quality.quality(memory, c.symbol).to_dict(),
        "regions": None if (r := regions.read(c, memory.params)) is None else r.to_json(),
    }


def render_json(memory: Any, concept: str | None = None) -> dict[str, Any]:
    """Symbol -> the concept's kind, generalizations, examples, near misses, quality, regions."""
    concepts = [memory.concept(concept)] if concept else memory.concepts()
    return {c.symbol: concept_json(memory, c) for c in concepts}


def json_chunks(memory: Any, concept: str | None = None) -> Iterator[str]:
    """`json.dumps(render_json(...), indent=2)`, a concept at a time (why: `text_blocks`):
    the pieces joined are that text exactly, one JSON object, valid once complete."""
    concepts = [memory.concept(concept)] if concept else memory.concepts()
    if not concepts:
        yield "{}"
        return
    for i, c in enumerate(concepts):
        body = json.dumps(concept_json(memory, c), indent=2).replace("\n", "\n  ")  # nested one level
        yield ("{" if i == 0 else ",") + "\n  " + json.dumps(c.symbol) + ": " + body
    yield "\n}"


def list_lines(memory: Any) -> Iterator[str]:
    """`aileen memory list`: one line per concept, its symbol, kind, word and counts, and no
    quality (which asks the rest of the memory): fast on a memory of 100,000 concepts."""
    from aileen.memory.semantic import word_of

    yield f"{len(memory)} concept{'s' if len(memory) != 1 else ''}"
    for c in memory.concepts():
        ctx = c.context
        ng, ne = len(ctx.generalizations), len(ctx.examples)
        seen = sum(g.size for g in ctx.generalizations) + ne
        yield (f"{c.symbol} ({c.kind}) {json.dumps(word_of(c.symbol))}: {seen} example{'s' if seen != 1 else ''} seen, "
               f"{ng} generalization{'s' if ng != 1 else ''}, {ne} example{'s' if ne != 1 else ''} apart")


def _stream(chunks: Iterable[str], *, sep: str = "") -> None:
    """Write each chunk as it is made, flushed (a closed output stops it: `closed_output`)."""
    out = sys.stdout
    for i, chunk in enumerate(chunks):
        out.write((sep if i else "") + chunk)
        out.flush()
    out.write("\n")
    out.flush()


class _Writer:
    """Saves a memory in one form (what `MemoryFile.save` asks of what it saves)."""

    def __init__(self, memory: Any, form: str) -> None:
        self.memory, self.form = memory, form

    def save(self, path: str) -> None:
        self.memory.save(path, self.form)


def _convert(args: argparse.Namespace) -> int:
    from aileen.memory.concept import ConceptMemory, file_form
    from aileen.memory.store import MemoryFile

    form = args.to or file_form(args.target)
    with MemoryFile.open(args.target, instead="choose another OUT") as out:  # checked and locked before IN is read
        _check_replaceable(args.target)
        memory = ConceptMemory.load(args.source)
        # a compact IN's concepts are read when first used: read them all now, so a damaged
        # one is IN's error, named so (the save read them, and blamed OUT)
        memory.read_all()
        out.save(_Writer(memory, form))
    print(f"{args.target}: {len(memory)} concepts, {form}")
    return 0


#: How much of an existing OUT is read to tell whether it is a memory file.
_SNIFF = 4096
#: The header a JSON memory file opens with (`persist.FORMAT`), whatever follows it.
_JSON_HEAD = re.compile(r'\A\ufeff?\s*\{\s*"format"\s*:\s*"' + re.escape(persist.FORMAT) + '"')


def is_memory_head(head: bytes) -> bool:
    """Whether a file's first bytes are a memory file's (JSON or compact, by their marks; the
    rest may be damaged): what `convert` may replace. An empty file has nothing to lose."""
    from aileen.memory import compact

    if not head or compact.is_compact(head, named_json=True):
        return True
    return _JSON_HEAD.match(head.decode("utf-8", errors="replace")) is not None


def _check_replaceable(path: str) -> None:
    """`convert` replaces only a memory file: OUT named a notes file or a lesson file, and it
    was overwritten with a memory, exit 0. A `UserError` when something else stands there."""
    try:
        with open(path, "rb") as fh:
            head = fh.read(_SNIFF)
    except FileNotFoundError:
        return
    except OSError as exc:
        raise UserError(f"cannot read what stands at OUT: {exc.strerror or exc}", path=path) from None
    if not is_memory_head(head):
        raise UserError("OUT exists and is not an aileen memory file, so it is not replaced; "
                        "remove it or choose another OUT", path=path)


def _show(args: argparse.Namespace) -> int:
    from aileen.memory.concept import ConceptMemory

    memory = ConceptMemory.load(args.path)
    concept = resolve_concept(memory, args.concept, args.path) if args.concept is not None else None
    _stream(json_chunks(memory, concept) if args.json else text_blocks(memory, concept),
            sep="" if args.json else "\n")
    return 0


def _list(args: argparse.Namespace) -> int:
    from aileen.memory.concept import ConceptMemory

    memory = ConceptMemory.load(args.path)
    memory.read_all()  # at once, faster than one concept at a time
    _stream(list_lines(memory), sep="\n")
    return 0
