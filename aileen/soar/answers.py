"""What the Soar agent answers: its run's result on the working memory, in the teacher's words.

Why apart from the learner: the learner runs the agent (the kernel, the input-link, the
commands it serves); this reads what the run left under the lesson's node -- failures,
unmet goals, referents -- into the same `Answer` the ASP agent gives, in the same words
(`judgement.reason_text` for comprehension's failures, the planner's own for a missing plan).
"""

from __future__ import annotations

from typing import Any

from aileen.agent import Answer
from aileen.agent.judgement import reason_text
from aileen.reasoning import language, planner
from aileen.reasoning.comprehension import FAILURE_REASONS
from aileen.soar import wm
from aileen.soar.bridge import Served
from aileen.soar.kernel import WMNode
from aileen.terms import Term

__all__ = ["REASONS", "answer_of", "reason_of", "plan_failure_text"]

#: The order the reasons of a failed lesson are given in: comprehension's, then the Soar
#: agent's own (episodes, demonstrations, projections), then any message.
REASONS: tuple[str, ...] = (*FAILURE_REASONS, "no_episode", "not_demonstrated", "no_projection", "not_complete",
                            "message")


def answer_of(signal: str, content: str, p: language.Parse, node: WMNode, served: list[Served]) -> Answer:
    """The answer of a lesson the Soar agent ran: its result, its reasons in the teacher's
    words (in `REASONS` order, as the ASP agent gives them), the referents it found, and the
    concepts the commands it served created and stored."""
    failures: dict[tuple[str, str], None] = {}
    for f in node.all("failure"):
        if isinstance(f, WMNode):
            why = str(f.get("reason"))
            if why in ("no_plan", "not_an_object"):  # the planner's own words (planner.plan)
                failures[("message", plan_failure_text(why, f.get("subject"), node.all("plan-goal")))] = None
                continue
            failures[(why, str(f.get("text") if why == "message" else f.get("subject")))] = None
    ordered = sorted(failures, key=lambda f: (REASONS.index(f[0]) if f[0] in REASONS else 99, f[1]))
    reasons = [reason_of(why, s, p, content) for why, s in ordered]
    unmet = sorted(str(wm.fact(u)) for u in node.all("unmet") if isinstance(u, WMNode))
    if unmet:
        reasons.append(f"after acting, the goal does not hold: {', '.join(unmet)}")
    if node.get("no-action") is not None:
        reasons.append("the sentence asks for no action")
    referents: dict[str, list[Term]] = {ref.id: [] for ref in p.objects}
    for r in node.all("referent"):
        if isinstance(r, WMNode):
            referents.setdefault(str(r.get("phrase")), []).append(Term(str(r.get("object"))))
    texts = {ref.id: ref.text for ref in p.objects}
    answer = Answer(
        signal, content, "failure" if reasons or node.get("result") == "failure" else "success",
        "; ".join(reasons) or None,
        {texts.get(k, k): [str(o) for o in sorted(v)] for k, v in referents.items()},
    )
    answer.unknown_words = sorted(s for why, s in ordered if why == "unknown_word")
    answer.created = [s.concept for s in served if s.command == "create" and s.status == "success"]
    answer.stored = [s.concept for s in served if s.command == "store" and s.status == "success"]
    return answer


def reason_of(why: str, subject: str, p: language.Parse, content: str) -> str:
    """One failure (`why`, what it is about) in the teacher's words."""
    if why == "not_demonstrated":
        return f"the demonstration is not '{subject.replace('_', ' ')}'"
    if why == "no_projection":
        return f"the concept memory projects no next state for '{content}'"
    if why == "not_complete":
        return f"the action was not complete after {subject} projections"
    if why == "no_episode":
        return f"episodic memory has no episode of time {subject}"
    if why == "message":
        return subject
    return reason_text(why, Term(subject), p)


def plan_failure_text(why: str, subject: object, goal: list[Any], state: list[Term] | None = None) -> str:
    """What the ASP agent's planner says when it finds no plan (`planner.NoPlan`, or a goal that
    names something the state does not have): the goal in its order in the projection; where
    no plan of any length reaches it, that it can never hold and why (`planner.never_holds`:
    a static fact is judged only with the `state`)."""
    facts = [g for g in goal if isinstance(g, WMNode)]
    facts.sort(key=lambda g: g.get("order") if isinstance(g.get("order"), int) else 1 << 30)
    terms = [wm.fact(g) for g in facts]
    if why == "not_an_object":
        return f"goal {terms[0] if terms else '?'} names {subject}, which is not an object of the state"
    never = planner.never_holds(state, terms)
    if never is not None:
        return str(planner.NoPlan(terms, 0, never))
    return f"no plan within depth {subject} for goal {', '.join(map(str, terms))}"
