"""The concept memory: the paper's worked examples, query semantics, projection, persistence."""

from __future__ import annotations

import json
import os

import pytest

from aileen.analogy.sage import SageParams
from aileen.errors import UserError
from aileen.memory.concept import ConceptMemory, latest_time_point
from aileen.terms import Term, parse, parse_many

A = "isa(o2,cv_red) isa(o2,cv_cylinder) isa(o2,r_red)"
B = "isa(o3,cv_red) isa(o3,cv_cube) isa(o3,r_red)"
PAPER_SCENE = "isa(o4,cv_red) isa(o4,cv_box) isa(o5,cv_green) isa(o2,cv_cylinder)"


@pytest.fixture
def red() -> ConceptMemory:
    m = ConceptMemory()
    m.create("r_red", "visual")
    m.store(parse_many(A), "r_red")
    m.store(parse_many(B), "r_red")
    return m


def test_store_paper_example(red: ConceptMemory) -> None:
    assert red.generalizations("r_red") == [{
        "isa(gen_ent(0,r_red),cv_red)": 1.0,
        "isa(gen_ent(0,r_red),r_red)": 1.0,
        "isa(gen_ent(0,r_red),cv_cube)": 0.5,
        "isa(gen_ent(0,r_red),cv_cylinder)": 0.5,
    }]


def test_store_result_counts() -> None:
    m = ConceptMemory()
    m.create("r_red", "visual")
    r1 = m.store(parse_many(A), "r_red")
    assert (r1.generalizations, r1.examples, r1.action) == (0, 1, "kept")
    r2 = m.store(parse_many(B), "r_red")
    assert (r2.generalizations, r2.examples, r2.action) == (1, 0, "new_generalization")


def test_query_paper_example(red: ConceptMemory) -> None:
    infs = red.query(parse_many(PAPER_SCENE), "isa(O,r_red)")
    assert [str(i.fact) for i in infs] == ["isa(o4,r_red)"]
    assert infs[0].similarity == pytest.approx(1.0)
    assert infs[0].binding == {Term("O"): Term("o4")}
    assert infs[0].source == "generalization"


def test_query_rejects_non_red_and_unknown(red: ConceptMemory) -> None:
    assert red.query(parse_many("isa(o5,cv_green) isa(o5,cv_box)"), "isa(O,r_red)") == []
    assert red.query(parse_many(PAPER_SCENE), "isa(O,r_blue)") == []  # unknown concept


def test_query_after_one_example_uses_the_example() -> None:
    m = ConceptMemory()
    m.create("r_green", "visual")
    m.store(parse_many("isa(o1,cv_green) isa(o1,r_green)"), "r_green")
    infs = m.query(parse_many("isa(o7,cv_green) isa(o7,cv_cone) isa(o8,cv_red)"), "isa(X,r_green)")
    assert [str(i.fact) for i in infs] == ["isa(o7,r_green)"]
    assert infs[0].source == "example"


def test_match_threshold_and_normalisation() -> None:
    facts = "isa(o1,cv_red) isa(o1,cv_box) isa(o1,r_thing)"
    scene = parse_many("isa(o4,cv_red) isa(o4,cv_sphere)")  # half of what the example has
    sig = ConceptMemory()
    sig.create("r_thing", "visual")
    sig.store(parse_many(facts), "r_thing")
    # Half of the example's own facts (cv_red of cv_red, cv_box): 0.5, below 0.75.
    assert sig.query(scene, "isa(O,r_thing)", concept="r_thing") == []
    loose = ConceptMemory(SageParams(match=0.4))
    loose.create("r_thing", "visual")
    loose.store(parse_many(facts), "r_thing")
    [inf] = loose.query(scene, "isa(O,r_thing)")
    assert inf.similarity == pytest.approx(0.5)
    # The paper's symmetric normalisation counts the whole scene, distractors included.
    paper = ConceptMemory(SageParams(match=0.0, normalisation="paper"))
    paper.create("r_thing", "visual")
    paper.store(parse_many(facts), "r_thing")
    few = paper.query(scene, "isa(O,r_thing)")[0].similarity
    many = paper.query(scene + parse_many("isa(o9,cv_blue) isa(o9,cv_cone) isa(o8,cv_green)"), "isa(O,r_thing)")[0].similarity
    assert many < few
    assert 0.0 < many < 1.0


