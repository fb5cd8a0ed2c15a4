"""Declarations of a user's own, named in `AILEEN_DOMAIN`, reach every command (in a child
process: a declaration lasts for its process, and the shipped domain must stay as it is here)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from aileen.domain import extensions
from aileen.errors import UserError

ROOT = Path(__file__).resolve().parents[1]

TEXTURE = '''
import numpy as np
from aileen.domain import channels


def stripes(value, canvas):
    if value == "striped":
        canvas.bright = canvas.bright * np.where(np.sin(canvas.X * 12.0) > 0, 0.45, 1.0)


def measure(image, detection, camera):
    return "plain", 1.0


channels.declare(channels.Channel("texture", ("plain", "striped"), measure, render=stripes, default="plain"))
'''

LESSONS = '''
[[lesson]]
signal = "inform"
content = "striped red box"
objects = ["striped red box"]
[[lesson]]
signal = "verify"
content = "striped box"
objects = [{shape = "box", colour = "red", texture = "striped"}]
'''


def _lessons(seed: int, rows: list[tuple[str, str, str, str]]) -> str:
    """A lesson file: (signal, content, objects as TOML, extra lines) per lesson."""
    return f"seed = {seed}\n" + "".join(
        f'[[lesson]]\nsignal = "{signal}"\ncontent = "{content}"\nobjects = {objects}\n{extra}'
        for signal, content, objects, extra in rows)


def _aileen(*args: str, domain: str, cwd: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, extensions.ENV: domain, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    return subprocess.run([sys.executable, "-m", "aileen", *args], capture_output=True, text=True, env=env,
                          cwd=cwd, timeout=300)


def test_a_channel_declared_in_a_file_of_ones_own_reaches_the_commands(tmp_path: Path) -> None:
    (tmp_path / "texture.py").write_text(TEXTURE)
    (tmp_path / "striped.toml").write_text(LESSONS)
    run = _aileen("render", "--seed", "1", "--objects", "2", "--out", "r.png", domain="./texture.py", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    assert run.stdout.splitlines()[1].split()[:5] == ["id", "shape", "colour", "size", "texture"]
    run = _aileen("run", "striped.toml", "--perception", "truth", domain=str(tmp_path / "texture.py"), cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    assert "cv_striped" in run.stdout and "learned:  created r_striped" in run.stdout
    # without it, "striped" is no value the trainer knows: the file is refused at its line
    run = _aileen("run", "striped.toml", "--perception", "truth", domain="", cwd=tmp_path)
    assert run.returncode == 2 and "striped.toml:" in run.stderr


@pytest.mark.parametrize("source,says", [
    ("import no_such_module_here\n",
     "cannot load './bad.py' (line 1): ModuleNotFoundError: No module named 'no_such_module_here'"),
    ("raise ValueError('half done')\n", "cannot load './bad.py' (line 1): ValueError: half done"),
    # a Python error inside one's module names its line there (the last frame in the file)
    ("from aileen.domain import channels\n\nchannels.declare(channels.Chanel('material', ('wood',), 'x:y'))\n",
     "cannot load './bad.py' (line 3): AttributeError: module 'aileen.domain.channels' has no attribute 'Chanel'"),
    ("from aileen.domain import actions\nactions.declare(\n    actions.PrimitiveAction('nudge', ('nudge',), 'tuoch', None, "
     "None, 'nudge N'))\n", "cannot load './bad.py' (line 2): ValueError: action nudge: kind must be one of"),
    ("from aileen.domain import channels\nchannels.declare(channels.Channel('colour', ('red',), 'x.y'))\n",
     "'./bad.py': "),
    # names the rest of the tool cannot read: a traceback, a clingo variable, never read, a
    # message that contradicts itself
    ("from aileen.domain import relations\nrelations.declare(relations.distance('2 steps from', 0.0, 0.1, (0.05, 0.1), (0.2, 0.3)))\n",
     "relation '2 steps from': a relation's name and spellings are lowercase words"),
    ("from aileen.domain import relations\nrelations.declare(relations.distance('Aside', 0.0, 0.1, (0.05, 0.1), (0.2, 0.3)))\n",
     "relation 'Aside'"),
    ("from aileen.domain import relations\nrelations.declare(relations.distance('pres de', 0.0, 0.1, (0.05, 0.1), (0.2, 0.3), "
     "aliases=('pr\u00e8s de',)))\n", "relation 'pr\u00e8s de'"),
    ("from aileen.domain import channels\n"
     "channels.declare(channels.Channel('finish', ('matte', 'Glossy'), lambda i, d, c: ('matte', 1.0)))\n",
     "channel 'finish': 'Glossy' must be lowercase"),
    # words the readers read otherwise: a traceback from clingo, a verb's or a shape's concept
    # taking spatial examples, "two red box" read as two boxes
    ("from aileen.domain import relations\nrelations.declare(relations.distance('not', 0.0, 0.1, (0.05, 0.1), "
     "(0.2, 0.3)))\n", "relation 'not': a word of the grammar or a verb"),
    ("from aileen.domain import relations\nrelations.declare(relations.distance('box', 0.0, 0.1, (0.05, 0.1), "
     "(0.2, 0.3)))\n", "relation 'box': it is what an object looks like"),
    ("from aileen.domain import channels\n"
     "channels.declare(channels.Channel('finish', ('matte', 'two'), lambda i, d, c: ('matte', 1.0)))\n",
     "channel 'finish': 'two' is a word of the grammar"),
    ("from aileen.domain import channels\n"
     "channels.declare(channels.Channel('finish', ('matte', 'cone'), lambda i, d, c: ('matte', 1.0)))\n",
     "channel 'finish': percept cv_cone is already a shape"),
])
def test_a_module_that_fails_is_one_line_and_exit_2(tmp_path: Path, source: str, says: str) -> None:
    (tmp_path / "bad.py").write_text(source)
    run = _aileen("render", "--seed", "1", "--out", "r.png", domain="./bad.py", cwd=tmp_path)
    assert run.returncode == 2 and "Traceback" not in run.stderr
    line = run.stderr.strip()
    assert line.startswith("aileen: AILEEN_DOMAIN: ") and says in line and len(line.splitlines()) == 1, line


def test_names_are_read_once_and_a_missing_file_is_named() -> None:
    assert extensions.load("") == []
    assert extensions.load("json, os.path") == ["json", "os.path"]  # importable names, each once
    assert extensions.load("json") == []
    with pytest.raises(UserError) as missing:
        extensions.load("nowhere/x.py")
    # named once: it said "AILEEN_DOMAIN: 'nowhere/x.py': AILEEN_DOMAIN: no such Python file ..."
    assert missing.value.message == "AILEEN_DOMAIN: 'nowhere/x.py': no such Python file"


LIFT = '''
from aileen.domain import actions

actions.declare(actions.Verb("lift", ("pick_up",), lambda out: out.objects[0].held))
'''


def test_a_verb_that_ends_with_the_object_in_the_hand_teaches_no_word_of_what_is_in_view(tmp_path: Path) -> None:
    """"lift the red box", demonstrated, ends with the box held, out of view: the blue cone,
    the only object in view, was taken for the red box and taught as one (a blue cone was then
    a "red box"). The object in the hand is remembered as it looked."""
    (tmp_path / "lift.py").write_text(LIFT)
    (tmp_path / "lift.toml").write_text(_lessons(12, [
            ("inform", "red box", '["red box"]', ""),
            ("inform", "blue cone", '["blue cone"]', ""),
            ("inform", "lift the red box", '["red box", "blue cone"]', 'demonstration = "auto"\n'),
            ("verify", "red box", '["blue cone"]', 'expect = "failure"\n'),
            ("react", "lift the red box", '["red box", "blue cone"]', ""),
        ]))
    run = _aileen("run", "lift.toml", "--perception", "truth", domain="./lift.py", cwd=tmp_path)
    assert run.returncode == 0, run.stdout + run.stderr
    taught = run.stdout.split("lesson  3")[1].split("lesson  4")[0]
    assert "stored r_lift" in taught and "r_red" not in taught and "r_box" not in taught
    assert "verify 1/1 right" in run.stdout and "react 1/1 reached the goal" in run.stdout


NUDGE = '''
import math
from pathlib import Path
from aileen.domain import actions


def _nudge(world, obj, position, onto):
    side = world.get(obj).footprint
    world.push(obj, math.sqrt(2.0 * world.physics.mu_table * world.physics.g * side), 0.0)
    return world.settle()


actions.declare(
    actions.Fluent("nudged", 1, actions.DEED, "the hand has just nudged O"),
    actions.PrimitiveAction("nudge", ("nudge",), actions.TOUCH, None, _nudge, "nudge N",
                            adds=("moved", "nudged"), dels=(actions.REL,), model=Path(__file__).parent / "nudge.lp"),
    actions.Verb("nudge", ("nudge",), actions.slid(1.0, 0.0), actions.room_ahead(1.0, 0.0)),
)
'''

NUDGE_MODEL = '''#program base.
action(nudge(O)) :- obj(O).
moves(nudge(O),O) :- action(nudge(O)).
#program step(t).
poss(nudge(O),t) :- action(nudge(O)), not busy(t-1), not holds(held(O),t-1), not stacked(O,t-1).
add(moved(O),t) :- occurs(nudge(O),t).
add(nudged(O),t) :- occurs(nudge(O),t)
del(rel(P,O,X),t) :- occurs(nudge(O),t), holds(rel(P,O,X),t-1), not static(P).
del(rel(P,X,O),t) :- occurs(nudge(O),t), holds(rel(P,X,O),t-1), not static(P).
'''


@pytest.mark.parametrize("model,says", [
    (NUDGE_MODEL, "nudge.lp:8:1: error: syntax error"),
    (NUDGE_MODEL.replace("add(nudged(O),t) :- occurs(nudge(O),t)\n", ""), "nudge adds nudged in "),
])
def test_a_declared_action_model_that_is_wrong_stops_the_run_before_any_lesson(tmp_path: Path, model: str,
                                                                              says: str) -> None:
    """A broken model file of one's own was each react's "failure" (graded, exit 1), and a
    model missing an effect named aileen/domain/actions.py for the user's declaration."""
    (tmp_path / "nudge.py").write_text(NUDGE)
    (tmp_path / "nudge.lp").write_text(model)
    (tmp_path / "l.toml").write_text('[[lesson]]\nsignal = "inform"\ncontent = "red box"\nobjects = ["red box"]\n')
    run = _aileen("run", "l.toml", "--perception", "truth", domain="./nudge.py", cwd=tmp_path)
    assert run.returncode == 2 and says in run.stderr and "lesson  1" not in run.stdout, run.stderr
    assert "aileen/domain/actions.py" not in run.stderr and run.stderr.count("\n") == 1


