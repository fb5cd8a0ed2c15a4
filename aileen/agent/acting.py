"""Acting: carry out an action sentence in the world (the `react` signal).

Project the next desired state from the action concept, plan it with clingo (iterative
deepening), execute each primitive action through the body, look again; until the projection
says the action is complete.
"""

from __future__ import annotations

import copy
from typing import TYPE_CHECKING, Any

import numpy as np

from aileen.agent import verbs
from aileen.agent.part import Part
from aileen.agent.records import Answer
from aileen.agent.state import id_order
from aileen.domain import actions, calculi
from aileen.errors import UserError
from aileen.memory import extent, reach
from aileen.perception.regions import DEFAULT_SLACK, Footprint, RegionEmpty, on_top_of, sample_region
from aileen.reasoning import planner
from aileen.reasoning.asp import RulesError
from aileen.terms import Term, fn

if TYPE_CHECKING:
    from aileen.agent.body import WorldBody


class Acting(Part):
    """The agent's part that acts: `react`, and the execution of plan steps (`execute`, also
    the Soar agent's hand). It understands the sentence through the grounding part, and moves
    the agent's hand (`Agent.held`) and eyes (`Agent.perceive`) through the agent. It keeps
    the random draws of where to put an object in a region (`rng`, seeded by the agent's
    `AgentParams.seed`)."""

    def __init__(self, agent: Any) -> None:
        super().__init__(agent)
        self.rng = np.random.default_rng(agent.params.seed)
        # what a react aims at for a word whose distance or direction is learned as a region
        # (a distance band, a direction region), and everywhere else the word holds, the
        # nearest or surest first: where the aim has no room, the next is tried, and the goal
        # holds at any of them (`_distance_goal`, `_direction_goal`)
        self._aims: dict[str, tuple[str, ...]] = {}

    def react(self, content: str, body: "WorldBody") -> Answer:
        """Carry out an action sentence in the world: project the next desired state from the
        action concept, plan it, act, look again; until the projection says it is complete."""
        try:
            return self._react(content, body)
        finally:
            self.agent.reading.acted()

    def _react(self, content: str, body: "WorldBody") -> Answer:
        self.agent.perceive(body.look())
        self._aims = {}
        read = self.agent.reading.read("react", content)
        if isinstance(read, Answer):
            return read  # not understood, or a slip asked about: nothing is done
        g, inferred = self.agent.grounding.understand(read, None)
        chosen = self._one_of_several(g)
        if chosen:
            g, inferred = self.agent.grounding.understand(read, None, chosen)
        answer = self.agent.grounding.answer("react", content, g, inferred, None)
        goal = g.result.goal
        if not answer.ok:
            return answer
        if goal is None:
            answer.result, answer.reason = "failure", _no_action(g)
            return answer
        act = g.parse.action
        declared = actions.find_verb(act.verb) if act is not None else None
        if act is not None and act.relation is None and declared is not None \
                and any(actions.ACTIONS[s].kind == actions.REGION for s in declared.steps if s in actions.ACTIONS):
            # "move the red box": it puts an object somewhere, and the sentence says nowhere (it
            # was "the concept memory projects no next state")
            answer.result, answer.reason = "failure", (f"where to? '{act.verb}' puts {g.parse.object(act.arg1).said} "
                                                       f"somewhere: say where, e.g. '{act.verb} "
                                                       f"{g.parse.object(act.arg1).said} left of ...'")
            return answer
        args, concept = [str(o) for o in goal.args], str(goal.concept)
        if self._so_already(goal, args):
            # "move the red box left of the blue cone" with it left of the cone already: a
            # person says so and leaves it (the agent picked it up and put it down again)
            answer.reason, answer.goal_holds = "it is so already: nothing to do", True
            return answer
        if self._unchangeable(goal, args):
            # "move the red box larger than the blue cone": it moved the box anywhere and said
            # success; which of two is larger no move changes, as a person says at once
            answer.result, answer.reason = "failure", f"no move makes {_phrase(g)}"
            return answer
        refused = self._foresee(g, goal, args)
        if refused is not None:
            # no plan reaches it, or no room where it would go: said before the object is
            # picked up (it was picked up, put back, and then refused)
            answer.result, answer.reason = "failure", refused
            return answer
        start = self.episodic.now
        final: list[Term] = []
        try:
            for _ in range(self.params.max_react_projections):
                # The trace names the action's arguments (`r_move_right_of(o1,o2)`), so the
                # mapping cannot swap mover and reference when their start state is symmetric.
                trace = self.episodic.trace(start, [Term(o) for o in args], extra=[fn(concept, *args)],
                                            movers=[Term(args[0])])
                proj = self.memory.project(trace, concept)
                answer.projections += 1
                if not proj.facts:
                    raise UserError(f"the concept memory projects no next state for '{content}'")
                final = list(proj.facts)
                if goal.relation is not None and self.params.one_verb:  # the slot: the sentence's relation
                    relation = str(goal.relation)
                    direction, directionless = self._direction_goal(relation)
                    final = verbs.fill_slot(self.memory, relation, final, direction=direction,
                                            directionless=directionless, distance=self._distance_goal(relation))
                assert self.state is not None
                plan = planner.plan(self.state.facts, final, max_depth=self.params.plan_depth, rules=self.agent.rules)
                for step in plan.steps:
                    self.execute(step, body)
                    answer.steps.append(step_text(step))
                if proj.complete:
                    break
            else:
                raise UserError(f"the action was not complete after {self.params.max_react_projections} projections")
        except RulesError:
            self._put_back(body)
            raise  # the rules, not the agent: the run stops (exit 2) with what was learned saved
        except UserError as exc:
            put = self._put_back(body)
            if put is not None:  # (the transcript showed the pick-up and not that it was put back)
                answer.steps.append(f"put back({put})")
            answer.result, answer.reason = "failure", _refusal(g, exc)
            return answer
        missing = self._missing(final)
        answer.goal_holds = not missing
        if missing:
            answer.result, answer.reason = "failure", f"after acting, the goal does not hold: {', '.join(missing)}"
        elif goal.relation is not None and len(args) == 2 and args[0] != args[1] and not self._so_already(goal, args):
            # the plan's facts hold, the sentence's relation does not, as the agent's own verify
            # finds: it was success, whatever the move had done
            answer.result, answer.goal_holds = "failure", False
            answer.reason = f"after acting, {_phrase(g)} does not hold as I see it"
        return answer

    def _one_of_several(self, g: Any) -> dict[str, str]:
        """For "a red box" (or "one red box") with several on the table: the one to act on, a
        person's pick: one the sentence's relation already holds of, else the first seen (it
        was "I see more than one 'red box'", where either would do)."""
        p, out = g.parse, {}
        for ref in p.objects:
            cands = sorted((str(o) for o in g.result.referents.get(ref.id, [])), key=id_order)
            if not ref.indefinite or len(cands) < 2:
                continue
            act, pick = p.action, cands[0]
            if act is not None and act.arg1 == ref.id and act.relation is not None and act.arg2 is not None:
                other = [str(o) for o in g.result.referents.get(act.arg2, [])]
                c = self.semantic.concept(act.relation)
                if len(other) == 1 and c is not None:
                    pick = next((o for o in cands if o != other[0] and self.agent.grounding.holds_binary(
                        c, o, other[0], self.state)), pick)
            out[ref.id] = pick
        return out

    def _missing(self, final: list[Term]) -> list[str]:
        """The goal facts that do not hold in the scene now (one aimed at holds where else the
        word holds: `_aims`)."""
        assert self.state is not None
        have = set(self.state.facts)
        return [str(f) for f in final
                if f not in have and not any(fn(b, *f.args) in have for b in self._aims.get(f.name, ()))]

    def _foresee(self, g: Any, goal: Any, args: list[str]) -> str | None:
        """Why the sentence's relation cannot be brought about, where that is known before
        acting, else None: no plan from the table as it is reaches the relation's own facts
        between the two ("on" a sphere: the world's refusals are the planner's), or, where the
        plan moves the mover alone into a region, no room there (a sector past an object at
        the table's edge). The room is looked for with a copy of the agent's draws, so where
        it acts it puts the object where it did before."""
        if goal.relation is None or len(args) != 2 or not self.params.one_verb or not self.memory.has(str(goal.relation)):
            return None
        assert self.state is not None
        relation = str(goal.relation)
        direction, directionless = self._direction_goal(relation)
        target = verbs.fill_slot(self.memory, relation, [fn(verbs.SLOT, *args)], direction=direction,
                                 directionless=directionless, distance=self._distance_goal(relation))
        if not target:
            return None
        depth = self.params.plan_depth * self.params.max_react_projections
        try:
            plan = planner.plan(self.state.facts, target, max_depth=depth, rules=self.agent.rules)
        except planner.NoPlan as exc:
            return f"no plan of mine puts {_phrase(g)} ({exc})"
        places = [s for s in plan.steps if s.relations]
        if any(str(s.obj) != args[0] for s in plan.steps) or len(places) != 1 \
                or any(str(r.name) == calculi.RESTS_ON for r in places[0].relations):
            return None  # others move first, or onto another: where it goes is known only then
        x0, y0, x1, y1 = self.agent.tracker.known[args[0]].box_m
        others = {i: s.box_m for i, s in self.state.objects.items() if i != args[0]}
        draws, self.rng = self.rng, copy.deepcopy(self.rng)
        try:
            self._spot((x1 - x0, y1 - y0), list(places[0].relations), others, args[0])
        except RegionEmpty as exc:
            return _refusal(g, exc)
        finally:
            self.rng = draws
        return None

    def _unchangeable(self, goal: Any, args: list[str]) -> bool:
        """Is the sentence's relation one no declared action changes between the two objects:
        every fact its concept says between them is of a relation no action changes
        (`actions.changes`: which of two is larger)?"""
        if goal.relation is None or len(args) != 2 or not self.memory.has(str(goal.relation)):
            return False
        facts = verbs.relation_facts(self.memory, str(goal.relation), Term(args[0]), Term(args[1]))
        return bool(facts) and not any(actions.changes(str(f.name)) for f in facts)

    def _so_already(self, goal: Any, args: list[str]) -> bool:
        """Does the sentence's relation hold now between the mover and the reference, as a
        verify of it would find (the relation word's own concept)?"""
        if goal.relation is None or len(args) != 2 or args[0] == args[1]:
            return False
        assert self.state is not None
        return self.agent.grounding.holds_binary(str(goal.relation), args[0], args[1], self.state)

    def execute(self, step: "planner.PlanStep", body: "WorldBody") -> None:
        """One primitive action through the body, then look again (and record both). Its
        declaration says where the hand goes: to the object's pixel (`touch`), or into the
        region the planner's relations describe, made a point here (`region`)."""
        assert self.state is not None
        action = step.action
        obj = str(action.args[0])
        act = actions.action(str(action.name))
        named = [o for o in (obj, *(str(r.args[1]) for r in step.relations if str(r.name) == calculi.RESTS_ON))
                 if not (act.hand == actions.RELEASE and o == obj)]
        lost = [o for o in named if o not in self.state.objects]
        if lost:  # the plan was made on a table that looks otherwise now: given up, not a KeyError
            raise UserError(f"I lost sight of {lost[0]} while acting (it looks otherwise now), so I stopped")
        if act.touches:
            u, v = _pixel(self.state.objects[obj].box_px)
            body.touch(act.name, u, v)
        else:  # into a region: the planner's relations, made concrete here
            # the held object (place), or the one on the table it is done to
            at = None if act.hand == actions.RELEASE else _pixel(self.state.objects[obj].box_px)
            stack = [r for r in step.relations if str(r.name) == calculi.RESTS_ON and str(r.args[0]) == obj]
            if stack:  # onto the object it must rest on
                ref = self.state.objects[str(stack[0].args[1])]
                half = self.agent.tracker.known[obj].extent / 2
                table = self.agent.camera.table
                x, y = on_top_of(ref.box_m, self.rng, within=(half, half, table.width - half, table.depth - half))
                body.put(act.name, x, y, at=at, onto=_pixel(ref.box_px))
            else:
                seen = self.agent.tracker.known[obj]
                others = {i: s.box_m for i, s in self.state.objects.items() if i != obj}
                # the room it takes is its box as seen: put down as it was held, a capsule
                # lying across the table is wider one way than the other
                x0, y0, x1, y1 = seen.box_m
                x, y = self._spot((x1 - x0, y1 - y0), list(step.relations), others, obj)
                body.put(act.name, x, y, at=at)
        released = None
        if act.hand == actions.GRASP:
            self.agent.held = obj
        elif act.hand == actions.RELEASE:
            released, self.agent.held = self.agent.held, None
        self.agent.perceive(body.look(), action=action, released=released)

    def _put_back(self, body: "WorldBody") -> str | None:
        """An action given up with an object in the hand: put it down where it was seen last,
        so the table keeps it (it was out of sight in the hand, and a failed react left it
        there: the next lesson saw no red box). Where even that fails, it stays held. Returns
        the object put back, or None."""
        obj = self.agent.held
        if obj is None or obj not in self.agent.tracker.known:
            return None
        release = next(a for a in actions.ACTIONS.values() if a.hand == actions.RELEASE)
        x, y = self.agent.tracker.known[obj].centre
        try:
            body.put(release.name, x, y)
        except UserError:
            return None
        self.agent.held = None
        self.agent.perceive(body.look(), released=obj)
        return obj

    def _spot(self, extent_m: Footprint, relations: list[Term], others: dict[str, tuple[float, float, float, float]],
              obj: str) -> tuple[float, float]:
        """Where to put `obj` so that `relations` hold (`sample_region`); where a distance band
        or a direction region it aims at has no room (a fine sector past an object near the
        edge misses the table), where else the word holds, nearest or surest first (`_aims`)."""
        table = self.agent.camera.table
        tries = [relations]
        for aimed in [r for r in relations if r.name in self._aims]:
            tries += [[fn(other, *r.args) if r is aimed else r for r in relations]
                      for other in self._aims[aimed.name][1:]]
        first: RegionEmpty | None = None
        # Where no spot holds with room for the measurements' noise (a box "far from" a cone
        # in the middle of the table has a strip 2 cm wide at the edge, and the noise eats
        # it), one where it holds as measured: the agent's own verify says yes there, and it
        # said "no room"
        for slack in (DEFAULT_SLACK, 0.0):
            for tried in tries:
                try:
                    return sample_region(extent_m, tried, others, table, self.rng, subject=obj, slack=slack)
                except RegionEmpty as exc:
                    first = first or exc
        assert first is not None
        raise first

    def _direction_goal(self, relation: str) -> tuple[str | None, bool]:
        """Where a react puts the object for the relation word, from its region read once:
        with extents, the widest declared region the word surely holds of (`extent.surest`),
        or, for a word that says nothing of direction (`Directions.region` is None: its
        examples show none, or it is more than a direction and the direction words say
        where), that its goal holds no direction; (None, False) without extents or for a word
        that is not spatial: its description is the goal as it is."""
        if not self.params.extents or self.semantic.kind(relation) != "spatial":
            return None, False
        region = self.directions.region(relation)  # read once; None: `Grounding.sideless`
        if region is None:
            return None, True
        aim = extent.surest(region)
        self._aims[aim] = extent.aims(region, aim)
        return aim, False

    def _distance_goal(self, relation: str) -> str | None:
        """The distance band a react puts the object at, for a word whose distance is learned
        as a region (`Directions.reach`): the middle of what it surely holds of
        (`reach.surest`); None for any other word (its description's facts are the goal)."""
        if not self.params.extents or self.semantic.kind(relation) != "spatial":
            return None
        reading = self.directions.reach(relation)
        if reading is None:
            return None
        within = reading.within
        aim = reach.surest(within)
        names = reading.measure.relations
        holds = sorted((k for k in range(len(within)) if within[k] >= extent.ACCEPT or k == aim),
                       key=lambda k: (abs(k - aim), k))
        self._aims[names[aim]] = tuple(names[k] for k in holds)
        return names[aim]


