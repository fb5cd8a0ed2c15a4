"""The compact memory file (issue 25): the same memory as the JSON file, read lazily, refused
whole when damaged, converted either way with `aileen memory convert` under the file's lock."""

from __future__ import annotations

import copy
import json
import os
import pickle
import signal
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from aileen.analogy.sage import SageParams
from aileen.cli import main
from aileen.errors import UserError
from aileen.memory import compact
from aileen.memory.concept import ConceptMemory
from aileen.memory.store import MemoryFile
from aileen.terms import Term, fn

PERCEPTS = ["cv_red", "cv_blue", "cv_box", "cv_cone", "cv_large", "cv_small"]


def object_facts(o: str, ps: list[str]) -> list[Term]:
    return [fn("isa", o, p) for p in ps]


_example = st.lists(st.sampled_from(PERCEPTS), min_size=1, max_size=4, unique=True)
_store = st.tuples(st.sampled_from(["visual", "spatial", "action"]), st.integers(0, 5), _example, _example,
                   st.booleans())


def build(ops, assimilation: float, notes: bool) -> ConceptMemory:  # noqa: ANN001
    """A memory of visual, spatial and action concepts (nested terms, numbers, gen_ents),
    with near misses and annotations."""
    m = ConceptMemory(SageParams(assimilation=assimilation))
    for kind, i, a, b, near in ops:
        c = f"r_{kind}{i}"
        if m.has(c) and m.concept(c).kind != kind:
            continue
        m.create(c, kind)
        if kind == "visual":
            facts = object_facts("o1", a) + [fn("isa", "o1", c)]
        elif kind == "spatial":
            facts = object_facts("o1", a) + object_facts("o2", b) + [fn("w", "o1", "o2"), fn(c, "o1", "o2")]
        else:
            facts = [fn("h", "t0", fn("w", "o1", "o2")), fn("h", "t1", fn("e", "o1", "o2")), fn("after", "t1", "t0"),
                     fn("isa", "t0", "start"), Term("n", (Term(len(a)), Term(-3))), fn(c, "o1", "o2")]
            facts += object_facts("o1", a)
        if near:
            m.store_near_miss(facts[:-1], c)
        else:
            m.store(facts, c)
    if notes:
        m.annotations = {"lexicon": {"positions": {"red": ["modifier"]}, "distance": {"red": [1, 1]}},
                         "mine": "a note é"}
    return m


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(_store, max_size=25), st.sampled_from([0.01, 0.5, 0.95]), st.booleans())
def test_the_compact_file_holds_the_same_memory_as_the_json_file(tmp_path_factory, ops, assimilation, notes) -> None:
    """Any memory, saved compact and loaded, is the memory saved as JSON and loaded: the same
    content, and the JSON file written from it is byte for byte the one written directly."""
    folder = tmp_path_factory.mktemp("m")
    m = build(ops, assimilation, notes)
    m.save(folder / "m.json")
    m.save(folder / "m.amem")
    assert compact.is_compact((folder / "m.amem").read_bytes())
    from_json = ConceptMemory.load(folder / "m.json")
    from_compact = ConceptMemory.load(folder / "m.amem")
    assert from_compact.to_dict() == from_json.to_dict() == m.to_dict()
    from_compact.save(folder / "back.json")
    assert (folder / "back.json").read_bytes() == (folder / "m.json").read_bytes()
    from_json.save(folder / "again.amem")
    assert (folder / "again.amem").read_bytes() == (folder / "m.amem").read_bytes()


def memory_of(n: int) -> ConceptMemory:
    m = ConceptMemory()
    for i in range(n):
        c = f"r_w{i}"
        m.create(c, "visual")
        for extra in ("cv_large", "cv_small"):
            m.store(object_facts("o1", [f"cv_p{i % 7}", f"cv_q{i % 5}", extra]) + [fn("isa", "o1", c)], c)
    return m


