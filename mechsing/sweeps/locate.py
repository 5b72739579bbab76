"""Locating the singularities along the rows of a sweep, from their sampled measures.

Owns :class:`Locator`: along each row (a path, or a row of a grid), which pairs of
neighbouring samples bracket a sign change of a test's compressed determinant, which
sampled minima could hide a zero, which folds the path met, and the tests singular all
along a row (its path inside their singular set, where the rank they keep can drop
further).  Each bracket or minimum is handed to the :class:`~.refine.Refiner` that
places it; the rows of a chunk are located together, each as alone.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from mechsing.kinematics.paths.folds import Fold
from mechsing.kinematics.paths.problem import Problem
from mechsing.numeric import Precision
from mechsing.sweeps.falling import others_fall, singular_samples
from mechsing.sweeps.measures import Measures, PointMeasures
from mechsing.sweeps.records import Located, Refined, RowPairs, RowSamples, located_at
from mechsing.sweeps.refine import Refiner
from mechsing.sweeps.settings import (
    SWEEP_FOLD_MOVE_RTOL,
    SWEEP_FOLD_TEST_RTOL,
    SWEEP_MINIMUM_SCREEN,
)

__all__ = ["Locator", "measured"]

_TAU_HI = Precision("float").tolerances.tau_hi
_TAU_LO = Precision("float").tolerances.tau_lo
#: measures are computed at most this many configurations at a time (bounds the working
#: memory) ...
_CHUNK = 4096
#: ... and so many that a chunk's closure matrices take at most this many bytes: the
#: chunk's largest arrays (the closure, its transposed copy and QR: the hexapod's 30 x 36,
#: 8.6 kB a configuration) then stay under glibc's largest mmap threshold (32 MB), so that
#: their memory is reused rather than mapped and faulted in again at every chunk (4096 of
#: the hexapod's cost its path about 7% of its CPU time in page faults; 2048 and 1024
#: measured alike); a small mechanism's chunks stay long (fewer batches)
_CHUNK_BYTES = 16 * 2**20


def measured(measures: Measures, Z: np.ndarray, reached: np.ndarray, n: int) -> PointMeasures:
    """The measures of the reached rows of the sweep's coordinates Z (their first ``n``,
    the joints), in chunks of at most _CHUNK configurations and _CHUNK_BYTES of
    closure matrices."""
    Q = Z[reached][:, :n]
    rows = 6 * len(measures.mech.loops) + len(measures.model.couplings)
    step = max(1, min(_CHUNK, _CHUNK_BYTES // max(8 * rows * n, 1)))
    parts = [measures(Q[i : i + step]) for i in range(0, max(len(Q), 1), step)]
    if len(parts) == 1:
        return parts[0]
    return PointMeasures.gather([(p, slice(None)) for p in parts])


class Locator:
    """Where a sweep's rows meet the singularities of the tests of ``measures`` (the
    sweep's, or one test's at a lower rank), its points refined by its :class:`Refiner`
    on ``problem``; ``cols``: the swept columns of the sweep's coordinates."""

    def __init__(self, problem: Problem, cols: list[int], measures: Measures) -> None:
        self.problem = problem
        self.cols = cols
        self.measures = measures
        self.refiner = Refiner(problem, measures)
        self.n = self.refiner.n
        #: per row of a grid, its samples listed as singular between rows
        #: (:func:`~mechsing.sweeps.falling.column_samples`)
        self.listed: dict[int, set[int]] = {}

    @property
    def tests(self) -> tuple[str, ...]:
        return self.measures.tests

    def inside(
        self,
        Z: np.ndarray,
        reached: np.ndarray,
        rank: dict[str, np.ndarray],
        ratio: dict[str, np.ndarray],
        col: int,
        index: int,
        located: list[Located],
    ) -> list[str]:
        """The tests singular at every reached sample of a row (the path lies in their
        singular set): said in the row's notes, and where the rank they keep along the
        path drops further, those points located (added to ``located``)."""
        K = len(Z)
        always = [t for t in self.tests if np.any(reached) and np.all(ratio[t][reached] <= _TAU_HI)]
        stopped: list[str] = []
        for t in always:
            g = self.measures.generic[t]
            stopped.append(
                f"{t} is singular at every reached sample (rank below its generic {g} all "
                "along): the path lies in that singular set"
            )
            # inside the set, the rank it keeps along the path can drop further (a PUMA's
            # elbow on a path inside its wrist singularity): located at that level
            level = int(np.max(rank[t][reached]))
            if 0 < level < g:
                # test t alone, at rank ``level`` instead of its generic rank (the
                # refinements read the levelled measures)
                lv = Locator(self.problem, self.cols, self.measures.levelled(t, level))
                pm_t = measured(lv.measures, Z, reached, self.n)
                ratio_t = np.full(K, np.nan)
                ratio_t[reached] = pm_t.ratio[t]
                if np.any(ratio_t[reached] > _TAU_HI):
                    located += lv.along(Z, reached, pm_t, {t: ratio_t}, col, index)
                    stopped.append(
                        f"{t}: inside that set its rank is {level} along the path; "
                        f"the points where it drops below {level} are located"
                    )
        return stopped

    def fold(self, f: Fold, index: int, values: np.ndarray) -> Located:
        """The located point of a fold the path of row ``index`` met (through ``values``),
        listed under the tests whose measure vanishes there.  The path places a fold along
        the swept value, which is quadratic in the distance to it there (float then knows
        the point only to about 1e-8 along the curve, and a measure that vanishes at the
        fold keeps that size): the point is placed again by the fold's own conditions
        (:meth:`Refiner.fold`: Newton on the closure and the vanishing singular value,
        which is linear in the distance), and kept when it closes and lowers the
        measures."""
        z = self._fold_again(f)
        if z is not f.z:
            f = Fold(
                float(z[min(self.cols, key=lambda c: abs(f.z[c] - f.value))]),
                z,
                f.direction,
                f.far_side,
            )
        pm = self.measures(f.z[None, : self.n])
        vanishing = tuple(t for t in self.tests if pm.ratio[t][0] <= SWEEP_FOLD_TEST_RTOL)
        ratio = min((float(pm.ratio[t][0]) for t in self.tests), default=0.0)
        i = int(np.searchsorted(np.sort(values), f.value)) - 1
        return self.at(f.z, "fold", vanishing, ratio, "row", (index, max(i, 0)), f.far_side)

    def _fold_again(self, f: Fold) -> np.ndarray:
        """The fold ``f``'s configuration placed by its own conditions (see :meth:`fold`),
        or ``f.z`` itself when that does not close to the sweep's tolerance, moves the
        swept value by more than SWEEP_FOLD_MOVE_RTOL of its unit, or does not lower the
        smallest measure."""
        pb = self.problem
        col = min(self.cols, key=lambda c: abs(f.z[c] - f.value))
        try:
            z = self.refiner.fold(f.z, col)
        except (ArithmeticError, ValueError, np.linalg.LinAlgError):
            return f.z
        if z is None or not abs(z[col] - f.value) <= SWEEP_FOLD_MOVE_RTOL * pb.scale(col):
            return f.z
        before = self.measures(f.z[None, : self.n])
        after = self.measures(z[None, : self.n])
        low = min((float(before.ratio[t][0]) for t in self.tests), default=0.0)
        low2 = min((float(after.ratio[t][0]) for t in self.tests), default=0.0)
        return z if low2 < low else f.z

    def at(
        self,
        z: np.ndarray,
        kind: str,
        tests: tuple[str, ...],
        ratio: float,
        edge: str,
        cell: tuple[int, int],
        far_side: bool = False,
    ) -> Located:
        """A located point at the sweep's coordinates z (:func:`~.records.located_at`)."""
        return located_at(z, kind, tests, ratio, edge, cell, self.cols, self.n, far_side)

    def along(
        self,
        Z: np.ndarray,
        reached: np.ndarray,
        pm: PointMeasures,
        ratio: dict[str, np.ndarray],
        col: int,
        index: int,
    ) -> list[Located]:
        """Sign changes and minima of each test along one row."""
        return self.along_rows(pm, [RowSamples(Z, reached, 0, ratio, col, index)])[0]

    def along_rows(self, pm: PointMeasures, rows: list[RowSamples]) -> list[list[Located]]:
        """Sign changes and minima of each test along several rows: each row's reached
        samples are the measured batch ``pm``'s from its ``offset`` on, in order.  Test by
        test, the sign changes of every row are refined together
        (:meth:`Refiner.crossings`, each bracket on its own), then each row's minima; each
        row's points are found as when it is alone."""
        outs: list[list[Located]] = [[] for _ in rows]
        # per row: its pairs of neighbouring reached samples, and their rows in the batch
        # (which holds the row's reached samples in order, from its offset)
        info: list[RowPairs | None] = []
        ias, ibs = [], []
        for row in rows:
            reached = row.reached
            where = np.flatnonzero(reached)
            first = np.flatnonzero((where[:-1] + 1 == where[1:]) if len(where) else [])
            PA = where[first]
            if not len(PA):
                info.append(None)
                continue
            K = len(row.Z)
            # the samples whose neighbours are both reached (the minima's candidates)
            inner = np.zeros(K, dtype=bool)
            inner[1:-1] = reached[:-2] & reached[1:-1] & reached[2:]
            info.append(RowPairs(PA, row.offset + first, inner))
            ias.append(row.offset + first)
            ibs.append(row.offset + first + 1)
        if not ias:
            return outs
        ia_all, ib_all = np.concatenate(ias), np.concatenate(ibs)
        dets_all = self.measures.compressed_pairs(pm, ia_all, ib_all)
        # a sign change of a weaker-than-generic pair other than the weakest (the UR5's
        # elbow just past its shoulder): the whole compressed determinant's sign
        for t, deeper in others_fall(self, pm, ia_all, ib_all).items():
            dets_all[t] = np.where(deeper < 0, np.minimum(dets_all[t], deeper), dets_all[t])
        dets: list[dict[str, np.ndarray] | None] = []
        at = 0
        for got in info:
            if got is None:
                dets.append(None)
                continue
            n = len(got.first)
            dets.append({t: d[at : at + n] for t, d in dets_all.items()})
            at += n
        crossed: list[set[int]] = [set() for _ in rows]
        for t in self.tests:
            todo = self._sign_changes(t, rows, info, dets, outs, crossed)
            # a sign change of the closure is a singular point the path passes through: a
            # double root for Newton, placed by the path on both sides (row by row);
            # the others' zeros, every row's together
            refined = self._refined(t, pm, rows, info, todo)
            for r, hits_r in enumerate(todo):
                got = info[r]
                if got is None:
                    continue
                row = rows[r]
                Z, col, index = row.Z, row.col, row.index
                out = outs[r]
                if hits_r is not None:
                    A = got.first[hits_r]
                    crossed[r].update(A.tolist() + (A + 1).tolist())
                    for a, found in zip(A, refined[r], strict=True):
                        if found is None:
                            crossed[r].difference_update((int(a), int(a) + 1))
                            continue
                        z, rr = found
                        out.append(self.at(z, "crossing", (t,), rr, "row", (index, int(a))))
                pos = row.offset + np.cumsum(row.reached) - 1  # each sample's batch row
                self._minima(
                    t,
                    Z,
                    row.reached,
                    row.ratio[t],
                    got.inner,
                    crossed[r],
                    col,
                    index,
                    out,
                    lambda k, pos=pos, t=t: self._changes_sign(
                        pm, t, int(pos[k - 1]), int(pos[k + 1])
                    ),
                )
                singular_samples(self, t, row, out)
        return outs

    def _sign_changes(
        self,
        t: str,
        rows: list[RowSamples],
        info: list[RowPairs | None],
        dets: list[dict[str, np.ndarray] | None],
        outs: list[list[Located]],
        crossed: list[set[int]],
    ) -> list[np.ndarray | None]:
        """Per row, the pairs (indices into its :class:`RowPairs`) where test t changes
        sign and that hold no point already located for another test (None: none);
        ``crossed`` gets, per row, the samples of the pairs such a point holds."""
        todo: list[np.ndarray | None] = []
        for r, row in enumerate(rows):
            Z, col = row.Z, row.col
            crossed[r] = set()
            got, dr = info[r], dets[r]
            if got is None or dr is None:
                todo.append(None)
                continue
            PA = got.first
            d = dr.get(t)
            rho = row.ratio[t]
            # between two samples that are both singular for the test, its sign is
            # noise: a sign change counts only where one end has a decided full generic
            # rank
            hits = (
                []
                if d is None
                else np.flatnonzero((d < 0) & (np.maximum(rho[PA], rho[PA + 1]) > _TAU_HI)).tolist()
            )
            # a pair holding a point already located for another test (the closure's
            # first) that zeroes this one too: the same point, placed by that test
            # (near a singular point of the closure this test's zero is blurred)
            done = [
                k for k in hits if self.holds(outs[r], t, Z[PA[k], col], Z[PA[k] + 1, col], col)
            ]
            crossed[r].update(x for k in done for x in (int(PA[k]), int(PA[k]) + 1))
            hits = [k for k in hits if k not in done]
            todo.append(np.array(hits, dtype=int) if hits else None)
        return todo

    def _refined(
        self,
        t: str,
        pm: PointMeasures,
        rows: list[RowSamples],
        info: list[RowPairs | None],
        todo: list[np.ndarray | None],
    ) -> list[list[Refined | None]]:
        """Per row, test t's sign changes ``todo`` refined: the closure's row by row
        (:meth:`Refiner.through`), the others' every row's together
        (:meth:`Refiner.crossings`)."""
        refined: list[list[Refined | None]] = [[] for _ in rows]
        if t == "closure":
            for r, hits_r in enumerate(todo):
                got = info[r]
                if hits_r is not None and got is not None:
                    row = rows[r]
                    refined[r] = [
                        self.refiner.through(row.Z, row.reached, int(a), int(a) + 1, row.col)
                        for a in got.first[hits_r]
                    ]
            return refined
        which = [r for r, h in enumerate(todo) if h is not None]
        if not which:
            return refined
        col = rows[which[0]].col
        picked = []  # per row: its samples, the pairs' first samples, their batch rows
        for r in which:
            got, hits_r = info[r], todo[r]
            assert got is not None and hits_r is not None
            picked.append((rows[r].Z, got.first[hits_r], got.rows[hits_r]))
        ZA = np.concatenate([Z[A] for Z, A, _ in picked])
        ZB = np.concatenate([Z[A + 1] for Z, A, _ in picked])
        ia = np.concatenate([ia_r for _, _, ia_r in picked])
        found_all = self.refiner.crossings(t, ZA, ZB, col, pm, ia)
        at = 0
        for r, (_, A, _) in zip(which, picked, strict=True):
            refined[r] = found_all[at : at + len(A)]
            at += len(A)
        return refined

    def _minima(
        self,
        t: str,
        Z: np.ndarray,
        reached: np.ndarray,
        rho: np.ndarray,
        inner: np.ndarray,
        crossed: set[int],
        col: int,
        index: int,
        out: list[Located],
        across: Callable[[int], bool] | None = None,
    ) -> None:
        """A row's sampled minima of test ``t`` that could hide a zero, refined (added to
        ``out``): not singular on both sides (no isolated zero to place there), at most
        its neighbours, and low next to how far they rise.  A minimum whose neighbours'
        determinants have opposite signs (``across(k)``: the sign test from sample k - 1
        to k + 1, past a sample k singular itself, where the test between neighbours reads
        the arbitrary sign of a zero singular pair) is a sign change: kind ``crossing``."""
        K = len(Z)
        lo, mid, hi = np.full(K, np.nan), rho, np.full(K, np.nan)
        lo[1:], hi[:-1] = rho[:-1], rho[1:]
        big = np.maximum(lo, hi)
        with np.errstate(invalid="ignore"):
            low = (
                inner
                & (big > _TAU_HI)
                & (mid <= lo)
                & (mid <= hi)
                & ~(mid > SWEEP_MINIMUM_SCREEN * (big - mid))
            )
        for k in np.flatnonzero(low).tolist():
            if k in crossed:
                continue
            if self.holds(out, t, Z[k - 1, col], Z[k + 1, col], col):
                continue  # the point located there for another test zeroes this one
            found = None
            if t == "closure":
                found = self.refiner.through(Z, reached, k - 1, k + 1, col)
            if found is None:
                found = self.refiner.minimum(t, Z[k - 1], Z[k], Z[k + 1], col)
            if found is not None:
                z, r = found
                kind = "crossing" if across is not None and across(k) else "minimum"
                out.append(self.at(z, kind, (t,), r, "row", (index, k)))

    def _changes_sign(self, pm: PointMeasures, t: str, ia: int, ib: int) -> bool:
        """Does test ``t``'s determinant change sign from batch row ``ia`` to ``ib``
        (:meth:`~mechsing.sweeps.measures.Measures.compressed_pairs`)?"""
        got = self.measures.compressed_pairs(pm, np.array([ia]), np.array([ib])).get(t)
        return got is not None and bool(got[0] < 0)

    def holds(self, out: list[Located], t: str, va: float, vb: float, col: int) -> bool:
        """Whether a point of ``out`` lies between the swept values va and vb and is
        singular for test ``t`` too (its measure below float's tau_hi there), or is a
        singular point of the closure (where the input and output tests' sign, read
        through the closure, changes too, and their measure is not defined)."""
        lo, hi = sorted((float(va), float(vb)))
        return any(
            lo <= float(p.z[col]) <= hi
            and ("closure" in p.tests or self.refiner.ratio(t, p.z) <= _TAU_HI)
            for p in out
            if p.z is not None
        )
