"""Learning-curve plots in the paper's style, and the original system's reference curves.

Bars: create/store commands per lesson (mean, with standard deviation); lines: mean
generality and specificity (0-5). On the same axes: the one-shot oracle (the ceiling an
ideal one-shot learner reaches on the same exams) and the original AILEEN's curves, recovered
from its published logs (`reference.csv`, a copy of `../shared/reference/aileen_original_curves.csv`).

matplotlib is an optional extra (`pip install aileen[plot]`), imported only when plotting.
"""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass
from pathlib import Path

from aileen.errors import UserError
from aileen.experiments.results import ExperimentResult
from aileen.experiments.tables import write_bytes

PACKAGE_REFERENCE = Path(__file__).with_name("reference.csv")
SHARED_REFERENCE = Path(__file__).resolve().parents[2].parent / "shared" / "reference" / "aileen_original_curves.csv"


@dataclass(frozen=True)
class ReferencePoint:
    """The original system's per-lesson means (one experiment, one lesson)."""

    experiment: str
    lesson: int
    runs: int
    commands: float
    generality: float
    specificity: float


def reference_path() -> Path | None:
    """The original system's curves: the package's copy, else `<repo>/../shared/reference/`."""
    for p in (PACKAGE_REFERENCE, SHARED_REFERENCE):
        if p.is_file():
            return p
    return None


def load_reference(path: str | Path | None = None) -> dict[str, list[ReferencePoint]]:
    """Per experiment, the original's per-lesson means in lesson order; {} when not found.

    A malformed file is a `UserError` naming the file and line."""
    p = Path(path) if path is not None else reference_path()
    if p is None or not p.is_file():
        return {}
    out: dict[str, list[ReferencePoint]] = {}
    with p.open(newline="", encoding="utf-8") as fh:
        reader = csv.DictReader(fh)
        need = {"experiment", "lesson", "runs", "mean_store_commands", "mean_generality", "mean_specificity"}
        if reader.fieldnames is None or not need <= set(reader.fieldnames):
            raise UserError(f"expected the columns {', '.join(sorted(need))}", path=str(p), line=1)
        for row in reader:
            try:
                pt = ReferencePoint(row["experiment"], int(row["lesson"]), int(row["runs"]),
                                    float(row["mean_store_commands"]), float(row["mean_generality"]),
                                    float(row["mean_specificity"]))
            except (TypeError, ValueError) as exc:
                raise UserError(f"expected numbers in lesson, runs and the means ({exc})", path=str(p),
                                line=reader.line_num) from None
            out.setdefault(pt.experiment, []).append(pt)
    for pts in out.values():
        pts.sort(key=lambda q: q.lesson)
    return out


def require_matplotlib() -> None:
    """Fail before a long run, not after it, when plots are asked for and cannot be drawn."""
    _matplotlib()


def _matplotlib():  # noqa: ANN202
    try:
        import matplotlib
    except ImportError:
        raise UserError("plots need matplotlib: install the plot extra, aileen[plot] (pip install -e '.[plot]'), "
                        "or add --no-plot to write the CSV files only") from None
    return matplotlib


def _pyplot():  # noqa: ANN202
    matplotlib = _matplotlib()
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


BASELINE_STYLE = {"paper": ("#b5651d", "paper's learner"), "nearest": ("#888888", "nearest neighbour"),
                  "cobweb": ("#c03a8a", "COBWEB"), "trestle": ("#7a6a00", "TRESTLE")}


def plot_curve(res: ExperimentResult, path: str | Path, *, reference: dict | None = None,
               baselines: "dict[str, ExperimentResult] | None" = None) -> list[str]:
    """Draw one experiment's learning curve to a PNG (`curve_png`); returns notes."""
    png, notes = curve_png(res, reference=reference, baselines=baselines)
    write_bytes(Path(path), png)
    return notes


