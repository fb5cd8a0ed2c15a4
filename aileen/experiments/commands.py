"""`aileen experiment visual|spatial|action|all|react`: the evaluation (wide or paper protocol), as one command.

Writes, under --out DIR: `<experiment>/trials.csv` (one row per trial and lesson),
`<experiment>/summary.csv` (per lesson: mean and standard deviation across trials),
`<experiment>/curve.png` (paper-style plot with the one-shot oracle and the original system's
curve), `react/tasks.csv`, and `summary.json` (the headline figures of docs/results.md).
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path
from typing import Any

from aileen import argtypes, lifecycle
from aileen.agent.records import ABLATIONS, SENSES
from aileen.errors import UserError
from aileen.experiments.protocol import (AGENT_KINDS, EXPERIMENTS, MAX_TRIALS, PROTOCOL_EXPERIMENTS, PROTOCOLS,
                                        not_in_protocol)

CHOICES = EXPERIMENTS + ("all", "react", "sweep")


class _KeepIndented(argparse.HelpFormatter):
    """Wraps paragraphs as usual but keeps indented blocks (the example grid) as written."""

    def _fill_text(self, text: str, width: int, indent: str) -> str:
        out = []
        for block in text.split("\n\n"):
            if block.startswith("    "):
                out.append("\n".join(indent + ln for ln in block.splitlines()))
            else:
                out.append(super()._fill_text(block, width, indent))
        return "\n\n".join(out)


def register(subparsers: Any) -> None:
    """Add the `experiment` subcommand."""
    from aileen.experiments.grid import EXAMPLE

    p = subparsers.add_parser(
        "experiment",
        help="run the paper's learning-curve experiments (CSV, PNG) and the react benchmark",
        description="Learning curves. visual: 24 inform lessons (the 20 colour-shape objects and 4 shapes); "
        "spatial: 20 lessons over left of / right of / in front of / behind, visual words taught first; action: 20 "
        "'move X <relation> Y' demonstrations, visual and spatial words taught first; repertoire (wide protocol "
        "only): 20 lessons over the size words and near / far from / next to / larger than / smaller than, visual "
        "words and the four directions taught first. After every lesson a 5-item "
        "generality and a 5-item specificity exam (verify lessons, 0-3 distractors), drawn once per trial. The wide "
        "protocol (default) lays relations out up to 40 degrees off their axis and makes the specificity exams near "
        "misses; --protocol paper is the paper's. react: after training, N random 'move X <relation> Y' tasks "
        "(wide: 'move' shown with left of / right of only, tasks behind / in front of; --relations: the tasks ask "
        "for those words); success = the goal holds in the world. teacher protocol (spatial): each trial draws a "
        "teacher, who accepts each direction word within its own half-angle (20-50 degrees) and uses one or two "
        "diagonal or narrow words; near misses just outside its edge; an ideal observer beside the one-shot oracle. "
        "all: every experiment of the protocol with the baselines, and react; with the wide protocol, the teacher "
        "protocol's experiments too.",
        epilog="sweep: GRID.toml names the points to run; an example with every key (python -c \"from "
        "aileen.experiments.grid import EXAMPLE; print(EXAMPLE)\" > grid.toml writes it):\n\n"
        + "\n".join("    " + line for line in EXAMPLE.splitlines())
        + "\n\nthen: aileen experiment sweep grid.toml --out sweep --jobs 2",
        formatter_class=_KeepIndented,
    )
    p.add_argument("which", choices=CHOICES, metavar="{" + ",".join(CHOICES) + "}",
                   help="which experiment to run; sweep: a grid of SAGE thresholds, mechanisms, "
                   "experiments, protocols and seeds read from GRID (see aileen/experiments/grid.py)")
    p.add_argument("grid", nargs="?", default=None, metavar="GRID.toml",
                   help="sweep only: the grid file (trials, seeds, perception and lessons come from it)")
    p.add_argument("--backend", choices=("local", "ray"), default="local",
                   help="sweep only: local (default) runs trials in --jobs processes; ray runs them as Ray "
                   "tasks (pip install 'aileen[ray]') on a local Ray, or on the cluster at --address")
    p.add_argument("--address", default=None, metavar="ADDR",
                   help="sweep with --backend ray: an existing Ray cluster (e.g. 10.0.0.5:6379)")
    p.add_argument("--trials", type=int, default=None,
                   help="trials per experiment (default visual 10, spatial 10, action 5, repertoire 10); for react, "
                   "the number of tasks (default 50; 'all' runs react's 50 whatever --trials says)")
    p.add_argument("--seed", type=argtypes.seed, default=0, help="trial i is seeded from (seed, i) alone (default 0)")
    p.add_argument("--jobs", type=int, default=1,
                   help="parallel worker processes; results are identical for any value (default 1)")
    p.add_argument("--out", default="results", help="output folder (default results)")
    p.add_argument("--perception", choices=("detector", "truth"), default="detector",
                   help="detector (default): the shipped vision (detector + colour module). truth: the "
                   "simulator's ground truth instead; an ablation that separates perception errors from "
                   "learning errors, not a result")
    p.add_argument("--lessons", type=int, default=None, metavar="K",
                   help="run only the first K training lessons of each trial (quick checks, tests)")
    p.add_argument("--without", action="append", default=[], metavar="MECHANISM",
                   help="switch a learning mechanism off, to measure what it is worth (repeatable; react "
                   "too: its training and its tasks): " + ", ".join(ABLATIONS))
    p.add_argument("--agent", choices=AGENT_KINDS, default=None,
                   help="asp (default), or soar: the paper's learner as Soar productions (the 'soar' extra), "
                   "or one baseline alone: paper (our agent with its mechanisms off), "
                   "nearest (nearest neighbour), cobweb (COBWEB, the 'baselines' extra; nearest and cobweb: "
                   "visual and spatial only), trestle (TRESTLE, the same extra; spatial only)")
    p.add_argument("--protocol", choices=PROTOCOLS, default=None,
                   help="wide (default): relations laid out over the whole region a person accepts (up to 40 "
                   "degrees off the axis) and near-miss specificity exams (the same colour or shape; the "
                   "opposite, a perpendicular or the role-swapped layout; the wrong object moved, or moved to "
                   "the wrong place). paper: the paper's protocol, exactly as published. teacher (spatial only): "
                   "a teacher drawn per trial, whose words' regions vary (experiments/teacher.py)")
    p.add_argument("--senses", choices=SENSES, default=None,
                   help="the agent's sense of direction: cones (four 90-degree cones), sectors (the paper's 8), or "
                   "all (every grain at once); the baselines that learn from the agent's facts get the same. "
                   "Default: the agent's own")
    p.add_argument("--baselines", action=argparse.BooleanOptionalAction, default=None,
                   help="also run the baseline learners side by side (the paper's learner, nearest neighbour, and "
                   "COBWEB with the 'baselines' extra): CSVs under <experiment>/baselines/, curves on the plot, "
                   "figures under \"baselines\" in summary.json. Default: on for 'all', off otherwise")
    p.add_argument("--relations", default=None, metavar="WORDS",
                   help="react only: the goal words the tasks ask for, comma-separated (e.g. "
                   "near,next-to,far-from,on: acting on distance and contact words); each is first taught as a "
                   "spatial word, 'move' is shown as without it. Default: the protocol's words")
    p.add_argument("--no-plot", action="store_true", help="write the CSV and JSON files only")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(handler=run_experiment_command)


def run_experiment_command(args: argparse.Namespace) -> int:
    """Run, write the files, print the headline table. Exit 0; UserError (2) for bad input."""
    if args.which == "sweep":
        return _sweep(args)
    args.protocol = args.protocol or "wide"  # (None: not given; a sweep refuses it given)
    args.agent = args.agent or "asp"
    if args.grid is not None:
        raise UserError(f"a grid file is for 'experiment sweep', not {args.which!r}")
    if args.trials is not None and not 1 <= args.trials <= MAX_TRIALS:
        raise UserError(f"--trials must be from 1 to {MAX_TRIALS}, got {args.trials}")
    if args.jobs < 1:
        raise UserError(f"--jobs must be at least 1, got {args.jobs}")
    if args.lessons is not None and args.lessons < 1:
        raise UserError(f"--lessons must be at least 1, got {args.lessons}")
    if args.which in EXPERIMENTS or args.which == "all":
        from aileen.experiments.protocol import too_many_lessons

        which = PROTOCOL_EXPERIMENTS[args.protocol] if args.which == "all" else (args.which,)
        why = too_many_lessons(args.lessons, which, (args.protocol,))
        if why is not None:
            raise UserError(f"--lessons {args.lessons}: {why}")
    if args.relations is not None and args.which != "react":
        raise UserError(f"--relations is for 'experiment react', not {args.which!r}")
    if args.relations is not None:
        from aileen.experiments.react import parse_relations

        args.relations = parse_relations(args.relations)
    if args.which in EXPERIMENTS and args.which not in PROTOCOL_EXPERIMENTS[args.protocol]:
        raise UserError(f"{not_in_protocol(args.which, args.protocol)}; expected one of "
                        f"{', '.join(PROTOCOL_EXPERIMENTS[args.protocol])} (or another --protocol)")
    if args.senses is not None and args.agent == "soar":
        raise UserError("--senses is for the asp agent and the baselines; the Soar agent, the paper's learner, has one sense (the cones)")
    if args.which == "react" and args.protocol == "teacher":
        raise UserError("react has the wide and the paper protocol; expected --protocol wide or paper")
    if args.which == "react" and args.agent != "asp":
        raise UserError(f"react runs the asp agent; for --agent {args.agent} expected --agent asp "
                        "(the Soar agent's react tasks: python benchmarks/soar.py)")
    args.without = list(dict.fromkeys(args.without or ()))  # a mechanism named twice is switched off once
    _check_consistent(args)
    from aileen.experiments.runner import check_learner

    check_learner(args.without, args.senses, args.agent)  # (--without bogus, a missing extra)
    from aileen.experiments import output

    out = output.out_folder(args.out)  # (after every check: a refused command leaves no folder behind)
    if not args.no_plot and args.which != "react":
        from aileen.experiments.plots import require_matplotlib

        require_matplotlib()  # before the work: the run takes minutes
    if args.perception == "detector":
        from aileen.perception.detector import load_detector

        load_detector()  # a missing or broken model fails here, before any trial runs
    from aileen.experiments.local_backend import shared_pool

    names = PROTOCOL_EXPERIMENTS[args.protocol] if args.which == "all" else (
        () if args.which == "react" else (args.which,))
    from aileen.experiments.baselines import EXPERIMENTS as BASELINE_EXPERIMENTS

    if args.which == "all" and args.agent in BASELINE_EXPERIMENTS:
        takes = BASELINE_EXPERIMENTS[args.agent]
        left = [n for n in names if n not in takes] + ["react"]
        print(f"aileen: note: --agent {args.agent} takes {', '.join(takes)}; {', '.join(left)} left out",
              file=sys.stderr)
        names = tuple(n for n in names if n in takes)
    try:
        cpu0, t0 = os.times(), time.perf_counter()
        with output.locked(out, f"aileen experiment {args.which}"), shared_pool(args.jobs):
            rc = _run(args, out, names)
        print(_cpu_line(cpu0, os.times(), time.perf_counter() - t0, args.jobs))
        return rc
    except KeyboardInterrupt as exc:  # a stop signal before the files were written: say what was kept
        if lifecycle.kept(exc) is None:
            lifecycle.set_kept(exc, f"nothing of this run was written (its finished trials too); the files in "
                               f"{out} are as before")
        raise


def _cpu_line(before: os.times_result, after: os.times_result, wall_s: float, jobs: int) -> str:
    """The run's CPU time (this process and its worker processes, which have ended by now),
    beside its wall time: wall time on a shared or slower machine is not the work done, and the
    CPU time tells a reader how busy the cores were."""
    cpu = sum(after[k] - before[k] for k in range(4))  # user and system, of this process and its children
    return (f"CPU time: {cpu:.1f} s in {wall_s:.1f} s of wall time (this process and its workers; "
            f"{cpu / max(wall_s, 1e-9):.2f} cores busy on average, {jobs} job{'s' if jobs != 1 else ''})")


def _check_consistent(args: argparse.Namespace) -> None:
    """Options a run would leave out without a word are refused, one line each: a baseline
    agent on an experiment it cannot take (its figures were printed as ours), mechanisms
    switched off in an agent that has none of them, a sense the same command switches off,
    the sweep's backend outside a sweep, baselines beside react (which has none)."""
    from aileen.experiments.baselines import EXPERIMENTS as BASELINE_EXPERIMENTS

    if args.agent in BASELINE_EXPERIMENTS and args.which in EXPERIMENTS \
            and args.which not in BASELINE_EXPERIMENTS[args.agent]:
        raise UserError(f"--agent {args.agent} takes {', '.join(BASELINE_EXPERIMENTS[args.agent])} only, "
                        f"not {args.which}")
    if args.without and args.agent != "asp":
        # (the Soar agent is the paper's learner: it ran as without them, and the summary
        # recorded mechanisms switched off that it never had)
        raise UserError(f"--without switches off the asp agent's mechanisms; --agent {args.agent} has none of them")
    if args.agent == "soar" and args.protocol == "teacher":
        # its trials learn from the trainer's verdicts, which the Soar agent does not yet: it
        # stopped after the first trial's work with nothing written
        raise UserError("--protocol teacher gives the trainer's verdicts ('wrong'), which the Soar agent does not "
                        "learn from yet; use --agent asp")
    if args.senses is not None and "cones" in args.without:
        if args.senses == "sectors":
            raise UserError("--without cones is --senses sectors (the paper's sectors): give one of them")
        raise UserError(f"--without cones is the paper's sectors, which contradicts --senses {args.senses}; "
                        "give one (--senses sectors says the same)")
    if args.backend != "local" or args.address is not None:
        raise UserError("--backend and --address are for 'experiment sweep'")
    if args.which == "react" and args.baselines:
        raise UserError("react has no baselines: it runs the asp agent alone")
    if args.which == "react" and args.lessons is not None:
        raise UserError("--lessons cuts the learning curves' training; react's training is its protocol's, whole")


