"""Mutation testing of one module against the tests that cover it (mutmut 3), with a score.

Run: python tools/mutation.py MODULE [MODULE ...] [--children N] [--tests FILE ...] [--fresh]
e.g. `python tools/mutation.py aileen/memory/concept.py`; `--list` shows the modules it knows.

Why: a line every test executes is not a line any test checks. mutmut changes one thing at a
time (`<` to `<=`, `-x` to `x`, `True` to `False`) and runs the tests that reach the changed
function; a change that no test notices ("survived") is either a gap in the tests or an
*equivalent* mutant: one that changes nothing the module promises (a pre-filter's cutoff, a
choice between two strategies that give the same answer). The equivalent ones are listed,
each with the reason, in `tools/mutation_equivalent.toml`; the score leaves them out:
killed / (mutants - equivalent), where a mutant whose tests time out counts as killed.

Not part of CI: a module takes minutes to an hour. Each run works in its own folder,
`build/mutation/<module>/` (a copy of `COPIED`), runs niced, with hypothesis derandomized
(`CI=1`, tests/conftest.py) so two runs agree. mutmut itself lives outside the
project's environment (it is not a dependency): `python3 -m venv /work/mutvenv` then
`/work/mutvenv/bin/pip install mutmut==3.8.1`, and a `.pth` file in that venv's
site-packages naming the project venv's site-packages (so pytest, hypothesis, clingo, ...
import); `--mutmut` or `$MUTMUT` names its executable.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tomllib
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
EQUIVALENT_FILE = ROOT / "tools" / "mutation_equivalent.toml"

#: SME's tests, shared by the modules SME was split into (sme.py and its sme_*.py).
_SME_TESTS = ["tests/test_sme.py", "tests/test_sme_behaviour.py", "tests/test_sage.py"]

#: Each module with the test files that are its own (mutmut runs, per mutant, only those of
#: these tests that reach the mutated function).
MODULES: dict[str, list[str]] = {
    "aileen/memory/concept.py": ["tests/test_concept_memory.py", "tests/test_memory_behaviour.py",
                                 "tests/test_retrieval.py", "tests/test_feedback.py", "tests/test_sage_filter.py"],
    "aileen/memory/recognition.py": ["tests/test_concept_memory.py", "tests/test_memory_behaviour.py",
                                     "tests/test_retrieval.py", "tests/test_feedback.py"],
    "aileen/memory/projection.py": ["tests/test_concept_memory.py", "tests/test_memory_behaviour.py"],
    "aileen/analogy/sage.py": ["tests/test_sage.py", "tests/test_concept_memory.py",
                               "tests/test_memory_behaviour.py", "tests/test_sage_filter.py"],
    "aileen/agent/lexicon.py": ["tests/test_lexicon_behaviour.py", "tests/test_learning_defects.py",
                                "tests/test_lexicon_incremental.py"],
    "aileen/reasoning/spelling.py": ["tests/test_learning_defects.py", "tests/test_lexicon_behaviour.py"],
    "aileen/memory/claims.py": ["tests/test_claims.py", "tests/test_lexicon_behaviour.py",
                                "tests/test_learning_defects.py", "tests/test_lexicon_incremental.py"],
    "aileen/memory/claims_pass.py": ["tests/test_claims.py", "tests/test_lexicon_behaviour.py",
                                     "tests/test_learning_defects.py", "tests/test_lexicon_incremental.py"],
    "aileen/memory/claims_replay.py": ["tests/test_claims.py", "tests/test_lexicon_behaviour.py",
                                       "tests/test_learning_defects.py", "tests/test_lexicon_incremental.py"],
    "aileen/memory/compact.py": ["tests/test_compact_memory.py"],
    "aileen/analogy/sme.py": _SME_TESTS,
    "aileen/analogy/sme_descriptions.py": _SME_TESTS,
    "aileen/analogy/sme_hypotheses.py": _SME_TESTS,
    "aileen/analogy/sme_merge.py": _SME_TESTS,
    "aileen/analogy/sme_mappings.py": _SME_TESTS,
    "aileen/world/geometry.py": ["tests/test_qsr.py", "tests/test_qsr_behaviour.py"],
}

#: What a run copies: the package (its links followed: aileen/asp) and what tests read.
COPIED = ("aileen", "tests", "benchmarks", "lessons", "asp")

#: Appended to the copy's tests/conftest.py: every aileen module's functools caches emptied
#: before each test, so that the mutated code runs (see `prepare`).
CLEAR_CACHES = """

import sys as _sys

import pytest as _pytest


@_pytest.fixture(autouse=True)
def _mutation_clear_caches():
    for _name, _mod in list(_sys.modules.items()):
        if _name.startswith("aileen") and _mod is not None:
            for _v in list(vars(_mod).values()):
                if callable(getattr(_v, "cache_clear", None)):
                    _v.cache_clear()
    yield
