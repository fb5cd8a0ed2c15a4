"""The grid file of `aileen experiment sweep`: which points to run, read and checked up front.

Why: a sweep is hundreds of trials; a typo in the grid must fail in a second with the file
and line, not after an hour. Every axis is a list of values; a point is one value of each
axis, and every point runs `trials` trials for every seed. The file is TOML; `EXAMPLE` below
(shown by `aileen experiment sweep --help`) has every key, each with a comment.

SAGE parameters not named keep the paper's values (`SageParams()`).
"""

from __future__ import annotations

import itertools
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from aileen import textfile
from aileen.agent.records import ABLATIONS
from aileen.analogy.sage import SageParams
from aileen.errors import UserError
from aileen.experiments.protocol import EXPERIMENTS, MAX_TRIALS, PROTOCOL_EXPERIMENTS, too_many_lessons

#: A grid with every key (parsed by the tests, shown by `aileen experiment sweep --help`).
EXAMPLE = """\
experiment = "visual"                   # or a list: ["visual", "spatial"]
protocol = "paper"                      # optional axis: paper (default), wide, teacher; or a list
trials = 2                              # per point and seed
seeds = [0, 1, 2]
without = [[], ["mutual-exclusivity"]]  # optional axis: mechanisms switched off
perception = "detector"                 # optional: detector (default) or truth
lessons = 24                            # optional: only the first K training lessons
[params]                                # SAGE parameters, each a list of values in [0, 1]
assimilation = [0.01, 0.1, 0.3, 0.6, 0.9]
match = [0.5, 0.65, 0.75, 0.85, 0.95]
[heatmap]                               # optional: the two axes of heatmap.png
x = "assimilation"
y = "match"
"""

#: The protocol a sweep's trials run when the grid names none (`trial.run_trial`'s own default).
SWEEP_PROTOCOL = "paper"
#: SAGE parameters a grid may sweep (each a threshold in [0, 1]).
PARAMS: tuple[str, ...] = ("assimilation", "probability", "match")
TOP_KEYS: tuple[str, ...] = ("experiment", "protocol", "trials", "seeds", "without", "perception", "lessons",
                             "params", "heatmap")
PERCEPTIONS: tuple[str, ...] = ("detector", "truth")
MECHANISMS: tuple[str, ...] = tuple(ABLATIONS)


@dataclass(frozen=True)
class Point:
    """One point of the grid: an experiment, the mechanisms switched off, SAGE's thresholds
    and the protocol its trials follow."""

    experiment: str
    without: tuple[str, ...]
    assimilation: float
    probability: float
    match: float
    protocol: str = SWEEP_PROTOCOL

    def sage(self) -> SageParams:
        return SageParams(assimilation=self.assimilation, probability=self.probability, match=self.match)

    def label(self) -> str:
        off = "+".join(self.without) or "-"
        return (f"{self.experiment} protocol={self.protocol} without={off} assimilation={self.assimilation} "
                f"probability={self.probability} match={self.match}")


@dataclass(frozen=True)
class Grid:
    """A parsed grid file: its axes, and what every trial shares."""

    path: str
    experiments: tuple[str, ...]
    trials: int
    seeds: tuple[int, ...]
    without: tuple[tuple[str, ...], ...]
    params: dict[str, tuple[float, ...]] = field(default_factory=dict)
    perception: str = "detector"
    lessons: int | None = None
    heatmap: tuple[str, str] | None = None
    protocols: tuple[str, ...] = (SWEEP_PROTOCOL,)

    def axes(self) -> dict[str, tuple]:
        """Every axis with its values, in the order points are enumerated."""
        d = SageParams()
        return {
            "experiment": self.experiments,
            "protocol": self.protocols,
            "without": self.without,
            **{p: self.params.get(p, (getattr(d, p),)) for p in PARAMS},
        }

    def points(self) -> list[Point]:
        """Every point, in a fixed order (experiment, protocol, without, then the SAGE parameters)."""
        ax = self.axes()
        return [Point(e, w, a, p, m, pr) for e, pr, w, a, p, m in itertools.product(
            ax["experiment"], ax["protocol"], ax["without"], ax["assimilation"], ax["probability"], ax["match"])]

    def swept(self) -> list[str]:
        """The axes with more than one value (the heat map's default axes come from these)."""
        return [k for k, v in self.axes().items() if len(v) > 1]

    def heatmap_axes(self) -> tuple[str, str] | None:
        """The heat map's (x, y): the grid's [heatmap] choice, else the first two numeric axes
        with more than one value; None when there are not two."""
        if self.heatmap is not None:
            return self.heatmap
        numeric = [k for k in self.swept() if k in PARAMS]
        return (numeric[0], numeric[1]) if len(numeric) >= 2 else None


