"""Qualitative calculi: the relations perception computes between every ordered pair of objects.

Each calculus is a set of pairwise disjoint relations (at most one holds of an ordered pair),
its converse table, and the one function that computes it from two perceived objects (`Body`:
box in table metres, measured footprint, layer). Topology is exhaustive, direction too except
between overlapping footprints (one object over another has no direction to it); the
others report only the *marked* cases, as people notice them: two objects of about the same
size, at an ordinary distance, side by side on the table, give no size, distance or stacking
fact. Unmarked relations would add the same facts to every spatial example and make any two
relations look alike. Predicates are named for the calculus, never for a word: "near" is *learned* over
`qd_close`, "larger than" over `sz_larger`.

| calculus  | relations                                   | from                                  |
|-----------|---------------------------------------------|---------------------------------------|
| `cdc`     | `n ne e se s sw w nw cdc_eq`                | box centres (QSRlib's cardinal directions, 8 sectors) |
| `cone`    | `cone_n cone_e cone_s cone_w cone_eq`       | box centres (cone-based directions, 4 cones) |
| `d16`     | `d16_00 ... d16_15 d16_eq`                  | box centres (16 sectors, the first centred on east) |
| `d64`     | `d64_00 ... d64_63 d64_eq`                  | box centres (64 sectors from east: every coarser edge is one of theirs) |
| `rcc8`    | `dc ec po eq tpp ntpp tppi ntppi`           | boxes, with a 1 cm quantisation margin |
| `qdist`   | `qd_close qd_far` (in between: none)        | gap between footprints / the larger footprint (QSRlib's `argd`) |
| `dband`   | `dband_00 ... dband_15`                     | the same ratio in 16 bands (`BAND_EDGES`), with every grain of direction |
| `dgap`    | `dgap_00 ... dgap_15`                       | centres' distance less half of each footprint / the larger footprint, in the same bands (the gap two discs would leave: alike on every side) |
| `qsize`   | `sz_larger sz_smaller` (about equal: none)  | measured footprints                    |
| `stack`   | `st_on st_under`                            | layers and overlapping boxes           |

The direction calculi are grains of one sense, each declaring its regions (`Calculus.regions`):
an agent perceives one grain (`--senses cones`, or `sectors` as the paper's AILEEN did) or all
of them at once (`--senses all`, the agent's default, `AGENT_DIRECTIONS`), a relation word's
grain then learned from its examples (memory/extent.py). With every grain of direction the
agent also perceives distance in bands (`FINER`), a word's distance learned likewise
(memory/reach.py). Perception's own scene facts (`aileen
render --json`, `perceive()` without senses) use `DEFAULT_DIRECTIONS`, the cones. Everything
else sees every calculus (the planner's converse table, region sampling).

To add a calculus: declare it below with its relations, converses and compute function. The
facts perception builds (`aileen.perception.facts.scene_facts`), the converse table the
planner hands to clingo, and the relation vocabulary the ASP programs check are all read from
`CALCULI`.
"""

from __future__ import annotations

import dataclasses
import math
import sys
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Protocol

from aileen.world import geometry
from aileen.terms import DECLARED_NAME, Term, fn


class Body(Protocol):
    """What a calculus needs of a perceived object."""

    box_m: tuple[float, float, float, float]
    footprint: float  # measured side or diameter, metres
    level: int  # 0 on the table, 1 resting on another object


@dataclass(frozen=True)
class Calculus:
    name: str
    relations: tuple[str, ...]
    converse: Mapping[str, str]  # one direction per pair; the other is implied
    compute: Callable[[Body, Body], str | None]  # the relation of a to b, None when none holds
    doc: str = ""
    # Static: the relation depends on the objects alone, not where they stand (moving them
    # neither makes nor breaks it), so the planner keeps it through pick-up and place.
    static: bool = False
    # Values nearly every pair of objects on a table has (two objects apart: `dc`): a concept
    # that keeps only these tells no pairs apart (agent/disjunction.py).
    common: frozenset[str] = frozenset()
    # For a direction calculus: each relation's region, (centre, width) in degrees, the centre
    # counter-clockwise from east, of a's centre seen from b's. The grain of the calculus is
    # the width; the size principle (memory/extent.py) reads the regions, never the names.
    regions: Mapping[str, tuple[float, float]] = field(default_factory=dict)
    _full: dict[str, str] = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        full = dict(self.converse)
        full.update({v: k for k, v in self.converse.items()})
        missing = [r for r in self.relations if r not in full]
        if missing:
            raise ValueError(f"calculus {self.name}: no converse for {missing}")
        self._full.update(full)

    def converse_of(self, relation: str) -> str:
        return self._full[relation]

    @property
    def is_direction(self) -> bool:
        return bool(self.regions)


