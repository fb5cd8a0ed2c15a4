"""Actions say what they mean (issue 21): each primitive action declares its kind, the fluents
its model changes (held to `asp/actions.lp` by `reasoning/models.py`) and the marks the agent
perceives; each verb its goal test, the room it needs and its spellings. A new verb with a new
primitive action ("pull") is its declaration plus its `.lp` model, both inside the test only,
and is taught end to end (the recipe in docs/architecture.md)."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import pytest

from aileen.agent import Agent
from aileen.curriculum import demonstration, grading, trainer
from aileen.curriculum.formats import load_curriculum
from aileen.curriculum.interpreter import Interpreter
from aileen.curriculum.lesson import ActionSpec, Lesson, ObjectSpec, Step, auto_demonstration
from aileen.curriculum.sentences import action_from_content, read_content
from aileen.domain import actions
from aileen.errors import UserError
from aileen.experiments import exams
from aileen.perception.truth import TruthVision
from aileen.reasoning import asp, language, models, planner
from aileen.terms import parse_many
from aileen.world.camera import DEFAULT_CAMERA, Table
from aileen.world.sim import World

LESSONS = Path(__file__).resolve().parent.parent / "lessons"

# ------------------------------------------------------------------ the test's own verb: pull

PULL_MODEL = """\
% pull(O): the hand draws O toward the trainer (south) by about its own width.
#program base.
action(pull(O)) :- obj(O).
moves(pull(O),O) :- action(pull(O)).

