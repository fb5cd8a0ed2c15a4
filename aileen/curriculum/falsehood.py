"""The trainer says something false about the scene: the original scripts' negative lessons.

An original lesson with `is_positive: "False"` and no `content` asked the trainer to make up a
false sentence about the scene it laid out (`Lesson.say_false`). The sentence needs the table,
so it is decided here, when the lesson is laid out, and the lesson the agent gets is an
ordinary one whose `content` is that sentence (graded `expect = "failure"` on verify):

* a visual lesson: the objects are laid out as described, and the trainer names a
  colour-shape pair that is not on the table; it prefers a pair recombined from colours and
  shapes that are there ("blue box" over a red box and a blue cone: the hardest exam for the
  words at hand), else any pair;
* a spatial lesson: the objects are laid out in another relation, one the trainer says with a
  different word (both objects on the table), and the trainer names the asked relation
  between them. Whether the asked
  relation really does not hold is checked on the settled table, as a person would judge it;
  otherwise the next relation (or layout) is tried. A lesson that no relation can be laid out
  for raises `LayoutError` with the trainer's reason (the run skips it and goes on);
* an action lesson (the original's generator writes them: `is_positive` false, no sentence):
  the objects are laid out and the action demonstrated as described, and the trainer says the
  verb with the opposite direction word ("move red box left of blue cone" for a move right
  of it), else with the two objects' roles swapped, and for a verb on one object ("push") it
  names a kind of object that is not on the table. The sentence must be false of its own
  demonstration as the trainer grades it (`grading.expected`), else the next one is tried.

Every choice is drawn from the lesson's seed: same lesson, same seed, same sentence.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from aileen.curriculum import grading, trainer
from aileen.curriculum.lesson import Lesson
from aileen.curriculum.stage import LayoutError, Setup
from aileen.domain import relations
from aileen.errors import UserError
from aileen.world import catalog
from aileen.world.camera import Table

LAYOUT_TRIES = 3  # layouts tried per other relation before moving on to the next one


def prepare(lesson: Lesson, *, seed: int, table: Table = Table()) -> tuple[Lesson, Setup]:
    """Lay the lesson out; for a `say_false` lesson also make up its false sentence.

    Returns the lesson to give (with the false `content`, `say_false` cleared) and its setup;
    an ordinary lesson comes back unchanged with `trainer.layout`'s setup.
    """
    if not lesson.say_false:
        return lesson, trainer.layout(lesson, seed=seed, table=table)
    rng = np.random.default_rng([seed, 0x5A1D])  # its own stream: the layout's draws stay as they were
    if lesson.action is not None:
        return _false_action(lesson, seed, rng, table)
    if lesson.relation is None:
        setup = trainer.layout(lesson, seed=seed, table=table)
        return _said(lesson, absent_pair(setup, rng)), setup
    return _false_relation(lesson, seed, rng, table)


def absent_pair(setup: Setup, rng: np.random.Generator) -> str:
    """`"<colour> <shape>"` for a kind of object that is not on the table."""
    visible = [o for o in setup.world.objects() if not o.held]
    there = {(o.colour, o.shape) for o in visible}
    colours = {o.colour for o in visible}
    shapes = {o.shape for o in visible}
    absent = [(c, s) for c in catalog.COLOURS for s in catalog.drawn_shapes() if (c, s) not in there]
    if not absent:
        raise UserError("cannot say something false: every colour-shape pair is on the table")
    recombined = [(c, s) for c, s in absent if c in colours and s in shapes]
    pool = recombined or absent
    colour, shape = pool[int(rng.integers(len(pool)))]
    return f"{colour} {shape}"


def _false_relation(lesson: Lesson, seed: int, rng: np.random.Generator,
                    table: Table) -> tuple[Lesson, Setup]:
    assert lesson.relation is not None
    asked = relations.get(lesson.relation)
    # plain layouts of the other words; both objects stay on the table (stacked, every relation
    # between table-top objects would be false for a reason that has nothing to do with its word)
    others = [r.name for r in relations.RELATIONS.values()
              if r.name == r.word and r.word != asked.word and not r.stacked]
    order = [others[int(i)] for i in rng.permutation(len(others))]
    refused: LayoutError | None = None  # why the first relation that could not be laid out was not
    laid_out = False
    for other in order:
        trial = dataclasses.replace(lesson, relation=other, say_false=False, near_miss=False)
        for k in range(LAYOUT_TRIES):
            try:
                setup = trainer.layout(trial, seed=seed + 7919 * k, table=table)
            except LayoutError as exc:  # not a mistake in the file (those are raised as they are)
                refused = refused or exc
                break  # this relation cannot be laid out with these objects
            laid_out = True
            a, b = (setup.world.get(i) for i in setup.ids[:2])
            sentence = f"{a.colour} {a.shape} {asked.word} {b.colour} {b.shape}"
            if asked.accepts(a, b) or grading.content_true(sentence, setup.world.objects()) is not False:
                continue
            return _said(trial, sentence), setup
    if not laid_out and refused is not None:
        # no relation could be laid out at all: the reason is the objects', not the sentence's
        # (two red boxes the sentence cannot tell apart), and the run skips the lesson with it
        raise LayoutError(refused.reason, lesson)
    raise LayoutError(f"cannot lay out a scene where {lesson.objects[0].describe()} is not "
                      f"{asked.word} {lesson.objects[1].describe()}: every other relation "
                      "would make the sentence true", lesson)


def _false_action(lesson: Lesson, seed: int, rng: np.random.Generator,
                  table: Table) -> tuple[Lesson, Setup]:
    """The action laid out as described, and a sentence about it that its demonstration makes
    false: the opposite direction, else the roles swapped; a verb on one object, an absent one."""
    action = lesson.action
    assert action is not None
    trial = dataclasses.replace(lesson, say_false=False)
    setup = trainer.layout(trial, seed=seed, table=table)
    shown = [setup.world.get(setup.ids[i]) for i in grading.demonstrated_roles(lesson)]
    names = [f"{o.colour} {o.shape}" for o in shown]
    if action.relation is None:
        candidates = [f"{action.verb} {absent_pair(setup, rng)}"]
    else:
        asked = relations.get(action.relation)
        opposite = asked.direction.opposite if asked.direction is not None else None
        candidates = ([f"{action.verb} {names[0]} {opposite} {names[1]}"] if opposite else []) \
            + [f"{action.verb} {names[1]} {asked.word} {names[0]}"]
    for sentence in candidates:
        said = _said(trial, sentence)
        if grading.expected(dataclasses.replace(said, expect=None), setup) == "failure":
            return said, setup
    raise lesson.source.error(f"cannot say something false of '{action.name}' shown with "
                              f"{' and '.join(names)}: every sentence tried is true of it")


def _said(lesson: Lesson, sentence: str) -> Lesson:
    return dataclasses.replace(lesson, content=sentence, say_false=False)