# Run beside the wide protocol's experiments by `aileen experiment all`: the teacher protocol
# (ours alone: its baselines are a separate `--protocol teacher --baselines` run, to keep `all`
# within its time), written under <out>/teacher-<experiment>/.
ALL_EXTRA: dict[str, tuple[str, ...]] = {"wide": ("teacher",)}


def _run(args: argparse.Namespace, out: Path, names: tuple[str, ...]) -> int:
    """Every run the command asks for (ours, the baselines, react) is started at once, so their
    trials share the worker pool; the files and the table come out in a fixed order."""
    from concurrent.futures import ThreadPoolExecutor

    from aileen.experiments import output
    from aileen.experiments import react as react_mod
    from aileen.experiments import results as records
    from aileen.experiments import runner, tables

    t_all = time.perf_counter()
    with_baselines = args.baselines if args.baselines is not None else args.which == "all"
    # (protocol, experiment): the runs asked for, each under its key in summary.json
    plan = [(args.protocol, n) for n in names]
    if args.which == "all":
        plan += [(extra, n) for extra in ALL_EXTRA.get(args.protocol, ()) for n in PROTOCOL_EXPERIMENTS[extra]]

    def key(protocol: str, name: str) -> str:
        return name if protocol == args.protocol else f"{protocol}-{name}"

    learners = {(pr, n): [args.agent] + ([b for b in _baselines_for(n) if b != args.agent]
                                         if with_baselines and pr == args.protocol else [])
                for pr, n in plan}

    def one(protocol: str, name: str, learner: str):  # noqa: ANN202
        return runner.run_experiment(name, trials=args.trials, seed=args.seed, jobs=args.jobs,
                                     perception=args.perception, lessons=args.lessons, progress=_bars(args),
                                     without=args.without if learner == args.agent else (),
                                     agent_kind=learner, protocol=protocol, senses=args.senses)

    do_react = args.which in ("react", "all") and args.protocol != "teacher" and args.agent == "asp"
    if args.which == "all" and not do_react:
        why = ("the teacher protocol has no react tasks" if args.protocol == "teacher"
               else f"react runs the asp agent alone, not --agent {args.agent}")
        print(f"aileen: note: 'all' runs no react benchmark here: {why}", file=sys.stderr)
    # every file the run will write, tried before any trial runs (a file where a folder goes
    # was a traceback once every trial had run)
    output.check_writable([out / "summary.json"] + [
        p for pr, n in plan
        for p in output.experiment_paths(out, key(pr, n), plot=not args.no_plot, baselines=learners[(pr, n)][1:])
    ] + ([out / "react" / "tasks.csv"] if do_react else []))
    tasks = args.trials if args.which == "react" and args.trials is not None else react_mod.DEFAULT_TASKS
    runs = [(pr, n, k) for pr, n in plan for k in learners[(pr, n)]]
    with ThreadPoolExecutor(max_workers=max(1, len(runs) + do_react) if args.jobs > 1 else 1) as threads:
        futures = {run: threads.submit(one, *run) for run in runs}
        react_future = threads.submit(react_mod.run_react, tasks, seed=args.seed, perception=args.perception,
                                      jobs=args.jobs, progress=_bars(args), protocol=args.protocol,
                                      words=args.relations or (), without=tuple(args.without or ()),
                                      senses=args.senses) if do_react else None
        results = {run: f.result() for run, f in futures.items()}
        rr = react_future.result() if react_future is not None else None
    # the files of the run are replaced together (output.Batch): a write error, or a stop
    # while they are written, leaves the folder as it was, never new CSVs beside old figures
    batch = output.Batch()
    summary, bad = tables.read_summary_json(out)
    kept_bad = None
    if bad is not None:
        n = next(i for i in range(1, 10**6) if not (out / f"summary.json.bad-{i}").exists())
        batch.put(out / f"summary.json.bad-{n}", bad)
        kept_bad = (f"aileen: note: {out / 'summary.json'} was not a summary (not valid JSON): kept as "
                    f"summary.json.bad-{n}, written anew")
    rows = []
    families = []
    for pr, name in plan:
        res = results[(pr, name, args.agent)]
        k = key(pr, name)
        others = {b: results[(pr, name, b)] for b in learners[(pr, name)][1:]}
        for note in output.write_experiment(res, out, plot=not args.no_plot, baselines=others, name=k, batch=batch):
            print(f"aileen: note: {note}", file=sys.stderr)
        wrong = records.trial_words_check(res)
        if wrong:  # an honest learner cannot beat the oracle: this is a bug, not a result
            raise RuntimeError("generality above the one-shot oracle: " + "; ".join(wrong[:3]))
        assert res.headline is not None
        h = tables.headline_dict(res.headline)
        summary[k] = dict(h)
        h["experiment"] = k if args.agent == "asp" else f"{k} ({args.agent})"  # whose figures they are
        rows.append(h)
        if h["by_family"]:
            families.append((k, h))
        if not others:
            _update_baselines(summary, k, None, None)
        for bname, other in others.items():
            assert other.headline is not None
            bh = tables.headline_dict(other.headline)
            _update_baselines(summary, k, bname, dict(bh))
            bh["experiment"] = f"{k} ({bname})"
            rows.append(bh)
            if bh["by_family"]:
                families.append((f"{k} ({bname})", bh))
    if rr is not None:
        batch.put(out / "react" / "tasks.csv", react_mod.tasks_csv(rr))
        summary["react"] = rr.summary
    batch.put(out / "summary.json", tables.summary_json_text(summary))
    with lifecycle.deferred() as writing:
        batch.commit()
        writing.note = f"the figures were written to {out}"
    if kept_bad is not None:
        print(kept_bad, file=sys.stderr)
    if rr is not None:
        s = rr.summary
        print(f"react ({args.protocol}, {args.perception}): {s['success_rate'] * 100:.1f} % of {s['tasks']} tasks "
              f"reached the goal; {s['projections_mean']} projections and {s['steps_mean']} steps per task; "
              f"median {s['task_s_median'] * 1000:.0f} ms per task")
        for word, (reached, asked) in s.get("by_relation", {}).items():
            print(f"  {word}: {reached} of {asked} reached the goal")
        for f in s["failures"]:
            print(f"  failed: {f}")
    if rows:
        print(format_table(rows, protocol=args.protocol, perception=args.perception))
    for label, h in families:
        print(format_families(label, h))
    print(f"wall time: {time.perf_counter() - t_all:.1f} s ({args.jobs} job{'s' if args.jobs != 1 else ''})")
    print(f"wrote {out / 'summary.json'}" + "".join(f", {out / key(pr, n)}/" for pr, n in plan) + (
        f", {out / 'react'}/" if do_react else ""))
    return 0


