"""The paper's learner as a Soar agent, behind the same methods the lesson interpreter calls.

Perception is the shipped visual module (detector, colour, QSR, object tracking) and the
body is `aileen.agent.body`, as for the ASP agent: each perceived state goes onto the input-link
(`perception.py`); the sentence, parsed by syntax alone (`aileen.reasoning.language`), goes
there with its signal. Everything else is Soar productions (`agent/*.soar`): word meanings
from smem, grounding through concept-memory queries, comprehension, learning on failure
with create and store, the answer. The agent implements neither mutual exclusivity nor
syntactic bootstrapping (the paper's learner had neither), and it does not act yet: action
words (epmem traces, project, plans) are not in its productions.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from aileen.agent import Agent, AgentParams, Answer
from aileen.agent.grounding import reason_text
from aileen.errors import UserError
from aileen.memory.concept import ConceptMemory
from aileen.memory.semantic import SemanticMemory, from_concepts
from aileen.reasoning import language
from aileen.soar.bridge import ConceptMemoryBridge, Served
from aileen.soar.kernel import SoarKernel, WMNode
from aileen.soar.perception import SceneLink
from aileen.terms import Term

AGENT_DIR = Path(__file__).parent / "agent"
RULE_FILES: tuple[str, ...] = ("lesson.soar", "words.soar", "ground.soar", "comprehend.soar", "learn.soar",
                               "answer.soar")
REASONS: tuple[str, ...] = ("unknown_word", "no_referent", "ambiguous", "relation_false")
MAX_ROUNDS = 200  # output-link rounds per lesson before the agent is declared stuck


def rule_paths(rules: str | os.PathLike[str] | None = None) -> list[Path]:
    """The shipped productions, each replaced by a file of the same name in `rules`."""
    out = []
    for name in RULE_FILES:
        own = Path(rules) / name if rules is not None else None
        out.append(own if own is not None and own.is_file() else AGENT_DIR / name)
    return out


class SoarAgent:
    """A Soar agent with aileen's concept memory on its output-link (see docs/soar.md).
    Use it as a context manager, or call `close()`: the kernel is shut down either way."""

    def __init__(self, memory: ConceptMemory | None = None, *, perceiver: Any = None,
                 rules: str | os.PathLike[str] | None = None, seed: int = 0) -> None:
        self.memory = memory if memory is not None else ConceptMemory()
        # The eyes: the shipped visual module and tracker, shared with the ASP agent.
        self.eyes = Agent(self.memory, params=AgentParams(mutual_exclusivity=False,
                                                          syntactic_bootstrapping=False, seed=seed),
                          perceiver=perceiver)
        self.kernel = SoarKernel()
        try:
            self.kernel.command("smem --enable")
            for path in rule_paths(rules):
                self.kernel.source(path)
            for c in self.memory.concepts():  # words already learned: into smem
                word = c.symbol[2:] if c.symbol.startswith("r_") else c.symbol
                self.kernel.command(f"smem --add {{(<w> ^word |{word}| ^concept |{c.symbol}| ^kind {c.kind})}}")
            self.bridge = ConceptMemoryBridge(self.kernel, self.memory)
            self.scene = SceneLink(self.kernel)
            self._lesson: Any = None
            self._lessons = 0
            self.served: list[Served] = []  # every command the bridge executed, in order
        except BaseException:
            self.kernel.close()
            raise

    # ------------------------------------------------------------------ lifecycle
    def close(self) -> None:
        self.kernel.close()

    def __enter__(self) -> "SoarAgent":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def save(self, path: str) -> None:
        self.memory.save(path)

    # ------------------------------------------------------------------ what the interpreter reads
    @property
    def semantic(self) -> SemanticMemory:
        """The word maps, as smem holds them (rebuilt from the concept memory's kinds)."""
        return from_concepts(self.memory)

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
        self.scene.update(state)
        return state

    def describe_scene(self) -> list[str]:
        return self.eyes.describe_scene()

    def locate(self, u: float, v: float) -> str:
        return self.eyes.locate(u, v)

    def watch(self, action: str, u: float | None, v: float | None, image: np.ndarray) -> None:
        self.eyes.watch(action, u, v, image)
        assert self.eyes.state is not None
        self.scene.update(self.eyes.state)

    def episode_now(self) -> int:
        return self.eyes.episode_now()

    # ------------------------------------------------------------------ signals
    def inform(self, content: str, *, demo_start: int | None = None) -> Answer:
        return self._lesson_run("inform", content)

    def verify(self, content: str, *, demo_start: int | None = None) -> Answer:
        return self._lesson_run("verify", content)

    def react(self, content: str, body: Any) -> Answer:
        return Answer("react", content, "failure", "the Soar agent does not act yet (no action words in Soar)")

    def generate(self, content: str = "") -> Answer:
        return Answer("generate", content, "failure", "the Soar agent does not generate sentences yet")

    def told_wrong(self, answer: Answer) -> None:
        raise UserError("the Soar agent does not learn from the trainer's verdicts ('wrong') yet; "
                        "use the ASP agent (--agent asp)")

    def confirmed(self, answer: Answer) -> None:
        raise UserError("the Soar agent does not learn from the trainer's verdicts ('confirm') yet; "
                        "use the ASP agent (--agent asp)")

    def _lesson_run(self, signal: str, content: str) -> Answer:
        assert self.eyes.state is not None, "perceive before a lesson"
        p = language.parse(content)
        if p.action is not None:
            return Answer(signal, content, "failure", "the Soar agent does not learn action words yet")
        self._lessons += 1
        self.bridge.reset()
        self._put_lesson(signal, content, p)
        answer = None
        served: list[Served] = []
        for _ in range(MAX_ROUNDS):
            self.kernel.run_until_output()
            served += self.bridge.serve()
            answer = self._read_answer()
            if answer is not None:
                break
        self.served += served
        if answer is None:  # only rules of one's own (--rules) can leave the agent stuck
            raise UserError(f"the Soar agent gave no answer to {content!r} (check its rules)")
        return self._answer(signal, content, p, answer, served)

    def _put_lesson(self, signal: str, content: str, p: language.Parse) -> None:
        k = self.kernel
        if self._lesson is not None:
            k.remove(self._lesson)
        lesson = self._lesson = k.add(k.input_link, "lesson")
        k.add(lesson, "id", self._lessons)
        k.add(lesson, "signal", signal)
        k.add(lesson, "content", content)
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
            r = k.add(lesson, "relation")
            k.add(r, "id", p.relation.id)
            k.add(r, "word", p.relation.word)
            k.add(r, "arg1", p.relation.arg1)
            k.add(r, "arg2", p.relation.arg2)
            k.add(r, "order", order + 1)
        k.commit()

    def _read_answer(self) -> WMNode | None:
        for attr, node in self.kernel.output():
            if attr == "answer" and node.get("lesson-id") == self._lessons and node.get("result") is not None:
                return node
        return None

    def _answer(self, signal: str, content: str, p: language.Parse, node: WMNode, served: list[Served]) -> Answer:
        failures = []
        for f in node.all("failure"):
            if isinstance(f, WMNode):
                failures.append((str(f.get("reason")), Term(str(f.get("subject")))))
        failures.sort(key=lambda f: (REASONS.index(f[0]) if f[0] in REASONS else 99, f[1]))
        referents: dict[str, list[Term]] = {ref.id: [] for ref in p.objects}
        for r in node.all("referent"):
            if isinstance(r, WMNode):
                referents.setdefault(str(r.get("phrase")), []).append(Term(str(r.get("object"))))
        texts = {ref.id: ref.text for ref in p.objects}
        answer = Answer(
            signal, content, "failure" if failures else "success",
            "; ".join(reason_text(why, s, p) for why, s in failures) or None,
            {texts.get(k, k): [str(o) for o in sorted(v)] for k, v in referents.items()},
        )
        answer.created = [s.concept for s in served if s.command == "create" and s.status == "success"]
        answer.stored = [s.concept for s in served if s.command == "store" and s.status == "success"]
        return answer


def soar_agent(memory: ConceptMemory | None, *, without: Sequence[str] = (), perceiver: Any = None,
               rules: str | None = None, seed: int = 0) -> SoarAgent:
    """The Soar agent for `aileen run --agent soar` (it has neither mechanism `--without` names)."""
    from aileen.agent.records import ablation_params

    ablation_params(without)  # an unknown name is still an error
    if rules is not None and not Path(rules).is_dir():
        raise UserError("--rules must be a directory of .soar files", path=str(rules))
    return SoarAgent(memory, perceiver=perceiver, rules=rules, seed=seed)