def test_a_calculus_of_ones_own_is_declared_in_ones_own_module(tmp_path: Path) -> None:
    """The recipe said to edit calculi.py; rebinding CALCULI from one's own module worked only
    when it ran before perception was imported (its tables were built at import). Declared
    after the import, its relation is perceived, learned, and placed by a react."""
    data = ROOT / "tests" / "data"
    run = _aileen("run", str(data / "level_with.toml"), "--perception", "truth",
                  domain=str(data / "align_calculus.py"), cwd=tmp_path)
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr
    assert "al_row" in run.stdout and "react 2/2 reached the goal" in run.stdout


def test_an_object_in_the_hand_stays_in_mind_from_lesson_to_lesson_in_teach(tmp_path: Path) -> None:
    """In `aileen teach` every lesson began a new scene and forgot the object in the hand:
    "lift the blue cone" after "lift the red box" was "already holding the red box", and
    "where is the red box?" while it was held a KeyError."""
    (tmp_path / "lift.py").write_text(LIFT)
    script = "\n".join([
        "place red box at 0.3 0.5", "inform red box", "clear", "place blue cone at 0.6 0.5", "inform blue cone",
        "place red box at 0.3 0.5", "inform lift the red box", "clear",
        "place red box at 0.3 0.5", "place blue cone at 0.6 0.5", "react lift the red box",
        "verify where is the red box?", "react lift the blue cone"]) + "\n"
    env = {**os.environ, extensions.ENV: "./lift.py", "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    run = subprocess.run([sys.executable, "-m", "aileen", "teach", "--perception", "truth"], input=script,
                         capture_output=True, text=True, env=env, cwd=tmp_path, timeout=300)
    assert run.returncode == 0 and "Traceback" not in run.stderr, run.stdout[-1500:] + run.stderr
    assert "'red box' is in my hand, not on the table" in run.stdout
    last = run.stdout.split('react   "lift the blue cone"')[1]
    assert "answer:   success" in last and "already holding" not in last


