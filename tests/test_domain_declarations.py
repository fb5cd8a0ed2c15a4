"""A declaration of one's own domain that cannot work is refused when it is made, in one line
naming it, whichever module was loaded first (aileen/domain: actions, relations, calculi,
channels, extensions)."""

from __future__ import annotations

import math
import os
from pathlib import Path

import pytest

from aileen.curriculum import legacy, lessonfile  # noqa: F401 - the lesson readers reserve their keys
from aileen.domain import actions, calculi, channels, extensions, relations
from aileen.errors import UserError


def _pull(world, obj, position, onto):  # noqa: ANN001, ANN202 - a world call, never made here
    return None


PULLED = actions.Fluent("pulled", 1, actions.DEED)
PULL = actions.PrimitiveAction("pull", ("pull",), actions.TOUCH, None, _pull, "pull N",
                               adds=("moved", "pulled"), dels=(actions.REL,), model=Path("pull.lp"))


def _verb(name: str, *spellings: str) -> actions.Verb:
    return actions.Verb(name, ("pull",), actions.slid(0.0, -1.0), spellings=spellings)


@pytest.mark.parametrize(("items", "says"), [
    ((PULLED, PULL, _verb("push")), "verb 'push' is already declared"),
    ((PULLED, PULL, _verb("pull", "push")), "'push' already says the verb 'push'"),
    ((PULLED, PULL, _verb("pull", "move")), "'move' already says the verb 'move'"),
    ((PULLED, PULL, _verb("pull", "the")), "'the' is a word of the grammar"),
    ((PULLED, PULL, _verb("pull", "left")), "'left' is a word of the grammar"),
    ((PULLED, PULL, _verb("pull", "red")), "'red' already says a colour"),
    ((PULLED, PULL, _verb("pull", "distant")), "'distant' already says the relation 'far from'"),
    ((PULLED, PULL, _verb("Pull")), "verb 'Pull': expected a name of lowercase letters"),
    ((PULLED, PULL, _verb("pull it")), "verb 'pull it': expected a name"),
    ((PULLED, PULL, _verb("pull", "tug"), _verb("yank", "tug")), "'tug' already says the verb 'pull'"),
    ((actions.Fluent("held", 1, actions.DEED),), "fluent 'held' is already declared"),
    ((actions.Fluent("Pulled", 1, actions.DEED),), "fluent 'Pulled': expected a name"),
    ((PULLED, actions.PrimitiveAction("place", ("place",), actions.TOUCH, None, _pull, "place N", adds=("pulled",))),
     "action 'place' is already declared; expected an action of one's own"),
    ((PULLED, actions.PrimitiveAction("pull", ("pull", "pick up"), actions.TOUCH, None, _pull, "pull N")),
     "spelling 'pick up' already spells the action 'pick_up'"),
])
def test_an_action_or_verb_that_would_replace_or_shadow_a_word_is_refused(items: tuple, says: str) -> None:
    before = dict(actions.FLUENTS), dict(actions.ACTIONS), dict(actions.VERBS)
    with pytest.raises(UserError, match=says):
        actions.declare(*items)
    assert (actions.FLUENTS, actions.ACTIONS, actions.VERBS) == before  # nothing of a refused call stays


def test_the_same_declaration_made_again_is_no_change() -> None:
    with actions.declared(PULLED, PULL, _verb("pull", "tug")):
        actions.declare(PULLED, PULL)
        assert actions.find_verb("tug").name == "pull"
    assert math.isfinite(actions.version())


# ------------------------------------------------------------------ relations


@pytest.mark.parametrize(("rel", "says"), [
    (lambda: relations.directional("left of", 0.0), "'left of' already says the relation 'left of'"),
    (lambda: relations.directional("east of", 0.0, aliases=("left of",)), "'left of' already says the relation"),
    (lambda: relations.directional("east of", 0.0, aliases=("to the left of",)), "already says the relation 'left of'"),
    (lambda: relations.directional("cube", 0.0), "'cube' already says a shape"),
])
def test_a_relation_that_would_take_a_declared_word_is_refused(rel, says: str) -> None:  # noqa: ANN001
    with relations.kept():
        with pytest.raises(UserError, match=says):
            relations.declare(rel())
        assert relations.direction("left of").axis == 180.0


