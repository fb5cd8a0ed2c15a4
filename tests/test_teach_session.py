"""`aileen teach` keeps what was learned whatever ends the session, and leaves the table whole."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from console_helpers import truth_console

from aileen.errors import UserError

TEACH_MOVE = ["place red box", "inform red box", "clear", "place blue cone", "inform blue cone",
              "scene red box left of blue cone", "inform move the red box right of the blue cone"]


def _react(taught: list[str], box: str, cone: str):  # noqa: ANN202 - (console, transcript)
    """A console taught `taught`, then a red box at `box` and a blue cone at `cone` ("x y") on
    an empty table, and "react move the red box right of the blue cone": the console and what
    it printed."""
    _agent, con = truth_console()
    for line in taught:
        con.do(line)
    con.do("clear")
    con.do(f"place red box at {box}")
    con.do(f"place blue cone at {cone}")
    return con, con.do("react move the red box right of the blue cone")


def test_a_scene_with_a_relation_and_one_object_is_a_one_line_error() -> None:
    _agent, con = truth_console()
    for said in ("scene red box left of", "scene red box near"):
        with pytest.raises(UserError, match="needs a second object"):
            con.do(said)


def test_a_react_given_up_puts_the_object_back(monkeypatch) -> None:
    """No room right of a cone near the edge: the react fails after the box was picked up;
    the box goes back where it was (it stayed in the hand, off the table, before). No room is
    now seen before acting, so the box is not picked up at all; where it is found only after
    the pick-up (here: not looked for before), the box is put back."""
    from aileen.agent.acting import Acting

    con, said = _react(TEACH_MOVE, "0.6 0.5", "0.9 0.5")
    assert "failure: there is no room" in said and "acted:    nothing" in said
    assert "cv_red cv_box at (0.60, 0.50)" in con.do("show")
    monkeypatch.setattr(Acting, "_foresee", lambda self, g, goal, args: None)
    con, said = _react(TEACH_MOVE, "0.6 0.5", "0.9 0.5")
    assert "failure" in said and "pick_up(o1)" in said and "put back(o1)" in said
    assert "cv_red cv_box at (0.60, 0.50)" in con.do("show")


def _teach(lines: list[str], memory: Path, *, read_out: bool = True) -> subprocess.CompletedProcess | int:
    cmd = [sys.executable, "-m", "aileen", "teach", "--memory", str(memory), "--perception", "truth"]
    text = "\n".join(lines) + "\n"
    if read_out:
        return subprocess.run(cmd, input=text, capture_output=True, text=True, timeout=120)
    proc = subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    assert proc.stdout is not None and proc.stdin is not None
    try:
        proc.stdin.write(text)
        proc.stdin.close()
    except BrokenPipeError:
        pass
    for _ in range(8):  # `aileen teach ... | head -8`: what it prints after that, nobody reads
        proc.stdout.readline()
    proc.stdout.close()
    return proc.wait(timeout=120)


def test_what_was_learned_is_kept_when_nobody_reads_the_output(tmp_path: Path) -> None:
    memory = tmp_path / "m.json"
    # and it is no whole run: exit 141 (128 + SIGPIPE), as a signal's stop is, not 0 (more
    # output than a pipe holds, so that writing it fails)
    assert _teach(["place red box", "inform red box"] + ["show"] * 3000, memory, read_out=False) == 141
    assert {c["symbol"] for c in json.loads(memory.read_text())["concepts"]} == {"r_red", "r_box"}


def test_a_session_keeps_what_it_learned_before_a_one_line_error_and_goes_on(tmp_path: Path) -> None:
    memory = tmp_path / "m.json"
    done = _teach(["place red box", "inform red box", "scene red box left of", "clear", "place blue cone",
                   "inform blue cone"], memory)
    assert done.returncode == 2 and "<stdin>:3:" in done.stderr and "Traceback" not in done.stderr
    assert {c["symbol"] for c in json.loads(memory.read_text())["concepts"]} >= {"r_red", "r_cone"}


def test_what_the_agent_says_at_the_console_is_graded_against_the_table() -> None:
    _agent, con = truth_console()
    for line in ("place red box", "inform red box", "clear", "place blue cone", "inform blue cone",
                 "scene red box left of blue cone", "inform red box left of blue cone"):
        con.do(line)
    assert "trainer:  true of the table" in con.do("describe")
    assert "trainer:  true of the table" in con.do("verify where is the red box?")


def test_quit_in_any_letter_case_ends_the_session(tmp_path: Path) -> None:
    done = _teach(["place red box", "QUIT", "place blue cone"], tmp_path / "m.json")
    assert done.returncode == 0 and "blue cone" not in done.stdout


def test_a_scene_the_table_cannot_hold_says_how_many_distractors_it_got() -> None:
    _agent, con = truth_console()
    said = con.do("scene red box left of blue cone with 99 distractors")
    assert "note: laid out with" in said and "of 99 distractors" in said


def test_undo_takes_back_a_lesson_and_a_verdict() -> None:
    agent, con = truth_console()
    con.do("place red box")
    con.do("inform red box")
    assert agent.memory.has("r_red")
    assert "undone: inform red box" in con.do("undo")
    assert not agent.memory.has("r_red") and "no words yet" in con.do("show")
    for line in ("inform red box", "clear", "place blue cone", "inform blue cone", "clear",
                 "place red box at 0.3 0.5", "place blue cone at 0.6 0.5", "inform red box left of blue cone",
                 "clear", "place red box at 0.3 0.62", "place blue cone at 0.6 0.5"):
        con.do(line)
    con.do("verify red box left of blue cone")
    con.do("wrong")
    assert agent.memory.concept("r_left_of").near_misses
    con.do("undo")
    assert not agent.memory.concept("r_left_of").near_misses
    assert "stored r_left_of" in con.do("wrong")  # the answer it was about is back too
    con.do("undo")
    con.do("show")  # a look at the same table is no new scene: the verdict is still on its answer
    assert "stored r_left_of" in con.do("wrong")
    con.do("undo")
    con.do("place green sphere")
    assert "cv_green cv_sphere" in con.do("show")  # a changed table is seen anew: a new scene
    with pytest.raises(UserError, match="on the scene now seen"):
        con.do("wrong")
    with pytest.raises(UserError, match="nothing to undo"):
        for _ in range(20):
            con.do("undo")


def test_place_says_what_settling_moved_and_keeps_the_lesson_files_margin() -> None:
    # a teacher setting angles by hand got other angles without a word: an object put where
    # another stood was pushed clear, and pushed the other; a centre 0.055 m from the edge was
    # taken (the world's rule) and moved, where a lesson file refuses it (the trainer's rule)
    from aileen.curriculum.lessonfile import loads
    from aileen.curriculum.trainer import layout

    _agent, con = truth_console()
    assert con.do("place red box at 0.5 0.5") == "placed a red box at (0.50, 0.50)"
    said = con.do("place blue cone at 0.52 0.5")
    assert "not at (0.52, 0.50)" in said and "the medium red box was pushed to" in said
    with pytest.raises(UserError, match=r"is off the table: a medium object needs its centre at least 0\.060 m"):
        con.do("place green box at 0.055 0.5")
    lesson = loads('[[lesson]]\nsignal = "inform"\ncontent = "green box"\n'
                   'objects = [{shape = "box", colour = "green", position = [0.055, 0.5]}]\n', "x.toml").lessons[0]
    with pytest.raises(UserError, match=r"is off the table: a medium object needs its centre at least 0\.060 m"):
        layout(lesson, seed=0)
    with pytest.raises(UserError, match="expected 'at X Y': two numbers"):
        con.do("place red box at 0.5")


def test_an_answer_names_the_relation_as_the_teacher_said_it() -> None:
    # "touching" is read as next to; the answer said "I do not know the word 'next to'" and
    # "'next to' does not hold", a word the teacher never used
    _agent, con = truth_console()
    con.do("place red box at 0.3 0.5")
    con.do("place blue cone at 0.6 0.5")
    assert "I do not know the word 'touching'" in con.do("verify red box touching blue cone")
    assert "'next to'" not in con.do("verify red box touching blue cone")
    said = con.do("verify is the red box to the left of the blue cone?")
    assert "I do not know the word 'left of'" in said  # its own word where the teacher's says it


def test_a_react_moving_an_object_beside_itself_says_it_cannot() -> None:
    _agent, con = truth_console()
    for line in ("place red box", "inform red box", "clear", "place blue cone", "inform blue cone", "clear",
                 "scene red box left of blue cone", "inform red box left of blue cone",
                 "clear", "place red box at 0.7 0.5", "place blue cone at 0.5 0.5",
                 "inform move the red box left of the blue cone", "clear",
                 "place red box at 0.3 0.5", "place blue cone at 0.7 0.5"):
        con.do(line)
    said = con.do("react move the red box left of the red box")
    assert "the red box cannot be left of itself" in said  # it said "the sentence asks for no action"
    con.do("clear")
    con.do("place red box at 0.7 0.5")
    con.do("place blue cone at 0.07 0.5")  # nothing fits between it and the table's edge
    assert "there is no room left of the blue cone for the red box (" in con.do(
        "react move the red box left of the blue cone")


def test_a_wrong_that_leaves_the_answer_yes_says_so() -> None:
    # told `wrong` on the very scene "left of" was taught on, the agent said "learned: stored
    # r_left_of" and answered yes again, leaving the teacher to wonder what was learned
    _agent, con = truth_console()
    for line in ("place red box", "inform red box", "clear", "place blue cone", "inform blue cone", "clear",
                 "place red box at 0.3 0.5", "place blue cone at 0.5 0.5", "inform red box left of blue cone"):
        con.do(line)
    assert "success" in con.do("verify red box left of blue cone")
    said = con.do("wrong")
    assert said.startswith("learned: stored r_left_of (the answer would still be yes here")


def test_a_react_whose_goal_holds_already_leaves_the_table_as_it_is() -> None:
    # the agent picked the red box up and put it down again beside where it stood
    _agent, con = truth_console()
    for line in ("place red box", "inform red box", "clear", "place blue cone", "inform blue cone", "clear",
                 "place red box at 0.3 0.5", "place blue cone at 0.5 0.5", "inform red box left of blue cone",
                 "clear", "place red box at 0.7 0.5", "place blue cone at 0.5 0.5",
                 "inform move the red box left of the blue cone", "clear",
                 "place red box at 0.25 0.52", "place blue cone at 0.55 0.5"):
        con.do(line)
    said = con.do("react move the red box left of the blue cone")
    assert "success: it is so already: nothing to do" in said and "acted:    nothing" in said
    # the table as it was: the box where it stood
    assert "cv_red cv_box at (0.25, 0.52)" in con.do("show")


def test_a_react_that_does_not_reach_its_goal_names_what_does_not_hold(monkeypatch) -> None:
    # a hand that does nothing: the goal's facts do not hold after acting, and the answer says
    # which (the check of the goal after acting is one function, `Acting._missing`)
    from aileen.agent.acting import Acting

    agent, con = truth_console()
    for line in ("place red box", "inform red box", "clear", "place blue cone", "inform blue cone", "clear",
                 "place red box at 0.3 0.5", "place blue cone at 0.5 0.5", "inform red box left of blue cone",
                 "clear", "place red box at 0.7 0.5", "place blue cone at 0.5 0.5",
                 "inform move the red box left of the blue cone", "clear",
                 "place red box at 0.7 0.52", "place blue cone at 0.45 0.5"):
        con.do(line)
    monkeypatch.setattr(Acting, "execute", lambda self, step, body: self.agent.perceive(body.look()))
    said = con.do("react move the red box left of the blue cone")
    assert "failure: after acting, the goal does not hold: " in said and "(o1,o2)" in said, said


def test_a_lesson_shows_the_table_before_the_action_and_a_react_is_graded() -> None:
    """The transcript's "saw:" is the table the agent saw before acting (it showed the table
    after, the goal looking true already), and a react gets the trainer's verdict, as in a
    lesson file's run."""
    _con, said = _react(TEACH_MOVE, "0.3 0.5", "0.6 0.5")
    assert "cv_red cv_box at (0.30, 0.50)" in said.split("saw:", 1)[1].splitlines()[0]
    assert "trainer:  the goal holds" in said


