"""Actions in Soar (issue 24): demonstrations recorded as epmem episodes and recalled by the
agent's rules, action concepts stored and recognised through the output-link, and react
carried out by projecting, planning and one `^act` command per step. The Soar agent is held to
the ASP agent with the same mechanisms off (`PAPER_LEARNER`), lesson by lesson."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

pytest.importorskip("soar_sml")

from aileen.cli import main  # noqa: E402
from aileen.memory.concept import ConceptMemory  # noqa: E402
from aileen.soar.learner import AGENT_DIR, PAPER_LEARNER, PAPER_SENSES  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
LESSONS = ROOT / "lessons"
WITHOUT = [a for m in PAPER_LEARNER for a in ("--without", m)] + ["--senses", PAPER_SENSES]
KEYS = ("signal", "content", "result", "reason", "referents", "created", "stored", "seen", "expected", "correct",
        "steps", "projections", "goal_holds")


def _run(capsys, files: list[Path], *args: str) -> list[dict]:
    rc = main(["run", *map(str, files), "--json", *args])
    assert rc in (0, 1)
    return [json.loads(line) for line in capsys.readouterr().out.splitlines() if line.strip()]


@pytest.mark.parametrize("files", [
    [LESSONS / "visual.toml", LESSONS / "spatial.toml", LESSONS / "action.toml"],
    [LESSONS / "push.toml"],
], ids=["move", "push"])
def test_the_soar_agent_learns_and_acts_as_the_paper_learner_in_asp(capsys, tmp_path, files) -> None:
    """The Done-when check: the same answer for every lesson of the action and push files (with
    the shipped vision), the same steps when it acts, and the same concepts learned."""
    asp_mem, soar_mem = tmp_path / "asp.json", tmp_path / "soar.json"
    asp = _run(capsys, files, *WITHOUT, "--memory", str(asp_mem))
    soar = _run(capsys, files, "--agent", "soar", "--memory", str(soar_mem))
    assert len(asp) == len(soar) > 0
    for a, s in zip(asp, soar):
        assert {k: a.get(k) for k in KEYS} == {k: s.get(k) for k in KEYS}, a["content"]
    # it learned actions, recognised them, told a wrong one apart, and carried them out
    actions = [r for r in soar if r["content"].startswith(("move", "push"))]
    assert any(c.startswith(("r_move", "r_push")) for r in actions for c in r["created"])
    assert any(r["signal"] == "verify" and r["correct"] and r["result"] == "failure" for r in actions)
    reacts = [r for r in soar if r["signal"] == "react"]
    assert reacts and all(r["goal_holds"] and r["correct"] and r["steps"] for r in reacts)
    # the memory a Soar run saved loads, and is what the ASP agent learned (up to the order of
    # an example's facts and the numbering of a generalization's entities)
    assert _learned(ConceptMemory.load(soar_mem)) == _learned(ConceptMemory.load(asp_mem))


def _learned(mem: ConceptMemory) -> dict:
    out = {}
    for c in mem.to_dict()["concepts"]:
        gens = [(g["examples"], sorted((re.sub(r"gen_ent\(\d+,", "gen_ent(_,", f["fact"]), f["count"])
                                       for f in g["facts"])) for g in c["generalizations"]]
        out[c["symbol"]] = (c["kind"], sorted(gens), sorted(sorted(ex) for ex in c["examples"]))
    return out


def _agent_on(lesson_text: str, tmp_path: Path, rules: Path | None = None):  # noqa: ANN202
    from aileen.curriculum.formats import load_curriculum
    from aileen.curriculum.interpreter import Interpreter
    from aileen.perception.truth import TruthVision
    from aileen.soar.learner import SoarAgent

    f = tmp_path / "l.toml"
    f.write_text(lesson_text)
    cur = load_curriculum(f)
    vision = TruthVision()
    agent = SoarAgent(perceiver=vision, rules=rules)
    interp = Interpreter(agent, on_frame=vision.see_frame)
    return agent, [interp.run(lesson, index=i + 1, seed=cur.lesson_seed(i)) for i, lesson in enumerate(cur.lessons)]


PUSH = """
[[lesson]]
signal = "inform"
content = "red box"
objects = ["red box"]
[[lesson]]
signal = "inform"
content = "blue cone"
objects = ["blue cone"]
[[lesson]]
signal = "inform"
content = "push the red box"
objects = ["red box", "blue cone"]
demonstration = "auto"
[[lesson]]
signal = "react"
content = "push the blue cone"
objects = ["blue cone", "red box"]
"""


def test_each_perceived_state_is_one_episode_and_react_goes_through_the_output_link(tmp_path) -> None:
    agent, results = _agent_on(PUSH, tmp_path)
    with agent:
        stats = agent.kernel.command("epmem --stats")
        stored = int(re.search(r"Time:\s+(\d+)", stats).group(1)) - 1
        assert stored == len(agent.episodic)  # one episode per state the agent perceived
        assert [r.answer.result for r in results] == ["failure", "failure", "failure", "success"]
        assert results[2].answer.created == ["r_push"] and results[2].answer.stored == ["r_push"]
        react = results[3]
        assert react.goal_holds and react.answer.steps == ["push(o1)"]
        # nothing piles up: each command was removed once its answer was taken (^status
        # complete), and its answer with it
        assert agent.bridge.answers() == []
        assert [a for a, _ in agent.kernel.output() if a in ("concept-memory", "act")] == []
        served = [s.command for s in agent.served]
        # the react lesson's commands: unary queries, then a projection each time; the plans
        # are the agent's own (plan.soar), so no `plan` command
        assert served.count("project") == react.answer.projections >= 1
        assert "plan" not in served
        # the push example is the recalled trace: two time points, the object moved, its percepts
        (example,) = agent.memory.examples("r_push")
        assert {"isa(t0,start)", "after(t1,t0)", "h(t1,moved(o1))", "r_push(o1)", "isa(o1,cv_red)"} <= set(example)


def test_the_recall_rules_decide_what_an_action_example_holds(tmp_path) -> None:
    """Break one rule of episodes.soar (it no longer copies one-argument facts from an
    episode): the push example loses `moved(o1)` and react cannot carry the push out."""
    rules = tmp_path / "rules"
    rules.mkdir()
    text = (AGENT_DIR / "episodes.soar").read_text()
    broken = re.sub(r"sp \{aileen\*apply\*recall\*fact\*unary.*?\)\}\n", "", text, flags=re.S)
    assert broken != text
    (rules / "episodes.soar").write_text(broken)
    agent, results = _agent_on(PUSH, tmp_path, rules)
    with agent:
        (example,) = agent.memory.examples("r_push")
        assert "h(t1,moved(o1))" not in example and "after(t1,t0)" in example
        assert not results[3].goal_holds and not results[3].answer.steps


def _agent_with(lesson_text: str, tmp_path: Path, **kw):  # noqa: ANN202
    from aileen.curriculum.formats import load_curriculum
    from aileen.curriculum.interpreter import Interpreter
    from aileen.perception.truth import TruthVision
    from aileen.soar.learner import SoarAgent

    f = tmp_path / "l.toml"
    f.write_text(lesson_text)
    cur = load_curriculum(f)
    vision = TruthVision()
    agent = SoarAgent(perceiver=vision, **kw)
    return agent, Interpreter(agent, on_frame=vision.see_frame), cur


def test_a_repeated_react_lesson_is_done_by_the_rules_chunking_learned(tmp_path) -> None:
    """The first time, each word is looked up in a substate and the plan searched for in one;
    chunking learns from them, so the same lesson again goes without any impasse: the learned
    rules give the meanings and the plan, and the agent does the same."""
    agent, interp, cur = _agent_with(PUSH, tmp_path)
    with agent:
        results = [interp.run(lesson, index=i + 1, seed=cur.lesson_seed(i)) for i, lesson in enumerate(cur.lessons)]
        react = cur.lessons[-1]
        assert results[-1].goal_holds and results[-1].answer.steps == ["push(o1)"]
        learned, fired = agent.kernel.chunks()
        impasses = agent.kernel.counts.impasses
        again = interp.run(react, index=5, seed=cur.lesson_seed(3))
        assert again.goal_holds and again.answer.steps == ["push(o1)"]
        assert agent.kernel.counts.impasses == impasses  # no substate: no lookup, no search
        assert agent.kernel.chunks()[0] == learned and agent.kernel.chunks()[1] > fired
        chunks = agent.kernel.command("print --chunks")
        assert "take-meaning" in chunks and "return-plan" in chunks


def test_neither_chunking_nor_the_planner_changes_what_the_agent_does(tmp_path) -> None:
    """The agent that learns rules and plans for itself, and the one that does neither (clingo's
    plans, served as the `plan` command): the same answers, stores and steps."""
    def run(name: str, **kw) -> tuple[list[tuple], list[str]]:  # noqa: ANN003
        (tmp_path / name).mkdir()
        agent, interp, cur = _agent_with(PUSH + PUSH_AGAIN, tmp_path / name, **kw)
        with agent:
            out = []
            for i, lesson in enumerate(cur.lessons):
                r = interp.run(lesson, index=i + 1, seed=cur.lesson_seed(i))
                out.append((r.answer.result, r.answer.reason, r.answer.created, r.answer.stored, r.answer.steps,
                            r.goal_holds))
            served = [s.command for s in agent.served]
        return out, served

    plain, plain_served = run("plain", planner="clingo", chunking=False)
    own, own_served = run("own")
    assert own == plain and own[-1][4] == ["push(o1)"]
    assert "plan" in plain_served and "plan" not in own_served


PUSH_AGAIN = """
[[lesson]]
signal = "react"
content = "push the red box"
objects = ["red box", "blue cone"]
"""