def curve_png(res: ExperimentResult, *, reference: dict | None = None,
              baselines: "dict[str, ExperimentResult] | None" = None) -> tuple[bytes, list[str]]:
    """One experiment's learning curve as PNG bytes (written with the run's other files, all
    together), and notes (e.g. reference missing). The original system's curve is drawn for
    the paper's protocol only (it was measured on it); `baselines` adds each baseline
    learner's generality and specificity."""
    plt = _pyplot()
    notes: list[str] = []
    ref = load_reference() if reference is None else reference
    paper = getattr(res, "protocol", "paper") == "paper"
    orig = ref.get(res.experiment, []) if paper else []
    if not orig and paper:
        notes.append(f"{res.experiment}: the original system's curve was not found; plotted without it")
    s = res.summary
    xs = [x.lesson for x in s]
    who = "ours" if getattr(res, "agent", "asp") == "asp" else res.agent  # a baseline run alone says so
    fig, ax = plt.subplots(figsize=(8, 4.5), dpi=110)
    ax.bar(xs, [x.commands_mean for x in s], yerr=[x.commands_std for x in s], width=0.6, color="#9db4d0",
           ecolor="#5a6f8a", capsize=2, label=f"create/store commands ({who})")
    if orig:
        ax.bar([p.lesson + 0.3 for p in orig if p.lesson <= len(xs) or not xs],
               [p.commands for p in orig if p.lesson <= len(xs) or not xs], width=0.25, color="#d9b38c",
               label="create/store commands (original)")
    ax.plot(xs, [x.oracle_mean for x in s], color="black", ls=":", lw=1.8, label="one-shot oracle", zorder=5)
    ceil = [x.ceiling_mean for x in s]
    if any(abs(c - o.oracle_mean) > 1e-9 for c, o in zip(ceil, s)):
        ax.plot(xs, ceil, color="#7a4fa0", ls="-.", lw=1.2, label="cross-situational learner, no syntax")
    sector = [[r.sector_ceiling for r in t.records] for t in res.trials]
    whole = bool(sector) and all(len(c) == len(xs) and min(c, default=0) >= 0 for c in sector)
    sector_mean = [sum(c[i] for c in sector) / len(sector) for i in range(len(xs))] if whole else []
    if whole and any(abs(c - o.oracle_mean) > 1e-9 for c, o in zip(sector_mean, s)):  # (no directions: the oracle)
        ax.plot(xs, sector_mean, color="#555555", ls="-", lw=1.0, alpha=0.8,
                label="an ideal 8-sector learner (its ceiling, not ours)")
    ax.errorbar(xs, [x.generality_mean for x in s], yerr=[x.generality_std for x in s], color="#1f5fa8",
                marker="o", ms=4, lw=2, capsize=2, label=f"generality ({who})")
    ax.plot(xs, [x.specificity_mean for x in s], color="#2a9d47", marker="s", ms=4, lw=2,
            label=f"specificity ({who})")
    ax.plot(xs, [x.balanced_mean for x in s], color="#d2691e", lw=1.6, alpha=0.9,
            label=f"balanced ({who}): mean of the two")
    if s and all(x.ideal_generality_mean == x.ideal_generality_mean for x in s):  # not nan: an ideal observer
        ax.plot(xs, [x.ideal_generality_mean for x in s], color="#1f5fa8", ls=(0, (1, 1)), lw=1.4,
                label="generality (ideal observer)")
        ax.plot(xs, [x.ideal_specificity_mean for x in s], color="#2a9d47", ls=(0, (1, 1)), lw=1.4,
                label="specificity (ideal observer)")
    if orig:
        ox = [p.lesson for p in orig]
        ax.plot(ox, [p.generality for p in orig], color="#1f5fa8", ls="--", lw=1.2, alpha=0.7,
                label=f"generality (original, {orig[0].runs} runs)")
        ax.plot(ox, [p.specificity for p in orig], color="#2a9d47", ls="--", lw=1.2, alpha=0.7,
                label="specificity (original)")
    for name, other in (baselines or {}).items():
        colour, label = BASELINE_STYLE.get(name, ("#444444", name))
        bx = [x.lesson for x in other.summary]
        ax.plot(bx, [x.generality_mean for x in other.summary], color=colour, ls="--", lw=1.2,
                label=f"generality ({label})")
        ax.plot(bx, [x.specificity_mean for x in other.summary], color=colour, ls=":", lw=1.2,
                label=f"specificity ({label})")
    items = max(getattr(res.headline, "exam_items", (5, 5)) if res.headline is not None else (5, 5))
    ax.set_xlabel("lesson")
    ax.set_ylabel(f"exam score (of {items}) / commands")
    ax.set_ylim(0, items * 1.28)
    last = max(xs + [p.lesson for p in orig]) if (xs or orig) else 1
    ax.set_xlim(0.3, last + 0.7)
    ax.set_xticks(range(1, last + 1, 1 if last <= 24 else 2))
    ax.set_title(curve_title(res), fontsize=9)
    ax.grid(axis="y", alpha=0.3)
    ax.legend(fontsize=7, loc="upper center", ncol=3, framealpha=0.9)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png")
    plt.close(fig)
    return buf.getvalue(), notes


