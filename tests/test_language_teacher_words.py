"""What the agent reads of a teacher's own words around the ones it learns: copula verbs
("looks"), general nouns ("the object"), comparatives, possessives (probe 51's sentences)."""

from __future__ import annotations

import pytest
from console_helpers import truth_console

from aileen.reasoning.language import NotUnderstood, parse

HEADS = frozenset({"box", "cone", "sphere"})
NAMED = HEADS | frozenset({"red", "blue", "green"})


def _read(sentence: str):  # noqa: ANN202 - a Parse
    return parse(sentence, heads=HEADS, named=NAMED)


def _taught() -> object:
    """A console whose agent knows red, blue, box, cone (each shown alone)."""
    _agent, con = truth_console()
    for line in ("place red box", "inform red box", "clear", "place blue cone", "inform blue cone", "clear"):
        con.do(line)
    return con


@pytest.mark.parametrize("sentence", ["the box looks crimson", "the box seems crimson", "the box appears crimson",
                                      "the box seems to be crimson", "the boxes look crimson"])
def test_a_copula_verb_says_what_is_says(sentence: str) -> None:
    p = _read(sentence)
    assert [o.words for o in p.objects] == [("crimson", "box")] and not p.relations


def test_looks_teaches_the_word_of_the_box_and_nothing_of_the_cone() -> None:
    """q29: "inform the box looks crimson" beside a blue cone made r_looks, a relation, and
    r_crimson with the cone as its example."""
    con = _taught()
    con.do("scene red box left of blue cone")
    said = con.do("inform the box looks crimson")
    assert "r_looks" not in said and "looks" not in con.agent.semantic.words()
    con.do("clear")
    con.do("place blue cone")
    assert "success" not in con.do("verify is the cone crimson?")
    con.do("clear")
    con.do("place red box")
    assert "success" in con.do("verify is the box crimson?")


@pytest.mark.parametrize("sentence", ["the box is coloured crimson", "the box is painted crimson",
                                      "the box is colored crimson"])
def test_a_participle_after_is_says_only_is(sentence: str) -> None:
    p = _read(sentence)
    assert [o.words for o in p.objects] == [("crimson", "box")] and not p.relations
    assert [o.words for o in _read("is the box painted red?").objects] == [("red", "box")]


def test_coloured_and_painted_are_never_learned() -> None:
    """q18, q19: "the box is coloured cherry" created r_coloured, "painted crimson" r_painted."""
    con = _taught()
    con.do("place red box")
    said = con.do("inform the box is coloured cherry") + con.do("inform the box is painted crimson")
    assert "r_coloured" not in said and "r_painted" not in said
    assert not {"coloured", "painted"} & set(con.agent.semantic.words())
    assert "success" in con.do("verify is the box cherry?")


@pytest.mark.parametrize("sentence,words", [
    ("the object is a box", [("box",)]), ("the thing is red", [("red",)]), ("this is a red object", [("red",)]),
    ("the item is red", [("red",)]), ("is there an object?", [()]), ("is the cone an object?", [("cone",)]),
    ("the shape is a box", [("box",)]), ("the colour is red", [("red",)]),
    ("the object is left of the cone", [(), ("cone",)]), ("is there something left of the cone?", [(), ("cone",)]),
])
def test_a_general_noun_names_the_thing_and_no_property(sentence: str, words: list) -> None:
    assert [o.words for o in _read(sentence).objects] == words


def test_object_thing_and_shape_are_never_learned() -> None:
    """q19, q20: "the object is a box" created r_object (then "is the cone an object?" -> no),
    "the thing is red" r_thing, "the shape is a box" r_shape."""
    con = _taught()
    con.do("place red box")
    said = "".join(con.do(f"inform {s}") for s in ("the object is a box", "the thing is red", "the shape is a box"))
    assert "created" not in said
    assert not {"object", "thing", "shape"} & set(con.agent.semantic.words())
    con.do("clear")
    con.do("place blue cone")
    assert "success" in con.do("verify is there an object?")
    assert "success" in con.do("verify is the cone an object?")


@pytest.mark.parametrize("sentence,words", [
    ("the box's colour is ruby", [("ruby", "box")]), ("the box\u2019s color is ruby", [("ruby", "box")]),
    ("is the box's colour red?", [("red", "box")]), ("the box's shape is a box", [("box",)]),
    ("the box's left of the cone", [("box",), ("cone",)]),
])
def test_a_things_colour_is_said_of_the_thing(sentence: str, words: list) -> None:
    assert [o.words for o in _read(sentence).objects] == words


