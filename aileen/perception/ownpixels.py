"""An object's own pixels in its box: what size and colour are measured on.

A detection box holds the object, the pale table around it, and sometimes pixels of a
neighbour (a turned box's box reaches past its corners) or of an object resting on it. The
object's own pixels are the saturated ones (every catalogued colour is; the wood is not) of
its own chromaticity: the renderer changes brightness, never hue, and the nearest shades of
two different catalogued colours are 0.24 apart in chromaticity; of those, the largest
connected piece (a neighbour of the same colour whose corner reaches into the box lies
apart).

`own_pixels` finds them in one crop; `own_pixels_of` in many windows of one image at once,
and `OwnPixels` keeps them for the windows one perceive() call asks of its image, so that no
window is looked at twice (issue 25: on crops this small numpy's cost is per call).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from functools import lru_cache

import cv2
import numpy as np

__all__ = ["own_pixels", "own_pixels_of", "OwnPixels", "Window", "MIN_SATURATION", "CHROMA_TOL", "saturated",
           "own_hue_pixels", "HUE_TOL", "hue_near"]

# Table wood is pale (HSV saturation about 60/255 under any lighting); every catalogued
# colour is above 130. Half-way leaves room for shading and sensor noise.
MIN_SATURATION = 95
CHROMA_TOL = 0.1
# `own_hue_pixels`: how far (OpenCV hue units, 0-179 around the circle) a pixel's hue may lie
# from the object's own. The catalogued colours' hues lie 26 or more apart (red 0, yellow 26,
# green 62, blue 114, purple 142).
HUE_TOL = 8

Window = tuple[int, int, int, int]  # (u0, v0, u1, v1) integer pixels, as `pixels.crop_window` gives


def saturated(rgb: np.ndarray) -> np.ndarray:
    """Which pixels of an (h, w, 3) RGB uint8 array are saturated (HSV saturation at least
    `MIN_SATURATION`): the catalogued colours' pixels, never the wood's.

    The pixels go to OpenCV as one row: its RGB-to-HSV conversion costs about half a
    microsecond per row whatever the row's length, so a 33-pixel-wide crop converts five
    times faster laid out flat (issue 25). The conversion is per pixel, so the mask is the
    same."""
    h, w = rgb.shape[:2]
    return (_hsv_flat(rgb)[:, 1] >= MIN_SATURATION).reshape(h, w)


def _hsv_flat(rgb: np.ndarray) -> np.ndarray:
    """The (h * w, 3) HSV values of an (h, w, 3) RGB uint8 array, converted as one row
    (`saturated` says why)."""
    h, w = rgb.shape[:2]
    if h == 0 or w == 0:
        return np.zeros((0, 3), dtype=np.uint8)
    return cv2.cvtColor(np.ascontiguousarray(rgb).reshape(1, h * w, 3), cv2.COLOR_RGB2HSV)[0]


def own_pixels(crop: np.ndarray, hidden: np.ndarray | None = None, *, close: int = 0) -> np.ndarray:
    """The crop's pixels that belong to the object: saturated, not `hidden`, and of the
    object's chromaticity, the median of the saturated pixels in the middle half of the crop
    (of all that show, when part of the object is hidden). `close` > 0 closes gaps up to
    that many pixels wide first (a lying capsule's specular streak, white along its whole
    length, splits its colour in two).

    Only the saturated pixels' chromaticities are computed (the others are never the
    object's): per pixel the same float32 arithmetic as over the whole crop, on a third to a
    half of the pixels (issue 25: perception's pixel checks were a third of `perceive`)."""
    crop = np.ascontiguousarray(crop)
    sat = saturated(crop)
    if hidden is not None:
        sat &= ~hidden
    # the saturated pixels by flat index: numpy's boolean indexing costs several times a
    # `take` on arrays this small (issue 25), and the values are the same
    idx = np.flatnonzero(sat)
    ref = None  # the saturated pixels the object's chromaticity is read on (None: all)
    if hidden is None:
        inner = np.flatnonzero(_middle_half(*sat.shape).take(idx))
        if len(inner) >= 6:
            ref = inner
    if ref is None and len(idx) < 6:
        return sat
    # channel planes of the saturated pixels (row-major order): a numpy reduction over an
    # axis of three is slow, elementwise sums are not, and the order of the sums is the
    # reduction's ((r + g) + b), so every value is the same float32 as over the whole crop
    rgb = np.ascontiguousarray(crop.reshape(-1, 3).take(idx, axis=0).T, dtype=np.float32)  # (3, n)
    chroma = rgb / np.maximum((rgb[0] + rgb[1]) + rgb[2], np.float32(1.0))
    own = _row_medians(chroma if ref is None else chroma.take(ref, axis=1))
    d = chroma - own[:, None]
    d *= d
    mask = np.zeros(sat.shape, dtype=bool)
    mask.ravel()[idx] = np.sqrt((d[0] + d[1]) + d[2]) < CHROMA_TOL
    if close > 0:  # on a border of wood, or the erosion keeps what the dilation spread to the edge
        k, p = np.ones((close + 1, close + 1), np.uint8), close + 1
        padded = cv2.copyMakeBorder(mask.view(np.uint8), p, p, p, p, cv2.BORDER_CONSTANT, value=0)
        mask = cv2.morphologyEx(padded, cv2.MORPH_CLOSE, k)[p:-p, p:-p] > 0
        if hidden is not None:
            mask &= ~hidden
    return _one_object(mask, hidden)


def own_hue_pixels(crop: np.ndarray) -> np.ndarray:
    """The crop's saturated pixels of the object's hue (the circular mean of every saturated
    pixel's), within `HUE_TOL`: an object's own pixels where a highlight runs its whole
    length. A lying capsule's specular streak mixes white into its colour along its middle,
    which moves chromaticity (`own_pixels` then keeps a strip of it, and the rest of the
    capsule passes for something else's pixels: of 300 lone capsules, 19 left 6 to 280
    pixels unexplained around them) but never hue, which white and shade leave where it is
    (none of 200). Every piece is kept: the streak splits the capsule."""
    h, w = crop.shape[:2]
    hsv = _hsv_flat(crop)
    sat = hsv[:, 1] >= MIN_SATURATION
    if np.count_nonzero(sat) < 6:
        return sat.reshape(h, w)
    return (sat & _hue_within(hsv, sat)).reshape(h, w)


def _hue_within(hsv: np.ndarray, of: np.ndarray) -> np.ndarray:
    """Which of the (n, 3) HSV pixels lie within `HUE_TOL` of the circular mean hue of the
    pixels `of` (a boolean mask over them, some true)."""
    turn = hsv[:, 0].astype(np.float64) * (2.0 * np.pi / 180.0)
    mean = np.angle(np.exp(1j * turn[of]).mean())
    return np.abs(np.angle(np.exp(1j * (turn - mean)))) * (180.0 / (2.0 * np.pi)) <= HUE_TOL


def hue_near(crop: np.ndarray, mine: np.ndarray) -> np.ndarray:
    """The crop's pixels of the hue of its saturated pixels in `mine` (their circular mean,
    within `HUE_TOL`); none when fewer than 6 of those are saturated (no hue to read)."""
    h, w = crop.shape[:2]
    hsv = _hsv_flat(crop)
    of = mine.ravel() & (hsv[:, 1] >= MIN_SATURATION)
    if np.count_nonzero(of) < 6:
        return np.zeros((h, w), dtype=bool)
    return _hue_within(hsv, of).reshape(h, w)


def own_pixels_of(image: np.ndarray, windows: Sequence[Window]) -> list[np.ndarray]:
    """`own_pixels(image[v0:v1, u0:u1])` for each window (nothing hidden, no closing), found
    for all of them together: perception asks it of every object in turn, and on crops this
    small numpy's cost is per call, not per pixel. The crops are stacked one under another
    (padded with black, which is never saturated), so the per-pixel steps -- saturation,
    chromaticity, distance to the object's own -- run once over all of them; each crop's
    own chromaticity (its median) and its largest piece are its own. Pixel by pixel the
    arithmetic is `own_pixels`', so each mask is the one it gives."""
    if len(windows) < 2:  # nothing to share
        return [own_pixels(image[v0:v1, u0:u1]) for u0, v0, u1, v1 in windows]
    heights = [v1 - v0 for _, v0, _, v1 in windows]
    width = max(u1 - u0 for u0, _, u1, _ in windows)
    tops = np.cumsum([0] + heights).tolist()
    stack = np.zeros((tops[-1], width, 3), dtype=np.uint8)
    middle = np.zeros((tops[-1], width), dtype=bool)
    for (u0, v0, u1, v1), top, h in zip(windows, tops, heights):
        w = u1 - u0
        stack[top : top + h, :w] = image[v0:v1, u0:u1]
        middle[top + h // 4 : top + h - h // 4, w // 4 : w - w // 4] = True
    sat = saturated(stack)
    idx = np.flatnonzero(sat)
    inner = np.flatnonzero(middle.ravel().take(idx))  # positions in idx of middle-half pixels
    # each crop's saturated pixels are a run of idx (the crops are stacked), and so are its
    # middle-half ones of `inner`
    starts = [top * width for top in tops]
    runs = np.searchsorted(idx, starts).tolist()
    inner_runs = np.searchsorted(inner, runs).tolist()
    rgb = np.ascontiguousarray(stack.reshape(-1, 3).take(idx, axis=0).T, dtype=np.float32)  # (3, n)
    chroma = rgb / np.maximum((rgb[0] + rgb[1]) + rgb[2], np.float32(1.0))
    own = np.zeros((3, len(windows)), dtype=np.float32)
    plain = []  # the crops with too few saturated pixels to tell: their saturated pixels, as `own_pixels`
    for j in range(len(windows)):
        a, b = runs[j], runs[j + 1]
        i0, i1 = inner_runs[j], inner_runs[j + 1]
        if i1 - i0 >= 6:
            own[:, j] = _row_medians(chroma.take(inner[i0:i1], axis=1))
        elif b - a >= 6:
            own[:, j] = _row_medians(chroma[:, a:b])
        else:
            plain.append(j)
    d = chroma - own.take(np.repeat(np.arange(len(windows)), np.diff(runs)), axis=1)
    d *= d
    mask = np.zeros(sat.shape, dtype=bool)
    mask.ravel()[idx] = np.sqrt((d[0] + d[1]) + d[2]) < CHROMA_TOL
    out = []
    for j, ((u0, _, u1, _), top, h) in enumerate(zip(windows, tops, heights)):
        if j in plain:
            out.append(np.ascontiguousarray(sat[top : top + h, : u1 - u0]))
        else:
            out.append(_one_object(np.ascontiguousarray(mask[top : top + h, : u1 - u0]), None))
    return out


@lru_cache(maxsize=4096)
def _middle_half(h: int, w: int) -> np.ndarray:
    """Which pixels of an h x w crop, by flat index, lie in its middle half (rows h // 4 to
    h - h // 4, columns likewise): where `own_pixels` reads the object's chromaticity.
    Read-only, as it is shared between calls."""
    inner = np.zeros((h, w), dtype=bool)
    inner[h // 4 : h - h // 4, w // 4 : w - w // 4] = True
    inner = inner.ravel()
    inner.setflags(write=False)
    return inner


def _row_medians(a: np.ndarray) -> np.ndarray:
    """`np.median(a.T, axis=0)` of a (3, n) float32 array, n >= 1, to the bit (the middle
    value, or the float32 sum of the two middle ones halved), without its overhead."""
    n = a.shape[1]
    if n % 2:
        k = (n - 1) // 2
        return np.partition(a, k, axis=1)[:, k]
    k = n // 2
    part = np.partition(a, (k - 1, k), axis=1)  # both middle values in place at once
    return (part[:, k - 1] + part[:, k]) / np.float32(2.0)


def _one_object(mask: np.ndarray, hidden: np.ndarray | None) -> np.ndarray:
    """The mask's largest connected piece, plus the pieces that border the hidden part (an
    object resting across another splits what shows of it): a neighbour of the same colour
    whose corner reaches into the box, apart from the object, is left out."""
    mask = np.ascontiguousarray(mask)
    # the labels alone (a third of the cost with their statistics): one piece is the rule
    n, labels = cv2.connectedComponents(mask.view(np.uint8), connectivity=8)
    if n <= 2:
        return mask
    areas = np.bincount(labels.ravel(), minlength=n)[1:]
    keep = np.zeros(n, dtype=bool)
    keep[1 + int(np.argmax(areas))] = True
    if hidden is not None and hidden.any():
        near = cv2.dilate(hidden.view(np.uint8), np.ones((5, 5), np.uint8)) > 0
        keep[np.unique(labels[near & mask])] = True
        keep[0] = False
    return keep[labels]


class OwnPixels:
    """The own pixels (`own_pixels`: nothing hidden, no closing) of windows of one image,
    each found once, for as long as this object lives: one perceive() call. Its steps ask
    some windows again (the box of an object that rests on another, when the lower one's
    footprint and colour leave it out), and many windows are found together (`find`). A
    window's pixels are those of the image, so what is kept never goes stale; the masks are
    read-only, as their askers share them."""

    def __init__(self, image: np.ndarray) -> None:
        self.image = image
        self._found: dict[Window, np.ndarray] = {}

    def find(self, windows: Iterable[Window]) -> None:
        """Find the own pixels of all these windows at once (`own_pixels_of`), those not
        found already."""
        new = list(dict.fromkeys(w for w in windows if w not in self._found))
        for window, mask in zip(new, own_pixels_of(self.image, new)):
            mask.setflags(write=False)
            self._found[window] = mask

    def __call__(self, window: Window) -> np.ndarray:
        """The window's own pixels, found now unless found before."""
        mask = self._found.get(window)
        if mask is None:
            u0, v0, u1, v1 = window
            mask = own_pixels(self.image[v0:v1, u0:u1])
            mask.setflags(write=False)
            self._found[window] = mask
        return mask
