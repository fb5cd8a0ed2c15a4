"""What a react can know before it acts: a relation no action changes, no plan, no room. It
picked the object up and put it back before refusing (the probe's t2 and t5), or moved it
anywhere and said success ("move the red box larger than the blue cone")."""

from __future__ import annotations

from pathlib import Path

import pytest
from console_helpers import teach_piped

from aileen.cli import main

LESSONS = Path(__file__).resolve().parents[1] / "lessons"


@pytest.fixture(scope="module")
def memory(tmp_path_factory) -> Path:
    """A memory taught the comparatives and distances, and "move" (lessons/relations.toml,
    lessons/demo.toml)."""
    m = tmp_path_factory.mktemp("foresight") / "m.json"
    assert main(["run", str(LESSONS / "relations.toml"), str(LESSONS / "demo.toml"), "--perception", "truth",
                 "--seed", "0", "--memory", str(m)]) in (0, 1)
    return m


def teach(memory: Path, tmp_path: Path, capsys, lines: list[str]) -> str:
    """`aileen teach` on a copy of `memory`, `lines` on stdin: what it printed."""
    mine = tmp_path / "m.json"
    mine.write_bytes(memory.read_bytes())
    capsys.readouterr()
    teach_piped(tmp_path, ["--memory", str(mine), "--perception", "truth", "--seed", "0"], lines)
    return capsys.readouterr().out


def test_a_relation_no_action_changes_is_refused_before_acting(memory: Path, tmp_path: Path, capsys) -> None:
    out = teach(memory, tmp_path, capsys, ["place small red box at 0.3 0.5", "place large blue cone at 0.7 0.5",
                                           "react move the red box larger than the blue cone"])
    assert "answer:   failure: no move makes the red box larger than the blue cone" in out
    assert "acted:    nothing" in out


def test_no_room_is_said_before_the_object_is_picked_up(memory: Path, tmp_path: Path, capsys) -> None:
    out = teach(memory, tmp_path, capsys, ["place red box at 0.3 0.5", "place blue cone at 0.94 0.5",
                                           "react move the red box right of the blue cone"])
    assert "answer:   failure: there is no room right of the blue cone for the red box" in out
    assert "acted:    nothing" in out and "pick_up" not in out


def test_a_react_whose_relation_does_not_hold_after_acting_says_so(memory: Path, tmp_path: Path, capsys,
                                                                   monkeypatch) -> None:
    """The plan's facts held, and it said success whatever its own look said of the relation
    (the agent's verify of the relation made to say no here)."""
    from aileen.agent.acting import Acting

    monkeypatch.setattr(Acting, "_so_already", lambda self, goal, args: False)
    out = teach(memory, tmp_path, capsys, ["place red box at 0.3 0.5", "place blue cone at 0.6 0.5",
                                           "react move the red box right of the blue cone"])
    assert "answer:   failure: after acting, the red box right of the blue cone does not hold as I see it" in out
