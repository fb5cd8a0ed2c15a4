"""`aileen run` (lesson files) and `aileen teach` (interactive lessons)."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from aileen import argtypes
from aileen.errors import UserError


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "run",
        help="run lesson files (our TOML or the original JSON) and print a transcript",
        description="Teach and test the agent with lesson files. Exit 0 when every graded lesson "
        "(verify, react) came out as the trainer expected, 1 otherwise, 2 for bad input.",
    )
    p.add_argument("files", nargs="+", metavar="FILE", help="lesson files (.toml or .json)")
    _common(p)
    p.add_argument("--json", action="store_true", help="one JSON object per lesson on stdout")
    p.add_argument("--save-images", metavar="DIR", help="write what the camera saw in each lesson")
    p.set_defaults(handler=_run)

    t = sub.add_parser(
        "teach",
        help="interactive session: set up scenes and type inform / verify / react lines",
        description="An interactive trainer's console (reads a script from stdin too). Type 'help'.",
    )
    _common(t)
    t.set_defaults(handler=_teach)


def _common(p: argparse.ArgumentParser) -> None:
    p.add_argument("--memory", metavar="PATH", help="load the agent's memory from PATH if it exists; save it there at the end")
    p.add_argument("--seed", type=argtypes.seed, default=None, help="seed for layouts and camera (default: the lesson file's)")
    p.add_argument("--rules", metavar="DIR", help="a directory of .lp files overriding the shipped asp/ rules")
    p.add_argument("--perception", choices=("detector", "truth"), default="detector",
                   help="'truth' replaces vision with the simulator's ground truth (an ablation)")


# ---------------------------------------------------------------------------- shared


def make_agent(args: argparse.Namespace):
    """An agent (with its memory loaded when --memory exists) and the frame hook for ablations."""
    from aileen.agent import Agent
    from aileen.memory.concept import ConceptMemory
    from aileen.memory.semantic import from_concepts

    memory = ConceptMemory()
    if args.memory and Path(args.memory).exists():
        memory = ConceptMemory.load(args.memory)
    on_frame = None
    perceiver = None
    if args.perception == "truth":
        from aileen.perception.truth import TruthVision

        perceiver = TruthVision()
        on_frame = perceiver.see_frame
    else:
        from aileen.perception.detector import load_detector

        load_detector()  # fail early, with the path and how to rebuild, if the model is missing
    if args.rules:
        _check_rules(args.rules)
    agent = Agent(memory, from_concepts(memory), rules=args.rules, perceiver=perceiver)
    return agent, on_frame


def _check_rules(rules: str) -> None:
    """Load and ground the user's rule files once, so a syntax error stops the run before
    any lesson (file:line:col, exit 2)."""
    from aileen.reasoning import asp, comprehension, planner

    if not Path(rules).is_dir():
        raise UserError("--rules must be a directory of .lp files", path=rules)
    asp.check_rule_files([asp.rule_paths(comprehension.RULE_FILES, rules), asp.rule_paths(planner.RULE_FILES, rules)])


def save_memory(agent, path: str | None) -> None:
    if path:
        agent.save(path)


# ---------------------------------------------------------------------------- run


def _run(args: argparse.Namespace) -> int:
    from dataclasses import replace

    from aileen.curriculum import trainer
    from aileen.curriculum.interpreter import Interpreter
    from aileen.curriculum.lesson import load_curriculum

    curricula = []
    for f in args.files:
        if not Path(f).is_file():
            raise UserError("no such lesson file", path=f)
        cur = load_curriculum(f)
        if args.seed is not None:
            cur = replace(cur, seed=args.seed)
        # Lay out every lesson before anything is learned: a bad lesson fails here, with its
        # file and line, and the memory file stays as it was.
        trainer.check_curriculum(cur.lessons, [cur.lesson_seed(i) for i in range(len(cur))])
        curricula.append(cur)
    agent, on_frame = make_agent(args)
    interp = Interpreter(agent, save_images=args.save_images, on_frame=on_frame)
    results = []
    out = sys.stdout
    for cur in curricula:
        if not args.json and len(curricula) > 1:
            print(f"== {cur.path or 'lessons'}: {cur.title}", file=out)
        for i, lesson in enumerate(cur.lessons):
            r = interp.run(lesson, index=i + 1, seed=cur.lesson_seed(i))
            results.append(r)
            if args.json:
                print(json.dumps(r.to_json()), file=out, flush=True)
            else:
                print(transcript(r), file=out, flush=True)
    summary = summarise(results)
    print(summary, file=sys.stderr if args.json else out)
    save_memory(agent, args.memory)
    graded = [r.correct for r in results if r.correct is not None]
    return 0 if all(graded) else 1


def transcript(r) -> str:
    """A lesson as a person reads it."""
    a = r.answer
    head = (f"lesson {r.index:>2}  " if r.index else "") + f"{a.signal:<6}  \"{a.content}\""
    if r.lesson.note:
        head += f"   ({r.lesson.note})"
    lines = [head, "  saw:      " + ("; ".join(r.seen) if r.seen else "nothing")]
    answer = a.result + (f": {a.reason}" if a.reason else "")
    if a.referents and a.result == "success":
        answer += "  [" + ", ".join(f"{k} = {' '.join(v) or '-'}" for k, v in a.referents.items()) + "]"
    lines.append(f"  answer:   {answer}")
    if a.signal == "react":
        lines.append(f"  acted:    {', '.join(a.steps) or 'nothing'} ({a.projections} projections)")
        if r.goal_holds is not None:
            lines.append(f"  trainer:  the goal {'holds' if r.goal_holds else 'does NOT hold'}")
    if a.created or a.stored:
        parts = []
        if a.created:
            parts.append("created " + ", ".join(a.created))
        if a.stored:
            parts.append("stored " + ", ".join(a.stored))
        lines.append(f"  learned:  {'; '.join(parts)}  ({a.commands} commands)")
    if r.correct is not None and a.signal == "verify":
        lines.append(f"  trainer:  expected {r.expected}: {'right' if r.correct else 'WRONG'}")
    return "\n".join(lines)


def summarise(results) -> str:
    n = len(results)
    cmds = sum(r.answer.commands for r in results)
    verify = [r for r in results if r.answer.signal == "verify" and r.correct is not None]
    react = [r for r in results if r.answer.signal == "react"]
    parts = [f"{n} lessons", f"{cmds} create/store commands"]
    if verify:
        parts.append(f"verify {sum(r.correct for r in verify)}/{len(verify)} right")
    if react:
        parts.append(f"react {sum(bool(r.correct) for r in react)}/{len(react)} reached the goal")
    ms = sorted(r.seconds for r in results)
    if ms:
        parts.append(f"median lesson {1000 * ms[len(ms) // 2]:.0f} ms")
    return "summary: " + ", ".join(parts)


# ---------------------------------------------------------------------------- teach


def _lines(interactive: bool):
    """Input lines: prompted when a person types, read straight through from a script."""
    if not interactive:
        yield from sys.stdin
        return
    while True:
        try:
            yield input("> ")
        except EOFError:
            print()
            return


def _teach(args: argparse.Namespace) -> int:
    from aileen.curriculum.console import Console

    agent, on_frame = make_agent(args)
    console = Console(agent, seed=args.seed or 0, on_frame=on_frame, memory_path=args.memory)
    interactive = sys.stdin.isatty()
    if interactive:
        print("aileen teach: type 'help' for commands, 'quit' to leave.")
    for lineno, line in enumerate(_lines(interactive), 1):
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        if line in ("quit", "exit"):
            break
        try:
            print(console.do(line), flush=True)
        except UserError as exc:
            if not interactive:  # a script: stop at its first mistake, naming the line
                raise UserError(exc.format(), path="<stdin>", line=lineno) from None
            print(f"error: {exc.format()}")
    if args.memory:
        save_memory(agent, args.memory)
    return 0
