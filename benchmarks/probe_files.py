"""What the person probes share (`person_probe.py`, `distance_probe.py`): write each lesson file,
run it as a user would (`aileen run lessons/visual.toml FILE --json` in a child process), and
tally the agent's answers to the items the file asks.

A probe gives, per file index, the file's text and per lesson what it asks (None for teaching
lessons); a key that groups an item, and a line that says a missed item.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def run_file(path: Path, seed: int, perception: str, extra: Sequence[str] = ()) -> list[dict]:
    """The records of a probe file's lessons run after the visual words' lessons; `extra`: more
    `aileen run` options (`--senses all`, `--without distance-bands`)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    proc = subprocess.run([sys.executable, "-m", "aileen.cli", "run", str(ROOT / "lessons" / "visual.toml"), str(path),
                           "--json", "--seed", str(seed), "--perception", perception, *extra],
                          capture_output=True, text=True, env=env, cwd=ROOT, check=False)
    if proc.returncode not in (0, 1):
        raise SystemExit(f"{path}: aileen run failed (exit {proc.returncode}): {proc.stderr.strip()[-300:]}")
    return [json.loads(line) for line in proc.stdout.splitlines() if line.startswith("{")]


@dataclass
class Tally:
    """Items answered right and asked, per key, and a line per miss."""

    right: Counter = field(default_factory=Counter)
    total: Counter = field(default_factory=Counter)
    misses: list[str] = field(default_factory=list)


def run_probe(files: int, make: Callable[[int], tuple[str, list[dict | None]]], name: Callable[[int], str],
              run: Callable[[Path], list[dict]], key: Callable[[dict], object], miss: Callable[[dict], str],
              keep: Path | None = None) -> Tally:
    """Write, run and grade `files` probe files: `make(i)` gives file i's text and asks, `name(i)`
    its file name, `run(path)` its records; each asked item is tallied under `key(ask)`, and a
    miss said as "<file> lesson <n>: <miss(ask)>: <result> (<reason>)". Files go to `keep`, or a
    temporary folder."""
    tally = Tally()
    with tempfile.TemporaryDirectory(prefix="aileen-probe-") as tmp:
        folder = keep or Path(tmp)
        folder.mkdir(parents=True, exist_ok=True)
        for i in range(files):
            text, asks = make(i)
            path = folder / name(i)
            path.write_text(text)
            records = run(path)[-len(asks):]
            for rec, ask in zip(records, asks):
                if ask is None:
                    continue
                k = key(ask)
                tally.total[k] += 1
                if rec.get("correct"):
                    tally.right[k] += 1
                else:
                    tally.misses.append(f"{path.name} lesson {rec['index']}: {miss(ask)}: "
                                        f"{rec['result']} ({rec.get('reason') or 'no reason'})")
            print(f"\r{i + 1}/{files} files", end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)
    return tally
