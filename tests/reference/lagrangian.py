"""Planar serial arms' dynamics from their Lagrangian, at mpmath's working precision.

The arm turns in the plane z = 0 about parallel z axes: joint 1 at the origin, joint i+1 at
distance ``lengths[i]`` along link i; link i has mass ``m_i``, its centre of mass on the
link at ``r_i`` from its joint, and ``I_i`` its moment of inertia about the z axis through
the centre of mass.  With ``theta_k = q_1 + ... + q_k`` the centre of link k is

    p_k = sum_{j<k} l_j (cos theta_j, sin theta_j) + r_k (cos theta_k, sin theta_k),

the Lagrangian ``L = T - V``, ``T = 1/2 qd^T M(q) qd``,
``M_ij = sum_k m_k dp_k/dq_i . dp_k/dq_j + I_k [i <= k][j <= k]``, ``V = -sum_k m_k g . p_k``,
and Lagrange's equations give the efforts

    tau = M qdd + (dM/dt) qd - 1/2 d(qd^T M qd)/dq + dV/dq,

every derivative written out here in closed form (no differentiation by mechsing nor by
finite differences).  Imports nothing from mechsing.
"""

from __future__ import annotations

from collections.abc import Sequence

import mpmath

__all__ = ["PlanarArm"]


class PlanarArm:
    """A planar serial arm of revolute joints (every number an mpmath number or convertible)."""

    def __init__(
        self,
        lengths: Sequence[object],
        masses: Sequence[object],
        centres: Sequence[object],
        inertias: Sequence[object],
        gravity: tuple[object, object] = (0, 0),
    ) -> None:
        f = mpmath.mpf
        self.l = [f(x) for x in lengths]
        self.m = [f(x) for x in masses]
        self.r = [f(x) for x in centres]
        self.I = [f(x) for x in inertias]
        self.g = (f(gravity[0]), f(gravity[1]))
        self.n = len(self.m)

    def _angles(self, q: Sequence[object]) -> list[object]:
        out, t = [], mpmath.mpf(0)
        for x in q:
            t += x
            out.append(t)
        return out

    def _arm(self, k: int, j: int) -> object:
        """The length from joint j's axis's contribution to link k's centre: l_j (j < k) or r_k."""
        return self.l[j] if j < k else self.r[k]

    def jacobian(self, q: Sequence[object], k: int) -> list[tuple[object, object]]:
        """dp_k/dq_i for each i."""
        th = self._angles(q)
        out = []
        for i in range(self.n):
            dx = dy = mpmath.mpf(0)
            for j in range(i, k + 1):
                a = self._arm(k, j)
                dx -= a * mpmath.sin(th[j])
                dy += a * mpmath.cos(th[j])
            out.append((dx, dy) if i <= k else (mpmath.mpf(0), mpmath.mpf(0)))
        return out

    def hessian(self, q: Sequence[object], k: int, i: int, l: int) -> tuple[object, object]:
        """d^2 p_k / dq_i dq_l."""
        th = self._angles(q)
        dx = dy = mpmath.mpf(0)
        for j in range(max(i, l), k + 1):
            a = self._arm(k, j)
            dx -= a * mpmath.cos(th[j])
            dy -= a * mpmath.sin(th[j])
        return dx, dy

    def mass_matrix(self, q: Sequence[object]) -> mpmath.matrix:
        M = mpmath.matrix(self.n, self.n)
        for k in range(self.n):
            J = self.jacobian(q, k)
            for i in range(self.n):
                for j in range(self.n):
                    M[i, j] += self.m[k] * (J[i][0] * J[j][0] + J[i][1] * J[j][1])
                    if i <= k and j <= k:
                        M[i, j] += self.I[k]
        return M

    def dmass(self, q: Sequence[object], l: int) -> mpmath.matrix:
        """dM/dq_l."""
        D = mpmath.matrix(self.n, self.n)
        for k in range(self.n):
            J = self.jacobian(q, k)
            for i in range(self.n):
                for j in range(self.n):
                    if i > k or j > k or l > k:
                        continue
                    Hi = self.hessian(q, k, i, l)
                    Hj = self.hessian(q, k, j, l)
                    D[i, j] += self.m[k] * (
                        Hi[0] * J[j][0] + Hi[1] * J[j][1] + J[i][0] * Hj[0] + J[i][1] * Hj[1]
                    )
        return D

    def efforts(self, q: Sequence[object], qd: Sequence[object], qdd: Sequence[object]) -> list:
        q = [mpmath.mpf(x) for x in q]
        v = mpmath.matrix([mpmath.mpf(x) for x in qd])
        a = mpmath.matrix([mpmath.mpf(x) for x in qdd])
        M = self.mass_matrix(q)
        dM = [self.dmass(q, l) for l in range(self.n)]
        Mdot = sum((dM[l] * v[l] for l in range(self.n)), mpmath.matrix(self.n, self.n))
        tau = M * a + Mdot * v
        for i in range(self.n):
            tau[i] -= (v.T * dM[i] * v)[0] / 2
            for k in range(self.n):  # dV/dq_i, V = -sum m_k g.p_k
                J = self.jacobian(q, k)
                tau[i] -= self.m[k] * (self.g[0] * J[i][0] + self.g[1] * J[i][1])
        return [tau[i] for i in range(self.n)]

    def kinetic_energy(self, q: Sequence[object], qd: Sequence[object]) -> object:
        v = mpmath.matrix([mpmath.mpf(x) for x in qd])
        return (v.T * self.mass_matrix([mpmath.mpf(x) for x in q]) * v)[0] / 2
