"""Words for groups of objects (agent/composite.py): which objects a new one is taught on."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from aileen.agent.composite import taught_group
from aileen.agent.state import State
from aileen.cli import main
from aileen.memory.concept import ConceptMemory
from aileen.terms import fn


def _state(n: int, touching: list[tuple[int, int]]) -> tuple[list[str], State]:
    objs = [f"o{i}" for i in range(1, n + 1)]
    facts = [fn("ec" if (i, j) in touching or (j, i) in touching else "dc", a, b)
             for i, a in enumerate(objs, 1) for j, b in enumerate(objs, 1) if a != b]
    return objs, State(objects={}, held=None, facts=facts)


def test_the_group_in_contact_among_things_apart_is_the_one_taught_on() -> None:
    objs, state = _state(6, [(2, 3), (3, 5)])  # o2-o3-o5 a chain of objects in contact
    assert taught_group(objs, state) == (["o2", "o3", "o5"], 1)


def test_a_table_with_no_group_is_taken_whole_and_two_groups_are_not_told_apart() -> None:
    objs, state = _state(3, [])
    assert taught_group(objs, state) == (objs, 0)
    objs, state = _state(5, [(1, 2), (4, 5)])
    assert taught_group(objs, state) == (None, 2)


@pytest.mark.parametrize("seed", [0, 1])
def test_a_wall_taught_among_distractors_is_the_wall_not_the_table(tmp_path: Path, capsys, seed: int) -> None:
    """A wall informed with 10 distractors was learned as one example of all 13 objects
    (1228 facts), and a bare wall afterwards was "I see no 'wall'" (probe 51, v/wall-crowd.json)."""
    script = tmp_path / "wall-crowd.json"
    script.write_text(json.dumps([
        {"lesson-type": "composite-word", "content": "wall", "description": {"composite": "wall"},
         "signal": "inform", "distractors": 10},
        {"lesson-type": "composite-word", "content": "wall", "description": {"composite": "wall"}, "signal": "verify"},
    ]))
    mem = tmp_path / "m.json"
    rc = main(["run", str(script), "--seed", str(seed), "--perception", "truth", "--json", "--memory", str(mem)])
    records = [json.loads(line) for line in capsys.readouterr().out.splitlines() if line.strip()]
    assert rc == 0 and records[-1]["result"] == "success", records[-1]
    [example] = ConceptMemory.load(mem).examples("r_wall")
    assert len(set(re.findall(r"\bo\d+\b", " ".join(map(str, example))))) == 3  # the wall's boxes alone


def test_a_new_word_taken_for_a_group_says_which_objects_it_took() -> None:
    """"dax" said alone over three objects apart was learned as a word for the three together,
    with nothing said but "I do not know the word 'dax'": a teacher who meant one of them could
    not tell. The answer names the objects taken, and how to show one alone."""
    import sys

    sys.path.insert(0, str(Path(__file__).parent))
    from console_helpers import lay_out, truth_console

    _agent, con = truth_console()
    lay_out(con, "red box at 0.2 0.5", "blue cone at 0.5 0.5", "green sphere at 0.8 0.5")
    said = con.do("inform dax")
    assert "I take 'dax' to name the 3 objects on the table together (o1, o2, o3); show one alone" in said, said
    lay_out(con, "red box at 0.2 0.5")
    assert "I take" not in con.do("inform blicket")  # one object: a word for it, as ever