def test_a_compact_file_is_read_one_concept_at_a_time(tmp_path: Path) -> None:
    memory_of(30).save(tmp_path / "m.amem")
    m = ConceptMemory.load(tmp_path / "m.amem")
    assert len(m) == 30 and all(not c.loaded for c in m.concepts())
    assert [c.kind for c in m.concepts()] == ["visual"] * 30  # kinds without reading
    m.descriptions("r_w3")
    assert [c.symbol for c in m.concepts() if c.loaded] == ["r_w3"]
    # storing into one reads that one only
    m.store(object_facts("o1", ["cv_p5", "cv_q0", "cv_large", "r_w5"]), "r_w5")
    assert {c.symbol for c in m.concepts() if c.loaded} == {"r_w3", "r_w5"}


def test_a_lazily_read_memory_answers_as_the_json_one(tmp_path: Path) -> None:
    m = memory_of(40)
    m.save(tmp_path / "m.json")
    m.save(tmp_path / "m.amem")
    a, b = ConceptMemory.load(tmp_path / "m.json"), ConceptMemory.load(tmp_path / "m.amem")
    probe = object_facts("o9", ["cv_p3", "cv_q1", "cv_small"])
    assert ([(x.fact, x.similarity) for x in a.fitting(probe, kind="visual")]
            == [(x.fact, x.similarity) for x in b.fitting(probe, kind="visual")])
    assert ([(x.fact, x.similarity) for x in a.query(probe, "isa(X,r_w3)")]
            == [(x.fact, x.similarity) for x in b.query(probe, "isa(X,r_w3)")])


def test_a_lazily_read_memory_copies_and_pickles(tmp_path: Path) -> None:
    memory_of(12).save(tmp_path / "m.amem")
    m = ConceptMemory.load(tmp_path / "m.amem")
    m.descriptions("r_w1")
    want = memory_of(12).to_dict()
    for twin in (copy.deepcopy(m), pickle.loads(pickle.dumps(m))):
        assert twin.to_dict() == want
    assert m.to_dict() == want


# ---------------------------------------------------------------- damaged files
def test_a_compact_file_damaged_in_its_first_bytes_is_named_so(tmp_path: Path) -> None:
    """It was read as JSON: "not UTF-8 text", or "not a JSON object; lesson files are run with
    'aileen run'"."""
    memory_of(3).save(tmp_path / "m.amem")
    good = (tmp_path / "m.amem").read_bytes()
    for what, data in (("mark", good[:5] + bytes([good[5] ^ 1]) + good[6:]), ("first8", good[:8])):
        p = tmp_path / f"{what}.amem"
        p.write_bytes(data)
        with pytest.raises(UserError) as e:
            ConceptMemory.load(p)
        assert "compact memory file is damaged or truncated" in e.value.message, e.value.message


def test_a_json_memory_saved_with_a_byte_order_mark_is_read(tmp_path: Path) -> None:
    memory_of(3).save(tmp_path / "m.json")
    text = (tmp_path / "m.json").read_text()
    (tmp_path / "bom.json").write_text(text, encoding="utf-8-sig")
    assert ConceptMemory.load(tmp_path / "bom.json").to_dict() == ConceptMemory.load(tmp_path / "m.json").to_dict()