class _Lines:
    """Where keys stand in the file (tomllib gives values, not lines)."""

    def __init__(self, text: str) -> None:
        self.where: dict[tuple[str, str], int] = {}
        table = ""
        key = r"""["']?([A-Za-z0-9_-]+)["']?"""  # bare or quoted
        for n, line in enumerate(text.splitlines(), 1):
            s = line.strip()
            m = re.match(rf"^\[\[?\s*{key}\s*\]\]?", s)  # [params], [[params]], ["params"]
            if m:
                table = m.group(1)
                self.where.setdefault(("", table), n)
                continue
            m = re.match(rf"^{key}\s*\.\s*{key}\s*=", s)  # params.match = ...
            if m:
                self.where.setdefault(("", m.group(1)), n)
                self.where.setdefault((m.group(1), m.group(2)), n)
                continue
            m = re.match(rf"^{key}\s*=\s*(\{{.*)?", s)
            if m:
                self.where.setdefault((table, m.group(1)), n)
                for inner in re.findall(rf"[{{,]\s*{key}\s*=", m.group(2) or ""):  # params = {{match = ...}}
                    self.where.setdefault((m.group(1), inner), n)

    def line(self, table: str, key: str) -> int | None:
        return self.where.get((table, key))


def _said(value: object) -> str:
    """A value as the grid file spells it (TOML: `true`, `"x"`, `[1, 2]`), for an error:
    Python's `True` and `'x'` are not what the user wrote."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return '"' + value.replace('"', '\\"') + '"'
    if isinstance(value, list):
        return "[" + ", ".join(_said(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k} = {_said(v)}" for k, v in value.items()) + "}"
    return repr(value)


def load_grid(path: str | Path) -> Grid:
    """Read and check a grid file; any problem is a `UserError` with the file and line."""
    text = textfile.read_text(path, "grid file", "grid file not found")
    return parse_grid(text, str(Path(path)))


def parse_grid(text: str, path: str = "<grid>") -> Grid:
    """Parse grid TOML text (see the module docstring); errors name `path` and the line."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"line (\d+)", str(exc))
        line = int(m.group(1)) if m else max(1, len(text.splitlines()))  # "at end of document"
        raise UserError(f"not valid TOML ({exc})", path=path, line=line) from None
    lines = _Lines(text)

    def bad(msg: str, table: str, key: str) -> UserError:
        return UserError(msg, path=path, line=lines.line(table, key))

    for k in data:
        if k not in TOP_KEYS:
            raise bad(f"unknown key {k!r}; expected one of {', '.join(TOP_KEYS)}", "", k)

    exp = data.get("experiment")
    if exp is None:
        raise UserError("missing key 'experiment' (one of " + ", ".join(EXPERIMENTS) + ", or a list)", path=path,
                        line=1)
    def names(key: str, noun: str, allowed: "tuple[str, ...] | dict", default: object) -> list[str]:
        """An axis of names: one name, or a non-empty list of them, each known, none twice."""
        value = data.get(key, default)
        values = [value] if isinstance(value, str) else value
        if not isinstance(values, list) or not values:
            raise bad(f"'{key}' must be {noun}'s name or a non-empty list of them", "", key)
        for v in values:
            if v not in allowed:
                raise bad(f"unknown {key} {_said(v)}; expected one of {', '.join(allowed)}", "", key)
        if len(set(values)) != len(values):
            raise bad(f"'{key}' repeats a value", "", key)
        return values

    exps = names("experiment", "an experiment", EXPERIMENTS, exp)
    prots = names("protocol", "a protocol", PROTOCOL_EXPERIMENTS, SWEEP_PROTOCOL)
    for e in exps:
        for pr in prots:
            if e not in PROTOCOL_EXPERIMENTS[pr]:  # every trial of such a point would fail
                owners = [q for q in PROTOCOL_EXPERIMENTS if e in PROTOCOL_EXPERIMENTS[q]]
                raise bad(f"the {pr} protocol has no {e} experiment (it has {', '.join(PROTOCOL_EXPERIMENTS[pr])}; "
                          f"{e} is in {', '.join(owners)})", "", "protocol" if "protocol" in data else "experiment")

    trials = data.get("trials", 1)
    if not isinstance(trials, int) or isinstance(trials, bool) or not 1 <= trials <= MAX_TRIALS:
        raise bad(f"'trials' must be a positive integer, at most {MAX_TRIALS}, not {_said(trials)}", "", "trials")

    seeds = data.get("seeds", [0])
    if not isinstance(seeds, list) or not seeds:
        raise bad("'seeds' must be a non-empty list of integers", "", "seeds")
    if any(not isinstance(s, int) or isinstance(s, bool) or s < 0 for s in seeds):
        raise bad(f"'seeds' must hold non-negative integers, not {_said(seeds)}", "", "seeds")
    if len(set(seeds)) != len(seeds):
        raise bad("'seeds' repeats a value", "", "seeds")

    without = data.get("without", [[]])
    if not isinstance(without, list) or not without:
        raise bad("'without' must be a non-empty list of lists of mechanisms (e.g. [[], [\"mutual-exclusivity\"]])",
                  "", "without")
    wo: list[tuple[str, ...]] = []
    for w in without:
        if not isinstance(w, list):
            raise bad(f"'without' must hold lists of mechanisms, not {_said(w)}", "", "without")
        for m in w:
            if m not in MECHANISMS:
                raise bad(f"unknown mechanism {m!r} in 'without'; expected one of {', '.join(MECHANISMS)}",
                          "", "without")
        t = tuple(sorted(set(w)))
        if t in wo:
            raise bad(f"'without' repeats {list(t)!r}", "", "without")
        wo.append(t)

    perception = data.get("perception", "detector")
    if perception not in PERCEPTIONS:
        raise bad(f"'perception' must be one of {', '.join(PERCEPTIONS)}, not {_said(perception)}", "", "perception")

    lessons = data.get("lessons")
    if lessons is not None and (not isinstance(lessons, int) or isinstance(lessons, bool) or lessons < 1):
        raise bad(f"'lessons' must be a positive integer, not {_said(lessons)}", "", "lessons")

    params = data.get("params", {})
    if not isinstance(params, dict):
        raise bad("'params' must be a table ([params])", "", "params")
    swept: dict[str, tuple[float, ...]] = {}
    for k, vals in params.items():
        if k not in PARAMS:
            raise bad(f"unknown SAGE parameter {k!r}; expected one of {', '.join(PARAMS)}", "params", k)
        if not isinstance(vals, list) or not vals:
            raise bad(f"parameter {k!r} needs a non-empty list of values", "params", k)
        out = []
        for v in vals:
            if isinstance(v, bool) or not isinstance(v, (int, float)):
                raise bad(f"parameter {k!r}: {_said(v)} is not a number", "params", k)
            if not 0.0 <= float(v) <= 1.0:
                raise bad(f"parameter {k!r}: {v} is out of range [0, 1]", "params", k)
            out.append(float(v))
        if len(set(out)) != len(out):
            raise bad(f"parameter {k!r} repeats a value", "params", k)
        swept[k] = tuple(out)

    heat = data.get("heatmap")
    axes_heat: tuple[str, str] | None = None
    if heat is not None:
        if not isinstance(heat, dict) or set(heat) != {"x", "y"}:
            raise bad("[heatmap] needs exactly the keys x and y", "", "heatmap")
        choices = ("experiment", "protocol", "without") + PARAMS
        for k in ("x", "y"):
            if heat[k] not in choices:
                raise bad(f"heatmap {k} = {heat[k]!r} is not an axis; expected one of {', '.join(choices)}",
                          "heatmap", k)
        if heat["x"] == heat["y"]:
            raise bad("heatmap x and y must be two different axes", "heatmap", "y")
        axes_heat = (heat["x"], heat["y"])

    why = too_many_lessons(lessons, exps, prots)
    if why is not None:
        raise bad(f"'lessons' = {lessons}: {why}", "", "lessons")
    return Grid(path, tuple(exps), trials, tuple(seeds), tuple(wo), swept, perception, lessons, axes_heat,
                tuple(prots))
