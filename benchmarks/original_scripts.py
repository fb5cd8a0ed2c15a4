"""The original AILEEN's lesson scripts, each run from a taught memory (issue 22).

Run: python benchmarks/original_scripts.py DIR [--seed 0] [--perception truth] [--teach FILE ...]

DIR holds the original's JSON scripts (they are someone else's files: keep them outside this
repository). An agent is first taught the colours, shapes, sizes, directions and the other
relation words from the project's own lesson files (`--teach`, by default lessons/visual.toml,
sizes.toml, spatial.toml and relations.toml) and "on" (`ON_LESSONS`: relations.toml has no "on";
lessons/stacking.toml would teach the verb "move" too), and the memory is saved. No verb is
taught: a script teaches its own. Then every script runs
on its own copy of that memory, as a user would run it: `aileen run FILE --memory COPY --json
--seed S --perception P`, in a child process (a crash is a crash, not the benchmark's).

Per script it prints the exit status, whether the run reached its end (every lesson has its
record, exit 0 or 1: 2 is a file refused, or a stop), the lessons run and skipped (with the
reasons), the graded answers right and wrong, and the lessons left ungraded because the script
contradicts itself: a verify lesson whose `is_positive` says one thing while its own layout (or
its own demonstration) says the other, e.g. "is_positive": "True" for a sentence that is false
of the objects the same lesson describes. Lessons that test a word neither the taught memory
nor an earlier lesson of the script teaches (the agent answers "I do not know the word 'move
right of'": the original's generated verify files were meant to follow its inform file in one
run) are counted apart as untaught, and the totals are given with and without them. Those are laid out again here as the run lays them
out (`rehearsal.check_curriculum`, same seeds), so the check reads the very table the agent saw.
Then the totals: scripts run to the end, graded lessons right (%), and every failure with its
reason.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field, replace
from pathlib import Path

from aileen.curriculum import legacy_scene

ROOT = Path(__file__).resolve().parent.parent
TEACH = tuple(str(ROOT / "lessons" / f) for f in ("visual.toml", "sizes.toml", "spatial.toml", "relations.toml"))
# "on" with the support in sight and sizes varied (so it is learned as resting on, whatever
# the footprints' overlap), on the shapes with a flat top.
ON_LESSONS = "\n".join(
    f'[[lesson]]\nsignal = "inform"\ncontent = "{a} on {b}"\nobjects = ["{sa} {a}", "{sb} {b}"]\nrelation = "on"\n'
    for (sa, a), (sb, b) in ((("medium", "red box"), ("medium", "blue box")),
                             (("small", "green cylinder"), ("large", "red box")),
                             (("large", "yellow sphere"), ("medium", "purple cylinder")),
                             (("medium", "blue cone"), ("large", "green box")),
                             (("medium", "purple box"), ("small", "yellow cylinder"))))
UNKNOWN = "I do not know the word '"


@dataclass
class ScriptResult:
    """One script's run: what came back from `aileen run`, and what the benchmark made of it."""

    name: str
    rc: int
    lessons: int | None  # in the file (None: the file could not be read)
    records: int  # lesson records printed
    skipped: list[str] = field(default_factory=list)  # "lesson N: reason"
    unread: int = 0  # answers not graded: no expected answer in the script, or a sentence not read
    right: int = 0
    wrong: list[str] = field(default_factory=list)  # "lesson N: content -> result (expected)"
    contradicted: list[str] = field(default_factory=list)  # ungraded: the script says both
    untaught: list[str] = field(default_factory=list)  # ungraded: a word nothing taught, "right" or not
    error: str = ""  # the last stderr line of a run that did not reach its end

    @property
    def to_end(self) -> bool:
        return self.rc in (0, 1) and self.lessons is not None and self.records == self.lessons


