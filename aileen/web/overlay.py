"""The agent's perception drawn over the camera image: boxes, percept labels, object ids, and
the relation a sentence stated, as an arrow between the objects it grounded to.

The boxes and labels are what the agent perceived (its own ids, its percept symbols), not the
simulator's truth, so the trainer sees what the agent sees. Objects a sentence grounded to are
drawn thick, in a colour no object has (cyan). Labels sit on a dark plate, are kept inside the
image and placed where they do not cover each other (above the box, else below, else inside,
else beside), so they stay readable on any table and any object colour.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import cv2
import numpy as np

SCALE = 2  # the page shows the 256 px camera image at twice its size
BOX = (255, 255, 255)
HIGHLIGHT = (0, 230, 255)  # cyan: not a catalogue colour, clear on the table and on every object
PLATE = (25, 25, 25)  # label background
INK = (255, 255, 255)
FONT = cv2.FONT_HERSHEY_SIMPLEX
FONT_SCALE = 0.5
PAD = 3  # pixels around a label's text


@dataclass(frozen=True)
class Mark:
    """One perceived object: the agent's id, its percepts and its box in camera pixels."""

    id: str
    percepts: tuple[str, ...]  # one per channel, in channel order (shape, colour, size)
    box_px: tuple[float, float, float, float]
    # Not seen now: the agent keeps it in mind under this object (`aileen.agent.state.Seen.under`).
    under: str | None = None

    @property
    def label(self) -> str:
        """`o1 medium red box`: modifiers first, the shape last; `(hidden under o2)` after an
        object the agent does not see but keeps in mind."""
        text = " ".join([self.id] + [p.removeprefix("cv_") for p in reversed(self.percepts)])
        return text if self.under is None else f"{text} (hidden under {self.under})"

    def to_json(self) -> dict:
        out = {"id": self.id, "percepts": list(self.percepts),
               "box_px": [round(float(b), 1) for b in self.box_px]}
        if self.under is not None:
            out["under"] = self.under
        return out


@dataclass(frozen=True)
class Arrow:
    """A relation between two perceived objects, as a sentence stated it: `src` word `dst`."""

    src: str
    dst: str
    word: str


Rect = tuple[int, int, int, int]  # x0, y0, x1, y1 in image pixels


def draw(image: np.ndarray, marks: Iterable[Mark] = (), highlight: Iterable[str] = (), *,
         overlay: bool = True, scale: int = SCALE, arrows: Iterable[Arrow] = ()) -> np.ndarray:
    """The image enlarged `scale` times (nearest pixel), with the marks drawn when `overlay`."""
    big = cv2.resize(image, None, fx=scale, fy=scale, interpolation=cv2.INTER_NEAREST)
    if not overlay:
        return big
    marks = list(marks)
    hot = set(highlight)
    boxes = {m.id: tuple(int(round(c * scale)) for c in m.box_px) for m in marks}
    for m in marks:
        u0, v0, u1, v1 = boxes[m.id]
        if m.id in hot:
            cv2.rectangle(big, (u0, v0), (u1, v1), (0, 0, 0), 5, cv2.LINE_AA)
            cv2.rectangle(big, (u0, v0), (u1, v1), HIGHLIGHT, 3, cv2.LINE_AA)
        else:
            cv2.rectangle(big, (u0, v0), (u1, v1), (0, 0, 0), 3, cv2.LINE_AA)
            cv2.rectangle(big, (u0, v0), (u1, v1), BOX, 1, cv2.LINE_AA)
    taken: list[Rect] = []
    objects: list[Rect] = [boxes[m.id] for m in marks]
    for a in arrows:
        if a.src in boxes and a.dst in boxes:
            _arrow(big, boxes[a.src], boxes[a.dst], a.word, taken, objects)
    for m in marks:
        size = _text_size(m.label)
        others = [b for b in objects if b != boxes[m.id]]
        spot = place_label(size, boxes[m.id], big.shape[1], big.shape[0], taken, others)
        taken.append(spot)
        _plate(big, spot, m.label, lit=m.id in hot)
    return big


def _text_size(text: str) -> tuple[int, int, int]:
    (w, h), base = cv2.getTextSize(text, FONT, FONT_SCALE, 1)
    return w, h, base


def _overlap(a: Rect, b: Rect) -> int:
    w = min(a[2], b[2]) - max(a[0], b[0])
    h = min(a[3], b[3]) - max(a[1], b[1])
    return max(w, 0) * max(h, 0)


