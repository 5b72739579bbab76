"""Whether six distance legs, all long against the base and the platform, can hold the
platform at a real pose: a necessary condition, written here with numpy only (nothing from
mechsing), solved by the quadratics' roots (mechsing bisects).

With the pose ``x -> R x + p``, ``D = |p|``, ``u = p / D``, ``v = R^T u`` and
``r_i = |a_i| + |b_i|``: ``|D - L_i| <= r_i``, and for i = 2..6

    v.(b_i - b_1) - u.(a_i - a_1) = (L_i^2 - L_1^2) / (2 D) + eta_i,
    |eta_i| <= max(r_i, r_1)^2 / (2 D).

``x = (u, v)`` then lies within ``omega`` of the line ``x_c + t n`` (least-norm solution
at the intervals' centres plus the null vector of the 5 x 6 matrix), ``|t| <= sqrt(2)``;
a real pose needs both ``| |x_c,u + t n_u| - 1 |`` and ``| |x_c,v + t n_v| - 1 |`` at most
``omega``.
"""

from __future__ import annotations

import numpy as np


def _where_between(A: float, B: float, C: float, lo: float, hi: float) -> list[tuple[float, float]]:
    """The t with lo <= A t^2 + 2 B t + C <= hi (A >= 0), as closed intervals."""
    if A <= 0:  # constant
        return [(-np.inf, np.inf)] if lo <= C <= hi else []

    def roots(level: float) -> tuple[float, float] | None:
        disc = B * B - A * (C - level)
        if disc < 0:
            return None
        s = np.sqrt(disc)
        return (-B - s) / A, (-B + s) / A

    below_hi = roots(hi)
    if below_hi is None:
        return []
    below_lo = roots(lo) if lo > 0 else None
    if below_lo is None:
        return [below_hi]
    return [(below_hi[0], below_lo[0]), (below_lo[1], below_hi[1])]


def far_pose_possible(base: list, plat: list, lengths: list) -> tuple[bool, float]:
    """(whether the necessary condition allows a real pose, omega)."""
    a = [np.asarray(x, float) for x in base]
    b = [np.asarray(x, float) for x in plat]
    L = np.asarray(lengths, float)
    r = np.array([np.linalg.norm(a[i]) + np.linalg.norm(b[i]) for i in range(6)])
    d_lo, d_hi = float(np.max(L - r)), float(np.min(L + r))
    assert d_lo > 0 and d_hi >= d_lo
    M = np.array([np.r_[-(a[i] - a[0]), b[i] - b[0]] for i in range(1, 6)])
    g = np.array([[(L[i] ** 2 - L[0] ** 2) / (2 * d) for d in (d_lo, d_hi)] for i in range(1, 6)])
    eta = np.array([max(r[i], r[0]) ** 2 / (2 * d_lo) for i in range(1, 6)])
    lo, hi = g.min(axis=1) - eta, g.max(axis=1) + eta
    _, s, vt = np.linalg.svd(M)
    n = vt[-1]
    x_c = np.linalg.lstsq(M, (lo + hi) / 2, rcond=None)[0]
    omega = float(np.linalg.norm((hi - lo) / 2) / s[-1]) * (1 + 1e-6) + 1e-9
    sets = []
    for k in (0, 1):
        c, m = x_c[3 * k : 3 * k + 3], n[3 * k : 3 * k + 3]
        sets.append(_where_between(m @ m, c @ m, c @ c, max(0.0, 1 - omega) ** 2, (1 + omega) ** 2))
    top = np.sqrt(2)
    for p0, p1 in sets[0]:
        for q0, q1 in sets[1]:
            if max(p0, q0, -top) <= min(p1, q1, top):
                return True, omega
    return False, omega
