"""Several detectors side by side on the same scenes: `aileen perception compare`.

Why: a retrained detector ships only where it is no worse than the one it replaces on every
figure that matters (the plain scenes' errors, the stacks' on-top error and partly hidden
recall, a held-out seed), and judging that meant running `eval` six times per model and
reading six reports. This runs one battery of evaluations (`Battery`: plain scenes, then
stacked scenes on each seed) for every model, on the shapes all of them know (so a model
that knows a fifth shape is judged on the scenes the others can see), plus, for a model
that knows more shapes than that, the same scenes with every shape it knows; and prints
one table, a row per figure and a column per model (`format_table`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass

from aileen.errors import UserError
from aileen.perception.detector import load_detector
from aileen.perception.evaluate import STACK_SHARE, evaluate
from aileen.perception.matching import AGREE
from aileen.world import catalog

__all__ = ["Battery", "compare", "format_table"]

SHIPPED = "shipped"  # how the shipped model is named on the command line and in the table
EVERY = "every shape it knows"  # a run on the shapes of the model alone (it knows more than the others)


@dataclass(frozen=True)
class Battery:
    """The scenes every model is judged on: `plain` scenes without stacks on the first seed,
    and `stacked` scenes (half of them with stacks, as `eval`) on each seed; for a model that
    knows more shapes than the others, each of these again with every shape it knows."""

    plain: int = 2000
    stacked: int = 1000
    seeds: tuple[int, ...] = (12345, 54321)
    matching: str = AGREE

    def runs(self, common: tuple[str, ...], own: tuple[str, ...]) -> list[tuple[str, int, int, float, tuple[str, ...]]]:
        """(name, scenes, seed, stack share, shapes) of each evaluation of a model that knows
        `own`, where every compared model knows `common`."""
        out = [("plain", self.plain, self.seeds[0], 0.0, common)]
        if own != common:
            out.append((f"plain, {EVERY}", self.plain, self.seeds[0], 0.0, own))
        for s in self.seeds:
            out.append((f"stacked, seed {s}", self.stacked, s, STACK_SHARE, common))
            if own != common:
                out.append((f"stacked, seed {s}, {EVERY}", self.stacked, s, STACK_SHARE, own))
        return [r for r in out if r[1] > 0]

    def order(self) -> list[str]:
        """Every run's name, in the order of the table: those of a model that knows more
        shapes than the others (any two different shape lists say so)."""
        return [name for name, *_ in self.runs(common=(), own=("any",))]


def _path(model: str) -> str | None:
    return None if model == SHIPPED else model


def compare(models: Sequence[str], battery: Battery = Battery(),
            progress: Callable[[str, int, int], None] | None = None) -> dict:
    """{"shapes": the shapes every model knows, "battery": what was run, "models": {model:
    {run: eval report}}} for each model (`SHIPPED` for the shipped one). `progress(label,
    done, total)` is called as each evaluation ends."""
    if not models:
        raise UserError("name at least one model (a detector .onnx, or 'shipped')")
    if not battery.seeds:
        raise UserError("--seeds: name at least one seed")
    known = {m: load_detector(_path(m)).shapes for m in models}
    common = tuple(s for s in catalog.SHAPES if all(s in k for k in known.values()))
    if not common:
        raise UserError("the models share no shape to be compared on")
    out: dict = {"shapes": list(common), "battery": asdict(battery), "models": {}}
    plan = [(m, run) for m in models for run in battery.runs(common, known[m])]
    for done, (m, (name, n, seed, share, shapes)) in enumerate(plan, start=1):
        out["models"].setdefault(m, {})[name] = evaluate(n, seed, model=_path(m), stack_share=share, shapes=shapes,
                                                         failures=0, matching=battery.matching)
        if progress is not None:
            progress(f"{m}: {name}", done, len(plan))
    return out


def _pct(x: float) -> str:
    return f"{x * 100:.3f} %"


def _of(k: int, n: int, x: float) -> str:
    return f"{x * 100:.3f} % ({k} of {n})"


def _spurious(r: dict) -> str:
    return str(r["shape_confusion"].get("none->spurious", 0))


# The figures of each kind of run: (row label, how a report gives it).
_PLAIN: tuple[tuple[str, Callable[[dict], str]], ...] = (
    ("recall", lambda r: _pct(r["recall"])),
    ("precision", lambda r: _pct(r["precision"])),
    ("shape error", lambda r: _pct(r["shape_error"])),
    ("colour error", lambda r: _pct(r["color_error"])),
    ("size error", lambda r: _pct(r["size_error"])),
    ("spurious detections", _spurious),
)
_STACKED: tuple[tuple[str, Callable[[dict], str]], ...] = (
    ("recall", lambda r: _pct(r["recall"])),
    ("shape error", lambda r: _pct(r["shape_error"])),
    ("colour error", lambda r: _pct(r["color_error"])),
    ("size error", lambda r: _pct(r["size_error"])),
    ("on-top error, support in sight", lambda r: _of(r["on_top_wrong_in_sight"], r["on_top_in_sight"],
                                                      r["on_top_error_in_sight"])),
    ("partly hidden recall, >= 25 % visible", lambda r: _of(r["partly_hidden_found_from_25"],
                                                             r["partly_hidden_from_25"],
                                                             r["partly_hidden_recall_from_25"])),
    ("spurious detections", _spurious),
)


def format_table(result: dict) -> str:
    """The comparison as a Markdown table: a row per figure, a column per model ("-" where a
    model has no such run)."""
    models = list(result["models"])
    order = Battery(**{**result["battery"], "seeds": tuple(result["battery"]["seeds"])}).order()
    runs = [name for name in order if any(name in reports for reports in result["models"].values())]
    lines = [f"scenes of {', '.join(result['shapes'])} (the shapes every model knows) unless a row says otherwise",
             "", "| | " + " | ".join(models) + " |", "|---" * (len(models) + 1) + "|"]
    for run in runs:
        figures = _PLAIN if run.startswith("plain") else _STACKED
        for label, get in figures:
            cells = [get(result["models"][m][run]) if run in result["models"][m] else "-" for m in models]
            lines.append(f"| {run}: {label} | " + " | ".join(cells) + " |")
    return "\n".join(lines)
