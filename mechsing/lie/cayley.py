"""Cayley transforms on SO(3) and on D = SE(3) (backend-generic, batched, rational).

Conventions
-----------
* **Gibbs vector** ``a`` (shape (..., 3)): ``cay(a) = (I + a^)(I - a^)^-1`` is the
  right-handed rotation by ``2 atan|a|`` about ``a``, so ``a = tan(t/2) u``.
  Closed form (no matrix inverse, since ``a^3 = -|a|^2 a^``)::

      cay(a) = I + 2 (a^ + a^ a^) / (1 + |a|^2)

  It is rational in ``a``: a rational Gibbs vector gives an exactly orthogonal
  rational matrix with det 1 in exact mode.  It is the rotation of the
  quaternion ``(1, a)`` (:func:`mechsing.lie.quaternion.quat_to_rotation_matrix`).
* Inverse: ``a = vee(R - R^T) / (1 + tr R)``.  It is undefined at half-turns
  (``1 + tr R = 0``, ``|a| = tan(pi/2)``); there the inverse maps raise
  ``ValueError``.  Close to a half-turn ``|a|`` is large and its relative
  accuracy in float is about ``eps / (1 + tr R)``.
* **SE(3)** (Selig): the Cayley map of the 4x4 representation,
  ``cay(xi) = (I + xi^)(I - xi^)^-1`` for a twist ``xi = (omega, v)``, is the
  displacement ``(R, p)`` with ::

      R = cay(omega),   p = (I + R) v = 2 (v + omega x v + omega (omega . v)) / (1 + |omega|^2)

  and its inverse is ``omega = cay^-1(R)``, ``v = (p - omega x p) / 2`` (since
  ``I + R = 2 (I - omega^)^-1``).  Near the identity ``cay(xi) ~ I + 2 xi^``
  (twice the exponential's first order).  It is equivariant:
  ``cay(Ad(g) xi) = g cay(xi) g^-1``.  This is the Cayley map of the 4x4
  representation, not the one of the adjoint (6x6) representation.

References: exact alternatives; J. M. Selig, *Geometric Fundamentals of Robotics*,
2nd ed., Springer 2005 (Cayley map); J. M. Selig, "Cayley maps for SE(3)",
12th IFToMM World Congress, 2007; A. Müller, Proc. R. Soc. A 477 (2021) 20210303.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing.lie._se3 import ANGULAR, LINEAR
from mechsing.lie._so3 import _asarr as _arr
from mechsing.lie._so3 import cross, hat3, vee3
from mechsing.lie._so3 import dot as _dot
from mechsing.numeric import backend_of
from mechsing.numeric.backend import bool_mask

__all__ = [
    "cayley_se3",
    "cayley_se3_inverse",
    "cayley_skew",
    "cayley_skew_inverse",
    "cayley_so3",
    "cayley_so3_inverse",
]


def _check(x: np.ndarray, tail: tuple[int, ...], name: str, what: str) -> None:
    if x.ndim < len(tail) or x.shape[x.ndim - len(tail) :] != tail:
        shape = "(..., " + ", ".join(str(t) for t in tail) + ")"
        raise ValueError(f"{name}: expected {what} of shape {shape}, got shape {x.shape}")


def cayley_so3(a: Any) -> np.ndarray:
    """Rotation matrix of a Gibbs vector: (..., 3) -> (..., 3, 3).

    ``cay(a) = (I + a^)(I - a^)^-1 = I + 2 (a^ + a^ a^)/(1 + |a|^2)``: the
    right-handed rotation by ``2 atan|a|`` about ``a``.  Rational in ``a``.
    """
    a = _arr(a)
    _check(a, (3,), "cayley_so3", "a Gibbs vector")
    bk = backend_of(a)
    A = hat3(a)
    den = np.asarray(1 + _dot(a, a))[..., None, None]
    eye = np.broadcast_to(bk.eye(3), a.shape[:-1] + (3, 3))
    return eye + 2 * (A + A @ A) / den


def cayley_skew(A: Any) -> np.ndarray:
    """Cayley transform of a skew-symmetric operator: (..., 3, 3) -> (..., 3, 3).

    ``(I + A)(I - A)^-1`` for ``A = a^``; only the skew part ``(A - A^T)/2``
    of the input is used.  Same as ``cayley_so3(vee(A))``.
    """
    A = _arr(A)
    _check(A, (3, 3), "cayley_skew", "a skew matrix")
    return cayley_so3(vee3(A))


def cayley_so3_inverse(R: Any) -> np.ndarray:
    """Gibbs vector of a rotation matrix: (..., 3, 3) -> (..., 3).

    ``a = vee(R - R^T) / (1 + tr R)`` (rational in R).

    Raises
    ------
    ValueError
        at a half-turn (``1 + tr R <= 0``: rotation angle pi), where the Gibbs
        vector is infinite.
    """
    R = _arr(R)
    _check(R, (3, 3), "cayley_so3_inverse", "a rotation matrix")
    den = np.asarray(1 + R[..., 0, 0] + R[..., 1, 1] + R[..., 2, 2])
    bad = np.asarray(den <= 0)
    bad = bool_mask(bad)
    if np.any(bad):
        where = tuple(int(i) for i in np.argwhere(bad)[0]) if bad.ndim else ()
        raise ValueError(
            "cayley_so3_inverse: the Cayley transform is not defined at a half-turn "
            f"(rotation angle pi, 1 + trace R = 0) at index {where}; use the "
            "exponential chart (log) or a quaternion there"
        )
    return 2 * vee3(R) / den[..., None]


def cayley_skew_inverse(R: Any) -> np.ndarray:
    """Skew operator ``A = (R - I)(R + I)^-1`` of a rotation matrix: (..., 3, 3) -> (..., 3, 3).

    ``hat`` of :func:`cayley_so3_inverse`; raises ``ValueError`` at half-turns.
    """
    return hat3(cayley_so3_inverse(R))


def cayley_se3(xi: Any) -> np.ndarray:
    """Cayley map of a twist (Selig): (..., 6) -> (..., 4, 4).

    ``(I + xi^)(I - xi^)^-1`` with ``xi^`` the 4x4 hat of ``xi = (omega, v)``:
    ``R = cayley_so3(omega)``,
    ``p = 2 (v + omega x v + omega (omega . v)) / (1 + |omega|^2)``.
    Rational in xi.
    """
    xi = _arr(xi)
    _check(xi, (6,), "cayley_se3", "a twist (omega, v)")
    bk = backend_of(xi)
    w = xi[..., ANGULAR]
    v = xi[..., LINEAR]
    R = cayley_so3(w)
    p = 2 * (v + cross(w, v) + _dot(w, v)[..., None] * w) / np.asarray(1 + _dot(w, w))[..., None]
    top = np.concatenate([R, p[..., None]], axis=-1)
    row = np.concatenate([bk.zeros(3), bk.eye(1)[0]])
    bottom = np.broadcast_to(row, xi.shape[:-1] + (1, 4))
    return np.concatenate([top, bottom], axis=-2)


def cayley_se3_inverse(g: Any) -> np.ndarray:
    """Twist whose Cayley map is the displacement g: (..., 4, 4) -> (..., 6).

    ``omega = cayley_so3_inverse(R)``, ``v = (p - omega x p)/2`` (rational in g).

    Raises
    ------
    ValueError
        if the rotation of g is a half-turn.
    """
    g = _arr(g)
    _check(g, (4, 4), "cayley_se3_inverse", "a displacement")
    w = cayley_so3_inverse(g[..., :3, :3])
    p = g[..., :3, 3]
    v = (p - cross(w, p)) / 2
    return np.concatenate([w, v], axis=-1)