def test_a_relation_and_a_verb_of_one_name_are_refused_in_either_order() -> None:
    with relations.kept(), actions.declared(PULLED, PULL, _verb("pull")):
        with pytest.raises(UserError, match="'pull' already says the verb 'pull'"):
            relations.declare(relations.directional("pull", 0.0))
    with relations.kept():
        relations.declare(relations.directional("tug", 0.0))
        with pytest.raises(UserError, match="'tug' already says the relation 'tug'"):
            actions.declare(PULLED, PULL, _verb("tug"))


# ------------------------------------------------------------------ channels


def _measure(image, detection, camera):  # noqa: ANN001, ANN202 - never called here
    return "plain", 0.0


def _texture(*values: str, name: str = "texture", **kw) -> channels.Channel:  # noqa: ANN003
    return channels.Channel(name, values, _measure, default=values[0] if values else None, **kw)


@pytest.mark.parametrize(("decl", "says"), [
    (lambda: _texture("plain", "striped", name="position"), "'position' is a key a TOML lesson file gives"),
    (lambda: _texture("plain", "striped", name="signal"), "'signal' is a key a TOML lesson file gives"),
    (lambda: _texture("plain", "striped", name="content"), "'content' is a key a TOML lesson file gives"),
    (lambda: _texture("plain", "striped", name="color"), "channel 'color' is already declared"),
    (lambda: _texture("plain", "cube"), "'cube' already says a shape"),
    (lambda: _texture("plain", "object"), "'object' already says an object of any shape"),
    (lambda: _texture("plain", "distant"), "'distant' already says the relation 'far from'"),
    (lambda: _texture("plain", "striped", spellings=(("red", "striped"),)), "'red' already says a colour"),
    (lambda: _texture("plain", "striped", spellings=(("cube", "striped"),)), "'cube' already says a shape"),
    (lambda: _texture("plain", "striped", spellings=(("stripy", "zebra"),)), "expected \\(word, value\\)"),
    (lambda: _texture("plain", "Striped"), "'Striped' must be lowercase"),
    (lambda: channels.Shape("Ring", footprint="disc", render=lambda n, c: None), "'Ring': expected lowercase"),
    (lambda: channels.Shape("distant", footprint="disc", render=lambda n, c: None), "already says the relation"),
    (lambda: "texture", "expected a channels.Channel or a catalog.Shape"),
])
def test_a_channel_that_would_take_a_word_or_key_is_refused(decl, says: str) -> None:  # noqa: ANN001
    before = channels.names(), channels.SHAPE.values
    with pytest.raises(UserError, match=says):
        with channels.scope(decl()):
            pass
    assert (channels.names(), channels.SHAPE.values) == before


def test_a_channel_named_as_a_lesson_key_is_refused_when_the_reader_comes_after_it() -> None:
    with channels.scope(_texture("plain", "striped", name="weave")):
        with pytest.raises(UserError, match="channel 'weave': 'weave' is a key the original JSON"):
            channels.reserve_keys("the original JSON lesson format", ("weave",))


def test_a_relation_and_a_channel_value_of_one_word_are_refused_in_either_order() -> None:
    with relations.kept():
        relations.declare(relations.directional("striped", 0.0))
        with pytest.raises(UserError, match="'striped' already says the relation 'striped'"):
            with channels.scope(_texture("plain", "striped")):
                pass
    with channels.scope(_texture("plain", "striped")), relations.kept():
        with pytest.raises(UserError, match="relation 'striped': it is what an object looks like"):
            relations.declare(relations.directional("striped", 0.0))