def _bars(args: argparse.Namespace) -> bool:
    """Progress bars: on a terminal, unless --quiet. Written to a file or a pipe, several bars
    at once (`all` runs its experiments side by side) garbled the log and buried its notes."""
    return not args.quiet and sys.stderr.isatty()


def _baselines_for(experiment: str) -> list[str]:
    """The baseline learners that can take the experiment (experiments/baselines.py); COBWEB
    only when its extra is installed (a note otherwise)."""
    from aileen.experiments import baselines

    out = []
    for bname in baselines.NAMES:
        if experiment not in baselines.EXPERIMENTS[bname]:
            continue
        if bname in baselines.NEEDS_CONCEPT_FORMATION:
            try:
                baselines.require_cobweb(bname)
            except UserError as exc:
                print(f"aileen: note: {exc.message}; the {bname} baseline is left out", file=sys.stderr)
                continue
        out.append(bname)
    return out


def _update_baselines(summary: dict, experiment: str, name: str | None, headline: dict | None) -> None:
    """summary.json's "baselines" entry for the experiment: the baseline's figures, or (name
    None) none at all, for a run without baselines (an earlier run's would stand beside the
    new figures)."""
    base = summary.get("baselines", {}) if isinstance(summary.get("baselines"), dict) else {}
    if name is None:
        if experiment not in base:
            return
        del base[experiment]
    else:
        base.setdefault(experiment, {})[name] = headline
    summary["baselines"] = base