#program step(t).
poss(pull(O),t) :- action(pull(O)), not busy(t-1), not holds(held(O),t-1), not stacked(O,t-1).
add(moved(O),t) :- occurs(pull(O),t).
add(pulled(O),t) :- occurs(pull(O),t).
del(rel(P,O,X),t) :- occurs(pull(O),t), holds(rel(P,O,X),t-1), not static(P).
del(rel(P,X,O),t) :- occurs(pull(O),t), holds(rel(P,X,O),t-1), not static(P).
"""


def _pull(world: World, obj: str, position: tuple[float, float] | None, onto: str | None):
    """The world call: a shove south fast enough to slide about one footprint on the table."""
    side = world.get(obj).footprint
    world.push(obj, 0.0, -math.sqrt(2.0 * world.physics.mu_table * world.physics.g * side))
    return world.settle()


def pull_declarations(model: Path) -> tuple:
    return (
        actions.Fluent("pulled", 1, actions.DEED, "the hand has just pulled O"),
        actions.PrimitiveAction("pull", ("pull", "draw"), actions.TOUCH, None, _pull, "pull N",
                                adds=("moved", "pulled"), dels=(actions.REL,), model=model),
        actions.Verb("pull", ("pull",), actions.slid(0.0, -1.0), actions.room_ahead(0.0, -1.0), spellings=("tug",)),
    )


@pytest.fixture
def pull(tmp_path: Path):
    model = tmp_path / "pull.lp"
    model.write_text(PULL_MODEL)
    with actions.declared(*pull_declarations(model)):
        yield model
    assert "pull" not in actions.ACTIONS and "pull" not in actions.VERBS  # declared in the test only


def _objects(*names: str) -> list[ObjectSpec]:
    return [ObjectSpec(*reversed(n.split())) for n in names]


def _action_lesson(signal: str, content: str, objects: list[str], verb: str, *, steps: list[Step] | None = None,
                   distractors: int = 0, expect: str | None = None) -> Lesson:
    spec = ActionSpec(verb)
    demo = None if signal == "react" else (steps if steps is not None else auto_demonstration(spec))
    return Lesson(signal, content, _objects(*objects), action=spec, demonstration=demo, distractors=distractors,
                  expect=expect)


def _truth_interpreter() -> Interpreter:
    vision = TruthVision()
    return Interpreter(Agent(perceiver=vision), on_frame=vision.see_frame)


def _teach_words(interp: Interpreter, words: list[str], seed: int) -> None:
    for i, o in enumerate(words):
        interp.run(Lesson("inform", o, _objects(o)), index=1, seed=seed + i)


def test_pull_is_taught_end_to_end_through_its_declaration_and_model_alone(pull) -> None:
    interp = _truth_interpreter()
    _teach_words(interp, ["red box", "blue cone", "green cylinder"], 400)
    first = interp.run(_action_lesson("inform", "pull the red box", ["red box", "blue cone"], "pull"), index=1, seed=410)
    assert first.answer.created == ["r_pull"]
    interp.run(_action_lesson("inform", "pull the blue cone", ["blue cone", "green cylinder"], "pull"), index=1, seed=411)
    yes = interp.run(_action_lesson("verify", "pull the green cylinder", ["green cylinder"], "pull", distractors=2),
                     index=1, seed=412)
    assert yes.expected == "success" and yes.correct, yes.answer.reason
    other = interp.run(_action_lesson("verify", "pull the red box", ["red box", "blue cone"], "pull",
                                      steps=[Step("pull", 1)]), index=1, seed=413)
    assert other.expected == "failure" and other.correct, other.answer.reason
    pushed = interp.run(_action_lesson("verify", "pull the red box", ["red box", "blue cone"], "pull",
                                       steps=[Step("push", 0)], expect="failure"), index=1, seed=414)
    assert pushed.correct, pushed.answer.reason  # a push is not a pull: the marks differ
    for seed, content in ((415, "pull the blue cone"), (416, "tug the green cylinder")):
        done = interp.run(_action_lesson("react", content, ["blue cone", "red box"] if seed == 415
                                         else ["green cylinder"], "pull"), index=1, seed=seed)
        assert done.answer.steps == ["pull(o1)"], done.answer.reason
        assert done.goal_holds is True  # the verb's own goal test: slid toward the trainer


def test_the_shipped_push_curriculum_still_plans_push_when_pull_is_declared(pull) -> None:
    curriculum = load_curriculum(LESSONS / "push.toml")
    interp = _truth_interpreter()
    results = list(interp.run_all(curriculum, seed=curriculum.seed))
    reacts = [r for r in results if r.lesson.signal == "react"]
    assert reacts and all(r.answer.steps == ["push(o1)"] and r.goal_holds for r in reacts), \
        [(r.answer.steps, r.answer.reason) for r in reacts]
    assert all(r.correct for r in results if r.lesson.signal == "verify")


def test_the_planner_tells_push_from_pull_by_their_declared_marks(pull) -> None:
    state = parse_many("w(o1,o2). isa(o1,cv_box). isa(o2,cv_cone).")
    assert [str(s.action) for s in planner.plan(state, parse_many("moved(o1). pushed(o1).")).steps] == ["push(o1)"]
    assert [str(s.action) for s in planner.plan(state, parse_many("moved(o1). pulled(o1).")).steps] == ["pull(o1)"]


def test_without_its_declaration_pull_is_not_planned() -> None:
    state = parse_many("w(o1,o2). isa(o1,cv_box). isa(o2,cv_cone).")
    with pytest.raises(planner.NoPlan):
        planner.plan(state, parse_many("pulled(o1)."), max_depth=3)


def test_a_declared_verb_is_read_by_its_spellings() -> None:
    assert language.parse("lift red box").action is None  # undeclared: a three-word noun phrase
    lift = actions.Verb("lift", ("pick_up",), lambda out: out.objects[0].held, spellings=("raise",))
    with actions.declared(lift):
        for said in ("lift red box", "raise red box", "please lift the red box"):
            p = language.parse(said)
            assert p.action is not None and p.action.verb == "lift" and p.action.word == "lift", said
        assert read_content("raise the red box").verb == "lift"
        assert action_from_content("lift the red box") == ActionSpec("lift")
    assert language.parse("lift red box").action is None  # gone with its declaration


def test_every_declared_verb_and_spelling_parses() -> None:
    for word, name in actions.verb_words().items():
        p = language.parse(f"{word} red box" if not actions.VERBS[name].takes_relation
                           else f"{word} red box left of blue cone")
        assert p.action is not None and p.action.verb == name


# ------------------------------------------------------------------ the checked table


def test_the_shipped_models_are_exactly_the_declared_effects() -> None:
    effects, _uses = models.read_effects(planner.model_paths())
    for act in actions.ACTIONS.values():
        assert effects[act.name].modelled is not None
        assert set(effects[act.name].adds) == set(act.adds), act.name
        assert set(effects[act.name].dels) == set(act.dels), act.name


def _rules_with(tmp_path: Path, old: str, new: str) -> Path:
    text = asp.rule_path("actions.lp").read_text()
    assert old in text
    (tmp_path / "actions.lp").write_text(text.replace(old, new))
    return tmp_path


def test_a_model_that_drops_a_declared_effect_is_refused_at_load(tmp_path: Path) -> None:
    rules = _rules_with(tmp_path, "add(pushed(O),t) :- occurs(push(O),t).\n", "")
    with pytest.raises(UserError, match=r"push adds pushed in aileen/domain/actions.py") as err:
        planner.plan(parse_many("isa(o1,cv_box)."), parse_many("moved(o1)."), rules=rules)
    assert err.value.path == str(tmp_path / "actions.lp") and err.value.line is not None


def test_a_model_with_an_undeclared_effect_is_refused_with_its_line(tmp_path: Path) -> None:
    rules = _rules_with(tmp_path, "add(pushed(O),t) :- occurs(push(O),t).",
                        "add(pushed(O),t) :- occurs(push(O),t).\nadd(shoved(O),t) :- occurs(push(O),t).")
    with pytest.raises(UserError, match="push adds shoved here") as err:
        planner.model_paths(rules)
    text = (tmp_path / "actions.lp").read_text().splitlines()
    assert text[err.value.line - 1].startswith("add(shoved(O),t)")


def test_asp_check_refuses_a_model_against_its_declaration_with_file_and_line(tmp_path: Path, capsys) -> None:
    from aileen.cli import main

    rules = _rules_with(tmp_path, "add(pushed(O),t) :- occurs(push(O),t).",
                        "add(pushed(O),t) :- occurs(push(O),t).\nadd(held(O),t) :- occurs(push(O),t).")
    line = (tmp_path / "actions.lp").read_text().splitlines().index("add(held(O),t) :- occurs(push(O),t).") + 1
    assert main(["asp", "check", "--rules", str(rules)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.endswith(f"actions.lp:{line}: push adds held here, but aileen/domain/actions.py declares it adds "
                        "only moved, pushed") and "\n" not in err


def test_a_fluent_with_the_wrong_arity_is_refused(tmp_path: Path) -> None:
    rules = _rules_with(tmp_path, "add(pushed(O),t) :- occurs(push(O),t).", "add(pushed(O,O),t) :- occurs(push(O),t).")
    with pytest.raises(UserError, match="pushed has 1 argument"):
        planner.model_paths(rules)


def test_a_declared_action_without_a_model_is_refused(tmp_path: Path) -> None:
    decl = pull_declarations(tmp_path / "pull.lp")
    with actions.declared(decl[0], actions.PrimitiveAction("pull", ("pull",), actions.TOUCH, None, _pull, "pull N",
                                                           adds=("moved", "pulled"), dels=(actions.REL,))):
        with pytest.raises(UserError, match="the declared action pull has no model"):
            planner.model_paths()


def test_a_declared_model_file_that_is_missing_is_named(tmp_path: Path) -> None:
    with actions.declared(*pull_declarations(tmp_path / "nope.lp")):
        with pytest.raises(UserError, match="the model of the declared action pull is not a file") as err:
            planner.model_paths()
    assert err.value.path == str(tmp_path / "nope.lp")


def test_an_action_only_a_rule_file_knows_is_planned_unchecked(tmp_path: Path) -> None:
    """docs/asp.md's `slide`: planning with a user's .lp alone still works (no declaration)."""
    text = asp.rule_path("actions.lp").read_text()
    (tmp_path / "actions.lp").write_text(text + "\n#program base.\naction(slide(O,R)) :- region(O,R), R != free.\n"
                                         "#program step(t).\nposs(slide(O,R),t) :- action(slide(O,R)), not busy(t-1).\n"
                                         "add(F,t) :- occurs(slide(O,R),t), region_fact(O,R,F).\n")
    p = planner.plan(parse_many("w(o1,o2). isa(o1,cv_box). isa(o2,cv_box)."), parse_many("e(o1,o2)."), rules=tmp_path)
    assert [s.name for s in p.steps] == ["slide"]


def test_declarations_name_only_declared_things() -> None:
    with pytest.raises(ValueError, match="undeclared fluents: lit"):
        actions.declare(actions.PrimitiveAction("light", ("light",), actions.TOUCH, None, _pull, "light N", adds=("lit",)))
    with pytest.raises(ValueError, match="steps must be declared actions"):
        actions.declare(actions.Verb("juggle", ("toss",), actions.in_relation))
    assert "light" not in actions.ACTIONS and "juggle" not in actions.VERBS


# ------------------------------------------------------------------ grading, the trainer, the body


def test_the_kind_decides_the_relation_and_the_region_step() -> None:
    assert actions.VERBS["move"].takes_relation and not actions.VERBS["push"].takes_relation
    assert [s.action for s in auto_demonstration(ActionSpec("move", "left of"))] == ["pick_up", "place"]
    assert {a.name for a in actions.ACTIONS.values() if a.kind == actions.REGION} == {"place"}
    assert actions.ACTIONS["push"].marks == ("pushed",) and actions.ACTIONS["place"].marks == ()


def test_a_verb_on_one_object_is_graded_by_its_own_goal_test(pull) -> None:
    """A pulled object is where a pull leaves it and not where a push does, and the trainer
    lays it out with room toward itself (south), as the declaration says."""
    lesson = _action_lesson("react", "pull the red box", ["red box"], "pull")
    for seed in range(5):
        setup = trainer.layout(lesson, seed=seed)
        obj = setup.world.get(setup.ids[0])
        assert obj.y - 5 * obj.footprint / 2 - 0.01 > 0.0  # room to pull
        assert not grading.goal_holds(lesson, setup.world, setup.ids, setup.start)
        demonstration.execute(setup.world, Step("pull", setup.ids[0]))
        assert grading.goal_holds(lesson, setup.world, setup.ids, setup.start)
        push = _action_lesson("react", "push the red box", ["red box"], "push")
        assert not grading.goal_holds(push, setup.world, setup.ids, setup.start)


def test_a_demonstration_of_another_action_is_graded_a_failure(pull) -> None:
    """Probe p51f: "push the red box" shown by pointing at it, or "pull" shown by a push, was
    expected "success" (the verb compared was read from the sentence itself), and the agent's
    right "the demonstration is not 'push'" was graded WRONG; an `expect = "failure"` written
    for it was left ungraded as a contradiction. The steps shown are judged by the verb's own
    declaration: a point is not a push, a push is not a pull."""
    cases = [("push the red box", "push", [Step("point", 0)], "failure"),
             ("pull the red box", "pull", [Step("push", 0)], "failure"),
             ("move the red box left of the blue cone", "move", [Step("point", 0)], "failure"),
             ("push the red box", "push", [Step("point", 1), Step("push", 0)], "success"),
             ("pull the red box", "pull", [Step("pull", 0)], "success")]
    for content, verb, steps, answer in cases:
        relation = read_content(content).relation
        lesson = dataclasses.replace(_action_lesson("verify", content, ["red box", "blue cone"], verb, steps=steps),
                                     action=ActionSpec(verb, relation))
        setup = trainer.layout(lesson, seed=3)
        assert grading.expected(lesson, setup) == answer, (content, steps)
        said = dataclasses.replace(lesson, expect="failure")
        assert (grading.contradiction(said, setup) is None) == (answer == "failure"), (content, steps)


def test_the_room_a_verb_needs_follows_its_heading() -> None:
    table = Table()
    north, south = actions.room_ahead(0.0, 1.0), actions.room_ahead(0.0, -1.0)
    assert north(0.5, 0.2, 0.05, table, 0.01) and not north(0.5, 0.8, 0.05, table, 0.01)
    assert south(0.5, 0.8, 0.05, table, 0.01) and not south(0.5, 0.2, 0.05, table, 0.01)


def test_exam_recording_watches_a_demonstration_as_a_lesson_does() -> None:
    """A recorded push exam shows the hand at the pushed object's pixel, as `Interpreter`
    does, and an agent taught "push" answers the replayed exam as it does live."""
    vision = TruthVision()
    replayer = exams.Replayer(vision)
    interp = Interpreter(Agent(perceiver=replayer), on_frame=vision.see_frame)
    _teach_words(interp, ["red box", "blue cone"], 500)
    for seed in (510, 511):
        interp.run(_action_lesson("inform", "push the red box", ["red box", "blue cone"], "push"), index=1, seed=seed)
    exam = _action_lesson("verify", "push the blue cone", ["blue cone", "red box"], "push")
    recorder = TruthVision()
    tape = exams.record(exam, 520, recorder, on_frame=recorder.see_frame)
    setup = trainer.layout(exam, seed=520)
    pushed = setup.world.get(setup.ids[0])
    assert tape.looks[1].step == ("push", *DEFAULT_CAMERA.to_pixels(pushed.x, pushed.y))
    live = interp.run(exam, index=1, seed=520)
    assert tape.replay(interp.agent, replayer).result == live.answer.result == "success"


def test_the_action_rules_header_lists_the_declared_fluents() -> None:
    # the header of asp/actions.lp repeats the fluent table for a reader of the rules; a
    # fluent declared without it (or gone from the declarations) left it stale, unnoticed
    import re
    from pathlib import Path

    text = (Path(__file__).resolve().parents[1] / "asp" / "actions.lp").read_text()
    block = text.split("% Fluents", 1)[1].split("% In (base facts)", 1)[0]
    listed = re.findall(r"^%\s{3}(\w+)\(", block, flags=re.M)
    assert sorted(listed) == sorted(actions.FLUENTS), listed
