"""The scanner's screen compiled with numba (optional: the ``fast`` extra).

Owns :func:`screen_bounds` (the compiled screen) and :func:`available`.

One pass per configuration does what :class:`mechsing.kinematics.forward.SerialJacobian`
and the screen of :mod:`mechsing.sweeps.scan` do with numpy arrays: the product of
exponentials of a serial chain of one-dof joints in the commensurate frame (the
same Rodrigues update, the same table ``[K, K^2, K a, K^2 a, u, v]`` per joint),
the chain's matrix (current screws, or the output point's velocity), its length
columns times L, then the certified lower bound of sigma_min / sigma_max:
``|det| / (|J|_F^2 / (m - 1))^((m - 1) / 2) / |J|_F`` with the determinant of J
(square) or of its m x m Gram matrix (then its square root), minus the
determinant's backward error.  The matrix stays in registers and the stack: per
configuration it reads the joint values and writes one float, so the work is
compute-bound, not memory-bound.

The determinant is LU with partial pivoting written out, so the bound differs from
numpy's (LAPACK) by rounding only; configurations at the screen's threshold get
the SVD in both paths, so the verdicts are the same (tested).

Numba is imported lazily; :func:`available` is False without it, or when fast paths
are off (``MECHSING_FAST=0``, or its alias ``MECHSING_NO_COMPILED=1``:
:mod:`mechsing.numeric.dispatch`, where :func:`screen_bounds` is the form ``compiled``
of the table ``serial screen``), and the scanner then uses its numpy path.  It is the serial test's
optional backend (:meth:`mechsing.singularity.criteria.SerialTest.screen`).
"""

from __future__ import annotations

import sys
from typing import Any

import numpy as np

from mechsing.numeric import dispatch
from mechsing.singularity.criteria import SerialTest

__all__ = ["available", "screen_bounds"]

_KERNEL: list[Any] = []


def available() -> bool:
    """Is the compiled screen usable (numba installed, not switched off)?"""
    if dispatch.table("serial screen").get("compiled") is None:
        return False
    try:
        import numba  # noqa: F401
    except ImportError:
        return False
    return True