def _sweep(args: argparse.Namespace) -> int:
    for flag, val in (("--trials", args.trials), ("--lessons", args.lessons), ("--without", args.without or None),
                      ("--seed", args.seed or None), ("--perception", None if args.perception == "detector" else 1)):
        if val is not None:
            raise UserError(f"{flag} is set in the grid file for a sweep, not on the command line")
    if args.protocol is not None:  # it was silently left out: the grid says which protocols
        raise UserError("--protocol is set in the grid file for a sweep (protocol = \"wide\", or a list), "
                        "not on the command line")
    for flag, val in (("--agent", args.agent), ("--senses", args.senses), ("--baselines", args.baselines),
                      ("--relations", args.relations)):
        if val is not None:  # they were silently left out
            raise UserError(f"{flag} is not for a sweep: a sweep runs the asp agent with its own senses over "
                            "the grid's experiments, protocols, mechanisms and SAGE's thresholds")
    from aileen.experiments.sweep import sweep_command

    return sweep_command(args.grid, args.out, backend=args.backend, jobs=args.jobs, address=args.address,
                         plot=not args.no_plot, progress=_bars(args))


def _pct(x: float | None) -> str:
    """A figure for the printed table: "-" where it is undefined (None in summary.json)."""
    return "-" if x is None else f"{x:.1f}"


