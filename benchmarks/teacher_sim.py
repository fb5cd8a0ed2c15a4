"""An offline simulation of the spatial teacher and wide protocols, for trying extent priors fast.

Why: the real experiment (`aileen experiment spatial --protocol teacher|wide`) runs the agent,
physics and clingo, about 15 s for 10 trials, and 10 trials leave a point or two of noise on
the headline. The direction of a relation word, though, is decided by `memory/extent.py` alone,
from per-fine-sector counts of examples and near misses. This script replays the two
protocols on those counts only (no vision, no SAGE, no clingo), over hundreds of trials, so a
change to the extent model's prior or likelihood can be compared in seconds before the real
experiment decides. Not a published figure.

What it copies from the real protocols:

* teacher (`experiments/teacher.py`): the teacher is drawn by `teacher.draw_teacher`; 18
  informs spread over the words, laid uniformly in angle within h - 1 degrees of the axis, and
  6 near misses 2-9 degrees beyond the edge on either side (each after its word's first
  inform); exams of 12 generality items (inside) and 12 specificity items (8 at the edge, 4 far:
  the far ones are always refused once a region is learned, so they count as right); the ideal
  observer is `ideal.IdealObserver` given the same angles.
* wide (`experiments/wide.py`): 20 informs, balanced over the four cardinal words, laid within
  40 degrees of the axis; 5 generality items within 40 degrees; specificity items are far and
  always right; the one-shot oracle knows a word once taught.
* the agent (`agent/grounding.py`, `agent/feedback.py`): an inform is stored when the word does
  not yet hold in its sector, or when it would tell the word something (`extent.news`: change an
  answer, or hold where the word is not yet sure); a near
  miss is always stored (told `wrong` after a yes; a no the trainer lets stand).

Where it differs: perception is the exact fine sector of the drawn angle (ground-truth vision
reads it after physics settles, which moves an object little); the exam items are drawn once
per trial. Usage:

    PYTHONPATH=. python benchmarks/teacher_sim.py --trials 300 [--set NAME=VALUE ...]

`--set` assigns a module constant of `memory/extent.py` (a Python literal) before the run.
Diagnostic learners in place of ours: `--generic LO HI` (the ideal observer's inference told
each word's axis, its half-angle uniform in [LO, HI]) and `--hprior LO-HI:W ...` (told the axis,
a prior over the half-angle of its own: a mixture of uniform parts, on a grid;
`benchmarks/grain_frontier.py` runs a set of them); `--blind` (the ideal observer not told
which word is which: the teacher family's axes and half-angle ranges, each word any of them)
and `--symmetric CENTRES WIDEST` (a generic learner with the trainer's layout likelihood:
regions symmetric about one of CENTRES evenly spaced directions, half-angle up to WIDEST).
These last two say how much of the gap to the ideal observer is the word's name and how much
the family's shape (docs/results.md, "Stop 52: what the 95 % target asks of a learner").
"""

from __future__ import annotations

import ast
import math
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_args  # noqa: E402

from aileen.domain import calculi  # noqa: E402
from aileen.experiments import ideal, teacher  # noqa: E402
from aileen.memory import extent  # noqa: E402

N = len(calculi.FINEST.regions)
STORE_ALL = False  # diagnostic: store every inform (the agent stores only news)
W = 360.0 / N


def sector(angle: float) -> int:
    """The fine sector (index as `extent` counts them) of a direction in degrees."""
    return int(math.floor((angle % 360.0) / W)) % N


OVERHYP_ALPHA: float | None = None  # a width overhypothesis shared by a trial's words (None: off)