"""

#: mutmut's exit codes (mutmut/stats.py), as this score counts them.
KILLED = {1, 3, 36, -24, 24, 152, 255, -11, -9}  # a failing test, a timeout or a crash
SURVIVED = {0}
NO_TESTS = {5, 33}


@dataclass
class Equivalent:
    module: str
    line: str  # the original line, stripped
    mutant: str | None  # the mutated line, stripped; None: every mutant of the line
    why: str
    after: str | None = None  # the line before it, where the line alone is ambiguous (`continue`)

    def covers(self, module: str, old: str, new: str, before: str) -> bool:
        return (self.module == module and self.line == old and (self.mutant is None or self.mutant == new)
                and (self.after is None or self.after == before))


def load_equivalents(path: Path = EQUIVALENT_FILE) -> list[Equivalent]:
    if not path.exists():
        return []
    data = tomllib.loads(path.read_text("utf-8"))
    out = []
    for i, e in enumerate(data.get("equivalent", [])):
        try:
            out.append(Equivalent(e["module"], _code(e["line"]), _code(e["mutant"]) if e.get("mutant") else None,
                                  e["why"], _code(e["after"]) if e.get("after") else None))
        except KeyError as missing:
            sys.exit(f"{path}: entry {i + 1}: missing {missing}")
    return out


def prepare(module: str, tests: list[str], work: Path, fresh: bool) -> None:
    """A folder with a copy of the package and what the tests read (`COPIED`), and a
    pyproject.toml that tells mutmut what to mutate and which tests to run."""
    if fresh and work.exists():
        shutil.rmtree(work)
    work.mkdir(parents=True, exist_ok=True)
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc", ".hypothesis")
    for name in COPIED:
        dst = work / name
        if dst.exists():
            shutil.rmtree(dst)
        shutil.copytree(ROOT / name, dst, symlinks=False, ignore=ignore)
    cfg = {
        "source_paths": ["aileen"],
        "only_mutate": [module],
        "also_copy": [n for n in COPIED if n != "aileen"],
        "pytest_add_cli_args_test_selection": tests,
        "pytest_add_cli_args": ["-p", "no:cacheprovider", "-q", "-x"],
    }
    # mutmut forks each mutant's test run from a process that has run the tests already: a
    # cache filled there (sme_descriptions._prepare, recognition._skeleton) would answer for the mutated code.
    with (work / "tests" / "conftest.py").open("a") as fh:
        fh.write(CLEAR_CACHES)
    lines = ["[tool.mutmut]"] + [f"{k} = {json.dumps(v)}" for k, v in cfg.items()]
    lines += ["", "[tool.pytest.ini_options]", 'testpaths = ["tests"]',
              'markers = ["slow: longer end-to-end tests"]', ""]
    (work / "pyproject.toml").write_text("\n".join(lines))


def _code(line: str) -> str:
    """A source line without its indentation and trailing comment (`  # ...`)."""
    return re.sub(r"\s\s+#.*$", "", line).strip()


_DIFFS = """
import json, sys
from pathlib import Path
from mutmut.mutation.diff_apply import get_diff_for_mutant
path, names = sys.argv[1], sys.argv[2:]
print(json.dumps({n: get_diff_for_mutant(n, path=Path(path)) for n in names}))
"""


def diffs(mutmut: str, work: Path, module: str, names: list[str]) -> dict[str, tuple[str, str, str]]:
    """Each mutant's original and mutated line and the line before them (as `_code`), from
    mutmut's own diff, in one process (`mutmut show` per mutant takes a second each)."""
    if not names:
        return {}
    python = str(Path(mutmut).with_name("python"))
    out = subprocess.run([python, "-c", _DIFFS, module, *names], cwd=work, capture_output=True, text=True,
                         check=True).stdout
    got = {}
    for name, diff in json.loads(out).items():
        lines = diff.splitlines()
        old = [_code(ln[1:]) for ln in lines if ln.startswith("-") and not ln.startswith("---")]
        new = [_code(ln[1:]) for ln in lines if ln.startswith("+") and not ln.startswith("+++")]
        first = next((i for i, ln in enumerate(lines) if ln.startswith("-") and not ln.startswith("---")), 0)
        before = next((_code(ln[1:]) for ln in reversed(lines[:first]) if ln.startswith(" ") and _code(ln[1:])), "")
        got[name] = (" / ".join(old), " / ".join(new), before)
    return got