def test_a_spelling_that_starts_with_an_article_is_read_in_the_bare_form() -> None:
    """"red box a short way from blue cone" read "box" as a relation before "a"."""
    from aileen.domain import relations
    from aileen.reasoning.language import parse

    with relations.kept():
        relations.declare(relations.distance("short way from", 0.6, 2.0, (0.9, 1.5), (4.2, 5.5),
                                             aliases=("a short way from",)))
        p = parse("red box a short way from blue cone")
        assert [o.words for o in p.objects] == [("red", "box"), ("blue", "cone")]
        assert [r.word for r in p.relations] == ["short_way_from"]


def test_an_error_inside_a_verbs_goal_of_ones_own_is_one_line_and_what_was_learned_is_saved(tmp_path: Path) -> None:
    """A goal test raising AttributeError was a traceback and exit 1, and the memory learned
    before it was lost (no memory file written)."""
    (tmp_path / "nudge.py").write_text(NUDGE.replace("actions.slid(1.0, 0.0)", "lambda out: out.nosuch"))
    (tmp_path / "nudge.lp").write_text(NUDGE_MODEL.replace("occurs(nudge(O),t)\n", "occurs(nudge(O),t).\n"))
    (tmp_path / "l.toml").write_text(_lessons(7, [
            ("inform", "red box", '["red box"]', ""),
            ("inform", "nudge the red box", '["red box", "blue cone"]', 'demonstration = "auto"\n'),
            ("react", "nudge the red box", '["red box", "blue cone"]', ""),
        ]))
    run = _aileen("run", "l.toml", "--perception", "truth", "--memory", "m.json", domain="./nudge.py", cwd=tmp_path)
    assert run.returncode == 2 and "Traceback" not in run.stderr, run.stderr
    line = run.stderr.strip()
    assert len(line.splitlines()) == 1, line
    assert "verb 'nudge': its goal " in line and "nudge.py:" in line and "failed: AttributeError" in line, line
    assert line.endswith("what was learned is saved in m.json") and (tmp_path / "m.json").is_file()
