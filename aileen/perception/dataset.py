"""Rendered training and evaluation scenes for the detector and the colour module.

A scene holds 1-6 objects (evaluation: 1-4). Shape-colour pairs are drawn from a shuffled
deck of all combinations (25: five shapes, five colours), refilled when empty, so every
combination is equally common. Sizes: mostly medium, some small and large. Shades: every
catalog shade. Boxes and capsules take a random rotation half the time (else they lie
square to the table, as the agent's world adds them).
About a third of the objects are put *near-touching* a previous one (touching, or a gap of up
to 12 mm, along a table axis or a random direction, found by bisection on the exact
footprints), the
case where detectors merge objects and crops mix colours; the rest are uniform on the table.
Rows (`SceneSpec.row_share`, default none): a scene may start with two or three square boxes
touching side by side along a table axis, as the trainer lays out a wall.
Stacks: in `STACK_P` of the scenes, one or two objects go on top of a box or cylinder already
there (through `World.place(..., onto=)`), offset from its centre by 30 % to 95 % of its
radius (never concentric: see `MIN_OFFSET`), so the lower object shows anything from nothing
or a thin rim to most of its top. Labels carry each object's level and how much of it is visible.
Lighting comes from the render seed (random direction, elevation, intensity, gradient), plus
Gaussian sensor noise of 0-3 levels; one scene in ten uses the neutral, noiseless render the
agent's own camera gives (`seed=None`).

On disk (`aileen perception dataset`): `DIR/images.npy` (N, H, W, 3) uint8 RGB, written as a
memory map, and `DIR/labels.json` with, per image, each object's value of every channel
(shape, colour, size, any declared one: `ObjectLabel.to_json`), pixel box and pixel centre,
level, visible share, and for an object on another how much of that one shows
(`support_visible`). Nothing here is committed; the data is regenerated from its seed.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterator
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from aileen.errors import UserError
from aileen.io import atomic_path, atomic_write_text
from aileen.domain import channels
from aileen.world import catalog
from aileen.world.appearance import LOOKS, Appearance, BodyChannels
from aileen.world.camera import DEFAULT_CAMERA, Camera

__all__ = ["SceneSpec", "ObjectLabel", "Sample", "ComboDeck", "sample_world", "generate", "write_dataset", "load_dataset"]

_SIZE_CHOICES = ("small", "medium", "medium", "medium", "large")
NEAR_TOUCH_P = 0.35
MAX_GAP = 0.012  # m
STACK_P = 0.5  # share of scenes with stacks, by default (`SceneSpec.stack_share`)
# The upper object's centre is at least this share of the lower's radius from the lower's
# centre: two objects centred on one point leave the centre-heatmap detector one centre
# for two objects (and a top-down camera often nothing of the lower one).
MIN_OFFSET = 0.3


@dataclass(frozen=True)
class ObjectLabel(BodyChannels):
    appearance: Appearance  # every channel's true value (shape, colour, size, any declared look)
    box_px: tuple[float, float, float, float]
    centre_px: tuple[float, float]
    centre_m: tuple[float, float]
    level: int = 0  # 0 on the table, 1 resting on another object
    visible: float = 1.0  # share of its footprint that shows (render's `Truth.visible`)
    support_visible: float = 1.0  # for an object on another: how much of that one shows

    def to_json(self) -> dict:
        """The label as `labels.json` holds it: one key per channel ("shape", "colour", "size",
        ...), then the box, centres, level and visible shares."""
        row = asdict(self)
        del row["appearance"]
        return {**self.appearance, **row}


@dataclass(frozen=True)
class Sample:
    image: np.ndarray  # (H, W, 3) uint8 RGB
    objects: list[ObjectLabel]


@dataclass(frozen=True)
class SceneSpec:
    min_objects: int = 1
    max_objects: int = 6
    stack_share: float = 0.5  # share of scenes with stacks (`STACK_P`)
    row_share: float = 0.0  # share of scenes that start with a row of touching square boxes
    shapes: tuple[str, ...] | None = None  # the shapes drawn (None: the catalog's)


class ComboDeck:
    """All shape-colour pairs in shuffled rounds: balanced over any long run."""

    def __init__(self, rng: np.random.Generator, shapes: tuple[str, ...] | None = None) -> None:
        self.rng = rng
        self.shapes = shapes
        self.deck: list[tuple[str, str]] = []

    def draw(self) -> tuple[str, str]:
        if not self.deck:
            combos = [(s, c) for s in (self.shapes or catalog.SHAPES) for c in catalog.COLOURS]
            order = self.rng.permutation(len(combos))
            self.deck = [combos[i] for i in order]
        return self.deck.pop()


def _outline(shape: str, size: str, x: float, y: float, angle: float) -> np.ndarray:
    """The footprint as a convex polygon (k, 2) in metres; round shapes as a circumscribed 24-gon
    (not `world.footprints`' exact shapes: the recipes' data sets stay as they were made)."""
    r = catalog.SIZES[size] / 2
    w = catalog.ELONGATED_FOOTPRINTS.get(shape)
    if w is not None:  # a stadium: two half 12-gons round the ends of its axis, circumscribed
        k, a, rr = 12, r * (1.0 - w), r * w / math.cos(math.pi / 24)
        t = (np.arange(k + 1) / k - 0.5) * math.pi  # -90 .. 90 degrees: the east end
        half = np.stack([a + rr * np.cos(t), rr * np.sin(t)], axis=1)
        pts = np.concatenate([half, -half])
        c, s = math.cos(angle), math.sin(angle)
        return pts @ np.array([[c, -s], [s, c]]).T + [x, y]
    if shape in catalog.SQUARE_FOOTPRINTS:
        c, s = math.cos(angle), math.sin(angle)
        pts = np.array([[-r, -r], [r, -r], [r, r], [-r, r]])
        rot = np.array([[c, -s], [s, c]])
        return pts @ rot.T + [x, y]
    k = 24
    t = np.arange(k) * 2 * math.pi / k
    rr = r / math.cos(math.pi / k)
    return np.stack([x + rr * np.cos(t), y + rr * np.sin(t)], axis=1)


def _angle(shape: str, rng: np.random.Generator) -> float:
    """An object's turn: half the boxes stand square to the table (the agent's world adds them
    so), half turned; a capsule lies square to the table half the time, else any way round.
    Round shapes draw nothing (older datasets stay as they were)."""
    if shape in catalog.SQUARE_FOOTPRINTS:
        return float(rng.uniform(0, math.pi / 2)) if rng.random() < 0.5 else 0.0
    if shape in catalog.ELONGATED_FOOTPRINTS:
        return float(rng.uniform(0, math.pi)) if rng.random() < 0.5 else 0.0
    return 0.0


def _separated(a: np.ndarray, b: np.ndarray) -> bool:
    """Separating-axis test for two convex polygons: True when they do not overlap."""
    for poly in (a, b):
        edges = np.roll(poly, -1, axis=0) - poly
        normals = np.stack([-edges[:, 1], edges[:, 0]], axis=1)
        pa = a @ normals.T
        pb = b @ normals.T
        if np.any((pa.max(axis=0) <= pb.min(axis=0)) | (pb.max(axis=0) <= pa.min(axis=0))):
            return True
    return False


def sample_world(rng: np.random.Generator, n_objects: int, deck: ComboDeck, camera: Camera = DEFAULT_CAMERA,
                 stack_share: float = STACK_P, row_share: float = 0.0):
    """A World with `n_objects` non-overlapping objects (fewer if the table is too full)."""
    from aileen.world.records import footprint_half_extent
    from aileen.world.sim import World

    table = camera.table
    world = World(table, seed=int(rng.integers(2**31)))
    placed: list[tuple[float, float, np.ndarray]] = []
    if row_share > 0.0 and rng.random() < row_share:  # (no draw without rows: older datasets stay as they were)
        n_objects -= _add_row(world, rng, deck, placed, min(3, n_objects))
    for _ in range(n_objects):
        shape, colour = deck.draw()
        size = str(_SIZE_CHOICES[int(rng.integers(len(_SIZE_CHOICES)))])
        shade = int(rng.integers(len(catalog.SHADES[colour])))
        # Half the boxes stand square to the table (the agent's world adds them so), half turned.
        angle = _angle(shape, rng)
        half = footprint_half_extent(shape, catalog.SIZES[size], angle)
        pos = None
        for attempt in range(60):
            if placed and attempt < 30 and rng.random() < NEAR_TOUCH_P * (2 if attempt else 1):
                ax, ay, apoly = placed[int(rng.integers(len(placed)))]
                # half along a table axis: side by side and one behind the other are what
                # lessons lay out, and two square boxes edge to edge are the hardest case
                if rng.random() < 0.5:
                    th = int(rng.integers(4)) * math.pi / 2 + float(rng.normal(0.0, 0.05))
                else:
                    th = float(rng.uniform(0, 2 * math.pi))
                ux, uy = math.cos(th), math.sin(th)
                lo, hi = 0.0, 0.3  # bisection on the contact distance along (ux, uy)
                for _ in range(18):
                    mid = (lo + hi) / 2
                    if _separated(_outline(shape, size, ax + ux * mid, ay + uy * mid, angle), apoly):
                        hi = mid
                    else:
                        lo = mid
                # a quarter touch exactly (as after a push), the rest leave a gap of up to MAX_GAP
                d = hi + (0.0 if rng.random() < 0.25 else float(rng.uniform(0.0, MAX_GAP)))
                x, y = ax + ux * d, ay + uy * d
            else:
                x, y = float(rng.uniform(half, table.width - half)), float(rng.uniform(half, table.depth - half))
            if not (half <= x <= table.width - half and half <= y <= table.depth - half):
                continue
            poly = _outline(shape, size, x, y, angle)
            if all(_separated(poly, p) for _, _, p in placed):
                pos = (x, y, poly)
                break
        if pos is None:
            continue
        world.add(shape, colour, pos[0], pos[1], size=size, shade=shade, angle=angle, **_looks(rng))
        placed.append(pos)
    if rng.random() < stack_share:
        add_stacks(world, rng, deck, int(rng.integers(1, 3)))
    return world


def _looks(rng: np.random.Generator) -> dict[str, str]:
    """A value of each declared look the trainer draws (`channels.drawn`), at random: a data set
    of a world with a texture shows every texture. None declared, nothing is drawn."""
    return {c.name: c.values[int(rng.integers(len(c.values)))] for c in channels.drawn() if c.name in LOOKS}


def _add_row(world, rng: np.random.Generator, deck: ComboDeck, placed: list, n: int) -> int:
    """A row of `n` (at most 3, at least 2) square boxes touching side by side along a table
    axis, as the trainer lays out a wall: the layout where a detector reads touching boxes as
    overlapping. Returns how many were put down (0 when the row does not fit)."""
    if n < 2:
        return 0
    sizes = [str(_SIZE_CHOICES[int(rng.integers(len(_SIZE_CHOICES)))]) for _ in range(n)]
    along_x = rng.random() < 0.5
    length = sum(catalog.SIZES[z] for z in sizes)
    table = world.table
    span, across = (table.width, table.depth) if along_x else (table.depth, table.width)
    big = max(catalog.SIZES[z] for z in sizes) / 2
    if length >= span:
        return 0
    start = float(rng.uniform(0.0, span - length))
    side = float(rng.uniform(big, across - big))
    pos = start
    for z in sizes:
        half = catalog.SIZES[z] / 2
        c = pos + half
        x, y = (c, side) if along_x else (side, c)
        colour = deck.draw()[1]
        shade = int(rng.integers(len(catalog.SHADES[colour])))
        world.add("box", colour, x, y, size=z, shade=shade)
        placed.append((x, y, _outline("box", z, x, y, 0.0)))
        pos += 2 * half
    return n


def add_stacks(world, rng: np.random.Generator, deck: ComboDeck, n: int) -> None:
    """Put up to `n` new objects on top of boxes and cylinders already on the table, each
    offset from the lower one's centre by 30 % to 95 % of its radius, never
    overlapping another upper object; a draw that does not fit is skipped."""
    from aileen.errors import UserError
    from aileen.world.stacks import FLAT_TOPS

    uppers: list[np.ndarray] = []
    for _ in range(n):
        free = [o for o in world.objects() if o.level == 0 and o.shape in FLAT_TOPS and world.carries(o.id) is None]
        if not free:
            return
        lower = free[int(rng.integers(len(free)))]
        shape, colour = deck.draw()
        size = str(_SIZE_CHOICES[int(rng.integers(len(_SIZE_CHOICES)))])
        shade = int(rng.integers(len(catalog.SHADES[colour])))
        angle = _angle(shape, rng)
        th = int(rng.integers(4)) * math.pi / 2 if rng.random() < 0.5 else float(rng.uniform(0, 2 * math.pi))
        d = float(rng.uniform(MIN_OFFSET, 0.95)) * lower.footprint / 2
        x, y = lower.x + d * math.cos(th), lower.y + d * math.sin(th)
        poly = _outline(shape, size, x, y, angle)
        if not all(_separated(poly, p) for p in uppers):
            continue
        try:
            oid = world.add(shape, colour, x, y, size=size, shade=shade, angle=angle)
        except UserError:  # over the table's edge
            continue
        world.pick_up(oid)
        world.place(oid, x, y, onto=lower.id)
        uppers.append(poly)


def generate(
    n: int,
    seed: int,
    spec: SceneSpec = SceneSpec(),
    camera: Camera = DEFAULT_CAMERA,
) -> Iterator[Sample]:
    """`n` rendered scenes with their labels, reproducibly from `seed`."""
    from aileen.world.render import render

    rng = np.random.default_rng([seed, 0xDA7A])
    deck = ComboDeck(rng, spec.shapes)
    for _ in range(n):
        k = int(rng.integers(spec.min_objects, spec.max_objects + 1))
        world = sample_world(rng, k, deck, camera, spec.stack_share, spec.row_share)
        if rng.random() < 0.1:
            frame = render(world, camera=camera, seed=None)
        else:
            frame = render(world, camera=camera, seed=int(rng.integers(2**31)), noise=float(rng.uniform(0.0, 3.0)))
        objs = []
        shows = {t.id: t.visible for t in frame.truth}
        for t in frame.truth:
            cu, cv = camera.to_pixels(*t.centre_m)
            objs.append(ObjectLabel(t.appearance, tuple(t.box_px), (cu, cv), tuple(t.centre_m), t.level,
                                    round(t.visible, 4), round(shows.get(t.on, 1.0), 4) if t.on else 1.0))
        yield Sample(frame.image, objs)


def write_dataset(out: str | Path, n: int, seed: int, spec: SceneSpec = SceneSpec(), camera: Camera = DEFAULT_CAMERA,
                  progress: bool = False) -> Path:
    """Render `n` scenes into `out` (created if needed); returns the folder."""
    out = Path(out)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise UserError(f"{out}: cannot create the dataset folder ({exc.strerror})") from None
    with atomic_path(out / "images.npy") as tmp:
        images = np.lib.format.open_memmap(tmp, mode="w+", dtype=np.uint8,
                                           shape=(n, camera.height, camera.width, 3))
        labels = []
        it = generate(n, seed, spec, camera)
        if progress:
            try:
                from tqdm import tqdm

                it = tqdm(it, total=n, desc="rendering", unit="img")
            except ImportError:  # pragma: no cover
                pass
        for i, s in enumerate(it):
            images[i] = s.image
            labels.append([o.to_json() for o in s.objects])
        images.flush()
        del images
    meta = {"version": 1, "n": n, "seed": seed, "width": camera.width, "height": camera.height,
            "min_objects": spec.min_objects, "max_objects": spec.max_objects, "stack_share": spec.stack_share,
            "row_share": spec.row_share, "shapes": list(spec.shapes or catalog.SHAPES), "images": labels}
    atomic_write_text(out / "labels.json", json.dumps(meta))
    return out


def load_dataset(folder: str | Path) -> tuple[np.ndarray, list[list[dict]], dict]:
    """(images memmap, per-image object dicts, metadata) of a dataset folder, or a UserError."""
    folder = Path(folder)
    ip, lp = folder / "images.npy", folder / "labels.json"
    for p in (ip, lp):
        if not p.is_file():
            raise UserError(f"{p}: missing; make a dataset with: aileen perception dataset --n 12000 --seed 0 --out {folder}")
    try:
        meta = json.loads(lp.read_text())
        images = np.load(ip, mmap_mode="r")
    except (OSError, ValueError) as exc:
        raise UserError(f"{folder}: unreadable dataset ({exc})") from None
    labels = meta.pop("images", None)
    if not isinstance(labels, list) or len(labels) != images.shape[0] or images.ndim != 4 or images.dtype != np.uint8:
        raise UserError(f"{lp}: labels do not match {ip} (expected one list of objects per image)")
    return images, labels, meta