def test_a_damaged_compact_file_is_refused_whole(tmp_path: Path) -> None:
    memory_of(10).save(tmp_path / "m.amem")
    good = (tmp_path / "m.amem").read_bytes()
    for what, data in (("flipped", good[:300] + bytes([good[300] ^ 1]) + good[301:]),
                       ("truncated", good[:len(good) // 2]), ("short", good[:20])):
        p = tmp_path / f"{what}.amem"
        p.write_bytes(data)
        with pytest.raises(UserError) as e:
            ConceptMemory.load(p)
        assert str(p) in e.value.format() and "\n" not in e.value.format()
        assert "damaged or truncated" in e.value.message or "malformed" in e.value.message


def rewrite(data: bytes, change) -> bytes:  # noqa: ANN001
    """A compact file whose header `change` edited, with a checksum that matches."""
    import struct
    import zlib

    room = struct.unpack_from("<I", data, 20)[0]
    header = json.loads(data[24:24 + room])
    change(header)
    head = json.dumps(header).encode()
    assert len(head) <= room
    body = head + b" " * (room - len(head)) + data[24 + room:]
    return data[:16] + struct.pack("<II", zlib.crc32(body), room) + body


@pytest.mark.parametrize(("change", "said"), [
    (lambda h: h["params"].update(match=5), "\"params\".\"match\" must be a number"),
    (lambda h: h.update(mine=1), "unknown key \"mine\""),
    (lambda h: h.update(version=99), "newer than this aileen reads"),
    (lambda h: h.update(version=True), "bad format version true "),
    (lambda h: h.pop("version"), "the format version is missing"),
    (lambda h: h.update(format="x"), "not an aileen concept memory"),
    (lambda h: h["sections"].pop("data"), "\"sections\" must name"),
    (lambda h: h["sections"]["data"].__setitem__(0, 10**9), "section data lies outside the file"),
    (lambda h: h.update(annotations={"lexicon": 3}), "\"annotations\".\"lexicon\""),
])
def test_a_bad_header_is_one_line_naming_what_is_wrong(tmp_path: Path, change, said) -> None:  # noqa: ANN001
    memory_of(3).save(tmp_path / "m.amem")
    p = tmp_path / "bad.amem"
    p.write_bytes(rewrite((tmp_path / "m.amem").read_bytes(), change))
    with pytest.raises(UserError, match=said.replace("(", r"\(").replace(".", r"\.")) as e:
        ConceptMemory.load(p)
    assert e.value.path == str(p)


def _with_a_bad_concept(tmp_path: Path) -> Path:
    """tmp_path/bad.amem: a memory of 3 concepts whose concept 0 names a term that does not
    exist, under a checksum that matches (a file aileen did not write)."""
    import struct
    import zlib

    memory_of(3).save(tmp_path / "m.amem")
    data = bytearray((tmp_path / "m.amem").read_bytes())
    room = struct.unpack_from("<I", data, 20)[0]
    start, _n = json.loads(data[24:24 + room])["sections"]["data"]
    struct.pack_into("<I", data, start + 4 * 4, 10**6)  # concept 0's first fact: no such term
    struct.pack_into("<I", data, 16, zlib.crc32(bytes(data[24:])))
    (tmp_path / "bad.amem").write_bytes(bytes(data))
    return tmp_path / "bad.amem"


def test_bad_numbers_in_a_concept_are_an_error_naming_the_concept(tmp_path: Path) -> None:
    """A file written with a matching checksum but wrong numbers (not one aileen wrote) is
    refused when the concept is read, naming it, never with a traceback."""
    _with_a_bad_concept(tmp_path)
    m = ConceptMemory.load(tmp_path / "bad.amem")
    with pytest.raises(UserError, match="concept 'r_w0': no term 1000000"):
        m.descriptions("r_w0")
    assert m.descriptions("r_w1")  # the others read


def test_a_name_no_fact_can_have_is_refused_as_the_json_reader_refuses_it(tmp_path: Path, capsys) -> None:
    """A byte changed under a good checksum (`cv_` read `c\x01_`, or a variable) loaded and ran,
    and `memory convert` wrote a JSON file that could not be read back."""
    import struct
    import zlib

    memory_of(3).save(tmp_path / "m.amem")
    for bad in (b"c\x01", b"CV"):
        data = bytearray((tmp_path / "m.amem").read_bytes())
        room = struct.unpack_from("<I", data, 20)[0]
        at = data.index(b"cv_", 24 + room)
        data[at:at + 2] = bad
        struct.pack_into("<I", data, 16, zlib.crc32(bytes(data[24:])))
        (tmp_path / "bad.amem").write_bytes(bytes(data))
        assert main(["memory", "convert", str(tmp_path / "bad.amem"), str(tmp_path / "out.json")]) == 2
        assert "is not a term's name" in capsys.readouterr().err
        assert not (tmp_path / "out.json").exists()


# ---------------------------------------------------------------- the command
def test_convert_goes_either_way_and_back_to_the_same_bytes(tmp_path: Path, capsys) -> None:
    memory_of(20).save(tmp_path / "m.json")
    assert main(["memory", "convert", str(tmp_path / "m.json"), str(tmp_path / "m.amem")]) == 0
    assert "20 concepts, compact" in capsys.readouterr().out
    assert compact.is_compact((tmp_path / "m.amem").read_bytes())
    assert main(["memory", "convert", str(tmp_path / "m.amem"), str(tmp_path / "back.json")]) == 0
    assert (tmp_path / "back.json").read_bytes() == (tmp_path / "m.json").read_bytes()
    # the flag over the name
    assert main(["memory", "convert", str(tmp_path / "m.json"), str(tmp_path / "c.bin"), "--to", "compact"]) == 0
    assert compact.is_compact((tmp_path / "c.bin").read_bytes())
    assert main(["memory", "convert", str(tmp_path / "m.amem"), str(tmp_path / "j.amem"), "--to", "json"]) == 0
    assert json.loads((tmp_path / "j.amem").read_text())["format"] == "aileen-concept-memory"
    assert main(["memory", "show", str(tmp_path / "c.bin"), "--concept", "w4"]) == 0
    assert "r_w4 (visual)" in capsys.readouterr().out


def test_convert_refuses_a_file_a_run_holds_and_leaves_it(tmp_path: Path, capsys) -> None:
    memory_of(5).save(tmp_path / "m.json")
    (tmp_path / "out.amem").write_bytes(b"held")
    with MemoryFile.open(tmp_path / "out.amem"):
        assert main(["memory", "convert", str(tmp_path / "m.json"), str(tmp_path / "out.amem")]) == 2
    err = capsys.readouterr().err
    assert "in use by another aileen run" in err and err.count("\n") == 1
    assert (tmp_path / "out.amem").read_bytes() == b"held"


def test_convert_of_a_bad_file_is_one_line_and_writes_nothing(tmp_path: Path, capsys) -> None:
    (tmp_path / "bad.json").write_text('{"format": "aileen-concept-memory", "version": 1, "concepts": [1]}')
    assert main(["memory", "convert", str(tmp_path / "bad.json"), str(tmp_path / "out.amem")]) == 2
    err = capsys.readouterr().err
    assert str(tmp_path / "bad.json") in err and err.count("\n") == 1
    assert not (tmp_path / "out.amem").exists()


def test_a_run_keeps_its_memory_in_the_compact_form(tmp_path: Path) -> None:
    lesson = tmp_path / "a.toml"
    lesson.write_text('[[lesson]]\nsignal = "inform"\ncontent = "red box"\nobjects = ["red box"]\n')
    mem = tmp_path / "m.amem"
    assert main(["run", str(lesson), "--perception", "truth", "--memory", str(mem)]) == 0
    assert compact.is_compact(mem.read_bytes())
    assert {c.symbol for c in ConceptMemory.load(mem).concepts()} == {"r_red", "r_box"}
    lesson.write_text('[[lesson]]\nsignal = "inform"\ncontent = "blue cone"\nobjects = ["blue cone"]\n')
    assert main(["run", str(lesson), "--perception", "truth", "--memory", str(mem)]) == 0
    assert {c.symbol for c in ConceptMemory.load(mem).concepts()} == {"r_red", "r_box", "r_blue", "r_cone"}


def test_a_compact_save_killed_at_any_moment_leaves_the_old_or_the_new_file(tmp_path: Path) -> None:
    """The compact form is written through the same atomic path as the JSON file."""
    mem = tmp_path / "m.amem"
    memory_of(5).save(mem)
    old = mem.read_bytes()
    big = memory_of(400)
    new = compact.encode(big)
    for k in range(10):
        pid = os.fork()
        if pid == 0:  # pragma: no cover - the child
            try:
                big.save(mem)
            finally:
                os._exit(0)
        if k % 2:
            os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
        now = mem.read_bytes()
        assert now in (old, new)
        assert len(ConceptMemory.load(mem)) in (5, 400)
        mem.write_bytes(old)


def test_a_run_on_a_compact_file_with_a_bad_concept_stops_before_any_lesson(tmp_path: Path, capsys) -> None:
    """Read when first used, a damaged concept (its checksum right) failed lesson after
    lesson, and the save at the end failed on it too: what the run learned was in no file.
    A run reads every concept first: one line, exit 2, the file as it was."""
    import struct
    import zlib

    memory_of(3).save(tmp_path / "m.amem")
    data = bytearray((tmp_path / "m.amem").read_bytes())
    room = struct.unpack_from("<I", data, 20)[0]
    start, n = json.loads(data[24:24 + room])["sections"]["data"]
    struct.pack_into("<I", data, start + 4 * 4, 10**6)
    struct.pack_into("<I", data, 16, zlib.crc32(bytes(data[24:])))
    (tmp_path / "bad.amem").write_bytes(bytes(data))
    lessons = tmp_path / "one.toml"
    lessons.write_text('[[lesson]]\nsignal = "inform"\ncontent = "red box"\nobjects = ["red box"]\n')
    before = (tmp_path / "bad.amem").read_bytes()
    capsys.readouterr()
    assert main(["run", str(lessons), "--memory", str(tmp_path / "bad.amem"), "--perception", "truth"]) == 2
    out = capsys.readouterr()
    assert "concept 'r_w0': no term 1000000" in out.err and "lesson" not in out.out
    assert (tmp_path / "bad.amem").read_bytes() == before


def test_convert_of_a_compact_file_with_a_bad_concept_names_that_file(tmp_path: Path, capsys) -> None:
    """A concept damaged under a good checksum was read by the save, and the error blamed OUT
    ("out.json: cannot save the memory (malformed ...); what was learned is in no file")."""
    _with_a_bad_concept(tmp_path)
    assert main(["memory", "convert", str(tmp_path / "bad.amem"), str(tmp_path / "out.json")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"aileen: {tmp_path / 'bad.amem'}: ") and "concept 'r_w0'" in err
    assert "out.json" not in err and "cannot save" not in err and err.count("\n") == 1
    assert not (tmp_path / "out.json").exists()


@pytest.mark.parametrize(("name", "text"), [
    ("notes.txt", b"my precious notes\n"),
    ("lessons.toml", b'[[lesson]]\nsignal = "inform"\ncontent = "red box"\n'),
    ("other.json", b'{"format": "something-else", "version": 1}\n'),
    ("pic.amem", b"\x89PNG\r\n\x1a\n"),
])
def test_convert_never_replaces_a_file_that_is_not_a_memory(tmp_path: Path, capsys, name: str, text: bytes) -> None:
    """`memory convert m.json notes.txt` replaced the notes with a memory, exit 0."""
    memory_of(2).save(tmp_path / "m.json")
    out = tmp_path / name
    out.write_bytes(text)
    assert main(["memory", "convert", str(tmp_path / "m.json"), str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"aileen: {out}: ") and "not an aileen memory file" in err and err.count("\n") == 1
    assert out.read_bytes() == text


def test_convert_replaces_a_memory_file_of_either_form_or_an_empty_file(tmp_path: Path, capsys) -> None:
    memory_of(2).save(tmp_path / "m.json")
    memory_of(4).save(tmp_path / "old.json")
    memory_of(4).save(tmp_path / "old.amem")
    (tmp_path / "damaged.amem").write_bytes((tmp_path / "old.amem").read_bytes()[:40])
    (tmp_path / "empty.json").write_bytes(b"")
    for out in ("old.json", "old.amem", "damaged.amem", "empty.json"):
        assert main(["memory", "convert", str(tmp_path / "m.json"), str(tmp_path / out)]) == 0, out
        assert len(ConceptMemory.load(tmp_path / out)) == 2


def test_convert_refused_for_a_held_out_says_what_convert_can_do(tmp_path: Path, capsys) -> None:
    """Two converts at once: the second was told to "use another --memory file", a flag convert has not."""
    memory_of(2).save(tmp_path / "m.json")
    with MemoryFile.open(tmp_path / "out.json"):
        assert main(["memory", "convert", str(tmp_path / "m.json"), str(tmp_path / "out.json")]) == 2
    err = capsys.readouterr().err
    assert "in use by another aileen run" in err and "choose another OUT" in err and "--memory" not in err
