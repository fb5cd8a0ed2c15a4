"""SME's structural evaluation and greedy merge: the scores of the match hypotheses, the
kernels, the global mappings built from them, and their similarity (steps 3, 4 and 6 of
`sme.py`'s overview).

Why a module of its own: this is the part of SME that decides which interpretation wins
(trickle-down with one-to-one parent evidence, seed-and-gobble merge, the cutoff), and it
only reads the MH table that `sme_hypotheses._Hypotheses` builds; `_Engine` extends that
class so both halves share one table without copying it (the inner loops read its lists
as before the split). Split from `sme.py`.
"""

from __future__ import annotations

from aileen.analogy.sme_descriptions import _from_sme, is_entity
from aileen.analogy.sme_hypotheses import _Hypotheses
from aileen.analogy.sme_mappings import Mapping, MatchResult
from aileen.terms import Term

__all__: list[str] = []


class _Engine(_Hypotheses):
    """One comparison: its MHs (built by `_Hypotheses`), evaluated and merged into mappings."""

    # -- evaluation
    def _global_scores(self) -> list[float]:
        """Trickle-down with each MH taking evidence from a one-to-one set of its parents."""
        n = len(self.mb)
        score = [0.0] * n
        td = self.p.trickle_down
        ok = self.ok
        ids = [i for i in range(n) if ok[i]]
        ids.sort(key=lambda i: -self.order[i])
        mb, mt = self.mb, self.mt
        for i in ids:
            s = self.local[i]
            ps = [q for q in self.parents[i] if ok[q]]
            if len(ps) == 1:
                s += td * score[ps[0]]
            elif ps:
                ps.sort(key=lambda q: -score[q])
                used_b: set[Term] = set()
                used_t: set[Term] = set()
                for q in ps:
                    if mb[q] in used_b or mt[q] in used_t:
                        continue
                    used_b.add(mb[q])
                    used_t.add(mt[q])
                    s += td * score[q]
            score[i] = s
        return score

    def _descendants(self, i: int) -> list[int]:
        out = [i]
        seen = {i}
        k = 0
        while k < len(out):
            for c in self.children[out[k]]:
                if c not in seen:
                    seen.add(c)
                    out.append(c)
            k += 1
        return out

    def _mapping_score(self, ids: set[int]) -> float:
        td = self.p.trickle_down
        sc: dict[int, float] = {}
        total = 0.0
        for i in sorted(ids, key=lambda i: -self.order[i]):
            s = self.local[i]
            for q in self.parents[i]:
                if q in ids:
                    s += td * sc[q]
            sc[i] = s
            total += s
        return total

    def run(self) -> MatchResult:
        self._generate()
        if self.require:
            self._apply_required()
        n = len(self.mb)
        ok = self.ok
        # Roots: ok, non-entity-only-by-parent MHs without an ok parent.
        roots = [i for i in range(n) if ok[i] and not any(ok[q] for q in self.parents[i])]
        gscore = self._global_scores()
        kernels: list[tuple[float, int, list[int], dict[Term, Term]]] = []
        for r in roots:
            desc = self._descendants(r)
            kernels.append((sum(gscore[i] for i in desc), r, desc, self.corr[r]))  # type: ignore[arg-type]
        kernels.sort(key=lambda k: (-k[0], k[1]))
        mappings = self._merge(kernels)
        bs, ts = self.b.self_score, self.t.self_score
        denom = bs + ts
        out: list[Mapping] = []
        for score, ids, b2t, root_ids in mappings:
            sim = 0.0 if denom <= 0 else min(1.0, max(0.0, 2.0 * score / denom))
            fpairs = {(self.mb[i].name, self.mt[i].name) for i in ids if self.mb[i].args and not is_entity(self.mb[i])}
            ents = {str(_from_sme(x)): str(_from_sme(y)) for x, y in b2t.items() if is_entity(x)}
            pairs = {_from_sme(x): _from_sme(y) for x, y in b2t.items()}
            out.append(Mapping(
                score=score, similarity=sim, entities=ents, pairs=pairs,
                mh_count=len(ids) + len(fpairs),
                root_pairs=[(_from_sme(self.mb[i]), _from_sme(self.mt[i])) for i in root_ids],
                _b2t=b2t, _base=self.b, _target=self.t,
            ))
        return MatchResult(
            mappings=out,
            mh_count=n + len(self.functor_pairs),
            kernel_count=len(kernels),
            base_self_score=bs,
            target_self_score=ts,
        )

    def _merge(self, kernels: list) -> list[tuple[float, set[int], dict[Term, Term], list[int]]]:
        p = self.p
        results: list[tuple[float, set[int], dict[Term, Term], list[int]]] = []
        seeded: set[int] = set()  # kernel roots already inside some mapping
        seen_sets: set[frozenset[int]] = set()
        attempts = 0
        for k_index, (_, root, _desc, _corr) in enumerate(kernels):
            if len(results) >= p.max_mappings or attempts >= p.max_mappings:
                break
            if root in seeded:
                continue
            attempts += 1
            ids: set[int] = set()
            b2t: dict[Term, Term] = {}
            t2b: dict[Term, Term] = {}
            roots_in: list[int] = []
            order = [kernels[k_index]] + [k for j, k in enumerate(kernels) if j != k_index]
            for _s, r, desc, corr in order:
                consistent = True
                for x, y in corr.items():
                    if b2t.get(x, y) is not y or t2b.get(y, x) is not x:
                        consistent = False
                        break
                if not consistent:
                    continue
                b2t.update(corr)
                for x, y in corr.items():
                    t2b[y] = x
                ids.update(desc)
                roots_in.append(r)
            seeded.update(roots_in)
            key = frozenset(ids)
            if key in seen_sets:
                continue
            seen_sets.add(key)
            # Roots of the merged mapping: MHs with no parent inside it.
            mroots = [r for r in roots_in if not any(q in ids for q in self.parents[r])]
            results.append((self._mapping_score(ids), ids, b2t, mroots))
        results.sort(key=lambda m: -m[0])
        if results:
            best = results[0][0]
            results = [m for m in results if m[0] >= p.cutoff * best - 1e-12]
        return results[: p.max_mappings]