def _size_prior(others: list[tuple[tuple[int, ...], tuple[int, ...]]]) -> np.ndarray:
    """The log prior over regions given the other words' evidence: a Polya urn over region
    sizes (a new word has the size of one of the others, or a size from the base prior)."""
    member, _size, logp = extent.hypotheses()
    sizes = member.sum(axis=1)
    p0 = np.exp(logp)
    p0_size = np.bincount(sizes, weights=p0, minlength=N + 1)
    mix = OVERHYP_ALPHA * p0
    for pos, neg in others:
        post = extent.posterior(logp, pos, neg)
        pi = np.bincount(sizes, weights=post, minlength=N + 1)
        mix = mix + pi[sizes] * p0 / p0_size[sizes]
    return np.log(mix / mix.sum())


@dataclass
class Word:
    """The learner's evidence for one word (per-fine-sector counts)."""

    pos: list[int] = field(default_factory=lambda: [0] * N)
    neg: list[int] = field(default_factory=lambda: [0] * N)
    lexicon: list = field(default_factory=list)

    def known(self) -> bool:
        return any(self.pos)

    def region(self, pos=None) -> np.ndarray:
        pos = self.pos if pos is None else pos
        if OVERHYP_ALPHA is None:
            return extent.predictive(pos, self.neg)
        others = [(tuple(w.pos), tuple(w.neg)) for w in self.lexicon if w is not self and w.known()]
        member, _s, _l = extent.hypotheses()
        return extent.posterior(_size_prior(others), tuple(pos), tuple(self.neg)) @ member

    def says(self, angle: float) -> bool:
        if not self.known():
            return False
        return bool(self.region()[sector(angle)] >= extent.ACCEPT)

    def inform(self, angle: float) -> None:
        k = sector(angle)
        if self.known() and not STORE_ALL and self.says(angle) and not self.news(k):
            return
        self.pos[k] += 1

    def news(self, k: int) -> bool:
        if OVERHYP_ALPHA is None:
            return extent.news(self.pos, self.neg, k)
        more = list(self.pos)
        more[k] += 1
        region = self.region()
        return bool(((region >= extent.ACCEPT) != (self.region(more) >= extent.ACCEPT)).any()
                    or region[k] < extent.SURE)

    def near_miss(self, angle: float) -> None:
        self.neg[sector(angle)] += 1


def _inside(rng: np.random.Generator, axis: float, lay: float) -> float:
    return axis + rng.uniform(-lay, lay)


def _edge(rng: np.random.Generator, axis: float, h: float) -> float:
    off = h + rng.uniform(*teacher.NEAR_MISS_BAND)
    return axis + (off if rng.random() < 0.5 else -off)


GENERIC: tuple[float, float] | None = None  # diagnostic: the learner is an ideal observer with this half-angle range


class GenericIdeal:
    """Diagnostic learner: the ideal observer's inference, knowing the axis but not the family."""

    def __init__(self, axis: float) -> None:
        p = ideal.WordPrior("w", axis, GENERIC, teacher.LAY_MARGIN, teacher.NEAR_MISS_BAND,
                            teacher.LAY_MARGIN - teacher.CLEAR_MARGIN)
        self.post = ideal.Posterior(p)

    def known(self) -> bool:
        return bool(self.post.positives)

    def says(self, angle: float) -> bool:
        return self.known() and self.post.p_holds(ideal.offset(angle, self.post.prior.axis)) >= 0.5

    def inform(self, angle: float) -> None:
        self.post.positives.append(ideal.offset(angle, self.post.prior.axis))

    def near_miss(self, angle: float) -> None:
        self.post.misses.append(ideal.offset(angle, self.post.prior.axis))


HPRIOR: list[tuple[float, float, float]] | None = None  # diagnostic: (lo, hi, weight) uniform parts of a prior over h
H_GRID = np.arange(0.025, 90.0, 0.05)
HPRIOR_FLOOR = 0.01


