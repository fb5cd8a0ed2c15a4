"""The concept memory file in a compact binary form, read lazily (`aileen memory convert`).

Why: the JSON file is for people, and reading it means parsing every fact's text into terms:
100,000 concepts took about 9 s and 7 KB of memory per concept, most of it terms and dicts
that a run never looks at. The compact form keeps each distinct term once (a table of
name and argument numbers, children before parents) and each concept as a run of numbers
into that table, so that loading it is reading the bytes and the concept symbols: a
concept's generalizations and examples are made into terms the first time something asks
for them (`Source.read`). At rest a loaded concept costs its share of the file and a small
placeholder. The JSON file stays the readable form; `aileen memory convert` goes either way
and the two hold the same memory (the facts keep the JSON file's order).

Layout (every number a little-endian unsigned 32-bit integer):

    bytes 0-15   MAGIC
    16-19        CRC-32 of every byte from 24 on (a damaged or truncated file is refused)
    20-23        length H of the header
    24-(24+H)    the header, JSON: "format", "version", "params" and "annotations" as in the
                 JSON file, and "sections": {name: [byte offset, length in numbers]}
    then, each at a multiple of 4 bytes, the sections:
      string_ends      end (in bytes, within `text`) of each string
      term_names       per term: string number * 2, + 1 when the name is an integer
      term_arg_ends    per term: end of its arguments within term_args
      term_args        argument term numbers (each lower than its term's own number)
      concept_symbols  per concept: string number of its symbol
      concept_kinds    per concept: string number of its kind
      concept_ends     per concept: end of its numbers within data
      data             per concept: generalizations (count, then per generalization its
                       size, next entity, number of facts, and (term, count) per fact),
                       kept examples (count, then per example its length and terms), near
                       misses (the same)
      text             (bytes, not numbers) the strings, UTF-8, one after the other

Writing goes through `aileen.io` like the JSON file (temporary file, fsync, rename), and
the memory file's lock and save checks (`store.MemoryFile`) are the same for both forms.
"""

from __future__ import annotations

import json
import re
import struct
import sys
import zlib
from array import array
from collections.abc import Callable, Sequence
from typing import Any, Protocol, TypeVar

from aileen.analogy.sage import Generalization, GeneralizationContext, SageParams
from aileen.errors import UserError
from aileen.memory import codec, persist
from aileen.memory.kinds import KINDS
from aileen.strictjson import deeper_than, no_duplicates
from aileen.terms import CONSTANT, Term

__all__ = ["MAGIC", "SUFFIX", "SECTIONS", "encode", "is_compact", "Source", "decode", "LazyMemory"]

#: The first 16 bytes of a compact memory file (the last two: the layout's version).
MAGIC = b"AILEEN-MEMORY\x00c1"
#: The file name ending that `ConceptMemory.save` writes in the compact form.
SUFFIX = ".amem"
SECTIONS = ("string_ends", "term_names", "term_arg_ends", "term_args", "concept_symbols", "concept_kinds",
            "concept_ends", "data")
_PREAMBLE = 24
_SYMBOL = re.compile(r"[a-z][A-Za-z0-9_']*")
_LITTLE = sys.byteorder == "little"


def is_compact(data: bytes, *, named_json: bool = False) -> bool:
    """Whether `data` is a compact memory file (by its first bytes), or what is left of one:
    the start of the magic ("AILE"), or a NUL among the first bytes (no JSON text has one). A
    compact file damaged in its first bytes, or cut after eight, was read as JSON and said to
    be "not UTF-8 text" or "not a JSON object; lesson files are run with 'aileen run'";
    `decode` names it damaged or truncated. A file whose name says JSON (`named_json`) is
    compact only by the magic: one saved as UTF-16 or overwritten with binary bytes was called
    a damaged compact file."""
    head = data[:len(MAGIC)]
    return head == MAGIC or head[:4] == MAGIC[:4] or (not named_json and b"\x00" in data[:64])


def _u32(values: Sequence[int] | array) -> bytes:
    a = values if isinstance(values, array) else array("I", values)
    if not _LITTLE:  # pragma: no cover - the layout is little-endian
        a = array("I", a)
        a.byteswap()
    return a.tobytes()