def test_significant_normalisation_ignores_distractors(red: ConceptMemory) -> None:
    focused = red.query(parse_many("isa(o4,cv_red) isa(o4,cv_box)"), "isa(O,r_red)")
    crowded = red.query(parse_many(PAPER_SCENE + " isa(o6,cv_blue) isa(o6,cv_cone) dc(o4,o6)"), "isa(O,r_red)")
    assert focused[0].similarity == crowded[0].similarity == pytest.approx(1.0)


def test_binary_relation_query() -> None:
    m = ConceptMemory()
    m.create("r_left_of", "spatial")
    m.store(parse_many("w(o1,o2) dc(o1,o2) r_left_of(o1,o2)"), "r_left_of")
    m.store(parse_many("w(o3,o4) ec(o3,o4) r_left_of(o3,o4)"), "r_left_of")
    [inf] = m.query(parse_many("isa(o7,cv_red) isa(o8,cv_box) w(o7,o8) dc(o7,o8) e(o8,o7)"), "r_left_of(X,Y)")
    assert str(inf.fact) == "r_left_of(o7,o8)"
    assert m.query(parse_many("e(o7,o8) dc(o7,o8)"), "r_left_of(X,Y)") == []
    # The pattern filters inferences: a bound argument must match.
    assert m.query(parse_many("w(o7,o8) dc(o7,o8)"), "r_left_of(o8,Y)") == []


MOVE1 = ("isa(t0,start) h(t0,dc(o1,o2)) h(t0,e(o1,o2)) after(t1,t0) h(t1,held(o1)) "
         "after(t2,t1) h(t2,w(o1,o2)) h(t2,dc(o1,o2)) r_move_left_of(o1,o2)")
MOVE2 = ("isa(t0,start) h(t0,dc(o3,o1)) h(t0,n(o3,o1)) after(t1,t0) h(t1,held(o3)) "
         "after(t2,t1) h(t2,w(o3,o1)) h(t2,dc(o3,o1)) r_move_left_of(o3,o1)")


@pytest.fixture
def move() -> ConceptMemory:
    m = ConceptMemory()
    m.create("r_move_left_of", "action")
    m.store(parse_many(MOVE1), "r_move_left_of")
    m.store(parse_many(MOVE2), "r_move_left_of")
    return m


def test_projection_paper_example(move: ConceptMemory) -> None:
    trace = parse_many("isa(t0,start) h(t0,dc(o5,o6)) h(t0,e(o5,o6))")
    p1 = move.project(trace, "r_move_left_of")
    assert [str(f) for f in p1.facts] == ["held(o5)"]
    assert not p1.complete
    assert p1.time_point is not None and p1.time_point.name == "skolem"
    assert p1.after == Term("t0")
    assert parse(f"after({p1.time_point},t0)") in p1.mapping.inferences
    trace += parse_many("after(t1,t0) h(t1,held(o5))")
    p2 = move.project(trace, "r_move_left_of")
    assert {str(f) for f in p2.facts} == {"w(o5,o6)", "dc(o5,o6)"}
    assert p2.complete and p2.after == Term("t1")
    trace += parse_many("after(t2,t1) h(t2,w(o5,o6)) h(t2,dc(o5,o6))")
    p3 = move.project(trace, "r_move_left_of")
    assert p3.facts == [] and p3.complete


def test_projection_with_nothing_in_common(move: ConceptMemory) -> None:
    p = move.project(parse_many("isa(t0,start) h(t0,foo(o1))"), "r_move_left_of")
    assert p.facts == [] and not p.complete


def test_latest_time_point() -> None:
    assert latest_time_point(parse_many("isa(t0,start) after(t1,t0) after(t2,t1)")) == Term("t2")
    assert latest_time_point(parse_many("after(t2,t1) after(t1,t0)")) == Term("t2")
    assert latest_time_point(parse_many("h(t0,p(a))")) == Term("t0")
    assert latest_time_point([]) is None


