"""float64 kernels of the Lie layer: the generic code of :mod:`mechsing.lie._so3` and
:mod:`mechsing.lie._se3` for numpy float64 arrays, with the same numbers bit for bit.

The generic code runs one formula on float64, mpmath and sympy arrays alike, which
costs many small numpy calls (stacks of components, three Horner loops per
coefficient set, masks converted from comparison objects, concatenations into the
output).  The sweeps call the Lie layer on float batches thousands of times (small
batches in the path following, large ones in the closure of segments), where that
overhead is most of the time.  Here the float case performs the same floating-point
operations in the same order (so every entry, hence every result downstream, is the
generic one exactly, as the analysis snapshots require) with fewer numpy calls: the
hat matrix as one product with a constant 0/+-1 table (exact), the series of all the
coefficients in one Horner loop over a table of their terms, each branch of a switch
evaluated only when some entry takes it, outputs filled in place instead of stacked.
Each kernel registers itself as the form ``float64`` in the dispatch table of its
generic function (:mod:`mechsing.numeric.dispatch`: one table per function, named after
it), which picks it for float64 arrays only, so mp and exact never leave the generic code; ``MECHSING_FAST=0`` sends
float64 arrays there too.

Switch points and numbers of terms: those of :mod:`mechsing.lie._series`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import lru_cache
from typing import Any

import numpy as np

from mechsing.lie._series import (
    SWITCH_T2,
    _bernoulli_coeffs,
    _n_terms_bernoulli,
    _n_terms_factorial,
)
from mechsing.lie._so3 import _LIE
from mechsing.numeric import FLOAT

_EYE3 = np.eye(3)
_EYE3.flags.writeable = False


@lru_cache(maxsize=16)
def _factorial_table(shifts: tuple[int, ...]) -> np.ndarray:
    """Rows ``(-1)^k / (2k + shift)!`` of the series of each shift, float's number of
    terms each (:func:`mechsing.lie._series._n_terms_factorial`), the shorter rows padded
    with zeros at the high orders (Horner's steps through zeros are exact: each row's
    value is its own series' to the last bit)."""
    n = [_n_terms_factorial(FLOAT.digits, s) for s in shifts]
    table = np.zeros((len(shifts), max(n)))
    for row, (s, m) in enumerate(zip(shifts, n, strict=True)):
        table[row, :m] = [FLOAT.rational((-1) ** k, math.factorial(2 * k + s)) for k in range(m)]
    return table


@lru_cache(maxsize=1)
def _half_cot_table() -> np.ndarray:
    c = _bernoulli_coeffs(_n_terms_bernoulli(FLOAT))
    return np.array([[FLOAT.rational(x.numerator, x.denominator) for x in c]])


def _power_series(x: np.ndarray, table: np.ndarray) -> np.ndarray:
    """``sum_k table[s, k] x^k`` for each row s: (rows,) + x.shape, by Horner's rule on
    all rows at once (the generic :func:`mechsing.lie._series._horner`, step for step:
    each entry's value depends on that entry alone)."""
    shape = np.shape(x)
    x = np.reshape(x, -1)
    acc = np.empty((table.shape[0], x.size))
    acc[...] = table[:, -1:]
    for k in range(table.shape[1] - 2, -1, -1):
        acc *= x
        acc += table[:, k : k + 1]
    return acc.reshape((table.shape[0],) + shape)


def sq(w: np.ndarray) -> np.ndarray:
    """|w|^2 over the last axis (the generic ``dot(w, w)``, summed in the same order)."""
    return np.asarray(w[..., 0] * w[..., 0] + w[..., 1] * w[..., 1] + w[..., 2] * w[..., 2])


def coefficients(t2: np.ndarray, shifts: tuple[int, ...]) -> list[np.ndarray]:
    """The coefficients ``A = sin t / t`` (shift 1), ``B = (1 - cos t)/t^2`` (2) and
    ``C = (t - sin t)/t^3`` (3) at ``t = sqrt(t2)``, for the shifts asked: the closed
    forms of :func:`mechsing.lie._so3.so3_coefficients` above the switch, the series
    below (each branch evaluated only when some entry takes it)."""
    small = t2 <= SWITCH_T2
    anysmall = bool(small.any())
    series = _power_series(t2, _factorial_table(shifts)) if anysmall else None
    if series is not None and bool(small.all()):
        return list(series)
    t = np.sqrt(np.where(small, 1.0, t2))
    s = np.sin(t) if (1 in shifts or 3 in shifts) else None
    out = []
    for k, shift in enumerate(shifts):
        if shift == 1:
            closed = s / t
        elif shift == 2:
            sh = np.sin(t / 2)
            closed = sh * sh * 2 / (t * t)
        elif shift == 3:
            closed = (t - s) / (t * (t * t))
        else:
            raise ValueError(f"no closed form for the factorial series of shift {shift}")
        out.append(closed if series is None else np.where(small, series[k], closed))
    return out


def exp_so3(w: np.ndarray) -> np.ndarray:
    """:func:`mechsing.lie._so3.exp_so3`: ``I + A W + B (W @ W)``, the generic numbers bit
    for bit (the same products, W @ W by the same matrix product)."""
    t2 = sq(w)
    A, B = coefficients(t2, (1, 2))
    W = hat3(w)
    return _EYE3 + A[..., None, None] * W + B[..., None, None] * (W @ W)


def _cross_into(out: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """out = a x b over the last axis, component by component."""
    np.multiply(a[..., 1], b[..., 2], out=out[..., 0])
    out[..., 0] -= a[..., 2] * b[..., 1]
    np.multiply(a[..., 2], b[..., 0], out=out[..., 1])
    out[..., 1] -= a[..., 0] * b[..., 2]
    np.multiply(a[..., 0], b[..., 1], out=out[..., 2])
    out[..., 2] -= a[..., 1] * b[..., 0]
    return out


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a x b over the last axis (float64, broadcast)."""
    # the broadcast shape from the arrays themselves (a third of broadcast_shapes' cost)
    shape = a.shape if a.shape == b.shape else np.broadcast(a, b).shape
    return _cross_into(np.empty(shape), a, b)


def hat3(w: np.ndarray) -> np.ndarray:
    """The skew matrices of w (..., 3), the generic entries (zeros ``w_x * 0``)."""
    out = np.empty(w.shape[:-1] + (3, 3))
    x, y, z = w[..., 0], w[..., 1], w[..., 2]
    z0 = np.multiply(x, 0, out=out[..., 0, 0])
    out[..., 1, 1] = z0
    out[..., 2, 2] = z0
    np.negative(z, out=out[..., 0, 1])
    out[..., 0, 2] = y
    out[..., 1, 0] = z
    np.negative(x, out=out[..., 1, 2])
    np.negative(y, out=out[..., 2, 0])
    out[..., 2, 1] = x
    return out


def pose(R: np.ndarray, p: np.ndarray) -> np.ndarray:
    shape = np.broadcast_shapes(R.shape[:-2], p.shape[:-1])
    out = np.empty(shape + (4, 4))
    out[..., :3, :3] = R
    out[..., :3, 3] = p
    out[..., 3, :3] = 0.0
    out[..., 3, 3] = 1.0
    return out


def inverse(g: np.ndarray) -> np.ndarray:
    """``(R^T, -R^T p)`` (the generic formula, filled in place)."""
    out = np.empty(g.shape)
    Rt = np.swapaxes(g[..., :3, :3], -1, -2)
    out[..., :3, :3] = Rt
    out[..., :3, 3] = -(Rt @ g[..., :3, 3, None])[..., 0]
    out[..., 3, :3] = 0.0
    out[..., 3, 3] = 1.0
    return out


def exp(xi: np.ndarray) -> np.ndarray:
    """:func:`mechsing.lie._se3.exp`: ``R = I + A W + B W^2``, ``p = v + B w x v + C w x
    (w x v)``, the generic numbers bit for bit, filled in place."""
    w = xi[..., :3]
    v = xi[..., 3:]
    t2 = sq(w)
    A, B, C = coefficients(t2, (1, 2, 3))
    out = np.empty(xi.shape[:-1] + (4, 4))
    W = hat3(w)
    out[..., :3, :3] = _EYE3 + A[..., None, None] * W + B[..., None, None] * (W @ W)
    Wv = cross(w, v)
    WWv = cross(w, Wv)
    for i in range(3):
        np.add(v[..., i] + B * Wv[..., i], C * WWv[..., i], out=out[..., i, 3])
    out[..., 3, :3] = 0.0
    out[..., 3, 3] = 1.0
    return out


def _quaternion(R: np.ndarray) -> tuple[np.ndarray, ...]:
    """Shepperd's unit quaternion (w >= 0) of rotation matrices as four arrays, as the
    generic :func:`mechsing.lie._so3.quaternion_parts` (same pivot, first on ties; the
    same divisions), entry by entry."""
    r = [[R[..., i, j] for j in range(3)] for i in range(3)]
    tr = np.asarray(r[0][0] + r[1][1]) + r[2][2]
    t = [1 + tr, 1 + 2 * r[0][0] - tr, 1 + 2 * r[1][1] - tr, 1 + 2 * r[2][2] - tr]
    idx = np.zeros(tr.shape, dtype=np.intp)
    best = t[0]
    for i in range(1, 4):
        better = t[i] > best
        idx[better] = i
        best = np.where(better, t[i], best)
    big = np.sqrt(np.where(best > 0, best, 1.0)) / 2
    d = 4 * big
    s21, s02, s10 = r[2][1] - r[1][2], r[0][2] - r[2][0], r[1][0] - r[0][1]
    a01, a02, a12 = r[0][1] + r[1][0], r[0][2] + r[2][0], r[1][2] + r[2][1]
    # component j of the candidate of pivot i: big at i == j, else table[j][i] / d
    table = [
        (None, s21, s02, s10),
        (s21, None, a01, a02),
        (s02, a01, None, a12),
        (s10, a02, a12, None),
    ]
    q = []
    for j in range(4):
        num = np.choose(idx, [big if x is None else x for x in table[j]])
        q.append(np.where(idx == j, big, num / d))
    neg = q[0] < 0
    if neg.any():
        q = [np.where(neg, -x, x) for x in q]
    return tuple(q)


def quaternion_parts(R: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    qw, qx, qy, qz = _quaternion(R)
    qv = np.empty(R.shape[:-2] + (3,))
    qv[..., 0], qv[..., 1], qv[..., 2] = qx, qy, qz
    return qw, qv


def _log_so3(R: np.ndarray) -> tuple[np.ndarray, ...]:
    """(factor, theta, qw, n, qx, qy, qz): the rotation vector is factor * (qx, qy, qz)."""
    qw, qx, qy, qz = _quaternion(R)
    n2 = np.asarray(qx * qx + qy * qy + qz * qz)
    zero = n2 <= 0
    n = np.sqrt(n2)
    theta = 2 * np.arctan2(n, qw)
    factor = np.where(zero, 2 / np.where(zero, qw, 1.0), theta / np.where(zero, 1.0, n))
    return factor, theta, qw, n, qx, qy, qz


def log_so3_parts(R: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    factor, theta, qw, n, qx, qy, qz = _log_so3(R)
    w = np.empty(R.shape[:-2] + (3,))
    w[..., 0], w[..., 1], w[..., 2] = factor * qx, factor * qy, factor * qz
    return w, theta, qw, n


def log(g: np.ndarray) -> np.ndarray:
    """log of displacements (..., 4, 4): the generic :func:`mechsing.lie._se3.log`."""
    factor, theta, qw, n, qx, qy, qz = _log_so3(g[..., :3, :3])
    out = np.empty(g.shape[:-2] + (6,))
    w = out[..., :3]
    w[..., 0], w[..., 1], w[..., 2] = factor * qx, factor * qy, factor * qz
    t2 = theta * theta
    small = t2 <= SWITCH_T2
    anysmall = bool(small.any())
    if anysmall and bool(small.all()):
        c = _power_series(t2, _half_cot_table())[0]
    else:
        ts = np.where(small, 1.0, theta)
        c = (1 - qw * (ts / 2) / np.where(small, 1.0, n)) / (ts * ts)
        if anysmall:
            c = np.where(small, _power_series(t2, _half_cot_table())[0], c)
    p = g[..., :3, 3]
    wp = cross(w, p)
    wwp = cross(w, wp)
    for i in range(3):
        np.add(p[..., i] - wp[..., i] / 2, c * wwp[..., i], out=out[..., 3 + i])
    return out


def act_screw(g: np.ndarray, xi: np.ndarray) -> np.ndarray:
    """:func:`mechsing.lie._se3.act_screw`: ``(R w, p x R w + R v)`` (the generic
    products), filled in place."""
    R = g[..., :3, :3]
    w = (R @ xi[..., :3, None])[..., 0]
    Rv = (R @ xi[..., 3:, None])[..., 0]
    out = np.empty(w.shape[:-1] + (6,))
    out[..., :3] = w
    np.add(cross(g[..., :3, 3], w), Rv, out=out[..., 3:])
    return out


_BIT_FOR_BIT = "float64 arrays: the generic formula's numbers bit for bit, fewer numpy calls"
_FORMS: list[tuple[str, Callable[..., Any]]] = [
    ("cross", cross),
    ("hat3", hat3),
    ("quaternion_parts", quaternion_parts),
    ("log_so3_parts", log_so3_parts),
    ("pose", pose),
    ("log", log),
    ("inverse", inverse),
    ("act_screw", act_screw),
    ("exp", exp),
    ("exp_so3", exp_so3),
]
for _name, _function in _FORMS:
    _LIE[_name].register("float64", _BIT_FOR_BIT)(_function)