def _no_action(g: Any) -> str:
    """Why a react's sentence gives no goal: one object said to go somewhere of itself ("move
    the red box left of the red box": a person says it cannot), else it asks for none."""
    act = g.parse.action
    if act is not None and act.arg2 is not None:
        mover, ref = g.result.referents.get(act.arg1, []), g.result.referents.get(act.arg2, [])
        if len(mover) == 1 and mover == ref:
            where = (act.relation or "there").replace("_", " ")
            return f"{g.parse.object(act.arg1).said} cannot be {where} itself"
    return "the sentence asks for no action"


def _refusal(g: Any, exc: UserError) -> str:
    """What a react says of a move it cannot make: for no room, in the word's terms ("no room
    left of the blue cone"), the planner's facts after it; else the world's own line."""
    act = g.parse.action
    if isinstance(exc, RegionEmpty) and act is not None and act.relation is not None and act.arg2 is not None:
        return (f"there is no room {act.relation.replace('_', ' ')} {g.parse.object(act.arg2).said} "
                f"for {g.parse.object(act.arg1).said} ({exc.message})")
    return exc.message


def _phrase(g: Any) -> str:
    """The sentence's mover, relation and reference as said: "the red box larger than the blue
    cone"."""
    act = g.parse.action
    return (f"{g.parse.object(act.arg1).said} {(act.relation or '').replace('_', ' ')} "
            f"{g.parse.object(act.arg2).said}")


def _pixel(box_px: tuple[float, float, float, float]) -> tuple[float, float]:
    u0, v0, u1, v1 = box_px
    return (u0 + u1) / 2, (v0 + v1) / 2


def step_text(step: "planner.PlanStep") -> str:
    """A plan step for the transcript: `place(o1) where w(o1,o2), dc(o1,o2)` for an action into
    a region, else the action (`push(o1)`)."""
    if step.relations:
        return f"{step.action.name}({step.action.args[0]}) where {', '.join(str(r) for r in step.relations)}"
    return str(step.action)


