"""Shortest plans of primitive actions by iterative deepening in clingo.

The action models are `asp/actions.lp` (and the model file of each declared action that brings
its own, `PrimitiveAction.model`), the generic incremental search `asp/planning.lp` (both
user-editable); they are held to the declarations in `aileen/domain/actions.py` when loaded
(`reasoning/models.py`). This module converts the state and goal into facts, drives the
search one horizon at a time (0, 1, 2, ... up to `max_depth`), and returns the first plan
found, which is a shortest one. Relation facts `w(o1,o2)` appear on the ASP side as
`rel(w,o1,o2)` so rules can talk about any relation generically (clingo cannot build a
term with a variable functor); the conversion is here, both ways.

A `place` step comes with the relations the placed object must satisfy, e.g.
`place(o1,goal)` with `[w(o1,o2), dc(o1,o2)]`; the spatial module turns those into a point.
"""

from __future__ import annotations

import os
import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from aileen.domain import actions, calculi
from aileen.errors import UserError
from aileen.reasoning import models
from aileen.reasoning.reify import is_relation, reify, unreify
from aileen.terms import Term, fn

__all__ = ["PlanStep", "Plan", "NoPlan", "plan", "planning_facts", "never_holds", "model_paths", "RULE_FILES"]

RULE_FILES: tuple[str, ...] = ("actions.lp", "planning.lp")
#: What `_read` takes from the answer set, per rule file (`rulefiles.check_reads`).
READS: dict[str, tuple[str, ...]] = {"planning.lp": ("occurs/2",), "actions.lp": ("region_fact/3", "region_src/4")}

_STATIC = frozenset({"isa", "obj"})


@dataclass(frozen=True)
class PlanStep:
    """One primitive action; for `place`, the relations the object must end up in,
    seen from the placed object and in the order of the goal facts they come from."""

    action: Term
    relations: list[Term] = field(default_factory=list)

    @property
    def name(self) -> str:
        return str(self.action.name)

    @property
    def obj(self) -> Term:
        return self.action.args[0]

    def __str__(self) -> str:
        if self.relations:
            return f"{self.action} [{', '.join(str(r) for r in self.relations)}]"
        return str(self.action)


@dataclass(frozen=True)
class Plan:
    """A shortest plan; `depth` is its length (0 when the goal already holds)."""

    steps: list[PlanStep]
    depth: int

    @property
    def actions(self) -> list[Term]:
        return [s.action for s in self.steps]


class NoPlan(Exception):
    """No sequence of at most `max_depth` actions reaches the goal; with `never`, no sequence
    of any length does, and why (a deeper search would not help)."""

    def __init__(self, goal: Iterable[Term], max_depth: int, never: str | None = None) -> None:
        self.goal = tuple(goal)
        self.max_depth = max_depth
        self.never = never
        goals = ", ".join(str(g) for g in self.goal)
        super().__init__(f"the goal {goals} can never hold: {never}" if never is not None
                         else f"no plan within depth {max_depth} for goal {goals}")


#: The clock the whole search is held to the solving limit by (a test moves it on).
_clock = time.monotonic


def planning_facts(state: Iterable[Term], goal: Iterable[Term]) -> list[Term]:
    """The facts planning.lp reads: obj/1, static isa/2, init/1 and goal/1 (relations as rel/3).

    Objects are the explicit `obj/1` facts, the first arguments of `isa/2`, the arguments of
    relation facts and of the declared unary fluents (`held/1`, `pointed/1`, ...). A goal that
    names anything else is a `UserError`: the planner cannot put something relative to an
    object it does not see.
    """
    fluents = actions.unary_fluents()
    objs: dict[Term, None] = {}
    out: list[Term] = []
    for f in state:
        if f.name == "obj" and len(f.args) == 1:
            objs[f.args[0]] = None
        elif f.name == "isa" and len(f.args) == 2:
            objs[f.args[0]] = None
            out.append(f)
        else:
            if is_relation(f):
                objs[f.args[0]] = None
                objs[f.args[1]] = None
            elif f.name in fluents and len(f.args) == 1:
                objs[f.args[0]] = None
            out.append(fn("init", reify(f)))
    goals = list(goal)
    held = [f for f in state if f.name == "held" and len(f.args) == 1]
    if len(held) > 1:  # the hand holds one object at most (`Fluent` held; the world refuses a second)
        raise UserError(f"the state holds {len(held)} objects in the hand at once ({', '.join(map(str, held))}): "
                        "expected one at most")
    for g in goals:
        named = g.args if (is_relation(g) or g.name in fluents) else ()
        for a in named:
            if a not in objs:
                raise UserError(f"goal {g} names {a}, which is not an object of the state")
        out.append(fn("goal", reify(g)))
    out.extend(fn("obj", o) for o in objs)
    out.extend(calculi.asp_facts())
    out.extend(actions.asp_facts())
    return out


def model_paths(rules: "str | os.PathLike[str] | None" = None) -> list[Path]:
    """The planner's rule files (the user's in `rules` before the shipped ones), then the model
    file of each declared action that brings its own; checked against the declarations
    (`models.check`: a `UserError` naming file and line where they disagree)."""
    from aileen.reasoning import asp

    paths = asp.rule_paths(RULE_FILES, rules)
    for a in actions.ACTIONS.values():
        if a.model is not None and a.model not in paths:
            if not Path(a.model).is_file():
                raise UserError(f"the model of the declared action {a.name} is not a file; expected it in "
                                f"{Path(a.model).parent} (a relative model path is read from the folder of the "
                                f"module that declares the action)", path=str(a.model))
            paths.append(Path(a.model))
    models.check(paths)
    return paths


