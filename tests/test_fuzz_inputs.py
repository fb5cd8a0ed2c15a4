"""Property-based: the lesson readers, the memory loader (its parameters too) and the sentence parser, fed random and
mutated input, answer with a result or a `UserError` (exit 2 on the command line), never
another exception, and never change the file they read. `AILEEN_FUZZ_EXAMPLES=N` runs N examples per property (60 by
default; CI runs them derandomized, see conftest.py)."""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path
from typing import Any

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from aileen.curriculum import rehearsal
from aileen.curriculum.formats import load_curriculum
from aileen.errors import UserError
from aileen.memory.concept import ConceptMemory
from aileen.memory.semantic import from_concepts
from aileen.reasoning.language import parse

ROOT = Path(__file__).resolve().parents[1]
LESSON_TEXTS = {p.name: p.read_text() for p in sorted((ROOT / "lessons").iterdir()) if p.suffix in (".toml", ".json")}
SETTINGS = settings(max_examples=int(os.environ.get("AILEEN_FUZZ_EXAMPLES", "60")), deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _memory_text() -> str:
    mem = ConceptMemory()
    mem.create("r_red", "visual")
    mem.store(["isa(o1,cv_red)", "isa(o1,cv_box)"], "r_red")
    mem.store(["isa(o2,cv_red)", "isa(o2,cv_cone)"], "r_red")
    mem.create("r_left_of", "spatial")
    mem.store(["r_left_of(o1,o2)", "w(o1,o2)", "dc(o1,o2)"], "r_left_of")
    mem.annotations["lexicon"] = {"positions": {"red": ["modifier"], "box": ["head"]}}
    return json.dumps(mem.to_dict(), indent=2)


MEMORY_TEXT = _memory_text()

_json = st.recursive(
    st.none() | st.booleans() | st.integers(-3, 10**6) | st.floats(allow_nan=True) | st.text(max_size=12),
    lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=8), inner, max_size=3),
    max_leaves=8,
)


@st.composite
def mutated_text(draw, base: str) -> str:
    """`base` with a few characters deleted, inserted or replaced, or cut short."""
    text = base
    for _ in range(draw(st.integers(1, 4))):
        if not text:
            break
        i = draw(st.integers(0, len(text) - 1))
        op = draw(st.sampled_from(["delete", "insert", "replace", "truncate"]))
        ch = draw(st.sampled_from(list('[]{}"=,:-\n 0a.\\')) | st.characters())
        text = {"delete": text[:i] + text[i + 1:], "insert": text[:i] + ch + text[i:],
                "replace": text[:i] + ch + text[i + 1:], "truncate": text[:i]}[op]
    return text


def _paths(x: Any, prefix: tuple = ()) -> list[tuple]:
    out = [prefix]
    if isinstance(x, dict):
        for k, v in x.items():
            out += _paths(v, prefix + (k,))
    elif isinstance(x, list):
        for i, v in enumerate(x):
            out += _paths(v, prefix + (i,))
    return out


@st.composite
def mutated_document(draw, base: Any) -> Any:
    """`base` (a JSON value) with one node replaced by a random JSON value."""
    doc = json.loads(json.dumps(base))
    path = draw(st.sampled_from(_paths(doc)))
    value = draw(_json)
    if not path:
        return value
    node = doc
    for k in path[:-1]:
        node = node[k]
    node[path[-1]] = value
    return doc


def _read_lessons(name: str, text: str) -> None:
    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / name
        p.write_bytes(text.encode("utf-8", errors="surrogatepass"))
        before = p.read_bytes()
        try:
            cur = load_curriculum(p)
            rehearsal.check_curriculum(cur.lessons, [cur.lesson_seed(i) for i in range(len(cur))])
        except UserError:
            pass
        assert p.read_bytes() == before


@SETTINGS
@given(st.sampled_from(sorted(LESSON_TEXTS)), st.data())
def test_mutated_lesson_files_read_or_fail_cleanly(name: str, data) -> None:
    _read_lessons(name, data.draw(mutated_text(LESSON_TEXTS[name])))


@SETTINGS
@given(st.sampled_from([".toml", ".json"]), st.text(max_size=200))
def test_random_lesson_files_read_or_fail_cleanly(suffix: str, text: str) -> None:
    _read_lessons("random" + suffix, text)


@SETTINGS
@given(st.data())
def test_structurally_mutated_json_lessons_read_or_fail_cleanly(data) -> None:
    base = json.loads(LESSON_TEXTS["original-format.json"])
    _read_lessons("mutated.json", json.dumps(data.draw(mutated_document(base))))


def _load_memory(text: str) -> None:
    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "m.json"
        p.write_bytes(text.encode("utf-8", errors="surrogatepass"))
        before = p.read_bytes()
        try:
            mem = ConceptMemory.load(p)
            from_concepts(mem)
        except UserError:
            pass
        assert p.read_bytes() == before


