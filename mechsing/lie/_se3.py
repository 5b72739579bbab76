"""D = SE(3) and its Lie algebra of screws (backend-generic, batched).

Conventions (as in the README):

* twist ``xi = (omega, v)`` shape (..., 6): ``omega = xi[..., ANGULAR]``, ``v =
  xi[..., LINEAR]`` the velocity of the body point at the ground origin;
* wrench ``(f, m)``: force, then moment about the ground origin;
* displacement ``g`` shape (..., 4, 4) = ``[[R, p], [0, 1]]``, ``x -> R x + p``;
* bracket ``[x, y]`` = commutator of the 4x4 hats
  = ``(w1 x w2, w1 x v2 - w2 x v1)``; ``ad(x) @ y == bracket(x, y)``;
* ``Ad(g) = [[R, 0], [p^ R, R]]`` moves twists (``hat(Ad(g) xi) = g hat(xi) g^-1``)
  and, in the (f, m) layout, wrenches;
* Klein form ``K(x, y) = w1.v2 + w2.v1`` (a wrench (f, m) does power
  ``K((w, v), (f, m)) = f.v + m.w`` on a twist); Killing form ``-4 w1.w2``.

Every function accepts float64 arrays, object arrays of mpmath numbers
(mp:N) and object arrays of sympy numbers (exact) and runs the same formula.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing.lie._series import factorial_series, half_cot_series, safe, use_series
from mechsing.lie._so3 import (
    _LIE,
    _asarr,
    _mask,
    cross,
    dot,
    exp_so3,
    hat3,
    left_jacobian_so3,
    left_jacobian_so3_inv,
    log_so3_parts,
    so3_coefficients,
)
from mechsing.numeric import backend_of, screw_zero_rtol

#: the only place the twist ordering is written down
ANGULAR = slice(0, 3)
LINEAR = slice(3, 6)


def _block(a: np.ndarray, b: np.ndarray, c: np.ndarray, d: np.ndarray) -> np.ndarray:
    top = np.concatenate([a, b], axis=-1)
    bot = np.concatenate([c, d], axis=-1)
    return np.concatenate([top, bot], axis=-2)


def rotation(g: Any) -> np.ndarray:
    """R of g: (..., 4, 4) -> (..., 3, 3)."""
    return _asarr(g)[..., :3, :3]


def translation(g: Any) -> np.ndarray:
    """p of g: (..., 4, 4) -> (..., 3)."""
    return _asarr(g)[..., :3, 3]


def pose(R: Any, p: Any) -> np.ndarray:
    """The displacement ``x -> R x + p`` as a 4x4 matrix: (..., 3, 3), (..., 3) -> (..., 4, 4)."""
    R = _asarr(R)
    p = _asarr(p)
    fast = _LIE["pose"].pick(R, p)
    if fast is not None:
        return fast(R, p)
    bk = backend_of(R, p)
    shape = np.broadcast_shapes(R.shape[:-2], p.shape[:-1])
    R = np.broadcast_to(R, shape + (3, 3))
    p = np.broadcast_to(p, shape + (3,))
    bottom = np.broadcast_to(np.concatenate([bk.zeros(3), bk.eye(1)[0]]), shape + (4,))
    top = np.concatenate([R, p[..., None]], axis=-1)
    return np.concatenate([top, bottom[..., None, :]], axis=-2)


def identity(precision_or_backend: Any = None) -> np.ndarray:
    """The identity displacement in the given backend (float by default)."""
    bk = precision_or_backend
    if bk is None:
        return np.eye(4)
    bk = getattr(bk, "backend", bk)
    return bk.eye(4)


def hat(xi: Any) -> np.ndarray:
    """4x4 matrix of a twist: (..., 6) -> (..., 4, 4), ``[[omega^, v], [0, 0]]``."""
    xi = _asarr(xi)
    W = hat3(xi[..., ANGULAR])
    v = xi[..., LINEAR]
    top = np.concatenate([W, v[..., None]], axis=-1)
    bottom = np.zeros(xi.shape[:-1] + (1, 4), dtype=xi.dtype) * xi[..., None, :1]
    return np.concatenate([top, bottom], axis=-2)


def vee(X: Any) -> np.ndarray:
    """Twist of a 4x4 element of se(3): (..., 4, 4) -> (..., 6)."""
    X = _asarr(X)
    w = np.stack([X[..., 2, 1], X[..., 0, 2], X[..., 1, 0]], axis=-1)
    return np.concatenate([w, X[..., :3, 3]], axis=-1)


def exp(xi: Any) -> np.ndarray:
    """Exponential se(3) -> D: (..., 6) -> (..., 4, 4).

    ``R = I + A W + B W^2``, ``p = (I + B W + C W^2) v`` with A = sin t/t,
    B = (1 - cos t)/t^2, C = (t - sin t)/t^3, ``t = |omega|`` (series near 0;
    any angle, also beyond pi).  Pure translations give ``p = v`` exactly.
    References: the exponential of D.
    """
    xi = _asarr(xi)
    fast = _LIE["exp"].pick(xi)
    if fast is not None:
        return fast(xi)
    w = xi[..., ANGULAR]
    v = xi[..., LINEAR]
    _t2, A, B, C = so3_coefficients(w)
    W = hat3(w)
    W2 = W @ W
    Wv = cross(w, v)
    WWv = cross(w, Wv)
    bk = backend_of(xi)
    eye = np.broadcast_to(bk.eye(3), w.shape[:-1] + (3, 3))
    R = eye + A[..., None, None] * W + B[..., None, None] * W2
    p = v + B[..., None] * Wv + C[..., None] * WWv
    return pose(R, p)


def log(g: Any) -> np.ndarray:
    """Logarithm D -> se(3): (..., 4, 4) -> (..., 6), rotation angle in [0, pi].

    ``omega`` from the unit quaternion of R (Shepperd; accurate at 0 and pi),
    ``v = V^-1 p`` with ``V^-1 = I - W/2 + c W^2``,
    ``c = (1 - (t/2) cot(t/2))/t^2`` (finite at pi: 1/pi^2).
    At exactly pi the axis sign makes its largest component positive.
    ``exp(log(g)) == g`` always; ``log(exp(xi)) == xi`` for angles below pi.
    References: the logarithm of D.
    """
    g = _asarr(g)
    fast = _LIE["log"].pick(g)
    if fast is not None:
        return fast(g)
    R = rotation(g)
    p = translation(g)
    w, theta, qw, n = log_so3_parts(R)
    bk = backend_of(g)
    t2 = theta * theta
    # c from the half-angle quaternion parts: (t/2) cot(t/2) = (t/2) qw / n
    small = use_series(bk, t2)
    ts = safe(bk, small, theta)
    # an array on the left of each operation (see so3_coefficients), same rounding as
    # (t/2) qw / n
    closed = (1 - np.asarray(qw * (ts / 2)) / safe(bk, small, n)) / (ts * ts)
    c = np.where(small, half_cot_series(bk, t2), closed)
    wp = cross(w, p)
    wwp = cross(w, wp)
    v = p - wp / 2 + c[..., None] * wwp
    return np.concatenate([w, v], axis=-1)


def inverse(g: Any) -> np.ndarray:
    """g^-1 = (R^T, -R^T p): (..., 4, 4) -> (..., 4, 4)."""
    g = _asarr(g)
    fast = _LIE["inverse"].pick(g)
    if fast is not None:
        return fast(g)
    Rt = np.swapaxes(rotation(g), -1, -2)
    return pose(Rt, -(Rt @ translation(g)[..., None])[..., 0])


def compose(g: Any, h: Any) -> np.ndarray:
    """g h (apply h first, then g)."""
    return _asarr(g) @ _asarr(h)


def act_point(g: Any, x: Any) -> np.ndarray:
    """g(x) = R x + p for points x of shape (..., 3)."""
    g = _asarr(g)
    x = _asarr(x)
    return (rotation(g) @ x[..., None])[..., 0] + translation(g)


def Ad(g: Any) -> np.ndarray:  # noqa: N802 - the name of the operator
    """Adjoint matrix of a displacement: (..., 4, 4) -> (..., 6, 6), ``[[R, 0], [p^ R, R]]``."""
    g = _asarr(g)
    R = rotation(g)
    P = hat3(translation(g)) @ R
    Z = R * 0
    return _block(R, Z, P, R)


def act_screw(g: Any, xi: Any) -> np.ndarray:
    """Ad(g) xi: a twist (or (f, m) wrench) moved by g; (..., 4, 4), (..., 6) -> (..., 6)."""
    g = _asarr(g)
    xi = _asarr(xi)
    fast = _LIE["act_screw"].pick(g, xi)
    if fast is not None:
        return fast(g, xi)
    R = rotation(g)
    w = (R @ xi[..., ANGULAR, None])[..., 0]
    Rv = (R @ xi[..., LINEAR, None])[..., 0]
    return np.concatenate([w, cross(translation(g), w) + Rv], axis=-1)


def ad(xi: Any) -> np.ndarray:
    """Adjoint of a twist: (..., 6) -> (..., 6, 6), ``[[w^, 0], [v^, w^]]``."""
    xi = _asarr(xi)
    W = hat3(xi[..., ANGULAR])
    V = hat3(xi[..., LINEAR])
    return _block(W, W * 0, V, W)


def bracket(x: Any, y: Any) -> np.ndarray:
    """Lie bracket [x, y] = (w1 x w2, w1 x v2 - w2 x v1) (commutator of hats)."""
    x = _asarr(x)
    y = _asarr(y)
    w1, v1, w2, v2 = x[..., ANGULAR], x[..., LINEAR], y[..., ANGULAR], y[..., LINEAR]
    return np.concatenate([cross(w1, w2), cross(w1, v2) - cross(w2, v1)], axis=-1)


def klein(x: Any, y: Any) -> np.ndarray:
    """Klein form w1.v2 + w2.v1 (zero iff reciprocal; Ad-invariant)."""
    x = _asarr(x)
    y = _asarr(y)
    return dot(x[..., ANGULAR], y[..., LINEAR]) + dot(y[..., ANGULAR], x[..., LINEAR])


def killing(x: Any, y: Any) -> np.ndarray:
    """Killing form tr(ad_x ad_y) = -4 w1.w2 (Ad-invariant, degenerate on translations)."""
    x = _asarr(x)
    y = _asarr(y)
    return -4 * dot(x[..., ANGULAR], y[..., ANGULAR])


def magnitude(xi: Any) -> np.ndarray:
    """``|omega|`` if omega != 0, else ``|v|`` (the amplitude of the screw)."""
    xi = _asarr(xi)
    bk = backend_of(xi)
    w2 = dot(xi[..., ANGULAR], xi[..., ANGULAR])
    v2 = dot(xi[..., LINEAR], xi[..., LINEAR])
    rot = _mask(w2 > 0)
    return bk.sqrt(np.where(rot, w2, v2))


def pitch(xi: Any) -> np.ndarray:
    """Pitch ``omega.v / |omega|^2`` in length per radian; ``inf`` (float) where omega = 0."""
    xi = _asarr(xi)
    bk = backend_of(xi)
    w2 = dot(xi[..., ANGULAR], xi[..., ANGULAR])
    zero = _mask(w2 <= 0)
    h = dot(xi[..., ANGULAR], xi[..., LINEAR]) / safe(bk, zero, w2)
    if np.any(zero):
        h = np.where(zero, bk.inf, h)
    return h


def axis(xi: Any) -> tuple[np.ndarray, np.ndarray]:
    """Axis of a screw: unit direction and the axis point nearest the origin.

    For omega != 0: ``u = omega/|omega|``, ``r0 = omega x v / |omega|^2``.
    For a translation (omega = 0): ``u = v/|v|`` and the point is the origin
    (a translation has a direction, not a line).  Zero screws give zeros.
    """
    xi = _asarr(xi)
    bk = backend_of(xi)
    w = xi[..., ANGULAR]
    v = xi[..., LINEAR]
    w2 = dot(w, w)
    rot = _mask(w2 > 0)
    v2 = dot(v, v)
    tr = _mask(v2 > 0)
    nw = bk.sqrt(safe(bk, ~rot, w2))
    nv = bk.sqrt(safe(bk, ~tr, v2))
    u = np.where(
        rot[..., None], w / nw[..., None], np.where(tr[..., None], v / nv[..., None], w * 0)
    )
    r0 = np.where(rot[..., None], cross(w, v) / safe(bk, ~rot, w2)[..., None], w * 0)
    return u, r0


def classify_screw(xi: Any, length_scale: float = 1.0) -> np.ndarray | str:
    """``"zero"``, ``"translation"``, ``"rotation"`` or ``"helical"`` for each screw.

    ``omega`` counts as zero when ``|omega| L <= rtol |v|``; the pitch as zero
    when ``|h| <= rtol L`` (rtol from :func:`mechsing.numeric.screw_zero_rtol`:
    1e-9 in float, 10^(-N/2) at mp:N, exactly 0 in exact mode).
    """
    xi = _asarr(xi)
    bk = backend_of(xi)
    rtol = screw_zero_rtol(bk)
    w = xi[..., ANGULAR]
    v = xi[..., LINEAR]
    nw = bk.sqrt(dot(w, w))
    nv = bk.sqrt(dot(v, v))
    out = np.empty(xi.shape[:-1], dtype=object)
    for idx in np.ndindex(out.shape):
        a, b = nw[idx] * length_scale, nv[idx]
        if a <= rtol * b or a == 0:
            out[idx] = "zero" if b == 0 else "translation"  # b is a norm: never below 0
            continue
        h = dot(w[idx], v[idx]) / (nw[idx] * nw[idx])
        out[idx] = "rotation" if abs(h) <= rtol * length_scale else "helical"
    return out[()] if out.shape == () else out


# ---------------------------------------------------------------------------
# Chasles: classification of a displacement
# ---------------------------------------------------------------------------


@dataclass(frozen=True)
class ChaslesScrew:
    """Chasles decomposition of a displacement.

    ``kind``: ``"identity"``, ``"translation"``, ``"rotation"`` or ``"screw"``.
    ``angle`` in [0, pi]; ``axis`` unit direction (the translation direction
    for a translation); ``point`` the axis point nearest the origin; ``slide``
    the translation along the axis (the length of a translation).
    """

    kind: str
    angle: Any
    axis: Any
    point: Any
    slide: Any


def classify_displacement(g: Any, length_scale: float = 1.0) -> ChaslesScrew:
    """Chasles/Mozzi decomposition of one displacement (Chasles-Mozzi).

    A rotation angle counts as zero when ``|angle| <= rtol`` and a length
    when ``<= rtol L`` (rtol from :func:`mechsing.numeric.screw_zero_rtol`).
    The axis point nearest the origin is ``(p_perp + cot(t/2) u x p_perp)/2``.
    """
    g = _asarr(g)
    if g.shape != (4, 4):
        raise ValueError(f"classify_displacement takes one 4x4 displacement, got shape {g.shape}")
    bk = backend_of(g)
    rtol = screw_zero_rtol(bk)
    R = rotation(g)
    p = translation(g)
    w, theta, qw, n = log_so3_parts(R)
    plen = bk.sqrt(dot(p, p)[None])[0]
    if theta <= rtol or n == 0:
        if plen <= rtol * length_scale:
            return ChaslesScrew("identity", theta, w * 0, p * 0, plen * 0)
        return ChaslesScrew("translation", theta * 0, p / plen, p * 0, plen)
    u = w / theta
    d = dot(u, p)
    pperp = p - d * u
    cot_half = qw / n
    point = (pperp + cot_half * cross(u, pperp)) / 2
    kind = "rotation" if abs(d) <= rtol * length_scale else "screw"
    return ChaslesScrew(kind, theta, u, point, d)


# ---------------------------------------------------------------------------
# Jacobians of exp (dexp) and their inverses
# ---------------------------------------------------------------------------


def _q_block(xi: np.ndarray) -> np.ndarray:
    """Lower-left block Q of the left Jacobian of SE(3) (the Jacobians of exp, block form)."""
    bk = backend_of(xi)
    w = xi[..., ANGULAR]
    v = xi[..., LINEAR]
    t2 = dot(w, w)
    small = use_series(bk, t2)
    t = bk.sqrt(safe(bk, small, t2))
    s = bk.sin(t)
    co = bk.cos(t)
    # b = (t - sin t)/t^3; c = (1 - t^2/2 - cos t)/t^4; d = c - 3 (t - sin t - t^3/6)/t^5
    b = np.where(small, factorial_series(bk, t2, 3), (t - s) / t**3)
    c = np.where(small, -factorial_series(bk, t2, 4), (1 - t2 / 2 - co) / t**4)
    e5 = np.where(small, -factorial_series(bk, t2, 5), (t - s - t**3 / 6) / t**5)
    d = np.asarray(c - 3 * e5)
    W = hat3(w)
    V = hat3(v)
    WV = W @ V
    VW = V @ W
    WVW = WV @ W
    VWW = VW @ W
    WWV = W @ WV
    WVWW = WVW @ W
    B = b[..., None, None]
    C = c[..., None, None]
    Dd = d[..., None, None]
    return V / 2 + B * (WV + VW + WVW) - C * (VWW + WWV - 3 * WVW) - Dd * WVWW


def left_jacobian(xi: Any) -> np.ndarray:
    """Left Jacobian of exp on D: (..., 6) -> (..., 6, 6), ``[[J, 0], [Q, J]]``.

    ``exp(xi + d) ~ exp(J_l(xi) d) exp(xi)``; ``d/dt exp(xi(t)) = hat(J_l xi') exp(xi)``.
    Equals ``sum_k ad(xi)^k / (k+1)!``.  References: the Jacobians of exp.
    """
    xi = _asarr(xi)
    J = left_jacobian_so3(xi[..., ANGULAR])
    return _block(J, J * 0, _q_block(xi), J)


def right_jacobian(xi: Any) -> np.ndarray:
    """Right Jacobian: ``exp(xi + d) ~ exp(xi) exp(J_r(xi) d)``; ``J_r(xi) = J_l(-xi)``."""
    return left_jacobian(-_asarr(xi))


def left_jacobian_inv(xi: Any) -> np.ndarray:
    """Inverse of :func:`left_jacobian`: ``[[J^-1, 0], [-J^-1 Q J^-1, J^-1]]``."""
    xi = _asarr(xi)
    Ji = left_jacobian_so3_inv(xi[..., ANGULAR])
    Q = _q_block(xi)
    return _block(Ji, Ji * 0, -(Ji @ Q @ Ji), Ji)


def right_jacobian_inv(xi: Any) -> np.ndarray:
    """Inverse of :func:`right_jacobian` (= ``left_jacobian_inv(-xi)``)."""
    return left_jacobian_inv(-_asarr(xi))


__all__ = [
    "ANGULAR",
    "LINEAR",
    "Ad",
    "ChaslesScrew",
    "act_point",
    "act_screw",
    "ad",
    "axis",
    "bracket",
    "classify_displacement",
    "classify_screw",
    "compose",
    "cross",
    "dot",
    "exp",
    "exp_so3",
    "hat",
    "hat3",
    "identity",
    "inverse",
    "killing",
    "klein",
    "left_jacobian",
    "left_jacobian_inv",
    "left_jacobian_so3",
    "left_jacobian_so3_inv",
    "log",
    "magnitude",
    "pitch",
    "pose",
    "right_jacobian",
    "right_jacobian_inv",
    "rotation",
    "translation",
    "vee",
]
