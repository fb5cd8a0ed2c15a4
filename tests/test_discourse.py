"""What "it" refers to across lessons: what the last lesson grounded, where it stands now."""

from __future__ import annotations

from console_helpers import truth_console


def _referent(said: str, name: str) -> str:
    line = next(line for line in said.splitlines() if line.strip().startswith("answer:"))
    return line.split(f"{name} = ", 1)[1].split(",")[0].split("]")[0].strip()


def test_it_after_the_agents_own_move_is_the_object_it_moved() -> None:
    """"move a red box right of the blue cone" moved o1; "move it behind the blue cone" then
    took the other red box, the lookalike nearest where o1 had stood (probe p7's it.txt)."""
    agent, con = truth_console()
    for obj in ("red box", "blue cone"):
        con.do("clear")
        con.do(f"place {obj}")
        con.do(f"inform {obj}")
    con.do("clear")
    for line in ("place red box at 0.6 0.5", "place blue cone at 0.3 0.5", "inform the red box is right of the blue cone",
                 "clear", "place red box at 0.3 0.5", "place blue cone at 0.6 0.5",
                 "inform move the red box right of the blue cone"):
        con.do(line)
    con.do("clear")
    for line in ("place red box at 0.2 0.5", "place red box at 0.2 0.8", "place blue cone at 0.6 0.5"):
        con.do(line)
    first = con.do("react move a red box right of the blue cone")
    moved = _referent(first, "red box")
    said = con.do("verify is it right of the blue cone?")
    assert "success" in said and _referent(said, "it") == moved, said
