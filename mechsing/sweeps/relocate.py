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
* a **fold** (the swept value's limit of travel): the same with the roles swapped, the
  passive coordinate that moves most along the fold's direction held and driven, and the
  swept value solved: the test that vanishes at the fold changes sign there as a function
  of that coordinate.

Each secant step gains digits superlinearly from float's point; it stops when the step is
below 10^(5-N) of the variable's scale.  A point whose relocation fails keeps its float
values (its classification then says what N digits see there).
"""

from __future__ import annotations

from typing import Any

import mpmath
import numpy as np

from mechsing.kinematics import Closer, KinematicModel
from mechsing.kinematics.pose import PoseModel
from mechsing.numeric import POLISH_DIGITS_SPARE, Precision, decide_rank, to_float
from mechsing.screws import chain_matrix

__all__ = ["Relocator"]

#: most secant steps of one relocation (each gains digits superlinearly)
_SECANT_STEPS = 16


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
            fm = pb.cm
            with precision.context():
                self.pose = PoseModel(
                    self.model,
                    [self.model.backend.convert(float(x)) for x in to_float(fm.c0)],
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
            if meas.out_point is not None:
                g = m.poses(q)[self.sweep.mech.output.body]
                x = g[:3, :3] @ m.asarray([float(v) for v in meas.out_point]) + g[:3, 3]
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
        joints (object array), or None when the secant does not converge."""
        sw = self.sweep
        nb = sw.model.n
        # the float point's bases and, for a fold, the coordinate that drives it
        pm = sw.measures(np.asarray(z[:nb], dtype=float)[None, :])
        if test not in pm.rank:
            return None
        U, V = pm.basis(test, slice(0, 1))
        U0, V0 = U[0], V[0]
        N0 = None if pm.kernel is None or test not in ("input", "output") else pm.kernel[0]
        if kind == "fold":
            # the passive coordinate that moves most along the fold is held and driven,
            # and the row's swept value is solved
            drive = self._fold_driver(z)
            if drive is None:
                return None
            given = tuple(sorted((set(self.given) - {sw.cols[0]}) | {drive}))
        else:
            drive = sw.cols[0] if kind == "row" else sw.cols[1]
            given = self.given
        return self._secant(z, drive, given, test, U0, V0, N0)

    def _fold_driver(self, z: np.ndarray) -> int | None:
        """At a fold, the unknown coordinate with the largest share of the direction the
        configuration moves in as the swept value reaches its limit."""
        from mechsing.kinematics.newton import scaled_system

        pb = self.sweep.problem
        Js, _ = scaled_system(pb.cm, z)
        free = ~pb.given
        _, s, Vt = np.linalg.svd(Js[:, free])
        x = Vt[-1]
        cols = np.flatnonzero(free)
        return int(cols[int(np.argmax(np.abs(x)))])

    def _secant(
        self,
        z: np.ndarray,
        drive: int,
        given: tuple[int, ...],
        test: str,
        U0: np.ndarray,
        V0: np.ndarray,
        N0: np.ndarray | None,
    ) -> np.ndarray | None:
        m, sw = self.model, self.sweep
        nb = sw.model.n
        scale = sw.scale(drive)
        pose = self.pose
        given = tuple(sorted(set(given) | {drive}))
        with m.precision.context():
            small = mpmath.mpf(10) ** (POLISH_DIGITS_SPARE - mpmath.mp.dps) * scale
            target = np.array([mpmath.mpf(repr(float(x))) for x in z], dtype=object)
            q = target.copy()

            def f(v: Any) -> tuple[Any, np.ndarray]:
                nonlocal q
                t = target.copy()
                t[drive] = v
                qn, _res = self.closer.polish(q, t, given, pose)
                q = qn
                A = self._matrix(qn[:nb], test)
                return self._det(A, U0, V0, N0), qn

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