def test_a_possessive_is_never_a_word_of_its_own() -> None:
    """q30: "inform the box's colour is ruby" asked "did you mean 'box'?" of "boxs", which
    nobody typed, and "no" learned r_boxs, r_colour and r_ruby."""
    with pytest.raises(NotUnderstood, match="'the box is ...'"):
        _read("the box's lid is red")
    con = _taught()
    con.do("place red box")
    said = con.do("inform the box's colour is ruby")
    assert "boxs" not in said and "created r_ruby;" in said
    assert not {"boxs", "colour"} & set(con.agent.semantic.words())


def test_a_tag_after_a_pause_is_the_word_blamed() -> None:
    """q13: "react move the red box right of the blue cone, will you?" said "I did not expect
    'cone,' (word 9)": the tag after the pause is what could not be read."""
    with pytest.raises(NotUnderstood, match=r"did not expect 'will' \(word 10\) after 'move the red box right of "
                                            r"the blue cone,'"):
        parse("move the red box right of the blue cone, will you?", action=True)


@pytest.mark.parametrize("sentence", ["the red box is left of the blue cone, not right of it",
                                      "is the red box left of the blue cone and not right of it?"])
def test_it_after_a_thing_in_the_sentence_is_that_thing(sentence: str) -> None:
    """q14: "it" was found among what the last lesson grounded (a sphere), not the cone the
    sentence had just named."""
    p = _read(sentence)
    second = p.relations[1]
    assert p.object(second.arg2).words == ("blue", "cone") and p.object(second.arg2).anaphor is None
    assert p.object(second.arg1).words == ("red", "box")
    assert _read("it is left of the cone").objects[0].anaphor == "it"


@pytest.mark.parametrize("word,stem", [("bigger", ("big", "er")), ("smallest", ("small", "est")),
                                       ("largest", ("large", "est")), ("leftmost", ("left", "most")),
                                       ("redder", ("red", "er")), ("tower", None), ("crimson", None)])
def test_a_comparative_is_told_by_its_ending(word: str, stem: tuple | None) -> None:
    from aileen.reasoning.spelling import degree_of

    assert degree_of(word, {"big", "small", "large", "left", "red", "box"}) == stem


def test_a_word_that_compares_is_not_learned_of_one_thing() -> None:
    """q25, q26: "the box is bigger" created r_bigger, "the leftmost cone is green" r_leftmost,
    which then held of the rightmost cone."""
    con = _taught()
    con.do("scene red box left of blue cone")
    said = {s: con.do(f"inform {s}") for s in ("the box is bigger", "the smallest box is left of the cone",
                                               "the leftmost box is red", "the box is redder")}
    assert all("not understood" in a and "created" not in a for a in said.values()), said
    assert "bigger than" in said["the box is bigger"] and "left of" in said["the leftmost box is red"]
    assert not {"bigger", "smallest", "leftmost", "redder"} & set(con.agent.semantic.words())


@pytest.mark.parametrize("sentence", ["the red box is towards the left of the blue cone",
                                      "the red box is toward the left of the blue cone"])
def test_towards_the_left_of_is_left_of(sentence: str) -> None:
    """q23: "towards the left of" was a word of its own, stored as "towards left of"."""
    assert _read(sentence).relation.word == "left_of"


def test_a_count_says_the_things_seen_in_the_plural() -> None:
    """q17: "is there one box?" with two boxes said "I see 2 'box', not 1"."""
    con = _taught()
    con.do("place red box at 0.2 0.5")
    con.do("place red box at 0.2 0.2")
    assert "I see 2 'boxes', not 1" in con.do("verify is there one box?")
    assert "I see 2 'boxes', not 3" in con.do("verify are there three boxes?")


def test_another_box_by_the_one_box_says_it_sees_only_that_one() -> None:
    """q7: "another box" with one box on the table said "I see no 'box'" while it saw one."""
    con = _taught()
    con.do("place red box")
    con.do("inform red box")
    said = con.do("inform another box")
    assert "I see no 'box' but the one we talked about" in said and "I see no 'box'\n" not in said + "\n", said
    assert "I see no 'box'" not in con.do("verify the other box is red")


def test_a_thing_named_by_a_general_noun_is_said_back_as_a_thing() -> None:
    """q20: "is there an object?" answered "[ = o1]", "the object is left of the cone" "I
    cannot tell which '' you mean"."""
    con = _taught()
    con.do("place red box at 0.3 0.5")
    assert "[thing = o1]" in con.do("verify is there an object?")
    con.do("place blue cone at 0.7 0.5")
    assert "I cannot tell which 'thing' you mean" in con.do("verify the object is left of the cone")
