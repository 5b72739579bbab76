"""The singular curves and cusps of a family of univariate polynomials in two parameters.

A mechanism whose direct (or inverse) kinematics reduces to one polynomial ``P(t; a, b)``
-- its real roots in ``t`` the assembly modes (postures) at the inputs ``(a, b)`` of a
section of the input space -- is singular where two roots meet, ``P = P_t = 0`` (the
discriminant's curves, the singular curves of the section), and has a **cusp** where
three meet, ``P = P_t = P_tt = 0`` (Innocenti & Parenti-Castelli, ASME J. Mech. Des.
1998; Zein, Wenger & Chablat, Mech. Mach. Theory 43, 2008).  The triple-root system is
square in ``(t, a, b)``: each cusp is refined at 50 digits and certified by the Krawczyk
test (:func:`~mechsing.assembly.certify.krawczyk`: one true triple root in the box).

How they are found: the number of real roots on a grid of the section (the modes'
regions); on every grid edge whose ends differ, the crossing bisected on that count and
then placed by Newton on ``P = P_t = 0`` along the edge (to 1e-12 relative); from every
pair of neighbouring located singular points on which d2P/dt2 has opposite signs,
Newton on the triple-root system, the points it converges to in the section kept once.  The count of cusps is therefore what the grid sees: a cusp whose
curves cross no grid edge is missed (a finer grid, ``points``, finds it).

Owns :class:`Family`, :class:`Section` and :func:`section`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import mpmath
import numpy as np
import numpy.polynomial.polynomial as P3
import sympy

from mechsing.assembly.certify import krawczyk, newton
from mechsing.numeric import CUSP_DISTINCT_RTOL, CUSP_REAL_RTOL, MODE_CERTIFY_RADIUS

__all__ = ["Family", "Section", "section"]

#: grid points along each side of the section (the modes' count is taken at each)
GRID_POINTS = 81
#: bisection steps of a crossing along a grid edge before Newton places it
EDGE_BISECTIONS = 30
#: Newton steps (double precision) on the double-root and the triple-root systems
NEWTON_STEPS = 40
#: Newton steps on the triple-root system from a singular point (a seed near a cusp
#: converges in a few; the others are given up)
TRIPLE_STEPS = 40
#: digits a cusp is refined and certified at
CUSP_DIGITS = 50


@dataclass(frozen=True)
class Family:
    """``P(t; a, b)``: a polynomial (sympy, with exact coefficients, algebraic or
    rational) and its monomials for fast evaluation."""

    poly: sympy.Poly  # in (t, a, b)
    t: sympy.Symbol
    a: sympy.Symbol
    b: sympy.Symbol
    monos: np.ndarray = field(repr=False)  # (n, 3) exponents of t, a, b
    coeffs: np.ndarray = field(repr=False)  # (n,) floats
    cache: dict = field(default_factory=dict, repr=False, compare=False)

    @classmethod
    def of(cls, expr: sympy.Expr, t: sympy.Symbol, a: sympy.Symbol, b: sympy.Symbol) -> Family:
        poly = sympy.Poly(sympy.expand(expr), t, a, b)
        monos = np.array(poly.monoms(), dtype=int).reshape(-1, 3)
        coeffs = np.array([float(sympy.N(c, 30)) for c in poly.coeffs()])
        scale = float(np.max(np.abs(coeffs))) if len(coeffs) else 1.0
        return cls(poly, t, a, b, monos, coeffs / scale)

    @property
    def degree(self) -> int:
        return int(self.monos[:, 0].max())

    def derivative(self, p: int, q: int, r: int, t: Any, a: Any, b: Any) -> Any:
        """d^(p+q+r) P / dt^p da^q db^r at (t, a, b) (floats or arrays)."""
        return P3.polyval3d(t, a, b, self._array(p, q, r))

    def _array(self, p: int, q: int, r: int) -> np.ndarray:
        """The coefficient array (t, a, b axes) of a derivative, built once."""
        cache = self.cache
        if (p, q, r) not in cache:
            i, j, k = self.monos.max(axis=0)
            C = np.zeros((i + 1, j + 1, k + 1))
            C[self.monos[:, 0], self.monos[:, 1], self.monos[:, 2]] = self.coeffs
            for axis, n in enumerate((p, q, r)):
                if n:
                    C = P3.polyder(C, n, axis=axis)
            cache[(p, q, r)] = C
        return cache[(p, q, r)]

    def in_t(self, a: float, b: float) -> np.ndarray:
        """The coefficients in t at (a, b), highest power first."""
        out = np.zeros(self.degree + 1)
        vals = self.coeffs * a ** self.monos[:, 1] * b ** self.monos[:, 2]
        np.add.at(out, self.degree - self.monos[:, 0], vals)
        return out

    def real_roots(self, a: float, b: float) -> np.ndarray:
        """The real roots in t at (a, b), sorted."""
        c = np.trim_zeros(self.in_t(a, b), "f")
        if len(c) <= 1:
            return np.zeros(0)
        z = np.roots(c)
        real = np.abs(z.imag) <= CUSP_REAL_RTOL * np.maximum(1.0, np.abs(z))
        return np.sort(z.real[real])

    def count(self, a: float, b: float) -> int:
        """The number of distinct real roots (roots closer than CUSP_DISTINCT_RTOL kept once)."""
        r = self.real_roots(a, b)
        if len(r) == 0:
            return 0
        gaps = np.diff(r) > CUSP_DISTINCT_RTOL * np.maximum(1.0, np.abs(r[1:]))
        return int(1 + np.sum(gaps))


@dataclass(frozen=True)
class SingularPoint:
    """A located point of a singular curve: the inputs (a, b), the double root t and
    the sign of P_tt there (which side of the fold)."""

    a: float
    b: float
    t: float
    placed: bool  # Newton closed (else the bisection's point, to 1e-9 of the edge)


@dataclass(frozen=True)
class TripleRoot:
    """A cusp: the inputs (a, b) and the triple root t (mpmath, 50 digits), whether the
    Krawczyk test proved one true triple root within ``radius``, the number of real roots
    there (distinct) and on the grid on either side."""

    a: Any
    b: Any
    t: Any
    certified: bool
    radius: float
    real_roots: int


@dataclass(frozen=True)
class Section:
    """What :func:`section` found: the grid and its counts of real roots, the located
    singular points, the cusps, and how many Newton runs were started."""

    a_values: np.ndarray
    b_values: np.ndarray
    counts: np.ndarray  # (len(a), len(b))
    points: list[SingularPoint]
    cusps: list[TripleRoot]
    seeds: int  # Newton runs on the triple-root system


def section(
    family: Family, a_range: tuple[float, float], b_range: tuple[float, float],
    points: int = GRID_POINTS,
) -> Section:
    """The singular curves and the cusps of ``family`` over the box ``a_range x
    b_range`` (see the module)."""
    A = np.linspace(*a_range, points)
    B = np.linspace(*b_range, points)
    counts = np.array([[family.count(a, b) for b in B] for a in A])
    located: list[SingularPoint] = []
    for i in range(points):
        for j in range(points):
            for di, dj in ((1, 0), (0, 1)):
                k, m = i + di, j + dj
                if k < points and m < points and counts[i, j] != counts[k, m]:
                    p = _crossing(family, (A[i], B[j]), (A[k], B[m]), counts[i, j], counts[k, m])
                    if p is not None:
                        located.append(p)
    span = np.array([a_range[1] - a_range[0], b_range[1] - b_range[0]])
    found: list[np.ndarray] = []
    step = span / (points - 1)
    runs = 0
    for seed in _seeds(family, located, step):
        if any(np.all(np.abs(seed[1:] - w[1:]) <= 2 * step) for w in found):
            continue  # beside a cusp already found
        runs += 1
        z = _triple(family, seed, span)
        if z is None:
            continue
        inside = a_range[0] <= z[1] <= a_range[1] and b_range[0] <= z[2] <= b_range[1]
        if inside and not any(_same(z, w, span) for w in found):
            found.append(z)
    cusps = [_certified(family, z) for z in sorted(found, key=lambda z: (z[1], z[2]))]
    return Section(A, B, counts, located, cusps, runs)


def _seeds(family: Family, located: list[SingularPoint], step: np.ndarray) -> list[np.ndarray]:
    """Where Newton on the triple-root system starts: first between two located points
    (within a grid cell and a half) on which d2P/dt2 has opposite signs: a cusp may
    lie between them (along one curve d2P/dt2 changes sign only there)."""
    if not located:
        return []
    z = np.array([[p.t, p.a, p.b] for p in located])
    sign = np.sign(family.derivative(2, 0, 0, z[:, 0], z[:, 1], z[:, 2]))
    near = (np.abs(z[:, None, 1] - z[None, :, 1]) <= 1.5 * step[0]) & (
        np.abs(z[:, None, 2] - z[None, :, 2]) <= 1.5 * step[1]
    )
    opposite = sign[:, None] * sign[None, :] < 0
    i, j = np.nonzero(np.triu(near & opposite, 1))
    mids = (z[i] + z[j]) / 2
    # the half-angle tangent stretches: the midpoint's angle, not its tangent
    mids[:, 0] = np.tan((np.arctan(z[i, 0]) + np.arctan(z[j, 0])) / 2)
    return list(mids)


def _same(z: np.ndarray, w: np.ndarray, span: np.ndarray) -> bool:
    scale = np.array([max(1.0, abs(z[0])), *span])
    return bool(np.all(np.abs(z - w) <= 1e-6 * scale))


def _crossing(
    family: Family, u: tuple[float, float], v: tuple[float, float], nu: int, nv: int
) -> SingularPoint | None:
    """The singular point on the edge u-v (counts nu != nv): bisected on the count, then
    placed by Newton on P = P_t = 0 along the edge."""
    lo, hi = 0.0, 1.0
    du = (v[0] - u[0], v[1] - u[1])
    for _ in range(EDGE_BISECTIONS):
        mid = (lo + hi) / 2
        n = family.count(u[0] + mid * du[0], u[1] + mid * du[1])
        if n == nu:
            lo = mid
        elif n == nv:
            hi = mid
        else:  # a third count between: two crossings on this edge, the first kept
            hi = mid
            nv = n
    more = lo if nu > nv else hi
    roots = family.real_roots(u[0] + more * du[0], u[1] + more * du[1])
    if len(roots) < 2:
        return None
    k = int(np.argmin(np.diff(roots)))
    t, s = (roots[k] + roots[k + 1]) / 2, (lo + hi) / 2
    for _ in range(NEWTON_STEPS):
        a, b = u[0] + s * du[0], u[1] + s * du[1]
        f = np.array([family.derivative(0, 0, 0, t, a, b), family.derivative(1, 0, 0, t, a, b)])
        ds_p = family.derivative(0, 1, 0, t, a, b) * du[0] + family.derivative(0, 0, 1, t, a, b) * du[1]
        ds_pt = family.derivative(1, 1, 0, t, a, b) * du[0] + family.derivative(1, 0, 1, t, a, b) * du[1]
        J = np.array([[f[1], ds_p], [family.derivative(2, 0, 0, t, a, b), ds_pt]])
        try:
            step = np.linalg.solve(J, f)
        except np.linalg.LinAlgError:
            break
        t, s = t - step[0], s - step[1]
        if abs(step[1]) < 1e-15 and abs(step[0]) < 1e-13 * max(1.0, abs(t)):
            a, b = u[0] + s * du[0], u[1] + s * du[1]
            if -1e-9 <= s <= 1 + 1e-9:
                return SingularPoint(float(a), float(b), float(t), True)
            break
    s = (lo + hi) / 2
    return SingularPoint(u[0] + s * du[0], u[1] + s * du[1], float(roots[k]), False)


def _triple_residual(family: Family, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    t, a, b = z
    d = family.derivative
    f = np.array([d(0, 0, 0, t, a, b), d(1, 0, 0, t, a, b), d(2, 0, 0, t, a, b)])
    J = np.array([[d(p + 1, 0, 0, t, a, b), d(p, 1, 0, t, a, b), d(p, 0, 1, t, a, b)] for p in range(3)])
    return f, J


def _triple(family: Family, z: np.ndarray, span: np.ndarray) -> np.ndarray | None:
    """Newton on the triple-root system from ``z`` (steps limited to a tenth of the
    section): the real triple root it converges to, or None."""
    limit = np.array([max(1.0, abs(z[0])), *span]) * 0.1
    start = z
    for _ in range(TRIPLE_STEPS):
        f, J = _triple_residual(family, z)
        try:
            step = np.linalg.solve(J, f)
        except np.linalg.LinAlgError:
            return None
        if not np.all(np.isfinite(step)):
            return None
        step = step * min(1.0, float(np.min(limit / np.maximum(np.abs(step), 1e-300))))
        z = z - step
        if np.any(np.abs(z[1:] - start[1:]) > span):  # wandered off: not this seed's cusp
            return None
        if np.all(np.abs(step) <= 1e-13 * np.array([max(1.0, abs(z[0])), *np.maximum(1.0, np.abs(z[1:]))])):
            return z
    return None


def _certified(family: Family, z: np.ndarray) -> TripleRoot:
    """The triple root near ``z`` refined at CUSP_DIGITS digits and Krawczyk-tested."""
    t, a, b = family.t, family.a, family.b
    P = family.poly
    eqs = [P.as_expr(), P.diff(t).as_expr(), P.diff(t).diff(t).as_expr()]
    with mpmath.workdps(CUSP_DIGITS + 10):
        root = newton(eqs, [t, a, b], list(z), CUSP_DIGITS)
    with mpmath.workdps(CUSP_DIGITS):
        if root is None:
            return TripleRoot(z[1], z[2], z[0], False, 0.0, family.count(z[1], z[2]))
        ok = krawczyk(eqs, [t, a, b], root, mpmath.mpf(MODE_CERTIFY_RADIUS))
    tr, ar, br = root
    return TripleRoot(ar, br, tr, ok, MODE_CERTIFY_RADIUS, family.count(float(ar), float(br)))
