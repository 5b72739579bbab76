"""Refining a located singularity between samples of a sweep: where exactly it lies.

Owns :class:`Refiner`: given two closed samples that bracket a singularity of one test,
it places the singular point to :data:`~mechsing.sweeps.settings.SWEEP_LOCATE_TOL` in the swept
value:

* a sign change of the test's compressed determinant, by the Illinois variant of regula
  falsi, every bracket of a batch together (:meth:`Refiner.crossings`);
* a sampled minimum that could hide a zero, by golden-section search
  (:meth:`Refiner.minimum`);
* a singular point of the closure the path passes through (two branches crossing), by
  walks along the path from both sides and a cubic fit (:meth:`Refiner.through`).

Every trial point is closed on the path (:meth:`Refiner.close_at`); the measures are
the float ones of :class:`~mechsing.sweeps.measures.Measures` the refiner is given.
"""

from __future__ import annotations

import math

import numpy as np

from mechsing.errors import ClosureError
from mechsing.kinematics.paths.nodes import reach_node
from mechsing.kinematics.paths.problem import Problem
from mechsing.kinematics.settings import SWEEP_JUMP_RATIO, SWEEP_LOCATE_TOL
from mechsing.numeric import Precision
from mechsing.sweeps.measures import Measures, PointMeasures
from mechsing.sweeps.records import Refined
from mechsing.sweeps.settings import (
    SWEEP_BRANCH_FIT_RTOL,
    SWEEP_BRANCH_OFFSET,
    SWEEP_BRANCH_ROOT_IMAG,
)

__all__ = ["Refiner"]

_TAU_LO = Precision("float").tolerances.tau_lo
_TAU_HI = Precision("float").tolerances.tau_hi
#: most regula falsi steps of one crossing (superlinear: about ten are needed)
_ILLINOIS_ITERATIONS = 60
#: most steps of a walk towards a singular point the path passes through
_WALK_STEPS = 60
#: most Newton steps of a fold's placement on its augmented system (quadratic: a few)
_FOLD_NEWTON_STEPS = 8
#: the central differences' step of the fold's singular value (commensurate; its error
#: h^2 next to the singular value's rounding eps / h: about eps^(1/3))
_FOLD_DIFFERENCE = 1e-5
#: the fold's Newton stops when its step is this small (commensurate: rounding)
_FOLD_STEP_STOP = 1e-14


