"""The similarities SAGE's assimilation threshold is compared with, measured (issue 11, point 2).

Run: python benchmarks/assimilation.py [--trials N]

Every example the agent stores is captured as it is stored; then, per concept, each pair of
its examples is matched with SME and the similarity SAGE compares with the assimilation
threshold (SME's symmetric similarity, `Mapping.similarity`) is printed as a distribution:

* relation words, pairs in the same CDC sector and in different sectors (wide protocol,
  spatial trials), with and without mutual exclusivity, and per word of the shipped
  `lessons/relations.toml` (a pair where an example holds no CDC fact is in "no sector");
* visual words, wide protocol (visual trials) and the shipped `lessons/visual.toml`;
* the verb "move" (wide protocol, action trials).

What the figures show: no assimilation threshold keeps "left of" apart across sectors while
"far from", "larger than" and the visual words still merge (their pairs score as low or
lower), so the agent decides relation merges by what a merge keeps instead
(agent/disjunction.py; docs/results.md, "When relation examples merge").
"""

from __future__ import annotations

import itertools
import os
import sys
from collections import defaultdict
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_args  # noqa: E402

from aileen.analogy import sme  # noqa: E402
from aileen.domain import calculi  # noqa: E402
from aileen.experiments import runner  # noqa: E402
from aileen.memory.concept import ConceptMemory  # noqa: E402
from aileen.terms import Term, as_term  # noqa: E402

CDC = frozenset(calculi.CDC.relations)


def _capture() -> tuple[dict, callable]:
    """Wrap ConceptMemory.store so every stored example is kept, per (kind, concept)."""
    seen: dict[tuple[str, str], list[list[Term]]] = defaultdict(list)
    orig = ConceptMemory.store

    def store(self, facts, concept, **kw):  # noqa: ANN001, ANN003, ANN202  (accept=..., as the agent passes)
        c = self.concept(concept)
        facts = list(facts)
        seen[(c.kind, c.symbol)].append([as_term(f) for f in facts])
        return orig(self, facts, concept, **kw)

    ConceptMemory.store = store  # type: ignore[method-assign]
    return seen, lambda: setattr(ConceptMemory, "store", orig)


def _sector(example: list[Term]) -> tuple[str, ...]:
    return tuple(sorted(f.name for f in example if f.name in CDC and len(f.args) == 2))


def sectors(x: list[Term], y: list[Term]) -> str:
    """Which pairs a pair of relation examples is counted with: the same CDC sector, different
    sectors, or no sector where either example holds no CDC fact. Two examples without one are
    in no sector, not the same one: until the examples of a word taught after the direction
    words kept their direction facts (345bd93), every pair of "near", "far from" and "larger
    than" in lessons/relations.toml was printed as "same sector"."""
    sx, sy = _sector(x), _sector(y)
    if not sx or not sy:
        return "no sector"
    return "same sector" if sx == sy else "other sector"


def _sims(examples: list[list[Term]], split) -> dict[str, list[float]]:  # noqa: ANN001
    out: dict[str, list[float]] = defaultdict(list)
    for x, y in itertools.combinations(examples, 2):
        ms = sme.match(x, y)
        out[split(x, y)].append(ms[0].similarity if ms else 0.0)
    return out


#: The table's rows as they are measured: (what was run, which pairs, their similarities).
Row = tuple[str, str, list[float]]


def _report(label: str, sims: dict[str, list[float]], rows: list[Row]) -> None:
    rows.extend((label, k, sorted(v)) for k, v in sorted(sims.items()))


def table(rows: list[Row]) -> list[str]:
    """The rows as lines, each column as wide as its widest entry: at fixed widths (34 and 16)
    the long rows of relations.toml ("r_larger_than same sector") pushed their figures out of
    line with the others'."""
    wl = max((len(label) for label, _k, _v in rows), default=0)
    wk = max((len(k) for _label, k, _v in rows), default=0)
    return [f"  {label:<{wl}}  {k:<{wk}}  pairs {len(v):>4}  min {v[0]:.3f}  median {v[len(v) // 2]:.3f}  max {v[-1]:.3f}"
            for label, k, v in rows]


def _collect(run) -> dict:  # noqa: ANN001
    seen, undo = _capture()
    try:
        run()
    finally:
        undo()
    return seen


def main() -> None:
    ap = bench_args.Parser(description=__doc__.split("\n")[0])
    ap.add_argument("--trials", type=bench_args.count, default=3)
    args = ap.parse_args()
    print("SME similarity between two examples of one concept (what the assimilation threshold is compared with)")
    rows: list[Row] = []
    for without in ((), ("mutual-exclusivity",)):
        tag = "spatial (wide)" + (" without ME" if without else "")
        seen = _collect(lambda: [runner.run_trial("spatial", t, 0, perception="truth", protocol="wide",
                                                  without=without) for t in range(args.trials)])
        sims: dict[str, list[float]] = defaultdict(list)
        for (kind, _c), exs in seen.items():
            if kind == "spatial":
                for k, v in _sims(exs, sectors).items():
                    sims[k] += v
        _report(tag, sims, rows)
    seen = _collect(lambda: [runner.run_trial("visual", t, 0, perception="truth", protocol="wide")
                             for t in range(args.trials)])
    sims = defaultdict(list)
    for (kind, _c), exs in seen.items():
        for k, v in _sims(exs, lambda x, y: kind).items():
            sims[k] += v
    _report("visual + spatial (wide, visual trials)", sims, rows)

    def _run_file(name: str) -> None:
        from aileen.agent import Agent
        from aileen.curriculum.interpreter import Interpreter
        from aileen.curriculum.lessonfile import load
        from aileen.perception.truth import TruthVision

        v = TruthVision()
        interp = Interpreter(Agent(perceiver=v), on_frame=v.see_frame)
        for _ in interp.run_all(load(str(Path(__file__).resolve().parent.parent / "lessons" / name))):
            pass

    def curriculum() -> None:
        from aileen.agent import Agent
        from aileen.curriculum.interpreter import Interpreter
        from aileen.curriculum.lessonfile import load
        from aileen.perception.truth import TruthVision

        v = TruthVision()
        interp = Interpreter(Agent(perceiver=v), on_frame=v.see_frame)
        root = Path(__file__).resolve().parent.parent / "lessons"
        for _ in interp.run_all(load(str(root / "visual.toml"))):
            pass

    seen = _collect(curriculum)
    rel_seen = _collect(lambda: _run_file("relations.toml"))
    sims = defaultdict(list)
    for (kind, c), exs in rel_seen.items():
        if kind == "spatial":
            for k, v in _sims(exs, lambda x, y, c=c: f"{c} {sectors(x, y)}").items():
                sims[k] += v
    _report("lessons/relations.toml", sims, rows)
    sims = defaultdict(list)
    for (kind, _c), exs in seen.items():
        for k, v in _sims(exs, lambda x, y: kind).items():
            sims[k] += v
    _report("lessons/visual.toml", sims, rows)
    seen = _collect(lambda: [runner.run_trial("action", t, 0, perception="truth", protocol="wide")
                             for t in range(args.trials)])
    sims = defaultdict(list)
    for (kind, _c), exs in seen.items():
        if kind == "action":
            for k, v in _sims(exs, lambda x, y: "action").items():
                sims[k] += v
    _report("move (wide, action trials)", sims, rows)
    print("\n".join(table(rows)))


if __name__ == "__main__":
    main()
