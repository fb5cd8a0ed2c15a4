"""Training the shape detector (the only module that imports torch; `pip install .[train]`).

Network: a plain CNN, six 3x3 conv-BN-ReLU layers (16, 24, 32 channels at strides 2, 4, 8,
then 48, 48 (dilated 2), 48 at stride 8; receptive field 79 px, three times a medium
object) and a 1x1 head with 9 outputs per stride-8 cell: 4 shape-centre heatmaps (sigmoid),
the centre's sub-cell offset (x, y), the box size (w, h) in cells, and the level score
(sigmoid): whether the object centred there rests on another one. About 67k parameters,
85 MMAC for a 256 x 256 image; OpenCV's dnn runs it in about 3 ms on one core.

Loss (CenterNet): penalty-reduced focal loss on the heatmaps against Gaussians at the true
centres (sigma from the object's size), L1 on offset and size at the centre cells, binary
cross-entropy on the level score at the centre cells. An object almost wholly hidden under
another (less than `MIN_VISIBLE` of it shows) is no target: a camera cannot see it, and
teaching the network to invent it would teach it to invent objects.
Training samples are random 128 x 128 crops (aligned to the 8 px grid) of the rendered
256 x 256 scenes, flipped and transposed at random: a 4x cheaper step, the same statistics.
Targets are computed once per full image and cropped with it.

Everything random draws from `seed` (numpy and torch), and torch runs with a fixed number of
threads, so `aileen perception train DIR --seed 0` reproduces the shipped model on the same
machine type (floating-point summation order can differ across CPUs).
"""

from __future__ import annotations

import json
import math
import time
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import torch
from torch import nn

from aileen.errors import UserError
from aileen.io import atomic_path, atomic_write_text
from aileen.perception.dataset import load_dataset
from aileen.perception.detector import N_CLASSES, STRIDE, decode
from aileen.world.catalog import SHAPES

__all__ = ["DetectorNet", "TrainConfig", "make_targets", "train", "export_onnx", "MIN_VISIBLE"]

N_OUT = N_CLASSES + 5  # heatmaps, offset x y, size w h, level
MIN_VISIBLE = 0.1


def _cbr(i: int, o: int, stride: int = 1, dilation: int = 1) -> list[nn.Module]:
    return [nn.Conv2d(i, o, 3, stride, dilation, dilation=dilation, bias=False), nn.BatchNorm2d(o), nn.ReLU(inplace=True)]


class DetectorNet(nn.Module):
    """Centre-heatmap detector; forward returns (B, 8, H/8, W/8) with sigmoid heatmaps."""

    def __init__(self, width: int = 48) -> None:
        super().__init__()
        self.body = nn.Sequential(
            *_cbr(3, 16, 2),
            *_cbr(16, 24, 2),
            *_cbr(24, 32, 2),
            *_cbr(32, width),
            *_cbr(width, width, 1, 2),
            *_cbr(width, width),
        )
        self.head = nn.Conv2d(width, N_OUT, 1)
        with torch.no_grad():  # start the heatmaps near the background rate (focal-loss prior)
            self.head.bias[:N_CLASSES].fill_(-4.0)
            self.head.bias[N_CLASSES + 2 :].fill_(3.0)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        y = self.head(self.body(x))
        o = N_CLASSES
        return torch.cat([torch.sigmoid(y[:, :o]), y[:, o : o + 4], torch.sigmoid(y[:, o + 4 :])], dim=1)


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


