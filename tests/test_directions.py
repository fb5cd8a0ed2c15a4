"""The agent's sense of direction (four cones by default, the paper's 8 sectors with
`--without cones`) and the verb's start contrast: one demonstration of "move" covers every
start."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from dataclasses import dataclass

from hypothesis import assume, given, settings
from hypothesis import strategies as st

from aileen.agent import Agent, AgentParams, verbs
from aileen.curriculum.interpreter import Interpreter
from aileen.curriculum.lesson import ActionSpec, Lesson, ObjectSpec
from aileen.domain import calculi
from aileen.world.geometry import CARDINALS, CONES, cardinal, cone
from aileen.perception.regions import sample_region
from aileen.perception.truth import TruthVision
from aileen.terms import parse
from aileen.world.camera import Table

REF = (0.45, 0.45, 0.55, 0.55)


def at(bearing_deg: float, r: float = 0.25, s: float = 0.1) -> tuple[float, float, float, float]:
    """A box of side s whose centre lies r from REF's centre, at the compass bearing (0 north,
    90 east) *from* it."""
    x = 0.5 + r * math.sin(math.radians(bearing_deg))
    y = 0.5 + r * math.cos(math.radians(bearing_deg))
    return (x - s / 2, y - s / 2, x + s / 2, y + s / 2)


@given(st.floats(-44.0, 44.0), st.sampled_from([(0, "cone_n"), (90, "cone_e"), (180, "cone_s"), (270, "cone_w")]))
def test_a_cone_spans_45_degrees_either_side_of_its_axis(off: float, axis: tuple[int, str]) -> None:
    assert cone(at(axis[0] + off), REF) == axis[1]


@given(st.floats(0.0, 360.0), st.floats(0.12, 0.4))
def test_cones_are_converse_and_coarsen_the_sectors(bearing: float, r: float) -> None:
    # (exactly on a diagonal, the cone's edge, rounding decides each way on its own)
    assume(abs(math.remainder(bearing - 45.0, 90.0)) > 1e-6)
    a = at(bearing, r)
    c = cone(a, REF)
    assert c in CONES
    assert calculi.CONE.converse_of(c) == cone(REF, a)
    # an axis sector lies inside its cone
    sector = cardinal(a, REF)
    if sector in ("n", "e", "s", "w"):
        assert c == f"cone_{sector}"


def test_an_agent_perceives_one_direction_calculus() -> None:
    assert [c.name for c in calculi.senses("cones")].count("cone") == 1
    assert "cdc" not in [c.name for c in calculi.senses("cones")]
    assert "cone" not in [c.name for c in calculi.senses("sectors")]
    assert AgentParams().directions == "all" and AgentParams(senses_of_direction="sectors").directions == "sectors"
    with pytest.raises(ValueError, match="expected one of cones, sectors"):
        calculi.senses("compass")


@pytest.mark.parametrize("cones", [True, False])
def test_the_agents_facts_follow_its_sense(cones: bool) -> None:
    v = TruthVision()
    agent = Agent(params=AgentParams(seed=0, senses_of_direction="cones" if cones else "sectors"), perceiver=v)
    interp = Interpreter(agent, on_frame=v.see_frame)
    interp.run(Lesson("inform", "red box left of blue cone", [ObjectSpec("box", "red"), ObjectSpec("cone", "blue")],
                      relation="left of"), index=1, seed=3)
    names = {f.name for f in agent.state.facts}
    if cones:
        assert "cone_w" in names and not names & set(CARDINALS)
    else:
        assert "w" in names and not names & set(CONES)


@pytest.mark.parametrize("pred", CONES)
def test_regions_sample_inside_a_cone(pred: str) -> None:
    rng = np.random.default_rng(4)
    boxes = {"o2": REF}
    for _ in range(10):
        x, y = sample_region(0.1, [parse(f"{pred}(o1,o2)"), parse("dc(o1,o2)")], boxes, Table(), rng)
        assert cone((x - 0.05, y - 0.05, x + 0.05, y + 0.05), REF) == pred


def test_the_start_contrast_replaces_only_what_the_action_changed() -> None:
    trace = [parse(x) for x in (
        "isa(t0,start)", "h(t0,cone_n(o1,o2))", "h(t0,cone_s(o2,o1))", "h(t0,dc(o1,o2))", "h(t0,qd_far(o1,o2))",
        "after(t1,t0)", "h(t1,held(o1))",
        "after(t2,t1)", "h(t2,cone_w(o1,o2))", "h(t2,cone_e(o2,o1))", "h(t2,dc(o1,o2))")]
    explained = [parse("cone_w(o1,o2)"), parse("cone_e(o2,o1)"), parse("dc(o1,o2)")]
    a, b = parse("o1"), parse("o2")
    out = {str(f) for f in verbs.slotted(trace, explained, a, b)}
    assert "h(t0,not_said_rel(o1,o2))" in out and "h(t2,said_rel(o1,o2))" in out
    assert not {"h(t0,cone_n(o1,o2))", "h(t0,cone_s(o2,o1))", "h(t2,cone_w(o1,o2))"} & out
    assert "h(t0,dc(o1,o2))" in out  # unchanged: still there at the end
    assert "h(t0,qd_far(o1,o2))" not in out  # it started far; where it started is no part of "move"
    plain = {str(f) for f in verbs.slotted(trace, explained, a, b, contrast=False)}
    assert "h(t0,cone_n(o1,o2))" in plain and not any("not_said_rel" in f for f in plain)


def _after_one_demonstration(params: AgentParams) -> Interpreter:
    v = TruthVision()
    agent = Agent(params=params, perceiver=v)
    interp = Interpreter(agent, on_frame=v.see_frame)
    for i, (c, s) in enumerate((("red", "box"), ("blue", "cylinder"), ("green", "cone"), ("yellow", "sphere"))):
        interp.run(Lesson("inform", f"{c} {s}", [ObjectSpec(s, c)]), index=i, seed=i)
    a, b = ObjectSpec("box", "red"), ObjectSpec("cylinder", "blue")
    for i, rel in enumerate(("left of", "right of", "behind", "in front of")):
        interp.run(Lesson("inform", f"red box {rel} blue cylinder", [a, b], relation=rel), index=10 + i, seed=10 + i)
    # "move" shown once, from a start behind the reference
    interp.run(Lesson("inform", "move the red box left of the blue cylinder", [a, b], relation="behind",
                      action=ActionSpec("move", "left of")), index=20, seed=20)
    return interp


@pytest.mark.parametrize("contrast", [True, False])
def test_one_demonstration_of_move_covers_other_starts(contrast: bool) -> None:
    interp = _after_one_demonstration(AgentParams(seed=0, start_contrast=contrast))
    g, y = ObjectSpec("cone", "green"), ObjectSpec("sphere", "yellow")
    right = []
    for i, (start, goal) in enumerate((("in front of", "right of"), ("right of", "behind"), ("left of", "in front of"))):
        r = interp.run(Lesson("verify", f"move the green cone {goal} the yellow sphere", [g, y], relation=start,
                              action=ActionSpec("move", goal)), index=30 + i, seed=30 + i)
        right.append(r.answer.result == "success")
    if contrast:
        assert all(right)
    else:
        assert not all(right)  # the start it was shown from is part of the verb


@pytest.mark.parametrize("exclusive", [True, False])
def test_a_known_direction_word_keeps_its_side_out_of_a_new_relation(exclusive: bool) -> None:
    """Mutual exclusivity over relations: "far from" shown with the box on some side of the
    cone, once the four directions are known, is not about that side. The example keeps the
    side it was seen on (the word's examples together say whether its sides are a
    coincidence: `Directions.explained`); the word is read as holding on every side."""
    v = TruthVision()
    agent = Agent(params=AgentParams(seed=0, mutual_exclusivity=exclusive), perceiver=v)
    interp = Interpreter(agent, on_frame=v.see_frame)
    a, b = ObjectSpec("box", "red"), ObjectSpec("cone", "blue")
    interp.run(Lesson("inform", "red box", [a]), index=0, seed=0)
    interp.run(Lesson("inform", "blue cone", [b]), index=1, seed=1)
    for i, rel in enumerate(("left of", "right of", "behind", "in front of")):
        interp.run(Lesson("inform", f"red box {rel} blue cone", [a, b], relation=rel), index=2 + i, seed=2 + i)
    interp.run(Lesson("inform", "red box far from blue cone", [a, b], relation="far from"), index=9, seed=9)
    example = {parse(f).name for f in agent.memory.examples("r_far_from")[0]}
    assert "qd_far" in example and example & set(CONES)
    # one example's side is chance: with exclusivity "far from" says no side, without it one
    assert (agent.directions.region("r_far_from") is None) == exclusive


def test_converse_words_are_not_each_others_parts() -> None:
    """"larger than" and "smaller than" hold the same size facts with the roles swapped: neither
    is a conjunction of the other, so both leave their side to the direction words
    (`Directions.explained`), as "near" does; none of them is tied to the side its
    examples happened to lie on."""
    v = TruthVision()
    agent = Agent(params=AgentParams(seed=0), perceiver=v)
    interp = Interpreter(agent, on_frame=v.see_frame)
    a, b = ObjectSpec("box", "red"), ObjectSpec("cone", "blue")
    for k, size in enumerate(("small", "medium", "large")):  # the phrases name any size
        interp.run(Lesson("inform", "red box", [ObjectSpec("box", "red", size=size)]), index=0, seed=20 + k)
        interp.run(Lesson("inform", "blue cone", [ObjectSpec("cone", "blue", size=size)]), index=1, seed=30 + k)
    for i, rel in enumerate(("left of", "right of", "behind", "in front of")):
        interp.run(Lesson("inform", f"red box {rel} blue cone", [a, b], relation=rel), index=2 + i, seed=2 + i)
    for i, rel in enumerate(("larger than", "smaller than", "near")):
        interp.run(Lesson("inform", f"red box {rel} blue cone", [a, b], relation=rel), index=9 + i, seed=9 + i)
    for word in ("r_larger_than", "r_smaller_than", "r_near"):
        assert agent.directions.marked_word(word), word
        assert agent.directions.explained(word), word


@dataclass
class _Body:
    box_m: tuple[float, float, float, float]
    footprint: float = 0.04
    level: int = 0


@settings(max_examples=300, deadline=None)
@given(st.floats(0.0, 359.999), st.floats(0.1, 0.4))
def test_the_finest_grain_nests_in_every_coarser_one(angle: float, r: float) -> None:
    """Each grain's region holds the direction it names, and the finest sector holding a
    direction lies inside the 16-sector, the 8-sector and the cone region holding it (so each
    coarser region is a run of the finest sectors; regions read from the declarations, never
    from names)."""
    # (a direction exactly on an edge goes to either side, as each calculus rounds it)
    assume(abs(math.remainder(angle, 360.0 / 64)) > 1e-6)
    b = _Body((0.5 - 0.02, 0.5 - 0.02, 0.5 + 0.02, 0.5 + 0.02))
    x, y = 0.5 + r * math.cos(math.radians(angle)), 0.5 + r * math.sin(math.radians(angle))
    a = _Body((x - 0.02, y - 0.02, x + 0.02, y + 0.02))
    spans = []
    for c in calculi.DIRECTIONS["all"]:
        rel = c.compute(a, b)
        centre, width = c.regions[rel]
        spans.append((centre, width))
        off = abs(math.remainder(angle - centre, 360.0))
        assert off <= width / 2 + 1e-6, (c.name, rel, angle)
    fine_c, fine_w = min(spans, key=lambda s: s[1])
    for centre, width in spans:
        assert abs(math.remainder(fine_c - centre, 360.0)) + fine_w / 2 <= width / 2 + 1e-6


def test_all_senses_perceive_every_grain() -> None:
    names = [c.name for c in calculi.senses("all")]
    assert {"cone", "cdc", "d16", "d64"} <= set(names)
    assert AgentParams(senses_of_direction="all").extents
    assert not AgentParams(senses_of_direction="all", size_principle=False).extents
    assert AgentParams().extents and not AgentParams(senses_of_direction="cones").extents


def _placed(signal: str, word: str, degrees: float, metres: float, pair: int, expect: str | None = None) -> str:
    """A lesson with the first object `metres` from the second at `degrees` (east 0, counter-clockwise)."""
    import math

    a, b = (("red box", "blue cone"), ("green sphere", "yellow box"), ("purple cylinder", "red sphere"))[pair % 3]
    x, y = 0.5 + metres * math.cos(math.radians(degrees)), 0.5 + metres * math.sin(math.radians(degrees))
    (ca, sa), (cb, sb) = a.split(), b.split()
    out = (f'[[lesson]]\nsignal = "{signal}"\ncontent = "{a} {word} {b}"\n'
           f'objects = [{{ shape = "{sa}", colour = "{ca}", position = [{x:.3f}, {y:.3f}] }}, '
           f'{{ shape = "{sb}", colour = "{cb}", position = [0.5, 0.5] }}]\n')
    return out + (f'expect = "{expect}"\n' if expect else "")


def _graded(tmp_path: Path, capsys, memory: Path, seed: int, lessons: list[str]) -> list[tuple[str, str]]:  # noqa: ANN001
    """Run `lessons` (one file, `seed`) on `memory` with ground-truth vision: each verify's
    (result, expected)."""
    import json

    from aileen.cli import main

    path = tmp_path / "lessons.toml"
    path.write_text(f"seed = {seed}\n" + "".join(lessons))
    capsys.readouterr()
    main(["run", str(path), "--perception", "truth", "--memory", str(memory), "--json"])
    records = [json.loads(line) for line in capsys.readouterr().out.splitlines() if line.startswith("{")]
    return [(r["result"], r["expected"]) for r in records if r["signal"] == "verify"]


@pytest.mark.parametrize("after", ["visual", "spatial"])
def test_a_word_shown_close_by_on_one_side_keeps_that_side_once_direction_words_are_known(
        tmp_path, capsys, after: str) -> None:
    """"jlo of" shown five times close by on the left: once "left of" is known (before it, or
    taught after it), it still holds close by on the left only. Its examples' sides were
    taken from it ("left of" says the side), or it kept two of five and chance explained
    them; it held close by in front, behind and on the right (probe p51a)."""
    from aileen.cli import main

    shipped = Path(__file__).resolve().parents[1] / "lessons"
    memory = tmp_path / "m.json"
    files = [shipped / "visual.toml"] + ([shipped / "spatial.toml"] if after == "spatial" else [])
    main(["run", *map(str, files), "--perception", "truth", "--memory", str(memory)])
    lessons = [_placed("inform", "jlo of", d, m, k) for k, (d, m) in
               enumerate(((176, 0.13), (184, 0.125), (179, 0.135), (187, 0.13), (172, 0.128)))]
    if after == "visual":
        lessons.append(_placed("inform", "right of", 0, 0.25, 0))
    lessons += [_placed("verify", "jlo of", d, 0.13, 0, e)
                for d, e in ((180, "success"), (0, "failure"), (270, "failure"), (90, "failure"))]
    graded = _graded(tmp_path, capsys, memory, 7, lessons)
    assert graded == [("success", "success")] + [("failure", "failure")] * 3


def test_a_wrong_on_the_side_its_examples_leave_open_is_about_the_side(tmp_path, capsys) -> None:
    """"zup of" shown 0.2 m apart on every side but behind (a three-quarter word), told `wrong`
    straight behind at 0.2 m: behind is not the word's. Its examples' sides alone say little
    (six points leave such a gap by chance), and the near miss lay in the band five of them
    lie in, at its end, so it was read as about distance (outside with 1/6) and dropped: the
    agent said yes straight behind again. Its side explains it better (probe p52)."""
    from aileen.cli import main

    shipped = Path(__file__).resolve().parents[1] / "lessons"
    memory = tmp_path / "m.json"
    main(["run", str(shipped / "visual.toml"), "--perception", "truth", "--memory", str(memory)])
    lessons = [_placed("inform", "zup of", d, 0.2, k) for k, d in enumerate((0, 170, 200, 260, 300, 340, 20))]
    lessons.append(_placed("verify", "zup of", 90, 0.2, 1, "failure") + 'feedback = "wrong"\n')
    lessons += [_placed("verify", "zup of", d, 0.2, 2, e)
                for d, e in ((90, "failure"), (110, "failure"), (225, "success"), (150, "success"))]
    graded = _graded(tmp_path, capsys, memory, 3, lessons)[1:]
    assert graded == [("failure", "failure")] * 2 + [("success", "success")] * 2
