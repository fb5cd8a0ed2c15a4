"""Training the shape detector (torch, with `net`, `warmstart` and `distill` the only modules
that import it; `pip install .[train]`). The network is `net.DetectorNet`: six conv layers, a 1x1 head,
per level (on the table, on another object) C shape heatmaps, offset and size at stride 8.

Loss (CenterNet): penalty-reduced focal loss on each layer's heatmaps against Gaussians at
the true centres of that layer's objects (sigma from the object's size), L1 on offset and
`SIZE_WEIGHT` x L1 on size at the centre cells. An object almost wholly hidden under
another (less than `MIN_VISIBLE` of it shows) is no target: a camera cannot see it, and
teaching the network to invent it would teach it to invent objects.
Training samples are random 128 x 128 crops (aligned to the 8 px grid) of the rendered
256 x 256 scenes, flipped and transposed at random: a 4x cheaper step, the same statistics.
Targets are computed once per full image and cropped with it.

The network's classes are the shapes its datasets draw (their metadata's `shapes`; the
catalog's for a dataset written before it said). `TrainConfig.init` (`--init MODEL.onnx`)
starts from an exported model instead of random weights (`warmstart.load_onnx_weights`),
pruned to `TrainConfig.width` (`--width`) where that is thinner than the model.
`TrainConfig.distill` (`--distill MODEL.onnx`) adds `distill_weight` x a term that pulls the
network's maps towards a trained teacher's on the same crops (`distill`).

Everything random draws from `seed` (numpy and torch), and torch runs with a fixed number of
threads, so `aileen perception train DIR --seed 0` (with the same `--init`) reproduces a
model on the same machine type (floating-point summation order can differ across CPUs).
"""

from __future__ import annotations

import json
import math
import time
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import torch
from torch import nn

from aileen.errors import UserError
from aileen.io import atomic_path, atomic_write_text
from aileen.perception.branch import HIDDEN, BranchedNet, branched
from aileen.perception.dataset import load_dataset
from aileen.perception.detector import N_CLASSES, STRIDE, decode
from aileen.perception.distill import distill_loss, load_teacher
from aileen.perception.net import DEFAULT_WIDTH, LAYERS, DetectorNet, layer_maps
from aileen.perception.warmstart import load_onnx_weights, read_export
from aileen.world.catalog import SHAPES

__all__ = ["DetectorNet", "TrainConfig", "make_targets", "train", "export_onnx", "load_onnx_weights", "MIN_VISIBLE"]

LAYER_MAPS = layer_maps(N_CLASSES)  # per layer, for the catalog's shapes: heatmaps, offset x y, size w h
N_OUT = LAYERS * LAYER_MAPS
MIN_VISIBLE = 0.1
# Weight of the L1 box-size loss. A partly hidden object's size is read off its box (a
# quarter of a medium side parts two sizes), so the box must be right to a few pixels.
SIZE_WEIGHT = 0.5


@dataclass(frozen=True)
class TrainConfig:
    steps: int = 12000
    batch: int = 32
    crop: int = 128
    lr: float = 3e-3
    weight_decay: float = 1e-4
    seed: int = 0
    threads: int = 2
    val_images: int = 200
    init: str | None = None  # a trained .onnx to start from (`load_onnx_weights`)
    width: int | None = None  # the body's width (`net.DetectorNet`); None: the init model's, else 48
    # share of crops placed around an object resting on another (where there is one): stacks
    # are the hard case, and a random crop of a stacked scene often misses its stack
    stack_crops: float = 0.0
    distill: str | None = None  # a trained .onnx whose maps the network also learns (`distill`)
    distill_weight: float = 1.0  # the weight of the distillation term beside the label losses
    # train only a branch for the shapes the `init` model lacks, the model frozen (`branch`)
    branch: bool = False