def contradictions(path: Path, seed: int) -> dict[int, str]:
    """Lesson index (1-based) -> why its `is_positive` contradicts the script's own lesson.

    A verify lesson with its own expectation is judged again without it: a visual or spatial
    sentence against the table the lesson is laid out on, an action sentence against the
    demonstration (`grading.expected`). Where the two disagree, the script says both.
    """
    from aileen.curriculum import grading, placeholders, rehearsal
    from aileen.curriculum.formats import load_curriculum
    from aileen.curriculum.stage import Skip

    cur = replace(load_curriculum(path), seed=seed)
    seeds = [cur.lesson_seed(i) for i in range(len(cur))]
    setups = rehearsal.check_curriculum(cur.lessons, seeds, skip=True)
    out: dict[int, str] = {}
    for i, (lesson, setup, s) in enumerate(zip(cur.lessons, setups, seeds, strict=True), start=1):
        if lesson.signal != "verify" or lesson.expect is None or setup is None or isinstance(setup, Skip):
            continue
        why = grading.contradiction(placeholders.name(lesson, seed=s), setup)
        if why is not None:
            out[i] = why
    return out


def run_script(path: Path, memory: Path, seed: int, perception: str) -> ScriptResult:
    """`aileen run` on one script from a copy of `memory`; its records read back."""
    work = Path(tempfile.mkdtemp(prefix="aileen-orig-"))
    try:
        mem = work / "memory.json"
        shutil.copy(memory, mem)
        proc = _aileen_run(str(path), "--memory", str(mem), "--json", "--seed", str(seed), "--perception", perception)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    records = [json.loads(line) for line in proc.stdout.splitlines() if line.startswith("{")]
    lessons = _count_lessons(path)
    res = ScriptResult(path.name, proc.returncode, lessons, len(records))
    if not res.to_end:
        lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
        res.error = lines[-1] if lines else "(no message)"
    try:
        contra = contradictions(path, seed) if records else {}
    except Exception as exc:  # noqa: BLE001 - a script the check cannot lay out: reported, not fatal
        contra = {}
        res.error = res.error or f"contradiction check failed: {exc}"
    taught: list[str] = []  # the sentences of the script's informs so far
    for r in records:
        n = r["index"]
        word = _unknown_word(r.get("reason"))
        if r["signal"] == "inform":
            taught.append(r["content"])
        if "skipped" in r:
            res.skipped.append(f"lesson {n}: {r['skipped']}")
        elif word is not None and r["correct"] is not None and not any(word.split()[0] in t.split() for t in taught):
            res.untaught.append(f"lesson {n} {r['signal']} {r['content']!r}: {r['result']}, "
                                f"{'right' if r['correct'] else 'wrong'} ('{word}' is taught nowhere before)")
        elif n in contra:
            res.contradicted.append(f"lesson {n} {r['content']!r}: {contra[n]}")
        elif r["correct"] is True:
            res.right += 1
        elif r["correct"] is False:
            why = f"goal_holds={r.get('goal_holds')}" if r["signal"] == "react" else f"expected {r['expected']}"
            if r["signal"] == "generate":
                why = f"said {r.get('said')!r}"
            res.wrong.append(f"lesson {n} {r['signal']} {r['content']!r} -> {r['result']} ({why}; {r['reason']})")
        elif r["signal"] in ("verify", "react", "generate"):
            res.unread += 1
    return res


def _unknown_word(reason: str | None) -> str | None:
    """The word in the agent's "I do not know the word 'move right of'" (None: no such answer)."""
    if not reason or UNKNOWN not in reason:
        return None
    return reason.split(UNKNOWN, 1)[1].split("'", 1)[0] or None


def _count_lessons(path: Path) -> int | None:
    """The lessons in a script, as its JSON list holds them, or 1 for a scene the original's
    instructor saved (`legacy_scene`); None: neither."""
    try:
        data = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    if legacy_scene.is_scene(data):
        return 1
    return len(data) if isinstance(data, list) else None


def _aileen_run(*args: str) -> subprocess.CompletedProcess:
    """`aileen run ARGS` in a child process, this checkout's code first on the path."""
    env = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    return subprocess.run([sys.executable, "-m", "aileen.cli", "run", *args], capture_output=True, text=True,
                          env=env, cwd=ROOT, check=False)


