"""`aileen perception dataset | train | eval | compare | tune-color`."""

from __future__ import annotations

import argparse
import json
import sys

from aileen import argtypes
from aileen.errors import UserError
from aileen.perception.matching import AGREE, MATCHINGS


def register(subparsers: argparse._SubParsersAction) -> None:
    p = subparsers.add_parser("perception", help="the visual and spatial modules: data, training, evaluation")
    sub = p.add_subparsers(dest="perception_command", metavar="SUBCOMMAND")
    p.set_defaults(handler=lambda a: (p.print_help(), 0)[1])

    d = sub.add_parser("dataset", help="render labelled scenes for training the detector")
    d.add_argument("--n", type=int, default=12000, help="number of images (default 12000)")
    d.add_argument("--seed", type=argtypes.seed, default=0, help="seed of the scenes, a whole number >= 0 (default 0)")
    d.add_argument("--out", required=True, help="output folder (images.npy + labels.json)")
    d.add_argument("--min-objects", type=int, default=1,
                   help="fewest objects laid on the table (default 1); a stacked scene puts more on top of them")
    d.add_argument("--max-objects", type=int, default=6,
                   help="most objects laid on the table (default 6; a table that cannot hold them gets fewer); a "
                   "stacked scene puts more on top of them")
    d.add_argument("--stack-share", type=float, default=0.5,
                   help="share of scenes with one or two stacks (default 0.5)")
    d.add_argument("--row-share", type=float, default=0.0,
                   help="share of scenes that start with a row of 2-3 touching boxes, as a wall (default 0)")
    d.add_argument("--shapes", default=None,
                   help="the shapes drawn, comma-separated (default: the catalog's); a detector trained on the "
                        "data knows these")
    d.set_defaults(handler=_dataset)

    t = sub.add_parser("train", help="train the shape detector and export it to ONNX (needs the train extra)")
    t.add_argument("data", nargs="+", help="dataset folder(s) from `aileen perception dataset`, sampled as one set")
    t.add_argument("--out", required=True, help="output .onnx (metadata goes beside it as .json)")
    t.add_argument("--steps", type=int, default=None, help="training steps (default 12000)")
    t.add_argument("--batch", type=int, default=None, help="crops per step (default 32)")
    t.add_argument("--seed", type=argtypes.seed, default=0, help="seed of the initial weights and the sampling (default 0)")
    t.add_argument("--threads", type=int, default=2, help="CPU threads torch may use (default 2)")
    t.add_argument("--lr", type=float, default=None, help="peak learning rate (default 3e-3)")
    t.add_argument("--init", default=None, help="a trained detector .onnx to start from (fine-tuning)")
    t.add_argument("--width", type=int, default=None,
                   help="channels of the body's last three convs (default: the --init model's, else 48); "
                        "thinner than the --init model prunes it (the filters of largest L1 norm are kept)")
    t.add_argument("--stack-crops", type=float, default=0.0,
                   help="share of training crops placed around an object resting on another (default 0)")
    t.add_argument("--distill", default=None,
                   help="a trained detector .onnx whose output maps the network learns beside the labels "
                        "(knowledge distillation; the teacher keeps its own width)")
    t.add_argument("--distill-weight", type=float, default=1.0,
                   help="weight of the distillation term beside the label losses (default 1)")
    t.add_argument("--branch", action="store_true",
                   help="keep the --init model frozen and train a small branch for the datasets' shapes it "
                        "lacks (its outputs stay the model's where no new shape lies)")
    t.set_defaults(handler=_train)

    e = sub.add_parser("eval", help="compare perception with ground truth on fresh rendered scenes")
    e.add_argument("--n", type=int, default=200, help="number of scenes (1-4 objects each)")
    e.add_argument("--seed", type=argtypes.seed, default=12345, help="seed of the scenes (default 12345)")
    e.add_argument("--model", default=None, help="detector .onnx (default: the shipped one)")
    e.add_argument("--stack-share", type=float, default=0.5, help="share of scenes with stacks (default 0.5)")
    e.add_argument("--shapes", default=None,
                   help="the shapes drawn, comma-separated (default: every shape the model knows)")
    e.add_argument("--failures", type=int, default=None, metavar="N",
                   help="list the first N failures, one line each (default 20; -1: every one)")
    e.add_argument("--matching", choices=MATCHINGS, default=AGREE,
                   help="how perceived objects are paired with true ones: nearest first, the same objects paired "
                        "the other way round where that is within 1 cm and agrees on more of shape, colour, size "
                        "and level (agree, the default); nearest first alone (greedy, the rule until stop 37); "
                        "docs/perception.md")
    e.add_argument("--json", action="store_true", help="print one JSON object")
    e.set_defaults(handler=_eval)

    m = sub.add_parser("compare", help="several detectors side by side on the same plain and stacked scenes")
    m.add_argument("models", nargs="+", metavar="MODEL",
                   help="detector .onnx files to compare; 'shipped' names the shipped one")
    m.add_argument("--plain", type=int, default=2000, help="scenes without stacks (default 2000; 0: none)")
    m.add_argument("--stacked", type=int, default=1000,
                   help="scenes per seed, half with stacks (default 1000; 0: none)")
    m.add_argument("--seeds", default="12345,54321",
                   help="seeds of the scenes, comma-separated: the first for the plain scenes, each for the "
                        "stacked ones (default 12345,54321: the issue's and a held-out one)")
    m.add_argument("--matching", choices=MATCHINGS, default=AGREE,
                   help="how perceived objects are paired with true ones (as for eval)")
    m.add_argument("--json", action="store_true", help="print one JSON object with every model's eval reports")
    m.set_defaults(handler=_compare)

    c = sub.add_parser("tune-color", help="grid-search the colour module's weight w1 on rendered crops")
    c.add_argument("--n", type=int, default=400, help="number of scenes (1-6 objects each)")
    c.add_argument("--seed", type=argtypes.seed, default=777, help="seed of the scenes (default 777)")
    c.add_argument("--json", action="store_true", help="print one JSON object")
    c.set_defaults(handler=_tune)