def make_targets(objects: list[dict], height: int, width: int) -> np.ndarray:
    """Training targets (4 + 4 + 1 + 1, h, w) at stride 8 for one image: class heatmaps,
    offset (x, y) and size (w, h) in cells, the mask of centre cells, and the level (1 where
    the object centred there rests on another)."""
    h, w = height // STRIDE, width // STRIDE
    t = np.zeros((N_CLASSES + 6, h, w), dtype=np.float32)
    ys, xs = np.mgrid[0:h, 0:w].astype(np.float32)
    for o in objects:
        if o.get("visible", 1.0) < MIN_VISIBLE:
            continue
        c = SHAPES.index(o["shape"])
        cu, cv = o["centre_px"][0] / STRIDE, o["centre_px"][1] / STRIDE
        u0, v0, u1, v1 = o["box_px"]
        bw, bh = (u1 - u0) / STRIDE, (v1 - v0) / STRIDE
        ix, iy = int(math.floor(cu)), int(math.floor(cv))
        sigma = max(0.5, 0.18 * min(bw, bh))
        g = np.exp(-((xs - ix) ** 2 + (ys - iy) ** 2) / (2 * sigma * sigma))
        np.maximum(t[c], g, out=t[c])
        if 0 <= ix < w and 0 <= iy < h:
            t[N_CLASSES : N_CLASSES + 4, iy, ix] = (cu - ix, cv - iy, bw, bh)
            t[N_CLASSES + 4, iy, ix] = 1.0
            t[N_CLASSES + 5, iy, ix] = float(o.get("level", 0) > 0)
            t[c, iy, ix] = 1.0
    return t