def test_create_checks() -> None:
    m = ConceptMemory()
    c = m.create("r_red", "visual")
    assert m.create("r_red", "visual") is c
    with pytest.raises(UserError, match="already exists"):
        m.create("r_red", "spatial")
    with pytest.raises(UserError, match="kind"):
        m.create("r_x", "smell")
    with pytest.raises(UserError, match="constant"):
        m.create("Red", "visual")
    with pytest.raises(UserError, match="unknown concept"):
        m.store(parse_many(A), "r_blue")
    with pytest.raises(UserError, match="empty"):
        m.store([], "r_red")


def test_save_load_round_trip(tmp_path, red: ConceptMemory, move: ConceptMemory) -> None:
    red.create("r_cone", "visual")
    red.store(parse_many("isa(o1,cv_cone) isa(o1,r_cone)"), "r_cone")
    path = tmp_path / "memory.json"
    red.save(path)
    data = json.loads(path.read_text())
    assert data["format"] == "aileen-concept-memory" and data["version"] == 1
    loaded = ConceptMemory.load(path)
    assert loaded.to_dict() == red.to_dict()
    assert [str(i.fact) for i in loaded.query(parse_many(PAPER_SCENE), "isa(O,r_red)")] == ["isa(o4,r_red)"]
    # Storing more after loading continues the same generalization.
    loaded.store(parse_many("isa(o9,cv_red) isa(o9,cv_cube) isa(o9,r_red)"), "r_red")
    assert loaded.generalizations("r_red")[0]["isa(gen_ent(0,r_red),cv_cube)"] == pytest.approx(2 / 3)
    assert not [p for p in os.listdir(tmp_path) if p.endswith(".tmp")]


@pytest.mark.parametrize(
    "text, message",
    [
        ('{"format": "aileen-concept-memory", "version": 1, "concepts": [', "truncated"),
        ("not json at all", "not an aileen concept memory: a memory file is a JSON object"),
        ('[[lesson]]\nsignal = "inform"\n', "lesson files are run with 'aileen run'"),
        ('{"format": "aileen-concept-memory" oops}', "not valid JSON"),
        ("", "empty"),
        ('{"format": "something-else", "version": 1}', "not an aileen concept memory"),
        ('{"format": "aileen-concept-memory", "version": 99, "concepts": []}', "newer"),
        ('{"format": "aileen-concept-memory", "version": 1, "concepts": [{"symbol": "r_red", "kind": "visual", '
         '"generalizations": [{"examples": 2, "facts": [{"fact": "isa(g,", "count": 1}]}]}]}', "malformed"),
        ('{"format": "aileen-concept-memory", "version": 1, "concepts": [{"symbol": "r_red", "kind": "visual", '
         '"generalizations": [{"examples": 2, "facts": [{"fact": "isa(g,r_red)", "count": 3}]}]}]}', "count"),
    ],
)
def test_load_bad_files(tmp_path, text: str, message: str) -> None:
    path = tmp_path / "memory.json"
    path.write_text(text)
    with pytest.raises(UserError, match=message) as exc:
        ConceptMemory.load(path)
    assert str(path) in str(exc.value)
    assert path.read_text() == text  # untouched


def test_load_missing_file(tmp_path) -> None:
    with pytest.raises(UserError, match="no such"):
        ConceptMemory.load(tmp_path / "nope.json")


def test_save_replaces_atomically(tmp_path, red: ConceptMemory) -> None:
    path = tmp_path / "m.json"
    path.write_text("old")
    red.save(path)
    assert ConceptMemory.load(path).to_dict() == red.to_dict()
    with pytest.raises(UserError, match="does not exist"):
        red.save(tmp_path / "no" / "m.json")


def test_has_and_significant_facts(red: ConceptMemory) -> None:
    assert red.has("r_red") and not red.has("r_blue") and "r_red" in red
    assert [str(f) for f in red.significant_facts("r_red")] == [
        "isa(gen_ent(0,r_red),cv_red)", "isa(gen_ent(0,r_red),r_red)"]
    red.create("r_cone", "visual")
    red.store(parse_many("isa(o1,cv_cone) isa(o1,cv_red) isa(o1,r_cone)"), "r_cone")
    assert len(red.significant_facts("r_cone")) == 3