def _positive(name: str, v: int | None) -> None:
    if v is not None and v < 1:
        raise UserError(f"--{name} must be a positive integer, got {v}")


def _share(name: str, v: float) -> None:
    if not 0.0 <= v <= 1.0:
        raise UserError(f"--{name} must lie in [0, 1], got {v}")


def _shapes(text: str | None) -> tuple[str, ...] | None:
    """`--shapes box,cone`: distinct catalog shapes, in the catalog's order (None: all)."""
    from aileen.world import catalog

    if text is None:
        return None
    names = [t.strip() for t in text.split(",") if t.strip()]
    bad = [t for t in names if t not in catalog.SHAPES]
    if not names or bad:
        raise UserError(f"--shapes takes shapes of {', '.join(catalog.SHAPES)}, comma-separated; got {text!r}")
    return tuple(s for s in catalog.SHAPES if s in names)


def _dataset(a: argparse.Namespace) -> int:
    from aileen.perception.dataset import SceneSpec, write_dataset

    _positive("n", a.n)
    if not (1 <= a.min_objects <= a.max_objects):
        raise UserError(f"expected 1 <= --min-objects <= --max-objects, got {a.min_objects} and {a.max_objects}")
    _share("stack-share", a.stack_share)
    _share("row-share", a.row_share)
    spec = SceneSpec(a.min_objects, a.max_objects, a.stack_share, a.row_share, _shapes(a.shapes))
    out = write_dataset(a.out, a.n, a.seed, spec, progress=sys.stderr.isatty())
    print(f"wrote {a.n} images to {out}")
    return 0


