"""`aileen run` (lesson files) and `aileen teach` (interactive lessons)."""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import sys
from pathlib import Path

from aileen import argtypes, lifecycle
from aileen.agent.records import ABLATIONS, SENSES
from aileen.curriculum.report import summarise, transcript
from aileen.errors import UserError
from aileen.memory.store import check_output_dir


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "run",
        help="run lesson files (our TOML or the original JSON) and print a transcript",
        description="Teach and test the agent with lesson files. Exit 0 when every graded lesson "
        "(verify, react) came out as the trainer expected and none was skipped, 1 otherwise (the summary "
        "says how many were wrong and how many skipped: a lesson the trainer cannot lay out on the table "
        "is skipped with its reason, and the run goes on), 2 for bad input.",
    )
    p.add_argument("files", nargs="+", metavar="FILE", help="lesson files (.toml or .json)")
    _common(p)
    p.add_argument("--json", action="store_true", help="one JSON object per lesson on stdout")
    p.add_argument("--save-images", metavar="DIR", help="write what the camera saw in each lesson")
    p.set_defaults(handler=_run, closed_output="so the lessons after it were not given")

    t = sub.add_parser(
        "teach",
        help="interactive session: set up scenes and type inform / verify / react lines",
        description="An interactive trainer's console (reads a script from stdin too). Type 'help'.",
    )
    _common(t, seed_default="0")
    add_autosave(t, "every lesson, verdict and undo")
    t.set_defaults(handler=_teach, closed_output="so the lines after it were not done")


def _common(p: argparse.ArgumentParser, *, seed_default: str = "the lesson file's") -> None:
    from aileen.reasoning.guard import add_limit_args

    p.add_argument("--memory", metavar="PATH", help="load the agent's memory from PATH if it exists; save it there "
                   "at the end (the file is locked while the run uses it)")
    p.add_argument("--seed", type=argtypes.seed, default=None,
                   help=f"seed for layouts and camera, a whole number >= 0 (default: {seed_default})")
    p.add_argument("--rules", metavar="DIR", help="a directory of .lp files overriding the shipped asp/ rules")
    add_limit_args(p)
    p.add_argument("--perception", choices=("detector", "truth"), default="detector",
                   help="'truth' replaces vision with the simulator's ground truth (an ablation)")
    p.add_argument("--without", action="append", default=[], metavar="MECHANISM",
                   help="switch a learning mechanism off (repeatable): " + ", ".join(ABLATIONS))
    add_senses(p)
    p.add_argument("--agent", choices=("asp", "soar"), default="asp",
                   help="asp (default): the ASP agent; soar: the paper's learner as Soar productions "
                   "(needs the 'soar' extra)")
    p.add_argument("--soar-listen", type=int, default=None, metavar="PORT",
                   help="with --agent soar: open Soar's listener on PORT, so Soar's debugger or CLI can attach")


def add_autosave(p: argparse.ArgumentParser, after: str) -> None:
    """`--autosave` (`aileen teach`, `serve`): save the memory file after each change, so a
    session killed where no signal can be caught (SIGKILL, the machine's power, an out-of-memory
    kill) loses at most the lesson under way. On by default: a save of a learner's memory takes
    milliseconds (it is written to a temporary file and renamed in, never half-written)."""
    p.add_argument("--autosave", action=argparse.BooleanOptionalAction, default=True,
                   help=f"with --memory: save it after {after} (default), so even a killed session keeps "
                   "every lesson it finished; --no-autosave saves only on 'save', at the end and on a stop signal")


def add_senses(p: argparse.ArgumentParser) -> None:
    """`--senses`: the agent's sense of direction (`aileen run`, `teach`, `serve`)."""
    p.add_argument("--senses", choices=SENSES, default=None,
                   help="the agent's sense of direction: cones (four 90-degree cones), sectors (the paper's 8), "
                   "or all (every grain at once). Default: the agent's own")


# ---------------------------------------------------------------------------- shared


def open_memory(args: argparse.Namespace):
    """The memory file, checked and locked for the whole run (None without --memory)."""
    from aileen.memory.store import MemoryFile

    if args.memory is None:
        return None
    if not args.memory:
        raise UserError("--memory needs a file name (an empty one was given); leave --memory out to run "
                        "without keeping what is learned")
    return MemoryFile.open(args.memory)


