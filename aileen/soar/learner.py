"""The paper's learner as a Soar agent, behind the same methods the lesson interpreter calls.

Perception is the shipped visual module (detector, colour, QSR, object tracking) and the
body is `aileen.agent.body`, as for the ASP agent: each perceived state goes onto the input-link
(`perception.py`) and is recorded as one episode in Soar's episodic memory; the sentence,
parsed by syntax alone (`aileen.reasoning.language`), goes there with its signal. Everything
else is Soar productions (`agent/*.soar`): word meanings from smem (each word in its own
substate), demonstrations recalled from epmem, grounding through concept-memory queries,
comprehension, learning on failure with create and store, acting (project, a plan searched for
by the agent's own operators over its action models, one `^act` command per step, which the host
carries out with the ASP agent's body), the answer; chunking compiles word lookups and one-step
plans into rules.

The agent is the paper's learner: it has none of the mechanisms `PAPER_LEARNER` names (the
ASP agent with `--without` each of them is the same learner; the tests hold them to the same
answers).
"""

from __future__ import annotations

import os
import tempfile
from collections import deque
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from aileen.agent import Agent, AgentParams, Answer
from aileen.agent.acting import step_text
from aileen.agent.records import not_understood
from aileen.errors import UserError
from aileen.memory.concept import ConceptMemory
from aileen.memory.semantic import SemanticMemory
from aileen.reasoning import language, planner
from aileen.soar import domainlink, wm
from aileen.soar import smem as smemdb
from aileen.soar.smem import smem_path
from aileen.soar.answers import answer_of
from aileen.soar.bridge import ConceptMemoryBridge, Served
from aileen.soar.kernel import SoarKernel, WMNode
from aileen.soar.perception import SceneLink
from aileen.terms import Term

AGENT_DIR = Path(__file__).parent / "agent"
RULE_FILES: tuple[str, ...] = ("lesson.soar", "words.soar", "episodes.soar", "ground.soar", "commands.soar",
                               "comprehend.soar", "learn.soar", "act.soar", "plan.soar", "answer.soar")
#: Who searches for a react lesson's plans: the agent's own operators (`agent/plan.soar`), or
#: the ASP agent's planner (clingo) served as the `plan` command.
PLANNERS = domainlink.PLANNERS
#: The ASP agent's mechanisms the Soar agent does not have: the ASP agent `--without` each of
#: them is the paper's learner, the same agent as this one.
PAPER_LEARNER: tuple[str, ...] = ("mutual-exclusivity", "syntactic-bootstrapping", "weak-comprehension",
                                  "disjunctive-concepts", "one-verb", "start-contrast")
#: The paper's learner's one sense of direction (no extents: memory/extent.py is the ASP
#: agent's); the ASP agent `--senses` this and `--without` each of `PAPER_LEARNER` is this agent.
PAPER_SENSES = "cones"
MAX_DECISIONS = 20_000  # decision cycles per run of the agent before it is declared stuck
MAX_ACTS = 60  # primitive actions per react lesson (6 projections x plans of at most 6 steps, and more)
SERVED_LIMIT = 10_000  # the latest commands kept in `SoarAgent.served`
EPMEM_EXCLUDED = ("task", "concept-memory", "lesson", "answer", "act", "domain")  # not part of an episode
PLAN_DEPTH = AgentParams().plan_depth  # the deepest plan searched for, as the ASP agent's


def rule_paths(rules: str | os.PathLike[str] | None = None) -> list[Path]:
    """The shipped productions, each replaced by a file of the same name in `rules`. A `.soar`
    file in `rules` that replaces none of them is refused (it would be silently ignored)."""
    if rules is not None:
        own = sorted(p.name for p in Path(rules).glob("*.soar"))
        unknown = [n for n in own if n not in RULE_FILES]
        if unknown:
            raise UserError(f"--rules: {', '.join(unknown)} replaces no rule file of the Soar agent; the rule files "
                            f"are {', '.join(RULE_FILES)}", path=str(Path(rules) / unknown[0]))
    out = []
    for name in RULE_FILES:
        own_file = Path(rules) / name if rules is not None else None
        out.append(own_file if own_file is not None and own_file.is_file() else AGENT_DIR / name)
    return out