def teach(files: list[str], seed: int, perception: str, memory: Path) -> None:
    """The taught memory: the teach files, then the "on" lessons, run once, the memory saved."""
    on = memory.parent / "on.toml"
    on.write_text(f'title = "on"\nseed = {seed}\n\n{ON_LESSONS}')
    proc = _aileen_run(*files, str(on), "--memory", str(memory), "--seed", str(seed), "--perception", perception)
    if proc.returncode not in (0, 1) or not memory.exists():
        raise SystemExit(f"teaching failed (exit {proc.returncode}): {proc.stderr.strip()[-400:]}")
    print(f"taught: {' '.join(Path(f).name for f in files)}: {proc.stdout.strip().splitlines()[-1]}")


def report(results: list[ScriptResult]) -> None:
    """The per-script table, the failures with their reasons, the totals."""
    print(f"{'script':50s} {'rc':>2s} {'end':>3s} {'run':>4s} {'skip':>4s} {'right':>5s} {'wrong':>5s} {'contra':>6s} "
          f"{'untaught':>8s} {'unread':>6s}")
    for r in results:
        ran = r.records - len(r.skipped)
        print(f"{r.name[:50]:50s} {r.rc:2d} {'yes' if r.to_end else 'NO':>3s} {ran:4d} {len(r.skipped):4d} "
              f"{r.right:5d} {len(r.wrong):5d} {len(r.contradicted):6d} {len(r.untaught):8d} {r.unread:6d}")
    print()
    for r in results:
        notes = ([f"  stopped: {r.error}"] if not r.to_end else []) + [f"  skipped {s}" for s in r.skipped] \
            + [f"  WRONG {w}" for w in r.wrong] + [f"  ungraded (contradicted) {c}" for c in r.contradicted] \
            + [f"  untaught {u}" for u in r.untaught]
        if notes:
            print(r.name)
            print("\n".join(notes))
    right = sum(r.right for r in results)
    graded = right + sum(len(r.wrong) for r in results)
    ends = sum(r.to_end for r in results)
    print()
    print(f"scripts run to the end: {ends} of {len(results)}")
    print(f"lessons: {sum(r.records for r in results)} run, {sum(len(r.skipped) for r in results)} skipped, "
          f"{sum(len(r.contradicted) for r in results)} contradicted by their script (not graded), "
          f"{sum(r.unread for r in results)} not graded (the script gives no expected answer, or a sentence was not read)")
    pct = 100.0 * right / graded if graded else 0.0
    print(f"graded lessons right: {right} of {graded} ({pct:.1f} %)")
    u_right = sum(u.split(", ")[-1].startswith("right") for r in results for u in r.untaught)
    u_all = sum(len(r.untaught) for r in results)
    both = graded + u_all
    print(f"untaught (a word nothing before taught; not in the figure above): {u_all}, {u_right} of them 'right'; "
          f"counted in: {right + u_right} of {both} ({100.0 * (right + u_right) / both if both else 0.0:.1f} %)")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("dir", type=lambda s: Path(s).resolve(),  # the runs start in the repository
                    help="a directory of the original's JSON lesson scripts")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--perception", choices=("truth", "detector"), default="truth")
    ap.add_argument("--teach", nargs="+", default=list(TEACH), help="lesson files that make the taught memory")
    args = ap.parse_args(argv)
    # A wrong DIR is bad input: one line naming it, exit 2 (an empty glob of a missing folder
    # used to end as "no .json scripts" with exit 1, as if the run had failed).
    if not args.dir.is_dir():
        print(f"{args.dir}: expected a directory of the original's JSON lesson scripts", file=sys.stderr)
        return 2
    scripts = sorted(p for p in args.dir.glob("*.json") if p.is_file())
    if not scripts:
        print(f"{args.dir}: expected the original's JSON lesson scripts (*.json), found none", file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory(prefix="aileen-taught-") as tmp:
        memory = Path(tmp) / "taught.json"
        teach([str(Path(f).resolve()) for f in args.teach], args.seed, args.perception, memory)
        results = []
        for p in scripts:
            results.append(run_script(p, memory, args.seed, args.perception))
            print(f"  {p.name}: exit {results[-1].rc}", file=sys.stderr, flush=True)
    report(results)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