def test_a_demonstration_whose_goal_holds_already_is_refused() -> None:
    _agent, con = truth_console()
    con.do("place red box at 0.8 0.5")
    con.do("place blue cone at 0.3 0.5")
    with pytest.raises(UserError, match="the red box is already right of the blue cone"):
        con.do("inform move red box right of blue cone")
    # `scene` of an action lays out its start, not its goal
    said = con.do("scene move red box right of blue cone")
    box, cone = (tuple(float(v) for v in line.split("(")[1].split(")")[0].split(", ")) for line in said.splitlines()[:2])
    assert box[0] < cone[0] + 0.05 or abs(box[1] - cone[1]) > abs(box[0] - cone[0])


def test_an_object_placed_where_another_stands_is_pushed_clear() -> None:
    _agent, con = truth_console()
    con.do("place red box at 0.3 0.3")
    said = con.do("place blue box at 0.3 0.3")
    assert "pushed clear" in said
    seen = con.do("show").splitlines()[0]
    assert "cv_red cv_box" in seen and "cv_blue cv_box" in seen


def test_looking_does_not_move_the_scenes_the_trainer_lays_out() -> None:
    _a, one = truth_console()
    _b, two = truth_console()
    two.do("show")
    two.do("place red box")
    two.do("show")
    two.do("clear")
    assert one.do("scene red box right of blue cone") == two.do("scene red box right of blue cone")