def _augment(img: np.ndarray, tgt: np.ndarray, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """Random flips and transpose of an image (H, W, 3) and its targets, consistently."""
    o = N_CLASSES
    if rng.random() < 0.5:  # mirror east-west
        img, tgt = img[:, ::-1], tgt[:, :, ::-1].copy()
        m = tgt[o + 4] > 0
        tgt[o][m] = 1.0 - tgt[o][m]
    if rng.random() < 0.5:  # mirror north-south
        img, tgt = img[::-1], tgt[:, ::-1].copy()
        m = tgt[o + 4] > 0
        tgt[o + 1][m] = 1.0 - tgt[o + 1][m]
    if rng.random() < 0.5:  # transpose
        img = img.transpose(1, 0, 2)
        tgt = tgt.transpose(0, 2, 1).copy()
        tgt[[o, o + 1, o + 2, o + 3]] = tgt[[o + 1, o, o + 3, o + 2]]
    return np.ascontiguousarray(img), np.ascontiguousarray(tgt)


def _loss(pred: torch.Tensor, tgt: torch.Tensor) -> tuple[torch.Tensor, dict[str, float]]:
    o = N_CLASSES
    p = pred[:, :o].clamp(1e-4, 1 - 1e-4)
    gt = tgt[:, :o]
    pos = gt.eq(1.0).float()
    neg = 1.0 - pos
    pos_loss = (torch.log(p) * (1 - p) ** 2 * pos).sum()
    neg_loss = (torch.log(1 - p) * p**2 * (1 - gt) ** 4 * neg).sum()
    mask = tgt[:, o + 4 : o + 5]
    n = mask.sum().clamp(min=1.0)
    focal = -(pos_loss + neg_loss) / n
    off = (torch.abs(pred[:, o : o + 2] - tgt[:, o : o + 2]) * mask).sum() / n
    size = (torch.abs(pred[:, o + 2 : o + 4] - tgt[:, o + 2 : o + 4]) * mask).sum() / n
    lv = pred[:, o + 4 : o + 5].clamp(1e-4, 1 - 1e-4)
    lt = tgt[:, o + 5 : o + 6]
    level = (-(lt * torch.log(lv) + (1 - lt) * torch.log(1 - lv)) * mask).sum() / n
    total = focal + off + 0.2 * size + level
    return total, {"focal": focal.item(), "off": off.item(), "size": size.item(), "level": level.item()}


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
                dets = decode(o)
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
                        wrong += SHAPES[d[0]] != truth[best]["shape"]
                        wrong_level += (d[7] > 0.5) != (truth[best].get("level", 0) > 0)
                    else:
                        fp += 1
                fn_ += len(truth) - len(used)
    model.train()
    return {
        "recall": tp / max(1, tp + fn_),
        "precision": tp / max(1, tp + fp),
        "shape_error": wrong / max(1, tp),
        "centre_err_px": err / max(1, tp),
        "level_error": wrong_level / max(1, tp),
    }


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


def train(data_dir: str | Path, out: str | Path, config: TrainConfig = TrainConfig(), *, log=print) -> dict:
    """Train on a dataset folder, export `out` (.onnx) and its metadata `out.json`; returns
    the metadata (including the validation figures on the last `val_images` images)."""
    images, labels, meta = load_dataset(data_dir)
    n = images.shape[0]
    if n < 2:
        raise UserError(f"{data_dir}: a dataset needs at least 2 images, has {n}")
    H, W = images.shape[1:3]
    if H % STRIDE or W % STRIDE or config.crop % STRIDE or config.crop > min(H, W):
        raise UserError(f"{data_dir}: images of {W}x{H} do not fit crops of {config.crop} at stride {STRIDE}")
    n_val = min(config.val_images, max(1, n // 10))
    n_train = n - n_val
    torch.manual_seed(config.seed)
    torch.set_num_threads(config.threads)
    rng = np.random.default_rng([config.seed, 0x7A1])
    log(f"targets for {n} images ...")
    targets = np.stack([make_targets(labels[i], H, W) for i in range(n)])
    model = DetectorNet()
    opt = torch.optim.AdamW(model.parameters(), lr=config.lr, weight_decay=config.weight_decay)
    sched = torch.optim.lr_scheduler.OneCycleLR(opt, max_lr=config.lr, total_steps=config.steps, pct_start=0.1)
    cs = config.crop // STRIDE
    t0 = time.time()
    model.train()
    running: dict[str, float] = {}
    for step in range(1, config.steps + 1):
        idx = rng.integers(0, n_train, size=config.batch)
        xb = np.empty((config.batch, config.crop, config.crop, 3), dtype=np.uint8)
        yb = np.empty((config.batch, targets.shape[1], cs, cs), dtype=np.float32)
        for b, i in enumerate(idx):
            gy = int(rng.integers(0, H // STRIDE - cs + 1))
            gx = int(rng.integers(0, W // STRIDE - cs + 1))
            img = images[i, gy * STRIDE : gy * STRIDE + config.crop, gx * STRIDE : gx * STRIDE + config.crop]
            tgt = targets[i, :, gy : gy + cs, gx : gx + cs]
            xb[b], yb[b] = _augment(np.asarray(img), tgt, rng)
        x = torch.from_numpy(xb).permute(0, 3, 1, 2).float() / 255.0
        loss, parts = _loss(model(x), torch.from_numpy(yb))
        opt.zero_grad(set_to_none=True)
        loss.backward()
        opt.step()
        sched.step()
        for k, v in parts.items():
            running[k] = 0.98 * running.get(k, v) + 0.02 * v
        if step % 500 == 0 or step == config.steps:
            log(f"step {step}/{config.steps} " + " ".join(f"{k} {v:.4f}" for k, v in running.items())
                + f" ({time.time() - t0:.0f} s)")
    wall = time.time() - t0
    val = _validate(model, images[n_train:], labels[n_train:])
    log("validation: " + " ".join(f"{k} {v:.4f}" for k, v in val.items()))
    export_onnx(model, out, (H, W))
    info = {
        "format": "aileen-detector-1",
        "input_size": [H, W],
        "input": "RGB uint8 / 255, NCHW",
        "stride": STRIDE,
        "classes": list(SHAPES),
        "outputs": "4 sigmoid centre heatmaps, offset x y (cells), size w h (cells), sigmoid level score",
        "threshold": 0.3,
        "parameters": int(sum(p.numel() for p in model.parameters())),
        "training": {
            "seed": config.seed,
            "steps": config.steps,
            "batch": config.batch,
            "crop": config.crop,
            "lr": config.lr,
            "threads": config.threads,
            "data_images": n,
            "data_seed": meta.get("seed"),
            "wall_s": round(wall, 1),
            "torch": torch.__version__,
        },
        "validation": {k: round(v, 5) for k, v in val.items()},
    }
    mp = Path(out).with_suffix(".json")
    atomic_write_text(mp, json.dumps(info, indent=2) + "\n")
    return info
