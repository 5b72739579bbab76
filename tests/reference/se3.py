"""SE(3) and screw algebra for the tests: hat/skew, exponentials, inverse, adjoint, unit
vectors and the in-plane directions of the conventions.

Twists are (omega, v): angular part first.  :func:`skew`, :func:`hat`, :func:`inv`,
:func:`unit`, :func:`in_plane`, :func:`revolute` and :func:`slide` keep the number type of their
input (floats, or mpmath or sympy numbers in an object array), so one set serves the float checks
and the multiprecision / exact ones; :func:`expm_mp`, :func:`rodrigues_mp` and
:func:`rotation_mp` compute at mpmath's working precision.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import mpmath
import numpy as np
import scipy.linalg
import sympy


def is_float(v: object) -> bool:
    """Whether v holds plain numbers (computed in float64) rather than mpmath / sympy ones."""
    return np.asarray(v).dtype != object


def sqrt(x: object) -> object:
    """The square root in x's number type (float, mpmath or sympy)."""
    if isinstance(x, sympy.Basic):
        return sympy.sqrt(x)
    if isinstance(x, mpmath.mpf):
        return mpmath.sqrt(x)
    return math.sqrt(x)


def wrap(x: float) -> float:
    """An angle modulo 2 pi, in [-pi, pi]."""
    return math.remainder(x, 2 * math.pi)


def skew(w: Sequence | np.ndarray) -> np.ndarray:
    """The 3 x 3 matrix of w x (.), in w's number type."""
    w = np.asarray(w)
    z = w[0] * 0
    return np.array([[z, -w[2], w[1]], [w[2], z, -w[0]], [-w[1], w[0], z]])


def hat(xi: Sequence | np.ndarray) -> np.ndarray:
    """The 4 x 4 matrix of the twist (omega, v), in xi's number type."""
    xi = np.asarray(xi)
    top = np.concatenate([skew(xi[:3]), xi[3:6, None]], axis=1)
    return np.concatenate([top, np.zeros((1, 4), dtype=xi.dtype) * xi[0]], axis=0)


def vee(X: np.ndarray) -> np.ndarray:
    """The twist (omega, v) of a 4 x 4 matrix of se(3)."""
    return np.array([X[2, 1], X[0, 2], X[1, 0], X[0, 3], X[1, 3], X[2, 3]])


def expt(xi: Sequence | np.ndarray) -> np.ndarray:
    """exp of a twist (omega, v) as a 4 x 4 matrix (scipy's Pade expm)."""
    return scipy.linalg.expm(hat(np.asarray(xi, dtype=float)))


def exp_rodrigues(xi: Sequence | np.ndarray) -> np.ndarray:
    """The same exponential in closed form (Rodrigues), for the path trackers, which need many
    of them (checked against :func:`expt` in tests/test_kinematics.py)."""
    w, v = np.asarray(xi[:3], float), np.asarray(xi[3:], float)
    th2 = float(w @ w)
    th = math.sqrt(th2)
    if th < 1e-4:
        a = 1 - th2 / 6 + th2 * th2 / 120
        b = 0.5 - th2 / 24 + th2 * th2 / 720
        c = 1 / 6 - th2 / 120 + th2 * th2 / 5040
    else:
        a = math.sin(th) / th
        b = (1 - math.cos(th)) / th2
        c = (th - math.sin(th)) / (th2 * th)
    W = skew(w)
    W2 = np.outer(w, w) - th2 * np.eye(3)
    g = np.eye(4)
    g[:3, :3] += a * W + b * W2
    g[:3, 3] = v + b * (W @ v) + c * (W2 @ v)
    return g


def expm_mp(xi: Sequence | np.ndarray) -> np.ndarray:
    """exp of a twist (omega, v) at mpmath's working precision (``mpmath.expm`` of its 4 x 4
    matrix), as an object array of mpmath numbers."""
    X = mpmath.matrix(hat(np.asarray(xi, dtype=object)).tolist())
    return np.array(mpmath.expm(X).tolist(), dtype=object)


