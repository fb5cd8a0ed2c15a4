"""Perception against ground truth on fresh rendered scenes, and colour-weight tuning.

`evaluate` renders scenes of 1-4 objects with the dataset generator (same distribution of
shapes, colours, sizes, near-touching neighbours, lighting and noise as training, a seed the
training never used), runs `perceive` on each image, and pairs perceived objects with true
ones by centre distance (a match must lie within 40 % of the object's footprint of its true
centre; where positions cannot tell two pairings apart, in a stack, by their attributes:
`aileen.perception.matching`). Recall, precision, shape, colour and size error (over matched objects),
on-top error (the perceived level against the true one), mean centroid error in metres and
the confusion matrices come back as one JSON-able dict.

Stacks (half the scenes, as in training): an object less than `MIN_VISIBLE` visible (one
wholly under another) is out of the camera's sight; it is counted apart ("hidden") and not
in recall. Objects partly hidden under another (between `MIN_VISIBLE` and `PARTLY` visible)
get their own recall, by how much of them shows, and their own colour and size errors.
The report ends with issue 22's stack targets: on-top error where the support is in sight
(<= 0.2 %), partly hidden recall of objects at least 25 % visible (>= 99.5 %), and the
objects under 10 % visible (and what rests on them) apart.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Sequence

import numpy as np

from aileen.errors import UserError
from aileen.perception.color import TuneResult, tune_weights
from aileen.perception.dataset import SceneSpec, generate
from aileen.perception.detector import load_detector
from aileen.perception.matching import AGREE, MATCH_FRACTION, MATCHINGS, match
from aileen.perception.scene import perceive
from aileen.world import catalog
from aileen.world.camera import DEFAULT_CAMERA

__all__ = ["evaluate", "format_report", "tune_colour", "match", "MATCH_FRACTION", "MATCHINGS"]

MIN_VISIBLE = 0.1  # less than this shows: hidden (the training data has no such targets either)
PARTLY = 0.99  # less than this shows: partly hidden
VISIBLE_BINS = (0.1, 0.25, 0.5, 0.75, PARTLY)
# Issue 22's stack targets: the on-top error where the support is at least MIN_VISIBLE in
# sight (a top-down image cannot tell what an object rests on when that is hidden), and the
# recall of partly hidden objects at least RECALL_FROM visible.
RECALL_FROM = 0.25
TARGET_ON_TOP_IN_SIGHT = 0.002
TARGET_PARTLY_RECALL = 0.995
FAILURES = 20  # failures listed in a report by default
STACK_SHARE = 0.5  # share of scenes with stacks by default (as the training data)


def evaluate(n: int, seed: int, *, model: str | None = None, max_objects: int = 4, stack_share: float = STACK_SHARE,
             shapes: tuple[str, ...] | None = None, failures: int | None = FAILURES, matching: str = AGREE) -> dict:
    """Perception figures on `n` fresh scenes of 1..max_objects objects, `stack_share` of
    them with stacks, drawing `shapes` (default: every shape the model knows; fewer to
    compare two models on the scenes both know, as a model's and its branch's). The report
    lists the first `failures` failures, one line each (None: every one; they say what to
    look at when a figure moves). `matching`: how perceived objects are paired with true ones
    (`aileen.perception.matching.MATCHINGS`; `greedy` was the rule until stop 37)."""
    if matching not in MATCHINGS:
        raise UserError(f"--matching {matching}: expected one of {', '.join(MATCHINGS)}")
    n_truth = n_pred = n_match = wrong_shape = wrong_colour = wrong_size = wrong_level = 0
    n_unseen_support = wrong_level_unseen = 0
    n_hidden = n_hidden_found = 0
    n_upper = n_upper_matched = 0
    partly = [0] * (len(VISIBLE_BINS) - 1)
    partly_found = [0] * (len(VISIBLE_BINS) - 1)
    partly_colour = partly_size = partly_matched = 0
    errs: list[float] = []
    size_conf: Counter[tuple[str, str]] = Counter()
    shape_conf: Counter[tuple[str, str]] = Counter()
    colour_conf: Counter[tuple[str, str]] = Counter()
    listed: list[str] = []

    def fail(line: str) -> None:
        if failures is None or len(listed) < failures:
            listed.append(line)
    # a model trained before a shape joined the catalog is judged on the shapes it knows
    model_shapes = load_detector(model).shapes
    known = model_shapes
    if shapes is not None:
        unknown = [s for s in shapes if s not in known]
        if unknown:
            raise UserError(f"--shapes: the model does not know {', '.join(unknown)} (it knows {', '.join(known)})")
        known = tuple(s for s in catalog.SHAPES if s in shapes)
    shapes = None if known == catalog.SHAPES else known
    for k, s in enumerate(generate(n, seed, SceneSpec(1, max_objects, stack_share, shapes=shapes), DEFAULT_CAMERA)):
        scene = perceive(s.image, model=model)
        truth = [(o.centre_m[0], o.centre_m[1], catalog.SIZES[o.size]) for o in s.objects]
        pred = [o.centre_m for o in scene.objects]
        pairs = match(pred, truth, _agreement(scene.objects, s.objects), rule=matching)
        n_pred += len(pred)
        mp = {j for _, j, _ in pairs}
        for j, o in enumerate(s.objects):
            if o.visible < MIN_VISIBLE:
                n_hidden += 1
                n_hidden_found += j in mp
                continue
            n_truth += 1
            n_upper += o.level > 0
            if o.visible < PARTLY:
                b = max(i for i, lo in enumerate(VISIBLE_BINS[:-1]) if o.visible >= lo)
                partly[b] += 1
                partly_found[b] += j in mp
            if j not in mp:
                shape_conf[(o.shape, "missed")] += 1
                colour_conf[(o.colour, "missed")] += 1
                fail(f"scene {k}: missed {o.colour} {o.shape} at {o.centre_m[0]:.3f},{o.centre_m[1]:.3f}"
                     f" ({o.visible * 100:.0f} % visible)")
        for i, j, d in pairs:
            p, t = scene.objects[i], s.objects[j]
            if t.visible < MIN_VISIBLE:
                continue  # found though hidden: neither counted nor spurious
            n_match += 1
            errs.append(d)
            size_conf[(t.size, p.size)] += 1
            n_upper_matched += t.level > 0
            if p.size != t.size:
                wrong_size += 1
                fail(f"scene {k}: {t.size} {t.colour} {t.shape} seen as {p.size} "
                     f"({p.footprint * 100:.1f} cm, {t.visible * 100:.0f} % visible)")
            if t.support_visible < MIN_VISIBLE:
                n_unseen_support += 1
                wrong_level_unseen += p.level != t.level
            if p.level != t.level:
                wrong_level += 1
                support = f", its support {t.support_visible * 100:.0f} % in sight" if t.level else ""
                fail(f"scene {k}: {t.colour} {t.shape} at level {t.level} seen at level {p.level}"
                     f" ({t.visible * 100:.0f} % visible{support})")
            if t.visible < PARTLY:
                partly_matched += 1
                partly_colour += p.colour != t.colour
                partly_size += p.size != t.size
            shape_conf[(t.shape, p.shape)] += 1
            colour_conf[(t.colour, p.colour)] += 1
            if p.shape != t.shape:
                wrong_shape += 1
                fail(f"scene {k}: {t.colour} {t.shape} seen as {p.shape}")
            if p.colour != t.colour:
                wrong_colour += 1
                fail(f"scene {k}: {t.colour} {t.shape} seen as {p.colour} (level {t.level}, {t.visible * 100:.0f} % visible)")
        extra = len(pred) - len(pairs)
        if extra:
            shape_conf[("none", "spurious")] += extra
            fail(f"scene {k}: {extra} spurious detection(s)")
    partly_25 = sum(k for b, k in enumerate(partly) if VISIBLE_BINS[b] >= RECALL_FROM)
    found_25 = sum(k for b, k in enumerate(partly_found) if VISIBLE_BINS[b] >= RECALL_FROM)
    return {
        "scenes": n,
        "seed": seed,
        "shapes": list(known),
        "model_shapes": list(model_shapes),
        "stack_share": stack_share,
        "matching": matching,
        "objects": n_truth,
        "detections": n_pred,
        "matched": n_match,
        "recall": n_match / max(1, n_truth),
        "precision": (n_match + n_hidden_found) / max(1, n_pred),
        "shape_error": wrong_shape / max(1, n_match),
        "color_error": wrong_colour / max(1, n_match),
        "size_error": wrong_size / max(1, n_match),
        "on_top_error": wrong_level / max(1, n_match),
        "objects_on_top": n_upper,
        # objects resting on one the camera cannot see (under MIN_VISIBLE shows): nothing in
        # the image says they rest on anything; the on-top error without them
        "on_unseen": n_unseen_support,
        "on_unseen_wrong": wrong_level_unseen,
        "on_top_in_sight": n_match - n_unseen_support,
        "on_top_wrong_in_sight": wrong_level - wrong_level_unseen,
        "on_top_error_in_sight": (wrong_level - wrong_level_unseen) / max(1, n_match - n_unseen_support),
        "objects_on_top_matched": n_upper_matched,
        "hidden": n_hidden,
        "hidden_found": n_hidden_found,
        "partly_hidden": sum(partly),
        "partly_hidden_recall": sum(partly_found) / max(1, sum(partly)),
        "partly_hidden_from_25": partly_25,
        "partly_hidden_found_from_25": found_25,
        "partly_hidden_recall_from_25": found_25 / max(1, partly_25),
        "partly_hidden_by_visible": {
            f"{lo:.2f}-{hi:.2f}": {"objects": partly[b], "found": partly_found[b]}
            for b, (lo, hi) in enumerate(zip(VISIBLE_BINS, VISIBLE_BINS[1:]))
        },
        "partly_hidden_color_error": partly_colour / max(1, partly_matched),
        "partly_hidden_size_error": partly_size / max(1, partly_matched),
        "centroid_error_m": float(np.mean(errs)) if errs else float("nan"),
        "centroid_error_p99_m": float(np.percentile(errs, 99)) if errs else float("nan"),
        "centroid_error_max_m": float(np.max(errs)) if errs else float("nan"),
        "shape_confusion": {f"{a}->{b}": c for (a, b), c in sorted(shape_conf.items())},
        "color_confusion": {f"{a}->{b}": c for (a, b), c in sorted(colour_conf.items())},
        "size_confusion": {f"{a}->{b}": c for (a, b), c in sorted(size_conf.items())},
        "failures": listed,
    }


def _agreement(seen: Sequence, true: Sequence) -> Callable[[int, int], int]:
    """How many of shape, colour, size and level perceived object i and true object j share."""
    def agree(i: int, j: int) -> int:
        p, t = seen[i], true[j]
        return (p.shape == t.shape) + (p.colour == t.colour) + (p.size == t.size) + (p.level == t.level)
    return agree


def _matrix(conf: dict[str, int], rows: tuple[str, ...], cols: tuple[str, ...]) -> list[str]:
    width = max(len(c) for c in cols + rows) + 1
    lines = ["truth \\ seen".ljust(width + 4) + "".join(c.rjust(width) for c in cols)]
    for r in rows:
        lines.append(r.ljust(width + 4) + "".join(str(conf.get(f"{r}->{c}", 0)).rjust(width) for c in cols))
    return lines


def _stack_targets(r: dict) -> list[str]:
    """Issue 22's stack measures against their targets (none for scenes without stacks)."""
    if not r["objects_on_top"] and not r["partly_hidden"]:
        return []
    in_sight, wrong = r["on_top_in_sight"], r["on_top_wrong_in_sight"]
    ok_top = r["on_top_error_in_sight"] <= TARGET_ON_TOP_IN_SIGHT
    ok_rec = r["partly_hidden_recall_from_25"] >= TARGET_PARTLY_RECALL
    found = r["partly_hidden_found_from_25"]
    return [
        "stack targets (issue 22):",
        f"  on-top error, support at least {MIN_VISIBLE * 100:.0f} % in sight: {r['on_top_error_in_sight'] * 100:.3f} % "
        f"({wrong} of {in_sight}; target <= {TARGET_ON_TOP_IN_SIGHT * 100:.1f} %: {'met' if ok_top else 'NOT met'})",
        f"  partly hidden recall, at least {RECALL_FROM * 100:.0f} % visible: {r['partly_hidden_recall_from_25'] * 100:.3f} % "
        f"({found} of {r['partly_hidden_from_25']}; target >= {TARGET_PARTLY_RECALL * 100:.1f} %: "
        f"{'met' if ok_rec else 'NOT met'})",
        f"  apart: {r['hidden']} objects under {MIN_VISIBLE * 100:.0f} % visible (found {r['hidden_found']}), "
        f"{r['on_unseen']} objects resting on one of them ({r['on_unseen_wrong']} read at the wrong level)",
    ]