def test_memory_modules_import_no_heavy_dependencies() -> None:
    import subprocess
    import sys

    code = ("import sys, aileen.memory.concept, aileen.memory.commands, aileen.analogy.sage; "
            "print(sorted({'clingo', 'cv2', 'pymunk', 'numpy', 'torch'} & set(sys.modules)))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_the_names_of_the_split_modules_are_still_the_concept_modules() -> None:
    # query/fitting moved to memory/recognition.py and project to memory/projection.py; every
    # name they took along is still importable from memory/concept.py, as the same object.
    from aileen.memory import concept, projection, recognition

    for name in ("Inference", "CONTEXT_MAC", "_skeleton", "_pattern_concept", "_ANY"):
        assert getattr(concept, name) is getattr(recognition, name), name
    assert concept._has_skolem is recognition.has_skolem
    for name in ("Projection", "time_chain", "latest_time_point", "_anchors"):
        assert getattr(concept, name) is getattr(projection, name), name
    assert set(concept.__all__) == {"KINDS", "Concept", "StoreResult", "Inference", "Projection", "ConceptMemory"}


def test_projection_prefers_temporally_coherent_mapping() -> None:
    # At t1 the trace also shows dc(o1,o2), which alone would align t1 with the action's
    # last state (t2); the projection must still read t1 as the second state.
    m = ConceptMemory()
    m.create("r_move", "action")
    m.store(parse_many("isa(t0,start) h(t0,dc(o1,o2)) h(t0,e(o1,o2)) after(t1,t0) h(t1,held(o1)) "
                       "after(t2,t1) h(t2,w(o1,o2)) h(t2,dc(o1,o2))"), "r_move")
    trace = parse_many("isa(t0,start) h(t0,dc(o1,o2)) h(t0,e(o1,o2)) after(t1,t0) h(t1,held(o1)) h(t1,dc(o1,o2))")
    p = m.project(trace, "r_move")
    assert {str(f) for f in p.facts} == {"w(o1,o2)", "dc(o1,o2)"}
    assert p.complete and p.after == Term("t1")


def test_projection_from_a_single_example() -> None:
    m = ConceptMemory()
    m.create("r_move", "action")
    m.store(parse_many(MOVE1), "r_move")
    p = m.project(parse_many("isa(t0,start) h(t0,dc(o7,o8)) h(t0,e(o7,o8))"), "r_move")
    assert [str(f) for f in p.facts] == ["held(o7)"] and p.source == "example"


def test_ground_and_variable_patterns_score_alike(red: ConceptMemory) -> None:
    scene = parse_many("isa(o4,cv_red) isa(o4,cv_box)")
    [ground] = red.query(scene, "isa(o4,r_red)")
    [free] = red.query(scene, "isa(O,r_red)")
    assert ground.fact == free.fact and ground.similarity == pytest.approx(free.similarity)
    assert ground.binding == {}


def test_store_keeps_a_relation_examples_roles_apart_when_swapping_them_matches_more() -> None:
    # The second example, mapped with its roles swapped, shares more (direction and colours)
    # with the first than mapped as said; the generalization must still keep who is next to whom.
    mem = ConceptMemory()
    mem.create("r_next_to", "spatial")
    mem.store(["w(a,b)", "e(b,a)", "ec(a,b)", "ec(b,a)", "isa(a,cv_red)", "isa(b,cv_blue)", "r_next_to(a,b)"],
              "r_next_to")
    mem.store(["e(c,d)", "w(d,c)", "ec(c,d)", "ec(d,c)", "isa(c,cv_blue)", "isa(d,cv_red)", "r_next_to(c,d)"],
              "r_next_to")
    (gen,) = mem.generalizations("r_next_to")
    membership = {f: p for f, p in gen.items() if f.startswith("r_next_to(")}
    assert list(membership.values()) == [1.0], membership