class PriorIdeal:
    """Diagnostic learner: Bayesian inference over a word's half-angle h, knowing the axis and
    the trainer's layout (as the ideal observer does) but with a prior over h of its own
    (`HPRIOR`, a mixture of uniform parts; `--hprior`), on a grid. With `HPRIOR` the teacher's
    own family mixture this is the ideal observer told the axis but not the family."""

    def __init__(self, axis: float) -> None:
        self.axis = axis
        dens = np.zeros_like(H_GRID)
        parts = HPRIOR or []
        for lo, hi, wt in parts:
            dens += wt * ((H_GRID >= lo) & (H_GRID <= hi)) / (hi - lo)
        # a floor: HPRIOR_FLOOR of the mass uniform over every h, so that no evidence outside
        # the parts empties the posterior (a mis-specified prior still learns)
        dens = (1 - HPRIOR_FLOOR) * dens / sum(w for _l, _h, w in parts) + HPRIOR_FLOOR / H_GRID[-1]
        self.logp = np.log(dens + 1e-300)
        self.n = 0

    def known(self) -> bool:
        return self.n > 0

    def says(self, angle: float) -> bool:
        if not self.known():
            return False
        t = ideal.offset(angle, self.axis)
        p = np.exp(self.logp - self.logp.max())
        return bool(p[H_GRID > t].sum() >= 0.5 * p.sum())

    def inform(self, angle: float) -> None:
        t = ideal.offset(angle, self.axis)
        lay, tol = teacher.LAY_MARGIN, teacher.LAY_MARGIN - teacher.CLEAR_MARGIN
        ok = H_GRID - lay >= t - tol
        self.logp = np.where(ok, self.logp - np.log(np.maximum(H_GRID - lay, 1e-3)), -np.inf)
        self.n += 1

    def near_miss(self, angle: float) -> None:
        f = ideal.offset(angle, self.axis)
        b0, b1 = teacher.NEAR_MISS_BAND
        tol = teacher.LAY_MARGIN - teacher.CLEAR_MARGIN
        ok = (H_GRID >= f - b1 - tol) & (H_GRID <= min(f - b0 + tol, f))
        # a miss outside the band is read as an exclusion only, as the ideal observer does
        self.logp = np.where(ok, self.logp, -np.inf)


class MixtureIdeal:
    """Diagnostic learner not told which axis a word has: Bayesian inference over (axis, h),
    the axis one of a set, each axis with a prior over h uniform on a grid, given the trainer's
    layout (positives uniform within h - lay of the axis on either side; near misses h + band
    beyond the edge). Two uses: `blind_hypotheses` (the teacher family's axes and half-angle
    ranges: the ideal observer *not told which word is which*) and `symmetric_hypotheses` (a
    generic learner: regions symmetric about one of n evenly spaced directions, any half-angle
    up to a bound)."""

    def __init__(self, hyps: list[tuple[float, np.ndarray, np.ndarray]]) -> None:
        self.hyps = hyps
        self.logp = [lp.copy() for _a, _h, lp in hyps]
        self.n = 0

    def known(self) -> bool:
        return self.n > 0

    def _see(self, angle: float, positive: bool) -> None:
        lay, tol = teacher.LAY_MARGIN, teacher.LAY_MARGIN - teacher.CLEAR_MARGIN
        b0, b1 = teacher.NEAR_MISS_BAND
        for i, (axis, h, _lp) in enumerate(self.hyps):
            t = ideal.offset(angle, axis)
            if positive:  # density per degree of direction: 1 / (2 (h - lay)) inside
                like = np.where(t <= h - lay + tol, -np.log(2.0 * np.maximum(h - lay, 1e-3)), -np.inf)
            else:
                like = np.where((t >= h + b0 - tol) & (t <= h + b1 + tol) & (t > h), -math.log(2.0 * (b1 - b0)), -np.inf)
            self.logp[i] = self.logp[i] + like

    def inform(self, angle: float) -> None:
        self._see(angle, True)
        self.n += 1

    def near_miss(self, angle: float) -> None:
        self._see(angle, False)

    def says(self, angle: float) -> bool:
        top = max(float(lp.max()) for lp in self.logp)
        if not self.n or not np.isfinite(top):
            return False
        yes = total = 0.0
        for (axis, h, _lp), lp in zip(self.hyps, self.logp):
            w = np.exp(lp - top)
            total += float(w.sum())
            yes += float(w[h > ideal.offset(angle, axis)].sum())
        return yes >= 0.5 * total