class SoarAgent:
    """A Soar agent with aileen's concept memory on its output-link (see docs/soar.md).
    Use it as a context manager, or call `close()`: the kernel is shut down either way.

    `smem`: Soar's semantic memory database to start from (beside the memory file, see
    `smem_path`), copied so the file itself changes only when `save` writes it; `listen`: a
    port for Soar's debugger or CLI to attach to; `planner`: `soar` (the agent searches for
    its plans, `agent/plan.soar`) or `clingo` (the ASP agent's planner, as the `plan`
    command); `chunking`: Soar's chunking learns from the substates that ask for it (a word's
    meaning, a one-step plan; see docs/soar.md)."""

    def __init__(self, memory: ConceptMemory | None = None, *, perceiver: Any = None,
                 rules: str | os.PathLike[str] | None = None, seed: int = 0,
                 smem: str | os.PathLike[str] | None = None, listen: int | None = None,
                 planner: str = "soar", chunking: bool = True) -> None:
        self.memory = memory if memory is not None else ConceptMemory()
        if planner not in PLANNERS:
            raise UserError(f"planner must be one of {', '.join(PLANNERS)}, not {planner!r}")
        paths = rule_paths(rules)
        # The eyes and the hand: the shipped visual module, tracker and body, shared with the ASP agent.
        self.eyes = Agent(self.memory, params=AgentParams(mutual_exclusivity=False, syntactic_bootstrapping=False,
                                                          weak_comprehension=False, disjunctive_concepts=False,
                                                          one_verb=False, start_contrast=False, seed=seed,
                                                          senses_of_direction=PAPER_SENSES),
                          perceiver=perceiver)
        self._tmp = tempfile.TemporaryDirectory(prefix="aileen-smem-")
        self.kernel = SoarKernel(listen=listen)
        try:
            smemdb.open_smem(self.kernel, self.memory, Path(self._tmp.name) / "smem.sqlite",
                             Path(smem) if smem is not None else None)
            self.kernel.command("epmem --set learning on")
            self.kernel.command("epmem --set trigger none")  # one episode per perceived state (`_record`)
            self.kernel.command("epmem --set phase selection")  # stored after the input phase that brings it
            for attr in EPMEM_EXCLUDED:
                self.kernel.command(f"epmem --set exclusions {attr}")
            self.kernel.command(f"srand {int(seed) % (1 << 31)}")  # Soar's own choices (among indifferent operators)
            # learn only where a rule asks for it (force-learn): a word's meaning, a one-step plan
            self.kernel.command("chunk only" if chunking else "chunk never")
            domainlink.put_domain(self.kernel, planner=planner, plan_depth=PLAN_DEPTH)
            for path in paths:
                self.kernel.source(path)
            self.bridge = ConceptMemoryBridge(self.kernel, self.memory)
            self.scene = SceneLink(self.kernel)
            self._lesson: Any = None
            self._lessons = 0
            self._answer: WMNode | None = None
            self._acts: list[WMNode] = []
            self._semantic: SemanticMemory | None = None
            self.served: deque[Served] = deque(maxlen=SERVED_LIMIT)  # the latest commands the bridge executed
            self.kernel.on_output("answer", self._on_answer)
            self.kernel.on_output("act", self._on_act)
        except BaseException:
            self.close()
            raise

    # ------------------------------------------------------------------ lifecycle
    def close(self) -> None:
        kernel = getattr(self, "kernel", None)
        if kernel is not None:
            kernel.close()
        self._tmp.cleanup()

    def __enter__(self) -> "SoarAgent":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def save(self, path: str) -> None:
        """The concept memory to `path`, Soar's semantic memory to `smem_path(path)` (each file
        whole or not at all)."""
        self.memory.save(path)
        smemdb.backup(self.kernel, smem_path(path))

    # ------------------------------------------------------------------ what the interpreter reads
    @property
    def semantic(self) -> SemanticMemory:
        """The word maps, read from Soar's semantic memory."""
        if self._semantic is None:
            words = smemdb.words(self.kernel)
            self._semantic = SemanticMemory.from_dict({w: {"concept": c, "kind": k} for w, (c, k) in words.items()})
        return self._semantic

    @property
    def episodic(self):  # noqa: ANN201 - aileen.memory.episodic.EpisodicMemory
        return self.eyes.episodic

    @property
    def state(self):  # noqa: ANN201
        return self.eyes.state

    @property
    def held(self) -> str | None:
        return self.eyes.held

    @held.setter
    def held(self, value: str | None) -> None:
        self.eyes.held = value

    # ------------------------------------------------------------------ perceiving
    def new_scene(self) -> None:
        self.eyes.new_scene()
        self.scene.clear()

    def perceive(self, image: np.ndarray, action: Term | None = None):  # noqa: ANN201
        state = self.eyes.perceive(image, action=action)
        self._record()
        return state

    def describe_scene(self) -> list[str]:
        return self.eyes.describe_scene()

    def locate(self, u: float, v: float) -> str:
        return self.eyes.locate(u, v)

    def watch(self, action: str, u: float | None, v: float | None, image: np.ndarray) -> None:
        self.eyes.watch(action, u, v, image)
        self._record()

    def episode_now(self) -> int:
        return self.eyes.episode_now()

    def _record(self, run: bool = True) -> None:
        """The state just perceived onto the input-link, and into epmem as one episode (its
        scene's ^time is the episode index, so the agent can recall it)."""
        assert self.eyes.state is not None
        self.scene.update(self.eyes.state, self.eyes.episode_now())
        self.kernel.command("epmem --set force remember")
        if run:  # the episode is stored in this decision (the agent has nothing to do: it waits)
            self.kernel.run(1)

    # ------------------------------------------------------------------ signals
    def inform(self, content: str, *, demo_start: int | None = None) -> Answer:
        return self._lesson_run("inform", content, demo_start)

    def verify(self, content: str, *, demo_start: int | None = None) -> Answer:
        return self._lesson_run("verify", content, demo_start)

    def react(self, content: str, body: Any) -> Answer:
        """Carry out an action sentence: the Soar agent projects, plans and acts through its
        output-link; each `^act` command is done here with the body, as the ASP agent does it."""
        self.perceive(body.look())
        return self._lesson_run("react", content, self.eyes.episode_now(), body)

    def generate(self, content: str = "") -> Answer:
        # no answer it could give: not understood, counted apart (it was a "failure" the
        # summary left out, exit 0)
        return not_understood("generate", content, "the Soar agent does not generate sentences yet "
                                                   "(the ASP agent does: --agent asp)")

    def told_wrong(self, answer: Answer) -> None:
        raise UserError("the Soar agent does not learn from the trainer's verdicts ('wrong') yet; "
                        "use the ASP agent (--agent asp)")

    def told_right(self, answer: Answer) -> None:
        """A verify answer the trainer lets stand: the Soar agent learns from no verdict
        (`told_wrong` says so); a right answer needs nothing from it."""

    def confirmed(self, answer: Answer) -> None:
        raise UserError("the Soar agent does not learn from the trainer's verdicts ('confirm') yet; "
                        "use the ASP agent (--agent asp)")

    def _lesson_run(self, signal: str, content: str, trace_start: int | None, body: Any = None) -> Answer:
        assert self.eyes.state is not None, "perceive before a lesson"
        try:
            p = language.parse(content)
        except language.NotUnderstood as exc:  # (in `teach` it was an error line, exit 2)
            return not_understood(signal, content, exc.message)
        beyond = beyond_soar(p)
        if beyond is not None:  # never an answer it did not reach: not understood, not graded
            return not_understood(signal, content,
                                  f"the Soar agent does not read {beyond} yet (the ASP agent does: --agent asp)")
        self._lessons += 1
        self._semantic = None  # smem may change in this lesson
        self.kernel.pump()
        self._put_lesson(signal, content, p, trace_start, demonstration=signal != "react" and trace_start is not None)
        self._answer, self._acts = None, []
        self.bridge.serve()  # anything served before this lesson is not this lesson's
        steps: list[str] = []
        answer_node = None
        error: str | None = None
        for _ in range(MAX_ACTS + 1):
            self.kernel.run(MAX_DECISIONS)
            if self._acts:
                act, self._acts = self._acts[0], []
                if body is None or len(steps) >= MAX_ACTS:
                    self.kernel.mark(act, "error")
                    error = "the Soar agent acted outside a react lesson" if body is None else \
                        f"the Soar agent did more than {MAX_ACTS} steps"
                    break
                try:
                    step = self._step(act)
                    self.eyes.acting.execute(step, body)
                except (UserError, wm.MalformedFact, KeyError) as exc:
                    self.kernel.mark(act, "error")
                    error = exc.message if isinstance(exc, UserError) else f"cannot carry out {act.name}: {exc}"
                    break
                steps.append(step_text(step))
                self.kernel.mark(act, "complete")
                self._record(run=False)  # stored in the next decision, as the agent goes on
                continue
            answer_node = self._answer
            break
        served = self.bridge.serve()
        self.served.extend(served)
        if error is not None:
            out = Answer(signal, content, "failure", error)
            out.steps = steps
            return out
        if answer_node is None:  # only rules of one's own (--rules) can leave the agent stuck
            raise UserError(f"the Soar agent gave no answer to {content!r} (check its rules)")
        answer = answer_of(signal, content, p, answer_node, served)
        answer.steps = steps
        if signal == "react":
            answer.projections = sum(1 for s in served if s.command == "project")
            if answer_node.get("finished") is not None:  # it acted to the end: does the goal hold?
                answer.goal_holds = not answer_node.all("unmet")
        return answer

    def _on_answer(self, node: WMNode) -> None:
        if node.get("lesson-id") == self._lessons and node.get("result") is not None:
            self._answer = node
            self.kernel.mark(node)  # read: the agent removes it (commands.soar)
            self.kernel.stop()

    def _on_act(self, node: WMNode) -> None:
        self._acts.append(node)
        self.kernel.stop()

    @staticmethod
    def _step(act: WMNode) -> planner.PlanStep:
        """An `^act` command as the plan step the body carries out."""
        if act.error:
            raise wm.MalformedFact(act.error)
        step = act.get("step")
        if not isinstance(step, WMNode) or step.get("action") is None:
            raise wm.MalformedFact("an ^act with no ^step (^action, ^relation ...)")
        action = wm.fact(step.get("action"))
        rels = [(r.get("rank") if isinstance(r, WMNode) else None, wm.fact(r)) for r in step.all("relation")]
        rels.sort(key=lambda x: (x[0] if isinstance(x[0], int) else 1 << 30, str(x[1])))
        return planner.PlanStep(action, [r for _k, r in rels])

    def _put_lesson(self, signal: str, content: str, p: language.Parse, trace_start: int | None,
                    demonstration: bool) -> None:
        k = self.kernel
        if self._lesson is not None:
            k.remove(self._lesson)
        lesson = self._lesson = k.add(k.input_link, "lesson")
        k.add(lesson, "id", self._lessons)
        k.add(lesson, "signal", signal)
        k.add(lesson, "content", content)
        if trace_start is not None:
            k.add(lesson, "trace-start", trace_start)
        if demonstration:
            k.add(lesson, "demonstration", "yes")
        order = 0
        for ref in p.objects:
            ph = k.add(lesson, "phrase")
            k.add(ph, "id", ref.id)
            k.add(ph, "text", ref.text)
            for i, w in enumerate(ref.words, 1):
                order += 1
                wd = k.add(ph, "word")
                k.add(wd, "name", w)
                k.add(wd, "index", i)
                k.add(wd, "prev", i - 1)
                k.add(wd, "order", order)
        if p.relation is not None:
            order += 1
            r = k.add(lesson, "relation")
            k.add(r, "id", p.relation.id)
            k.add(r, "word", p.relation.word)
            k.add(r, "arg1", p.relation.arg1)
            k.add(r, "arg2", p.relation.arg2)
            k.add(r, "order", order)
        if p.action is not None:
            order += 1
            a = k.add(lesson, "action")
            k.add(a, "id", p.action.id)
            k.add(a, "word", p.action.word)
            k.add(a, "verb", p.action.verb)
            if p.action.relation is not None:
                k.add(a, "relation", p.action.relation)
            k.add(a, "arg1", p.action.arg1)
            if p.action.arg2 is not None:
                k.add(a, "arg2", p.action.arg2)
            k.add(a, "order", order)
        k.commit()


