"""The sector ceiling: what a learner that sees directions as the camera's 8 CDC sectors can pass.

Why: in the wide protocol a relation is laid out up to 40 degrees off its axis, so a "left of"
scene lies in sector `w`, `nw` or `sw`. The one-shot oracle counts an exam item as passable once
its words have been taught; a learner whose sense of direction is the 8 sectors cannot know that
"left of" also covers `sw` before it has seen it there (disjunctive concepts, DESIGN.md 14). This
curve is the best such a learner can do: a generality item with a relation passes once its
relation word has been taught in the item's sector (an action item: the sector the mover ends
in, and the verb taught). Visual items count as in the oracle. The gap between the one-shot
oracle and this curve is the curriculum's, not the learner's.

The sectors come from the trainer's own layouts (the same seeds the trial runs with), read
with the camera's CDC function on ground truth; the agent never sees any of this.
"""

from __future__ import annotations

from collections.abc import Sequence

from aileen.curriculum import demonstration, trainer
from aileen.curriculum.lesson import Lesson
from aileen.curriculum.sentences import read_content
from aileen.experiments.protocol import Trial, lesson_words
from aileen.world import geometry


def sector_of(lesson: Lesson, setup: "trainer.Setup | None") -> str | None:
    """The CDC sector of objects[0] to objects[1] on the trainer's table as the lesson left it
    (after its demonstration); None without a relation or a table."""
    if setup is None or read_content(lesson.content).relation is None or len(setup.ids) < 2:
        return None
    a, b = setup.world.get(setup.ids[0]), setup.world.get(setup.ids[1])
    return geometry.cardinal(a.box_m(), b.box_m())


def sector(lesson: Lesson, seed: int) -> str | None:
    """`sector_of` a lesson laid out (and demonstrated) anew with its seed."""
    if read_content(lesson.content).relation is None or len(lesson.objects) < 2:
        return None
    setup = trainer.layout(lesson, seed=seed)
    if lesson.action is not None or lesson.demonstration is not None:
        for step in demonstration.demonstrate(lesson, setup, seed=seed):
            demonstration.execute(setup.world, step)
    return sector_of(lesson, setup)


def sector_ceiling_curve(trial: Trial, pre_sectors: Sequence[str | None], lesson_sectors: Sequence[str | None],
                         item_sectors: Sequence[str | None]) -> list[int]:
    """Per training lesson, the generality items a sector learner can pass (see the module doc);
    the sectors of the prerequisites, lessons and generality items, in order."""
    taught_words: set[str] = set()
    taught: set[tuple[str, str]] = set()

    def learn(lesson: Lesson, s: str | None) -> None:
        taught_words.update(lesson_words(lesson))
        rel = read_content(lesson.content).relation
        if rel is not None and s is not None:
            taught.add((rel, s))

    items = [(item, read_content(item.content).relation, s)
             for item, s in zip(trial.generality, item_sectors, strict=True)]
    for lesson, s in zip(trial.prerequisites, pre_sectors, strict=True):
        learn(lesson, s)
    out = []
    for lesson, s in zip(trial.lessons, lesson_sectors):
        learn(lesson, s)
        out.append(sum(1 for item, rel, sec in items
                       if lesson_words(item) <= taught_words and (rel is None or (rel, sec) in taught)))
    return out