def test_words_after_a_bare_command_are_refused_and_undo_takes_a_count() -> None:
    _agent, con = truth_console()
    for said in ("clear the table please", "show me", "help me", "quit now", "wrong it was", "undo x", "undo 0"):
        with pytest.raises(UserError):
            con.do(said)
    for line in ("place red box", "inform red box", "clear", "place blue cone", "inform blue cone"):
        con.do(line)
    said = con.do("undo 2")
    assert "undone: inform blue cone" in said and "undone: inform red box" in said
    assert "knows: no words yet" in con.do("show")
    with pytest.raises(UserError, match="only 0|nothing to undo"):
        con.do("undo 1")


def test_an_unknown_verb_is_named_alone() -> None:
    """One verb for every relation: "I do not know the word 'move'", not 'move right of'."""
    _con, said = _react(TEACH_MOVE[:5], "0.3 0.5", "0.6 0.5")
    assert "I do not know the word 'move'" in said and "'move right of'" not in said


def test_a_known_verb_with_an_unknown_relation_names_the_relation() -> None:
    """"move" learned, "right of" never taught: it said "I do not know the word 'move'" (the
    original's scripts' reacts over relations they had not taught were graded as wrong)."""
    _agent, con = truth_console()
    for line in ("place red box at 0.3 0.5", "inform red box", "clear", "place blue cone at 0.6 0.5",
                 "inform blue cone", "place red box at 0.3 0.5", "inform move red box behind blue cone"):
        con.do(line)
    said = con.do("verify move red box right of blue cone")
    assert "I do not know the word 'right of'" in said and "'move'" not in said