def _cell(x: object) -> str:
    return "-" if x is None else str(x)


def format_table(rows: list[dict], *, protocol: str = "wide", perception: str = "detector") -> str:
    """The headline figures, one line per experiment (the table of docs/results.md); the
    protocol and perception above it when they are not the defaults, and a note under it for a
    row whose balanced area exceeds its generality area (`area % oracle`, printed beside it) by
    more than `SPECIFICITY_ALONE` points: a learner that says no to everything scores 50-100 %
    there (`results.all_no_pct_oracle`), so balanced alone must not be read as good."""
    from aileen.experiments.results import SPECIFICITY_ALONE, all_no_pct_oracle

    head = ("experiment", "trials", "holds from", "final gen.", "lowest spec.", "cmds/trial",
            "area % oracle", "balanced % oracle", "balanced % ideal", "wall s")
    lines = [f"({protocol} protocol, perception {perception})"] if (protocol, perception) != ("wide", "detector") else []
    lines.append(" | ".join(head))
    notes = []
    for h in rows:
        # of how many items, where an exam is not the usual 5 (the teacher protocol's 12)
        ng, ns = h.get("exam_items") or (5, 5)
        gen, spec = (_cell(h["final_generality"]), _cell(h["lowest_specificity"])) if (ng, ns) == (5, 5) else (
            f"{_cell(h['final_generality'])} of {ng}", f"{_cell(h['lowest_specificity'])} of {ns}")
        area, balanced = h["area_pct_of_oracle"], h.get("balanced_pct_oracle")
        lines.append(" | ".join(str(x) for x in (
            h["experiment"], h["trials"], h["holds_from"] if h["holds_from"] is not None else "never",
            gen, spec, _cell(h["commands_per_trial"]), _pct(area),
            _pct(balanced), _pct(h.get("balanced_pct_ideal")), h["wall_s"])))
        if area is not None and balanced is not None and balanced - area > SPECIFICITY_ALONE:
            no = all_no_pct_oracle(h.get("oracle_area") or 0.0, h.get("lessons") or 0, ng)
            notes.append(f"note: {h['experiment']}: balanced {balanced:.1f} % is high from specificity alone "
                         f"(generality {area:.1f} % of the oracle): a learner that says no to everything scores "
                         f"{_pct(no if no == no else None)} % here")
    return "\n".join(lines + notes)