def test_a_word_of_a_relation_phrase_and_a_channel_value_are_refused_in_either_order() -> None:
    with relations.kept():
        relations.declare(relations.directional("abreast of", 0.0))
        with pytest.raises(UserError, match="'abreast' already says a word of the relation 'abreast of'"):
            with channels.scope(_texture("plain", "abreast")):
                pass
    with channels.scope(_texture("plain", "abreast")), relations.kept():
        with pytest.raises(UserError, match=r"'abreast of' already says a texture \('abreast'\) "
                                            r"\(its word 'abreast'\)"):
            relations.declare(relations.directional("abreast of", 0.0))


def test_a_channel_value_and_a_verb_of_one_word_are_refused_in_either_order() -> None:
    with actions.declared(PULLED, PULL, _verb("pull", "tug")):
        with pytest.raises(UserError, match="'tug' already says the verb 'pull'"):
            with channels.scope(_texture("plain", "tug")):
                pass
    with channels.scope(_texture("plain", "tug")):
        with pytest.raises(UserError, match="'tug' already says a texture"):
            actions.declare(PULLED, PULL, _verb("pull", "tug"))


# ------------------------------------------------------------------ calculi


def _none(a, b):  # noqa: ANN001, ANN202
    return None


def _calculus(*rels: str, name: str = "align", compute=_none, converse=None) -> calculi.Calculus:  # noqa: ANN001
    return calculi.Calculus(name, rels, {r: r for r in rels} if converse is None else converse, compute)


@pytest.fixture
def own_calculi(monkeypatch: pytest.MonkeyPatch) -> None:
    """A calculus declared in the test is gone after it (`calculi.declare` is for good)."""
    monkeypatch.setattr(calculi, "CALCULI", calculi.CALCULI)


@pytest.mark.parametrize(("calc", "says"), [
    (lambda: _calculus("al_row", name="My Calc"), "calculus 'My Calc': expected a name of lowercase"),
    (lambda: _calculus("al_row", compute=None), "compute None: expected a function"),
    (lambda: _calculus(), "expected one relation at least"),
    (lambda: _calculus("al_row", "al_row"), "expected one relation at least, each once"),
    (lambda: _calculus("al_row", converse={"al_row": "al_zzz"}), "its converse names 'al_zzz'"),
    (lambda: _calculus("holds"), "relation 'holds' is a predicate"),
    (lambda: _calculus("occurs"), "relation 'occurs' is a predicate"),
    (lambda: _calculus("moved"), "relation 'moved' is a predicate"),
    (lambda: _calculus("held"), "relation 'held' is a predicate"),
    (lambda: _calculus("isa"), "relation 'isa' is a predicate"),
    (lambda: _calculus("cv_red"), "relation 'cv_red' is a predicate"),
    (lambda: _calculus("r_left_of"), "relation 'r_left_of' is a predicate"),
])
def test_a_calculus_that_cannot_work_is_refused_when_declared(own_calculi, calc, says: str) -> None:  # noqa: ANN001
    before = calculi.CALCULI
    with pytest.raises(UserError, match=says):
        calculi.declare(calc())
    assert calculi.CALCULI == before


class _Body:
    box_m = (0.0, 0.0, 0.1, 0.1)
    footprint = 0.1
    level = 0


def test_a_calculus_that_computes_what_it_did_not_declare_is_named_when_it_does(own_calculi) -> None:  # noqa: ANN001
    calculi.declare(_calculus("al_row", compute=lambda a, b: "Zzz"))
    with pytest.raises(UserError, match=r"calculus 'align': its compute .*test_domain_declarations.py:\d+ "
                                        r".*returned 'Zzz'; expected one of al_row or None"):
        calculi.pair_relations(_Body(), _Body(), (calculi.calculus_by_name("align"),))


def test_an_error_inside_a_calculus_of_ones_own_is_one_line_naming_its_function(own_calculi) -> None:  # noqa: ANN001
    def broken(a, b):  # noqa: ANN001, ANN202
        return {}["x"]

    calculi.declare(_calculus("al_row", compute=broken))
    with pytest.raises(UserError, match=r"calculus 'align': its compute .*:\d+ .*broken failed: KeyError: 'x'"):
        calculi.pair_relations(_Body(), _Body(), (calculi.calculus_by_name("align"),))