def test_confirm_after_a_react_that_missed_its_goal_is_refused() -> None:
    _agent, con = truth_console()
    con.do("scene red box left of blue cone")
    assert "the goal does NOT hold" in con.do("react move red box right of blue cone")
    with pytest.raises(UserError, match="did not see it reached"):
        con.do("confirm")


def test_a_demonstration_the_trainer_cannot_do_is_said_in_the_consoles_words() -> None:
    """It printed the lesson file's bookkeeping: "<teach>: demonstration step 2 (place(1)
    [right of 2]): no free spot right of obj2 on the table" (the browser console named the
    objects: both say it one way now, `curriculum.plain`)."""
    _agent, con = truth_console()
    con.do("place red box at 0.3 0.5")
    con.do("place blue cone at 0.93 0.5")
    with pytest.raises(UserError) as err:
        con.do("inform move red box right of blue cone")
    said = err.value.format()
    assert "the blue cone" in said and not any(x in said for x in ("<teach>", "obj2", "demonstration step"))


def test_a_scene_of_a_verb_without_its_relation_is_refused() -> None:
    """"scene move red box" laid out a lone red box."""
    _agent, con = truth_console()
    with pytest.raises(UserError, match="as the start of 'move'"):
        con.do("scene move red box")
    with pytest.raises(UserError, match="'describe' takes nothing"):
        con.do("describe the table")


