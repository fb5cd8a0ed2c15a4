"""Where `aileen perception tune-color`'s accuracy goes: its crops split by kind, the same
grid without stacks, and the stacked crops read the way perception reads them.

Run from the repository root (about 1.5 min on two cores, 2026-12-04):

    PYTHONPATH=. .venv/bin/python benchmarks/tune_color_split.py [--n 1000] [--seed 777]

The crops are drawn exactly as `aileen.perception.evaluate.tune_colour` draws them (the same
scenes, the same box jitter); only the scoring is split. A diagnostic for docs/perception.md,
"Colour module"; it changes nothing.
"""

from __future__ import annotations

import argparse

import numpy as np

from aileen.perception.color import colour_of, tune_weights
from aileen.perception.dataset import SceneSpec, generate
from aileen.world.camera import DEFAULT_CAMERA


def crops(n: int, seed: int, spec: SceneSpec, jitter_px: float = 2.0) -> list[tuple]:
    """(image, box, true colour, kind, uppers) per object, as `tune_colour` draws them."""
    rng = np.random.default_rng([seed, 0xC01])
    cam = DEFAULT_CAMERA
    out = []
    for s in generate(n, seed, spec, cam):
        uppers = [o.box_px for o in s.objects if o.level > 0]
        for o in s.objects:
            j = rng.uniform(-jitter_px, jitter_px, size=4)
            u0, v0, u1, v1 = (o.box_px[i] + j[i] for i in range(4))
            box = (max(0.0, u0), max(0.0, v0), min(cam.width, max(u1, u0 + 2)), min(cam.height, max(v1, v0 + 2)))
            kind = "on another" if o.level > 0 else ("partly hidden" if o.visible < 0.999 else "unstacked")
            out.append((s.image, box, o.colour, kind, uppers, o.box_px))
    return out


def line(name: str, rows: list[tuple], **kw) -> None:
    r = tune_weights([(im, b, c) for im, b, c, *_ in rows], **kw)
    g = dict(r.grid)
    print(f"{name}: {r.n} crops; w1 0.50 {g[0.5] * 100:.2f} %; best w1 {r.w1:.2f} {r.accuracy * 100:.2f} %; "
          f"range {min(g.values()) * 100:.2f}-{max(g.values()) * 100:.2f} %")


def overlaps(a, b) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--n", type=int, default=1000)
    p.add_argument("--seed", type=int, default=777)
    a = p.parse_args()

    rows = crops(a.n, a.seed, SceneSpec(1, 6))
    print("as tune-color draws them (half the scenes with stacks, every catalog shape):")
    line("  all", rows)
    for kind in ("unstacked", "on another", "partly hidden"):
        line(f"  {kind}", [r for r in rows if r[3] == kind])
    print("  the paper's method unchanged (RGB match, every cluster competes), all crops:")
    line("    k = 4", rows, match="rgb", min_saturation=0.0)

    print("stacked crops at w1 = 0.5, whole crop vs. as perception reads them "
          "(colour_of upper=True; exclude= the boxes of objects on it):")
    for kind, kw in (("on another", lambda r: {"upper": True}),
                     ("partly hidden", lambda r: {"exclude": [b for b in r[4] if overlaps(b, r[5])]})):
        sub = [r for r in rows if r[3] == kind]
        whole = sum(colour_of(r[0], r[1]).name == r[2] for r in sub)
        read = sum(colour_of(r[0], r[1], **kw(r)).name == r[2] for r in sub)
        print(f"  {kind}: {len(sub)} crops; whole crop {whole / len(sub) * 100:.2f} %; "
              f"as perception reads them {read / len(sub) * 100:.2f} %")

    flat = crops(a.n, a.seed, SceneSpec(1, 6, stack_share=0.0))
    print("the same command's scenes without stacks (SceneSpec stack_share=0), grid:")
    r = tune_weights([(im, b, c) for im, b, c, *_ in flat])
    for w1, acc in r.grid:
        print(f"  w1 {w1:.2f}  accuracy {acc * 100:.2f} %")
    print(f"  {r.n} crops; best w1 {r.w1:.2f} {r.accuracy * 100:.2f} %")
    print("  the paper's method unchanged (RGB match, every cluster competes):")
    line("    k = 4", flat, match="rgb", min_saturation=0.0)
    line("    k = 3", flat, match="rgb", min_saturation=0.0, k=3)
    line("  chromaticity match alone (every cluster competes)", flat, min_saturation=0.0)
    line("  chromatic-candidate rule alone (RGB match)", flat, match="rgb")


if __name__ == "__main__":
    main()
