"""What `perceive()` returns on a fixed set of scenes, written down to the last bit:
`python tools/perceive_reference.py --out tests/data/perceive_reference.json [--n 80 --seed 2501]`.

Why: the perception path is sped up by changes that must not move any output (issue 25:
the same boxes, percepts, sizes, levels, scores and facts). `tests/test_perceive_reference.py`
recomputes every scene and compares it with the file, float for float (JSON keeps a float's
shortest repr, which reads back to the same double).

The scenes are the evaluation's (`aileen.perception.dataset.generate`, 1-4 objects, half of
them with stacks) plus a few the agent's own camera gives (neutral light, no noise). The
file records the detector's SHA-256: a retrained model perceives differently, and the file
is then written again with this command from a perception path already held equal to the old
one (the test says so).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import sys
from pathlib import Path

from aileen.perception.dataset import SceneSpec, generate
from aileen.perception.detector import DEFAULT_MODEL
from aileen.perception.scene import Scene, perceive

__all__ = ["model_digest", "scene_record", "snapshot", "main"]

DEFAULT_N = 80
DEFAULT_SEED = 2501


def model_digest(path: Path = DEFAULT_MODEL) -> str:
    """SHA-256 of the detector file: the reference holds for this model only."""
    return hashlib.sha256(path.read_bytes()).hexdigest()


def scene_record(scene: Scene) -> dict:
    """Everything `perceive` returned, as JSON-able lists and dicts (floats unrounded)."""
    return {
        "objects": [
            {
                "id": o.id,
                "box_px": list(o.box_px),
                "box_m": list(o.box_m),
                "centre_px": list(o.centre_px),
                "centre_m": list(o.centre_m),
                "values": dict(o.values),
                "footprint": o.footprint,
                "level": o.level,
                "scores": dict(o.scores),
            }
            for o in scene.objects
        ],
        # the facts follow from the objects (`scene_facts`); their digest keeps the file small
        "facts": len(scene.facts),
        "facts_sha256": hashlib.sha256("\n".join(str(f) for f in scene.facts).encode()).hexdigest(),
    }


def _agent_images() -> list:
    """Scenes as the agent's camera shows them: neutral light, squared boxes, a stack."""
    from aileen.world.render import render
    from aileen.world.sim import World

    out = []
    w = World()
    for shape, colour, x, y in (("box", "red", 0.25, 0.3), ("cone", "blue", 0.7, 0.6),
                                ("sphere", "green", 0.4, 0.75), ("cylinder", "yellow", 0.8, 0.2)):
        w.add(shape, colour, x, y)
    out.append(render(w).image)
    out.append(render(w, seed=3, noise=2.0).image)
    top = w.add("sphere", "purple", 0.5, 0.5, size="small")
    w.pick_up(top)
    w.place(top, 0.27, 0.32, onto="obj1")
    out.append(render(w, seed=3, noise=2.0).image)
    return out


def snapshot(n: int = DEFAULT_N, seed: int = DEFAULT_SEED) -> dict:
    """The reference: the model's digest and one record per scene, in a fixed order."""
    images = [s.image for s in generate(n, seed, SceneSpec(1, 4, 0.5))] + _agent_images()
    return {"n": n, "seed": seed, "model_sha256": model_digest(),
            "scenes": [scene_record(perceive(img)) for img in images]}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, required=True, help="JSON file to write")
    ap.add_argument("--n", type=int, default=DEFAULT_N, help="evaluation scenes (besides 3 of the agent's camera)")
    ap.add_argument("--seed", type=int, default=DEFAULT_SEED)
    args = ap.parse_args(argv)
    data = snapshot(args.n, args.seed)
    tmp = args.out.with_suffix(args.out.suffix + ".tmp")
    tmp.write_text(json.dumps(data, indent=None, separators=(",", ":")) + "\n")
    tmp.replace(args.out)
    print(f"{args.out}: {len(data['scenes'])} scenes, model {data['model_sha256'][:12]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