def test_it_with_one_object_on_the_table_is_that_object() -> None:
    """"it is a purple cone" over a purple cone alone, the last lesson about a purple box no
    longer on the table: "I do not see what 'it' was on this table; I see no 'purple cone'"."""
    _agent, con = truth_console()
    for line in ("place red box", "inform red box", "clear", "place purple cone", "inform purple cone", "clear",
                 "place purple box", "inform that is a purple box", "clear", "place purple cone"):
        con.do(line)
    said = con.do("verify it is a purple cone")
    assert "success" in said and "what 'it' was" not in said
    for line in ("clear", "place red box", "place blue cone"):  # two, neither the one talked about
        con.do(line)
    assert "I do not see what 'it' was" in con.do("verify it is a red box")


RIGHT = ["place red box at 0.3 0.5", "inform red box", "clear", "place blue cone at 0.6 0.5", "inform blue cone",
         "clear", "place red box at 0.5 0.7", "place blue cone at 0.5 0.5", "inform red box behind blue cone",
         "clear", "place red box at 0.52 0.7", "place blue cone at 0.5 0.5", "inform red box behind blue cone",
         "clear", "place red box at 0.7 0.62", "place blue cone at 0.5 0.5"]


def test_right_lets_a_no_stand_and_keeps_the_scene_as_a_near_miss() -> None:
    """A lesson file's verdict on a right "no" stores the scene as a near miss of the relation;
    `aileen teach` had no way to say the answer was right."""
    agent, con = truth_console()
    for line in RIGHT:
        con.do(line)
    assert "does not hold" in con.do("verify red box behind blue cone")
    assert "stored r_behind" in con.do("right")
    assert len(agent.memory.concept("r_behind").near_misses) == 1
    with pytest.raises(UserError, match="'right' needs a verify answer"):
        con.do("right")  # one verdict per answer


@pytest.mark.parametrize("line,says", [
    ("place red box at nan nan", "expected 'at X Y' with finite numbers in metres, got (nan, nan)"),
    ("scene red box with -1 distractors", "expected 'with N distractors', N a whole number >= 0 (got '-1')"),
])
def test_a_bad_number_in_a_table_command_says_what_was_expected(line: str, says: str) -> None:
    """nan said "position (nan, nan) and angle 0.0 must be finite" (no angle was given); -1
    distractors "cannot lay out 'red box with -1 distractors'"."""
    _agent, con = truth_console()
    with pytest.raises(UserError) as refused:
        con.do(line)
    assert refused.value.message == says