# ------------------------------------------------------------------ compute functions

# qdist thresholds on the gap between footprints, in units of the larger footprint of the
# two (QSRlib's argd takes absolute thresholds; relative ones make "close" mean the same for
# small and large objects). Close: under half an object's width apart; far: more than 3.5
# widths. The trainer's directional layouts (centres 1.5-4 widths apart) fall in between.
QD_CLOSE = 0.4
QD_MID = 3.5
# qsize: footprints within this ratio read as the same size (catalogued sizes differ by 30 %
# or more; the size measure is good to about 5 mm).
SZ_SAME_RATIO = 1.15


def _cdc(a: Body, b: Body) -> str | None:
    # Seen from above, one object over another (a stack) has no direction to it: its centre
    # lies on the other's footprint, and which side it leans to is noise.
    if geometry.rcc8(a.box_m, b.box_m) not in ("dc", "ec"):
        return None
    return geometry.cardinal(a.box_m, b.box_m)


def _cone(a: Body, b: Body) -> str | None:
    if geometry.rcc8(a.box_m, b.box_m) not in ("dc", "ec"):  # as for `_cdc`
        return None
    return geometry.cone(a.box_m, b.box_m)


def _apart(a: Body, b: Body) -> bool:
    return geometry.rcc8(a.box_m, b.box_m) in ("dc", "ec")