def rodrigues_mp(u: Sequence, t: object) -> np.ndarray:
    """The rotation by t about the unit vector u (Rodrigues' formula) at mpmath's working
    precision, as an object array of mpmath numbers."""
    K = mpmath.matrix(skew(np.array([mpmath.mpf(x) for x in u], dtype=object)).tolist())
    R = mpmath.eye(3) + mpmath.sin(t) * K + (1 - mpmath.cos(t)) * K * K
    return np.array(R.tolist(), dtype=object)


def rotation_mp(v: Sequence) -> np.ndarray:
    """The rotation matrix of the rotation vector v at mpmath's working precision; the entries
    of v are read as their decimal text."""
    w = [mpmath.mpf(str(x)) for x in v]
    t = mpmath.sqrt(mpmath.fsum(x * x for x in w))
    return rodrigues_mp([x / t for x in w], t)


def inv(g: np.ndarray) -> np.ndarray:
    """The inverse of a rigid displacement (R^T, -R^T p), in g's number type."""
    if not is_float(g):
        R, p = g[:3, :3], g[:3, 3]
        top = np.concatenate([R.T, (-(R.T @ p))[:, None]], axis=1)
        return np.concatenate([top, g[3:4] * 0 + np.array([[0, 0, 0, 1]])], axis=0)
    out = np.eye(4)
    out[:3, :3] = g[:3, :3].T
    out[:3, 3] = -g[:3, :3].T @ g[:3, 3]
    return out


def adjoint(g: np.ndarray) -> np.ndarray:
    """The 6 x 6 adjoint of g acting on twists (omega, v): [[R, 0], [p^ R, R]]."""
    R, p = g[:3, :3], g[:3, 3]
    out = np.zeros((6, 6))
    out[:3, :3] = R
    out[3:, :3] = skew(p) @ R
    out[3:, 3:] = R
    return out


def unit(v: Sequence | np.ndarray) -> np.ndarray:
    """v / |v|, in v's number type."""
    if not is_float(v):
        v = np.asarray(v)
        return v / sqrt(sum(x * x for x in v))
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def in_plane(raw: Sequence | np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """e1 = normalise(a - (a.w) w), a the coordinate axis least aligned with w
    (first in x, y, z order on a tie, decided on the vector as written), e2 = w x e1; in raw's
    number type."""
    raw = np.asarray(raw) if not is_float(raw) else np.asarray(raw, dtype=float)
    mags = [abs(x) for x in raw]
    i = 0
    for k in (1, 2):
        if mags[k] < mags[i]:
            i = k
    w = unit(raw)
    a = np.zeros(3) if is_float(w) else w * 0
    a[i] = a[i] + 1
    e1 = unit(a - w[i] * w)
    return e1, np.cross(w, e1)


def revolute(u: Sequence | np.ndarray, p: Sequence | np.ndarray) -> np.ndarray:
    """The unit twist of a rotation about the line through p along u: (u, p x u), in the number
    type of u and p."""
    exact = not (is_float(u) and is_float(p))
    u = unit(np.asarray(u, dtype=object) if exact else u)
    return np.concatenate([u, np.cross(np.asarray(p) if exact else np.asarray(p, float), u)])


def slide(u: Sequence | np.ndarray) -> np.ndarray:
    """The unit twist of a translation along u: (0, u), in u's number type."""
    u = unit(u)
    return np.concatenate([np.zeros(3) if is_float(u) else u * 0, u])


def screw_motion(u: np.ndarray, N: np.ndarray, theta: float, d: float) -> np.ndarray:
    """The screw motion by theta about the line (N, u) sliding d along it, from scipy's
    Rotation (orthogonal to rounding) and Chasles: p = (I - R) N + d u."""
    from scipy.spatial.transform import Rotation

    g = np.eye(4)
    g[:3, :3] = Rotation.from_rotvec(theta * u).as_matrix()
    g[:3, 3] = N - g[:3, :3] @ N + d * u
    return g