def make_targets(objects: list[dict], height: int, width: int, classes: Sequence[str] = SHAPES) -> np.ndarray:
    """Training targets (2 (C + 4) + 2, h, w) at stride 8 for one image and C shape `classes`:
    per layer (0 on the table, 1 resting on another object) the class heatmaps, offset (x, y)
    and size (w, h) in cells; then per layer the mask of centre cells. An object goes to the
    layer of its level, so the lower object of a stack and the one on it never compete for one
    peak or one cell."""
    h, w = height // STRIDE, width // STRIDE
    nc = len(classes)
    maps = layer_maps(nc)
    n_out = LAYERS * maps
    t = np.zeros((n_out + LAYERS, h, w), dtype=np.float32)
    ys, xs = np.mgrid[0:h, 0:w].astype(np.float32)
    for o in objects:
        if o.get("visible", 1.0) < MIN_VISIBLE:
            continue
        k = int(o.get("level", 0) > 0)
        c = k * maps + classes.index(o["shape"])
        r = k * maps + nc
        cu, cv = o["centre_px"][0] / STRIDE, o["centre_px"][1] / STRIDE
        u0, v0, u1, v1 = o["box_px"]
        bw, bh = (u1 - u0) / STRIDE, (v1 - v0) / STRIDE
        ix, iy = int(math.floor(cu)), int(math.floor(cv))
        sigma = max(0.5, 0.18 * min(bw, bh))
        g = np.exp(-((xs - ix) ** 2 + (ys - iy) ** 2) / (2 * sigma * sigma))
        np.maximum(t[c], g, out=t[c])
        if 0 <= ix < w and 0 <= iy < h:
            t[r : r + 4, iy, ix] = (cu - ix, cv - iy, bw, bh)
            t[n_out + k, iy, ix] = 1.0
            t[c, iy, ix] = 1.0
    return t