def blind_hypotheses(step: float = 0.05) -> list[tuple[float, np.ndarray, np.ndarray]]:
    """The teacher family as the ideal observer knows it, less the word: every family's axes,
    each family weighted by how many of a trial's words it draws on average (`teacher`: every
    wide word, and `EXTRA_WORDS` more from the extra families alike), h uniform in its range."""
    extra = float(np.mean(teacher.EXTRA_WORDS)) / len(teacher.EXTRA_FAMILIES)
    out = []
    for name, fam in teacher.FAMILIES.items():
        count = extra if name in teacher.EXTRA_FAMILIES else float(len(fam.axes))
        axes = sorted(set(fam.axes.values()))
        h = np.arange(fam.half_angle[0] + step / 2, fam.half_angle[1], step)
        out += [(a, h, np.full(len(h), math.log(count / len(axes) / len(h)))) for a in axes]
    return out


def symmetric_hypotheses(centres: int, widest: float, step: float = 0.25) -> list[tuple[float, np.ndarray, np.ndarray]]:
    """A generic learner's regions: symmetric about one of `centres` evenly spaced directions
    (east first), half-angle uniform from 1 degree to `widest`."""
    h = np.arange(1.0 + step / 2, widest, step)
    return [(k * 360.0 / centres, h, np.full(len(h), -math.log(centres * len(h)))) for k in range(centres)]


MIXTURE: list[tuple[float, np.ndarray, np.ndarray]] | None = None  # diagnostic: a MixtureIdeal's hypotheses

# `--off-axis`: a teacher who may also say a word centred 30 degrees off a cardinal axis (a
# band 5-15 degrees each side), drawn as the other extra families are: a learner that
# assumes every word centred on an axis or a diagonal fails there, where the teacher protocol
# as published could not tell
OFF_AXIS = teacher.Family("off-axis", {"zup of": 30.0, "blick of": 120.0, "dax of": 210.0, "wug of": 300.0},
                          (5.0, 15.0))


def _learner(axis: float, lexicon: list) -> "Word | GenericIdeal | PriorIdeal | MixtureIdeal":
    if MIXTURE:
        return MixtureIdeal(MIXTURE)
    if HPRIOR:
        return PriorIdeal(axis)
    if GENERIC:
        return GenericIdeal(axis)
    return Word(lexicon=lexicon)


def teacher_trial(rng: np.random.Generator) -> dict[str, np.ndarray]:
    """One teacher trial: per family, [ours gen, ours spec, ideal gen, ideal spec, gen items,
    spec items] summed over the lessons."""
    who = teacher.draw_teacher(rng)
    words = who.words()
    plan_lessons = teacher.training_lessons(rng, who)
    plan = [("inform" if ls.signal == "inform" else "miss", ls.relation) for ls in plan_lessons]
    gen = [(w, _inside(rng, who.sense(w).axis, who.sense(w).half_angle - teacher.LAY_MARGIN))
           for w in teacher._spread(rng, words, teacher.GEN_ITEMS)]
    edge = [(w, _edge(rng, who.sense(w).axis, who.sense(w).half_angle))
            for w in teacher._spread(rng, words, teacher.SPEC_EDGE_ITEMS)]
    far = teacher._spread(rng, words, teacher.SPEC_FAR_ITEMS)
    lex: list[Word] = []
    learner = {w: _learner(who.sense(w).axis, lex) for w in words}
    lex.extend(learner.values())
    obs = ideal.IdealObserver(ideal.priors(who.family_of()))
    fams = {w: who.sense(w).family for w in words}
    out = {f: np.zeros(6) for f in teacher.FAMILIES}
    for kind, w in plan:
        s = who.sense(w)
        if kind == "inform":
            a = _inside(rng, s.axis, s.half_angle - teacher.LAY_MARGIN)
            learner[w].inform(a)
            obs.see(w, a, True)
        else:
            a = _edge(rng, s.axis, s.half_angle)
            learner[w].near_miss(a)
            obs.see(w, a, False)
        for x, a in gen:
            o = out[fams[x]]
            o[0] += learner[x].says(a)
            post = obs.posteriors[x]
            o[2] += bool(post.positives) and obs.p_holds(x, a) >= 0.5
            o[4] += 1
        for x, a in edge:
            o = out[fams[x]]
            o[1] += not learner[x].says(a)
            post = obs.posteriors[x]
            o[3] += not (post.positives and obs.p_holds(x, a) >= 0.5)
            o[5] += 1
        for x in far:
            o = out[fams[x]]
            o[1] += 1
            o[3] += 1
            o[5] += 1
    return out


