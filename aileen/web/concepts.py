"""The memory panel: each concept the agent holds, as the page lists it (`GET /api/memory`).

Why a module of its own (split out of `session`): it only reads, the memory (as `aileen memory
show` renders it) beside this session's lesson records (how a word fared in the verify lessons
that used it), and what it reads is the memory's, not the teaching's.
"""

from __future__ import annotations

from aileen.agent import Agent


def memory_json(agent: Agent, records: list[dict], *, saved_to_file: bool) -> dict:
    """Per concept: the memory's own figures and text, its word, and how the word fared this
    session; the memory's thresholds; whether there is a file to save to."""
    from aileen.memory.commands import render_json, render_text

    mem = agent.memory
    out = render_json(mem)
    words = agent.semantic.words()
    by_concept = {c: w for w, c in words.items()}
    for sym, entry in out.items():
        entry["word"] = by_concept.get(sym)
        entry["text"] = render_text(mem, sym).split("\n", 1)[1].strip()
        entry["concept_quality"] = entry["quality"]  # the memory's own figures (memory/quality.py)
        entry["quality"] = quality(records, by_concept.get(sym))
    p = mem.params
    return {"concepts": out, "thresholds": {"assimilation": p.assimilation, "probability": p.probability,
                                             "match": p.match}, "path": saved_to_file}


def quality(records: list[dict], word: str | None) -> dict | None:
    """How the word fared in this session's graded verify lessons that used it."""
    if not word:
        return None
    graded = [r for r in records if r["signal"] == "verify" and r["correct"] is not None
              and word.replace("_", " ") in r["content"]]
    if not graded:
        return None
    return {"verify_right": sum(bool(r["correct"]) for r in graded), "verify_graded": len(graded)}