def _augment(img: np.ndarray, tgt: np.ndarray, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """Random flips and transpose of an image (H, W, 3) and its targets, consistently."""
    n_out = tgt.shape[0] - LAYERS
    maps = n_out // LAYERS
    regs = [(k * maps + maps - 4, n_out + k) for k in range(LAYERS)]  # (first regression map, mask)
    if rng.random() < 0.5:  # mirror east-west
        img, tgt = img[:, ::-1], tgt[:, :, ::-1].copy()
        for r, m in regs:
            sel = tgt[m] > 0
            tgt[r][sel] = 1.0 - tgt[r][sel]
    if rng.random() < 0.5:  # mirror north-south
        img, tgt = img[::-1], tgt[:, ::-1].copy()
        for r, m in regs:
            sel = tgt[m] > 0
            tgt[r + 1][sel] = 1.0 - tgt[r + 1][sel]
    if rng.random() < 0.5:  # transpose
        img = img.transpose(1, 0, 2)
        tgt = tgt.transpose(0, 2, 1).copy()
        for r, _ in regs:
            tgt[[r, r + 1, r + 2, r + 3]] = tgt[[r + 1, r, r + 3, r + 2]]
    return np.ascontiguousarray(img), np.ascontiguousarray(tgt)


def _centres(tgt: torch.Tensor) -> torch.Tensor:
    """The batch's labelled object centres (its mask maps' sum, at least 1): what every loss
    term is divided by, so that the terms and their weights compare."""
    return tgt[:, -LAYERS:].sum().clamp(min=1.0)


def _loss(pred: torch.Tensor, tgt: torch.Tensor) -> tuple[torch.Tensor, dict[str, float]]:
    n_out = pred.shape[1]
    maps = n_out // LAYERS
    n = _centres(tgt)
    focal = off = size = pred.new_zeros(())
    for k in range(LAYERS):
        b, r = k * maps, k * maps + maps - 4
        p = pred[:, b:r].clamp(1e-4, 1 - 1e-4)
        gt = tgt[:, b:r]
        pos = gt.eq(1.0).float()
        pos_loss = (torch.log(p) * (1 - p) ** 2 * pos).sum()
        neg_loss = (torch.log(1 - p) * p**2 * (1 - gt) ** 4 * (1.0 - pos)).sum()
        mask = tgt[:, n_out + k : n_out + k + 1]
        focal = focal - (pos_loss + neg_loss) / n
        off = off + (torch.abs(pred[:, r : r + 2] - tgt[:, r : r + 2]) * mask).sum() / n
        size = size + (torch.abs(pred[:, r + 2 : r + 4] - tgt[:, r + 2 : r + 4]) * mask).sum() / n
    total = focal + off + SIZE_WEIGHT * size
    return total, {"focal": focal.item(), "off": off.item(), "size": size.item()}


def _validate(model: DetectorNet, images: np.ndarray, labels: list[list[dict]]) -> dict[str, float]:
    """Quick recall / precision / shape accuracy / centre error (px) on full images."""
    model.eval()
    tp = fp = fn_ = wrong = wrong_level = 0
    err = 0.0
    with torch.no_grad():
        for i in range(0, len(images), 16):
            x = torch.from_numpy(np.array(images[i : i + 16])).permute(0, 3, 1, 2).float() / 255.0
            out = model(x).numpy()
            for j, o in enumerate(out):
                dets = decode(o, n_classes=len(model.classes))
                truth = [t for t in labels[i + j] if t.get("visible", 1.0) >= MIN_VISIBLE]
                used = set()
                for d in dets:
                    best, bd = None, 1e9
                    for k, t in enumerate(truth):
                        dd = math.hypot(d[2] - t["centre_px"][0], d[3] - t["centre_px"][1])
                        if k not in used and dd < bd:
                            best, bd = k, dd
                    if best is not None and bd < 8.0:
                        used.add(best)
                        tp += 1
                        err += bd
                        wrong += model.classes[d[0]] != truth[best]["shape"]
                        wrong_level += (d[7] > 0.5) != (truth[best].get("level", 0) > 0)
                    else:
                        fp += 1
                fn_ += len(truth) - len(used)
    return {
        "recall": tp / max(1, tp + fn_),
        "precision": tp / max(1, tp + fp),
        "shape_error": wrong / max(1, tp),
        "centre_err_px": err / max(1, tp),
        "level_error": wrong_level / max(1, tp),
    }


def _train_mode(model: DetectorNet, frozen_bn: bool) -> None:
    """Training mode, with the BatchNorms kept in eval mode when the model started from an
    export (their statistics were folded away; batch statistics would rescale every layer)."""
    model.train()
    if frozen_bn:
        for m in model.modules():
            if isinstance(m, nn.BatchNorm2d):
                m.eval()


def export_onnx(model: DetectorNet, out: str | Path, size: tuple[int, int] = (256, 256)) -> None:
    """Write the model as ONNX (opset 13, fixed input 1x3xHxW float, RGB / 255)."""
    model.eval()
    out = Path(out)
    dummy = torch.zeros(1, 3, size[0], size[1])
    # The TorchScript exporter on purpose (DESIGN.md section 6): OpenCV's dnn module reads its
    # output; torch warns that it is the legacy path, which we know.
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", category=DeprecationWarning, module=r"torch\.onnx.*")
        warnings.filterwarnings("ignore", category=DeprecationWarning, message=".*legacy TorchScript-based ONNX export")
        with atomic_path(out) as tmp:
            torch.onnx.export(model, dummy, str(tmp), dynamo=False, opset_version=13, input_names=["image"],
                              output_names=["maps"])


def _crop_origin(uppers: list[tuple[int, int]], grid: tuple[int, int], cs: int, stack_crops: float,
                 rng: np.random.Generator) -> tuple[int, int]:
    """A crop's top-left cell (x, y) on a grid of (w, h) cells: uniform, or, with chance
    `stack_crops` where the image has objects resting on others, uniform among the crops
    that hold one of them (drawn at random) two cells or more inside the crop's edge."""
    w, h = grid
    if uppers and stack_crops > 0.0 and rng.random() < stack_crops:
        cx, cy = uppers[int(rng.integers(len(uppers)))]
        x0, x1 = max(0, cx - cs + 3), min(w - cs, cx - 2)
        y0, y1 = max(0, cy - cs + 3), min(h - cs, cy - 2)
        if x0 <= x1 and y0 <= y1:
            return int(rng.integers(x0, x1 + 1)), int(rng.integers(y0, y1 + 1))
    return int(rng.integers(0, w - cs + 1)), int(rng.integers(0, h - cs + 1))


def _load_all(data_dirs: Sequence[str | Path]) -> tuple[list[np.ndarray], list[list[dict]], list[dict]]:
    """The dataset folders' image memmaps, their labels (one list, in folder order) and
    metadata, checked to share one image size."""
    parts, labels, metas = [], [], []
    for d in data_dirs:
        images, lab, meta = load_dataset(d)
        if parts and images.shape[1:] != parts[0].shape[1:]:
            raise UserError(f"{d}: images of {images.shape[2]}x{images.shape[1]}, but {data_dirs[0]} has "
                            f"{parts[0].shape[2]}x{parts[0].shape[1]}; one training run takes one image size")
        parts.append(images)
        labels += lab
        metas.append(meta)
    return parts, labels, metas


def _data_classes(metas: list[dict]) -> tuple[str, ...]:
    """The shapes the datasets draw (their metadata's `shapes`; all the catalog's where a
    dataset does not say), in the catalog's order: the classes the network learns."""
    drawn = {s for m in metas for s in m.get("shapes", SHAPES)}
    unknown = drawn - set(SHAPES)
    if unknown:
        raise UserError(f"the datasets draw shapes the catalog does not have: {', '.join(sorted(unknown))}")
    return tuple(s for s in SHAPES if s in drawn)


def train(data_dir: str | Path | Sequence[str | Path], out: str | Path, config: TrainConfig = TrainConfig(), *,
          log=print) -> dict:
    """Train on one or more dataset folders (sampled as one set), export `out` (.onnx) and its
    metadata `out.json`; returns the metadata (including the validation figures on the last
    `val_images` images of the last folder)."""
    dirs = [data_dir] if isinstance(data_dir, (str, Path)) else list(data_dir)
    parts, labels, metas = _load_all(dirs)
    # image k of the joined set: in the last folder f with starts[f] <= k, row k - starts[f]
    starts = np.cumsum([0] + [p.shape[0] for p in parts])
    n = int(starts[-1])
    if n < 2:
        raise UserError(f"{dirs[0]}: a dataset needs at least 2 images, has {n}")
    H, W = parts[0].shape[1:3]
    if H % STRIDE or W % STRIDE or config.crop % STRIDE or config.crop > min(H, W):
        raise UserError(f"{dirs[0]}: images of {W}x{H} do not fit crops of {config.crop} at stride {STRIDE}")
    n_val = min(config.val_images, max(1, parts[-1].shape[0] // 10))
    n_train = n - n_val

    def image(k: int) -> np.ndarray:
        f = int(np.searchsorted(starts, k, side="right")) - 1
        return parts[f][k - starts[f]]
    torch.manual_seed(config.seed)
    torch.set_num_threads(config.threads)
    rng = np.random.default_rng([config.seed, 0x7A1])
    classes = _data_classes(metas)
    init_width = read_export(config.init).width if config.init is not None else None
    width = config.width or init_width or DEFAULT_WIDTH
    frozen = config.init is not None
    if config.branch:
        if config.width is not None or config.distill is not None:
            raise UserError("--branch trains a branch beside a frozen model: it takes neither --width nor --distill")
        model: DetectorNet | BranchedNet = branched(config.init, classes)
        classes = model.classes
        log(f"a branch for {', '.join(model.new)} on {config.init} (frozen; it knows {', '.join(model.base.classes)})")
    else:
        model = DetectorNet(width, classes)
        if frozen:
            load_onnx_weights(model, config.init)
            log(f"starting from {config.init}" + (f", pruned from width {init_width} to {width}" if width != init_width else ""))
    log(f"targets for {n} images ...")
    targets = np.stack([make_targets(labels[i], H, W, classes) for i in range(n)])
    uppers = [[(int(o["centre_px"][0] // STRIDE), int(o["centre_px"][1] // STRIDE)) for o in lab if o.get("level", 0) > 0]
              for lab in labels]
    teacher = load_teacher(config.distill, classes) if config.distill is not None else None
    if teacher is not None:
        log(f"distilling from {config.distill} (width {teacher.width}), weight {config.distill_weight}")
    opt = torch.optim.AdamW([p for p in model.parameters() if p.requires_grad], lr=config.lr,
                            weight_decay=config.weight_decay)
    sched = torch.optim.lr_scheduler.OneCycleLR(opt, max_lr=config.lr, total_steps=config.steps, pct_start=0.1)
    cs = config.crop // STRIDE
    t0 = time.time()
    _train_mode(model, frozen)
    running: dict[str, float] = {}
    for step in range(1, config.steps + 1):
        idx = rng.integers(0, n_train, size=config.batch)
        xb = np.empty((config.batch, config.crop, config.crop, 3), dtype=np.uint8)
        yb = np.empty((config.batch, targets.shape[1], cs, cs), dtype=np.float32)
        for b, i in enumerate(idx):
            gx, gy = _crop_origin(uppers[i], (W // STRIDE, H // STRIDE), cs, config.stack_crops, rng)
            img = image(int(i))[gy * STRIDE : gy * STRIDE + config.crop, gx * STRIDE : gx * STRIDE + config.crop]
            tgt = targets[i, :, gy : gy + cs, gx : gx + cs]
            xb[b], yb[b] = _augment(np.asarray(img), tgt, rng)
        x = torch.from_numpy(xb).permute(0, 3, 1, 2).float() / 255.0
        y = torch.from_numpy(yb)
        if isinstance(model, BranchedNet):
            pred, boxes = model.parts(x)
            loss, terms = _loss(pred, y)
            extra = model.new_box_loss(boxes, y, _centres(y), SIZE_WEIGHT)
            loss = loss + extra
            terms["new_box"] = extra.item()
        elif teacher is None:
            loss, terms = _loss(model(x), y)
        else:
            raw = model.logits(x)
            loss, terms = _loss(model.activate(raw), y)
            with torch.no_grad():
                t_raw = teacher.logits(x)
            d, d_terms = distill_loss(raw, t_raw, len(classes), _centres(y), SIZE_WEIGHT)
            loss = loss + config.distill_weight * d
            terms |= d_terms
        opt.zero_grad(set_to_none=True)
        loss.backward()
        opt.step()
        sched.step()
        for k, v in terms.items():
            running[k] = 0.98 * running.get(k, v) + 0.02 * v
        if step % 500 == 0 or step in (100, config.steps):
            log(f"step {step}/{config.steps} " + " ".join(f"{k} {v:.4g}" for k, v in running.items())
                + f" ({time.time() - t0:.0f} s)")
    wall = time.time() - t0
    val = _validate(model, parts[-1][parts[-1].shape[0] - n_val :], labels[n_train:])
    model.eval()
    log("validation: " + " ".join(f"{k} {v:.4f}" for k, v in val.items()))
    export_onnx(model, out, (H, W))
    info = {
        "format": "aileen-detector-1",
        "input_size": [H, W],
        "input": "RGB uint8 / 255, NCHW",
        "stride": STRIDE,
        "classes": list(classes),
        "outputs": f"per level (0 on the table, 1 resting on another object): {len(classes)} sigmoid centre heatmaps, "
                   "offset x y (cells), size w h (cells)",
        "layers": LAYERS,
        "threshold": 0.3,
        "width": width,
        "parameters": int(sum(p.numel() for p in model.parameters())),
        **({"branch": {"base": config.init, "base_classes": list(model.base.classes), "new": list(model.new),
                       "hidden": HIDDEN,
                       "parameters": int(sum(p.numel() for p in model.branch.parameters()))}}
           if isinstance(model, BranchedNet) else {}),
        "training": {
            "seed": config.seed,
            "steps": config.steps,
            "batch": config.batch,
            "crop": config.crop,
            "lr": config.lr,
            "threads": config.threads,
            "size_weight": SIZE_WEIGHT,
            "init": config.init,
            "stack_crops": config.stack_crops,
            "distill": config.distill,
            "distill_weight": config.distill_weight if config.distill is not None else None,
            "branch": config.branch,
            "data_images": n,
            "data_seed": metas[0].get("seed") if len(metas) == 1 else [m.get("seed") for m in metas],
            "wall_s": round(wall, 1),
            "torch": torch.__version__,
        },
        "validation": {k: round(v, 5) for k, v in val.items()},
    }
    mp = Path(out).with_suffix(".json")
    atomic_write_text(mp, json.dumps(info, indent=2) + "\n")
    return info
