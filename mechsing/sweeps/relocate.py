"""Located singularities placed again at N digits, for a classification at mp:N.

Owns :class:`Relocator`.  A sweep locates its singular points in float, to about 1e-13 of
the swept value: close enough for float's verdicts, but at mp:N such a point is a regular
configuration 1e-13 from the singular one, which N digits tell apart.  So before the full
analysis classifies a located point at mp:N, the point is found again at N digits:

* a **crossing** of a test (its matrix loses rank as the swept value passes): secant
  iterations on the swept value of the test's compressed determinant
  ``det(U0^T A(v) V0)`` (``U0``, ``V0``: the leading singular vectors of the float point;
  for the input and output tests the motion space enters by its projector ``N N^T``,
  which has no orientation to choose), each point closed by Newton at N digits with the
  held coordinates given;
* a **fold** (the swept value's limit of travel): the point where the swept value ``v`` is
  extremal on the closure's solutions ``F(x, v) = 0``, by its Lagrange conditions
  ``F = 0``, ``F_x^T lam = 0``, ``F_v . lam = 1`` (Moore and Spence's system with the left
  null vector): Gauss-Newton at N digits on the unknowns and the multiplier ``lam``
  (minimum-norm steps), the second derivatives by central differences at N digits.  Float
  places the swept value of a fold to 1e-16 but its unknowns only to about 1e-8 (the
  curve is quadratic there); the system needs no test, no coordinate to drive, and stays
  solvable where several legs reach their limit at once (then ``lam`` is any point of an
  affine set, along which the minimum-norm step does not move);
* a **bifurcation** (a crossing of the closure's own test: it loses rank, two branches
  cross): the same system with ``F_v . lam = 0`` in place of ``= 1`` (the swept value is
  not extremal there), so ``[F_x F_v]^T lam = 0``, and ``lam`` normalised by holding its
  components on the left singular vectors that vanish there at the float point's.  Where
  the branches cross transversally that system is regular, and Gauss-Newton places the
  point to N digits, where the closure's double root leaves the secant on its test's
  determinant N/2 (the secant remains where this does not converge).  So at mp:N the
  sweep (:mod:`.classify`) solves this system at N and a few guard digits, and only
  where it does not converge relocates at 2N + 10 digits.

Each secant step gains digits superlinearly from float's point; it stops when the step is
below 10^(5-N) of the variable's scale (10^(5-N/2) for the closure's test, whose point is
a double root known to N/2 digits; a fold: when its Gauss-Newton step is).  A point
whose relocation fails keeps its float values (its classification then says what N
digits see there).
"""

from __future__ import annotations

from typing import Any

import mpmath
import numpy as np

from mechsing.kinematics import Closer, KinematicModel
from mechsing.kinematics.pose import PoseModel
from mechsing.kinematics.settings import POLISH_DIGITS_SPARE
from mechsing.numeric import Precision, decide_rank
from mechsing.screws import chain_matrix
from mechsing.sweeps.settings import SWEEP_FOLD_KERNEL_RTOL

__all__ = ["Relocator"]

#: most secant steps of one relocation (each gains digits superlinearly)
_SECANT_STEPS = 16
#: most Gauss-Newton steps of one fold's or bifurcation's relocation (each about
#: doubles its digits)
_FOLD_STEPS = 12
#: size of the move off a bifurcation (commensurate) at which the left singular vectors
#: that vanish there are told apart: the closure's lost rank comes back in proportion
_PROBE = 1e-2


