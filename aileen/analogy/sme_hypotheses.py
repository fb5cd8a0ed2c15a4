"""SME's match hypotheses (MHs) for one comparison, with their structural consistency.

Why a module of its own: the MH table is the comparison's state: built once from two
prepared descriptions (steps 1 and 2 of `sme.py`'s overview: pairing expressions by
functor, aligning their arguments, and carrying incompleteness and one-to-one
inconsistency up to parents), then only read by the evaluation and merge
(`sme_merge._Engine`, which extends this class). SME's required correspondences are
applied here too, since they only drop MHs. Split from `sme.py`.
"""

from __future__ import annotations

from aileen.analogy.sme_descriptions import Params, _Desc, is_entity
from aileen.terms import Term

__all__: list[str] = []


class _Hypotheses:
    """The MH tables of one comparison, indexed by MH id, and how they are built."""

    def __init__(self, base: _Desc, target: _Desc, params: Params,
                 require: "dict[Term, Term] | None" = None) -> None:
        self.require = dict(require) if require else {}
        self.b = base
        self.t = target
        self.p = params
        # MH tables, indexed by id.
        self.mb: list[Term] = []
        self.mt: list[Term] = []
        self.children: list[tuple[int, ...]] = []
        self.parents: list[list[int]] = []
        self.ok: list[bool] = []
        self.local: list[float] = []
        self.order: list[int] = []
        self.corr: list[dict[Term, Term] | None] = []  # base->target over descendants (ok MHs)
        self.index: dict[tuple[Term, Term], int] = {}
        self.functor_pairs: set[tuple] = set()

    # -- MH creation
    def _alignable(self, ba: Term, ta: Term) -> bool:
        be, te = is_entity(ba), is_entity(ta)
        if be or te:
            return be and te
        if ba.name == ta.name and len(ba.args) == len(ta.args):
            return True
        return self.b.is_function(ba) and self.t.is_function(ta)

    def _new(self, bi: Term, ti: Term, order: int, local: float) -> int:
        i = len(self.mb)
        self.mb.append(bi)
        self.mt.append(ti)
        self.children.append(())
        self.parents.append([])
        self.ok.append(True)
        self.local.append(local)
        self.order.append(order)
        self.corr.append(None)
        self.index[(bi, ti)] = i
        return i

    def _make(self, bi: Term, ti: Term) -> int:
        i = self.index.get((bi, ti))
        if i is not None:
            return i
        if is_entity(bi):
            i = self._new(bi, ti, 0, 0.0)
            self.corr[i] = {bi: ti}
            return i
        p = self.p
        if bi.name == ti.name:
            local = p.same_functor
        elif self.b.is_function(bi):
            local = p.same_function
        else:  # pragma: no cover - callers only pair alignable items
            local = p.same_functor
        self.functor_pairs.add((bi.name, ti.name))
        order = max(self.b.order[bi], self.t.order[ti])
        i = self._new(bi, ti, order, local)
        if len(bi.args) != len(ti.args) or not all(
            self._alignable(ba, ta) for ba, ta in zip(bi.args, ti.args)
        ):
            self.ok[i] = False
            return i
        kids: list[int] = []
        for ba, ta in zip(bi.args, ti.args):
            c = self._make(ba, ta)
            if c not in kids:
                kids.append(c)
        self.children[i] = tuple(kids)
        for c in kids:
            self.parents[c].append(i)
        # Completeness and consistency propagate upwards.
        b2t: dict[Term, Term] = {bi: ti}
        t2b: dict[Term, Term] = {ti: bi}
        ok = True
        for c in kids:
            if not self.ok[c]:
                ok = False
                break
            for x, y in self.corr[c].items():  # type: ignore[union-attr]
                if b2t.get(x, y) is not y or t2b.get(y, x) is not x:
                    ok = False
                    break
                b2t[x] = y
                t2b[y] = x
            if not ok:
                break
        self.ok[i] = ok
        self.corr[i] = b2t if ok else None
        return i

    def _generate(self) -> None:
        tix = self.t.by_functor
        for be in self.b.exprs:
            for te in tix.get((be.name, len(be.args)), ()):
                self._make(be, te)

    def _apply_required(self) -> None:
        """Drop every MH whose correspondences contradict a required one."""
        req_b2t = self.require
        req_t2b = {y: x for x, y in req_b2t.items()}
        for i, corr in enumerate(self.corr):
            if not self.ok[i] or corr is None:
                continue
            for x, y in corr.items():
                if req_b2t.get(x, y) is not y or req_t2b.get(y, x) is not x:
                    self.ok[i] = False
                    self.corr[i] = None
                    break