@contextlib.contextmanager
def agent_session(args: argparse.Namespace):
    """The memory file (locked) and an agent on it, for the length of a `run` or `teach`:
    yields (agent, on_frame, memory_file); the agent and the file are closed on every path.

    The final save is the caller's (what counts as finished differs). A run that stops early
    (a `UserError` such as rules over their limit, or a stop signal: `lifecycle.Stopped`) has
    what it learned saved here on the way out, and the exception says where (`kept`), for the
    one line the command line ends with. A process stuck in clingo saves through the keeper."""
    from aileen.curriculum.interpreter import close_agent

    memory_file = open_memory(args)
    agent = None
    try:
        agent, on_frame = make_agent(args, memory_file)
        with lifecycle.keeper(lambda: keep(memory_file, agent)):
            yield agent, on_frame, memory_file
    except (UserError, KeyboardInterrupt) as exc:
        if agent is not None and lifecycle.kept(exc) is None:
            lifecycle.set_kept(exc, keep(memory_file, agent, stopped=isinstance(exc, KeyboardInterrupt)))
        raise
    except Exception as exc:  # a closed pipe (`| head`), or a defect: what was learned is still kept
        if agent is not None:
            note = keep(memory_file, agent, stopped=False)
            if isinstance(exc, BrokenPipeError):  # the closed-output line says where it went, as a signal's does
                lifecycle.set_kept(exc, note)
            elif note:
                with contextlib.suppress(OSError, ValueError):
                    print(f"aileen: {type(exc).__name__} inside aileen, a defect to report; {note}",
                          file=sys.stderr, flush=True)
        raise
    finally:
        if agent is not None:
            close_agent(agent)
        if memory_file is not None:
            memory_file.close()


def keep(memory_file, agent, *, stopped: bool = True) -> str | None:  # noqa: ANN001
    """Save what `agent` learned to the memory file on the way out; a note of where it went
    (None without --memory, for an error: nothing to say)."""
    if memory_file is None:
        return "nothing is kept without --memory" if stopped else None
    return memory_file.keep(agent)


def make_agent(args: argparse.Namespace, memory_file=None):
    """An agent (with its memory loaded when the memory file exists) and the frame hook for
    ablations. Checks the rules (under the time limit) and the detector first."""
    from aileen.agent import Agent
    from aileen.agent.records import ablated
    from aileen.memory.concept import ConceptMemory
    from aileen.memory.semantic import from_concepts
    from aileen.reasoning import asp, watchdog
    from aileen.reasoning.commands import guard_rules

    senses = getattr(args, "senses", None)
    if senses is not None and getattr(args, "agent", "asp") == "soar":
        raise UserError("--senses is for the asp agent; the Soar agent, the paper's learner, sees the cones")
    params = ablated(getattr(args, "without", []), senses)
    memory = ConceptMemory(params.sage())
    if memory_file is not None and memory_file.exists:
        memory = ConceptMemory.load(memory_file.path)
        # a compact file's concepts are read when first used: read them all now, so a damaged
        # one (its checksum right) stops the run before any lesson, not lesson by lesson and
        # then the save, with what was learned in no file; a run reads them all anyway
        memory.read_all()
    from aileen.domain.extensions import ENV as DOMAIN_ENV

    # rules of the user's own, or declarations (`AILEEN_DOMAIN`: an action's model file): checked
    # before any work (a broken model file was each react's "failure", graded, exit 1)
    lp_rules = None if getattr(args, "agent", "asp") == "soar" else args.rules  # (Soar's are .soar files)
    if lp_rules or os.environ.get("AILEEN_RULES") or os.environ.get(DOMAIN_ENV):
        for w in guard_rules(lp_rules, args.rules_timeout, args.rules_memory):
            print(f"aileen: rules: {w}", file=sys.stderr)  # a misspelt predicate shows here first
    else:  # the shipped rules: a call past the limit is a slow search (a busy machine), not a user's rule
        from aileen.reasoning.comprehension import RULE_FILES as COMP
        from aileen.reasoning.planner import RULE_FILES as PLAN
        from aileen.reasoning.rulefiles import readable_rule_paths

        readable_rule_paths((*COMP, *PLAN))  # a broken install stops here, before any lesson
        asp.set_solve_limit(args.rules_timeout, watchdog.SHIPPED, megabytes=args.rules_memory)
    on_frame = None
    perceiver = None
    if args.perception == "truth":
        from aileen.perception.truth import TruthVision

        perceiver = TruthVision()
        on_frame = perceiver.see_frame
    else:
        from aileen.perception.detector import load_detector

        load_detector()  # fail early, with the path and how to rebuild, if the model is missing
    if getattr(args, "agent", "asp") == "soar":  # its rules are .soar files, checked as it loads them
        from aileen.soar.learner import soar_agent

        return soar_agent(memory, without=args.without, perceiver=perceiver, rules=args.rules,
                          memory_path=memory_file.path if memory_file is not None else None,
                          listen=getattr(args, "soar_listen", None)), on_frame
    if getattr(args, "soar_listen", None) is not None:
        raise UserError("--soar-listen is for the Soar agent (--agent soar)")
    agent = Agent(memory, from_concepts(memory), params=params, rules=args.rules, perceiver=perceiver)
    return agent, on_frame


