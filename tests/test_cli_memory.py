"""`aileen memory show`."""

from __future__ import annotations

import json

import pytest

from aileen.cli import main
from aileen.memory.concept import ConceptMemory
from aileen.terms import parse_many


@pytest.fixture
def saved(tmp_path):
    m = ConceptMemory()
    m.create("r_red", "visual")
    m.store(parse_many("isa(o2,cv_red) isa(o2,cv_cylinder) isa(o2,r_red)"), "r_red")
    m.store(parse_many("isa(o3,cv_red) isa(o3,cv_cube) isa(o3,r_red)"), "r_red")
    m.create("r_cone", "visual")
    m.store(parse_many("isa(o1,cv_cone) isa(o1,r_cone)"), "r_cone")
    path = tmp_path / "memory.json"
    m.save(path)
    return path


def test_show_text(saved, capsys) -> None:
    assert main(["memory", "show", str(saved)]) == 0
    out = capsys.readouterr().out
    assert "r_red (visual): 1 generalization, 0 examples" in out
    assert "r_cone (visual): 0 generalizations, 1 example" in out
    assert "1.00  isa(gen_ent(0,r_red),r_red)" in out
    assert "0.50  isa(gen_ent(0,r_red),cv_cube)" in out
    assert "isa(o1,cv_cone)" in out


