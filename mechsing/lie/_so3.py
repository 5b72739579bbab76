"""SO(3): hat/vee, exp, log and the left Jacobian (backend-generic, batched).

Conventions: a rotation vector ``w`` (shape (..., 3)) is the axis times the
angle, right-handed; ``hat3(w) @ x == cross(w, x)``.  ``log_so3`` returns the
angle in [0, pi]; at exactly pi the axis sign is the one whose component of
largest magnitude is positive (first of x, y, z on a tie).

References: the exponential of SO(3) and D (exp), their logarithm (log; Shepperd's quaternion-from-matrix
method, the atan2-based angle), the Jacobians of exp.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing.lie._series import factorial_series, half_cot_series, safe, use_series
from mechsing.numeric import backend_of, dispatch
from mechsing.numeric.backend import bool_mask, holds_objects

#: the dispatch table of each Lie function with fast forms (one per signature; their
#: float64 forms: :mod:`mechsing.lie._float`; :mod:`mechsing.numeric.dispatch`)
_LIE = {
    name: dispatch.table(name, f"mechsing.lie.{name}")
    for name in (
        "exp",
        "exp_so3",
        "cross",
        "hat3",
        "quaternion_parts",
        "log_so3_parts",
        "pose",
        "log",
        "inverse",
        "act_screw",
    )
}


def _asarr(x: Any) -> np.ndarray:
    """ndarray of x: object dtype if it holds non-float numbers (mp, exact), else float64."""
    if isinstance(x, np.ndarray):
        return x
    a = np.asarray(x)
    return a if holds_objects(a) else a.astype(np.float64)


def _mask(c: Any) -> np.ndarray:
    """Boolean ndarray of a comparison (object arrays of sympy booleans included)."""
    return bool_mask(c)


def cross(a: Any, b: Any) -> np.ndarray:
    """Cross product over the last axis (backend-generic; numpy's cross rejects objects)."""
    a = _asarr(a)
    b = _asarr(b)
    fast = _LIE["cross"].pick(a, b)
    if fast is not None:
        return fast(a, b)
    return np.stack(
        [
            a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1],
            a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2],
            a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0],
        ],
        axis=-1,
    )


def dot(a: Any, b: Any) -> np.ndarray:
    """Inner product over the last axis, always an ndarray (0-d for two vectors)."""
    a = _asarr(a)
    b = _asarr(b)
    return np.asarray((a * b).sum(axis=-1))


def hat3(w: Any) -> np.ndarray:
    """Skew matrix of a 3-vector: (..., 3) -> (..., 3, 3), ``hat3(w) @ x = w x x``."""
    w = _asarr(w)
    fast = _LIE["hat3"].pick(w)
    if fast is not None:
        return fast(w)
    z = w[..., 0] * 0
    return np.stack(
        [
            np.stack([z, -w[..., 2], w[..., 1]], axis=-1),
            np.stack([w[..., 2], z, -w[..., 0]], axis=-1),
            np.stack([-w[..., 1], w[..., 0], z], axis=-1),
        ],
        axis=-2,
    )


def vee3(W: Any) -> np.ndarray:
    """3-vector of the skew part of a matrix: (..., 3, 3) -> (..., 3).

    For a skew matrix it inverts :func:`hat3`; otherwise it returns the vector of
    ``(W - W^T)/2``.
    """
    W = _asarr(W)
    return np.stack(
        [
            (W[..., 2, 1] - W[..., 1, 2]) / 2,
            (W[..., 0, 2] - W[..., 2, 0]) / 2,
            (W[..., 1, 0] - W[..., 0, 1]) / 2,
        ],
        axis=-1,
    )


def _eye3_like(w: np.ndarray) -> np.ndarray:
    bk = backend_of(w)
    e = bk.eye(3)
    return np.broadcast_to(e, w.shape[:-1] + (3, 3)).copy()


def so3_coefficients(w: np.ndarray) -> tuple[Any, Any, Any, Any]:
    """theta^2 and A = sin t/t, B = (1 - cos t)/t^2, C = (t - sin t)/t^3 at t = |w|."""
    bk = backend_of(w)
    t2 = dot(w, w)
    small = use_series(bk, t2)
    t = bk.sqrt(safe(bk, small, t2))
    s = bk.sin(t)
    A = np.where(small, factorial_series(bk, t2, 1), s / t)
    # (1 - cos t)/t^2 written as 2 sin^2(t/2)/t^2: no cancellation
    sh = bk.sin(t / 2)
    # operand order keeps an array on the left of each product: an mpf times a 0-d array
    # makes mpmath try (through the array's repr) to convert the array before numpy does
    B = np.where(small, factorial_series(bk, t2, 2), sh * sh * 2 / (t * t))
    C = np.where(small, factorial_series(bk, t2, 3), (t - s) / (t * (t * t)))
    return t2, A, B, C


def exp_so3(w: Any) -> np.ndarray:
    """Rotation matrix of a rotation vector (Rodrigues): (..., 3) -> (..., 3, 3).

    Any angle is accepted (tangents beyond pi wrap as rotations do).
    """
    w = _asarr(w)
    fast = _LIE["exp_so3"].pick(w)
    if fast is not None:
        return fast(w)
    _t2, A, B, _C = so3_coefficients(w)
    W = hat3(w)
    return _eye3_like(w) + A[..., None, None] * W + B[..., None, None] * (W @ W)


