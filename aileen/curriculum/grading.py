"""The trainer's grading: what a correct learner answers, judged the way a person judges.

A visual or spatial sentence against the table (`content_true`), a verify lesson's expected
answer (`expected`: its own `expect`, else the table, else the demonstration), and an action
lesson's goal in the world after a react (`goal_holds`). Layouts and demonstrations are the
trainer's (`trainer`); this module only looks.
"""

from __future__ import annotations

import dataclasses

import re

from aileen.curriculum.lesson import Lesson, goal_relation
from aileen.curriculum.sentences import ContentInfo, read_content
from aileen.curriculum.specs import ObjectSpec
from aileen.curriculum.stage import Setup
from aileen.domain import actions, composites, relations
from aileen.errors import UserError
from aileen.world.sim import World, WorldObject


#: What a console says to a `confirm` after a react whose goal the trainer did not see reached
#: (a lesson file's run ignores such a confirm: `Interpreter._feedback`).
CONFIRM_REFUSED = ("'confirm' is for a react that reached its goal, and the trainer did not see it reached: "
                   "nothing to learn from")


def confirmable(goal_holds: bool | None, agent_says_reached: bool) -> bool:
    """May a `confirm` follow this react? When the trainer saw its goal reached, or could not
    grade it (a relation word of the teacher's own: the trainer cannot read it) and the agent
    says it reached it: then the person confirming is the judge (it was refused, and a react
    in the teacher's own word could not be confirmed in the console, nor in a file)."""
    return goal_holds is True or (goal_holds is None and agent_says_reached)


def goal_holds(lesson: Lesson, world: World, ids: list[str], start: dict[str, tuple[float, float]] | None = None) -> bool:
    """Ground truth for an action lesson, graded the way a person would: the goal test its verb
    declares (`aileen.domain.actions`), on the lesson's objects as they are now and where they
    stood (`start`). For `move X <r> Y`: is objects[0] (on the table) in the goal relation to
    objects[1] (`relations.holds`, 45 degrees either side)? For `push X`: did objects[0] slide
    away from the trainer (north) by at least half its width, and stay on the table?"""
    if lesson.action is None:
        raise lesson.source.error("the lesson has no action, so no goal")
    verb = actions.verb(lesson.action.verb)
    mine = ids[:lesson.action.n_objects]
    outcome = actions.Outcome(tuple(world.get(i) for i in mine), tuple((start or {}).get(i) for i in mine),
                              goal_relation(lesson))
    try:
        return verb.goal(outcome)
    except UserError as exc:
        raise lesson.source.error(f"cannot grade '{lesson.action.name}': {exc.message}") from None


def content_true(content: str, objects: list[WorldObject]) -> bool | None:
    """Ground truth for a visual or spatial sentence: is what it describes on the table?

    Every object phrase needs a matching object on the table; with a relation, some matching
    pair must stand in it (lenient reading). Parts joined by "and" ("red box and blue cone and
    something", as `generate` lists three or more objects) must each hold, the plain phrases
    by different objects; plain phrases just before a relation are its subjects too, each in
    it ("the red box and the green box are left of the blue cone"). None when the trainer cannot read the sentence (a word outside its
    language, or no object phrase): not graded, never counted as false.
    """
    visible = [o for o in objects if not o.held]
    parts = _conjuncts(content)
    if len(parts) > 1:
        return _all_true(parts, visible)
    words = content.lower().split()
    if len(words) == 1 and words[0] in composites.COMPOSITES:
        return composites.COMPOSITES[words[0]].accepts(visible)
    info = read_content(content)
    if info.unknown or not info.phrases or info.verb is not None:
        return None
    matches = [[o for o in visible if p.fits(o.appearance)] for p in info.phrases]
    if _which(info, [[o.id for o in m] for m in matches]):
        return None
    if info.relation is None:
        return all(matches)
    if len(matches) != 2:
        return None
    return any(a.id != b.id and relations.holds(info.relation, a, b) for a in matches[0] for b in matches[1])


def _which(info: ContentInfo, candidates: list[list[str]]) -> bool:
    """Does the sentence say "the X" where several objects are X? Then it names none of them:
    a correct learner asks which (docs/lessons.md), and the trainer cannot say what it answers
    (it read "the box" as "some box" over a red and a green box, and graded the question WRONG)."""
    return any(the and len(c) > 1 for the, c in zip(info.definite, candidates))


def _conjuncts(content: str) -> list[str]:
    """The parts of a sentence joined by the word "and" (one part when there is none)."""
    return [p for p in re.split(r"\band\b", content, flags=re.IGNORECASE)]


