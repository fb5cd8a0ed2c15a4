"""A trainer's console over an agent with ground-truth vision, as the console tests drive it."""

from __future__ import annotations

import sys
from pathlib import Path

from aileen.agent import Agent, AgentParams
from aileen.curriculum.console import Console
from aileen.perception.truth import TruthVision


def truth_console(**params: object) -> tuple[Agent, Console]:
    """An agent (seed 0, `params` beside it) that sees through ground truth, and its console."""
    v = TruthVision()
    agent = Agent(params=AgentParams(seed=0, **params), perceiver=v)
    return agent, Console(agent, on_frame=v.see_frame)


def teach_piped(folder: Path, args: list[str], lines: list[str]) -> int:
    """`aileen teach ARGS` with `lines` on its stdin, as a pipe gives them (a file in `folder`):
    its exit status."""
    from aileen.cli import main

    with (folder / "s.txt").open("w+") as fh:
        fh.write("\n".join(lines) + "\n")
        fh.seek(0)
        old, sys.stdin = sys.stdin, fh
        try:
            return main(["teach", *args])
        finally:
            sys.stdin = old


def teach_alone(con: Console, *lessons: str | tuple[str, str]) -> None:
    """Show each object alone on a clear table and inform its name, or (object, sentence): the
    sentence said of it ("red box", ("red box", "kube box"))."""
    for lesson in lessons:
        obj, said = (lesson, lesson) if isinstance(lesson, str) else lesson
        con.do("clear")
        con.do(f"place {obj}")
        con.do(f"inform {said}")


def lay_out(con: Console, *placements: str) -> None:
    """Clear the table and place each object ("red box at 0.3 0.5")."""
    con.do("clear")
    for p in placements:
        con.do(f"place {p}")