def format_report(r: dict) -> str:
    """The evaluation as readable text with both confusion matrices."""
    unknown = [s for s in catalog.SHAPES if s not in r["shapes"]]
    lines = [
        f"{r['scenes']} scenes ({r['stack_share'] * 100:.0f} % with stacks), seed {r['seed']}: {r['objects']} objects, {r['detections']} detections, {r['matched']} matched"
        + ("" if r.get("matching", AGREE) == AGREE else f" ({r['matching']} pairing)"),
        *([f"(the scenes are drawn without {', '.join(unknown)}: "
            + ("the model does not know it)" if r.get("model_shapes") == r["shapes"] else "as --shapes asks)")]
          if unknown else []),
        f"recall      {r['recall'] * 100:.3f} %",
        f"precision   {r['precision'] * 100:.3f} %",
        f"shape error {r['shape_error'] * 100:.3f} %",
        f"colour error {r['color_error'] * 100:.3f} %",
        f"size error  {r['size_error'] * 100:.3f} %",
        f"on-top error {r['on_top_error'] * 100:.3f} % ({r['objects_on_top']} objects on another)",
        f"  without the {r['on_unseen']} objects on one wholly hidden ({r['on_unseen_wrong']} of them wrong): "
        f"{r['on_top_error_in_sight'] * 100:.3f} %",
        f"partly hidden: {r['partly_hidden']} objects, recall {r['partly_hidden_recall'] * 100:.3f} %, "
        f"colour error {r['partly_hidden_color_error'] * 100:.3f} %, size error {r['partly_hidden_size_error'] * 100:.3f} %",
        "  by share visible: " + ", ".join(f"{k}: {v['found']}/{v['objects']}" for k, v in r["partly_hidden_by_visible"].items()),
        f"wholly hidden (under {MIN_VISIBLE * 100:.0f} % visible, not in recall): {r['hidden']}, found {r['hidden_found']}",
        f"centroid error mean {r['centroid_error_m'] * 100:.3f} cm, p99 {r['centroid_error_p99_m'] * 100:.3f} cm, "
        f"max {r['centroid_error_max_m'] * 100:.3f} cm",
        *_stack_targets(r),
        "",
        "shapes:",
        *_matrix(r["shape_confusion"], tuple(r["shapes"]), tuple(r["shapes"]) + ("missed",)),
        "",
        "colours:",
        *_matrix(r["color_confusion"], catalog.COLOURS, catalog.COLOURS + ("missed",)),
        "",
        "sizes:",
        *_matrix(r["size_confusion"], tuple(catalog.SIZES), tuple(catalog.SIZES)),
    ]
    spurious = r["shape_confusion"].get("none->spurious", 0)
    lines.append(f"spurious detections: {spurious}")
    if r["failures"]:
        lines += ["", "first failures:", *("  " + f for f in r["failures"])]
    return "\n".join(lines)


