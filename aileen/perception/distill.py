"""Knowledge distillation for the detector (`aileen perception train --distill MODEL.onnx`): a
student (often thinner, `--width`) learns the labels and, beside them, to give the maps a
trained teacher gives on the same crops. The teacher's heatmaps carry what hard labels do not:
how sure it is of an object mostly hidden under another, or which level a stacked one is on.

The term (`distill_loss`), per level:
- heatmaps: the binary cross-entropy of the student's heatmaps against the teacher's as soft
  targets, less the teacher's own entropy, i.e. KL(teacher || student) per cell (0 where the
  student matches; the gradient is the cross-entropy's). Cross-entropy rather than MSE
  because its gradient on the logit is (p - q), which does not vanish where the student is
  saturated and wrong (MSE's is (p - q) p (1 - p)), so a missed faint peak still pulls. It
  is computed from logits (`DetectorNet.logits`) for the same reason, with no clamping.
- offset and size: L1 between the student's and the teacher's, at the teacher's peaks (cells
  whose largest heatmap is the largest of its 3x3 neighbourhood), weighted by that heatmap:
  only where the teacher sees an object are its offset and size meaningful (`decode` reads
  them only there); elsewhere nothing trained them. Size weighs `size_weight`, as in labels.
Each sum is divided by `n` (the batch's labelled centres), as the label losses are, so the
weight `--distill-weight` compares with them.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import torch
import torch.nn.functional as F

from aileen.errors import UserError
from aileen.perception.net import LAYERS, DetectorNet, layer_maps

__all__ = ["load_teacher", "distill_loss"]


def load_teacher(path: str | Path, classes: Sequence[str]) -> DetectorNet:
    """The exported model at `path` in a DetectorNet of its own width, with the student's
    `classes` (so the maps line up; a shape it does not know has a blank heatmap), in eval
    mode and without gradients; a UserError where it cannot be read."""
    from aileen.perception.warmstart import load_onnx_weights, read_export

    if not Path(path).is_file():
        raise UserError(f"{path}: no such model to distil from")
    teacher = DetectorNet(read_export(path).width, classes)
    load_onnx_weights(teacher, path)
    teacher.eval()
    for p in teacher.parameters():
        p.requires_grad_(False)
    return teacher


def distill_loss(student: torch.Tensor, teacher: torch.Tensor, n_classes: int, n: torch.Tensor,
                 size_weight: float) -> tuple[torch.Tensor, dict[str, float]]:
    """The distillation term between the student's and the teacher's raw maps (logits for the
    heatmaps, `DetectorNet.logits`), both (B, 2 (C + 4), h, w); `n` the normaliser."""
    maps = layer_maps(n_classes)
    heat = off = size = student.new_zeros(())
    for k in range(LAYERS):
        b, r = k * maps, k * maps + n_classes
        s_logit, t_logit = student[:, b:r], teacher[:, b:r]
        q = torch.sigmoid(t_logit)
        # BCE(student; q) - H(q): the teacher's entropy is its BCE against its own output
        kl = (F.binary_cross_entropy_with_logits(s_logit, q, reduction="none")
              - F.binary_cross_entropy_with_logits(t_logit, q, reduction="none"))
        heat = heat + kl.sum() / n
        top = q.amax(dim=1, keepdim=True)
        peak = top.eq(F.max_pool2d(top, 3, 1, 1)).float() * top
        off = off + (torch.abs(student[:, r : r + 2] - teacher[:, r : r + 2]) * peak).sum() / n
        size = size + (torch.abs(student[:, r + 2 : r + 4] - teacher[:, r + 2 : r + 4]) * peak).sum() / n
    total = heat + off + size_weight * size
    return total, {"d_heat": heat.item(), "d_off": off.item(), "d_size": size.item()}