WIDE_AXES = (0.0, 90.0, 180.0, 270.0)
WIDE_LAY = 40.0


def wide_trial(rng: np.random.Generator, informs: int = 20, items: int = 5) -> np.ndarray:
    """One wide trial: [ours gen, oracle gen, gen items] summed over the lessons."""
    words = [WIDE_AXES[i % 4] for i in range(informs)]
    words = [words[i] for i in rng.permutation(informs)]
    exam = [(ax, _inside(rng, ax, WIDE_LAY)) for ax in rng.choice(WIDE_AXES, size=items)]
    lex: list[Word] = []
    learner = {ax: _learner(ax, lex) for ax in WIDE_AXES}
    lex.extend(learner.values())
    out = np.zeros(3)
    for ax in words:
        learner[ax].inform(_inside(rng, ax, WIDE_LAY))
        for x, a in exam:
            out[0] += learner[x].says(a)
            out[1] += learner[x].known()
            out[2] += 1
    return out


def ratio(num: float, den: float) -> float:
    """num / den, or NaN (printed "n/a") when den is 0: a family no teacher drew in a short
    run has no exam items, and NumPy would warn and print nan."""
    return float(num / den) if den else math.nan


def show(value: float) -> str:
    """A figure of `run`, one decimal, "n/a" where nothing was measured."""
    return "n/a" if math.isnan(value) else f"{value:.1f}"


def run(trials: int, seed: int) -> dict[str, float]:
    """Per family and in all, % right (ours and the ideal observer's) and ours as % of the
    ideal's; NaN for a family with no exam items (no teacher of it was drawn)."""
    rng = np.random.default_rng(seed)
    tot = {f: np.zeros(6) for f in teacher.FAMILIES}
    for _ in range(trials):
        for f, v in teacher_trial(rng).items():
            tot[f] += v
    res: dict[str, float] = {}
    allv = sum(tot.values())

    def pct(v: np.ndarray) -> float:
        ours = 0.5 * (ratio(v[0], v[4]) + ratio(v[1], v[5]))
        top = 0.5 * (ratio(v[2], v[4]) + ratio(v[3], v[5]))
        return 100.0 * ratio(ours, top)

    res["TEACHER"] = pct(allv)
    for f, v in tot.items():
        res[f] = pct(v)
        res[f + "_gen"] = 100.0 * ratio(v[0], v[4])
        res[f + "_spec"] = 100.0 * ratio(v[1], v[5])
        res[f + "_igen"] = 100.0 * ratio(v[2], v[4])
        res[f + "_ispec"] = 100.0 * ratio(v[3], v[5])
    w = np.zeros(3)
    for _ in range(trials):
        w += wide_trial(rng)
    res["WIDE_PROTOCOL"] = 100.0 * (w[0] / w[2] + 1.0) / (w[1] / w[2] + 1.0)
    return res


