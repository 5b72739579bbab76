"""The inverse dynamics of a tree compiled with numba (optional: the ``fast`` extra).

Owns :func:`inverse_compiled`, the form ``"compiled tree"`` of the dispatch table
``"inverse dynamics"`` (:mod:`mechsing.numeric.dispatch`), whose generic definition is
:meth:`mechsing.kinetics.tree.TreeDynamics.inverse`.  One pass per sample does what the
generic code does on whole arrays, with the same formulas: each joint's element by the
closed form of the exponential of a one-dof screw (Rodrigues, ``|omega| = 1`` or a
translation), the poses composed from the ground, the twists and accelerations forward
(``a_b = a_p + s qdd + [xi_b, s qd]``), each body's wrench ``I(a) + [xi, I(xi)]`` with
its inertia carried to its pose, the wrenches backward and ``tau = <F, s>``.  Equal to
the generic code to rounding (tests/test_dispatch.py); registered only when numba is
installed, compiled on first use (without numba it answers None: the generic code runs).
"""

from __future__ import annotations

import importlib.util
from typing import Any

import numpy as np

from mechsing.numeric import dispatch

__all__ = ["inverse_compiled"]

_KERNEL: list[Any] = []


def _build() -> Any:
    import numba

    momentum = numba.njit(cache=False, nogil=True)(_momentum)

    @numba.njit(cache=False, nogil=True, error_model="numpy")
    def kernel(Q, V, A, prev, col, sign, E, mass, C0, I0, a0, out):  # pragma: no cover
        N = Q.shape[0]
        nb = prev.shape[0]
        G = np.zeros((nb + 1, 3, 4))  # poses; index nb: the ground
        X = np.zeros((nb + 1, 6))  # twists
        Acc = np.zeros((nb + 1, 6))  # accelerations
        S = np.zeros((nb, 6))  # signed current screws
        F = np.zeros((nb + 1, 6))  # wrenches carried
        M = np.zeros((3, 4))
        K = np.zeros((3, 3))
        Ic = np.zeros((3, 3))
        T = np.zeros((3, 3))
        c = np.zeros(3)
        hx = np.zeros(6)
        ha = np.zeros(6)
        for n in range(N):
            for i in range(3):
                for j in range(4):
                    G[nb, i, j] = 1.0 if i == j else 0.0
            for i in range(6):
                X[nb, i] = 0.0
                Acc[nb, i] = a0[i]
            for b in range(nb):
                p = prev[b]
                k = col[b]
                th = Q[n, k] * sign[b]
                w0, w1, w2 = E[b, 0], E[b, 1], E[b, 2]
                v0, v1, v2 = E[b, 3], E[b, 4], E[b, 5]
                # the element exp(th e) (|w| = 1, or w = 0: a translation)
                if w0 == 0.0 and w1 == 0.0 and w2 == 0.0:
                    for i in range(3):
                        for j in range(3):
                            M[i, j] = 1.0 if i == j else 0.0
                    M[0, 3] = v0 * th
                    M[1, 3] = v1 * th
                    M[2, 3] = v2 * th
                else:
                    sn, cs = np.sin(th), np.cos(th)
                    K[0, 0], K[0, 1], K[0, 2] = 0.0, -w2, w1
                    K[1, 0], K[1, 1], K[1, 2] = w2, 0.0, -w0
                    K[2, 0], K[2, 1], K[2, 2] = -w1, w0, 0.0
                    for i in range(3):
                        for j in range(3):
                            kk = K[i, 0] * K[0, j] + K[i, 1] * K[1, j] + K[i, 2] * K[2, j]
                            M[i, j] = (1.0 if i == j else 0.0) + sn * K[i, j] + (1.0 - cs) * kk
                    x0 = w1 * v2 - w2 * v1
                    x1 = w2 * v0 - w0 * v2
                    x2 = w0 * v1 - w1 * v0
                    wv = (w0 * v0 + w1 * v1 + w2 * v2) * th
                    # t = (1 - R)(w x v) + w (w . v) th
                    M[0, 3] = x0 - (M[0, 0] * x0 + M[0, 1] * x1 + M[0, 2] * x2) + w0 * wv
                    M[1, 3] = x1 - (M[1, 0] * x0 + M[1, 1] * x1 + M[1, 2] * x2) + w1 * wv
                    M[2, 3] = x2 - (M[2, 0] * x0 + M[2, 1] * x1 + M[2, 2] * x2) + w2 * wv
                # g_b = g_p M
                for i in range(3):
                    for j in range(4):
                        acc = G[p, i, 0] * M[0, j] + G[p, i, 1] * M[1, j] + G[p, i, 2] * M[2, j]
                        if j == 3:
                            acc += G[p, i, 3]
                        G[b, i, j] = acc
                # the current screw Ad(g_p) e (= Ad(g_b) e), times the crossing's sign
                r0 = G[p, 0, 0] * w0 + G[p, 0, 1] * w1 + G[p, 0, 2] * w2
                r1 = G[p, 1, 0] * w0 + G[p, 1, 1] * w1 + G[p, 1, 2] * w2
                r2 = G[p, 2, 0] * w0 + G[p, 2, 1] * w1 + G[p, 2, 2] * w2
                u0 = G[p, 0, 0] * v0 + G[p, 0, 1] * v1 + G[p, 0, 2] * v2
                u1 = G[p, 1, 0] * v0 + G[p, 1, 1] * v1 + G[p, 1, 2] * v2
                u2 = G[p, 2, 0] * v0 + G[p, 2, 1] * v1 + G[p, 2, 2] * v2
                p0, p1, p2 = G[p, 0, 3], G[p, 1, 3], G[p, 2, 3]
                sg = sign[b]
                S[b, 0], S[b, 1], S[b, 2] = sg * r0, sg * r1, sg * r2
                S[b, 3] = sg * (u0 + p1 * r2 - p2 * r1)
                S[b, 4] = sg * (u1 + p2 * r0 - p0 * r2)
                S[b, 5] = sg * (u2 + p0 * r1 - p1 * r0)
                qd = V[n, k]
                qdd = A[n, k]
                for i in range(6):
                    X[b, i] = X[p, i] + S[b, i] * qd
                # a_b = a_p + s qdd + [xi_b, s qd]
                x = X[b]
                s0, s1, s2 = S[b, 0] * qd, S[b, 1] * qd, S[b, 2] * qd
                s3, s4, s5 = S[b, 3] * qd, S[b, 4] * qd, S[b, 5] * qd
                Acc[b, 0] = Acc[p, 0] + S[b, 0] * qdd + x[1] * s2 - x[2] * s1
                Acc[b, 1] = Acc[p, 1] + S[b, 1] * qdd + x[2] * s0 - x[0] * s2
                Acc[b, 2] = Acc[p, 2] + S[b, 2] * qdd + x[0] * s1 - x[1] * s0
                Acc[b, 3] = (
                    Acc[p, 3] + S[b, 3] * qdd + x[1] * s5 - x[2] * s4 - (s1 * x[5] - s2 * x[4])
                )
                Acc[b, 4] = (
                    Acc[p, 4] + S[b, 4] * qdd + x[2] * s3 - x[0] * s5 - (s2 * x[3] - s0 * x[5])
                )
                Acc[b, 5] = (
                    Acc[p, 5] + S[b, 5] * qdd + x[0] * s4 - x[1] * s3 - (s0 * x[4] - s1 * x[3])
                )
            # each body's wrench I(a) + [xi, I(xi)], its inertia carried to its pose
            for b in range(nb):
                for i in range(6):
                    F[b, i] = 0.0
                m = mass[b]
                if m == 0.0 and I0[b, 0, 0] == 0.0 and I0[b, 1, 1] == 0.0 and I0[b, 2, 2] == 0.0:
                    continue
                for i in range(3):
                    c[i] = (
                        G[b, i, 0] * C0[b, 0]
                        + G[b, i, 1] * C0[b, 1]
                        + G[b, i, 2] * C0[b, 2]
                        + G[b, i, 3]
                    )
                    for j in range(3):
                        T[i, j] = (
                            G[b, i, 0] * I0[b, 0, j]
                            + G[b, i, 1] * I0[b, 1, j]
                            + G[b, i, 2] * I0[b, 2, j]
                        )
                for i in range(3):
                    for j in range(3):
                        Ic[i, j] = (
                            T[i, 0] * G[b, j, 0] + T[i, 1] * G[b, j, 1] + T[i, 2] * G[b, j, 2]
                        )
                momentum(m, c, Ic, X[b], hx)
                momentum(m, c, Ic, Acc[b], ha)
                x = X[b]
                # [xi, h] with h = (f, m) read as a screw
                F[b, 0] = ha[0] + x[1] * hx[2] - x[2] * hx[1]
                F[b, 1] = ha[1] + x[2] * hx[0] - x[0] * hx[2]
                F[b, 2] = ha[2] + x[0] * hx[1] - x[1] * hx[0]
                F[b, 3] = ha[3] + x[1] * hx[5] - x[2] * hx[4] - (hx[1] * x[5] - hx[2] * x[4])
                F[b, 4] = ha[4] + x[2] * hx[3] - x[0] * hx[5] - (hx[2] * x[3] - hx[0] * x[5])
                F[b, 5] = ha[5] + x[0] * hx[4] - x[1] * hx[3] - (hx[0] * x[4] - hx[1] * x[3])
            # backward: the joints' efforts
            for b in range(nb - 1, -1, -1):
                f = F[b]
                s = S[b]
                out[n, col[b]] = (
                    f[0] * s[3]
                    + f[1] * s[4]
                    + f[2] * s[5]
                    + f[3] * s[0]
                    + f[4] * s[1]
                    + f[5] * s[2]
                )
                p = prev[b]
                if p != nb:
                    for i in range(6):
                        F[p, i] += f[i]

    return kernel