def _train(a: argparse.Namespace) -> int:
    try:
        import torch  # noqa: F401
    except ImportError:
        raise UserError("training needs torch and onnx: pip install -e '.[train]'") from None
    from aileen.perception.train import TrainConfig, train

    _positive("steps", a.steps)
    _positive("batch", a.batch)
    _positive("width", a.width)
    kw = {"seed": a.seed, "threads": a.threads}
    if a.steps:
        kw["steps"] = a.steps
    if a.batch:
        kw["batch"] = a.batch
    if a.lr is not None:
        if not 0.0 < a.lr < 1.0:
            raise UserError(f"--lr must lie between 0 and 1 (exclusive), got {a.lr}")
        kw["lr"] = a.lr
    if a.init is not None:
        kw["init"] = a.init
    if a.width is not None:
        kw["width"] = a.width
    _share("stack-crops", a.stack_crops)
    kw["stack_crops"] = a.stack_crops
    if a.distill is not None:
        if not (a.distill_weight >= 0.0 and a.distill_weight < float("inf")):
            raise UserError(f"--distill-weight must be a finite number >= 0, got {a.distill_weight}")
        kw["distill"] = a.distill
        kw["distill_weight"] = a.distill_weight
    kw["branch"] = a.branch
    info = train(a.data, a.out, TrainConfig(**kw))
    print(json.dumps(info["validation"]))
    return 0


def _eval(a: argparse.Namespace) -> int:
    from aileen.perception.evaluate import FAILURES, evaluate, format_report

    _positive("n", a.n)
    _share("stack-share", a.stack_share)
    if a.failures is not None and a.failures < -1:
        raise UserError(f"--failures {a.failures}: expected a whole number >= 0, or -1 for every failure")
    listed = FAILURES if a.failures is None else (None if a.failures == -1 else a.failures)
    report = evaluate(a.n, a.seed, model=a.model, stack_share=a.stack_share, shapes=_shapes(a.shapes),
                      failures=listed, matching=a.matching)
    if a.json:
        print(json.dumps(report))
    else:
        print(format_report(report))
    return 0


def _compare(a: argparse.Namespace) -> int:
    from tqdm import tqdm

    from aileen.perception.compare import Battery, compare, format_table

    if a.plain < 0 or a.stacked < 0:
        raise UserError(f"--plain and --stacked are numbers of scenes (>= 0), got {a.plain} and {a.stacked}")
    if a.plain + a.stacked == 0:
        raise UserError("nothing to compare: --plain and --stacked are both 0 scenes")
    try:
        seeds = tuple(argtypes.seed(x.strip()) for x in a.seeds.split(",") if x.strip())
    except (argparse.ArgumentTypeError, ValueError) as exc:
        raise UserError(f"--seeds {a.seeds!r}: {exc}") from None
    battery = Battery(a.plain, a.stacked, seeds, a.matching)
    with tqdm(desc="compare", unit="eval", disable=a.json or not sys.stderr.isatty()) as bar:
        def step(label: str, done: int, total: int) -> None:
            bar.total = total
            bar.set_postfix_str(label)
            bar.update(done - bar.n)
        result = compare(a.models, battery, progress=step)
    print(json.dumps(result) if a.json else format_table(result))
    return 0


def _tune(a: argparse.Namespace) -> int:
    from aileen.perception.evaluate import tune_colour

    _positive("n", a.n)
    res = tune_colour(a.n, a.seed)
    if a.json:
        print(json.dumps({"w1": res.w1, "w2": round(1 - res.w1, 6), "accuracy": res.accuracy, "crops": res.n,
                          "grid": res.grid}))
        return 0
    print(f"{res.n} crops (truth boxes jittered by up to 2 px, neighbours and table included)")
    for w1, acc in res.grid:
        print(f"  w1 {w1:.2f}  w2 {1 - w1:.2f}  accuracy {acc * 100:.2f} %")
    print(f"best: w1 = {res.w1:.2f}, w2 = {1 - res.w1:.2f}, accuracy {res.accuracy * 100:.2f} %")
    return 0


__all__ = ["register"]
