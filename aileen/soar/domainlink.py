"""What the Soar agent's action models need to know of the domain, on its input-link.

The qualitative calculi and the primitive actions are declared once (`aileen.domain.calculi`,
`aileen.domain.actions`); the ASP action models read the calculi as `calculus/2`, `converse/2`,
`static/1` facts (`calculi.asp_facts`) and are held to the actions' declarations, and the Soar
agent's (`agent/plan.soar`) read the same declarations here:

    (<il> ^domain <d>)
    (<d> ^plan-depth 6 ^planner soar ^relation <r> ... ^action <a> ... ^unary-fluent held ...)
    (<r> ^name cone_w ^converse cone_e ^calculus cone ^static no)
    (<a> ^name push ^kind touch ^adds moved ^adds pushed ^dels rel)     (^hand grasp|release)
    (<d> ^no-flat-top cv_sphere ... ^max-height 2)   (`actions.asp_facts`: what the world refuses of a stack)

An action's `^adds` and `^dels` are the fluents its model makes true and false
(`PrimitiveAction.adds`, `.dels`): `rel` the relations of its object, the others facts about
its object alone (`held`, `moved`, and the marks it leaves, `pushed`).

`^plan-depth` is the deepest plan the search looks for (the ASP agent's `plan_depth`);
`^planner` says who searches for plans: `soar` (the agent's own operators, plan.soar) or
`clingo` (the `plan` command, the ASP agent's planner served on the output-link).
"""

from __future__ import annotations

from typing import Any

from aileen.domain import actions, calculi
from aileen.soar.kernel import SoarKernel

PLANNERS: tuple[str, ...] = ("soar", "clingo")
DEFAULT_PLAN_DEPTH = 6


def put_domain(kernel: SoarKernel, *, planner: str = "soar", plan_depth: int = DEFAULT_PLAN_DEPTH) -> Any:
    """Put the domain on the input-link (once, when the agent starts); returns its identifier."""
    if planner not in PLANNERS:
        raise ValueError(f"planner must be one of {', '.join(PLANNERS)}, not {planner!r}")
    d = kernel.add(kernel.input_link, "domain")
    kernel.add(d, "plan-depth", int(plan_depth))
    kernel.add(d, "planner", planner)
    for c in calculi.CALCULI:
        for name in c.relations:
            r = kernel.add(d, "relation")
            kernel.add(r, "name", name)
            kernel.add(r, "converse", c.converse_of(name))
            kernel.add(r, "calculus", c.name)
            kernel.add(r, "static", "yes" if c.static else "no")
    for act in actions.ACTIONS.values():
        a = kernel.add(d, "action")
        kernel.add(a, "name", act.name)
        kernel.add(a, "kind", act.kind)
        if act.hand is not None:
            kernel.add(a, "hand", act.hand)
        for f in act.adds:
            kernel.add(a, "adds", f)
        for f in act.dels:
            kernel.add(a, "dels", f)
    for f in sorted(actions.unary_fluents()):
        kernel.add(d, "unary-fluent", f)
    for fact in actions.asp_facts():  # what the world refuses of a stack, as actions.lp reads it
        arg = str(fact.args[0])
        # a number as a number: plan.soar tests ^max-height 2, which a string "2" never matched,
        # so the Soar planner stacked three high where the world and clingo refuse
        kernel.add(d, str(fact.name).replace("_", "-"), int(arg) if arg.isdigit() else arg)
    kernel.commit()
    return d