def _build() -> Any:
    import numba

    @numba.njit(cache=False, nogil=True, fastmath=True, error_model="numpy")
    def kernel(
        Q, cols, pos, T, h, rot, point, has_point, lengths, L, err, out
    ):  # pragma: no cover - compiled
        N = Q.shape[0]
        nj = cols.shape[0]
        k = pos.shape[0]
        rows = 3 if has_point else 6
        m = min(rows, k)
        J = np.empty((6, k))
        M = np.empty((m, m))
        R = np.empty((3, 3))
        RT = np.empty((3, 10))
        P = np.empty(3)
        for r in range(N):
            for a in range(3):
                for b in range(3):
                    R[a, b] = 1.0 if a == b else 0.0
                P[a] = 0.0
            for i in range(nj):
                for a in range(3):
                    for c in range(10):
                        acc = 0.0
                        for b in range(3):
                            acc += R[a, b] * T[i, b, c]
                        RT[a, c] = acc
                p = pos[i]
                w0, w1, w2 = RT[0, 8], RT[1, 8], RT[2, 8]
                J[0, p] = w0
                J[1, p] = w1
                J[2, p] = w2
                J[3, p] = RT[0, 9] + (P[1] * w2 - P[2] * w1)
                J[4, p] = RT[1, 9] + (P[2] * w0 - P[0] * w2)
                J[5, p] = RT[2, 9] + (P[0] * w1 - P[1] * w0)
                if i == nj - 1 and not has_point:
                    break
                th = Q[r, cols[i]]
                if rot[i]:
                    s = np.sin(th)
                    c1 = 1.0 - np.cos(th)
                    for a in range(3):
                        for b in range(3):
                            R[a, b] = R[a, b] + s * RT[a, b] + c1 * RT[a, 3 + b]
                        P[a] = P[a] - s * RT[a, 6] - c1 * RT[a, 7]
                    if h[i] != 0.0:
                        for a in range(3):
                            P[a] = P[a] + (h[i] * th) * RT[a, 8]
                else:
                    for a in range(3):
                        P[a] = P[a] + th * RT[a, 9]
            if has_point:
                X0 = R[0, 0] * point[0] + R[0, 1] * point[1] + R[0, 2] * point[2] + P[0]
                X1 = R[1, 0] * point[0] + R[1, 1] * point[1] + R[1, 2] * point[2] + P[1]
                X2 = R[2, 0] * point[0] + R[2, 1] * point[1] + R[2, 2] * point[2] + P[2]
                for p in range(k):
                    w0, w1, w2 = J[0, p], J[1, p], J[2, p]
                    v0 = J[3, p] + (w1 * X2 - w2 * X1)
                    v1 = J[4, p] + (w2 * X0 - w0 * X2)
                    v2 = J[5, p] + (w0 * X1 - w1 * X0)
                    J[0, p] = v0
                    J[1, p] = v1
                    J[2, p] = v2
            F2 = 0.0
            for p in range(k):
                if lengths[p]:
                    for a in range(rows):
                        J[a, p] *= L
                for a in range(rows):
                    F2 += J[a, p] * J[a, p]
            if m < 2 or F2 <= 0.0:
                out[r] = 0.0
                continue
            # the m x m matrix whose determinant is taken: J (square) or its Gram matrix
            if rows == k:
                for a in range(m):
                    for b in range(m):
                        M[a, b] = J[a, b]
            elif k < rows:
                for a in range(m):
                    for b in range(m):
                        acc = 0.0
                        for c in range(rows):
                            acc += J[c, a] * J[c, b]
                        M[a, b] = acc
            else:
                for a in range(m):
                    for b in range(m):
                        acc = 0.0
                        for c in range(k):
                            acc += J[a, c] * J[b, c]
                        M[a, b] = acc
            det = 1.0
            for c in range(m):
                piv = c
                big = abs(M[c, c])
                for a in range(c + 1, m):
                    if abs(M[a, c]) > big:
                        big = abs(M[a, c])
                        piv = a
                if big == 0.0:
                    det = 0.0
                    break
                if piv != c:
                    for b in range(m):
                        tmp = M[c, b]
                        M[c, b] = M[piv, b]
                        M[piv, b] = tmp
                    det = -det
                det *= M[c, c]
                for a in range(c + 1, m):
                    f = M[a, c] / M[c, c]
                    for b in range(c + 1, m):
                        M[a, b] -= f * M[c, b]
            d = abs(det) if rows == k else np.sqrt(max(det, 0.0))
            lb = d / (F2 / (m - 1)) ** ((m - 1) / 2) / np.sqrt(F2)
            out[r] = max(lb - err, 0.0)

    return kernel


@dispatch.table(
    "serial screen", "mechsing.singularity.criteria.SerialTest's numpy screen"
).register(
    "compiled",
    "the scan's serial chain of one-dof joints, compiled with numba (its screen's bound "
    "to the determinant's backward error)",
    accepts=None,  # the scanner asks for it where its chain is a SerialJacobian's
)
def screen_bounds(serial: Any, Q: np.ndarray, err: float) -> np.ndarray:
    """The screen's lower bound of sigma_min / sigma_max at every row of Q, for a
    :class:`~mechsing.kinematics.forward.SerialJacobian` chain (compiled on first use)."""
    if not _KERNEL:
        _KERNEL.append(_build())
    tables = serial.table
    cols = np.array([t[0] for t in tables], dtype=np.int64)
    pos = np.array([t[1] for t in tables], dtype=np.int64)
    T = np.ascontiguousarray(np.stack([t[2] for t in tables]), dtype=float)
    h = np.array([t[3] for t in tables], dtype=float)
    rot = np.array([t[4] for t in tables], dtype=np.bool_)
    has_point = serial.point is not None
    point = np.zeros(3) if serial.point is None else np.asarray(serial.point, dtype=float)
    lc = serial.frame.lengths(serial.order)
    lengths = (
        np.zeros(serial.columns, dtype=np.bool_) if lc is None else np.asarray(lc, dtype=np.bool_)
    )
    out = np.empty(Q.shape[0])
    _KERNEL[0](
        np.ascontiguousarray(Q, dtype=float),
        cols,
        pos,
        T,
        h,
        rot,
        point,
        has_point,
        lengths,
        float(serial.frame.L),
        float(err),
        out,
    )
    return out


# the serial test's optional compiled screen (its numpy screen stays the scan's default)
SerialTest.register_screen(sys.modules[__name__])
