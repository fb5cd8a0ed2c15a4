"""A branch that teaches a trained detector new shapes and leaves what it knew as it was
(`aileen perception train --init MODEL.onnx --branch`; torch, `pip install .[train]`).

Why: the shipped detector learned stacks over 36,000 scenes and a chain of runs. Fine-tuning
all of it for a fifth shape (the capsule) on a CPU kept the new shape but lost part of the
upper layer every time (three runs, docs/perception.md): the network's weights are shared
by every shape, and a few thousand steps re-learn the new one at the others' cost. A branch
cannot do that. The exported network runs unchanged, frozen; a small branch reads its body's
features and its head's maps and adds, per level (on the table, on another object):

- a heatmap, offset and size for each new shape (the base's offset and size maps take the
  branch's at the cells where a new shape's heat beats every gated old one: the cell's own
  object is then the new shape, and its box is the branch's to tell);
- a *cover* map: where a new shape lies, the base, which never saw one, reads parts of it as
  the shapes it knows (a capsule as two spheres, or a cylinder and a cone); the branch learns
  to gate the base's heatmaps there, old heat x (1 - cover).

Nothing about the new shape is written here: the branch learns it, and the cover, from the
same labels and the same loss as the whole network (the gated old heatmaps are trained
against the old shapes' targets, so the cover rises only where the base's heat is wrong and
falls on the objects it reads right). Where the cover is low and no new shape's heat wins,
the output is the base's; the four-shape figures are measured to show how close
(docs/perception.md, "The capsule on a branch").

The output has the layout of any exported detector (per level C heatmaps in the catalog's
order, offset x y, size w h), so decoding and every reader of the model stay as they are.
A branched export cannot start another training run (`warmstart` refuses it): start from its
base, named in its metadata.
"""

from __future__ import annotations

from collections.abc import Sequence

import torch
from torch import nn

from aileen.errors import UserError
from aileen.perception.net import LAYERS, DetectorNet, layer_maps
from aileen.perception.warmstart import load_onnx_weights, read_export
from aileen.world.catalog import SHAPES

__all__ = ["BranchedNet", "HIDDEN", "COVER_BIAS", "branched"]

HIDDEN = 32  # the branch's channels
# The branch also reads the body's first stride-8 layer (its third conv, 32 channels, the
# output of `base.body[EARLY]`): its last layers were trained to tell four shapes apart, and
# a small sphere resting on a box and a capsule resting on one were alike there (without it,
# `br2` in docs/perception.md: 20 spurious detections on 1,000 stacked four-shape scenes
# against the base's 7; on 400 of them 22 capsules that were not there, nearly all a small
# sphere or cone resting on a box; with it, 14).
EARLY = 8
EARLY_CHANNELS = 32
COVER_BIAS = -6.0  # the cover starts closed: the base's output as it was (sigmoid: 0.25 %)
HEAT_BIAS = -4.0  # a new shape's heatmap starts at the background rate, as `net.DetectorNet`'s
SIZE_BIAS = 3.0  # and its box about a medium object's, in cells


