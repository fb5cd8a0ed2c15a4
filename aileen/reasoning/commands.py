"""`aileen asp check|comprehend|plan`: the ASP rules from the command line.

Exit codes: 0 success; 1 the reasoning answered "no" (comprehension failed, no plan within
the depth); 2 a user mistake (a syntax error in a `.lp` file: `comprehension.lp:12:5:
error: ...`, an unreadable facts file, a sentence outside the grammar).
"""

from __future__ import annotations

import argparse
import json
import os
import re
from pathlib import Path

from aileen.errors import UserError
from aileen.terms import Term

__all__ = ["register", "read_facts_file"]


def register(subparsers: argparse._SubParsersAction) -> None:
    p = subparsers.add_parser("asp", help="check the ASP rules, comprehend a sentence, plan a goal")
    sub = p.add_subparsers(dest="asp_command", metavar="ASP_COMMAND")
    p.set_defaults(handler=lambda args: (p.print_help(), 0)[1])

    c = sub.add_parser("check", help="load and ground every rule file (shipped, overridden by --rules DIR)")
    c.add_argument("--rules", metavar="DIR", help="your own rule directory (its files override shipped ones)")
    _timeout_arg(c)
    c.set_defaults(handler=_check)

    c = sub.add_parser("comprehend", help="ground a sentence in a scene given as ASP facts")
    c.add_argument("sentence", help="the sentence, e.g. \"red box left of blue cone\"")
    c.add_argument("--facts", required=True, metavar="FILE",
                   help="ASP facts: percepts isa(O,P), QSRs w(o1,o2), inferred concept facts, word_concept(W,C)")
    c.add_argument("--words", metavar="FILE", help="semantic memory as word_concept(W,C) facts")
    c.add_argument("--rules", metavar="DIR", help="your own rule directory")
    c.add_argument("--json", action="store_true", help="print the result as JSON")
    _timeout_arg(c)
    c.set_defaults(handler=_comprehend)

    c = sub.add_parser("plan", help="shortest plan from a state (ASP facts) to a goal")
    c.add_argument("--facts", required=True, metavar="FILE", help="the state: QSR facts, held(O), isa(O,P)")
    c.add_argument("--goal", required=True, help='a conjunction of facts, e.g. "w(o1,o2). dc(o1,o2)."')
    c.add_argument("--max-depth", type=int, default=6, metavar="N", help="longest plan to look for (default 6)")
    c.add_argument("--rules", metavar="DIR", help="your own rule directory")
    c.add_argument("--json", action="store_true", help="print the plan as JSON")
    _timeout_arg(c)
    c.set_defaults(handler=_plan)


def _timeout_arg(c: argparse.ArgumentParser) -> None:
    from aileen.reasoning.guard import add_limit_args

    add_limit_args(c)


def guard_rules(rules: str | None, timeout: float, megabytes: float | None = None) -> list[str]:
    """Check the rules (shipped, overridden by `rules`) in a child process within `timeout`
    seconds and `megabytes`, and limit every later clingo call in this process the same way;
    returns the warnings."""
    from aileen.reasoning import asp, guard, planner
    from aileen.reasoning.comprehension import RULE_FILES as COMP
    from aileen.reasoning.planner import RULE_FILES as PLAN

    if rules is not None and not Path(rules).is_dir():
        raise UserError("--rules must be a directory of .lp files", path=rules)
    label = rules if rules is not None else str(asp.rules_dir())
    groups = [asp.rule_paths(COMP, rules), planner.model_paths(rules)]  # the action models: held to their declarations
    from aileen.reasoning.comprehension import READS as COMP_READS
    from aileen.reasoning.rulefiles import check_reads

    check_reads([asp.rule_paths(COMP, rules), asp.rule_paths(PLAN, rules)], {**COMP_READS, **planner.READS})
    known = {n for n in (*COMP, *PLAN)}
    if rules:
        groups.extend([p] for p in sorted(p for p in Path(rules).glob("*.lp") if p.name not in known))
    warnings = guard.check_rules(groups, timeout=timeout, label=label, megabytes=megabytes)
    asp.set_solve_limit(timeout, label, megabytes=megabytes)
    if rules:
        from aileen.reasoning.rulefiles import unused_files

        warnings = unused_files(rules, known) + warnings
    return warnings