# --------------------------------------------------------------------------- writing
def encode(mem: codec.StoredMemory) -> bytes:
    """The memory in the compact form: every concept's generalizations (facts in the JSON
    file's order), kept examples and near misses, the parameters and the annotations."""
    strings: dict[str, int] = {}
    terms: dict[Term, int] = {}
    term_names, term_arg_ends, term_args = array("I"), array("I"), array("I")

    def string(s: str) -> int:
        i = strings.get(s)
        if i is None:
            i = strings[s] = len(strings)
        return i

    def term(t: Term) -> int:
        i = terms.get(t)
        if i is not None:
            return i
        args = [term(a) for a in t.args]
        i = terms[t] = len(term_names)
        name = t.name
        term_names.append(string(str(name)) * 2 + 1 if isinstance(name, int) else string(name) * 2)
        term_args.extend(args)
        term_arg_ends.append(len(term_args))
        return i

    symbols, kinds, ends, data = array("I"), array("I"), array("I"), array("I")
    for c in mem.concepts():
        symbols.append(string(c.symbol))
        kinds.append(string(c.kind))
        ctx = c.context
        data.append(len(ctx.generalizations))
        for g in ctx.generalizations:
            probs = g.probabilities()
            data.extend((g.size, g.next_entity, len(probs)))
            for f in probs:
                data.extend((term(f), g.counts[f]))
        for group in (ctx.examples, c.near_misses):
            data.append(len(group))
            for facts in group:
                data.append(len(facts))
                data.extend(term(f) for f in facts)
        ends.append(len(data))
    text = bytearray()
    string_ends = array("I")
    for s in strings:
        text += s.encode("utf-8")
        string_ends.append(len(text))
    arrays = {"string_ends": string_ends, "term_names": term_names, "term_arg_ends": term_arg_ends,
              "term_args": term_args, "concept_symbols": symbols, "concept_kinds": kinds, "concept_ends": ends,
              "data": data}
    header: dict[str, Any] = {"format": persist.FORMAT, "version": persist.VERSION,
                              "params": codec.encode_params(mem.params)}
    if mem.annotations:
        header["annotations"] = mem.annotations
    # the sections' offsets depend on the header's length, which depends on the offsets:
    # lay them out from a header long enough for any offset (numbers padded to 10 digits)
    sections: dict[str, list[int]] = {name: [0, len(a)] for name, a in arrays.items()}
    sections["text"] = [0, len(text)]
    header["sections"] = sections
    room = len(json.dumps(header, ensure_ascii=False).encode("utf-8")) + 11 * 2 * len(sections)
    at = _PREAMBLE + room
    at += -at % 4
    for name, a in arrays.items():
        sections[name][0] = at
        at += 4 * len(a)
    sections["text"][0] = at
    head = json.dumps(header, ensure_ascii=False).encode("utf-8")
    head += b" " * (room - len(head))
    body = bytearray(head)
    body += b"\0" * (-(_PREAMBLE + len(body)) % 4)
    for a in arrays.values():
        body += _u32(a)
    body += text
    return MAGIC + struct.pack("<II", zlib.crc32(body), room) + bytes(body)


