"""Scenes from descriptions: requested objects plus random distractors, laid out collision-free.

Exams should test the learner, not the physics, so generated objects never touch: every
object's axis-aligned footprint box (rotation included) keeps at least `margin` metres from
every other box and from the table edge. That also makes the boxes `dc` (disconnected) for
the RCC8 module whenever its quantisation margin is below `margin`, so a scene means what
its description says. A settle of such a scene moves nothing.

Layout: sequential random sampling (rejection), restarted a few times when it jams; if it
still fails, a shuffled grid of cells with jitter, which succeeds whenever the objects fit on
a grid. Only when neither works, or when the objects' padded areas alone exceed the table,
is the request refused, with a message that says why.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from aileen.errors import UserError
from aileen.world import catalog
from aileen.world.appearance import Appearance, BodyChannels, described
from aileen.world.camera import Table
from aileen.world.records import footprint_half_extent
from aileen.world.sim import World

__all__ = ["ObjectRequest", "build_scene", "sample_free_position", "random_scene"]

Box = tuple[float, float, float, float]


@dataclass(frozen=True, init=False)
class ObjectRequest(BodyChannels):
    """One object a scene must hold: what it looks like (a shape or colour left out is drawn
    at random from the scene's seed; a size left out is the default, a declared look its
    default) and where it goes."""

    appearance: Appearance
    position: tuple[float, float] | None = None  # None = random collision-free

    def __init__(self, shape: str | None = None, colour: str | None = None, size: str = catalog.DEFAULT_SIZE,
                 position: tuple[float, float] | None = None, *, appearance: Mapping[str, str] | None = None,
                 **looks: str) -> None:
        object.__setattr__(self, "appearance", described(shape, colour, size, appearance, looks))
        object.__setattr__(self, "position", position)


@dataclass(frozen=True)
class _Planned(BodyChannels):
    appearance: Appearance
    shade: int
    angle: float
    position: tuple[float, float] | None

    @property
    def extent(self) -> float:
        """Side of the axis-aligned square the footprint occupies."""
        return 2.0 * footprint_half_extent(self.shape, catalog.SIZES[self.size], self.angle)


def _free(boxes: Sequence[Box], box: Box, margin: float) -> bool:
    """True when `box` keeps `margin` from every box (separated on some axis by >= margin)."""
    x0, y0, x1, y1 = box
    for bx0, by0, bx1, by1 in boxes:
        if x0 < bx1 + margin and bx0 < x1 + margin and y0 < by1 + margin and by0 < y1 + margin:
            return False
    return True


def _sample(
    boxes: Sequence[Box],
    extent: float,
    rng: np.random.Generator,
    table: Table,
    margin: float,
    tries: int,
    predicate: Callable[[float, float], bool] | None,
) -> tuple[float, float] | None:
    h = extent / 2.0
    lo_x, hi_x = margin + h, table.width - margin - h
    lo_y, hi_y = margin + h, table.depth - margin - h
    if lo_x > hi_x or lo_y > hi_y:
        return None
    for _ in range(tries):
        x = float(rng.uniform(lo_x, hi_x))
        y = float(rng.uniform(lo_y, hi_y))
        if _free(boxes, (x - h, y - h, x + h, y + h), margin) and (predicate is None or predicate(x, y)):
            return x, y
    return None


def sample_free_position(
    world: World,
    footprint: float,
    rng: np.random.Generator,
    *,
    margin: float = 0.03,
    tries: int = 1000,
    predicate: Callable[[float, float], bool] | None = None,
) -> tuple[float, float]:
    """A random centre where a square of side `footprint` keeps `margin` from everything.

    `footprint` is the side of the axis-aligned square the new object will occupy (for a
    rotated box, its rotated extent). Held objects do not count: they are not on the table.
    `predicate(x, y)` can restrict the region (e.g. "west of o2"). Raises `UserError` when no
    position is found in `tries` draws.
    """
    if footprint <= 0 or margin < 0 or tries < 1:
        raise UserError(f"footprint must be > 0, margin >= 0 and tries >= 1 (got {footprint}, {margin}, {tries})")
    boxes = [o.box_m() for o in world.objects() if not o.held]
    pos = _sample(boxes, footprint, rng, world.table, margin, tries, predicate)
    if pos is None:
        raise UserError(
            f"no free position for an object of {footprint:.2f} m with margin {margin:.2f} m "
            f"among {len(boxes)} objects after {tries} tries"
        )
    return pos


def _cannot_fit(plans: Sequence[_Planned], table: Table, margin: float) -> UserError:
    sizes = {catalog.SIZES[p.size] for p in plans}
    size_txt = f"{max(sizes):.2f} m" if len(sizes) == 1 else f"up to {max(sizes):.2f} m"
    return UserError(
        f"cannot place {len(plans)} objects of {size_txt} on a {table.width:.1f} x {table.depth:.1f} m "
        f"table with margin {margin:.2f} m"
    )


def _grid_layout(
    plans: Sequence[_Planned], fixed: Sequence[Box], rng: np.random.Generator, table: Table, margin: float
) -> list[tuple[float, float]] | None:
    """Positions for `plans` on a shuffled grid of cells (jittered), avoiding `fixed` boxes."""
    cell = max(p.extent for p in plans) + margin
    nx = int((table.width - margin) // cell)
    ny = int((table.depth - margin) // cell)
    if nx < 1 or ny < 1:
        return None
    # Spread the spare room evenly between the cells.
    gap_x = (table.width - nx * (cell - margin)) / (nx + 1)
    gap_y = (table.depth - ny * (cell - margin)) / (ny + 1)
    cells = [(i, j) for i in range(nx) for j in range(ny)]
    order = rng.permutation(len(cells))
    boxes = list(fixed)
    out: list[tuple[float, float]] = []
    k = 0
    for p in plans:
        h = p.extent / 2.0
        while k < len(order):
            i, j = cells[order[k]]
            k += 1
            slack = (cell - margin) / 2.0 - h  # room to jitter inside the cell
            x = gap_x + i * (cell - margin + gap_x) + (cell - margin) / 2.0 + float(rng.uniform(-slack, slack))
            y = gap_y + j * (cell - margin + gap_y) + (cell - margin) / 2.0 + float(rng.uniform(-slack, slack))
            box = (x - h, y - h, x + h, y + h)
            if _free(boxes, box, margin):
                boxes.append(box)
                out.append((x, y))
                break
        else:
            return None
    return out


def build_scene(
    objects: Sequence[ObjectRequest],
    *,
    distractors: int = 0,
    seed: int = 0,
    margin: float = 0.03,
    table: Table = Table(),
    distractor_ok: Callable[[str, str], bool] | None = None,
    rotate_boxes: bool = True,
    restarts: int = 20,
) -> tuple[World, list[str]]:
    """A world holding the requested objects and `distractors` random ones, collision-free.

    Returns the world and the ids of the requested objects in request order (distractors are
    added after them and not listed). Unspecified shapes and colours, every shade, and the
    rotation of boxes and capsules (when `rotate_boxes`) are drawn from `seed`. `distractor_ok(shape,
    colour)` filters the kinds a distractor may be; among those, distractors are drawn
    balanced (the least used shape and colour first), so small scenes are varied. Objects with a given position are put
    exactly there (they must be on the table; they are not checked against each other); the
    others keep `margin` from everything. The world is not settled.
    """
    if distractors < 0:
        raise UserError(f"distractors must be >= 0, got {distractors}")
    if margin < 0 or not math.isfinite(margin):
        raise UserError(f"margin must be a finite number >= 0, got {margin}")
    rng = np.random.default_rng(seed)

    def angle_for(shape: str) -> float:
        if rotate_boxes and shape in catalog.SQUARE_FOOTPRINTS:
            return float(rng.uniform(0.0, math.pi / 2.0))
        if rotate_boxes and shape in catalog.ELONGATED_FOOTPRINTS:  # a lying capsule, any way round
            return float(rng.uniform(0.0, math.pi))
        return 0.0

    plans: list[_Planned] = []
    for req in objects:
        shape = catalog.check_shape(req.shape) if req.shape is not None else str(rng.choice(catalog.drawn_shapes()))
        colour = catalog.check_colour(req.colour) if req.colour is not None else str(rng.choice(catalog.COLOURS))
        catalog.check_size(req.size)
        shade = int(rng.integers(len(catalog.SHADES[colour])))
        angle = angle_for(shape) if req.position is None else 0.0
        pos = None if req.position is None else (float(req.position[0]), float(req.position[1]))
        plans.append(_Planned(req.appearance.replace(shape=shape, colour=colour), shade, angle, pos))
    if distractors:
        kinds = [
            (s, c)
            for s, c in itertools.product(catalog.drawn_shapes(), catalog.COLOURS)
            if distractor_ok is None or distractor_ok(s, c)
        ]
        if not kinds:
            raise UserError("distractor_ok rejects every shape and colour: no distractor can be made")
        # Balanced draws: each distractor takes a kind whose shape and colour have been used
        # least so far (ties at random), so four distractors show four shapes when allowed.
        used: dict[str, int] = {}
        for p in plans:
            used[p.shape] = used.get(p.shape, 0) + 1
            used[p.colour] = used.get(p.colour, 0) + 1
        for _ in range(distractors):
            cost = [used.get(s, 0) + used.get(c, 0) for s, c in kinds]
            best = [k for k, v in zip(kinds, cost) if v == min(cost)]
            shape, colour = best[int(rng.integers(len(best)))]
            used[shape] = used.get(shape, 0) + 1
            used[colour] = used.get(colour, 0) + 1
            shade = int(rng.integers(len(catalog.SHADES[colour])))
            plans.append(_Planned(Appearance(shape=shape, colour=colour, size=catalog.DEFAULT_SIZE), shade,
                                  angle_for(shape), None))

    fixed = [p for p in plans if p.position is not None]
    free = [p for p in plans if p.position is None]
    fixed_boxes: list[Box] = []
    for p in fixed:
        assert p.position is not None
        h = p.extent / 2.0
        fixed_boxes.append((p.position[0] - h, p.position[1] - h, p.position[0] + h, p.position[1] + h))
    laid = iter(_layout(free, fixed_boxes, rng, table, margin, restarts) if free else [])

    world = World(table, seed=seed)
    ids: list[str] = []
    for i, p in enumerate(plans):
        if p.position is None:
            p = next(laid)
        assert p.position is not None
        x, y = p.position
        obj_id = world.put(p.appearance, x, y, shade=p.shade, angle=p.angle)
        if i < len(objects):
            ids.append(obj_id)
    return world, ids


def _layout(
    free: Sequence[_Planned], fixed: Sequence[Box], rng: np.random.Generator, table: Table, margin: float, restarts: int
) -> list[_Planned]:
    """`free` with collision-free positions (largest first); a clear error when impossible.

    Rotated boxes take more room; when a crowded request jams, the layout is tried again with
    every box square to the table, first at random, then on the grid.
    """
    upright = [dataclasses.replace(p, angle=0.0) for p in free]
    usable = (table.width - margin) * (table.depth - margin)
    need = sum((p.extent + margin) ** 2 for p in upright)
    if need > usable or any(p.extent + 2 * margin > min(table.width, table.depth) for p in upright):
        raise _cannot_fit(free, table, margin)
    candidates = [free] if all(p.angle == 0.0 for p in free) else [free, upright]
    for plans in candidates:
        # Place the largest first: small objects fill the gaps the large ones leave.
        order = sorted(range(len(plans)), key=lambda i: -plans[i].extent)
        for _ in range(max(1, restarts)):
            boxes = list(fixed)
            placed: dict[int, tuple[float, float]] = {}
            for i in order:
                pos = _sample(boxes, plans[i].extent, rng, table, margin, 200, None)
                if pos is None:
                    break
                h = plans[i].extent / 2.0
                boxes.append((pos[0] - h, pos[1] - h, pos[0] + h, pos[1] + h))
                placed[i] = pos
            else:
                return [dataclasses.replace(p, position=placed[i]) for i, p in enumerate(plans)]
    grid = _grid_layout(upright, fixed, rng, table, margin)
    if grid is None:
        raise _cannot_fit(free, table, margin)
    return [dataclasses.replace(p, position=pos) for p, pos in zip(upright, grid)]


def random_scene(n: int, *, seed: int = 0, **kw: object) -> World:
    """A world of `n` random objects (random shapes, colours, shades), collision-free.

    Keyword arguments go to `build_scene` (margin, table, distractor_ok, rotate_boxes).
    """
    if n < 0:
        raise UserError(f"the number of objects must be >= 0, got {n}")
    world, _ = build_scene([], distractors=n, seed=seed, **kw)  # type: ignore[arg-type]
    return world
