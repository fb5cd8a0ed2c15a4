"""Lessons as a person reads them: one lesson's result as a transcript, and a run's summary line.

`aileen run` prints both (`curriculum.commands`) and `aileen teach` prints a transcript after
each lesson (`curriculum.console`): one module for the text, so the two read alike.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from aileen.curriculum.lesson import EMPTY_LESSON

if TYPE_CHECKING:  # the text needs no agent loaded: `aileen --help` stays quick
    from aileen.curriculum.interpreter import LessonResult

__all__ = ["printable", "summarise", "transcript"]


def printable(text: str) -> str:
    """`text` with control characters written as escapes: a lesson's sentence printed as it
    was could retitle or clear the reader's terminal (an escape sequence in a lesson file)."""
    return "".join(ch if ch.isprintable() or ch == " " else ascii(ch)[1:-1] for ch in text)


def transcript(r: LessonResult) -> str:
    """A lesson as a person reads it."""
    a = r.answer
    head = (f"lesson {r.index:>2}  " if r.index else "") + f"{a.signal:<6}  \"{printable(a.content)}\""
    if r.lesson.note:
        head += f"   ({r.lesson.note})"
    if r.skipped is not None:
        return f"{head}\n  skipped:  {r.skipped}"
    lines = [head, "  saw:      " + ("; ".join(r.seen) if r.seen else "nothing")]
    lines += [f"  trainer:  {note}" for note in r.notes]
    answer = a.result + (f": {a.reason}" if a.reason else "")
    if a.referents and a.result == "success":
        answer += "  [" + ", ".join(f"{k} = {' '.join(v) or '-'}" for k, v in a.referents.items()) + "]"
    lines.append(f"  answer:   {answer}")
    if a.said:
        lines.append(f"  said:     \"{a.said}\"")
        if r.said_true is not None:
            lines.append(f"  trainer:  {'true' if r.said_true else 'NOT true'} of the table")
        else:
            lines.append("  trainer:  not graded (a sentence the trainer cannot read)")
    if a.signal == "react":
        lines.append(f"  acted:    {', '.join(a.steps) or 'nothing'} ({a.projections} projections)")
        if r.goal_holds is not None and a.understood:  # (one it could not read is not graded)
            lines.append(f"  trainer:  the goal {'holds' if r.goal_holds else 'does NOT hold'}")
    if a.created or a.stored:
        parts = []
        if a.created:
            parts.append("created " + ", ".join(a.created))
        if a.stored:
            parts.append("stored " + ", ".join(a.stored))
        lines.append(f"  learned:  {'; '.join(parts)}  ({a.commands} commands)")
    if r.correct is not None and a.signal == "verify" and not a.said:
        why = (" (a word it does not know: its 'no' is no answer)"
               if not r.correct and r.expected == "failure" and a.unknown_words else "")
        lines.append(f"  trainer:  expected {r.expected}: {'right' if r.correct else 'WRONG'}{why}")
    if not a.understood:
        lines.append("  trainer:  not graded (the agent could not read the sentence)")
    elif r.ungraded is not None:
        lines.append(f"  trainer:  not graded ({r.ungraded})")
    elif a.signal == "verify" and r.expected is None and not a.said and r.index:  # a file's (the console's teacher judges)
        lines.append("  trainer:  not graded (it cannot tell what the sentence's words mean here: "
                     f"give the lesson's `{r.lesson.source.expect_key}`)")
    return "\n".join(lines)


def summarise(results: Sequence[LessonResult]) -> str:
    """The run's one summary line: lessons, commands, what was right, what was skipped."""
    n = len(results)
    cmds = sum(r.answer.commands for r in results)
    verify = [r for r in results if r.answer.signal == "verify" and r.correct is not None]
    react = [r for r in results if r.answer.signal == "react" and r.correct is not None]  # skipped, unread: not graded
    parts = [f"{n} lessons", f"{cmds} create/store commands"]
    if verify:
        parts.append(f"verify {sum(r.correct for r in verify)}/{len(verify)} right")
    if react:
        parts.append(f"react {sum(bool(r.correct) for r in react)}/{len(react)} reached the goal")
    said = [r for r in results if r.answer.signal == "generate" and r.correct is not None]
    if said:
        parts.append(f"generate {sum(bool(r.correct) for r in said)}/{len(said)} said something true")
    unread = sum(not r.answer.understood and r.skipped is None for r in results)
    if unread:
        parts.append(f"{unread} not understood (not graded)")
    untold = [r for r in results if r.answer.signal == "verify" and r.answer.understood and r.expected is None
              and r.skipped is None and not r.answer.said and r.ungraded is None]
    if untold:
        keys = " or ".join(f"`{k}`" for k in dict.fromkeys(r.lesson.source.expect_key for r in untold))
        parts.append(f"{len(untold)} verify not graded (no {keys})")
    contradicted = sum(r.ungraded is not None and r.answer.understood and r.skipped is None for r in results)
    if contradicted:
        parts.append(f"{contradicted} verify not graded (the file contradicts itself)")
    asked = sum(r.skipped is not None and r.answer.question is not None for r in results)
    empty = sum(r.skipped is not None and r.lesson.skip == EMPTY_LESSON for r in results)
    unshown = sum(r.skipped is not None and r.lesson.skip not in (None, EMPTY_LESSON) for r in results)
    skipped = sum(r.skipped is not None for r in results) - asked - empty - unshown
    if empty:
        parts.append(f"{empty} skipped (empty)")
    if unshown:  # a script's own demonstration that does not reach its goal (`legacy_trace`)
        parts.append(f"{unshown} skipped (the file's demonstration shows nothing to learn)")
    if skipped:
        parts.append(f"{skipped} skipped (the trainer could not lay {'it' if skipped == 1 else 'them'} out)")
    if asked:
        parts.append(f"{asked} skipped (the agent asked about a word)")
    ms = sorted(r.seconds for r in results)
    if ms:
        parts.append(f"median lesson {1000 * ms[len(ms) // 2]:.0f} ms")
    return "summary: " + ", ".join(parts)
