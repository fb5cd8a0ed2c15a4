"""The lexicon's behaviours one by one (issue 27): narrowing a word by its position in the
noun phrase, the evidence positions give, word order, and what is saved. Each test names the
behaviour it holds, and fails when that behaviour is broken (tools/mutation.py checks it).

The lexicon is driven directly, with meanings given by hand: a word's meaning stands for the
percepts its concept's generalization requires, as the agent would supply it."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.agent.lexicon import POSITIONS, Lexicon, exclusive
from aileen.reasoning.language import ObjectRef, Parse
from aileen.terms import Term


def percepts(*names: str) -> frozenset[Term]:
    return frozenset(Term(n) for n in names)


def lexicon(meanings: dict[str, frozenset[Term]], positions: dict[str, set[str]] | None = None,
            *, bootstrapping: bool = True) -> Lexicon:
    """A lexicon over visual concepts `r_<word>` with the given meanings, the words having
    stood where `positions` says."""
    lex = Lexicon(lambda c: meanings[c], lambda c: c[2:] if c.startswith("r_") else None,
                  lambda: list(meanings), bootstrapping=bootstrapping)
    for w, ps in (positions or {}).items():
        lex.positions[w] = set(ps)
    return lex


def phrase(*words: str, ref: str = "x1") -> ObjectRef:
    return ObjectRef(ref, tuple(words))


def parse_of(*refs: ObjectRef) -> Parse:
    return Parse(" and ".join(r.text for r in refs), tuple(refs))


#: Pinned words: `red` (a modifier) means a colour, `box` (a head noun) a shape.
PINNED = {"r_red": percepts("cv_red"), "r_box": percepts("cv_box")}
PINNED_AT = {"red": {"modifier"}, "box": {"head"}}


# ---------------------------------------------------------------- narrowing by position
def test_a_head_noun_is_narrowed_to_the_channels_head_nouns_name() -> None:
    lex = lexicon({**PINNED, "r_cone": percepts("cv_cone", "cv_green")}, {**PINNED_AT, "cone": {"head"}})
    assert lex.effective_meanings()["r_cone"] == percepts("cv_cone")


def test_a_word_that_stood_as_head_and_as_modifier_keeps_the_channels_of_both() -> None:
    # Both positions have evidence: the word keeps the shape and the colour, drops the size.
    lex = lexicon({**PINNED, "r_thing": percepts("cv_cone", "cv_green", "cv_large")},
                  {**PINNED_AT, "thing": {"head", "modifier"}})
    assert lex.effective_meanings()["r_thing"] == percepts("cv_cone", "cv_green")


def test_a_word_in_a_position_with_no_evidence_yet_is_not_narrowed() -> None:
    # Only modifiers have evidence (colour); the word also stood as a head, which might name
    # anything yet: narrowing it to colours would drop what the head position may mean.
    lex = lexicon({"r_red": percepts("cv_red"), "r_thing": percepts("cv_cone", "cv_green")},
                  {"red": {"modifier"}, "thing": {"head", "modifier"}})
    assert lex.effective_meanings()["r_thing"] == percepts("cv_cone", "cv_green")


def test_a_word_with_no_known_position_is_not_narrowed() -> None:
    lex = lexicon({**PINNED, "r_thing": percepts("cv_cone", "cv_green")}, PINNED_AT)
    assert lex.effective_meanings()["r_thing"] == percepts("cv_cone", "cv_green")


def test_narrowing_never_leaves_a_word_with_an_empty_meaning() -> None:
    # Modifiers name colours, but this modifier's meaning holds no colour: it keeps its meaning.
    lex = lexicon({**PINNED, "r_big": percepts("cv_large", "cv_cone")}, {**PINNED_AT, "big": {"modifier"}})
    assert lex.effective_meanings()["r_big"] == percepts("cv_large", "cv_cone")


def test_without_bootstrapping_positions_narrow_nothing() -> None:
    meanings = {**PINNED, "r_cone": percepts("cv_cone", "cv_green")}
    lex = lexicon(meanings, {**PINNED_AT, "cone": {"head"}}, bootstrapping=False)
    assert lex.effective_meanings()["r_cone"] == percepts("cv_cone", "cv_green")


def test_narrowed_meanings_are_made_exclusive_again() -> None:
    # Modifiers name colours (green). Narrowed, `dull` is {cv_red}, which `dark` then gives up;
    # before narrowing neither meaning held the other.
    lex = lexicon({"r_green": percepts("cv_green"), "r_dull": percepts("cv_red", "cv_cone"),
                   "r_dark": percepts("cv_red", "cv_blue")},
                  {"green": {"modifier"}, "dull": {"modifier"}, "dark": {"modifier"}})
    assert lex.effective_meanings() == {"r_green": percepts("cv_green"), "r_dull": percepts("cv_red"),
                                        "r_dark": percepts("cv_blue")}


def test_a_pinned_word_frees_the_words_taught_with_it() -> None:
    # `green` was taught with cone; `cone` pinned down frees it (no positions known). `red`
    # makes colour a channel whose values tell objects apart (a meaning is never left with
    # only percepts no word's meaning contrasts: issue 20 (a)).
    lex = lexicon({"r_cone": percepts("cv_cone"), "r_green": percepts("cv_green", "cv_cone"),
                   "r_red": percepts("cv_red")})
    assert lex.effective_meanings() == {"r_cone": percepts("cv_cone"), "r_green": percepts("cv_green"),
                                        "r_red": percepts("cv_red")}


def test_effective_meanings_are_kept_until_invalidated() -> None:
    # (blue and box: each channel has values that tell objects apart, issue 20 (a))
    meanings = {"r_red": percepts("cv_red"), "r_cone": percepts("cv_cone", "cv_red"),
                "r_blue": percepts("cv_blue"), "r_box": percepts("cv_box")}
    lex = lexicon(meanings)
    first = lex.effective_meanings()
    assert first["r_cone"] == percepts("cv_cone")
    meanings["r_cone"] = percepts("cv_cone", "cv_green")
    assert lex.effective_meanings() is first
    lex.invalidate()
    assert lex.effective_meanings()["r_cone"] == percepts("cv_cone", "cv_green")


def test_claimed_by_others_is_what_the_other_words_stand_for() -> None:
    lex = lexicon({"r_red": percepts("cv_red"), "r_cone": percepts("cv_cone", "cv_red"),
                   "r_blue": percepts("cv_blue"), "r_box": percepts("cv_box")})
    assert lex.claimed_by_others("r_cone") == percepts("cv_red")
    assert lex.claimed_by_others("r_red") == frozenset()


def test_a_concept_without_an_effective_meaning_has_all_of_its_meaning_claimed() -> None:
    lex = lexicon({"r_red": percepts("cv_red")})
    lex._meaning_of = lambda c: percepts("cv_red", "cv_box")  # a concept the lexicon does not list
    assert lex.claimed_by_others("r_other") == percepts("cv_red", "cv_box")


# ---------------------------------------------------------------- evidence from pinned words
def test_positions_name_the_channels_of_the_words_pinned_to_one_percept() -> None:
    lex = lexicon({**PINNED, "r_large": percepts("cv_large")}, {**PINNED_AT, "large": {"modifier"}})
    assert lex.position_channels(lex.effective_meanings()) == {"modifier": {"colour", "size"},
                                                                "head": {"shape"}}


def test_one_word_against_a_positions_main_channel_does_not_add_a_channel() -> None:
    # "capsule" taught on a capsule the eyes read as a small sphere: pinned to `cv_small`
    # (sphere claims the shape), one head noun against three that name shapes
    heads = {"r_box": percepts("cv_box"), "r_cone": percepts("cv_cone"), "r_sphere": percepts("cv_sphere"),
             "r_capsule": percepts("cv_small")}
    at = {w: {"head"} for w in ("box", "cone", "sphere", "capsule")}
    lex = lexicon(heads, at)
    assert lex.position_channels(heads) == {"head": {"shape"}}
    # ... and "cone", shown once large, is not narrowed to its size too
    cone = lexicon({**heads, "r_cone": percepts("cv_cone", "cv_large")}, at)
    assert cone.effective_meanings()["r_cone"] == percepts("cv_cone")


def test_a_second_word_of_a_channel_makes_it_a_positions_second_channel() -> None:
    mods = {"r_red": percepts("cv_red"), "r_blue": percepts("cv_blue"), "r_green": percepts("cv_green"),
            "r_large": percepts("cv_large")}
    at = {w: {"modifier"} for w in ("red", "blue", "green", "large", "small")}
    assert lexicon(mods, at).position_channels(mods) == {"modifier": {"colour"}}
    both = {**mods, "r_small": percepts("cv_small")}
    assert lexicon(both, at).position_channels(both) == {"modifier": {"colour", "size"}}


def test_a_word_left_only_what_a_pinned_word_means_takes_its_positions_weak_channel() -> None:
    # modifiers: three colour words pinned, one size word ("medium"): sizes are weak there.
    # "small", first shown on a red cylinder, is not narrowed to what "red" means.
    # ("cylinder", shown only small so far, holds the rest of its percepts: exclusivity
    # alone cannot take any of them from "small")
    mods = {"r_red": percepts("cv_red"), "r_blue": percepts("cv_blue"), "r_green": percepts("cv_green"),
            "r_medium": percepts("cv_medium"), "r_cylinder": percepts("cv_cylinder", "cv_small"),
            "r_small": percepts("cv_small", "cv_red", "cv_cylinder")}
    lex = lexicon(mods, {**{w: {"modifier"} for w in ("red", "blue", "green", "medium", "small")},
                         "cylinder": {"head"}})
    assert lex.effective_meanings()["r_small"] == percepts("cv_small")


def test_a_word_of_a_channel_its_position_does_not_name_keeps_its_meaning() -> None:
    mods = {"r_red": percepts("cv_red"), "r_blue": percepts("cv_blue"), "r_large": percepts("cv_large")}
    lex = lexicon(mods, {w: {"modifier"} for w in ("red", "blue", "large")})
    assert lex.effective_meanings()["r_large"] == percepts("cv_large")


def test_a_word_of_several_percepts_is_no_evidence() -> None:
    lex = lexicon({"r_red": percepts("cv_red", "cv_box")}, {"red": {"modifier"}})
    assert lex.position_channels({"r_red": percepts("cv_red", "cv_box")}) == {}


def test_a_concept_without_a_word_or_a_sense_is_no_evidence() -> None:
    lex = lexicon({"x_red": percepts("cv_red"), "r_odd": percepts("not_a_percept")},
                  {"red": {"modifier"}, "odd": {"head"}})
    assert lex.position_channels({"x_red": percepts("cv_red"), "r_odd": percepts("not_a_percept")}) == {}


def test_a_position_that_names_every_channel_tells_nothing() -> None:
    meanings = {"r_red": percepts("cv_red"), "r_box": percepts("cv_box"), "r_large": percepts("cv_large"),
                "r_cone": percepts("cv_cone")}
    lex = lexicon(meanings, {"red": {"modifier"}, "box": {"modifier"}, "large": {"modifier"}, "cone": {"head"}})
    assert lex.position_channels(meanings) == {"head": {"shape"}}


# ---------------------------------------------------------------- learning positions
def test_note_positions_takes_the_last_word_as_head_and_the_others_as_modifiers() -> None:
    lex = lexicon({})
    assert lex.note_positions(parse_of(phrase("large", "red", "box")))
    assert lex.positions == {"large": {"modifier"}, "red": {"modifier"}, "box": {"head"}}
    assert lex.distance == {"large": [2, 1], "red": [1, 1], "box": [0, 1]}


def test_note_positions_learns_nothing_from_one_word_phrases() -> None:
    lex = lexicon({})
    assert not lex.note_positions(parse_of(phrase("box")))
    assert lex.positions == {} and lex.distance == {}


def test_note_positions_sums_distances_and_says_whether_a_position_is_new() -> None:
    lex = lexicon({})
    assert lex.note_positions(parse_of(phrase("red", "box"), phrase("large", "red", "cone", ref="x2")))
    assert lex.distance["red"] == [2, 2] and lex.distance["large"] == [2, 1]
    assert not lex.note_positions(parse_of(phrase("red", "box")))  # nothing new
    assert lex.distance["red"] == [3, 3]
    assert lex.note_positions(parse_of(phrase("box", "red")))  # red as a head, box as a modifier
    assert lex.positions["red"] == {"modifier", "head"} and lex.positions["box"] == {"head", "modifier"}


def test_a_new_position_forgets_the_derived_meanings() -> None:
    lex = lexicon({**PINNED, "r_cone": percepts("cv_cone", "cv_green")}, PINNED_AT)
    assert lex.effective_meanings()["r_cone"] == percepts("cv_cone", "cv_green")
    lex.note_positions(parse_of(phrase("green", "cone")))
    assert lex.effective_meanings()["r_cone"] == percepts("cv_cone")


def test_a_known_position_keeps_the_derived_meanings() -> None:
    lex = lexicon({**PINNED}, PINNED_AT)
    first = lex.effective_meanings()
    lex.note_positions(parse_of(phrase("red", "box")))
    assert lex.effective_meanings() is first


# ---------------------------------------------------------------- word order
def test_noun_phrase_order_puts_words_further_from_the_head_first() -> None:
    lex = lexicon({})
    lex.note_positions(parse_of(phrase("large", "red", "box")))
    assert lex.noun_phrase_order(["box", "red", "large"]) == ["large", "red", "box"]


def test_noun_phrase_order_uses_the_mean_distance() -> None:
    lex = lexicon({})
    lex.distance = {"a": [3, 3], "b": [4, 2]}  # a: 1.0 on average, b: 2.0
    assert lex.noun_phrase_order(["a", "b"]) == ["b", "a"]


def test_noun_phrase_order_puts_an_unplaced_modifier_before_an_unplaced_head() -> None:
    # Words with no distance yet: a modifier stands one before the head; a head, or a word
    # never seen in a phrase, at the head; ties by the word itself.
    lex = lexicon({}, {"big": {"modifier"}, "ball": {"head"}, "cube": {"head", "modifier"}})
    assert lex.noun_phrase_order(["zed", "cube", "ball", "big"]) == ["big", "ball", "cube", "zed"]


def test_noun_phrase_order_breaks_ties_by_the_word() -> None:
    lex = lexicon({})
    lex.distance = {"b": [1, 1], "a": [1, 1]}
    assert lex.noun_phrase_order(["b", "a"]) == ["a", "b"]


# ---------------------------------------------------------------- saved with the memory
def test_the_annotation_round_trips_positions_and_distances() -> None:
    lex = lexicon({})
    lex.note_positions(parse_of(phrase("large", "red", "box"), phrase("box", "red", ref="x2")))
    saved = lex.to_annotation()
    assert saved == {"positions": {"box": ["head", "modifier"], "large": ["modifier"],
                                   "red": ["head", "modifier"]},
                     "distance": {"box": [1, 2], "large": [2, 1], "red": [1, 2]},
                     "seen": {"objects": 0, "percepts": {}}}
    lex.note_seen([("cv_red", "cv_box"), ("cv_red", "cv_cone")])
    again = lexicon({})
    again.load_annotation(lex.to_annotation())
    assert again.positions == lex.positions and again.distance == lex.distance
    assert again.seen.objects == 2 and again.seen.counts == {Term("cv_red"): 2, Term("cv_box"): 1, Term("cv_cone"): 1}


def test_a_malformed_annotation_loads_what_is_well_formed_and_nothing_else() -> None:
    lex = lexicon({})
    lex.load_annotation({"positions": {"red": ["modifier", "nowhere"], "box": "head"},
                         "distance": {"red": [1, 1], "box": [1], "cone": [-1, 1], "big": [1.5, 1],
                                      "ball": "far"}})
    assert lex.positions == {"red": {"modifier"}}
    assert lex.distance == {"red": [1, 1]}


def test_an_annotation_that_is_not_a_mapping_loads_nothing() -> None:
    for bad in (None, [], "x", {"positions": ["red"], "distance": {"red": [1, 1]}}):
        lex = lexicon({})
        lex.load_annotation(bad)
        assert lex.positions == {} and lex.distance == {}
    lex = lexicon({})
    lex.load_annotation({"positions": {"red": ["head"]}, "distance": "far"})
    assert lex.positions == {"red": {"head"}} and lex.distance == {}


def test_positions_are_the_two_of_a_noun_phrase() -> None:
    assert POSITIONS == ("head", "modifier")


# ---------------------------------------------------------------- exclusivity
_percept = st.sampled_from(["cv_red", "cv_blue", "cv_box", "cv_cone", "cv_large"])


@settings(max_examples=60, deadline=None)
@given(st.lists(st.frozensets(_percept, min_size=1, max_size=4), max_size=8))
def test_exclusivity_never_empties_a_meaning_nor_adds_to_it(ms: list[frozenset[str]]) -> None:
    meanings = {f"r_w{i}": frozenset(Term(p) for p in s) for i, s in enumerate(ms)}
    out = exclusive(meanings)
    assert list(out) == list(meanings)
    assert all(out[c] and out[c] <= meanings[c] for c in meanings)


def test_bootstrapping_is_on_unless_turned_off() -> None:
    meanings = {**PINNED, "r_cone": percepts("cv_cone", "cv_green")}
    lex = Lexicon(lambda c: meanings[c], lambda c: c[2:], lambda: list(meanings))
    lex.positions.update({**PINNED_AT, "cone": {"head"}})
    assert lex.effective_meanings()["r_cone"] == percepts("cv_cone")


def test_note_positions_says_false_when_nothing_is_new() -> None:
    lex = lexicon({})
    assert lex.note_positions(parse_of(phrase("red", "box"))) is True
    assert lex.note_positions(parse_of(phrase("red", "box"))) is False
    assert lex.note_positions(parse_of(phrase("cone"))) is False


def test_a_one_word_phrase_does_not_stop_learning_from_the_phrases_after_it() -> None:
    lex = lexicon({})
    assert lex.note_positions(parse_of(phrase("cone"), phrase("red", "box", ref="x2")))
    assert lex.positions == {"red": {"modifier"}, "box": {"head"}}


def test_noun_phrase_order_puts_a_word_placed_further_out_before_an_unplaced_modifier() -> None:
    lex = lexicon({}, {"big": {"modifier"}})
    lex.distance = {"very": [3, 2]}  # 1.5 words before the head on average
    assert lex.noun_phrase_order(["big", "very"]) == ["very", "big"]


def test_words_that_are_no_evidence_do_not_hide_the_evidence_after_them() -> None:
    meanings = {"r_two": percepts("cv_red", "cv_box"), "x_red": percepts("cv_red"),
                "r_odd": percepts("not_a_percept"), "r_green": percepts("cv_green"), "r_cone": percepts("cv_cone")}
    lex = lexicon(meanings, {"two": {"modifier"}, "odd": {"modifier"}, "green": {"modifier"}, "cone": {"head"}})
    assert lex.position_channels(meanings) == {"modifier": {"colour"}, "head": {"shape"}}


def test_an_annotation_with_distances_only_loads_them() -> None:
    lex = lexicon({})
    lex.load_annotation({"distance": {"box": [0, 1], "red": [1, 1]}})
    assert lex.distance == {"box": [0, 1], "red": [1, 1]} and lex.positions == {}


# ---------------------------------------------------------------- percepts every object has
GROX = {"r_green": percepts("cv_green"), "r_box": percepts("cv_box"), "r_red": percepts("cv_red"),
        "r_cone": percepts("cv_cone"), "r_grox": percepts("cv_green", "cv_box", "cv_medium")}


def test_uninformative_percepts_are_the_only_value_of_their_channel_any_meaning_holds() -> None:
    assert lexicon(GROX).uninformative() == percepts("cv_medium")
    assert lexicon({**GROX, "r_big": percepts("cv_large")}).uninformative() == frozenset()


def test_exclusivity_never_leaves_a_meaning_of_uninformative_percepts_alone() -> None:
    # Giving green and box up would leave grox "medium-sized", which every object seen is.
    for bootstrapping in (False, True):
        lex = lexicon(GROX, bootstrapping=bootstrapping)
        assert lex.effective_meanings()["r_grox"] == percepts("cv_green", "cv_box", "cv_medium"), bootstrapping