def satisfiable_on_a_sample(comprehension: list[Path], planning: list[Path], label: str) -> None:
    """The comprehension and planning programs, solved on a small sample scene (a red box and
    a blue cone, "red box left of blue cone"; planning with no goal at depth 0 and 1), have an
    answer set wherever the shipped rules do; else a `RulesUnsatisfiable` naming the file of
    one's own that takes it away. Grounding alone passed `:- obj(O).` as "ok", and then every
    lesson was the agent's failure. Run under the solving limit (`set_solve_limit`)."""
    from aileen.reasoning import asp, comprehension as comp, planner
    from aileen.reasoning.language import parse
    from aileen.terms import fn

    scene = [fn("isa", "o1", "cv_red"), fn("isa", "o1", "cv_box"), fn("isa", "o2", "cv_blue"),
             fn("isa", "o2", "cv_cone"), fn("w", "o1", "o2"), fn("e", "o2", "o1")]
    said = comp.working_memory(parse("red box left of blue cone"), words={}, facts=scene)
    facts = planner.planning_facts(scene, [])

    def comprehends(files: list[Path]) -> bool:
        return asp.solve_once(files, said) is not None

    def plans(files: list[Path]) -> bool:
        search = asp.Incremental(files, facts)
        return all([search.horizon(0) is not None, search.horizon(1) is not None])

    for what, files, solves in (("comprehension", comprehension, comprehends), ("planning", planning, plans)):
        shipped = asp.shipped_instead(files)
        if shipped == files or solves(files) or not solves(shipped):
            continue
        own = [f for f in files if f not in shipped]
        culprit = [f for f in own if solves(asp.shipped_instead(files, only=f))] or own
        raise asp.RulesUnsatisfiable(f"{culprit[0]}: the {what} program has no answer set on a sample scene (a red "
                                     f"box left of a blue cone) with it, where the shipped rules have one; check "
                                     f"its rules (a constraint that always applies, such as ':- obj(O).')",
                                     path=label if len(culprit) > 1 else None)


def _limit(args: argparse.Namespace) -> None:
    """User rules are checked under the limit first; shipped ones only get the solving limit."""
    from aileen.reasoning import asp

    if args.rules or os.environ.get("AILEEN_RULES"):  # rules of the user's own: checked before any work
        guard_rules(args.rules, args.rules_timeout, args.rules_memory)
    else:
        asp.set_solve_limit(args.rules_timeout, megabytes=args.rules_memory)


def read_facts_file(path: str | Path) -> list[Term]:
    """ASP facts from a file; a malformed one is a `UserError` naming file:line."""
    from aileen.terms import TermSyntaxError, parse_many, variables

    from aileen.memory.store import check_plain_file

    p = Path(path)
    if not check_plain_file(p, "facts file"):
        raise UserError("no such facts file", path=str(p))
    try:
        data = p.read_bytes()
    except OSError as exc:
        raise UserError(f"cannot read facts: {exc.strerror}", path=str(p)) from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise UserError(f"{p}:{line}: not UTF-8 text (byte {exc.start}); expected ASP facts such as "
                        "isa(o1,cv_red).") from None
    lines = []
    for raw in text.splitlines():
        lines.append(raw.split("%", 1)[0])  # ASP line comments
    text = "\n".join(lines)
    try:
        facts = parse_many(text)
    except TermSyntaxError as exc:
        line = text.count("\n", 0, exc.position) + 1
        col = exc.position - (text.rfind("\n", 0, exc.position) + 1) + 1
        raise UserError(f"{p}:{line}:{col}: {exc.reason} (expected ASP facts such as isa(o1,cv_red).)") from exc
    for f in facts:
        var = next(iter(variables(f)), None)
        if var is not None:  # clingo named it "<block>:3:1: ... unsafe", not this file
            at = re.search(rf"\b{re.escape(str(var))}\b", text)
            line = text.count("\n", 0, at.start()) + 1 if at else 1
            raise UserError(f"{p}:{line}: {f} holds the variable {var}: a fact names objects and classes "
                            "(lower case: isa(o1,cv_red).)")
    return facts


def _check(args: argparse.Namespace) -> int:
    from aileen.reasoning import asp, planner
    from aileen.reasoning.comprehension import RULE_FILES as COMP
    from aileen.reasoning.planner import RULE_FILES as PLAN

    groups = [asp.rule_paths(COMP, args.rules), planner.model_paths(args.rules)]
    known = {n for n in (*COMP, *PLAN)}
    if args.rules:
        extra = sorted(p for p in Path(args.rules).glob("*.lp") if p.name not in known)
        groups.extend([p] for p in extra)
    warnings = guard_rules(args.rules, args.rules_timeout, args.rules_memory)
    # (here, not before a run: a run meets such rules at its first call, and stops there)
    satisfiable_on_a_sample(groups[0], groups[1], args.rules or str(asp.rules_dir()))
    for g in groups:
        print(f"ok  {' + '.join(str(p) for p in g)}")
    for w in warnings:
        print(w)
    return 0


def _words(args: argparse.Namespace, facts: list[Term]) -> tuple[dict[str, str], list[Term]]:
    words: dict[str, str] = {}
    rest: list[Term] = []
    extra = read_facts_file(args.words) if args.words else []
    for f in (*facts, *extra):
        if f.name == "word_concept" and len(f.args) == 2:
            words[str(f.args[0])] = str(f.args[1])
        else:
            rest.append(f)
    return words, rest


