"""Unit quaternions: the double cover U -> SO(3) (backend-generic, batched).

Conventions
-----------
* Layout ``q = (w, x, y, z)``, **scalar first**, shape (..., 4).
  ``scipy.spatial.transform.Rotation`` is scalar-LAST by default: convert at
  the boundary with ``q[..., [1, 2, 3, 0]]`` (to scipy) or
  ``q[..., [3, 0, 1, 2]]`` (from scipy).
* Hamilton product, ``i j = k``.  The rotation of a unit quaternion
  ``q = (cos(t/2), sin(t/2) u)`` is the right-handed rotation by ``t`` about
  ``u``: ``R(q) v = q (0, v) q*``, and ``R(p q) = R(p) R(q)``.
* ``q`` and ``-q`` are the same rotation.  Functions returning a quaternion
  from a rotation choose ``w >= 0``; at ``w == 0`` (a half-turn) the vector
  component of largest magnitude is positive (first of x, y, z on a tie) --
  the same rule as :func:`mechsing.lie.log_so3` at angle pi.
* :func:`quat_to_rotation_matrix` and :func:`quat_rotate` use the homogeneous
  (rational) formulas, so they accept any non-zero quaternion (its direction
  is the rotation); with ``q = (1, a)`` they give the Cayley transform of the
  Gibbs vector ``a`` (:mod:`mechsing.lie.cayley`).

Every function runs unchanged on float64 arrays, on object arrays of mpmath
numbers (mp:N) and on object arrays of sympy numbers (exact); see
:mod:`mechsing.numeric`.

References: the exponential of D (the quaternion form of exp, Sophus), the logarithm of D
(Shepperd's quaternion-from-matrix method, the atan-based log of Hertzberg et
al. 2013).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing.lie._so3 import _asarr as _arr
from mechsing.lie._so3 import _mask, cross, hat3, quaternion_parts
from mechsing.lie._so3 import dot as _dot
from mechsing.numeric import backend_of

__all__ = [
    "quat_conjugate",
    "quat_exp",
    "quat_from_rotation_matrix",
    "quat_inverse",
    "quat_log",
    "quat_multiply",
    "quat_rotate",
    "quat_to_rotation_matrix",
]

# Series switch points (private to their formulas, derived from the backend's
# eps by Backend.threshold):
#   sin(t/2)/t = (1 - t^2/24 + t^4/1920)/2   first neglected term O(t^6)
#   atan(s)/s  =  1 - s^2/3 + s^4/5          first neglected term O(s^6)
_SINC_HALF_ORDER = 5
_ATAN_ORDER = 5


def _check_last(x: np.ndarray, n: int, name: str, what: str) -> None:
    if x.ndim < 1 or x.shape[-1] != n:
        raise ValueError(f"{name}: expected {what} of shape (..., {n}), got shape {x.shape}")


def quat_multiply(p: Any, q: Any) -> np.ndarray:
    """Hamilton product ``p q``: (..., 4), (..., 4) -> (..., 4).

    ``R(p q) = R(p) R(q)`` (apply q first).  Broadcasts over leading axes.
    """
    p = _arr(p)
    q = _arr(q)
    _check_last(p, 4, "quat_multiply", "a quaternion (w, x, y, z)")
    _check_last(q, 4, "quat_multiply", "a quaternion (w, x, y, z)")
    pw, pv = p[..., 0], p[..., 1:]
    qw, qv = q[..., 0], q[..., 1:]
    w = pw * qw - _dot(pv, qv)
    v = pw[..., None] * qv + qw[..., None] * pv + cross(pv, qv)
    return np.concatenate([np.asarray(w)[..., None], v], axis=-1)


def quat_conjugate(q: Any) -> np.ndarray:
    """Conjugate ``(w, -x, -y, -z)``: (..., 4) -> (..., 4); the inverse of a unit quaternion."""
    q = _arr(q)
    _check_last(q, 4, "quat_conjugate", "a quaternion (w, x, y, z)")
    return np.concatenate([q[..., :1], -q[..., 1:]], axis=-1)


def quat_inverse(q: Any) -> np.ndarray:
    """Inverse ``q* / |q|^2`` of a non-zero quaternion: (..., 4) -> (..., 4).

    Raises
    ------
    ValueError
        if some quaternion is zero.
    """
    q = _arr(q)
    _check_last(q, 4, "quat_inverse", "a quaternion (w, x, y, z)")
    n2 = _dot(q, q)
    if np.any(_mask(n2 == 0)):
        raise ValueError("quat_inverse: the zero quaternion has no inverse")
    return quat_conjugate(q) / n2[..., None]


def quat_rotate(q: Any, v: Any) -> np.ndarray:
    """Rotate vectors: ``R(q) v``, (..., 4), (..., 3) -> (..., 3).

    ``R(q) v = v + (2 w (u x v) + 2 u x (u x v)) / |q|^2`` with ``q = (w, u)``:
    the vector part of ``q (0, v) q^-1``, valid for any non-zero q and
    rational in q.
    """
    q = _arr(q)
    v = _arr(v)
    _check_last(q, 4, "quat_rotate", "a quaternion (w, x, y, z)")
    _check_last(v, 3, "quat_rotate", "a vector")
    w, u = q[..., 0], q[..., 1:]
    n2 = _dot(q, q)
    uv = cross(u, v)
    return v + (2 * w[..., None] * uv + 2 * cross(u, uv)) / n2[..., None]


def quat_to_rotation_matrix(q: Any) -> np.ndarray:
    """Rotation matrix of a quaternion: (..., 4) -> (..., 3, 3).

    ``R = I + (2 w U + 2 U^2) / |q|^2`` with ``U = hat(u)``, ``q = (w, u)``;
    for a unit quaternion this is the usual ``I + 2 w U + 2 U^2``.  Rational in
    q, so a rational q gives an exactly orthogonal rational matrix.
    """
    q = _arr(q)
    _check_last(q, 4, "quat_to_rotation_matrix", "a quaternion (w, x, y, z)")
    bk = backend_of(q)
    w = q[..., 0]
    U = hat3(q[..., 1:])
    n2 = _dot(q, q)[..., None, None]
    eye = np.broadcast_to(bk.eye(3), q.shape[:-1] + (3, 3))
    return eye + (2 * w[..., None, None] * U + 2 * (U @ U)) / n2


def quat_from_rotation_matrix(R: Any) -> np.ndarray:
    """Unit quaternion of a rotation matrix (Shepperd's method): (..., 3, 3) -> (..., 4).

    The largest of ``1 + tr R = 4 w^2`` and ``1 + 2 R_ii - tr R = 4 q_i^2``
    (first on a tie) gives its component by a square root; the three others
    follow by division by it, so nothing cancels, at angle 0 and at pi alike.

    Sign: ``w >= 0``; where ``w == 0`` exactly (a half-turn), the vector
    component of largest magnitude is positive (first of x, y, z on a tie).
    Near (not at) a half-turn the sign follows w, so the map is discontinuous
    there, as any section of the double cover must be.

    The result is unit to the accuracy of R's orthogonality (it is not
    renormalised).  References: the logarithm of D.
    """
    R = _arr(R)
    if R.ndim < 2 or R.shape[-2:] != (3, 3):
        raise ValueError(f"quat_from_rotation_matrix: expected shape (..., 3, 3), got {R.shape}")
    w, v = quaternion_parts(R)
    return np.concatenate([w[..., None], v], axis=-1)


def quat_exp(phi: Any) -> np.ndarray:
    """Unit quaternion of a rotation vector: (..., 3) -> (..., 4).

    ``exp(phi) = (cos(t/2), sin(t/2)/t * phi)`` with ``t = |phi|`` (the
    right-handed rotation by t about phi/t).  ``sin(t/2)/t`` switches to its
    series ``(1 - t^2/24 + t^4/1920)/2`` below ``Backend.threshold(5)``
    (exactly at 0 in exact mode).  Any angle is accepted; ``w < 0`` for
    ``pi < t < 3 pi`` (the other sheet of the double cover).
    """
    phi = _arr(phi)
    _check_last(phi, 3, "quat_exp", "a rotation vector")
    bk = backend_of(phi)
    t2 = _dot(phi, phi)
    thr = bk.threshold(_SINC_HALF_ORDER)
    small = _mask(t2 <= thr * thr)
    t = bk.sqrt(np.where(small, bk.convert(1), t2))
    closed = bk.sin(t / 2) / t
    series = (1 - t2 / 24 + t2 * t2 / 1920) / 2
    s = np.where(small, series, closed)
    # cos(t/2) itself needs no series; at t2 = 0 it is exactly 1
    c = bk.cos(bk.sqrt(t2) / 2)
    return np.concatenate([c[..., None], s[..., None] * phi], axis=-1)


def quat_log(q: Any) -> np.ndarray:
    """Rotation vector of a non-zero quaternion, angle in [0, pi]: (..., 4) -> (..., 3).

    atan-based (the logarithm of D, Hertzberg et al. 2013): with ``q`` replaced by
    ``-q`` where ``w < 0``, ``n = |(x, y, z)|``, the angle is
    ``t = 2 atan2(n, w)`` and the rotation vector ``(t / n) (x, y, z)``;
    ``t / n`` switches to the series ``(2/w)(1 - s^2/3 + s^4/5)``, ``s = n/w``,
    when ``n <= threshold(5) w`` (exactly at n = 0 in exact mode).  atan2 is
    well conditioned at both ends, so the log is accurate near 0 and near pi.
    Only the direction of q matters (q need not be unit).

    At ``w == 0`` (exactly a half-turn) the result is ``pi (x, y, z)/n``, whose
    sign is the sign of q: q and -q give the two valid answers ``+-pi u``.

    Raises
    ------
    ValueError
        if some quaternion is zero.
    """
    q = _arr(q)
    _check_last(q, 4, "quat_log", "a quaternion (w, x, y, z)")
    bk = backend_of(q)
    neg = _mask(q[..., 0] < 0)
    q = np.where(neg[..., None], -q, q)
    w, u = q[..., 0], q[..., 1:]
    n2 = _dot(u, u)
    if np.any(_mask(n2 + w * w == 0)):
        raise ValueError("quat_log: the zero quaternion is not a rotation")
    thr = bk.threshold(_ATAN_ORDER)
    small = _mask(n2 <= thr * thr * w * w)
    one = bk.convert(1)
    n = bk.sqrt(np.where(small, one, n2))
    closed = 2 * bk.atan2(n, w) / n
    ws = np.where(small, w, one)  # w > 0 wherever small holds (q != 0)
    s2 = n2 / (ws * ws)
    series = 2 * (1 - s2 / 3 + s2 * s2 / 5) / ws
    factor = np.where(small, series, closed)
    return factor[..., None] * u