# ---------------------------------------------------------------------------- run


def _run(args: argparse.Namespace) -> int:
    from dataclasses import replace

    from aileen.curriculum import rehearsal
    from aileen.curriculum.formats import load_curriculum
    from aileen.curriculum.lesson import check_lesson_path

    curricula = []
    setups = []
    for f in args.files:
        check_lesson_path(f)
        cur = load_curriculum(f)
        if args.seed is not None:
            cur = replace(cur, seed=args.seed)
        # Lay out every lesson before anything is learned: a bad lesson fails here, with its
        # file and line, and the memory file stays as it was. A lesson the trainer cannot lay
        # out is no mistake in the file: it is skipped with its reason when its turn comes.
        setups.append(rehearsal.check_curriculum(cur.lessons, [cur.lesson_seed(i) for i in range(len(cur))],
                                                 skip=True, progress=str(f) if sys.stderr.isatty() else None))
        curricula.append(cur)
    if args.save_images:
        check_output_dir(args.save_images, "--save-images")
    with agent_session(args) as (agent, on_frame, memory_file):
        notes = _prerequisites(curricula, agent, args.memory)
        if args.perception == "detector":
            notes += unseen_shapes(curricula, setups)
        for note in notes:
            print(note, file=sys.stderr, flush=True)
        results = _run_lessons(args, agent, on_frame, curricula, setups)
        summary = summarise(results)
        print(summary, file=sys.stderr if args.json else sys.stdout)
        if memory_file is not None:
            memory_file.save(agent)
    graded = [r.correct for r in results if r.correct is not None]
    skipped = [r for r in results if r.skipped is not None]
    return 0 if all(graded) and not skipped else 1



def _prerequisites(curricula, agent, memory: str | None) -> list[str]:  # noqa: ANN001
    """Notes for lesson files that take words as known which the memory lacks and nothing
    before them teaches (`curriculum.prerequisites`): which file to run first."""
    from aileen.curriculum.prerequisites import advice

    mem = getattr(agent, "memory", None)
    known = {c.symbol[2:] for c in mem.concepts() if c.symbol.startswith("r_")} if mem is not None else set()
    return advice(curricula, known, memory)


def unseen_shapes(curricula, setups) -> list[str]:  # noqa: ANN001
    """Notes for lessons that put on the table a shape the detector was not trained on (the
    capsule, with the shipped model): the agent perceives it as another shape, so what it
    learns there and answers is about that shape. One note per file and shape, naming its
    lessons; none when the detector knows every shape on the tables."""
    from aileen.curriculum.console import UNTRAINED_SEE
    from aileen.curriculum.stage import Setup
    from aileen.perception.detector import load_detector

    detector = load_detector()
    notes = []
    for cur, laid in zip(curricula, setups):
        where: dict[str, list[int]] = {}
        for i, setup in enumerate(laid, start=1):
            if isinstance(setup, Setup):
                for shape in sorted({o.shape for o in setup.world.objects()} & detector.untrained):
                    where.setdefault(shape, []).append(i)
        for shape, lessons in where.items():
            which = f"lesson {lessons[0]}" if len(lessons) == 1 else f"lessons {', '.join(map(str, lessons))}"
            notes.append(f"note: {cur.path or 'lessons'}: {which} put a {shape} on the table, a shape the detector "
                         f"({detector.path}) was not trained on: it is perceived as another shape {UNTRAINED_SEE}")
    return notes


