"""Which words a lesson file takes as known, and which lesson file beside it teaches them.

Why: a curriculum such as `spatial.toml` teaches relations between objects that it names with
visual words ("red box left of blue cylinder"). On an empty memory every one of its lessons
fails with "I do not know the word 'red'", and a newcomer cannot tell why. Before the first
lesson `aileen run` says which words are missing and which file teaches them, so the fix is
one command. The reading is the trainer's (`sentences`): a word is *taught* by an inform
lesson that names one object and no relation or action; it is *taken as known* where a
lesson names objects in a relation, an action or a group. It is advice, printed as a note:
the run goes on (a person may mean to watch the agent fail).
"""

from __future__ import annotations

import shlex
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from aileen.curriculum.lesson import Curriculum, Lesson
from aileen.curriculum.sentences import ARTICLES, _words, read_content
from aileen.domain import channels
from aileen.errors import UserError

__all__ = ["Missing", "object_words", "taught", "missing_words", "advice"]


def object_words(content: str) -> set[str]:
    """The words of `content` that name what an object looks like (a value of a channel:
    colour, shape, size, ...), as said ("cube" stays "cube": the agent learns the word it hears)."""
    return {w for w in _words(content.replace("-", " ")) if w not in ARTICLES and channels.read_value(w, {})}


def _names_one_object(lesson: Lesson) -> bool:
    info = read_content(lesson.content)
    # (one object laid out too: "red box northeast of blue cone", a relation of the teacher's
    # own, reads to the trainer as one phrase, and grain.toml's words counted as taught)
    return (lesson.signal == "inform" and info.relation is None and info.verb is None and lesson.composite is None
            and len(info.phrases) == 1 and len(lesson.objects) <= 1)


def taught(lessons: Iterable[Lesson]) -> set[str]:
    """The object words these lessons teach."""
    return set().union(*(object_words(x.content) for x in lessons if _names_one_object(x)))


@dataclass(frozen=True)
class Missing:
    """A curriculum's words that nothing before it teaches."""

    curriculum: Curriculum
    words: tuple[str, ...]


def missing_words(curricula: Sequence[Curriculum], known: Iterable[str]) -> list[Missing]:
    """Per curriculum, in order, the object words its lessons take as known that neither
    `known` (the memory's words) nor an earlier lesson of the run teaches."""
    have = set(known)
    out = []
    for cur in curricula:
        lacking: set[str] = set()
        for lesson in cur.lessons:
            if _names_one_object(lesson):
                have |= object_words(lesson.content)
            elif lesson.content:
                lacking |= object_words(lesson.content) - have
        if lacking:
            out.append(Missing(cur, tuple(sorted(lacking))))
    return out


def _teacher(missing: Missing, running: set[Path]) -> Path | None:
    """The lesson file beside the curriculum that teaches the most of the missing words
    (every one, preferably; ties: the shorter file), not one already in the run."""
    if not missing.curriculum.path:
        return None
    here = Path(missing.curriculum.path)
    best: tuple[int, int, str] | None = None
    found = None
    for p in sorted(here.parent.glob("*.toml")):
        if p.resolve() in running:
            continue
        try:
            from aileen.curriculum.formats import load_curriculum

            cur = load_curriculum(p)
        except UserError:
            continue
        covers = len(set(missing.words) & taught(cur.lessons))
        if covers == 0:
            continue
        key = (-covers, len(cur), p.name)
        if best is None or key < best:
            best, found = key, p
    return found


def advice(curricula: Sequence[Curriculum], known: Iterable[str], memory: str | None) -> list[str]:
    """One note per curriculum that takes unknown words as known: which, and what to run first."""
    running = {Path(c.path).resolve() for c in curricula if c.path}
    notes = []
    for m in missing_words(curricula, known):
        shown = ", ".join(m.words[:8]) + (", ..." if len(m.words) > 8 else "")
        name = m.curriculum.path or "the lessons"
        after = [Path(m.curriculum.path).parent / a for a in m.curriculum.after] if m.curriculum.path else []
        after = [a for a in after if a.resolve() not in running]
        if after:  # the file says what it follows (`after = [...]`): that, not a guess
            keep = f" --memory {shlex.quote(memory)}" if memory else ""
            both = " ".join(shlex.quote(str(p)) for p in [*after, *[c.path for c in curricula if c.path]])
            notes.append(f"note: {name} takes words as known that nothing before it teaches ({shown}); it follows "
                         f"{', '.join(map(str, after))} (its `after`): aileen run {both}{keep}")
            continue
        first = _teacher(m, running)
        if first is None:
            notes.append(f"note: {name} takes words as known that nothing before it teaches ({shown}); teach them "
                         "first, each with one object on the table (e.g. 'inform red box')")
            continue
        keep = f" --memory {shlex.quote(memory)}" if memory else ""
        both = " ".join(shlex.quote(str(p)) for p in [first, *[c.path for c in curricula if c.path]])
        from aileen.curriculum.formats import load_curriculum

        covered = sorted(set(m.words) & taught(load_curriculum(first).lessons))
        what = "them" if len(covered) == len(m.words) else ", ".join(covered)  # (not "them" for some of them)
        notes.append(f"note: {name} takes words as known that nothing before it teaches ({shown}); {first} "
                     f"teaches {what}: run it first{' with the same --memory' if memory else ''}, or both in one "
                     f"run: aileen run {both}{keep}")
    return notes