class Refiner:
    """The refinements of one sweep's located points, with the measures they read (the
    sweep's, or one test's at a lower rank: :meth:`Measures.levelled`)."""

    def __init__(self, problem: Problem, measures: Measures) -> None:
        self.problem = problem
        self.measures = measures
        #: the joints' columns of the sweep's coordinates (the pose's follow for a pose sweep)
        self.n = int(problem.model.n)

    def ratio(self, t: str, z: np.ndarray) -> float:
        return float(self.measures(z[None, : self.n]).ratio[t][0])

    def crossings(
        self,
        t: str,
        ZA: np.ndarray,
        ZB: np.ndarray,
        col: int,
        pm: PointMeasures,
        ia: np.ndarray,
    ) -> list[Refined | None]:
        """The zero of the test's compressed determinant between each pair of samples
        (ZA, ZB), all pairs together: the Illinois variant of regula falsi, each trial
        point closed by batched Newton from its interpolation; a zero where the measure
        does not reach float's tau_hi is not a singularity (the compressed determinant
        also vanishes where the two samples' singular vectors turned too far apart)."""
        pb = self.problem
        bc = pb.batch
        nb = bc.nb
        free = ~pb.given[:nb]
        za, zb = np.array(ZA, dtype=float), np.array(ZB, dtype=float)
        a, b = za[:, col].copy(), zb[:, col].copy()
        fa = self.measures.compressed(pm, ia, za[:, : self.n])[t]
        fb = self.measures.compressed(pm, ia, zb[:, : self.n])[t]
        ok = np.ones(len(a), dtype=bool)
        tol = SWEEP_LOCATE_TOL * self.problem.scale(col)
        side = np.zeros(len(a), dtype=int)
        # the kept end's true value (Illinois halves fa), the iterate before the last
        ta = fa.copy()
        p, fp, zq = b.copy(), np.full(len(a), np.nan), zb.copy()
        for _ in range(_ILLINOIS_ITERATIONS):
            act = ok & (np.abs(b - a) > tol) & (fb != 0)
            if not np.any(act):
                break
            i = np.flatnonzero(act)
            c = b[i] - fb[i] * (b[i] - a[i]) / (fb[i] - fa[i])
            lo, hi = np.minimum(a[i], b[i]), np.maximum(a[i], b[i])
            bad = ~((c > lo) & (c < hi))
            c[bad] = (a[i][bad] + b[i][bad]) / 2
            f = (c - a[i]) / (b[i] - a[i])
            zp = bc.between(za[i], zb[i], f)
            zp[:, col] = c
            zc, res, _ = bc.newton(zp, free, pb.tolerance)
            lost = res > pb.tolerance
            ok[i[lost]] = False
            fc = self.measures.compressed(pm, ia[i], zc[:, : self.n])[t]
            same = fc * fb[i] > 0
            # the end that keeps its sign twice in a row has its value halved (Illinois)
            j = i[same]
            fa[j] = np.where(side[j] == 1, fa[j] / 2, fa[j])
            side[j] = 1
            k = i[~same]
            a[k], fa[k], za[k], ta[k] = b[k], fb[k], zb[k], fb[k]
            side[k] = 0
            p[i], fp[i], zq[i] = b[i], fb[i], zb[i]
            b[i], fb[i], zb[i] = c, fc, zc
        # the bracket is within the tolerance: the end nearer the zero (by its true
        # value), then one secant step through the last two iterates (or, when the kept
        # end is the nearer, through the bracket's two ends), put the zero at the
        # rounding level, where the analysis of the point decides in float too
        swap = ok & (np.abs(ta) < np.abs(fb))
        p[swap], fp[swap], zq[swap] = b[swap], fb[swap], zb[swap]
        b[swap], fb[swap], zb[swap] = a[swap], ta[swap], za[swap]
        act = np.flatnonzero(ok & np.isfinite(fp) & (fb != fp) & (fb != 0))
        if len(act):
            c = b[act] - fb[act] * (b[act] - p[act]) / (fb[act] - fp[act])
            near = np.abs(c - b[act]) <= np.abs(b[act] - p[act])
            act, c = act[near], c[near]
        if len(act):
            f = (c - b[act]) / np.where(p[act] != b[act], p[act] - b[act], 1.0)
            zp = bc.between(zb[act], zq[act], f)
            zp[:, col] = c
            zc, res, _ = bc.newton(zp, free, pb.tolerance)
            fc = self.measures.compressed(pm, ia[act], zc[:, : self.n])[t]
            better = (res <= pb.tolerance) & (np.abs(fc) < np.abs(fb[act]))
            zb[act[better]] = zc[better]
        out: list[Refined | None] = []
        rho = self.measures(zb[:, : self.n]).ratio[t]
        for m in range(len(a)):
            out.append(Refined(zb[m], float(rho[m])) if ok[m] and rho[m] <= _TAU_HI else None)
        return out

    def minimum(
        self, t: str, za: np.ndarray, zm: np.ndarray, zb: np.ndarray, col: int
    ) -> Refined | None:
        """Golden-section search of the test's measure between two samples' neighbours;
        the point when the measure reaches float's tau_lo there."""
        g = (math.sqrt(5) - 1) / 2
        a, b = float(za[col]), float(zb[col])

        m, a0 = float(zm[col]), a

        def at(v: float) -> np.ndarray:
            pair = (za, zm) if (v - m) * (a0 - m) > 0 else (zm, zb)
            return self.close_at(pair[0], pair[1], col, v)

        try:
            c, d = b - g * (b - a), a + g * (b - a)
            zc, zd = at(c), at(d)
            fc, fd = self.ratio(t, zc), self.ratio(t, zd)
            while abs(b - a) > SWEEP_LOCATE_TOL * self.problem.scale(col):
                if fc < fd:
                    b, d, zd, fd = d, c, zc, fc
                    c = b - g * (b - a)
                    zc = at(c)
                    fc = self.ratio(t, zc)
                else:
                    a, c, zc, fc = c, d, zd, fd
                    d = a + g * (b - a)
                    zd = at(d)
                    fd = self.ratio(t, zd)
        except ClosureError:
            return None
        z, r = (zc, fc) if fc < fd else (zd, fd)
        return Refined(z, r) if r <= _TAU_LO else None

    def through(
        self, Z: np.ndarray, reached: np.ndarray, ka: int, kb: int, col: int
    ) -> Refined | None:
        """A singular point of the closure that the path passes through (two branches
        crossing, as at a change-point four-bar's flat position), between samples ka and
        kb of the path Z.

        There the unknown joints are a double root of the closure equations for the held
        values, so float closes them only to about 1e-8 and the measure has a floor
        there: neither Newton at the point nor a search down to it can place it to
        1e-10.  The path itself is smooth through the point, and the measure along it
        is, near the point, proportional to the distance from it (a V).  So the path is
        walked from each side towards the point, each step half the estimated distance
        left (the estimate from the last two steps' measures) and predicted from the
        last two points of the walk (the other branch is as near as the point is: a
        prediction from the coarse samples could land on it), until SWEEP_BRANCH_OFFSET
        away; then from six points on both sides, 1, 2 and 3 offsets away (far outside
        the double root's reach, closed to full accuracy), the measure signed by side is
        fitted by a cubic whose root is the swept value, and the configuration there is
        the cubic interpolation of theirs.  None when the walks lose the path, when the
        six points do not make one smooth signed curve or when the interpolated point is
        not singular to float's tau_lo."""
        t = "closure"
        cm = self.problem.cm
        sc = self.problem.scale(col)
        a, b = float(Z[ka, col]), float(Z[kb, col])
        rho = [self.ratio(t, Z[k]) for k in range(ka, kb + 1)]
        ra, rb = rho[0], rho[-1]
        if kb == ka + 2:
            # a minimum at the middle sample: on a V through it, c |v - g|, the point g is
            # on its lower neighbour's side, 2 h r_mid / (r_a + r_b) from it
            mid = (a + b) / 2
            toward = np.sign(b - a) * (1.0 if rb < ra else -1.0)
            guess = mid + toward * abs(b - a) * rho[1] / (ra + rb) if ra + rb > 0 else mid
        else:
            guess = a + (b - a) * ra / (ra + rb) if ra + rb > 0 else (a + b) / 2
        lo, hi = min(a, b), max(a, b)
        delta = min(SWEEP_BRANCH_OFFSET * sc, (hi - lo) / 8)
        if not lo + 3 * delta < guess < hi - 3 * delta:
            guess = min(max(guess, lo + 4 * delta), hi - 4 * delta)

        def behind(k: int, step: int) -> np.ndarray | None:
            j = k - step
            return Z[j] if 0 <= j < len(Z) and reached[j] else None

        walks = []
        for k, step in ((ka, 1), (kb, -1)):
            z, zp, r = np.asarray(Z[k], dtype=float), behind(k, step), (ra if k == ka else rb)
            g = guess
            for _ in range(_WALK_STEPS):
                v = float(z[col])
                if abs(g - v) <= 4 * delta:
                    break
                zn = reach_node(self.problem, z, zp, col, v + (g - v) / 2)
                if zn is None:
                    return None
                rn = self.ratio(t, zn)
                vn = float(zn[col])
                if rn < r:  # still descending the V: the distance left, from its slope
                    c = (r - rn) / abs(vn - v)
                    g_new = vn + np.sign(g - v) * rn / c
                    if lo < g_new < hi:
                        g = g_new
                z, zp, r = np.asarray(zn, dtype=float), z, rn
            else:
                return None
            walks.append((z, zp, g))
        guess = (walks[0][2] + walks[1][2]) / 2
        u = np.array([-3.0, -2.0, -1.0, 1.0, 2.0, 3.0])
        zs: list[np.ndarray] = []
        for (z, zp, _), side in zip(walks, (-1.0, 1.0), strict=True):
            pts = []
            for k in (3.0, 2.0, 1.0):
                zn = reach_node(self.problem, z, zp, col, guess + side * k * delta)
                if zn is None:
                    return None
                z, zp = np.asarray(zn, dtype=float), z
                pts.append(z)
            zs += pts if side < 0 else pts[::-1]
        f = np.sign(u) * np.array([self.ratio(t, z) for z in zs])
        coef = np.polyfit(u, f, 3)
        if np.max(np.abs(np.polyval(coef, u) - f)) > SWEEP_BRANCH_FIT_RTOL * np.max(np.abs(f)):
            return None  # not one smooth signed curve: not a crossing of the path
        roots = [
            r.real
            for r in np.roots(coef)
            if abs(r.imag) < SWEEP_BRANCH_ROOT_IMAG and abs(r.real) < 1
        ]
        if not roots:
            return None
        root = min(roots, key=abs)
        base = zs[2]
        D = np.array([cm.difference(z, base) for z in zs])
        dstar = np.array([np.polyval(np.polyfit(u, D[:, i], 3), root) for i in range(D.shape[1])])
        z = np.asarray(cm.update(base, dstar), dtype=float)
        z[col] = guess + root * delta
        r = self.ratio(t, z)
        return Refined(z, r) if r <= _TAU_LO else None

    def fold(self, z: np.ndarray, col: int) -> np.ndarray | None:
        """A fold of the swept coordinate ``col`` placed on its augmented system, from the
        path's point z: the closure ``F = 0`` and the vanishing singular value of the
        unknowns' Jacobian ``A`` (the closure's columns but the given ones and col),
        ``u^T A v = 0`` with (u, v) its smallest singular pair at the iterate, solved by
        Newton (least squares) in the unknowns and col together, the held coordinates
        kept; the singular value's derivatives by central differences.  Along the path
        the swept value is quadratic in the distance to the fold, so the path places the
        point to about 1e-8 along the curve; the singular value is linear in it, so this
        places it to rounding.  The iterate with the smallest singular value among those
        that close to the sweep's tolerance (None: none does)."""
        from mechsing.kinematics.newton import scaled_jacobian, scaled_system

        pb = self.problem
        cm, fr = pb.cm, pb.cm.float_frame
        free = ~np.asarray(pb.given, dtype=bool)
        free[col] = True
        fcols = np.flatnonzero(free)
        unknowns = fcols != col
        x = np.array(z, dtype=float)

        def moved(q: np.ndarray, d: np.ndarray) -> np.ndarray:
            dd = np.zeros(pb.n)
            dd[fcols] = d
            return np.asarray(cm.update(q, fr.rates_back(dd)), dtype=float)

        def unknowns_jacobian(q: np.ndarray) -> np.ndarray:
            J = scaled_jacobian(cm, q)
            return np.asarray(J, dtype=float)[:, fcols][:, unknowns]

        h = _FOLD_DIFFERENCE
        best: tuple[float, np.ndarray] | None = None
        for _ in range(_FOLD_NEWTON_STEPS):
            J, r = scaled_system(cm, x)
            J = np.asarray(J, dtype=float)[:, fcols]
            r = np.asarray(r, dtype=float)
            U, sv, Vt = np.linalg.svd(J[:, unknowns])
            k = len(sv) - 1
            if np.linalg.norm(r) * cm.length_scale <= pb.tolerance and (
                best is None or sv[k] < best[0]
            ):
                best = (float(sv[k]), x)
            u, v = U[:, k], Vt[k]
            grad = np.empty(len(fcols))
            for j in range(len(fcols)):
                e = np.zeros(len(fcols))
                e[j] = h
                Ap, Am = unknowns_jacobian(moved(x, e)), unknowns_jacobian(moved(x, -e))
                grad[j] = u @ ((Ap - Am) @ v) / (2 * h)
            G = np.vstack([J, grad[None, :]])
            step = np.linalg.lstsq(G, -np.concatenate([r, [sv[k]]]), rcond=None)[0]
            if np.max(np.abs(step)) <= _FOLD_STEP_STOP:
                break
            x = moved(x, step)
        # the iterate with the smallest singular value that closes (past it, at rounding
        # level, the steps follow the rounding of the singular pair)
        return None if best is None else best[1]

    def close_at(self, za: np.ndarray, zb: np.ndarray, col: int, t: float) -> np.ndarray:
        """The configuration with ``col`` at t between two closed neighbours za, zb (their
        interpolation closed by Newton; by continuation from za when that jumps)."""
        pb = self.problem
        ta, tb = za[col], zb[col]
        f = 0.0 if tb == ta else (t - ta) / (tb - ta)
        zp = pb.batch.between(za[None, :], zb[None, :], np.array([f]))[0]
        zp[col] = t
        span = pb.comm(pb.cm.difference(zb, za))
        Q, ok, _ = pb.close_near(zp[None, :], SWEEP_JUMP_RATIO * max(span, 1e-300))
        if ok[0]:
            return Q[0]
        # along the path from za by the tangent in halved steps, then the careful
        # continuation
        walked = reach_node(pb, np.asarray(za, dtype=float), None, col, t)
        return walked if walked is not None else pb.reach(za, col, t)