def _run_lessons(args: argparse.Namespace, agent, on_frame, curricula, setups=None) -> list:  # noqa: ANN001
    """Run the curricula in order; `setups` (per curriculum, per lesson) are the tables the
    up-front check laid out, used instead of laying each lesson out again."""
    from aileen.curriculum.interpreter import Interpreter

    interp = Interpreter(agent, save_images=args.save_images, on_frame=on_frame)
    interp.mean_as_said(lesson for cur in curricula for lesson in cur.lessons)
    interp.files_contradict = True
    results = []
    out = sys.stdout
    # The run may stop (rules over their time limit, an image that cannot be written, a stop
    # signal): `agent_session` keeps what was learned before. A stop signal waits for the
    # lesson to end (`lifecycle.lesson`), so only whole lessons are kept, each one reported.
    for k, cur in enumerate(curricula):
        if not args.json and len(curricula) > 1:
            print(f"== {cur.path or 'lessons'}" + (f": {cur.title}" if cur.title else ""), file=out)
        for i, lesson in enumerate(cur.lessons):
            laid = setups[k][i] if setups is not None else None
            with lifecycle.lesson():
                r = interp.run(lesson, index=i + 1, seed=cur.lesson_seed(i), setup=laid)
                results.append(r)
                if args.json:
                    # which file and lesson each record is of: `index` counts from 1 in every file
                    record = {**r.to_json(), "file": cur.path or None}
                    if lesson.note:
                        record["note"] = lesson.note
                    print(json.dumps(record), file=out, flush=True)
                else:
                    print(transcript(r), file=out, flush=True)
    return results


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
    """Read commands until `quit` or the end of input. A mistake is reported with its line
    and the session goes on (a script ends with exit 2 if any line failed); the memory is
    saved at the end."""
    from aileen.curriculum.console import Console
    from aileen.reasoning.asp import RulesError
    from aileen.reasoning.planner import NoPlan

    with agent_session(args) as (agent, on_frame, memory_file):
        unseen: frozenset[str] = frozenset()
        if args.perception == "detector":
            from aileen.perception.detector import load_detector

            unseen = load_detector().untrained
        console = Console(agent, seed=args.seed or 0, on_frame=on_frame, memory_file=memory_file, unseen=unseen)
        interactive = sys.stdin.isatty()
        if interactive:
            print("aileen teach: type 'help' for commands, 'quit' to leave.")
        failed = 0
        # Stopped early (a signal, rules over their limit): `agent_session` keeps what was learned.
        for lineno, line in enumerate(_lines(interactive), 1):
            line = line.split("#", 1)[0].strip()  # a comment: a whole line, or after a command
            if not line:
                continue
            if line.lower() in ("quit", "exit"):
                break
            try:
                with lifecycle.lesson(outcomes=(NoPlan,)):  # a stop waits for the lesson's end
                    print(console.do(line), flush=True)
                if memory_file is not None and args.autosave and console.changes_memory(line):
                    memory_file.save(console.agent)  # a kill now loses nothing finished
            except RulesError:
                raise
            except (UserError, NoPlan) as exc:
                failed += 1
                msg = exc.format() if isinstance(exc, UserError) else str(exc)
                where = "" if interactive else f"<stdin>:{lineno}: "
                print(f"error: {where}{msg}", file=sys.stdout if interactive else sys.stderr, flush=True)
        if memory_file is not None:
            memory_file.save(agent)
            # where it went, as `save` and a stop signal say it (quit and the end of input said nothing)
            print(f"aileen teach: {memory_file.saved_note()}", file=sys.stderr, flush=True)
    if failed and not interactive:
        print(f"aileen teach: {failed} line(s) failed", file=sys.stderr)
        return 2
    return 0
