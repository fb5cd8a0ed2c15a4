"""The detector network (torch; `pip install .[train]`), apart from its training so that
`warmstart` (starting it from an exported model) and `train` can both build it.

A plain CNN, six 3x3 conv-BN-ReLU layers (16, 24, 32 channels at strides 2, 4, 8, then
`width`, `width` (dilated 2), `width` at stride 8; receptive field 79 px, three times a
medium object) and a 1x1 head with 2 (C + 4) outputs per stride-8 cell for its C shape
classes, C + 4 per level (layer 0: objects on the table, layer 1: objects resting on
another): C shape-centre heatmaps (sigmoid), the centre's sub-cell offset (x, y) and the box
size (w, h) in cells. One set of maps per level because the two objects of a stack are
centred a cell or less apart: in one map of one shape the upper one's peak swallowed the
lower one's, and they fought over one cell's offset and size. At width 48 (the shipped
model) about 67k parameters and 85 MMAC for a 256 x 256 image; the three `width`-wide convs
at 32 x 32 cells are two thirds of the multiply-adds, so the width is what a faster
detector trims (`warmstart.prune`).
"""

from __future__ import annotations

from collections.abc import Sequence

import torch
from torch import nn

from aileen.world.catalog import SHAPES

__all__ = ["DetectorNet", "LAYERS", "WIDE_CONVS", "DEFAULT_WIDTH", "layer_maps"]

LAYERS = 2  # 0: on the table, 1: resting on another object
DEFAULT_WIDTH = 48  # the shipped model's
WIDE_CONVS = 3  # the last three body convs are `width` wide


def layer_maps(n_classes: int) -> int:
    """Maps per level: the heatmaps, offset x y, size w h."""
    return n_classes + 4


def _cbr(i: int, o: int, stride: int = 1, dilation: int = 1) -> list[nn.Module]:
    return [nn.Conv2d(i, o, 3, stride, dilation, dilation=dilation, bias=False), nn.BatchNorm2d(o), nn.ReLU(inplace=True)]


class DetectorNet(nn.Module):
    """Centre-heatmap detector; forward returns (B, 2 (C + 4), H/8, W/8) for its C shape
    `classes` (catalog names, in the order of its maps): per layer (on the table, on another
    object) C sigmoid heatmaps, offset x y and size w h."""

    def __init__(self, width: int = DEFAULT_WIDTH, classes: Sequence[str] = SHAPES) -> None:
        super().__init__()
        self.width = int(width)
        self.classes = tuple(classes)
        self.body = nn.Sequential(
            *_cbr(3, 16, 2),
            *_cbr(16, 24, 2),
            *_cbr(24, 32, 2),
            *_cbr(32, width),
            *_cbr(width, width, 1, 2),
            *_cbr(width, width),
        )
        nc, maps = len(self.classes), layer_maps(len(self.classes))
        self.head = nn.Conv2d(width, LAYERS * maps, 1)
        with torch.no_grad():  # start the heatmaps near the background rate (focal-loss prior)
            for k in range(LAYERS):
                b = k * maps
                self.head.bias[b : b + nc].fill_(-4.0)
                self.head.bias[b + nc + 2 : b + maps].fill_(3.0)

    def logits(self, x: torch.Tensor) -> torch.Tensor:
        """The maps before the heatmaps' sigmoid (distillation compares logits, `distill`)."""
        return self.head(self.body(x))

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        return self.activate(self.logits(x))

    def activate(self, y: torch.Tensor) -> torch.Tensor:
        """The outputs from `logits`: each level's heatmaps through a sigmoid, the rest as is."""
        nc, maps = len(self.classes), layer_maps(len(self.classes))
        parts = []
        for k in range(LAYERS):
            b = k * maps
            parts += [torch.sigmoid(y[:, b : b + nc]), y[:, b + nc : b + maps]]
        return torch.cat(parts, dim=1)
