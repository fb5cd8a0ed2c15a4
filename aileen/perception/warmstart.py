"""Starting a network from an exported detector (`aileen perception train --init MODEL.onnx`),
optionally thinner than it (`--width`): fine-tuning keeps what a model already does well, and
a pruned model starts from the filters that carried most of it.

ONNX export folds each BatchNorm into its conv, so the convs take the folded weights and
biases and the BatchNorms become identities (mean 0, variance 1 - eps, scale 1, shift 0), to
be kept frozen while training (`train._train_mode`).

Pruning (`prune`): in each of the three `width`-wide convs, the output channels whose
(folded) filters have the largest L1 norm are kept, the rest dropped, and the next layer's
input channels (the head's for the last) are sliced to match, one layer after the other (a
filter's norm is taken over the input channels that are left). Kept channels keep their
order, so pruning to the model's own width gives the model back unchanged.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import torch
from torch import nn

from aileen.errors import UserError
from aileen.perception.detector import shape_classes
from aileen.perception.net import LAYERS, WIDE_CONVS, DetectorNet, layer_maps
from aileen.world.catalog import SHAPES

__all__ = ["Export", "read_export", "prune", "load_onnx_weights"]

Conv = tuple[np.ndarray, np.ndarray | None]  # (weight (O, I, kh, kw), bias (O,) or None)


@dataclass(frozen=True)
class Export:
    """An exported detector's convolutions (BatchNorm folded; body, then the head) and the
    shape classes of its maps."""

    convs: list[Conv]
    classes: list[str]

    @property
    def width(self) -> int:
        """The body's width: the head's input channels."""
        return int(self.convs[-1][0].shape[1])


def read_export(path: str | Path) -> Export:
    """The convs of an exported model and its classes (`_classes`), or a UserError."""
    import onnx
    from onnx import numpy_helper

    try:
        g = onnx.load(str(path)).graph
    except Exception as exc:  # noqa: BLE001 - onnx raises several kinds
        raise UserError(f"{path}: cannot read the model to start from ({exc})") from None
    init = {i.name: numpy_helper.to_array(i) for i in g.initializer}
    convs = [(np.array(init[n.input[1]]), np.array(init[n.input[2]]) if len(n.input) > 2 else None)
             for n in g.node if n.op_type == "Conv"]
    if not convs:
        raise UserError(f"{path}: no convolutions; start from a model `aileen perception train` wrote")
    return Export(convs, _classes(path, convs[-1][0].shape[0]))


def prune(convs: list[Conv], width: int) -> list[Conv]:
    """The convs with each of the last `WIDE_CONVS` body convs cut to its `width` output
    channels of largest filter L1 norm (ties: the earlier channel), the next conv's input
    channels sliced to match; `convs` ends with the head."""
    wide = range(len(convs) - 1 - WIDE_CONVS, len(convs) - 1)
    if width < 1 or any(convs[i][0].shape[0] < width for i in wide):
        raise UserError(f"cannot prune to width {width}: the model is {convs[-1][0].shape[1]} wide "
                        "(a network can be made thinner than its start model, not wider)")
    out: list[Conv] = []
    keep: np.ndarray | None = None
    for i, (w, b) in enumerate(convs):
        if keep is not None:
            w = w[:, keep]
        keep = None
        if i in wide:
            norms = np.abs(w).reshape(w.shape[0], -1).sum(axis=1)
            keep = np.sort(np.argsort(-norms, kind="stable")[:width])
            w, b = w[keep], (b[keep] if b is not None else None)
        out.append((w, b))
    return out


def load_onnx_weights(model: DetectorNet, path: str | Path) -> None:
    """Start `model` from an exported detector, pruned to the model's width where it is wider
    (`prune`). A model with one set of maps (no layers) gives its heatmap, offset and size
    maps to both layers; the heatmaps of objects on others start blank, at the background
    rate. Each of `model.classes` the export knows (its metadata's `classes`) takes that
    shape's heatmap; a shape it does not know starts blank, every other channel from it."""
    exp = read_export(path)
    convs = prune(exp.convs, model.width) if exp.width != model.width else exp.convs
    body = [m for m in model.body if isinstance(m, nn.Conv2d)]
    bns = [m for m in model.body if isinstance(m, nn.BatchNorm2d)]
    if len(convs) != len(body) + 1 or any(tuple(w.shape) != tuple(c.weight.shape) for (w, _), c in zip(convs, body)):
        raise UserError(f"{path}: its layers do not match this network; start from a model `aileen perception train` wrote")
    hw, hb = convs[-1]
    old = exp.classes
    n_old = len(old)
    maps = n_old + 4  # the exported model's maps per level
    if hw.shape[0] == 2 * maps:
        levels = (0, 1)
    elif hw.shape[0] in (maps, maps + 1):
        levels = (0, None)  # one set of maps: given to both layers, the upper heatmaps blank
    else:
        raise UserError(f"{path}: {hw.shape[0]} output maps, expected {2 * maps}, {maps} or {maps + 1}")
    nc, new_maps = len(model.classes), layer_maps(len(model.classes))
    with torch.no_grad():
        for (w, b), conv, bn in zip(convs, body, bns):
            conv.weight.copy_(torch.from_numpy(w))
            bn.weight.fill_(1.0)
            bn.bias.copy_(torch.from_numpy(b) if b is not None else torch.zeros_like(bn.bias))
            bn.running_mean.zero_()
            bn.running_var.fill_(1.0 - bn.eps)
        hw_t, hb_t = torch.from_numpy(hw), torch.from_numpy(hb)
        for k in range(LAYERS):
            src = levels[k] if k < len(levels) else None
            base = 0 if src is None else src * maps
            for j in range(4):  # offset x y, size w h: the copy (for the upper layer too)
                model.head.weight[k * new_maps + nc + j] = hw_t[base + n_old + j]
                model.head.bias[k * new_maps + nc + j] = hb_t[base + n_old + j]
            for c, shape in enumerate(model.classes):
                if src is not None and shape in old:
                    model.head.weight[k * new_maps + c] = hw_t[base + old.index(shape)]
                    model.head.bias[k * new_maps + c] = hb_t[base + old.index(shape)]
                else:
                    # a shape the model did not know, or the upper layer of a model without
                    # one (a copy fires on every object and takes long to unlearn): blank,
                    # at the background rate
                    model.head.weight[k * new_maps + c] = 0.0
                    model.head.bias[k * new_maps + c] = -4.0


def _classes(path: str | Path, n_maps: int) -> list[str]:
    """The shape classes of an exported model, in its map order: its metadata's (`OUT.json`
    beside it), else the catalog's when the map count fits them, else the catalog's first
    ones that fit a layered model (a model trained before a shape joined the catalog)."""
    meta_path = Path(path).with_suffix(".json")
    if meta_path.is_file():
        try:
            meta = json.loads(meta_path.read_text())
            classes = meta.get("classes")
        except (OSError, ValueError, AttributeError) as exc:
            raise UserError(f"{meta_path}: unreadable model metadata ({exc})") from None
        if isinstance(meta.get("branch"), dict):
            raise UserError(f"{path}: a model with a branch (`--branch`) cannot start a training run; start from its "
                            f"base, {meta['branch'].get('base')}")
        if not shape_classes(classes):
            raise UserError(f"{meta_path}: \"classes\" must list distinct shapes of {', '.join(SHAPES)}")
        return list(classes)
    maps = layer_maps(len(SHAPES))
    if n_maps in (LAYERS * maps, maps, maps + 1):
        return list(SHAPES)
    if n_maps % 2 == 0 and 0 < n_maps // 2 - 4 <= len(SHAPES):
        return list(SHAPES[: n_maps // 2 - 4])
    raise UserError(f"{path}: {n_maps} output maps, expected {LAYERS * maps}, {maps} or {maps + 1}")
