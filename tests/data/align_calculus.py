"""A calculus of ones own, declared after perception was imported (tests/test_domain_extensions.py)."""
from aileen.perception import regions  # noqa: F401 - imported first: its tables once were built before
# 'align': centres in one row (al_row) or one column (al_col), and the relation word 'level
# with' (same row, either side) that needs it, made through AILEEN_DOMAIN.
import math
from aileen.domain import calculi, relations
from aileen.world import geometry

TOL = 0.2  # centres within 0.2 of the larger footprint on one axis


def _align(a, b):
    if not calculi._apart(a, b):
        return None
    (ax, ay), (bx, by) = geometry.centre(a.box_m), geometry.centre(b.box_m)
    f = max(a.footprint, b.footprint, 1e-6)
    if abs(ay - by) <= TOL * f:
        return "al_row"
    if abs(ax - bx) <= TOL * f:
        return "al_col"
    return None


ALIGN = calculi.Calculus("align", ("al_row", "al_col"), {"al_row": "al_row", "al_col": "al_col"}, _align,
                         "centres in one row / one column")
calculi.declare(ALIGN)


def _ext(p):
    x0, y0, x1, y1 = p.box_m()
    return max(x1 - x0, y1 - y0)


def accepts(a, b):
    return abs(a.y - b.y) <= 0.3 * max(_ext(a), _ext(b)) and abs(a.x - b.x) > max(_ext(a), _ext(b))


def clear(a, b):
    return abs(a.y - b.y) <= 0.1 * max(_ext(a), _ext(b)) and abs(a.x - b.x) > 1.3 * max(_ext(a), _ext(b))


def offset(rng, fa, fb):
    f = max(fa, fb)
    side = 1 if rng.random() < 0.5 else -1
    return side * f * rng.uniform(1.8, 3.5), f * rng.uniform(-0.05, 0.05)


def near_miss(rng, fa, fb):
    f = max(fa, fb)
    side = 1 if rng.random() < 0.5 else -1
    up = 1 if rng.random() < 0.5 else -1
    return side * f * rng.uniform(1.8, 3.5), up * f * rng.uniform(0.7, 1.2)


relations.declare(relations.TrainerRelation("level with", "level with", accepts, clear, offset, near_miss,
                                            symmetric=True))