# --------------------------------------------------------------------------- reading
class Source:
    """A compact file's bytes, with what is needed to read one concept at a time.

    Kept whole (not mapped): the file may be replaced while a run holds its memory, and a
    concept read late must be the one loaded. Copying or pickling a memory shares or carries
    the bytes; the views into them are made again."""

    def __init__(self, data: bytes, path: str) -> None:
        self.path = path
        self.data = data
        self._open()

    def _bad(self, what: str) -> UserError:
        return UserError(f"malformed memory file: {what}", path=self.path)

    def _open(self) -> None:
        data = self.data
        if not is_compact(data):
            raise self._bad("not a compact memory file")
        if len(data) < _PREAMBLE or data[:len(MAGIC)] != MAGIC:
            why = "shorter than its header" if len(data) < _PREAMBLE else "its first bytes are not the format's mark"
            raise UserError(f"compact memory file is damaged or truncated ({why})", path=self.path)
        crc, room = struct.unpack_from("<II", data, len(MAGIC))
        if zlib.crc32(memoryview(data)[_PREAMBLE:]) != crc:
            raise UserError("compact memory file is damaged or truncated (its checksum does not match)",
                            path=self.path)
        if _PREAMBLE + room > len(data):
            raise self._bad("the header runs past the end of the file")
        try:
            header = json.loads(bytes(data[_PREAMBLE:_PREAMBLE + room]).decode("utf-8"),
                                object_pairs_hook=no_duplicates)
        except (UnicodeDecodeError, ValueError) as exc:
            raise self._bad(f"the header is not JSON ({exc})") from None
        if not isinstance(header, dict) or deeper_than(header, persist.MAX_DEPTH):
            raise self._bad("the header is not a JSON object of the expected shape")
        if header.get("format") != persist.FORMAT:
            raise UserError(f"not an aileen concept memory (expected \"format\": \"{persist.FORMAT}\")",
                            path=self.path)
        problem = persist.version_problem(header)
        if problem is not None:
            raise UserError(problem, path=self.path)
        self.header = header
        sections = header.get("sections")
        if not isinstance(sections, dict) or set(sections) != {*SECTIONS, "text"}:
            raise self._bad(f"\"sections\" must name {', '.join(SECTIONS)} and text")
        view = memoryview(data)
        self._views: dict[str, Any] = {}
        for name, where in sections.items():
            if not (isinstance(where, list) and len(where) == 2
                    and all(isinstance(x, int) and not isinstance(x, bool) and x >= 0 for x in where)):
                raise self._bad(f"section {name}: expected [offset, length]")
            start, n = where
            size = n if name == "text" else 4 * n
            if start + size > len(data) or (name != "text" and start % 4):
                raise self._bad(f"section {name} lies outside the file")
            part = view[start:start + size]
            self._views[name] = part if name == "text" else part.cast("I")
        if not _LITTLE:  # pragma: no cover - the layout is little-endian
            for name in SECTIONS:
                a = array("I", self._views[name])
                a.byteswap()
                self._views[name] = a
        v = self._views
        n_strings, n_terms, n_concepts = len(v["string_ends"]), len(v["term_names"]), len(v["concept_symbols"])
        if (len(v["term_arg_ends"]) != n_terms or len(v["concept_kinds"]) != n_concepts
                or len(v["concept_ends"]) != n_concepts):
            raise self._bad("the tables disagree on how many terms or concepts there are")
        if ((n_strings and v["string_ends"][-1] != len(v["text"]))
                or (n_terms and v["term_arg_ends"][-1] != len(v["term_args"]))
                or (n_concepts and v["concept_ends"][-1] != len(v["data"]))):
            raise self._bad("a table does not end where its section does")
        self._strings: list[str | None] = [None] * n_strings
        self._named: set[int] = set()  # strings checked as term names (`name`)
        self._terms: list[Term | None] = [None] * n_terms
        self._reads = 0
        self._all_terms = False

    def __getstate__(self) -> dict[str, Any]:
        return {"path": self.path, "data": self.data, "strings": self._strings, "terms": self._terms,
                "all": self._all_terms}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.path, self.data = state["path"], state["data"]
        self._open()
        self._strings, self._terms, self._all_terms = state["strings"], state["terms"], state["all"]

    def __deepcopy__(self, memo: dict) -> "Source":
        return self  # the bytes never change, and what is read from them is immutable

    # ---------------------------------------------------------------- strings and terms
    def name(self, i: int) -> str:
        """String i as a term's name: a constant or a quoted string, as a fact of a JSON memory
        file is read (`terms.CONSTANT`); not a variable, not a control character (a byte changed
        under a good checksum read `dg\x01p_14`, and `memory convert` wrote a JSON file that
        could not be read). Checked once per string."""
        s = self.string(i)
        if i not in self._named:
            if not CONSTANT.fullmatch(s):
                raise self._bad(f"string {i} ({s[:40]!r}) is not a term's name")
            self._named.add(i)
        return s

    def string(self, i: int) -> str:
        s = self._strings[i]
        if s is None:
            ends = self._views["string_ends"]
            start = ends[i - 1] if i else 0
            try:
                s = bytes(self._views["text"][start:ends[i]]).decode("utf-8")
            except UnicodeDecodeError:
                raise self._bad(f"string {i} is not UTF-8") from None
            self._strings[i] = s
        return s

    def term(self, i: int) -> Term:
        t = self._terms[i]
        if t is None:
            v = self._views
            ends = v["term_arg_ends"]
            start = ends[i - 1] if i else 0
            if start > ends[i]:
                raise self._bad(f"term {i}: its arguments end before they start")
            args = []
            for j in v["term_args"][start:ends[i]]:
                if j >= i:
                    raise self._bad(f"term {i}: argument {j} is not an earlier term")
                args.append(self.term(j))
            ref = v["term_names"][i]
            if ref >> 1 >= len(self._strings):
                raise self._bad(f"term {i}: no string {ref >> 1}")
            text = self.string(ref >> 1) if ref & 1 else self.name(ref >> 1)
            try:
                name: str | int = int(text) if ref & 1 else text
                t = Term(name, tuple(args))
            except (TypeError, ValueError) as exc:
                raise self._bad(f"term {i}: {exc}") from None
            self._terms[i] = t
        return t

    def read_all_terms(self) -> None:
        """Make every term of the table at once (children before parents, so no recursion):
        several times faster per term than one fact at a time, for a memory read whole."""
        if self._all_terms:
            return
        v = self._views
        names, ends, args = v["term_names"].tolist(), v["term_arg_ends"].tolist(), v["term_args"].tolist()
        terms, n_strings, string, named = self._terms, len(self._strings), self.string, self.name
        start = 0
        with codec.gc_paused():
            for i, end in enumerate(ends):
                if terms[i] is None:
                    js = args[start:end]
                    if start > end or (js and max(js) >= i):
                        raise self._bad(f"term {i}: its arguments are not earlier terms")
                    ref = names[i]
                    if ref >> 1 >= n_strings:
                        raise self._bad(f"term {i}: no string {ref >> 1}")
                    text = string(ref >> 1) if ref & 1 else named(ref >> 1)
                    try:
                        terms[i] = Term(int(text) if ref & 1 else text, tuple([terms[j] for j in js]))
                    except (TypeError, ValueError) as exc:
                        raise self._bad(f"term {i}: {exc}") from None
                start = end
        self._all_terms = True

    # ---------------------------------------------------------------- concepts
    def concepts(self) -> list[tuple[str, str]]:
        """(symbol, kind) of every concept, in the file's order, each checked."""
        v = self._views
        out = []
        n = len(self._strings)
        for i, (s, k) in enumerate(zip(v["concept_symbols"], v["concept_kinds"])):
            if s >= n or k >= n:
                raise self._bad(f"concept {i + 1}: no such string")
            symbol, kind = self.string(s), self.string(k)
            if not _SYMBOL.fullmatch(symbol):
                raise self._bad(f"concept {i + 1}: symbol {symbol!r} is not a lowercase ASP constant")
            if kind not in KINDS:
                raise self._bad(f"concept {symbol!r}: \"kind\" must be one of {', '.join(KINDS)}")
            out.append((symbol, sys.intern(kind)))
        return out

    def read(self, i: int, symbol: str) -> tuple[GeneralizationContext, list[list[Term]]]:
        """The i-th concept's generalization context and near misses, made into terms."""
        self._reads += 1
        if not self._all_terms and self._reads * 16 > len(self._views["concept_ends"]) + 16_000:
            self.read_all_terms()  # the memory is being read whole (a retrieval index, the lexicon)
        v = self._views
        ends = v["concept_ends"]
        nums = v["data"][ends[i - 1] if i else 0:ends[i]].tolist()
        terms, n_terms = self._terms, len(self._terms)

        def fact(j: int) -> Term:
            if j >= n_terms:
                raise self._bad(f"concept {symbol!r}: no term {j}")
            t = terms[j]
            return t if t is not None else self.term(j)

        ctx = GeneralizationContext(symbol)
        try:
            pos = 1
            for _ in range(nums[0]):
                size, nxt, n = nums[pos], nums[pos + 1], nums[pos + 2]
                pos += 3
                if size < 1:
                    raise self._bad(f"concept {symbol!r}: a generalization of no examples")
                pairs = nums[pos:pos + 2 * n]
                if len(pairs) != 2 * n:
                    raise IndexError
                pos += 2 * n
                counts: dict[Term, int] = {}
                for k in range(0, 2 * n, 2):
                    f, count = fact(pairs[k]), pairs[k + 1]
                    if not 1 <= count <= size:
                        raise self._bad(f"concept {symbol!r}: count of {f} must be in 1..{size}")
                    counts[f] = count
                ctx.generalizations.append(Generalization(symbol, counts, size, nxt))
            groups: list[list[list[Term]]] = []
            for _ in range(2):
                group = []
                for _ in range(nums[pos]):
                    n = nums[pos + 1]
                    ids = nums[pos + 2:pos + 2 + n]
                    if len(ids) != n:
                        raise IndexError
                    group.append([fact(j) for j in ids])
                    pos += 1 + n
                groups.append(group)
                pos += 1
        except IndexError:
            raise self._bad(f"concept {symbol!r}: its entry ends early") from None
        if pos != len(nums):
            raise self._bad(f"concept {symbol!r}: its entry has numbers left over")
        ctx.examples = groups[0]
        return ctx, groups[1]