def test_show_one_concept_json(saved, capsys) -> None:
    assert main(["memory", "show", str(saved), "--concept", "r_red", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert list(data) == ["r_red"]
    g = data["r_red"]["generalizations"][0]
    assert g["examples"] == 2
    assert g["facts"]["isa(gen_ent(0,r_red),cv_cylinder)"] == 0.5


def test_show_unknown_concept(saved, capsys) -> None:
    assert main(["memory", "show", str(saved), "--concept", "r_blue"]) == 2
    err = capsys.readouterr().err
    assert "r_blue" in err and str(saved) in err and len(err.strip().splitlines()) == 1


def test_show_bad_file(tmp_path, capsys) -> None:
    p = tmp_path / "bad.json"
    p.write_text('{"format": "aileen-concept-memory", "version": 7}')
    assert main(["memory", "show", str(p)]) == 2
    assert "newer" in capsys.readouterr().err


@pytest.mark.parametrize("said", ["touching", "next to", "beside"])
def test_a_declared_spelling_of_a_relation_word_shows_that_word(tmp_path, capsys, said: str) -> None:
    """`--concept touching` found nothing (the word is "next to", `r_next_to`) and said no more."""
    m = ConceptMemory()
    m.create("r_next_to", "spatial")
    m.store(parse_many("ec(o1,o2) r_next_to(o1,o2)"), "r_next_to")
    path = tmp_path / "memory.json"
    m.save(path)
    assert main(["memory", "show", str(path), "--concept", said, "--json"]) == 0
    assert list(json.loads(capsys.readouterr().out)) == ["r_next_to"]


@pytest.mark.parametrize(("version", "said"), [
    ("true", "bad format version true (expected an integer >= 1)"),
    ('"1"', 'bad format version "1" (expected an integer >= 1)'),
    ("null", "bad format version null (expected an integer >= 1)"),
    (None, "the format version is missing (expected \"version\": an integer >= 1)"),
])
def test_a_bad_version_is_said_as_the_file_says_it(tmp_path, capsys, version, said) -> None:
    """`"version": true` was "bad format version True", and a missing one "None": Python's spellings."""
    p = tmp_path / "v.json"
    p.write_text('{"format": "aileen-concept-memory"' + (f', "version": {version}' if version else "") + "}")
    assert main(["memory", "show", str(p)]) == 2
    assert capsys.readouterr().err == f"aileen: {p}: {said}\n"


def test_a_file_of_zeros_after_its_text_is_said_to_hold_nul_bytes(tmp_path, capsys) -> None:
    """A JSON memory a crash left zero-filled was "truncated (not valid JSON): Invalid control character"."""
    p = tmp_path / "nul.json"
    p.write_bytes(b'{\n  "format": "aileen-concept-memory",\n  "version": 1,\n  "par' + b"\x00" * 100)
    assert main(["memory", "show", str(p)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"aileen: {p}:4: memory file is damaged: it holds NUL bytes from column 7 on")
    assert "truncated" not in err and err.count("\n") == 1


def test_show_help_says_it_reads_either_form(capsys) -> None:
    with pytest.raises(SystemExit):
        main(["memory", "show", "--help"])
    out = " ".join(capsys.readouterr().out.split())
    assert "(JSON or compact)" in out and "(JSON)" not in out


def test_an_unknown_concept_in_a_large_memory_names_a_few_and_the_count(tmp_path, capsys) -> None:
    """`--concept nosuch` on a memory of 10,000 concepts printed every one, on one 109 KB line."""
    m = ConceptMemory()
    for i in range(200):
        m.create(f"r_word{i}", "visual")
        m.store(parse_many(f"isa(o1,cv_red) isa(o1,r_word{i})"), f"r_word{i}")
    path = tmp_path / "big.json"
    m.save(path)
    assert main(["memory", "show", str(path), "--concept", "wrd17"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and len(err) < 400, err
    assert "did you mean 'word17'" in err and "it holds 200 concepts" in err and "192 more" in err
    assert "r_word199" not in err


class _Closed:
    """An output nobody reads any more (`aileen memory show ... | head -2`, after head ended)."""

    def write(self, text: str) -> int:
        raise BrokenPipeError(32, "Broken pipe")

    def flush(self) -> None:
        pass


def test_show_into_a_closed_output_says_what_show_did_not_do(saved, capsys, monkeypatch) -> None:
    """`memory show big.amem | head -2` ended "so the lessons after it were not given": show gives none."""
    monkeypatch.setattr("sys.stdout", _Closed())
    assert main(["memory", "show", str(saved)]) == 141
    err = capsys.readouterr().err
    assert err == ("aileen: stopped: the output was closed (nobody reads it any more), "
                   "so the rest of the memory was not shown\n")


def _store_examples(m: ConceptMemory, concept: str, sectors: tuple[int, ...], gap: str, *more: str) -> None:
    """Store one example of the relation word `concept` per fine sector in `sectors` (the pair
    `gap` apart and disconnected, with the relations `more` between them too)."""
    for k, sector in enumerate(sectors):
        pair = f"(o{k}1,o{k}2)"
        facts = " ".join(f"{r}{pair}" for r in (concept, f"d64_{sector:02d}", gap, "dc", *more))
        m.store(parse_many(facts), concept)


def test_show_gives_a_relation_words_learned_regions(tmp_path, capsys) -> None:
    """A relation word's direction and distance are regions read by the size principle, not
    its facts: `memory show` says where it holds, in degrees and gaps (it printed 64 sector
    facts with probability 1, and a researcher could not see the grain the word was learned at)."""
    m = ConceptMemory()
    m.create("r_zorp_of", "spatial")
    m.create("r_red", "visual")
    m.store(parse_many("isa(o1,cv_red) isa(o1,r_red)"), "r_red")
    _store_examples(m, "r_zorp_of", (30, 31, 32, 33), "dgap_05")  # 168.75 to 191.25 degrees: west
    path = tmp_path / "m.json"
    m.save(path)
    assert main(["memory", "show", str(path), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["r_red"]["regions"] is None
    regions = data["r_zorp_of"]["regions"]
    assert regions["examples"] == 4
    holds = regions["direction"]["holds"]
    inside = lambda deg: any(a <= deg <= b if a <= b else deg >= a or deg <= b for a, b in holds)  # noqa: E731
    assert inside(180) and inside(170) and not inside(0) and not inside(90)
    assert regions["direction"]["every_side"] < 0.01
    assert main(["memory", "show", str(path), "--concept", "zorp of"]) == 0
    out = capsys.readouterr().out
    assert "learned regions (the size principle over 4 examples and 0 near misses)" in out
    assert "holds 168.75-191.25" in out


def test_show_gives_no_distance_region_to_a_word_that_says_a_side(tmp_path, capsys) -> None:
    """A word that says a side has no distance of its own (`Directions.reach`: how far apart its
    examples lay is the distance words' business), and the agent takes it at every distance;
    `memory show` said "distance holds 0.75-1; any distance: 0 %" of "zup of" shown at one gap,
    as if it held there only. A word shown on every side still gets its distance, and so does
    one that says more than a side (close by: mutual exclusivity may leave its side to the
    direction words, and its distance is then read)."""
    m = ConceptMemory()
    m.create("r_zup_of", "spatial")
    m.create("r_nigh_of", "spatial")
    m.create("r_jlo_of", "spatial")
    _store_examples(m, "r_jlo_of", (31, 32, 33), "dgap_02", "qd_close")  # west, close by
    _store_examples(m, "r_zup_of", (3, 3, 4, 3), "dgap_08")  # 17 to 28 degrees
    _store_examples(m, "r_nigh_of", (0, 16, 32, 48, 8, 40), "dgap_02")  # every side, close by
    path = tmp_path / "m.json"
    m.save(path)
    assert main(["memory", "show", str(path), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    zup, nigh = data["r_zup_of"]["regions"], data["r_nigh_of"]["regions"]
    assert zup["direction"]["holds"] and zup["distance"] is None and zup["says_side"]
    assert nigh["distance"]["holds"] and not nigh["says_side"]
    jlo = data["r_jlo_of"]["regions"]
    assert jlo["direction"]["holds"] and jlo["distance"]["holds"] and not jlo["says_side"]
    assert main(["memory", "show", str(path), "--concept", "zup of"]) == 0
    out = capsys.readouterr().out
    assert "distance: no region of its own (it says a side" in out
    assert "distance, gap" not in out


class _Recording:
    """An output that records what was written, and when, among the other events of a run."""

    def __init__(self, events: list[str]) -> None:
        self.events = events

    def write(self, text: str) -> int:
        self.events.append("write " + text)
        return len(text)

    def flush(self) -> None:
        pass


@pytest.mark.parametrize("as_json", [False, True])
def test_show_writes_each_concept_before_it_reads_the_next_ones_quality(saved, monkeypatch, as_json) -> None:
    """On 10,000 concepts `memory show` (and `| head`) printed nothing for two minutes: every
    concept's quality was worked out before the first line was written."""
    from aileen.memory import commands, quality

    events: list[str] = []
    real = quality.quality
    monkeypatch.setattr(quality, "quality", lambda m, c, **kw: (events.append("quality " + c), real(m, c, **kw))[1])
    monkeypatch.setattr("sys.stdout", _Recording(events))
    assert main(["memory", "show", str(saved)] + (["--json"] if as_json else [])) == 0
    red, cone = events.index("quality r_red"), events.index("quality r_cone")
    assert any(e.startswith("write") and "r_red" in e for e in events[red:cone]), events
    text = "".join(e.removeprefix("write ") for e in events if e.startswith("write "))
    memory = ConceptMemory.load(saved)
    if as_json:  # the same text, one JSON object, as before it was written in pieces
        assert text == json.dumps(commands.render_json(memory), indent=2) + "\n"
    else:
        assert text == commands.render_text(memory) + "\n"


def test_list_names_every_concept_without_asking_its_quality(saved, capsys, monkeypatch) -> None:
    """`memory list`: one line per concept, fast on any size (no quality, which asks the rest of
    the memory); what an unknown `--concept` points to."""
    from aileen.memory import quality

    monkeypatch.setattr(quality, "quality", lambda *a, **k: pytest.fail("list asked a concept's quality"))
    assert main(["memory", "list", str(saved)]) == 0
    assert capsys.readouterr().out.splitlines() == [
        "2 concepts",
        'r_red (visual) "red": 2 examples seen, 1 generalization, 0 examples apart',
        'r_cone (visual) "cone": 1 example seen, 0 generalizations, 1 example apart',
    ]


def test_an_unknown_concept_points_to_the_fast_listing(tmp_path, capsys) -> None:
    """The error said "'aileen memory show' without --concept lists them": minutes on a large memory."""
    m = ConceptMemory()
    for i in range(20):
        m.create(f"r_word{i}", "visual")
    path = tmp_path / "m.json"
    m.save(path)
    assert main(["memory", "show", str(path), "--concept", "zzz"]) == 2
    assert "'aileen memory list' lists them" in capsys.readouterr().err