# ------------------------------------------------------------------ extensions


def test_a_file_named_by_two_paths_is_imported_once(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    (tmp_path / "own.py").write_text("from pathlib import Path\n"
                                     "with open(Path(__file__).with_name('imported.txt'), 'a') as f:\n"
                                     "    f.write('once\\n')\n")
    monkeypatch.chdir(tmp_path)
    loaded = extensions.load(os.pathsep.join(("./own.py", "own.py", str(tmp_path / "own.py"))))
    assert loaded == ["./own.py"]
    assert extensions.load("own.py") == []
    assert (tmp_path / "imported.txt").read_text() == "once\n"


# ------------------------------------------------------------------ a user's own function


def test_a_measure_path_that_names_no_module_is_refused_when_declared() -> None:
    with pytest.raises(UserError, match="its measure 'nosuch.module:fn': expected 'module:function' of a module"):
        with channels.scope(channels.Channel("texture", ("plain", "striped"), "nosuch.module:fn")):
            pass


def test_an_error_inside_a_measure_of_ones_own_is_one_line_naming_it() -> None:
    def measure(image, detection, camera):  # noqa: ANN001, ANN202
        raise RuntimeError("no camera here\nsecond line")

    with channels.scope(channels.Channel("texture", ("plain", "striped"), measure)):
        with pytest.raises(UserError, match=r"channel 'texture': its measure .*:\d+ .*measure failed: "
                                            r"RuntimeError: no camera here$"):
            channels.get("texture").measure(None, None, None)
    with channels.scope(channels.Channel("texture", ("plain", "striped"), "json:nosuch")):
        with pytest.raises(UserError, match="its measure 'json:nosuch': expected 'module:function' naming a"):
            channels.get("texture").measure(None, None, None)


def test_an_error_inside_a_relation_of_ones_own_is_one_line_naming_it() -> None:
    def accepts(a, b):  # noqa: ANN001, ANN202
        return a.nosuch > b.nosuch

    with relations.kept():
        relations.declare(relations.TrainerRelation("level with", "level with", accepts, accepts))
        with pytest.raises(UserError, match=r"relation 'level with': its accepts .*accepts failed: AttributeError"):
            relations.holds("level with", object(), object())
    assert relations.holds("left of", _At(0.0), _At(0.5)) is True  # aileen's own, as it was


class _At:
    def __init__(self, x: float) -> None:
        self.x, self.y, self.footprint, self.level = x, 0.5, 0.05, 0

    def box_m(self) -> tuple[float, float, float, float]:
        return self.x - 0.025, self.y - 0.025, self.x + 0.025, self.y + 0.025


def test_an_error_inside_an_action_or_verb_of_ones_own_is_one_line_naming_it() -> None:
    """A world call, goal or room test of one's own raising was a traceback (exit 1)."""
    def world(w, obj, position, onto):  # noqa: ANN001, ANN202
        return w.nosuch(obj)

    def goal(out):  # noqa: ANN001, ANN202
        return out.nosuch

    def room(x, y, half, table, margin):  # noqa: ANN001, ANN202
        raise ValueError("no table")

    pull = actions.PrimitiveAction("pull", ("pull",), actions.TOUCH, None, world, "pull N", adds=("moved", "pulled"))
    with actions.declared(PULLED, pull, actions.Verb("pull", ("pull",), goal, room)):
        with pytest.raises(UserError, match=r"action 'pull': its world call .*test_domain_declarations.py:\d+ "
                                            r".*world failed: AttributeError"):
            actions.action("pull").world(object(), "o1", None, None)
        with pytest.raises(UserError, match=r"verb 'pull': its goal .*goal failed: AttributeError"):
            actions.verb("pull").goal(object())
        with pytest.raises(UserError, match=r"verb 'pull': its room .*room failed: ValueError: no table"):
            actions.verb("pull").room(0.0, 0.0, 0.1, None, 0.0)
        actions.declare(PULLED, pull)  # the same declaration again is no change
    assert actions.action("push").world.__module__ == "aileen.domain.actions"  # aileen's own, as it was


def test_an_error_inside_a_render_of_ones_own_is_one_line_naming_it() -> None:
    def shine(value, canvas):  # noqa: ANN001, ANN202
        return canvas.nosuch

    with channels.scope(channels.Channel("texture", ("plain", "striped"), "json:loads", render=shine)):
        from aileen.world import appearance

        with pytest.raises(UserError, match=r"channel 'texture': its render .*shine failed: AttributeError"):
            appearance.LOOKS["texture"].render("plain", object())


@pytest.mark.parametrize("returned", [None, (0.1,), (0.1, "x"), (float("nan"), 0.0)])
def test_a_relations_offset_that_returns_no_pair_is_named_when_it_does(returned: object) -> None:
    """An offset returning None was "cannot unpack non-iterable NoneType" deep in the trainer."""
    def offset(rng, fa, fb):  # noqa: ANN001, ANN202
        return returned

    with relations.kept():
        relations.declare(relations.TrainerRelation("level with", "level with", bool, bool, offset, offset))
        with pytest.raises(UserError, match=r"relation 'level with': its offset .*offset failed: it returned .*; "
                                            r"expected \(dx, dy\): two finite numbers"):
            relations.get("level with").offset(None, 0.1, 0.1)


def test_a_relative_model_path_is_read_from_the_declaring_modules_folder(tmp_path: Path,
                                                                         monkeypatch: pytest.MonkeyPatch) -> None:
    """`model=Path("nudge.lp")`, as the recipe writes it, was looked for in the current
    directory: the module worked only when run from its own folder."""
    from aileen.reasoning import planner

    monkeypatch.chdir(tmp_path)
    with actions.declared(PULLED, PULL):
        assert actions.action("pull").model == Path(__file__).resolve().parent / "pull.lp"
        with pytest.raises(UserError, match=r"pull.lp: the model of the declared action pull is not a file; "
                                            r"expected it in .*tests \(a relative model path is read from the folder"):
            planner.model_paths()


@pytest.mark.parametrize(("word", "says"), [
    ("aligned  with", r"its word 'aligned  with': expected lowercase words .* separated by single spaces"),
    ("Aligned with", r"its word 'Aligned with': expected lowercase words"),
    ("lined up with", r"its word 'lined up with' is no declared relation's name"),
])
def test_a_relation_word_that_can_never_be_said_is_refused(word: str, says: str) -> None:
    """A word "aligned  with" (two spaces) was accepted, and the relation could never be said."""
    with relations.kept():
        with pytest.raises(UserError, match=says):
            relations.declare(relations.TrainerRelation("aligned with", word, bool, bool))
        relations.declare(relations.TrainerRelation("aligned with", "aligned with", bool, bool))
        assert relations.spellings()["aligned with"] == "aligned with"


@pytest.mark.parametrize(("name", "aliases"), [
    ("aligned-with", ()), ("aligned_with", ()), ("aligned with", ("aligned-with",)),
    ("aligned with", ("aligned_with",)), ("aligned with", ("lined  up with",)),
])
def test_a_relations_name_and_spellings_follow_one_rule(name: str, aliases: tuple[str, ...]) -> None:
    """The name "aligned-with" was refused with 'left-of' given as an example of what is
    allowed, and an alias "aligned-with" was accepted: names and spellings take one rule."""
    with relations.kept():
        with pytest.raises(UserError) as refused:
            relations.declare(relations.TrainerRelation(name, name, bool, bool, aliases=aliases))
    said = refused.value.message
    assert "separated by single spaces, with no hyphen or underscore (e.g. 'short way from')" in said
    assert "left-of" not in said
