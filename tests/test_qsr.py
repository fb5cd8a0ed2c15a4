"""QSRs on hand-built configurations: every cardinal sector, cdc_eq, every RCC8 relation,
boundary cases, and symmetry properties."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aileen.world.geometry import CARDINALS, DEFAULT_Q, cardinal, qsr_facts, rcc8
from aileen.terms import parse


def sq(x: float, y: float, s: float = 0.1) -> tuple[float, float, float, float]:
    return (x - s / 2, y - s / 2, x + s / 2, y + s / 2)


REF = sq(0.5, 0.5)


@pytest.mark.parametrize(
    "dx,dy,expected",
    [
        (0.0, 0.3, "n"), (0.3, 0.3, "ne"), (0.3, 0.0, "e"), (0.3, -0.3, "se"),
        (0.0, -0.3, "s"), (-0.3, -0.3, "sw"), (-0.3, 0.0, "w"), (-0.3, 0.3, "nw"),
    ],
)  # fmt: skip
def test_eight_directions(dx: float, dy: float, expected: str) -> None:
    # the first box lies (dx, dy) from the reference: +x east, +y north
    assert cardinal(sq(0.5 + dx, 0.5 + dy), REF) == expected


def test_eq_centres() -> None:
    assert cardinal(sq(0.5, 0.5, 0.05), REF) == "cdc_eq"


def test_sector_boundaries() -> None:
    # just inside each side of the 22.5 degree boundary between n and ne
    r = 0.3
    a_in = math.radians(22.0)
    a_out = math.radians(23.0)
    assert cardinal(sq(0.5 + r * math.sin(a_in), 0.5 + r * math.cos(a_in)), REF) == "n"
    assert cardinal(sq(0.5 + r * math.sin(a_out), 0.5 + r * math.cos(a_out)), REF) == "ne"


def test_rcc8_all_relations() -> None:
    assert rcc8(sq(0.2, 0.5), REF) == "dc"
    assert rcc8(sq(0.4, 0.5), REF) == "ec"  # touching edges
    assert rcc8(sq(0.45, 0.5), REF) == "po"
    assert rcc8(REF, REF) == "eq"
    assert rcc8(sq(0.475, 0.5, 0.05), REF) == "tpp"  # inside, touching the west edge
    assert rcc8(sq(0.5, 0.5, 0.05), REF) == "ntpp"
    assert rcc8(REF, sq(0.475, 0.5, 0.05)) == "tppi"
    assert rcc8(REF, sq(0.5, 0.5, 0.05)) == "ntppi"


def test_rcc8_margin_boundaries() -> None:
    q = DEFAULT_Q
    # a gap just within q is ec, just beyond is dc; a small overlap within q is still ec
    assert rcc8(sq(0.4 - 0.9 * q, 0.5), REF) == "ec"
    assert rcc8(sq(0.4 - 1.1 * q, 0.5), REF) == "dc"
    assert rcc8(sq(0.4 + 0.9 * q, 0.5), REF) == "ec"
    assert rcc8(sq(0.4 + 1.5 * q, 0.5), REF) == "po"
    # corner to corner touching is ec
    assert rcc8(sq(0.4, 0.4), REF) == "ec"
    # with q = 0 only exact contact is ec
    assert rcc8(sq(0.4 - 1e-4, 0.5), REF, q=0.0) == "dc"
    assert rcc8(sq(0.4, 0.5), REF, q=0.0) == "ec"


def test_facts_every_ordered_pair() -> None:
    facts = qsr_facts({"o1": sq(0.2, 0.5), "o2": sq(0.5, 0.5), "o3": sq(0.5, 0.6)})
    text = {str(f) for f in facts}
    assert len(facts) == 12
    assert {"w(o1,o2)", "dc(o1,o2)", "e(o2,o1)", "dc(o2,o1)", "n(o3,o2)", "s(o2,o3)", "ec(o3,o2)"} <= text
    assert "se(o2,o3)" not in text
    assert parse("w(o1,o2)") in facts
    assert qsr_facts({"o1": REF}) == []


_INV = {"n": "s", "s": "n", "e": "w", "w": "e", "ne": "sw", "sw": "ne", "nw": "se", "se": "nw", "cdc_eq": "cdc_eq"}
_RINV = {"dc": "dc", "ec": "ec", "po": "po", "eq": "eq", "tpp": "tppi", "tppi": "tpp", "ntpp": "ntppi", "ntppi": "ntpp"}

coord = st.floats(0.0, 1.0, allow_nan=False)
side = st.floats(0.01, 0.3, allow_nan=False)


@settings(max_examples=300, deadline=None)
@given(coord, coord, side, side, coord, coord, side, side)
def test_converse_properties(x1, y1, w1, h1, x2, y2, w2, h2) -> None:
    a = (x1, y1, x1 + w1, y1 + h1)
    b = (x2, y2, x2 + w2, y2 + h2)
    assert cardinal(b, a) == _INV[cardinal(a, b)]
    assert rcc8(b, a) == _RINV[rcc8(a, b)]
    assert cardinal(a, b) in CARDINALS or cardinal(a, b) == "cdc_eq"
