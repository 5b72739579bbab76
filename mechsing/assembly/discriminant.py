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
pair of neighbouring located singular points on which d2P/dt2 has opposite signs, and
from every located point, Newton on the triple-root system (all at once, in numpy), the points it converges to in the section kept once.  The count of cusps is therefore what the grid sees: a cusp whose
curves cross no grid edge is missed (a finer grid, ``points``, finds it).

Owns :class:`Family`, :class:`Section`, :func:`section`, :func:`without_free_factor`
and :func:`decoupled_evidence`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import mpmath
import numpy as np
import numpy.polynomial.polynomial as P3
import sympy

from mechsing.assembly.certify import krawczyk, newton, regular
from mechsing.assembly.settings import MODE_CERTIFY_RADIUS
from mechsing.numeric.tolerances import CUSP_DISTINCT_RTOL, CUSP_REAL_RTOL

__all__ = ["Family", "Section", "decoupled_evidence", "section", "without_free_factor"]

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

    @property
    def flipped(self) -> Family:
        """``t^n P(-1/t)``: the same modes in ``s = -1/t`` (theta moved by pi), where a
        root near t = oo (the platform angle near theta0 + pi) is near s = 0 and Newton
        on it is well conditioned; its triple roots are P's at t = -1/s."""
        if "flipped" not in self.cache:
            n = self.degree
            expr = sympy.expand(self.t**n * self.poly.as_expr().subs(self.t, -1 / self.t))
            self.cache["flipped"] = Family.of(expr, self.t, self.a, self.b)
        return self.cache["flipped"]

    def in_t(self, a: float, b: float) -> np.ndarray:
        """The coefficients in t at (a, b), highest power first."""
        out = np.zeros(self.degree + 1)
        vals = self.coeffs * a ** self.monos[:, 1] * b ** self.monos[:, 2]
        np.add.at(out, self.degree - self.monos[:, 0], vals)
        return out

    def vanishes(self, a: float, b: float) -> bool:
        """Is P(t; a, b) zero for every t (each coefficient below CUSP_DISTINCT_RTOL of
        its terms' size)?"""
        vals = self.coeffs * a ** self.monos[:, 1] * b ** self.monos[:, 2]
        size = np.zeros(self.degree + 1)
        np.add.at(size, self.degree - self.monos[:, 0], np.abs(vals))
        return bool(
            np.all(np.abs(self.in_t(a, b)) <= CUSP_DISTINCT_RTOL * np.maximum(size, 1e-300))
        )

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
    #: not certified because the triple-root system's Jacobian is singular there (at the
    #: working digits: :func:`~mechsing.assembly.certify.regular`): a degenerate cusp
    #: (``P_ttt (P_a P_tb - P_b P_ta) = 0``: the singular curve is itself singular
    #: there), which the Krawczyk test, on a regular root only, cannot certify
    degenerate: bool = False


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
    family: Family,
    a_range: tuple[float, float],
    b_range: tuple[float, float],
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
    seeds = _seeds(family, located, span / (points - 1))
    for z in _triple_batch(family, seeds, span):
        inside = a_range[0] <= z[1] <= a_range[1] and b_range[0] <= z[2] <= b_range[1]
        if inside and not any(_same(z, w, span) for w in found):
            found.append(z)
    refined = (_certified(family, z) for z in sorted(found, key=lambda z: (z[1], z[2])))
    cusps: list[TripleRoot] = []
    for c in refined:  # two starts' points that refine to one triple root: kept once
        if c is not None and not any(
            abs(c.a - d.a) + abs(c.b - d.b) <= 1e-20 * (1 + abs(c.a) + abs(c.b)) for d in cusps
        ):
            cusps.append(c)
    return Section(A, B, counts, located, cusps, len(seeds))


def _seeds(family: Family, located: list[SingularPoint], step: np.ndarray) -> np.ndarray:
    """Where Newton on the triple-root system starts: first between two located points
    (within a grid cell and a half) on which d2P/dt2 has opposite signs: a cusp may
    lie between them (along one curve d2P/dt2 changes sign only there); then every
    located point (the tip of a wedge thinner than a grid cell has only one side's)."""
    if not located:
        return np.zeros((0, 3))
    z = np.array([[p.t, p.a, p.b] for p in located])
    sign = np.sign(family.derivative(2, 0, 0, z[:, 0], z[:, 1], z[:, 2]))
    near = (np.abs(z[:, None, 1] - z[None, :, 1]) <= 1.5 * step[0]) & (
        np.abs(z[:, None, 2] - z[None, :, 2]) <= 1.5 * step[1]
    )
    opposite = sign[:, None] * sign[None, :] < 0
    i, j = np.nonzero(np.triu(near & opposite, 1))
    mids = (z[i] + z[j]) / 2
    # the half-angle tangent stretches and wraps at oo: the mean of the angles
    half = np.angle(np.exp(2j * np.arctan(z[i, 0])) + np.exp(2j * np.arctan(z[j, 0]))) / 2
    mids[:, 0] = np.tan(half)
    return np.array([*mids, *z]).reshape(-1, 3)


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
        ds_p = (
            family.derivative(0, 1, 0, t, a, b) * du[0]
            + family.derivative(0, 0, 1, t, a, b) * du[1]
        )
        ds_pt = (
            family.derivative(1, 1, 0, t, a, b) * du[0]
            + family.derivative(1, 0, 1, t, a, b) * du[1]
        )
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