class LazyMemory(Protocol):
    """What `decode` fills in (`aileen.memory.concept.ConceptMemory` is one)."""

    params: SageParams
    annotations: dict[str, Any]

    def adopt(self, symbol: str, kind: str, source: Source, index: int) -> None: ...


M = TypeVar("M", bound=LazyMemory)


def decode(cls: Callable[[SageParams], M], data: bytes, path: str = "<memory>") -> M:
    """A memory whose concepts are read from `data` (a compact file) when first used. The
    header, the tables' shapes, every concept's symbol and kind and the checksum of the
    whole are checked now; a malformed file is one `UserError` naming `path`."""
    source = Source(data, path)

    def bad(what: str) -> UserError:
        return UserError(f"malformed memory file: {what}", path=path)

    header = source.header
    extra = [k for k in header if k not in (*codec.TOP_KEYS, "sections") or k == "concepts"]
    if extra:
        raise bad(f"the header: unknown key {json.dumps(extra[0])}")
    mem = cls(codec.decode_params(header.get("params", {}), bad))
    seen: set[str] = set()
    for i, (symbol, kind) in enumerate(source.concepts()):
        if symbol in seen:
            raise bad(f"concept {symbol!r} appears twice (concept {i + 1})")
        seen.add(symbol)
        mem.adopt(symbol, kind, source, i)
    mem.annotations = codec.decode_annotations(header, bad)
    return mem