def format_families(label: str, h: dict) -> str:
    """The teacher protocol's figures per family of words (wide, narrow, diagonal)."""
    near = h.get("near_miss_final") or {}
    ideal_near = h.get("ideal_near_miss_final") or {}
    lines = [f"{label} by family (senses {h.get('senses') or '-'}; ideal observer in brackets):",
             "family | gen. items | area % oracle | specificity % | balanced % oracle | balanced % ideal | "
             "edge near misses right at the end"]

    def edge(f: dict) -> str:
        ours, ideal = f.get("near_miss_edge_final"), f.get("ideal_near_miss_edge_final")
        return "-" if ours is None else f"{100 * ours:.0f} % ({'-' if ideal is None else f'{100 * ideal:.0f} %'})"

    for name, f in h["by_family"].items():
        lines.append(" | ".join((name, str(f["generality_items"]), _pct(f["area_pct_of_oracle"]),
                                 _pct(f["specificity_pct"]), f"{_pct(f['balanced_pct_oracle'])} "
                                 f"({_pct(f['ideal_balanced_pct_oracle'])})", _pct(f["balanced_pct_ideal"]), edge(f))))
    kinds = ", ".join(f"{k.removeprefix('near miss: ')} {100 * v:.0f} % "
                      f"({'-' if ideal_near.get(k) is None else f'{100 * ideal_near[k]:.0f} %'})"
                      for k, v in near.items())
    if kinds:
        lines.append(f"near misses right at the end: {kinds}")
    return "\n".join(lines)