def _na(x: float) -> str:
    """A figure for a plot: "n/a" where it is undefined (nan; "-" in the printed table)."""
    return "n/a" if x != x else f"{x:.1f}"


def curve_title(res: ExperimentResult) -> str:
    """The learning curve's title: what ran, and the headline figures (an undefined one "n/a":
    it read "nan")."""
    without = getattr(res, "without", ())
    h = res.headline
    figures = ""
    if h is not None and h.balanced_pct_oracle == h.balanced_pct_oracle:
        figures = f"\nbalanced area: {h.balanced_pct_oracle:.1f} % of the one-shot oracle"
        if h.balanced_pct_ideal == h.balanced_pct_ideal:
            figures += f", {h.balanced_pct_ideal:.1f} % of the ideal observer"
        figures += f"; generality only: {_na(h.area_pct_of_oracle)} % of the oracle"
    senses = getattr(res, "senses", "")
    return (f"{res.experiment} ({getattr(res, 'protocol', 'paper')} protocol): {len(res.trials)} "
            f"trial{'s' if len(res.trials) != 1 else ''}, perception={res.perception}"
            + (f", senses={senses}" if senses else "") + (f", without {' + '.join(without)}" if without else "")
            + figures)


def plot_heatmap(cells: dict[tuple, float], x: str, y: str, path: str | Path, *, title: str) -> None:
    """A sweep's heat map: `cells[(x value, y value)]` = curve area (% of the oracle), each
    cell printed with its value; cells the grid lacks are left blank."""
    import numpy as np

    plt = _pyplot()
    xs = sorted({k[0] for k in cells}, key=_axis_order)
    ys = sorted({k[1] for k in cells}, key=_axis_order)
    grid = np.full((len(ys), len(xs)), np.nan)
    for (a, b), v in cells.items():
        grid[ys.index(b), xs.index(a)] = v
    width = 1.2 * len(xs) + 2.6
    fig, ax = plt.subplots(figsize=(width, 0.8 * len(ys) + 1.8), dpi=110)
    im = ax.imshow(grid, origin="lower", cmap="viridis", vmin=0, vmax=100, aspect="auto")
    for i in range(len(ys)):
        for j in range(len(xs)):
            if not np.isnan(grid[i, j]):
                ax.text(j, i, f"{grid[i, j]:.1f}", ha="center", va="center", fontsize=8,
                        color="white" if grid[i, j] < 60 else "black")
    ax.set_xticks(range(len(xs)), [str(v) for v in xs])
    ax.set_yticks(range(len(ys)), [str(v) for v in ys])
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    import textwrap

    # wrapped to the figure's width (about 9 characters an inch at this size): a long title
    # on a 2 x 2 map was cut off on the left
    ax.set_title(textwrap.fill(title, width=max(24, int(9 * width))), fontsize=9)
    fig.colorbar(im, ax=ax, label="curve area, % of oracle")
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", metadata={"Software": None})
    plt.close(fig)
    write_bytes(Path(path), buf.getvalue())


def _axis_order(v: object) -> tuple:
    return (0, float(v), "") if isinstance(v, (int, float)) else (1, 0.0, str(v))