def _all_true(parts: list[str], visible: list[WorldObject]) -> bool | None:
    """Each part true of the table; plain object phrases each by an object of its own. Plain
    phrases just before a part with a relation are its subjects too ("the red box and the green
    box are left of the blue cone": each box must be left of the cone; only the green box was
    asked, and a right-of scene was graded "success")."""
    plain: list[list[str]] = []
    truths: list[bool | None] = []
    subjects: list[ObjectSpec] = []  # plain phrases waiting for a relation to follow
    for part in parts:
        info = read_content(part)
        if not part.strip():
            return None  # "red box and" or "and and": not a sentence the trainer says
        if info.relation is None and len(info.phrases) == 1 and not info.unknown and info.verb is None:
            if _which(info, [[o.id for o in visible if info.phrases[0].fits(o.appearance)]]):
                return None
            subjects.append(info.phrases[0])
            continue
        if subjects and info.relation is not None:
            if info.unknown or info.verb is not None or len(info.phrases) != 2:
                return None
            obj = info.phrases[1]
            for phrase in (*subjects, info.phrases[0]):  # each subject, in the relation to the object
                plain.append([a.id for a in visible if phrase.fits(a.appearance)
                              and any(b.id != a.id and obj.fits(b.appearance) and relations.holds(info.relation, a, b)
                                      for b in visible)])
        else:
            plain += [[o.id for o in visible if p.fits(o.appearance)] for p in subjects]
            truths.append(content_true(part, visible))
        subjects = []
    plain += [[o.id for o in visible if p.fits(o.appearance)] for p in subjects]
    if any(t is None for t in truths):
        return None
    return all(truths) and _distinct(plain)


def _distinct(candidates: list[list[str]]) -> bool:
    """Whether each phrase can have an object of its own among its candidates (a bipartite
    matching, by augmenting paths: a handful of phrases and objects)."""
    owner: dict[str, int] = {}

    def place(i: int, seen: set[str]) -> bool:
        for o in candidates[i]:
            if o in seen:
                continue
            seen.add(o)
            if o not in owner or place(owner[o], seen):
                owner[o] = i
                return True
        return False

    return all(place(i, set()) for i in range(len(candidates)))


def expected(lesson: Lesson, setup: Setup) -> str | None:
    """What a correct learner answers to a verify lesson: `success`, `failure`, or None (unknown).

    The lesson's own `expect` wins. Otherwise: a visual or spatial sentence is judged against
    the laid-out table; an action sentence is judged against what is demonstrated (same verb,
    relation and objects); a demonstration holding none of the verb's own steps (its declaration
    in `aileen.domain.actions`: a point, or a push shown for "nudge") does not show the verb.
    """
    if lesson.expect is not None:
        return lesson.expect
    info = read_content(lesson.content)
    if info.verb is not None:
        if lesson.action is None or info.unknown or len(info.phrases) != lesson.action.n_objects:
            return None
        if not shows_verb(lesson):
            return "failure"
        roles = demonstrated_roles(lesson)
        shown = [setup.world.get(setup.ids[i]) for i in roles]
        same = (info.verb == lesson.action.verb and info.relation == lesson.action.relation
                and all(p.fits(o.appearance) for p, o in zip(info.phrases, shown)))
        return "success" if same else "failure"
    truth = content_true(lesson.content, setup.world.objects())
    return None if truth is None else ("success" if truth else "failure")


def contradiction(lesson: Lesson, setup: Setup) -> str | None:
    """Why a verify lesson's own expected answer contradicts its own lesson, or None.

    A file's `expect` (the original scripts' `is_positive`) says one answer while the trainer,
    judging the sentence against the table the same lesson lays out (or the demonstration it
    shows), finds the other: the file says both, so neither answer can be held wrong. Lessons
    the trainer cannot judge (a word it cannot read) are not contradicted."""
    if lesson.signal != "verify" or lesson.expect is None:
        return None
    own = expected(dataclasses.replace(lesson, expect=None), setup)
    if own is None or own == lesson.expect:
        return None
    return f"the file says the answer is {lesson.expect}, its own lesson says {own}"


def shows_verb(lesson: Lesson) -> bool:
    """Does the lesson's demonstration do its verb at all? Some step of the verb's own declared
    steps (`actions.Verb.steps`; for a verb with a relation, its step into a region) must be
    among the demonstrated ones: "push the red box" shown by `point 1`, or "nudge" shown by
    `push 1`, shows another action, and was graded as the verb because the verb compared was
    read from the sentence. No demonstration: the trainer's own, its verb's steps."""
    assert lesson.action is not None
    if lesson.demonstration is None:
        return True
    verb = actions.verb(lesson.action.verb)
    own = [s for s in lesson.demonstration if s.action in verb.steps]
    if lesson.action.relation is not None:
        own = [s for s in own if actions.action(s.action).kind == actions.REGION]
    return bool(own)


def demonstrated_roles(lesson: Lesson) -> list[int]:
    """Which of the lesson's objects the demonstration did its verb to (and relative to which):
    the last step into a region relative to another object (`place 1 left of 2`: mover,
    reference), or the last step of the verb's own done to an object for a verb on one object;
    objects 1 and 2 for the trainer's own demonstration."""
    assert lesson.action is not None
    steps = lesson.demonstration or []
    if lesson.action.relation is not None:
        places = [s for s in steps if actions.action(s.action).kind == actions.REGION and isinstance(s.ref, int)]
        return [int(places[-1].obj), int(places[-1].ref)] if places else [0, 1]
    done = [s for s in steps if s.action in actions.verb(lesson.action.verb).steps]
    return [int(done[-1].obj)] if done else [0]