def test_objects_alike_pushed_by_a_placement_are_told_apart_by_where_they_stood() -> None:
    """"the medium red box was pushed to ..." twice, with no way to tell which box was which."""
    _agent, con = truth_console()
    con.do("place red box at 0.3 0.5")
    con.do("place red box at 0.35 0.5")
    said = con.do("place red box at 0.3 0.5")
    assert said.count("the medium red box at (") == 2


def test_save_to_a_file_another_run_holds_says_what_the_console_can_do(tmp_path: Path) -> None:
    """`save PATH` on a held file advised "use another --memory file": the console saves to a PATH."""
    from aileen.memory.store import MemoryFile

    _agent, con = truth_console()
    with MemoryFile.open(tmp_path / "held.json"), pytest.raises(UserError) as e:
        con.do(f"save {tmp_path / 'held.json'}")
    assert "in use by another aileen run" in e.value.message and "save to another file" in e.value.message
    assert "--memory" not in e.value.message


@pytest.mark.parametrize("end", ["quit", None])
def test_quit_and_the_end_of_input_say_where_the_memory_was_saved(tmp_path: Path, capsys, monkeypatch, end) -> None:
    """`quit` or the end of input saved the memory without a word on where (`save` and a stop say it)."""
    import io

    from aileen.cli import main

    memory = tmp_path / "m.json"
    lines = ["place red box", "inform red box"] + ([end] if end else [])
    monkeypatch.setattr("sys.stdin", io.StringIO("\n".join(lines) + "\n"))
    assert main(["teach", "--memory", str(memory), "--perception", "truth"]) == 0
    err = capsys.readouterr().err
    assert err.endswith(f"aileen teach: what was learned is saved in {memory}\n")
    assert {c["symbol"] for c in json.loads(memory.read_text())["concepts"]} == {"r_red", "r_box"}


def test_save_to_a_hard_link_of_the_held_memory_file_saves_there(tmp_path: Path) -> None:
    """`save hl.json`, a hard link to the session's own --memory file, met the session's own
    lock on that file and was refused as "in use by another aileen run"."""
    import os

    from aileen.memory.concept import ConceptMemory
    from aileen.memory.store import MemoryFile

    mem = tmp_path / "m.json"
    ConceptMemory().save(mem)
    os.link(mem, tmp_path / "hl.json")
    agent, con = truth_console()
    with MemoryFile.open(mem) as held:
        con.memory_file = held
        con.do("place red box")
        con.do("inform red box")
        assert con.do(f"save {tmp_path / 'hl.json'}") == f"saved 2 concepts to {mem}"
    assert {c.symbol for c in ConceptMemory.load(mem).concepts()} == {"r_red", "r_box"}


def test_a_scene_with_a_slip_says_what_was_meant() -> None:
    """`scene red box lef of blue cone` said only that it could not lay it out, where a lesson
    file's relation asks "did you mean 'left of'?" (probe p6)."""
    import pytest as _pytest
    from console_helpers import truth_console

    from aileen.errors import UserError

    _agent, con = truth_console()
    for said, meant in (("red box lef of blue cone", "left of"), ("red box left of bleu cone", "blue")):
        with _pytest.raises(UserError, match=f"did you mean '{meant}'"):
            con.do(f"scene {said}")
    with _pytest.raises(UserError) as refused:
        con.do("scene red box zorp blue cone")
    assert "did you mean" not in refused.value.message
    # a word of the teacher's own is named, with how to show it (probe p51a: it was not)
    assert "the trainer does not know 'zorp'" in refused.value.message and "place red box at" in refused.value.message


def test_a_tab_after_the_command_word_is_a_space() -> None:
    """q24: "verify<TAB>the red box ..." was the unknown command 'verify\\tthe'."""
    _agent, con = truth_console()
    con.do("place\tred box")
    assert "created r_red, r_box" in con.do("inform\tred box")
    said = con.do("verify\t the red box")
    assert "verify" in said and "success" in said
    assert con.changes_memory("inform\tred box")