def _momentum(m, c, Ic, xi, out):  # type: ignore[no-untyped-def]  # pragma: no cover
    """I(xi) = (m (v + w x c), Ic w + c x p) into ``out``."""
    w0, w1, w2, v0, v1, v2 = xi[0], xi[1], xi[2], xi[3], xi[4], xi[5]
    f0 = m * (v0 + w1 * c[2] - w2 * c[1])
    f1 = m * (v1 + w2 * c[0] - w0 * c[2])
    f2 = m * (v2 + w0 * c[1] - w1 * c[0])
    out[0], out[1], out[2] = f0, f1, f2
    out[3] = Ic[0, 0] * w0 + Ic[0, 1] * w1 + Ic[0, 2] * w2 + c[1] * f2 - c[2] * f1
    out[4] = Ic[1, 0] * w0 + Ic[1, 1] * w1 + Ic[1, 2] * w2 + c[2] * f0 - c[0] * f2
    out[5] = Ic[2, 0] * w0 + Ic[2, 1] * w1 + Ic[2, 2] * w2 + c[0] * f1 - c[1] * f0


def _tables(td: Any) -> tuple[np.ndarray, ...]:
    """The tree's plan as arrays (built once per TreeDynamics): each body's previous body
    (the ground: the number of bodies), coordinate, sign, reference screw, and inertia at
    the drawn pose (zero for a body without mass)."""
    got = td.compiled_tables
    if got is not None:
        return got
    index = {body: i for i, (body, _, _, _) in enumerate(td.plan)}
    nb = len(td.plan)
    prev = np.array([index.get(p, nb) for _, _, p, _ in td.plan], dtype=np.int64)
    col = np.array([jk.columns.start for _, jk, _, _ in td.plan], dtype=np.int64)
    sign = np.array([float(s) for _, _, _, s in td.plan])
    E = np.array([np.asarray(jk.basis[0], dtype=float) for _, jk, _, _ in td.plan]).reshape(nb, 6)
    mass = np.zeros(nb)
    C0 = np.zeros((nb, 3))
    I0 = np.zeros((nb, 3, 3))
    for body, inertia in td.inertia.items():
        i = index[body]
        mass[i] = float(inertia.mass)
        C0[i] = np.asarray(inertia.centre, dtype=float)
        I0[i] = np.asarray(inertia.about_centre, dtype=float)
    got = (prev, col, sign, E, mass, C0, I0)
    td.compiled_tables = got
    return got