def results(module: str, work: Path) -> dict[str, int | None]:
    """Each mutant's exit code: mutmut's last run, over the codes kept from the runs before
    it for the mutants it did not run (`--again` runs only some, and mutmut forgets the rest)."""
    kept = work / "results.json"
    codes = json.loads(kept.read_text())["codes"] if kept.exists() else {}
    meta = work / "mutants" / (module + ".meta")
    if meta.exists():
        for name, code in json.loads(meta.read_text())["exit_code_by_key"].items():
            if code is not None or name not in codes:
                codes[name] = code
    return codes


def source_hash(module: str) -> str:
    return hashlib.sha256((ROOT / module).read_bytes()).hexdigest()


def saved_source(work: Path) -> str | None:
    kept = work / "results.json"
    return json.loads(kept.read_text())["source"] if kept.exists() else None


def save_results(module: str, work: Path, codes: dict[str, int | None]) -> None:
    data = {"source": source_hash(module), "codes": codes}
    (work / "results.json").write_text(json.dumps(data, indent=0, sort_keys=True))


def not_killed(module: str, work: Path) -> list[str]:
    return sorted(n for n, c in results(module, work).items() if c not in KILLED)


def score(module: str, work: Path, mutmut: str, equivalents: list[Equivalent]) -> dict:
    codes = results(module, work)
    save_results(module, work, codes)
    killed = survived = no_tests = other = 0
    equivalent: list[tuple[str, str, str]] = []
    alive: list[tuple[str, str, str]] = []
    names = sorted(codes, key=lambda n: (n.rsplit("__mutmut_", 1)[0], int(n.rsplit("_", 1)[-1])))
    lost = [n for n in names if codes[n] not in KILLED]
    lines = diffs(mutmut, work, module, lost)
    for name in lost:
        code = codes[name]
        if code in NO_TESTS:
            no_tests += 1
        elif code in SURVIVED:
            survived += 1
        else:
            other += 1
        old, new, before = lines[name]
        if any(e.covers(module, old, new, before) for e in equivalents):
            equivalent.append((name, old, new))
        else:
            alive.append((name, old, new))
    killed = len(names) - len(lost)
    total = len(codes)
    counted = total - len(equivalent)
    return {"module": module, "mutants": total, "killed": killed, "survived": survived,
            "no_tests": no_tests, "other": other, "equivalent": len(equivalent),
            "score": killed / counted if counted else 1.0, "alive": alive}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("modules", nargs="*", help="e.g. aileen/memory/concept.py")
    ap.add_argument("--tests", nargs="+", help="test files (default: the module's own, MODULES)")
    ap.add_argument("--children", type=int, default=1, help="mutants tested at once (default 1)")
    ap.add_argument("--mutmut", default=os.environ.get("MUTMUT", "/work/mutvenv/bin/mutmut"))
    ap.add_argument("--fresh", action="store_true", help="forget earlier results of these modules")
    ap.add_argument("--again", action="store_true",
                    help="run only the mutants the last run did not kill, against the tests as they are now")
    ap.add_argument("--score-only", action="store_true", help="score the last run again, run nothing")
    ap.add_argument("--list", action="store_true", help="the modules and their test files")
    args = ap.parse_args(argv)
    if args.list or not args.modules:
        for m, t in MODULES.items():
            print(m, " ".join(t))
        return 0
    equivalents = load_equivalents()
    rows = []
    for module in args.modules:
        if module not in MODULES and not args.tests:
            print(f"no test files known for {module}: give --tests", file=sys.stderr)
            return 2
        tests = args.tests or MODULES[module]
        work = ROOT / "build" / "mutation" / Path(module).with_suffix("").as_posix().replace("/", ".")
        if not args.score_only:
            again = not_killed(module, work) if args.again else []
            if args.again:
                if saved_source(work) not in (None, source_hash(module)):
                    print(f"{module} changed since its last run: run it without --again", file=sys.stderr)
                    return 2
                save_results(module, work, results(module, work))
            prepare(module, tests, work, args.fresh)
            env = dict(os.environ, CI="1", PYTHONDONTWRITEBYTECODE="1")
            cmd = ["nice", "-n", "19", args.mutmut, "run", "--max-children", str(args.children)]
            cmd += again
            log = work / "mutmut.log"
            with log.open("w") as fh:
                rc = subprocess.run(cmd, cwd=work, env=env, stdout=fh, stderr=subprocess.STDOUT).returncode
            if rc != 0:
                print(f"mutmut failed on {module} (exit {rc}); see {log}", file=sys.stderr)
                return 1
        rows.append(score(module, work, args.mutmut, equivalents))
    print("| module | mutants | killed | survived | no test | equivalent | score |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| `{r['module']}` | {r['mutants']} | {r['killed']} | {r['survived']} | {r['no_tests']} | "
              f"{r['equivalent']} | {100 * r['score']:.1f} % |")
    for r in rows:
        for name, old, new in r["alive"]:
            print(f"\n{name}\n  - {old}\n  + {new}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
