"""The camera model: the one place where table metres and image pixels meet.

The camera looks straight down at the table (orthographic). Table frame: metres, origin at
the table's south-west corner, +x east (the trainer's right), +y north (away from the
trainer, who stands at the south edge). Image frame: pixels, origin top-left, u to the
right (east), v downwards (south). So north is the top of the image.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Table:
    width: float = 1.0  # metres, along x (west -> east)
    depth: float = 1.0  # metres, along y (south -> north)

    def contains(self, x: float, y: float, margin: float = 0.0) -> bool:
        return margin <= x <= self.width - margin and margin <= y <= self.depth - margin

    def room(self, side: float) -> int:
        """How many objects `side` metres wide the table holds side by side, edge to edge: more
        than any layout fits (objects keep apart), so a bound on what a lesson may ask for."""
        return int(self.width // side) * int(self.depth // side)


@dataclass(frozen=True)
class Camera:
    table: Table = Table()
    width: int = 256  # pixels
    height: int = 256

    @property
    def px_per_m_x(self) -> float:
        return self.width / self.table.width

    @property
    def px_per_m_y(self) -> float:
        return self.height / self.table.depth

    def to_pixels(self, x: float, y: float) -> tuple[float, float]:
        """Table metres -> continuous pixel coordinates (u, v); pixel i covers [i, i+1)."""
        return x * self.px_per_m_x, (self.table.depth - y) * self.px_per_m_y

    def to_metres(self, u: float, v: float) -> tuple[float, float]:
        """Continuous pixel coordinates (u, v) -> table metres (x, y)."""
        return u / self.px_per_m_x, self.table.depth - v / self.px_per_m_y

    def box_to_metres(self, box: tuple[float, float, float, float]) -> tuple[float, float, float, float]:
        """Pixel box (u0, v0, u1, v1) -> metre box (x0, y0, x1, y1) with x0<x1, y0<y1."""
        u0, v0, u1, v1 = box
        x0, y1 = self.to_metres(u0, v0)
        x1, y0 = self.to_metres(u1, v1)
        return x0, y0, x1, y1

    def box_to_pixels(self, box: tuple[float, float, float, float]) -> tuple[float, float, float, float]:
        """Metre box (x0, y0, x1, y1) -> pixel box (u0, v0, u1, v1) with u0<u1, v0<v1."""
        x0, y0, x1, y1 = box
        u0, v1 = self.to_pixels(x0, y0)
        u1, v0 = self.to_pixels(x1, y1)
        return u0, v0, u1, v1


DEFAULT_CAMERA = Camera()