def _comprehend(args: argparse.Namespace) -> int:
    from aileen.reasoning.comprehension import comprehend
    from aileen.reasoning.language import parse

    _limit(args)
    parsed = parse(args.sentence)
    words, facts = _words(args, read_facts_file(args.facts))
    result = comprehend(parsed, words=words, facts=facts, rules=args.rules)
    if args.json:
        out = {
            "sentence": parsed.sentence,
            "references": {o.id: list(o.words) for o in parsed.objects},
            "relation": None if parsed.relation is None else parsed.relation.word,
            "action": None if parsed.action is None else parsed.action.word,
            "referents": {k: [str(o) for o in v] for k, v in result.referents.items()},
            "relation_holds": result.relation_holds,
            "pairs": [[str(a), str(b)] for a, b in result.pairs],
            "goal": None if result.goal is None else str(result.goal.term()),
            "failures": [[f.reason, str(f.subject)] for f in result.failures],
            "ok": result.ok,
        }
        print(json.dumps(out, indent=2))
    else:
        for o in parsed.objects:
            objs = ", ".join(str(x) for x in result.referents.get(o.id, [])) or "-"
            print(f"{o.id} {o.text!r}: {objs}")
        if parsed.relation is not None:
            r = parsed.relation
            pairs = ", ".join(f"({a},{b})" for a, b in result.pairs) or "-"
            said = {True: "holds", False: "does not hold", None: "undecided"}[result.relation_holds]
            print(f"{r.id} {r.word}({r.arg1},{r.arg2}): {said} {pairs}")
        if parsed.action is not None:
            a = parsed.action
            print(f"{a.id} {a.word}({a.arg1},{a.arg2}): goal {result.goal.term() if result.goal else '-'}")
        for f in result.failures:
            print(f"failure: {f.reason} {f.subject}")
        print("ok" if result.ok else "failed")
    return 0 if result.ok else 1


def _check_goal(goal: list) -> None:  # noqa: ANN001 - terms
    """Each goal fact a relation the declared calculi perceive (between two objects), or a
    mark an action leaves or `held` (of one): a misspelt relation ("wst(o1,o2)") was planned,
    as a placement its planner could not check, and exit 0."""
    from aileen.domain import actions, calculi

    marks = {m for a in actions.ACTIONS.values() for m in a.marks} | {"held", calculi.MOVED}
    for f in goal:
        name, n = str(f.name), len(f.args)
        if n == 2 and calculi.calculus_of(name) is not None and f.args[0] == f.args[1]:
            raise UserError(f"--goal: {f} relates {f.args[0]} to itself: expected two objects")  # (it was "no plan")
        if (n == 2 and calculi.calculus_of(name) is not None) or (n == 1 and name in marks):
            continue
        known = ", ".join(sorted({c.relations[0] for c in calculi.CALCULI if c.relations})[:8])
        raise UserError(f"--goal: {f} is no relation the agent perceives: expected a relation of two objects "
                        f"from the declared calculi (e.g. {known}, ...; aileen/domain/calculi.py) or "
                        f"{', '.join(sorted(marks))} of one")


def _check_hand(state: list[Term], path: str) -> None:
    """A state with two objects in the hand is no state (the hand holds one at most: the world
    refuses a second pick-up): named with the file and the line of the second, rather than
    planned from silently."""
    held = [f for f in state if f.name == "held" and len(f.args) == 1]
    if len(held) < 2:
        return
    text = Path(path).read_text(encoding="utf-8", errors="replace")
    at = re.search(rf"\bheld\s*\(\s*{re.escape(str(held[1].args[0]))}\s*\)", text)
    line = text.count("\n", 0, at.start()) + 1 if at else None
    raise UserError(f"{held[1]} with {held[0]}: the hand holds one object at most; expected one held/1 fact or none",
                    path=str(path), line=line)


def _plan(args: argparse.Namespace) -> int:
    from aileen.reasoning.planner import NoPlan, plan
    from aileen.terms import TermSyntaxError, parse_many, variables

    _limit(args)
    state = read_facts_file(args.facts)
    try:
        goal = parse_many(args.goal)
    except TermSyntaxError as exc:
        raise UserError(f"--goal: {exc}") from exc
    if not goal:
        raise UserError("--goal: expected at least one fact, e.g. \"w(o1,o2). dc(o1,o2).\"")
    _check_goal(goal)
    _check_hand(state, args.facts)
    try:
        result = plan(state, goal, max_depth=args.max_depth, rules=args.rules)
    except NoPlan as exc:
        if args.json:  # indented, as a plan is
            print(json.dumps({"plan": None, "max_depth": exc.max_depth, "never": exc.never is not None,
                              "message": str(exc)}, indent=2))
        else:
            print(exc)
        return 1
    if args.json:
        steps = [{"action": str(s.action), "relations": [str(r) for r in s.relations]} for s in result.steps]
        print(json.dumps({"plan": steps, "depth": result.depth}, indent=2))
    else:
        if not result.steps:
            print("the goal already holds")
        for i, s in enumerate(result.steps, 1):
            print(f"{i}. {s}")
    return 0