def left_jacobian_so3(w: Any) -> np.ndarray:
    """Left Jacobian of SO(3) (also the V of exp on SE(3)): I + B W + C W^2.

    ``exp(w + d) ~ exp(J_l(w) d) exp(w)``.
    """
    w = _asarr(w)
    _t2, _A, B, C = so3_coefficients(w)
    W = hat3(w)
    return _eye3_like(w) + B[..., None, None] * W + C[..., None, None] * (W @ W)


def left_jacobian_so3_inv(w: Any) -> np.ndarray:
    """Inverse left Jacobian of SO(3): I - W/2 + c(t) W^2, c = (1 - (t/2)cot(t/2))/t^2.

    Finite for ``|w| < 2 pi`` (singular at 2 pi, outside log's principal branch).
    """
    w = _asarr(w)
    bk = backend_of(w)
    t2 = dot(w, w)
    c = _half_cot_coefficient(bk, t2)
    W = hat3(w)
    return _eye3_like(w) - W / 2 + c[..., None, None] * (W @ W)


def _half_cot_coefficient(bk: Any, t2: Any) -> Any:
    small = use_series(bk, t2)
    t = bk.sqrt(safe(bk, small, t2))
    h = t / 2
    closed = (1 - h * bk.cos(h) / bk.sin(h)) / (t * t)
    return np.where(small, half_cot_series(bk, t2), closed)


# ---------------------------------------------------------------------------
# log: via the unit quaternion (Shepperd), accurate at 0 and at pi
# ---------------------------------------------------------------------------


def quaternion_parts(R: Any) -> tuple[np.ndarray, np.ndarray]:
    """Unit quaternion (w, x, y, z) of a rotation matrix with w >= 0.

    Shepperd's method: the largest of 1 + tr R, 1 + 2 R_ii - tr R (= 4 q_i^2)
    gives the component computed by a square root, the others by division, so
    nothing cancels.  Sign: w >= 0; when w is exactly 0 (a half-turn), the
    component of largest magnitude is positive (first of x, y, z on a tie).

    Returns
    -------
    w : ndarray, shape (...)
    q : ndarray, shape (..., 3)
    """
    R = _asarr(R)
    fast = _LIE["quaternion_parts"].pick(R)
    if fast is not None:
        return fast(R)
    bk = backend_of(R)
    tr = np.asarray(R[..., 0, 0] + R[..., 1, 1]) + R[..., 2, 2]
    t = np.stack(
        [1 + tr, 1 + 2 * R[..., 0, 0] - tr, 1 + 2 * R[..., 1, 1] - tr, 1 + 2 * R[..., 2, 2] - tr],
        axis=-1,
    )
    # argmax over the last axis, first on ties (works on object arrays)
    idx = np.zeros(t.shape[:-1], dtype=int)
    best = t[..., 0]
    for i in range(1, 4):
        better = _mask(t[..., i] > best)
        idx = np.where(better, i, idx)
        best = np.where(better, t[..., i], best)
    big = bk.sqrt(np.where(_mask(best > 0), best, bk.convert(1))) / 2
    d = 4 * big
    s21, s02, s10 = (
        R[..., 2, 1] - R[..., 1, 2],
        R[..., 0, 2] - R[..., 2, 0],
        R[..., 1, 0] - R[..., 0, 1],
    )
    a01, a02, a12 = (
        R[..., 0, 1] + R[..., 1, 0],
        R[..., 0, 2] + R[..., 2, 0],
        R[..., 1, 2] + R[..., 2, 1],
    )
    cand = [
        np.stack([big, s21 / d, s02 / d, s10 / d], axis=-1),
        np.stack([s21 / d, big, a01 / d, a02 / d], axis=-1),
        np.stack([s02 / d, a01 / d, big, a12 / d], axis=-1),
        np.stack([s10 / d, a02 / d, a12 / d, big], axis=-1),
    ]
    q = cand[0]
    for i in range(1, 4):
        q = np.where((idx == i)[..., None], cand[i], q)
    neg = _mask(q[..., 0] < 0)
    q = np.where(neg[..., None], -q, q)
    return q[..., 0], q[..., 1:]


def log_so3_parts(R: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(w_rotvec, theta, cos(theta/2), sin(theta/2)) of a rotation matrix."""
    R = _asarr(R)
    fast = _LIE["log_so3_parts"].pick(R)
    if fast is not None:
        return fast(R)
    bk = backend_of(R)
    qw, qv = quaternion_parts(R)
    n2 = dot(qv, qv)
    zero = _mask(n2 <= 0)
    n = bk.sqrt(n2)
    theta = 2 * bk.atan2(n, qw)
    # theta / n -> 2 / w as n -> 0; atan2(n, w)/n is accurate for every n > 0
    factor = np.where(
        zero, 2 / np.where(zero, qw, bk.convert(1)), np.asarray(theta) / safe(bk, zero, n)
    )
    return factor[..., None] * qv, theta, qw, n


def log_so3(R: Any) -> np.ndarray:
    """Rotation vector of a rotation matrix, angle in [0, pi]: (..., 3, 3) -> (..., 3)."""
    return log_so3_parts(R)[0]
