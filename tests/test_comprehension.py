"""Indexical comprehension (asp/comprehension.lp through comprehension.py), table-driven.

Each case is a sentence, a scene as hand-written facts, the semantic memory and the
concept memory's inferred facts, with the expected referents, relation, goal and failures.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import pytest

from aileen.errors import UserError
from aileen.reasoning import asp
from aileen.reasoning.comprehension import comprehend, working_memory
from aileen.reasoning.language import parse
from aileen.terms import Term, parse_many

SCENE = """
isa(o1,cv_blue). isa(o1,cv_cone).
isa(o2,cv_red).  isa(o2,cv_cylinder).
isa(o3,cv_green). isa(o3,cv_sphere).
e(o1,o2). w(o2,o1). dc(o1,o2). dc(o2,o1).
n(o3,o1). s(o1,o3). dc(o1,o3). dc(o3,o1).
ne(o3,o2). sw(o2,o3). dc(o2,o3). dc(o3,o2).
"""
TWO_RED_BOXES = """
isa(o1,cv_blue). isa(o1,cv_cone).
isa(o5,cv_red). isa(o5,cv_box). isa(o6,cv_red). isa(o6,cv_box).
w(o5,o1). e(o1,o5). e(o6,o1). w(o1,o6).
"""
TWO_CONES = SCENE + "isa(o4,cv_yellow). isa(o4,cv_cone)."

WORDS = {
    "blue": "cv_blue", "cone": "cv_cone", "red": "cv_red", "cylinder": "cv_cylinder",
    "green": "cv_green", "sphere": "cv_sphere", "box": "cv_box", "purple": "cv_purple",
    "left_of": "r_left_of", "move_right_of": "r_move_right_of",
}


@dataclass
class Case:
    id: str
    sentence: str
    scene: str = SCENE
    inferred: str = ""
    words: dict = field(default_factory=lambda: dict(WORDS))
    referents: dict = field(default_factory=dict)
    holds: bool | None = None
    pairs: list = field(default_factory=list)
    goal: str | None = None
    failures: list = field(default_factory=list)


CASES = [
    Case("one object", "blue cone", referents={"r1": ["o1"]}),
    Case("one word", "cylinder", referents={"r1": ["o2"]}),
    Case("ambiguous", "cone", scene=TWO_CONES, referents={"r1": ["o1", "o4"]}, failures=[("ambiguous", "r1")]),
    Case("no referent", "purple cone", referents={"r1": []}, failures=[("no_referent", "r1")]),
    Case("unknown word stops its reference", "wug cone", referents={"r1": []}, failures=[("unknown_word", "wug")]),
    Case("unknown words everywhere", "wug dax behind blicket",
         referents={"r1": [], "r2": []},
         failures=[("unknown_word", "behind"), ("unknown_word", "blicket"), ("unknown_word", "dax"), ("unknown_word", "wug")]),
    Case("relation holds", "blue cone left of red cylinder", inferred="r_left_of(o1,o2).",
         referents={"r1": ["o1"], "r2": ["o2"]}, holds=True, pairs=[("o1", "o2")]),
    Case("relation false", "blue cone left of red cylinder", inferred="r_left_of(o2,o1).",
         referents={"r1": ["o1"], "r2": ["o2"]}, holds=False, failures=[("relation_false", "l1")]),
    Case("relation word unknown", "blue cone behind red cylinder",
         referents={"r1": ["o1"], "r2": ["o2"]}, holds=None, failures=[("unknown_word", "behind")]),
    Case("relation with a missing referent", "green cone left of red cylinder", inferred="r_left_of(o3,o2).",
         referents={"r1": [], "r2": ["o2"]}, holds=None, failures=[("no_referent", "r1")]),
    Case("relation disambiguates", "the red box left of the blue cone", scene=TWO_RED_BOXES,
         inferred="r_left_of(o5,o1).", referents={"r1": ["o5"], "r2": ["o1"]}, holds=True, pairs=[("o5", "o1")]),
    Case("relation does not disambiguate", "the red box left of the blue cone", scene=TWO_RED_BOXES,
         inferred="r_left_of(o5,o1). r_left_of(o6,o1).", referents={"r1": ["o5", "o6"], "r2": ["o1"]},
         holds=True, pairs=[("o5", "o1"), ("o6", "o1")], failures=[("ambiguous", "r1")]),
    Case("ambiguous without the relation", "red box", scene=TWO_RED_BOXES,
         referents={"r1": ["o5", "o6"]}, failures=[("ambiguous", "r1")]),
    Case("an object is not related to itself", "cone left of cone", inferred="r_left_of(o1,o1).",
         referents={"r1": ["o1"], "r2": ["o1"]}, holds=False, failures=[("relation_false", "l1")]),
    Case("word straight to a QSR", "blue cone left of red cylinder", words={**WORDS, "left_of": "e"},
         referents={"r1": ["o1"], "r2": ["o2"]}, holds=True, pairs=[("o1", "o2")]),
    Case("inferred unary concepts", "blue sphere", words={**WORDS, "blue": "r_blue"}, inferred="isa(o3,r_blue).",
         referents={"r1": ["o3"]}),
    Case("learned concept alone does not match percepts", "blue cone", words={**WORDS, "blue": "r_blue"},
         referents={"r1": []}, failures=[("no_referent", "r1")]),
    Case("action goal", "move the blue cone right of the red cylinder",
         referents={"r1": ["o1"], "r2": ["o2"]}, goal="r_move_right_of(o1,o2)"),
    Case("action word unknown", "push the blue cone right of the red cylinder",
         referents={"r1": ["o1"], "r2": ["o2"]}, failures=[("unknown_word", "push_right_of")]),
    Case("action on an ambiguous object", "move the cone right of the red cylinder", scene=TWO_CONES,
         referents={"r1": ["o1", "o4"], "r2": ["o2"]}, failures=[("ambiguous", "r1")]),
    Case("action on a missing object", "move the purple cone right of the red cylinder",
         referents={"r1": [], "r2": ["o2"]}, failures=[("no_referent", "r1")]),
]


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_comprehension(case: Case):
    result = comprehend(parse(case.sentence), words=case.words, facts=parse_many(case.scene),
                        inferred=parse_many(case.inferred))
    assert {k: [str(o) for o in v] for k, v in result.referents.items()} == case.referents
    assert result.relation_holds == case.holds
    assert [(str(a), str(b)) for a, b in result.pairs] == case.pairs
    assert (str(result.goal.term()) if result.goal else None) == case.goal
    assert sorted((f.reason, str(f.subject)) for f in result.failures) == sorted(case.failures)
    assert result.ok == (not case.failures)


def test_action_relation_concept_is_reported():
    words = {**WORDS, "right_of": "r_right_of"}
    r = comprehend(parse("move the blue cone right of the red cylinder"), words=words, facts=parse_many(SCENE))
    assert r.goal is not None and r.goal.relation == Term("r_right_of")
    assert (r.goal.concept, r.goal.arg1, r.goal.arg2) == (Term("r_move_right_of"), Term("o1"), Term("o2"))


def test_unknown_words_and_helpers():
    r = comprehend(parse("wug cone left of red dax"), words=WORDS, facts=parse_many(SCENE))
    assert r.unknown_words == ["dax", "wug"]
    assert r.failed("unknown_word") == [Term("dax"), Term("wug")]
    assert r.referent("r1") is None


def test_binary_concept_facts_cross_the_boundary_as_rel():
    wm = {str(f) for f in working_memory(parse("cone"), words={}, facts=parse_many("w(o1,o2)."),
                                         inferred=parse_many("r_left_of(o1,o2). isa(o1,r_red)."))}
    assert {"rel(r_left_of,o1,o2)", "rel(w,o1,o2)", "w(o1,o2)", "isa(o1,r_red)", "obj(o1)", "obj(o2)"} <= wm


# ---- the encoding itself, with raw fact programs -------------------------------------------

RAW = [
    # facts, expected shown atoms
    ("ref(r). ref_word(r,x). word_concept(x,c). obj(a). isa(a,c).",
     {"referent(r,a)", "candidate(r,a)"}),
    ("ref(r). ref_word(r,x). ref_word(r,y). word_concept(x,c). word_concept(y,d). obj(a). obj(b). isa(a,c). isa(b,c). isa(b,d).",
     {"referent(r,b)", "candidate(r,b)"}),
    ("ref(r). ref_word(r,x). obj(a).",
     {"failure(unknown_word,x)"}),
    ("ref(r). ref_word(r,x). word_concept(x,c). obj(a). obj(b). isa(a,c). isa(b,c).",
     {"referent(r,a)", "referent(r,b)", "failure(ambiguous,r)", "candidate(r,a)", "candidate(r,b)"}),
    # "it": a reference pinned to the object an earlier lesson grounded
    ("ref(r). ref_is(r,b). obj(a). obj(b).",
     {"referent(r,b)", "candidate(r,b)"}),
    ("ref(r). ref_word(r,x). ref_is(r,a). word_concept(x,c). obj(a). obj(b). isa(b,c).",
     {"failure(no_referent,r)"}),
    ("ref(r1). ref(r2). ref_word(r1,x). ref_word(r2,y). word_concept(x,c). word_concept(y,d). word_concept(l,k)."
     "rel_ref(l1,r1,r2). rel_word(l1,l). obj(a). obj(b). isa(a,c). isa(b,d). rel(k,a,b).",
     {"referent(r1,a)", "referent(r2,b)", "holds(l1,a,b)", "candidate(r1,a)", "candidate(r2,b)"}),
    ("ref(r1). ref(r2). ref_word(r1,x). ref_word(r2,y). word_concept(x,c). word_concept(y,d). word_concept(l,k)."
     "rel_ref(l1,r1,r2). rel_word(l1,l). obj(a). obj(b). isa(a,c). isa(b,d). rel(k,b,a).",
     {"referent(r1,a)", "referent(r2,b)", "failure(relation_false,l1)", "candidate(r1,a)", "candidate(r2,b)"}),
    ("ref(r1). ref(r2). ref_word(r1,x). ref_word(r2,y). word_concept(x,c). word_concept(y,d). word_concept(m,g)."
     "act_ref(a1,r1,r2). act_word(a1,m). obj(a). obj(b). isa(a,c). isa(b,d).",
     {"referent(r1,a)", "referent(r2,b)", "goal(a1,g,a,b)", "candidate(r1,a)", "candidate(r2,b)"}),
]


@pytest.mark.parametrize("facts,expected", RAW)
def test_comprehension_lp_on_raw_facts(facts, expected):
    model = asp.solve_once(asp.rule_paths(["comprehension.lp"]), parse_many(facts))
    assert {str(a) for a in model} == expected


def test_user_rules_override_the_shipped_file(tmp_path):
    shipped = asp.rule_path("comprehension.lp").read_text()
    # a user's rule: red things also count as "blue" (silly, but visible)
    (tmp_path / "comprehension.lp").write_text(shipped + "\nsat(R,W,O) :- ref_word(R,W), W = blue, isa(O,cv_red), obj(O).\n")
    r = comprehend(parse("blue"), words=WORDS, facts=parse_many(SCENE), rules=tmp_path)
    assert [str(o) for o in r.referents["r1"]] == ["o1", "o2"]


def test_semantic_memory_concepts_must_be_terms():
    with pytest.raises(UserError, match="'red'"):
        comprehend(parse("red"), words={"red": "r red"}, facts=parse_many(SCENE))
    # compound concept symbols are fine
    r = comprehend(parse("red"), words={"red": "percept(cv_red)"}, facts=parse_many("isa(o2,percept(cv_red))."))
    assert r.referents == {"r1": [Term("o2")]}