def plan(state: Iterable[Term], goal: Iterable[Term], *, max_depth: int = 6, rules: "str | os.PathLike[str] | None" = None) -> Plan:
    """The shortest plan from `state` to a state where every fact of `goal` holds.

    state: QSR facts (`w(o1,o2)`), `held(O)`, `pointed(O)`, percepts (`isa`), `obj(O)`.
    goal: a conjunction of QSR facts, `held(O)`, `pointed(O)`.
    Raises `NoPlan` ("no plan within depth D") when none is within `max_depth` steps.
    """
    from aileen.reasoning import asp

    if max_depth < 0:
        raise UserError(f"max depth must be >= 0, got {max_depth}")
    goals = list(goal)
    state = list(state)
    facts = planning_facts(state, goals)
    never = never_holds(state, goals)
    if never is not None:
        raise NoPlan(goals, max_depth, never)
    paths = model_paths(rules)
    search = asp.Incremental(paths, facts)
    order = {reify(g): i for i, g in reversed(list(enumerate(goals)))}
    limit, label = asp.solve_limit()
    start = _clock()
    for t in range(max_depth + 1):
        if limit is not None and t > 0 and _clock() - start > limit:
            # each call is held to the limit, and so is the search: a million horizons of
            # quick calls ran for minutes under --rules-timeout 5
            raise asp.RulesTimeout(f"planning took longer than {limit:g} s: no plan of up to {t - 1} steps, of the "
                                   f"{max_depth} asked for; lower --max-depth or raise --rules-timeout", path=label)
        model = search.horizon(t)
        if model is not None:
            return _read(model, t, order)
    unsatisfiable(paths, state, rules)
    raise NoPlan(goals, max_depth)


def unsatisfiable(files: Sequence[Path], state: Iterable[Term], rules: "str | os.PathLike[str] | None") -> None:
    """A `RulesUnsatisfiable` where rules of one's own (`--rules`) leave the state itself, with
    no goal, without an answer set at depth 0 or 1 while the shipped rules have one there: "no
    plan within depth 36" blamed the search for the rules (`:- obj(O).` in actions.lp).
    Nothing with the shipped rules alone, whose "no plan" stays as it is."""
    from aileen.reasoning import asp

    shipped = asp.shipped_instead(files)
    if shipped == list(files):
        return
    facts = planning_facts(state, [])
    own, theirs = asp.Incremental(files, facts), asp.Incremental(shipped, facts)
    for t in (0, 1):
        mine, shipped_model = own.horizon(t), theirs.horizon(t)  # (each visits every horizon in order)
        if mine is None and shipped_model is not None:
            names = ", ".join(str(f) for f in files if f not in shipped)
            raise asp.RulesUnsatisfiable(f"the planning program has no answer set at depth {t}, with no goal, with "
                                         f"{names}, where the shipped rules have one; check your rules",
                                         path=str(rules if rules is not None else asp.own_files(files)[0].parent))


def never_holds(state: Iterable[Term] | None, goal: Iterable[Term]) -> str | None:
    """Why no plan of any length reaches `goal`, where the declarations say so cheaply, else
    None: a fact of a static calculus (no move changes which of two is larger) that does not
    hold now, two facts one calculus says cannot hold together (its relations are disjoint:
    `w(o1,o2)` and `w(o2,o1)`, read through the converse as `e(o1,o2)`), or two objects held
    (the hand holds one). Why here: the search would say "no plan within depth N", as if a
    deeper one might find it. Without a `state` (None), a static fact is not judged."""
    have = set(state) if state is not None else None
    goals = list(goal)
    held = [g for g in goals if g.name == "held" and len(g.args) == 1]
    if len(held) > 1:
        return f"{held[0]} and {held[1]}: the hand holds one object at most"
    seen: dict[tuple[str, Term, Term], Term] = {}
    for g in goals:
        c = calculi.calculus_of(str(g.name)) if len(g.args) == 2 else None
        if c is None:
            continue
        if c.static and have is not None and g not in have:
            return f"{g} does not hold, and no action changes it ({g.name} is of the static calculus {c.name})"
        a, b = g.args
        rel, pair = (str(g.name), (a, b)) if str(a) <= str(b) else (c.converse_of(str(g.name)), (b, a))
        other = seen.setdefault((c.name, *pair), g)
        if other is not g:
            o = other.args
            rel_other = str(other.name) if o == pair else c.converse_of(str(other.name))
            if rel_other != rel:
                return f"{other} and {g} cannot both hold (at most one relation of {c.name} holds of two objects)"
    return None


def _read(model: Iterable[Term], depth: int, order: dict[Term, int]) -> Plan:
    occurs: list[tuple[int, Term]] = []
    regions: dict[tuple[Term, Term], dict[Term, int]] = {}
    last = len(order)
    for a in model:
        if a.name == "occurs" and len(a.args) == 2 and isinstance(a.args[1].name, int):
            occurs.append((a.args[1].name, a.args[0]))
        elif a.name == "region_fact" and len(a.args) == 3:
            regions.setdefault((a.args[0], a.args[1]), {}).setdefault(a.args[2], last)
        elif a.name == "region_src" and len(a.args) == 4:
            rel = regions.setdefault((a.args[0], a.args[1]), {})
            rel[a.args[2]] = min(rel.get(a.args[2], last), order.get(a.args[3], last))
    occurs.sort(key=lambda x: x[0])
    steps = []
    for _, act in occurs:
        rels: list[Term] = []
        if len(act.args) == 2:  # place(O,R), or a user's action into a region: slide(O,R)
            found = regions.get((act.args[0], act.args[1]), {})
            rels = [unreify(f) for f in sorted(found, key=lambda f: (found[f], f))]
        steps.append(PlanStep(act, rels))
    return Plan(steps, depth)