def tune_colour(n: int, seed: int, *, jitter_px: float = 2.0) -> TuneResult:
    """Grid-search w1 on crops of `n` rendered scenes (1-6 objects, near-touching neighbours).

    Each crop is the true box with every edge moved by up to `jitter_px` (a detector's box
    error), so crops hold table and, for close neighbours, another object's pixels. The scenes
    have no stacks: a whole crop of a stacked object holds the one on top at its centre, which
    perception leaves out or reads alone (`colour_of(exclude=, upper=)`), so scoring it here
    measured the crop, not the colour module (with the generator's stacks, from 2026-12-01,
    the grid moved from a 100 % plateau to 94 %, and its pick from 0.5 to 0.3:
    benchmarks/tune_color_split.py splits it)."""
    rng = np.random.default_rng([seed, 0xC01])
    samples = []
    cam = DEFAULT_CAMERA
    for s in generate(n, seed, SceneSpec(1, 6, stack_share=0.0), cam):
        for o in s.objects:
            j = rng.uniform(-jitter_px, jitter_px, size=4)
            u0, v0, u1, v1 = (o.box_px[i] + j[i] for i in range(4))
            box = (max(0.0, u0), max(0.0, v0), min(cam.width, max(u1, u0 + 2)), min(cam.height, max(v1, v0 + 2)))
            samples.append((s.image, box, o.colour))
    return tune_weights(samples)