def place_label(size: tuple[int, int, int], box: tuple[int, ...], width: int, height: int,
                taken: list[Rect], objects: list[Rect] = ()) -> Rect:
    """Where a label of `size` (text width, height, baseline) goes for an object's `box`:
    the first of above, below, inside the top, right of and left of the box that covers no
    other label and no other object, kept inside the image; else the one covering least
    (another label counts four times an object)."""
    w, h, base = size
    pw, ph = w + 2 * PAD, h + base + 2 * PAD
    u0, v0, u1, v1 = box
    tries = [(u0, v0 - ph - 2), (u0, v1 + 2), (u0 + 2, v0 + 2), (u1 + 3, v0), (u0 - pw - 3, v0),
             (u0, v0 - 2 * ph - 4), (u0, v1 + ph + 4)]
    return _best(tries, pw, ph, width, height, taken, objects)


def _best(tries: list[tuple[int, int]], pw: int, ph: int, width: int, height: int, taken: list[Rect],
          objects: list[Rect]) -> Rect:
    best, best_cover = None, None
    for x, y in tries:
        x = int(min(max(x, 0), width - pw - 1))
        y = int(min(max(y, 0), height - ph - 1))
        rect = (x, y, x + pw, y + ph)
        cover = 4 * sum(_overlap(rect, t) for t in taken) + sum(_overlap(rect, o) for o in objects)
        if cover == 0:
            return rect
        if best_cover is None or cover < best_cover:
            best, best_cover = rect, cover
    assert best is not None
    return best


def _plate(img: np.ndarray, rect: Rect, text: str, *, lit: bool = False) -> None:
    x0, y0, x1, y1 = rect
    region = img[y0:y1, x0:x1]
    fill = np.array(HIGHLIGHT if lit else PLATE, dtype=np.float32)
    img[y0:y1, x0:x1] = (0.2 * region + 0.8 * fill).astype(img.dtype)  # a little of the table shows through
    _, h, _ = _text_size(text)
    ink = (0, 0, 0) if lit else INK
    cv2.putText(img, text, (x0 + PAD, y0 + PAD + h), FONT, FONT_SCALE, ink, 1, cv2.LINE_AA)


def _edge(box: tuple[int, ...], toward: tuple[float, float]) -> tuple[int, int]:
    """Where the line from the box's centre toward a point leaves the box."""
    u0, v0, u1, v1 = box
    cx, cy = (u0 + u1) / 2, (v0 + v1) / 2
    dx, dy = toward[0] - cx, toward[1] - cy
    if dx == 0 and dy == 0:
        return int(cx), int(cy)
    t = min((u1 - u0) / 2 / abs(dx) if dx else np.inf, (v1 - v0) / 2 / abs(dy) if dy else np.inf)
    t = min(t + 4 / max(np.hypot(dx, dy), 1e-9), 1.0)  # a few pixels clear of the box
    return int(round(cx + t * dx)), int(round(cy + t * dy))


def _arrow(img: np.ndarray, a: tuple[int, ...], b: tuple[int, ...], word: str, taken: list[Rect],
           objects: list[Rect]) -> None:
    ca = ((a[0] + a[2]) / 2, (a[1] + a[3]) / 2)
    cb = ((b[0] + b[2]) / 2, (b[1] + b[3]) / 2)
    p, q = _edge(a, cb), _edge(b, ca)
    length = max(np.hypot(q[0] - p[0], q[1] - p[1]), 1.0)
    tip = min(0.3, 14 / length)
    cv2.arrowedLine(img, p, q, (0, 0, 0), 5, cv2.LINE_AA, tipLength=tip)
    cv2.arrowedLine(img, p, q, HIGHLIGHT, 2, cv2.LINE_AA, tipLength=tip)
    w, h, base = _text_size(word)
    pw, ph = w + 2 * PAD, h + base + 2 * PAD
    mx, my = (p[0] + q[0]) // 2, (p[1] + q[1]) // 2
    # beside the arrow's middle (above, below, then on it), covering no object if it can
    tries = [(mx - pw // 2, my - ph - 6), (mx - pw // 2, my + 6), (mx - pw // 2, my - ph // 2)]
    rect = _best(tries, pw, ph, img.shape[1], img.shape[0], taken, objects)
    taken.append(rect)
    _plate(img, rect, word, lit=True)


def png(image: np.ndarray) -> bytes:
    # light compression: the page redraws after every lesson, and speed beats bytes on localhost
    ok, buf = cv2.imencode(".png", cv2.cvtColor(image, cv2.COLOR_RGB2BGR), [cv2.IMWRITE_PNG_COMPRESSION, 1])
    if not ok:  # pragma: no cover - cv2 encodes any uint8 RGB image
        raise RuntimeError("PNG encoding failed")
    return buf.tobytes()
