"""The ceilings under the one-shot oracle: what an ideal learner of a given kind can pass.

Two of them, each a curve per training lesson beside the oracle's (`protocol.oracle_curve`):
the cross-situational learner's (`cross_situational_curve`: it must find out which percept
each word names) and the sector learner's (below). Both are the curriculum's limits, not a
learner's mistakes; a trial (`trial.run_trial`) records them with its lessons, and they live
together here because both are read the same way: against the oracle, from the trial alone.

The sector ceiling: what a learner that sees directions as the camera's 8 CDC sectors can pass.

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


def cross_situational_curve(trial: Trial) -> list[int]:
    """Per lesson, the generality score of an ideal learner that, unlike the one-shot oracle,
    must find out which percept each word names (it has no prior that colour words name
    colours): a word's candidates are the percepts common to every object it was said of, and
    a word pinned to one percept removes it from every other word's candidates (mutual
    exclusivity), to a fixpoint. An exam item counts when it is true under every meaning the
    learner cannot yet rule out: each of its words' candidates is among the item's percepts
    (so "blue sphere" taught once already passes the exam item "blue sphere").

    "blue sphere" as the first lesson pins neither word; "blue box" later pins both "blue" and
    then "sphere". The gap between `oracle_curve` and this curve is what the curriculum leaves
    ambiguous, not what a learner gets wrong. Visual words only: relations and actions come
    from their own lessons (each names one relation of two already-known objects) and are
    pinned once taught, as in the oracle.
    """
    cands: dict[str, set[str]] = {}
    pinned_other: set[str] = set()  # relation/action words: pinned when taught

    def learn(lesson) -> None:  # noqa: ANN001
        info = read_content(lesson.content)
        if info.relation is not None:
            pinned_other.update(w for w in lesson_words(lesson) if w in (info.relation, info.verb))
        for phrase_spec, obj in zip(info.phrases, lesson.objects):
            percepts = {f"c:{obj.colour}", f"s:{obj.shape}"}
            for w in (phrase_spec.colour, phrase_spec.shape):
                if w:
                    cands[w] = cands[w] & percepts if w in cands else set(percepts)
        changed = True
        while changed:
            changed = False
            for w, cs in cands.items():
                if len(cs) == 1:
                    p = next(iter(cs))
                    for v, other in cands.items():
                        if v != w and p in other and len(other) > 1:
                            other.discard(p)
                            changed = True

    def sure(item) -> bool:  # noqa: ANN001
        info = read_content(item.content)
        for phrase_spec, obj in zip(info.phrases, item.objects):
            percepts = {f"c:{obj.colour}", f"s:{obj.shape}"}
            for w in (phrase_spec.colour, phrase_spec.shape):
                if w and not (w in cands and cands[w] <= percepts):
                    return False
        return all(w in pinned_other for w in lesson_words(item) if w in (info.relation, info.verb))

    for lesson in trial.prerequisites:
        learn(lesson)
    out = []
    for lesson in trial.lessons:
        learn(lesson)
        out.append(sum(1 for item in trial.generality if sure(item)))
    return out
