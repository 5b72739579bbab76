"""The Rodrigues closed forms of the exponential of a joint's float screws.

The fast forms of a joint's element at a float batch (the dispatch table ``joint
element`` of :func:`mechsing.kinematics.forward.element` takes them,
:mod:`mechsing.numeric.dispatch`), for the sweeps' and the scanner's batches:

``one-dof``
    ``exp(th e)`` of a one-dof float screw ``e = (u, v)`` (|u| = 1, or u = 0) for an
    array of angles: ``R = I + sin K + (1 - cos) K^2``,
    ``p = (th I + (1 - cos) K + (th - sin) K^2) v`` with ``K = u^`` (the closed form
    :func:`mechsing.lie.exp` evaluates by series; equal to it to rounding);
the entrywise one-dof form
    the same sums in the same order for a large batch of finite angles, entry by entry
    (bit for bit the ``one-dof`` numbers, fewer passes over the batch);
``spherical``
    ``exp(q B)`` of a spherical joint: the turn ``R = exp(w)`` about the joint's centre
    c (``v = c x w``): ``p = (I - R) c`` (equal to :func:`mechsing.lie.exp` to rounding).

The tables of a screw (K, K^2, the centre) are kept per basis (bounded caches).
"""

from __future__ import annotations

from functools import lru_cache
from typing import Any

import numpy as np

from mechsing.lie._se3 import ANGULAR, LINEAR, pose
from mechsing.lie._so3 import exp_so3
from mechsing.numeric import dispatch

__all__: list[str] = []

#: from this many angles on, the one-dof form fills its entries one by one
#: (:func:`one_dof_entrywise`; a size threshold, :func:`mechsing.numeric.dispatch.threshold`)
ENTRYWISE = 64


def _hat(w: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


@lru_cache(maxsize=1024)
def _one_dof_table(key: bytes) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool]:
    """K, K^2, v and whether the screw rotates, of a one-dof float screw (its bytes)."""
    e = np.frombuffer(key, dtype=np.float64)
    u, v = np.array(e[ANGULAR]), np.array(e[LINEAR])
    K = _hat(u)
    return K, K @ K, v, bool(np.any(u))


def one_dof_exp(e: np.ndarray, th: np.ndarray) -> np.ndarray:
    """``exp(th e)`` of a one-dof float screw ``e`` (6,) at the angles ``th`` (...,):
    (..., 4, 4) (module docstring)."""
    table = _one_dof_table(np.asarray(e, dtype=np.float64).tobytes())
    K, K2, v, rotates = table
    if rotates and th.size >= dispatch.threshold(ENTRYWISE) and np.isfinite(th).all():
        return one_dof_entrywise(table, th)
    out = np.zeros(th.shape + (4, 4))
    out[..., 3, 3] = 1.0
    if not rotates:
        out[..., 0, 0] = out[..., 1, 1] = out[..., 2, 2] = 1.0
        out[..., :3, 3] = th[..., None] * v
        return out
    s, c1 = np.sin(th), 1.0 - np.cos(th)
    out[..., :3, :3] = np.eye(3) + s[..., None, None] * K + c1[..., None, None] * K2
    out[..., :3, 3] = th[..., None] * v + c1[..., None] * (K @ v) + (th - s)[..., None] * (K2 @ v)
    return out


def one_dof_entrywise(table: tuple[Any, ...], th: np.ndarray) -> np.ndarray:
    """The one-dof form of a rotating screw at finite angles, entry by entry: the same
    sums ``(I + sin K) + (1 - cos) K^2`` and ``(th v + (1 - cos) K v) + (th - sin) K^2 v``
    in the same order, each over the batch at once, those of an entry where K and K^2
    vanish (exactly I's entry, for finite angles) not computed; fewer passes over a
    large batch than the (N, 3, 3) broadcasts, the same numbers bit for bit."""
    K, K2, v, _ = table
    s, c1 = np.sin(th), 1.0 - np.cos(th)
    out = np.zeros(th.shape + (4, 4))
    for i in range(3):
        for j in range(3):
            one = 1.0 if i == j else 0.0
            if K[i, j] == 0 and K2[i, j] == 0:
                if one:
                    out[..., i, j] = one
                continue
            np.add(one + s * K[i, j], c1 * K2[i, j], out=out[..., i, j])
    Kv, K2v, ts = K @ v, K2 @ v, th - s
    for i in range(3):
        np.add(th * v[i] + c1 * Kv[i], ts * K2v[i], out=out[..., i, 3])
    out[..., 3, 3] = 1.0
    return out


@lru_cache(maxsize=1024)
def _centre(key: bytes) -> np.ndarray:
    """The centre c of a spherical float basis (its bytes): ``v_i = c x w_i = -w_i^ c``
    for the three rotations, by least squares."""
    B = np.frombuffer(key, dtype=np.float64).reshape(-1, 6)
    A = -np.concatenate([_hat(w) for w in B[:, ANGULAR]])
    return np.linalg.lstsq(A, B[:, LINEAR].reshape(-1), rcond=None)[0]


def spherical_exp(basis: np.ndarray, qj: np.ndarray) -> np.ndarray:
    """``exp(q B)`` of a spherical joint (float) at the values ``qj`` (..., 3):
    ``R = exp(w)`` with ``w`` the angular part of ``q B``, ``p = (I - R) c``."""
    x = qj @ basis
    R = exp_so3(x[..., ANGULAR])
    c = _centre(np.asarray(basis, dtype=np.float64).tobytes())
    return pose(R, c - R @ c)
