"""What a demonstration shows: the action concept a sentence names, and the pairs it was done to.

Why a part of its own: comprehension (`Grounding`), learning and the trainer's verdicts all
ask the same three things of an action sentence: which concept it names (the verb's own, its
relation a slot, or a per-relation one), what the demonstration's trace looks like as that
verb's example (agent/verbs.py), and which objects the demonstration shows the action for.
They were the grounding's; here they are one job, asked by name (`agent.demonstrations`).
"""

from __future__ import annotations

import itertools

from aileen.agent import verbs
from aileen.agent.part import Part
from aileen.agent.state import id_order
from aileen.domain import calculi
from aileen.memory.projection import time_chain
from aileen.reasoning import language
from aileen.terms import Term, fn


class Demonstrations(Part):
    """The agent's part that reads demonstrations: the action concept of a sentence, the
    verb's trace, the pairs a demonstration shows the action for (`shown`)."""

    def action_concept(self, p: language.Parse) -> str | None:
        """The concept an action sentence names: the verb's own (`r_move`, its relation a
        slot) when the agent has one and knows the relation word; else a per-relation concept
        (`r_move_left_of`: the paper's, kept in memories saved before issue 11 and with
        `--without one-verb`), when there is one."""
        if p.action is None:
            return None
        if self.params.one_verb and p.action.relation is not None and p.action.arg2 is not None:
            c = self.semantic.concept(p.action.verb)
            if c is not None and self.semantic.kind(c) == "action" and self.semantic.concept(p.action.relation):
                return c
        return self.semantic.concept(p.action.word)

    def is_verb_concept(self, concept: str | None, p: language.Parse) -> bool:
        """Is `concept` the verb's own (a slot for the relation), not a per-relation one?"""
        return (concept is not None and p.action is not None and self.params.one_verb
                and p.action.relation is not None and p.action.arg2 is not None
                and concept == self.semantic.concept(p.action.verb))

    def verb_trace(self, demo_start: int, a: str, b: str, rel_c: str | None) -> list[Term]:
        """The demonstration's trace as a verb's example sees it: who moved, and the slot
        in place of what the sentence's relation accounts for at the end."""
        assert self.state is not None
        ta, tb = Term(a), Term(b)
        trace = self.episodic.trace(demo_start, [ta, tb])
        out = trace + verbs.roles(trace, [ta, tb])
        if rel_c is None:
            return out
        _t, final = verbs.last_facts(trace)
        between = [f for f in final if f.args and set(f.args) <= {ta, tb}]
        explained = self.agent.grounding.accounted(rel_c, a, b, between)
        if explained is None:
            return out
        if self.agent.grounding.sideless(rel_c):
            # which side the mover started or ended on is no part of a sideless word's action
            # ("move X near Y"): the slot stands for the end, and the trace keeps no side of
            # the two, so two demonstrations that both happened to start or end on the left
            # do not make the left side part of the verb
            out = [f for f in out if not _side_of(f, ta, tb)]
        return verbs.slotted(out, explained, ta, tb, contrast=self.params.start_contrast)

    def shown(self, p: language.Parse, unary: dict[str, list[str]], demo_start: int) -> list[Term]:
        """Which (mover, reference) pairs the demonstration since `demo_start` shows the action
        for. The action concept must match the trace, and, since the sentence also says
        where the mover ends up ("move X right of Y" ends with X right of Y), the relation's
        own concept must hold at the end when it is known: meaning composes. (The matches
        are the grounding's evidence: `Grounding.note`.)"""
        assert self.state is not None and p.action is not None
        grounding = self.agent.grounding
        c = self.action_concept(p)
        if c is None:
            return []
        rel_c = self.semantic.concept(p.action.relation) if p.action.relation else None
        objs = sorted(self.state.objects, key=id_order)
        out = []
        if self.is_verb_concept(c, p) and p.action.arg2 is not None:
            # one verb for every relation (agent/verbs.py): who moved, and the slot the
            # sentence's relation fills; the match must keep the action's whole outcome
            for a in unary.get(p.action.arg1, objs):
                for b in unary.get(p.action.arg2, objs):
                    if a == b:
                        continue
                    trace = self.verb_trace(demo_start, a, b, rel_c)
                    if not self._as_long_as(c, trace):
                        continue
                    kept = [inf for inf in self.memory.query(trace, fn(c, a, b))
                            if verbs.outcome_kept(self.memory, c, inf)]
                    if grounding.note(kept):
                        out.append(fn(c, a, b))
            return out
        for args in itertools.product(*(unary.get(r, objs) for r in p.action.args)):
            if len(set(args)) != len(args):
                continue
            trace = self.episodic.trace(demo_start, [Term(o) for o in args])
            if not self._as_long_as(c, trace) or not self.memory.query(trace, fn(c, *args)):
                continue
            if rel_c is not None and not grounding.holds_binary(rel_c, args[0], args[1], self.state):
                continue
            out.append(fn(c, *args))
        return out

    def _as_long_as(self, concept: str, trace: list[Term]) -> bool:
        """A demonstration shows the whole action and only it: its trace has as many steps as
        some description of the action concept (a pick-up and a place are two steps, a push
        one), so an action that matches part of a longer one is not taken for it."""
        steps = len(time_chain(trace))
        lengths = {len(time_chain(d)) for d in self.memory.descriptions(concept)}
        return not lengths or steps in lengths


def _side_of(fact: Term, a: Term, b: Term) -> bool:
    """Is `fact` a trace fact `h(t, dir(a, b))` (or b, a): a direction between the two?"""
    if fact.name != "h" or len(fact.args) != 2 or not isinstance(fact.args[1], Term):
        return False
    inner = fact.args[1]
    return calculi.is_direction(inner.name) and len(inner.args) == 2 and set(inner.args) == {a, b}
