"""`aileen render`: draw a random scene and print its ground truth.

A quick way to see what the camera sees, and the job the README runs before the agent exists.
"""

from __future__ import annotations

import argparse
import json
import os
from typing import Any

from aileen import argtypes
from aileen.errors import UserError


def register(subparsers: Any) -> None:
    """Add the `render` subcommand."""
    p = subparsers.add_parser(
        "render",
        help="render a random table-top scene to a PNG and print its ground truth",
        description="Build a random collision-free scene, draw it with the top-down camera, "
        "write the image as PNG and print every object's ground truth.",
    )
    p.add_argument("--seed", type=argtypes.seed, default=0, help="scene, lighting and noise seed (default 0)")
    p.add_argument("--objects", type=int, default=4, help="number of random objects (default 4)")
    p.add_argument("--out", default="scene.png", help="PNG file to write (default scene.png)")
    p.add_argument("--size", type=int, default=256, help="image width and height in pixels (default 256)")
    p.add_argument("--noise", type=float, default=0.0, help="sensor noise, std in 8-bit levels (default 0)")
    p.add_argument("--json", action="store_true", help="print the ground truth as one JSON object")
    p.set_defaults(handler=run_render)


def run_render(args: argparse.Namespace) -> int:
    """Build, render, save, print. User mistakes raise `UserError` (exit 2)."""
    if args.objects < 0:
        raise UserError(f"--objects must be >= 0, got {args.objects}")
    if not 16 <= args.size <= 4096:
        raise UserError(f"--size must be between 16 and 4096 pixels, got {args.size}")
    if not 0.0 <= args.noise <= 100.0:
        raise UserError(f"--noise must be between 0 and 100, got {args.noise}")
    out = str(args.out)
    folder = os.path.dirname(os.path.abspath(out))
    if not out or os.path.isdir(out):
        raise UserError(f"--out {out!r}: expected a file path for the PNG, got a folder")
    if not os.path.isdir(folder):
        raise UserError(f"--out {out!r}: folder {folder} does not exist")
    if not out.lower().endswith(".png"):
        raise UserError(f"--out {out!r}: expected a .png file name")

    from aileen.world.camera import Camera, Table
    from aileen.world.render import render, save_png
    from aileen.world.scenes import random_scene

    table = Table()
    world = random_scene(args.objects, seed=args.seed, table=table)
    camera = Camera(table, args.size, args.size)
    frame = render(world, camera=camera, seed=args.seed, noise=args.noise)
    try:
        save_png(frame.image, out)
    except OSError as exc:
        raise UserError(f"--out {out!r}: cannot write the image ({exc.strerror or exc})") from None

    rows = []
    for t in frame.truth:
        rows.append(
            {
                "id": t.id,
                **t.appearance,  # one key per channel: shape, colour, size (and any declared look)
                "x": round(t.centre_m[0], 6),
                "y": round(t.centre_m[1], 6),
                "box_px": [round(v, 3) for v in t.box_px],
                "box_m": [round(v, 6) for v in t.box_m],
            }
        )
    if args.json:
        print(json.dumps({"seed": args.seed, "image": out, "objects": rows}))
        return 0
    print(f"wrote {out} ({args.size}x{args.size}, seed {args.seed}, {len(rows)} objects)")
    if rows:
        # a column per channel an object's appearance holds (every declared one), each as
        # wide as its name or longest value
        names = list(frame.truth[0].appearance)
        width = {n: max(len(n), *(len(str(r.get(n, ""))) for r in rows)) + 2 for n in names}
        head = "".join(f"{n:<{width[n]}}" for n in names)
        print(f"{'id':<6} {head}{'x m':>6} {'y m':>6}  box px (u0 v0 u1 v1)")
        for r in rows:
            box = " ".join(f"{v:5.1f}" for v in r["box_px"])
            looks = "".join(f"{str(r.get(n, '')):<{width[n]}}" for n in names)
            print(f"{r['id']:<6} {looks}{r['x']:6.3f} {r['y']:6.3f}  {box}")
    return 0