def _check_senses(memory: ConceptMemory) -> None:
    """A memory whose words hold relations the paper's learner does not perceive (taught by
    the ASP agent with every grain of direction: `d16_*`, `d64_*`, distance bands) is refused:
    the Soar agent answered from it silently wrong (2 of 5 right where the ASP agent got 5)."""
    from aileen.domain import calculi

    seen = {c.name for c in calculi.senses(PAPER_SENSES)}
    for concept in memory.concepts():
        for description in memory.descriptions(concept.symbol):
            for fact in description:
                calc = calculi.calculus_of(str(fact.name))
                if calc is not None and calc.name not in seen:
                    raise UserError(f"the memory's {concept.symbol} holds {fact}, a relation of '{calc.name}', which "
                                    f"the Soar agent, the paper's learner, does not perceive (it sees the cones): it "
                                    f"was taught by the ASP agent with --senses all; teach the Soar agent anew, or "
                                    f"use --agent asp")


def beyond_soar(p: language.Parse) -> str | None:
    """What of a sentence the Soar agent's input-link does not carry (its phrases and relations
    only), said as the teacher would, or None: it answered "the red box is not left of the
    blue cone" as if "not" were not there, learned "left of" from it, and said yes to "are
    there two boxes?" over one box, to "every box ..." and to "A and B are left of C"."""
    if any(r.negated for r in p.relations):
        return "'not'"
    if any(o.count is not None or o.plural or o.quantifier is not None for o in p.objects):
        return "numbers, plurals or 'every', 'all', 'both'"
    if len(p.relations) > 1 or (p.action is None and len(p.objects) > 2):
        return "'and' between things or relations"
    if p.mood == "where":
        return "'where' questions"
    return None


def soar_agent(memory: ConceptMemory | None, *, without: Sequence[str] = (), perceiver: Any = None,
               rules: str | None = None, seed: int = 0, memory_path: str | os.PathLike[str] | None = None,
               listen: int | None = None, planner: str = "soar") -> SoarAgent:
    """The Soar agent for `aileen run --agent soar` (it has none of the mechanisms `--without`
    names). `memory_path`: the memory file, whose smem database (`smem_path`) it starts from."""
    from aileen.agent.records import ablation_params

    ablation_params(without)  # an unknown name is still an error
    if memory is not None:
        _check_senses(memory)
    if without:  # (it ran as without them, and nothing said so)
        raise UserError(f"--without switches off the asp agent's mechanisms; the Soar agent, the paper's learner, "
                        f"has none of them (--without {without[0]})")
    if rules is not None and not Path(rules).is_dir():
        raise UserError("--rules must be a directory of .soar files", path=str(rules))
    smem = smem_path(memory_path) if memory_path is not None else None
    return SoarAgent(memory, perceiver=perceiver, rules=rules, seed=seed, smem=smem, listen=listen, planner=planner)