def _triple_batch(family: Family, seeds: np.ndarray, span: np.ndarray) -> list[np.ndarray]:
    """Newton on the triple-root system from every seed at once (steps limited to a
    tenth of the section; a run that wanders a section away is dropped): the real
    triple roots reached.  Seeds with |t| > 1 run in the flipped polynomial
    (:attr:`Family.flipped`) and come back in t."""
    out = []
    far = np.abs(seeds[:, 0]) > 1
    for fam, part, flip in ((family, seeds[~far], False), (family.flipped, seeds[far], True)):
        if not len(part):
            continue
        z = part.copy()
        if flip:
            z[:, 0] = -1 / z[:, 0]
        done = _newton_batch(fam, z, span)
        for w in done:
            if flip:
                if w[0] == 0:
                    continue
                w = np.array([-1 / w[0], w[1], w[2]])
            out.append(w)
    return out


def _newton_batch(family: Family, z: np.ndarray, span: np.ndarray) -> list[np.ndarray]:
    start = z.copy()
    alive = np.ones(len(z), dtype=bool)
    converged = np.zeros(len(z), dtype=bool)
    d = family.derivative
    for _ in range(TRIPLE_STEPS):
        idx = np.nonzero(alive & ~converged)[0]
        if not len(idx):
            break
        t, a, b = z[idx, 0], z[idx, 1], z[idx, 2]
        f = np.stack([d(p, 0, 0, t, a, b) for p in range(3)], axis=-1)
        J = np.stack(
            [
                np.stack([d(p + 1, 0, 0, t, a, b), d(p, 1, 0, t, a, b), d(p, 0, 1, t, a, b)], -1)
                for p in range(3)
            ],
            axis=-2,
        )
        ok = np.abs(np.linalg.det(J)) > 0
        step = np.zeros_like(f)
        step[ok] = np.linalg.solve(J[ok], f[ok][..., None])[..., 0]
        limit = (
            np.stack([np.maximum(1.0, np.abs(t)), *(np.full(len(t), x) for x in span)], -1) * 0.1
        )
        scale = np.minimum(1.0, np.min(limit / np.maximum(np.abs(step), 1e-300), axis=1))
        z[idx] = z[idx] - step * scale[:, None]
        bad = (
            ~ok
            | ~np.all(np.isfinite(z[idx]), axis=1)
            | np.any(np.abs(z[idx, 1:] - start[idx, 1:]) > span, axis=1)
        )
        alive[idx[bad]] = False
        tol = 1e-13 * np.maximum(1.0, np.abs(z[idx]))
        converged[idx[~bad & np.all(np.abs(step) <= tol, axis=1)]] = True
    return [z[i] for i in np.nonzero(converged & alive)[0]]


def _certified(family: Family, z: np.ndarray) -> TripleRoot | None:
    """The triple root near ``z`` refined at CUSP_DIGITS digits and Krawczyk-tested
    (None: Newton at those digits does not close there: no triple root)."""
    if abs(z[0]) > 1:  # certified in the flipped polynomial, where the root is near 0
        flip = _certified(family.flipped, np.array([-1 / z[0], z[1], z[2]]))
        if flip is None:
            return None
        with mpmath.workdps(CUSP_DIGITS):
            return TripleRoot(
                flip.a,
                flip.b,
                -1 / flip.t,
                flip.certified,
                flip.radius,
                family.count(float(flip.a), float(flip.b)),
                flip.degenerate,
            )
    if family.vanishes(z[1], z[2]):
        return None  # every t solves there (a curve of modes), not three meeting
    t, a, b = family.t, family.a, family.b
    P = family.poly
    eqs = [P.as_expr(), P.diff(t).as_expr(), P.diff(t).diff(t).as_expr()]
    with mpmath.workdps(CUSP_DIGITS + 10):
        root = newton(eqs, [t, a, b], list(z), CUSP_DIGITS)
    with mpmath.workdps(CUSP_DIGITS):
        if root is None:  # double precision's point is not a triple root at 50 digits
            return None
        ok = krawczyk(eqs, [t, a, b], root, mpmath.mpf(MODE_CERTIFY_RADIUS))
        degenerate = not ok and not regular(eqs, [t, a, b], root)
    tr, ar, br = root
    return TripleRoot(
        ar, br, tr, ok, MODE_CERTIFY_RADIUS, family.count(float(ar), float(br)), degenerate
    )


def without_free_factor(
    F: sympy.Expr, t: sympy.Symbol, a: sympy.Symbol, b: sympy.Symbol
) -> sympy.Expr:
    """``F`` divided by its factor free of ``a`` and ``b`` (the gcd of its coefficients
    as a polynomial in them): roots that every point of the section shares are not modes."""
    poly = sympy.Poly(F, a, b)
    g = sympy.S.Zero
    for c in poly.coeffs():
        g = sympy.gcd(g, c)
        if g == 1:
            return sympy.expand(F)
    if not g.has(t):
        return sympy.expand(F)
    q, rem = sympy.div(sympy.expand(F), sympy.expand(g), t, a, b)
    return sympy.expand(q) if rem == 0 else sympy.expand(F)


def decoupled_evidence(
    P: sympy.Expr, t: sympy.Symbol, a: sympy.Symbol, b: sympy.Symbol, what: str
) -> dict[str, Any] | None:
    """Evidence that ``P`` has no triple root of its modes because every factor that
    holds ``t`` is repeated (the modes come in pairs of a lower-degree polynomial's
    roots: the kinematics decouples), or None."""
    _, factors = sympy.sqf_list(sympy.Poly(P, t, a, b))
    moving = [(f, m) for f, m in factors if f.degree(t) > 0]
    if moving and all(m >= 2 for _, m in moving):
        degree = sum(f.degree(t) for f, _ in moving)
        return {
            "kind": "decoupled",
            "reason": (
                f"the eliminant is a power of a polynomial of degree {degree} in t: {what}; "
                "its modes meet at most in pairs of that polynomial's double roots, never "
                "three at one point: no cusp anywhere"
            ),
        }
    return None