@SETTINGS
@given(st.data())
def test_mutated_memory_text_loads_or_fails_cleanly(data) -> None:
    _load_memory(data.draw(mutated_text(MEMORY_TEXT)))


@SETTINGS
@given(st.data())
def test_structurally_mutated_memory_loads_or_fails_cleanly(data) -> None:
    _load_memory(json.dumps(data.draw(mutated_document(json.loads(MEMORY_TEXT)))))


SENTENCES = ["red box", "the red box left of the blue cone", "move the red cylinder right of the blue box",
             "a green sphere in front of a yellow cube", "the red box touching the green sphere"]


@settings(max_examples=200, deadline=None)
@given(st.sampled_from(SENTENCES), st.data())
def test_mutated_sentences_parse_or_fail_cleanly(sentence: str, data) -> None:
    text = data.draw(mutated_text(sentence))
    try:
        p = parse(text)
    except UserError as exc:
        assert str(exc).startswith(("I could not read", "I cannot read")) and "\n" not in str(exc)
        return
    for o in p.objects:
        # no words only for "it", "the other one" or a bare "one" (any object)
        assert (o.words or o.anaphor or o.count == 1 or "one" in text.lower()) and len(set(o.words)) == len(o.words)


# ------------------------------------------------------------------ memory parameters

from aileen.memory import codec  # noqa: E402

_junk = (st.none() | st.booleans() | st.text(max_size=6) | st.lists(st.integers(), max_size=2)
         | st.floats(allow_nan=True, allow_infinity=True) | st.integers(-10**6, 10**6) | st.just({}))


def _in_range(rng: "codec.Range"):  # noqa: ANN202
    if rng.whole:
        return st.integers(int(rng.low), int(rng.high))
    return st.floats(rng.low, rng.high, exclude_min=rng.open_low, allow_nan=False)


@st.composite
def parameters(draw) -> dict:
    """A "params" object: each field left out, in range, or anything at all (and now and then
    a key the format does not have)."""
    out: dict[str, Any] = {}
    for name, rng in codec.SAGE_RANGES.items():
        how = draw(st.sampled_from(["absent", "good", "good", "junk"]))
        if how != "absent":
            out[name] = draw(_in_range(rng) if how == "good" else _junk)
    if draw(st.booleans()):
        out["normalisation"] = draw(st.sampled_from(["significant", "paper"]) | _junk)
    sme_obj: dict[str, Any] = {}
    for name, rng in codec.SME_RANGES.items():
        how = draw(st.sampled_from(["absent", "good", "good", "junk"]))
        if how != "absent":
            sme_obj[name] = draw(_in_range(rng) if how == "good" else _junk)
    if draw(st.integers(0, 9)) == 0:
        sme_obj[draw(st.text(min_size=1, max_size=6))] = 1
    out["sme"] = sme_obj if draw(st.integers(0, 19)) else draw(_junk)
    return out


def _holds(params: dict) -> bool:
    """Whether the drawn params are all well-formed (the loader must then accept them)."""
    sme_obj = params.get("sme", {})
    if not isinstance(sme_obj, dict) or set(sme_obj) - set(codec.SME_RANGES):
        return False
    for name, rng in codec.SAGE_RANGES.items():
        if name in params and not rng.holds(params[name]):
            return False
    if params.get("normalisation", "significant") not in ("significant", "paper"):
        return False
    return all(rng.holds(sme_obj[n]) for n, rng in codec.SME_RANGES.items() if n in sme_obj)


@SETTINGS
@given(parameters())
def test_memory_parameters_load_checked_or_fail_naming_the_field(params: dict) -> None:
    """Any "params" object: a well-formed one loads (its values kept, and the memory answers a
    query without an exception); anything else is a UserError naming "params" and the field,
    the file untouched."""
    doc = json.loads(MEMORY_TEXT)
    doc["params"] = {**params, "functions": []}
    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "m.json"
        p.write_text(json.dumps(doc))
        before = p.read_bytes()
        try:
            mem = ConceptMemory.load(p)
        except UserError as exc:
            assert not _holds(params), f"well-formed params refused: {exc}"
            assert '"params"' in exc.message, exc.message
            assert p.read_bytes() == before
            return
        assert _holds(params), f"malformed params loaded: {params}"
        for name in codec.SAGE_RANGES:
            if name in params:
                assert getattr(mem.params, name) == params[name]
        for name in codec.SME_RANGES:
            if name in params.get("sme", {}):
                assert getattr(mem.params.sme, name) == params["sme"][name]
        mem.query(["isa(o1,cv_red)", "isa(o1,cv_box)"], "isa(O,r_red)")
        again = Path(d) / "again.json"
        mem.save(again)
        assert ConceptMemory.load(again).params == mem.params