def _applies(td: Any) -> bool:
    """Joints with a unit rotation or none (R, H, P: the closed form above)."""
    for _, jk, _, _ in td.plan:
        w = np.asarray(jk.basis[0, :3], dtype=float)
        n = float(w @ w)
        if n != 0.0 and abs(n - 1.0) > 1e-15:
            return False
    return True


def inverse_compiled(
    td: Any, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray, gravity: bool
) -> np.ndarray | None:
    """The efforts of :meth:`TreeDynamics.inverse` for a float batch (N, n); None when the
    tree's joints are not all of the closed form's kind."""
    if q.ndim != 2 or not _applies(td) or not _NUMBA:
        return None
    if not _KERNEL:
        _KERNEL.append(_build())
    prev, col, sign, E, mass, C0, I0 = _tables(td)
    a0 = np.asarray(td.ground_acceleration, dtype=float) if gravity else np.zeros(6)
    N = q.shape[0]
    qd = np.broadcast_to(qd, q.shape)
    qdd = np.broadcast_to(qdd, q.shape)
    out = np.zeros((N, td.n))
    _KERNEL[0](
        np.ascontiguousarray(q),
        np.ascontiguousarray(qd),
        np.ascontiguousarray(qdd),
        prev,
        col,
        sign,
        E,
        mass,
        C0,
        I0,
        a0,
        out,
    )
    return out


#: numba is installed (the ``fast`` extra): without it the form answers None
_NUMBA = importlib.util.find_spec("numba") is not None

dispatch.table("inverse dynamics", "mechsing.kinetics.tree.TreeDynamics.inverse").register(
    "compiled tree",
    "a float batch of a tree of R, P, H joints: the recursive Newton-Euler compiled with "
    "numba, one pass per sample (equal to the generic code to rounding; None without numba)",
    accepts=lambda _tree, q, qd, qdd, _gravity: dispatch.float64_arrays(q, qd, qdd),
)(inverse_compiled)
