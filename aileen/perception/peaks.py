"""The peaks of the detector's class heatmaps, found on all maps at once (`find_peaks`).

A peak is a cell that is the largest in its 3x3 neighbourhood (nothing past a map's edge
counts), whose heat exceeds 0.05, and whose block score exceeds the threshold: the largest
2x2 sum of heat among the four 2x2 blocks that contain the cell (zero past the edge), capped
at 1. An object whose centre lies on a cell border splits its peak over two (or, on a
corner, four) cells -- at 0.5 m on the default camera the centre is exactly on a border --
and no single cell then reaches the threshold; the block sum restores it.

The maps are small (a few 32 x 32 maps per image) and numpy's loops over shifted
(c, h, w) views of them cost several times its loops over contiguous arrays. So the maps are
laid out flat, each in a frame one cell wide (`_framed`), and every neighbour of every cell
is one shifted slice of that one array: the same float32 sums in the same order, and maxima
(exact, whoever takes them), as over the maps one by one (issue 25).
"""

from __future__ import annotations

import numpy as np

__all__ = ["find_peaks", "MIN_HEAT"]

# A peak's own heat exceeds this, whatever its block score.
MIN_HEAT = 0.05


def _framed(heat: np.ndarray, fill: float) -> np.ndarray:
    """The maps (c, h, w) flat, map after map, each in a frame of `fill` one cell wide (rows
    of w + 2 cells), and w + 3 cells more of `fill` after the last: a read a row or a cell
    away from any cell of a map then stays in the array and in that map's frame."""
    c, h, w = heat.shape
    n = c * (h + 2) * (w + 2)
    flat = np.full(n + 2 * (w + 2) + 2, fill, dtype=heat.dtype)
    flat[:n].reshape(c, h + 2, w + 2)[:, 1:-1, 1:-1] = heat
    return flat


def _block_scores(heat: np.ndarray) -> np.ndarray:
    """Per cell, flat: index J = (map (h + 2) + y) (w + 2) + x holds cell (map, y, x)'s block
    score (the other indices are padding); length c (h + 2) (w + 2)."""
    c, h, w = heat.shape
    row, n = w + 2, c * (h + 2) * (w + 2)
    z = _framed(heat, 0.0)
    # the block whose top-left cell sits at framed index j: the four cells summed in the
    # order ((top-left + bottom-left) + top-right) + bottom-right
    s2 = z[: -row - 1] + z[row:-1]
    s2 += z[1:-row]
    s2 += z[row + 1 :]
    # cell J lies in the blocks at J, J + 1, J + row and J + row + 1 (framed index J + row + 1)
    best = np.maximum(s2[:n], s2[row : row + n])
    np.maximum(best, s2[1 : n + 1], out=best)
    np.maximum(best, s2[row + 1 : row + 1 + n], out=best)
    return np.minimum(best, 1.0, out=best)


def find_peaks(heat: np.ndarray, threshold: float) -> tuple[np.ndarray, tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Each map's block scores, (c, h, w), and its peaks as (map, y, x) index arrays in
    `np.nonzero`'s order (see the module's docstring)."""
    c, h, w = heat.shape
    row, n = w + 2, c * (h + 2) * (w + 2)
    top = _framed(heat, -np.inf)
    across = np.maximum(top[:-2], top[1:-1])  # across[k]: the row's max around k + 1
    np.maximum(across, top[2:], out=across)
    # cell J sits at framed index J + row + 1: its 3x3 maximum is that of the rows around
    # J + 1, J + row + 1 and J + 2 row + 1
    local = np.maximum(across[:n], across[row : row + n])
    np.maximum(local, across[2 * row : 2 * row + n], out=local)
    own = top[row + 1 : row + 1 + n]  # each cell's heat (-inf off the maps: no peak there)
    block = _block_scores(heat)
    hits = np.flatnonzero((own >= local) & (block > threshold) & (own > MIN_HEAT))
    maps, rest = np.divmod(hits, (h + 2) * row)
    ys, xs = np.divmod(rest, row)
    return block.reshape(c, h + 2, row)[:, :h, :w], (maps, ys, xs)