class BranchedNet(nn.Module):
    """A frozen `base` network and a branch for the shapes `new` (catalog names it lacks).
    `classes` are the base's and the new ones, in the catalog's order; forward returns the
    maps of a detector of those classes."""

    def __init__(self, base: DetectorNet, new: Sequence[str], hidden: int = HIDDEN) -> None:
        super().__init__()
        if not new or any(s in base.classes for s in new):
            raise ValueError(f"a branch adds shapes the base lacks; base {base.classes}, new {tuple(new)}")
        self.base = base
        for p in base.parameters():
            p.requires_grad_(False)
        self.new = tuple(s for s in SHAPES if s in new)
        self.classes = tuple(s for s in SHAPES if s in base.classes or s in self.new)
        self.width = base.width
        self.hidden = int(hidden)
        n_old, n_new = len(base.classes), len(self.new)
        self.per_level = n_new + 5  # new heatmaps, offset x y, size w h, cover
        self.branch = nn.Sequential(
            # 1x1 first: the base's features already see 79 px around a cell, a capsule's
            # whole length; one dilated 3x3 adds the neighbours' maps (about 13 MMAC in all
            # on a 256 x 256 image, a seventh of the base's 85)
            nn.Conv2d(base.width + EARLY_CHANNELS + LAYERS * layer_maps(n_old), hidden, 1),
            nn.ReLU(inplace=True),
            nn.Conv2d(hidden, hidden, 3, padding=2, dilation=2),
            nn.ReLU(inplace=True),
            nn.Conv2d(hidden, LAYERS * self.per_level, 1),
        )
        with torch.no_grad():
            last = self.branch[-1]
            for k in range(LAYERS):
                b = k * self.per_level
                last.bias[b : b + n_new].fill_(HEAT_BIAS)
                last.bias[b + n_new : b + n_new + 2].fill_(0.5)
                last.bias[b + n_new + 2 : b + n_new + 4].fill_(SIZE_BIAS)
                last.bias[b + n_new + 4].fill_(COVER_BIAS)
        # merged heatmaps (old ones, then new ones) -> the catalog's order
        joined = list(base.classes) + list(self.new)
        self.register_buffer("order", torch.tensor([joined.index(s) for s in self.classes]), persistent=False)

    def train(self, mode: bool = True) -> BranchedNet:
        """The base stays in eval mode: it is frozen, BatchNorm statistics included."""
        super().train(mode)
        self.base.eval()
        return self

    def parts(self, x: torch.Tensor) -> tuple[torch.Tensor, list[torch.Tensor]]:
        """The merged maps, and per level the branch's own offset and size maps (4 channels),
        which training also fits at the new shapes' centres (`new_box_loss`): the merged
        maps give them to a new shape's centre only once its heat beats the old ones'."""
        with torch.no_grad():
            early = self.base.body[: EARLY + 1](x)
            feats = self.base.body[EARLY + 1 :](early)
            old = self.base.head(feats)
        br = self.branch(torch.cat([feats, early, old], dim=1))
        n_old, n_new = len(self.base.classes), len(self.new)
        m_old = layer_maps(n_old)
        out, boxes = [], []
        for k in range(LAYERS):
            o = old[:, k * m_old : (k + 1) * m_old]
            q = br[:, k * self.per_level : (k + 1) * self.per_level]
            gated = torch.sigmoid(o[:, :n_old]) * (1.0 - torch.sigmoid(q[:, n_new + 4 : n_new + 5]))
            fresh = torch.sigmoid(q[:, :n_new])
            mine = (fresh.amax(dim=1, keepdim=True) > gated.amax(dim=1, keepdim=True)).float()
            box = q[:, n_new : n_new + 4]
            heat = torch.cat([gated, fresh], dim=1).index_select(1, self.order)
            out += [heat, o[:, n_old:] * (1.0 - mine) + box * mine]
            boxes.append(box)
        return torch.cat(out, dim=1), boxes

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        return self.parts(x)[0]

    def new_box_loss(self, boxes: list[torch.Tensor], tgt: torch.Tensor, n: torch.Tensor,
                     size_weight: float) -> torch.Tensor:
        """L1 of the branch's own offset and size at the new shapes' labelled centres (targets
        as `train.make_targets` lays them out for `self.classes`), over `n` centres."""
        nc, maps = len(self.classes), layer_maps(len(self.classes))
        idx = [self.classes.index(s) for s in self.new]
        loss = tgt.new_zeros(())
        for k, box in enumerate(boxes):
            b = k * maps
            centre = tgt[:, [b + i for i in idx]].eq(1.0).any(dim=1, keepdim=True).float()
            reg = tgt[:, b + nc : b + nc + 4]
            err = torch.abs(box - reg) * centre
            loss = loss + (err[:, :2].sum() + size_weight * err[:, 2:].sum()) / n
        return loss


def branched(init: str | None, classes: Sequence[str]) -> BranchedNet:
    """The exported model `init`, frozen, with a branch for the shapes of `classes` (the
    datasets') that it lacks; a UserError where there is no model or no such shape."""
    if init is None:
        raise UserError("--branch needs --init MODEL.onnx: the trained detector the branch adds shapes to")
    exp = read_export(init)
    base = DetectorNet(exp.width, exp.classes)
    load_onnx_weights(base, init)
    new = [s for s in classes if s not in base.classes]
    if not new:
        raise UserError(f"--branch: the datasets draw no shape that {init} lacks (it knows "
                        f"{', '.join(base.classes)}); a branch adds shapes, fine-tuning is without --branch")
    return BranchedNet(base, new)