def parse_hprior(parts: list[str]) -> list[tuple[float, float, float]]:
    """`["4-20:0.2", "35-50:0.8"]` -> [(4, 20, 0.2), (35, 50, 0.8)] (a part without ":W" weighs 1)."""
    out = []
    for r in parts:
        span, _, w = r.partition(":")
        lo, _, hi = span.partition("-")
        out.append((float(lo), float(hi), float(w) if w else 1.0))
    return out


def configure(*, extent_set: dict[str, object] | None = None, hprior: list[tuple[float, float, float]] | None = None,
              generic: tuple[float, float] | None = None, overhyp: float | None = None, store_all: bool = False,
              mixture: list[tuple[float, np.ndarray, np.ndarray]] | None = None, off_axis: bool = False) -> None:
    """Set the simulated learner: extent module constants (`--set`), or one of the diagnostic
    learners; the extent model's caches are cleared so that its constants take effect."""
    global STORE_ALL, OVERHYP_ALPHA, GENERIC, HPRIOR, MIXTURE
    STORE_ALL, OVERHYP_ALPHA, GENERIC, HPRIOR, MIXTURE = store_all, overhyp, generic, hprior, mixture
    if off_axis and OFF_AXIS.name not in teacher.FAMILIES:  # the teacher module reads them per draw
        teacher.FAMILIES = {**teacher.FAMILIES, OFF_AXIS.name: OFF_AXIS}
        teacher.EXTRA_FAMILIES = (*teacher.EXTRA_FAMILIES, OFF_AXIS.name)
    for name, value in (extent_set or {}).items():
        setattr(extent, name, value)
    for fn in (extent.hypotheses, extent._near_miss_loglik, extent._flat_near_miss_loglik, extent._loglik,
               extent._predictive):
        fn.cache_clear()


def main() -> None:
    ap = bench_args.Parser(description=__doc__.splitlines()[0])
    ap.add_argument("--trials", type=bench_args.count, default=200)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--set", action="append", default=[], help="NAME=VALUE: an extent module constant")
    ap.add_argument("--overhyp", type=float, default=None, help="alpha of a shared width overhypothesis")
    ap.add_argument("--generic", type=float, nargs=2, default=None, help="diagnostic: an ideal learner, h in [LO, HI]")
    ap.add_argument("--hprior", nargs="+", default=None, metavar="LO-HI:W",
                    help="diagnostic: an ideal learner told each word's axis, prior over h a mixture of uniform parts")
    ap.add_argument("--store-all", action="store_true", help="diagnostic: store every inform")
    ap.add_argument("--blind", action="store_true",
                    help="diagnostic: the ideal observer not told which word is which (the family's axes and ranges)")
    ap.add_argument("--symmetric", nargs=2, type=float, default=None, metavar=("CENTRES", "WIDEST"),
                    help="diagnostic: regions symmetric about one of CENTRES directions, half-angle up to WIDEST")
    ap.add_argument("--off-axis", action="store_true",
                    help="diagnostic: teachers may also say words centred 30 degrees off an axis (a third extra family)")
    args = ap.parse_args()
    sets = {}
    for s in args.set:
        name, value = s.split("=", 1)
        sets[name] = ast.literal_eval(value)
    configure(off_axis=args.off_axis)  # first: --blind reads the families
    configure(extent_set=sets, hprior=parse_hprior(args.hprior) if args.hprior else None,
              generic=tuple(args.generic) if args.generic else None, overhyp=args.overhyp, store_all=args.store_all,
              mixture=blind_hypotheses() if args.blind else
              symmetric_hypotheses(int(args.symmetric[0]), args.symmetric[1]) if args.symmetric else None,
              off_axis=args.off_axis)
    res = run(args.trials, args.seed)
    print(" ".join(f"{k}={show(v)}" for k, v in res.items()))


if __name__ == "__main__":
    main()