class Relocator:
    """Relocation of a sweep's float points at ``precision`` (mp:N)."""

    def __init__(self, sweep: Any, precision: Precision) -> None:
        self.sweep = sweep
        self.prec = precision
        self.model = KinematicModel(sweep.mech, precision)
        self.closer = Closer(self.model, data_precision=precision)
        pb = sweep.problem
        self.given = tuple(int(i) for i in np.flatnonzero(pb.given))
        self.pose: PoseModel | None = None
        if sweep.pose:
            # the output's reference point as the file gives it, at N digits (the float
            # sweep's is its rounding)
            with precision.context():
                self.pose = PoseModel(
                    self.model,
                    list(sweep.mech.output_reference_point()),
                    self.model.backend.eye(3),
                )

    # -------------------------------------------------------------- one point's test

    def _matrix(self, q: np.ndarray, test: str) -> np.ndarray:
        """The test's matrix at the joints q (N digits), as the float measures build it."""
        m, meas = self.model, self.sweep.measures
        S = m.current_screws(q)
        Ss = m.frame.screws(S)
        n = m.n
        blocks = [Ss * meas.loop_signs[i][None, :] for i in range(len(meas.loop_signs))]
        C = np.concatenate(blocks, axis=0) if blocks else m.backend.zeros((0, n))
        if test == "closure":
            return C
        if blocks:
            dec = decide_rank(C, self.prec, m.length_scale, want_spaces=True, native_spaces=True)
            Nk = dec.null_space
            P = Nk @ Nk.T  # the projector on the motion space: no orientation to choose
        else:
            P = m.backend.eye(n)
        if test == "input":
            x = None
            out = self.sweep.mech.output
            if meas.out_point is not None and out is not None and out.point is not None:
                # the point as the file gives it, at N digits (not the measures' float
                # rounding, which would move the test's zero by about 1e-17)
                g = m.poses(q)[out.body]
                x = g[:3, :3] @ m.asarray(list(out.point)) + g[:3, 3]
            T = chain_matrix(m, S, None, x, meas.out_signs)
            return T @ P
        return m.asarray(meas.E.tolist()) @ P

    def _det(self, A: np.ndarray, U0: np.ndarray, V0: np.ndarray, N0: np.ndarray | None) -> Any:
        m = self.model
        Am = A if N0 is None else A @ m.asarray(N0.tolist())
        C = m.asarray(U0.T.tolist()) @ Am @ m.asarray(V0.tolist())
        return mpmath.det(mpmath.matrix(C.tolist()))

    # -------------------------------------------------------------- relocation

    def relocate(self, z: np.ndarray, test: str, kind: str) -> np.ndarray | None:
        """The located point ``z`` (float, the sweep's coordinates) again at N digits: its
        joints (object array), or None when it does not converge or its test has no sign
        (the constraint test's minimum).  ``test``: the test whose crossing it is (a fold
        is placed by its own conditions, whatever vanishes there); ``kind``: ``fold``, or
        the edge (``row``, ``column``) it was found on."""
        sw = self.sweep
        nb = sw.model.n
        if kind == "fold":
            return self._fold(z)
        if test == "closure":  # a bifurcation: placed by its own conditions, as a fold
            q = self.bifurcation(z)
            if q is not None:
                return q
        if test not in ("closure", "input", "output"):
            return None  # a test with no sign (the constraint's, located at a minimum)
        # the float point's closure kernel (the closure is regular there)
        pm = sw.measures(np.asarray(z[:nb], dtype=float)[None, :])
        if test not in pm.rank:
            return None
        N0 = None if pm.kernel is None or test not in ("input", "output") else pm.kernel[0]
        drive = sw.cols[0] if kind == "row" else sw.cols[1]
        return self._secant(z, drive, self.given, test, sw.measures.generic[test], N0)

    def _free(self, z: np.ndarray) -> tuple[np.ndarray, int, Any, np.ndarray]:
        """The free coordinates at the float point z (the unknowns and the swept one),
        the swept one's place among them, the float closure model and its commensurate
        Jacobian on them there."""
        from mechsing.kinematics.newton import scaled_jacobian

        pb = self.sweep.problem
        col = self.sweep.cols[0]
        free = ~np.asarray(pb.given, dtype=bool)
        free[col] = True
        fcols = np.flatnonzero(free)
        Jf = scaled_jacobian(pb.cm, np.asarray(z, dtype=float))
        return fcols, int(fcols.tolist().index(col)), pb.cm, np.asarray(Jf, dtype=float)[:, fcols]

    def _fold(self, z: np.ndarray) -> np.ndarray | None:
        """The fold near the float point z again at N digits (see the module's note): its
        joints, or None when Gauss-Newton does not converge."""
        fcols, iv, _, A0 = self._free(z)
        nf = len(fcols)
        # the multiplier's start: the shortest combination of the left singular vectors
        # of the unknowns' Jacobian that vanish at the fold (one per chain at its limit)
        # with F_v . lam = 1.  Where several chains reach their limit together the
        # multiplier is any point of an affine set; it is held at this one's weights
        # (P (lam - lam0) = 0, P across a within those vectors), so that every chain
        # keeps its share: a multiplier that drifts away from one chain leaves that
        # chain's limit a double root, which Gauss-Newton only halves towards
        U, s, _ = np.linalg.svd(A0[:, [i for i in range(nf) if i != iv]])
        # the vanishing singular values (at least one: this is a fold), and the left
        # vectors beyond the unknowns' count (rows every configuration satisfies, as a
        # planar loop's out-of-plane ones: their weight is zero)
        k = max(int(np.sum(s < SWEEP_FOLD_KERNEL_RTOL * (s[0] if len(s) else 1.0))), 1)
        Uk = U[:, len(s) - k :]
        a = Uk.T @ A0[:, iv]
        if not np.any(a):
            return None
        lam0 = Uk @ (a / (a @ a))
        P = np.linalg.svd(a[None, :])[2][1:] @ Uk.T
        rhs = np.zeros(nf)
        rhs[iv] = 1.0
        return self._lagrange(z, fcols, rhs, lam0, P)

    def bifurcation(self, z: np.ndarray) -> np.ndarray | None:
        """The point near the float point z where the closure itself loses rank, again at
        N digits: the same Lagrange system as a fold's with ``[F_x F_v]^T lam = 0`` (the
        swept value is not extremal there: ``F_v . lam`` vanishes too) and ``lam``
        normalised by its components on the vanishing left singular vectors, held at the
        float point's.  Where two branches cross transversally (the second-order form
        ``lam . F''`` non-degenerate on the two-dimensional kernel) the system is
        regular, and Gauss-Newton converges quadratically to the singular point; its
        joints, or None when it does not converge."""
        fcols, _, cm, A0 = self._free(z)
        U, s, _ = np.linalg.svd(A0)
        k = max(int(np.sum(s < SWEEP_FOLD_KERNEL_RTOL * (s[0] if len(s) else 1.0))), 1)
        Uk = U[:, len(s) - k :]
        # which of them are rows every configuration satisfies (a planar loop's
        # out-of-plane ones): those stay vanishing at a configuration moved off the
        # point, where the closure's own lost rank comes back
        d = cm.zeros()
        d[fcols] = _PROBE * np.random.default_rng(0).standard_normal(len(fcols))
        *_, A1 = self._free(cm.update(np.asarray(z, dtype=float), cm.frame.rates_back(d)))
        W, w, _ = np.linalg.svd(Uk.T @ A1)
        lost = int(np.sum(w > SWEEP_FOLD_KERNEL_RTOL * (s[0] if len(s) else 1.0)))
        if lost != 1:  # no rank the closure lost, or more than one (not a simple crossing)
            return None
        return self._lagrange(z, fcols, np.zeros(len(fcols)), Uk @ W[:, 0], Uk.T)

    def _lagrange(
        self, z: np.ndarray, fcols: np.ndarray, rhs: np.ndarray, lam0: np.ndarray, P: np.ndarray
    ) -> np.ndarray | None:
        """Gauss-Newton at N digits from the float point z and multiplier lam0 on
        ``F(x, v) = 0``, ``[F_x F_v]^T lam = rhs``, ``P lam = P lam0`` (the free
        coordinates ``fcols``; minimum-norm steps, the second derivatives by central
        differences at N digits): the joints of its solution, or None when it does not
        converge."""
        from mechsing.kinematics.newton import mp_least_squares, scaled_system

        nb = self.sweep.model.n
        m: Any = self.pose if self.pose is not None else self.model
        nf = len(fcols)
        with m.precision.context():
            small = mpmath.mpf(10) ** (POLISH_DIGITS_SPARE - mpmath.mp.dps)
            h = mpmath.mpf(10) ** (-(mpmath.mp.dps // 3))
            q = m.asarray([repr(float(x)) for x in z])
            lam = np.array([mpmath.mpf(repr(float(x))) for x in lam0], dtype=object)

            def moved(q: np.ndarray, d: np.ndarray) -> np.ndarray:
                dd = m.zeros()
                dd[fcols] = d
                return m.update(q, m.frame.rates_back(dd))

            def parts(q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
                Js, rs = scaled_system(m, q)
                return np.asarray(Js, dtype=object)[:, fcols], np.asarray(rs, dtype=object)

            Pm = np.array([[mpmath.mpf(repr(float(x))) for x in row] for row in P], dtype=object)
            Pm = Pm.reshape(P.shape)
            pin = Pm @ lam

            def G(A: np.ndarray, rs: np.ndarray, lam: np.ndarray) -> np.ndarray:
                return np.concatenate([rs, A.T @ lam - rhs, Pm @ lam - pin])

            try:
                for _ in range(_FOLD_STEPS):
                    A, rs = parts(q)
                    g = G(A, rs, lam)
                    # d G / d (free coordinates): the residual's is A; the second
                    # derivatives by central differences at N digits
                    Dx = np.full((len(g), nf), mpmath.mpf(0), dtype=object)
                    for j in range(nf):
                        e = np.array([mpmath.mpf(0)] * nf, dtype=object)
                        e[j] = h
                        Ap, _ = parts(moved(q, e))
                        Am, _ = parts(moved(q, -e))
                        Dx[: len(rs), j] = A[:, j]
                        Dx[len(rs) : len(rs) + nf, j] = ((Ap - Am).T @ lam) / (2 * h)
                    # d G / d lam: zero for the residual, A^T for the conditions, P
                    Dl = np.full((len(g), len(lam)), mpmath.mpf(0), dtype=object)
                    Dl[len(rs) : len(rs) + nf] = A.T
                    Dl[len(rs) + nf :] = Pm
                    JJ = np.concatenate([Dx, Dl], axis=1)
                    step = mp_least_squares(JJ, -g)
                    q = moved(q, step[:nf])
                    lam = lam + step[nf:]
                    if max(abs(x) for x in step[:nf]) <= small:
                        res = m.residual_norm(m.chord_residuals(q))
                        if res <= small * m.length_scale:
                            return q[:nb]
                        return None
            except (ArithmeticError, ValueError, np.linalg.LinAlgError):
                return None
        return None

    def _secant(
        self,
        z: np.ndarray,
        drive: int,
        given: tuple[int, ...],
        test: str,
        g: int,
        N0: np.ndarray | None,
    ) -> np.ndarray | None:
        """The secant on the test's determinant compressed onto its ``g`` leading singular
        vectors (generic rank g), from both sides of the float point ``z`` along the
        swept value ``drive``.  The vectors are those at the first side, 1e-9 of the
        value's scale away, where the test has its generic rank: at the float point itself
        the g-th pair is any of the vectors the lost rank leaves, and such a one can be
        blind to the matrix's motion (a planar loop's twist rows out of its plane)."""
        m, sw = self.model, self.sweep
        nb = sw.model.n
        scale = sw.scale(drive)
        pose = self.pose
        given = tuple(sorted(set(given) | {drive}))
        with m.precision.context():
            # a singular point of the closure is a double root of the closure for the
            # held values: polished at D digits, its configuration (and so the test's
            # determinant) is known to D/2 only, below which the secant's steps are
            # noise; that is what it is placed to (the relocator works at 2N + 10 digits)
            digits = mpmath.mp.dps // 2 if test == "closure" else mpmath.mp.dps
            small = mpmath.mpf(10) ** (POLISH_DIGITS_SPARE - digits) * scale
            target = np.array([mpmath.mpf(repr(float(x))) for x in z], dtype=object)
            q = target.copy()

            vectors: tuple[np.ndarray, np.ndarray] | None = None

            def f(v: Any) -> tuple[Any, np.ndarray]:
                nonlocal q, vectors
                t = target.copy()
                t[drive] = v
                qn, _res = self.closer.polish(q, t, given, pose)
                q = qn
                A = self._matrix(qn[:nb], test)
                if vectors is None:
                    Af = np.array(A if N0 is None else A @ m.asarray(N0.tolist()), dtype=float)
                    U, _s, Vt = np.linalg.svd(Af)
                    vectors = U[:, :g], Vt[:g].T
                return self._det(A, *vectors, N0), qn

            v0 = target[drive]
            h = mpmath.mpf(1e-9) * scale
            a, b = v0 - h, v0 + h
            try:
                fa, _ = f(a)
                fb, qb = f(b)
                for _ in range(_SECANT_STEPS):
                    if fb == fa:
                        break
                    c = b - fb * (b - a) / (fb - fa)
                    fc, qc = f(c)
                    a, fa, b, fb, qb = b, fb, c, fc, qc
                    if abs(b - a) <= small:
                        return qb[:nb]
            except (ArithmeticError, ValueError, np.linalg.LinAlgError):
                return None
        return None