def sectors(name: str, n: int, doc: str, *, edge_on_east: bool = False) -> Calculus:
    """A direction calculus of `n` equal sectors, counter-clockwise from east: relations
    `<name>_00` ..., `<name>_eq` when the centres coincide. The first sector is centred on
    east, or starts there (`edge_on_east`: so that every edge of the cones, the 8 sectors and
    16 sectors is one of its edges). Like the others, no direction between overlapping
    footprints."""
    names = tuple(f"{name}_{k:02d}" for k in range(n))
    eq = f"{name}_eq"
    width = 360.0 / n
    shift = width / 2 if edge_on_east else 0.0

    def compute(a: Body, b: Body) -> str | None:
        if not _apart(a, b):
            return None
        h = geometry.heading(a.box_m, b.box_m)
        return eq if h is None else names[geometry.sector_index(h - shift, n)]

    converse = {names[k]: names[(k + n // 2) % n] for k in range(n // 2)} | {eq: eq}
    return Calculus(name, names + (eq,), converse, compute, doc,
                    regions={r: (k * width + shift, width) for k, r in enumerate(names)})


def _rcc8(a: Body, b: Body) -> str:
    return geometry.rcc8(a.box_m, b.box_m)


def _qdist(a: Body, b: Body) -> str | None:
    ratio = max(geometry.gap(a.box_m, b.box_m), 0.0) / max(a.footprint, b.footprint, 1e-6)
    if ratio <= QD_CLOSE:
        return "qd_close"
    return "qd_far" if ratio > QD_MID else None


# Distance at a finer grain than `qdist`: bands of the same gap ratio, their lower edges below
# (the first band from touching). `QD_CLOSE` and `QD_MID` are edges, so each of qdist's
# relations is a run of bands, as the cones are runs of the finest sectors; the bands widen
# with the distance, as what people tell apart does.
BAND_EDGES = (0.0, 0.05, 0.1, 0.15, 0.2, 0.3, QD_CLOSE, 0.55, 0.75, 1.0, 1.35, 1.8, 2.5, QD_MID, 5.0, 7.0)


def bands(name: str, gap: Callable[[Body, Body], float], doc: str) -> Calculus:
    """A distance calculus: `gap` (metres) over the larger footprint, in the bands of
    `BAND_EDGES`: relations `<name>_00` ... Like qdist, nothing between one object and another
    it lies over (how far apart is then no distance on the table)."""
    names = tuple(f"{name}_{k:02d}" for k in range(len(BAND_EDGES)))

    def compute(a: Body, b: Body) -> str | None:
        if not _apart(a, b):
            return None
        ratio = max(gap(a, b), 0.0) / max(a.footprint, b.footprint, 1e-6)
        return names[sum(1 for e in BAND_EDGES[1:] if ratio > e)]

    return Calculus(name, names, {r: r for r in names}, compute, doc)


def _disc_gap(a: Body, b: Body) -> float:
    """The gap two discs of the objects' footprints leave: the same whichever side one stands
    on. qdist's gap (the widest empty band along an axis) shrinks on the diagonals: two spheres
    0.14 m apart leave 4 cm side by side and nothing corner to corner. Neither is the right
    measure for every teacher; a word's examples pick (memory/reach.py)."""
    (ax, ay), (bx, by) = geometry.centre(a.box_m), geometry.centre(b.box_m)
    return math.hypot(ax - bx, ay - by) - (a.footprint + b.footprint) / 2


def _qsize(a: Body, b: Body) -> str | None:
    if a.footprint > b.footprint * SZ_SAME_RATIO:
        return "sz_larger"
    if b.footprint > a.footprint * SZ_SAME_RATIO:
        return "sz_smaller"
    return None


def _stack(a: Body, b: Body) -> str | None:
    if geometry.gap(a.box_m, b.box_m) >= 0.0 or a.level == b.level:
        return None
    return RESTS_ON if a.level > b.level else "st_under"


CDC = Calculus(
    "cdc",
    geometry.CARDINALS + (geometry.CDC_EQ,),
    {"n": "s", "ne": "sw", "e": "w", "se": "nw", geometry.CDC_EQ: geometry.CDC_EQ},
    _cdc,
    "cardinal direction of a's centre from b's",
    regions={r: (h, 45.0) for r, h in zip(("e", "ne", "n", "nw", "w", "sw", "s", "se"), range(0, 360, 45))},
)
CONE = Calculus(
    "cone",
    geometry.CONES + (geometry.CONE_EQ,),
    {"cone_n": "cone_s", "cone_e": "cone_w", geometry.CONE_EQ: geometry.CONE_EQ},
    _cone,
    "cone-based direction of a's centre from b's",
    regions={"cone_e": (0.0, 90.0), "cone_n": (90.0, 90.0), "cone_w": (180.0, 90.0), "cone_s": (270.0, 90.0)},
)
# Finer grains of direction, perceived beside the cones and the sectors (`senses("all")`):
# 16 sectors of 22.5 degrees, and 64 of 5.625 (the finest: every coarser region is a run of
# its sectors, and a word's edge can be learned to within a few degrees).
D16 = sectors("d16", 16, "direction of a's centre from b's, 16 sectors")
D64 = sectors("d64", 64, "direction of a's centre from b's, 64 sectors (edges on the coarser ones')",
              edge_on_east=True)
RCC8 = Calculus(
    "rcc8",
    geometry.RCC8,
    {"dc": "dc", "ec": "ec", "po": "po", "eq": "eq", "tpp": "tppi", "ntpp": "ntppi"},
    _rcc8,
    "region connection of the two footprints",
    common=frozenset({"dc"}),
)
# Objects in contact, touching or one over another: every topology relation but two objects
# apart. Things in contact are seen as one group (Gestalt connectedness): what a word for a
# group of objects is taught on among other objects (agent/composite.py).
CONTACT: frozenset[str] = frozenset(RCC8.relations) - RCC8.common
QDIST = Calculus(
    "qdist",
    ("qd_close", "qd_far"),
    {"qd_close": "qd_close", "qd_far": "qd_far"},
    _qdist,
    "gap between footprints relative to the larger one",
)
QSIZE = Calculus(
    "qsize",
    ("sz_larger", "sz_smaller"),
    {"sz_larger": "sz_smaller"},
    _qsize,
    "a's measured footprint against b's",
    static=True,
)
DBAND = bands("dband", lambda a, b: geometry.gap(a.box_m, b.box_m),
              "gap between footprints relative to the larger one, in bands (`BAND_EDGES`)")
DGAP = bands("dgap", _disc_gap,
             "centres' distance less half of each footprint, relative to the larger one, in bands (`BAND_EDGES`)")
RESTS_ON = "st_on"  # the stacking relation a placement can make true: put a onto b
STACK = Calculus("stack", (RESTS_ON, "st_under"), {RESTS_ON: "st_under"}, _stack, "a rests on b / b rests on a")

CALCULI: tuple[Calculus, ...] = (CDC, CONE, D16, D64, RCC8, QDIST, DBAND, DGAP, QSIZE, STACK)
_DECLARED = [0]  # how many times `declare` changed CALCULI (what is read from it is read again)


def declare(*calcs: Calculus) -> None:
    """Add calculi of one's own, for good (an `AILEEN_DOMAIN` module: the package is not
    edited): every scene's facts hold their relations, the planner reads their converses, a
    placement samples them, and the agent perceives them (a calculus that is not a direction
    is perceived by every sense; a direction one joins no `--senses` family). A name or a
    relation already declared, a name clingo cannot read, a relation named as a predicate of
    the planner, the memory or a percept (`_reserved`), a converse outside the calculus, no
    relations or no compute function is a `UserError` naming the calculus. Its compute is
    checked as it runs (`_Checked`): a relation it returns that it did not declare, or an
    error inside it, is one line naming the function, never a traceback from clingo."""
    global CALCULI
    from aileen.errors import UserError

    names = {c.name for c in CALCULI}
    taken = {r for c in CALCULI for r in c.relations}
    reserved, prefixes = _reserved(), _symbol_prefixes()
    for c in calcs:
        if not isinstance(c, Calculus):
            raise UserError(f"{c!r}: expected a calculi.Calculus")
        if c.name in names:
            raise UserError(f"calculus {c.name!r} is already declared")
        if not isinstance(c.name, str) or not DECLARED_NAME.fullmatch(c.name):
            raise UserError(f"calculus {c.name!r}: expected a name of lowercase letters a-z, digits and '_', a "
                            f"letter first (a clingo name)")
        if not callable(c.compute):
            raise UserError(f"calculus {c.name!r}: compute {c.compute!r}: expected a function (a, b) -> relation "
                            f"or None")
        if not c.relations or len(set(c.relations)) != len(c.relations):
            raise UserError(f"calculus {c.name!r}: expected one relation at least, each once (got "
                            f"{', '.join(c.relations) or 'none'})")
        for r in c.relations:
            if r in taken:
                raise UserError(f"calculus {c.name!r}: relation {r!r} is already declared")
            if not DECLARED_NAME.fullmatch(r):
                raise UserError(f"calculus {c.name!r}: relation {r!r} must be lowercase letters a-z, digits "
                                f"and '_', a letter first (a clingo name)")
            if r in reserved or r.startswith(prefixes):
                raise UserError(f"calculus {c.name!r}: relation {r!r} is a predicate of the planner, the memory "
                                f"or perception, or a percept's or a concept's symbol ({', '.join(prefixes)}...); "
                                f"expected a name of its own")
        outside = [q for pair in c.converse.items() for q in pair if q not in c.relations]
        if outside:
            raise UserError(f"calculus {c.name!r}: its converse names {outside[0]!r}; expected one of its relations "
                            f"({', '.join(c.relations)})")
        names.add(c.name)
        taken |= set(c.relations)
    CALCULI = CALCULI + tuple(dataclasses.replace(c, compute=_Checked(c.name, frozenset(c.relations), c.compute))
                              for c in calcs)
    _DECLARED[0] += 1


def _reserved() -> frozenset[str]:
    """The names a relation of one's own may not take: the memory's predicates
    (`predicates.MEMORY`: isa, h, ...), the fluents of the action models (held, pointed,
    moved, ...: `actions.FLUENTS`, declared before any of one's own), and every predicate the
    shipped ASP programs use (holds, occurs, rel, ...: `predicates.planner`)."""
    from aileen.domain import predicates

    actions = sys.modules.get("aileen.domain.actions")  # (it imports this module)
    fluents = set(getattr(actions, "FLUENTS", {})) | {MOVED}
    return predicates.MEMORY | predicates.planner() | fluents


def _symbol_prefixes() -> tuple[str, ...]:
    """How a percept's symbol and a concept's begin (`cv_red`, `r_left_of`), read from where
    they are declared: a relation so named reads as one of them."""
    from aileen.domain import predicates
    from aileen.world import catalog

    return catalog.percept(""), predicates.CONCEPT_PREFIX


@dataclass(frozen=True)
class _Checked:
    """A declared calculus's compute, whose answer is one of its relations or None, and whose
    failure is a `UserError` naming the user's function (a relation "Zzz" stopped a lesson with
    clingo's 'parsing failed'; an error inside it a traceback). A class, not a closure: a
    calculus may be pickled to a worker as its function is."""

    calculus: str
    relations: frozenset[str]
    compute: Callable[[Body, Body], str | None]

    def __call__(self, a: Body, b: Body) -> str | None:
        from aileen.domain.guard import failed, named
        from aileen.errors import UserError

        try:
            r = self.compute(a, b)
        except UserError:
            raise
        except Exception as exc:  # noqa: BLE001 - the user's own function: named, not a traceback
            raise failed(f"calculus {self.calculus!r}: its compute", self.compute, exc) from None
        if r is not None and r not in self.relations:
            raise UserError(f"calculus {self.calculus!r}: its compute {named(self.compute)} returned {r!r}; "
                            f"expected one of {', '.join(sorted(self.relations))} or None")
        return r


def version() -> int:
    """Changes when a calculus is declared (tables derived from `CALCULI` are made again)."""
    return _DECLARED[0]


# The calculi that give a fact for every pair (the others report only the marked cases).
EXHAUSTIVE: frozenset[str] = frozenset({CDC.name, CONE.name, RCC8.name})
# The senses of direction an agent may have: one grain (the cones, the paper's sectors) or all
# of them at once, the word's grain then learned from its examples (memory/extent.py).
DIRECTIONS: dict[str, tuple[Calculus, ...]] = {"cones": (CONE,), "sectors": (CDC,), "all": (CONE, CDC, D16, D64)}
# Finer grains of the other senses, perceived with every grain of direction (`senses("all")`)
# and by no fixed sense: distance in bands, measured two ways (qdist's gap, and the gap of
# discs), a word's examples picking the measure (memory/reach.py). The first is qdist's.
FINER: tuple[Calculus, ...] = (DBAND, DGAP)
DEFAULT_DIRECTIONS = "cones"  # perception's own scene facts, when no senses are given
AGENT_DIRECTIONS = "all"  # an agent's, unless --senses says otherwise (AgentParams)
FINEST = D64  # the finest grain: every other direction region is a run of its sectors


def direction_calculi() -> tuple[Calculus, ...]:
    """Every declared direction calculus, coarsest first."""
    return tuple(sorted((c for c in CALCULI if c.is_direction), key=lambda c: len(c.regions)))


def is_direction(relation: str) -> bool:
    """Is `relation` a direction (of any grain, `*_eq` included)?"""
    c = calculus_of(relation)
    return c is not None and c.is_direction


def is_static(relation: str) -> bool:
    """Is `relation` one no move changes (a `static` calculus: which of two is larger)? Such a
    fact describes the objects, never a goal an action can reach."""
    c = calculus_of(relation)
    return c is not None and c.static


def is_finer(relation: str) -> bool:
    """Is `relation` of a finer grain of a sense other than direction (`FINER`: a distance
    band)? Like the finer directions, such facts are read as regions by the size principle,
    never matched one by one."""
    c = calculus_of(relation)
    return c is not None and c in FINER


def senses(directions: str = DEFAULT_DIRECTIONS, *, finer: bool = True) -> tuple[Calculus, ...]:
    """The calculi an agent perceives: every calculus that is not a direction, the direction
    calculi of `directions` ("cones", "sectors" or "all"), and with every grain of direction
    the finer grains of the other senses (`FINER`), unless `finer` is off."""
    if directions not in DIRECTIONS:
        raise ValueError(f"unknown direction sense {directions!r}; expected one of {', '.join(DIRECTIONS)}")
    own = {c.name for c in DIRECTIONS[directions]}
    if finer and len(DIRECTIONS[directions]) > 1:
        own |= {c.name for c in FINER}
    return tuple(c for c in CALCULI if not (c.is_direction or c in FINER) or c.name in own)

# Motion, a property of one object across two frames: `moved(o)` when its centre shifted by more
# than MOVE_MIN metres since the agent last saw it (it was carried, pushed or shoved). It holds
# in the frame right after the motion only; a trace thereby says who moved.
MOVED = "moved"
MOVE_MIN = 0.015


def calculus_by_name(name: str) -> Calculus:
    return next(c for c in CALCULI if c.name == name)


def calculus_of(relation: str) -> Calculus | None:
    for c in CALCULI:
        if relation in c.relations:
            return c
    return None


def pair_relations(a: Body, b: Body, calculi: tuple[Calculus, ...] | None = None) -> list[str]:
    """The relation of a to b in each calculus (default: the default `senses()`), in calculus order."""
    out = []
    for c in senses() if calculi is None else calculi:
        r = c.compute(a, b)
        if r is not None:
            out.append(r)
    return out



def is_transitive(relation: str) -> bool:
    """Does `relation` compose with itself: a P of b and b P of c put a P of c? So for each
    direction whose region (`Calculus.regions`) is narrower than a half-plane: the region is a
    convex sector, and the sum of two offsets in it stays in it. The planner reads it so that
    it plans no place that puts three objects in directions that cannot all hold."""
    c = calculus_of(relation)
    return c is not None and relation in c.regions and c.regions[relation][1] < 180.0


def asp_facts() -> list[Term]:
    """The calculi as facts for the ASP action models: `calculus(C,P)` for each relation,
    `converse(P,Q)` both ways, `static(P)` for relations no move changes, `transitive(P)` for
    those that compose with themselves (`is_transitive`)."""
    out = []
    for c in CALCULI:
        for r in c.relations:
            out.append(fn("calculus", c.name, r))
            out.append(fn("converse", r, c.converse_of(r)))
            if c.static:
                out.append(fn("static", r))
            if is_transitive(r):
                out.append(fn("transitive", r))
    return out
