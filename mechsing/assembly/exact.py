"""Exact elimination of a planar platform system to one univariate polynomial, and the
certified isolation of its real roots (the built-in method; no extra needed).

The polynomial ``F(t)`` has algebraic coefficients (a given crank angle of 30 deg puts
sqrt(3) in them).  Its real roots are among those of its norm ``N(t) = res_a(F(t, a),
m(a))`` over Q (``a`` a primitive element of the coefficients' field, ``m`` its minimal
polynomial), which sympy isolates exactly in rational intervals.  In each interval, an
interval Newton step on ``F`` itself (mpmath interval arithmetic) either proves one root
of F there or an interval evaluation proves there is none; an interval neither proves
leaves the count unproven.  So ``proven`` means: every real solution is listed, each
exactly once.

Owns :class:`Eliminated` and :func:`eliminate_planar`.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import mpmath
import sympy

from mechsing.assembly.planar import OFFSETS, C, PlanarSystem, S, X, Y
from mechsing.errors import FormulationError

__all__ = ["Eliminated", "eliminate_planar", "interval_digits"]

T = sympy.Symbol("t", real=True)


@dataclass(frozen=True)
class Eliminated:
    """``finite``: False when the solution set is a curve (no count then); ``poses``:
    the platform poses (cos, sin, x, y; mpmath at the working precision); ``proven``:
    every real solution is listed; ``degree``: the univariate polynomial's degree
    (complex roots with multiplicity, before removing factors without real roots);
    ``offset``: tan(theta0/2); ``notes``: why a count is not proven."""

    finite: bool
    poses: tuple[tuple[Any, Any, Any, Any], ...]
    proven: bool
    degree: int
    offset: Any
    notes: tuple[str, ...]


def _split(system: PlanarSystem) -> tuple[list[sympy.Expr], sympy.Expr, int]:
    """Two equations linear in (x, y) and the third (its degree in x, y: 1 or 2)."""
    eqs = [sympy.expand(e) for e in system.equations]
    quads = [e for e in eqs if sympy.Poly(e, X, Y).total_degree() == 2]
    lins = [e for e in eqs if sympy.Poly(e, X, Y).total_degree() <= 1]
    if quads:
        base = quads[0]
        lins += [sympy.expand(q - base) for q in quads[1:]]
        if any(sympy.Poly(e, X, Y).total_degree() > 1 for e in lins):
            raise FormulationError("the distance equations do not share their quadratic part")
        return lins, base, 2
    return lins[:2], lins[2], 1


def _in_t(F: sympy.Expr, r: Any) -> sympy.Expr:
    """F(cos, sin) as a polynomial in t, theta = theta0 + 2 atan t, tan(theta0/2) = r."""
    P = sympy.Poly(F, C, S)
    m = P.total_degree()
    tau_n, tau_d = r + T, 1 - r * T  # tan(theta/2) = tau_n / tau_d
    cn, sn, dn = tau_d**2 - tau_n**2, 2 * tau_n * tau_d, tau_d**2 + tau_n**2
    out = sympy.S.Zero
    for (i, j), coeff in P.terms():
        out += coeff * cn**i * sn**j * dn ** (m - i - j)
    return sympy.expand(out)


def eliminate_planar(system: PlanarSystem, dps: int) -> Eliminated:
    """Every real platform pose of ``system`` (see the module)."""
    lins, base, k = _split(system)
    (a1, b1, e1), (a2, b2, e2) = (
        [sympy.expand(e).coeff(X), sympy.expand(e).coeff(Y), sympy.expand(e).subs({X: 0, Y: 0})]
        for e in lins
    )
    D = sympy.expand(a1 * b2 - a2 * b1)
    Dx = sympy.expand(-(e1 * b2 - e2 * b1))
    Dy = sympy.expand(-(a1 * e2 - a2 * e1))
    F = sympy.expand(sympy.cancel(base.subs({X: Dx / D, Y: Dy / D}, simultaneous=True) * D**k))
    notes: list[str] = []
    for r in OFFSETS:
        c0 = (1 - r**2) / (1 + r**2)
        s0 = 2 * r / (1 + r**2)
        at_infinity = sympy.simplify(F.subs({C: -c0, S: -s0}))
        if at_infinity != 0:
            break
    else:
        raise FormulationError("every offset tried has a solution at theta0 + pi")
    Ft = _in_t(F, r)
    if Ft == 0:
        return Eliminated(False, (), True, 0, r, ("the solutions form a curve",))
    Dt = _in_t(D, r) if D.has(C, S) else D
    with mpmath.workdps(dps + 20), interval_digits(dps + 20):
        roots, proven_roots = _certified_real_roots(Ft, dps)
        proven = proven_roots
        if not proven_roots:
            notes.append("a real root of the norm could be neither certified nor excluded")
        tiny = mpmath.mpf(10) ** (-dps // 2)
        degenerate = []  # angles where Cramer's rule has 0/0: solved apart
        if Dt != 0 and sympy.sympify(Dt).has(T):
            for tr in _certified_real_roots(Dt, dps)[0]:
                if abs(_value(_in_t(Dx, r), tr)) < tiny and abs(_value(_in_t(Dy, r), tr)) < tiny:
                    degenerate.append(tr)
        poses = []
        theta0 = 2 * mpmath.atan(mpmath.mpf(r.p) / r.q)
        for tr in roots:
            theta = theta0 + 2 * mpmath.atan(tr)
            c, s = mpmath.cos(theta), mpmath.sin(theta)
            d = _at(D, c, s)
            if abs(d) >= tiny:
                poses.append((c, s, _at(Dx, c, s) / d, _at(Dy, c, s) / d))
        for tr in degenerate:
            proven = False
            notes.append("Cramer's rule degenerates at a platform angle; solved there numerically")
            theta = theta0 + 2 * mpmath.atan(tr)
            extra = _degenerate_poses(lins, base, mpmath.cos(theta), mpmath.sin(theta), tiny)
            if extra is None:
                return Eliminated(
                    False,
                    (),
                    True,
                    sympy.Poly(Ft, T).degree(),
                    r,
                    (
                        f"the closed configurations form a curve at the platform angle "
                        f"{mpmath.nstr(theta, 12)} rad",
                    ),
                )
            poses.extend(extra)
    return Eliminated(True, tuple(poses), proven, sympy.Poly(Ft, T).degree(), r, tuple(notes))


def _degenerate_poses(
    lins: list[sympy.Expr], base: sympy.Expr, c: Any, s: Any, tiny: Any
) -> list[tuple[Any, Any, Any, Any]] | None:
    """The poses at a platform angle where both linear equations are dependent: the
    line they leave (rank 1) met with the third equation, or None when they vanish and
    the third leaves a curve (a circle of positive radius or a line)."""
    rows = [
        [_at(sympy.expand(e).coeff(v), c, s) for v in (X, Y)]
        + [_at(sympy.expand(e).subs({X: 0, Y: 0}), c, s)]
        for e in lins
    ]
    row = max(rows, key=lambda w: abs(w[0]) + abs(w[1]))
    b3 = sympy.Poly(sympy.expand(base), X, Y)
    q = {m: _at(k, c, s) for m, k in b3.terms()}
    if abs(row[0]) + abs(row[1]) < tiny:
        if any(abs(w[2]) >= tiny for w in rows):
            return []  # 0 = non-zero: no pose at this angle
        quad = q.get((2, 0), 0)
        if quad == 0:
            return None  # a line of positions
        gx, gy, h = q.get((1, 0), 0) / quad, q.get((0, 1), 0) / quad, q.get((0, 0), 0) / quad
        return None if (gx**2 + gy**2) / 4 - h > tiny else []
    a, b, e = row
    n2 = a * a + b * b
    p0 = (-e * a / n2, -e * b / n2)
    u = (-b, a)

    def at(lam: Any) -> Any:
        x, y = p0[0] + lam * u[0], p0[1] + lam * u[1]
        return sum(k * x**i * y**j for (i, j), k in q.items())

    c0, c1, c2 = at(0), (at(1) - at(-1)) / 2, (at(1) + at(-1)) / 2 - at(0)
    lams = [-c0 / c1] if abs(c2) < tiny and abs(c1) >= tiny else []
    if abs(c2) >= tiny:
        disc = c1 * c1 - 4 * c2 * c0
        if disc >= 0:
            lams = [(-c1 + sgn * mpmath.sqrt(disc)) / (2 * c2) for sgn in (1, -1)]
    return [(c, s, p0[0] + lam * u[0], p0[1] + lam * u[1]) for lam in lams]


@contextlib.contextmanager
def interval_digits(dps: int) -> Iterator[None]:
    """mpmath's interval context at ``dps`` digits for the block."""
    before = mpmath.iv.dps
    mpmath.iv.dps = dps
    try:
        yield
    finally:
        mpmath.iv.dps = before


def _at(expr: sympy.Expr, c: Any, s: Any) -> Any:
    """An mpmath value of a polynomial in (cos, sin) with algebraic coefficients."""
    total = mpmath.mpf(0)
    for (i, j), coeff in sympy.Poly(expr, C, S).terms():
        total += mpmath.mpf(sympy.N(coeff, mpmath.mp.dps + 5)) * c**i * s**j
    return total


def _value(expr: sympy.Expr, t: Any) -> Any:
    """An mpmath value of a polynomial in t with algebraic coefficients."""
    P = sympy.Poly(expr, T)
    coeffs = [mpmath.mpf(sympy.N(c, mpmath.mp.dps + 5)) for c in P.all_coeffs()]
    return mpmath.polyval(coeffs, t)


def _interval_coeffs(P: sympy.Poly) -> list[Any]:
    """Enclosures (mpmath intervals) of the algebraic coefficients of ``P``."""
    out = []
    dps = mpmath.mp.dps
    pad = mpmath.mpf(10) ** (-(dps - 5))
    for c in P.all_coeffs():
        if c.is_Rational:
            out.append(mpmath.iv.mpf(c.p) / c.q)
        else:
            v = mpmath.mpf(sympy.N(c, dps + 10))
            out.append(mpmath.iv.mpf([v - pad * (1 + abs(v)), v + pad * (1 + abs(v))]))
    return out


def _ipolyval(coeffs: list[Any], x: Any) -> Any:
    acc = mpmath.iv.mpf(0)
    for c in coeffs:
        acc = acc * x + c
    return acc


def _certified_real_roots(F: sympy.Expr, dps: int) -> tuple[list[Any], bool]:
    """The real roots of ``F`` (mpmath numbers at ``dps`` digits), and whether each
    interval of the norm's isolation was decided (root certified or excluded)."""
    P = sympy.Poly(F, T)
    irrational = [c for c in set(P.coeffs()) if not c.is_Rational]
    if irrational:
        # square-free over the coefficients' field: a double root (two modes merging at a
        # singular configuration) stays a simple root that interval Newton can prove
        P = sympy.Poly(sympy.Poly(F, T, extension=True).sqf_part().as_expr(), T)
        irrational = [c for c in set(P.coeffs()) if not c.is_Rational]
    if irrational:
        a = sympy.Dummy("a")
        _, combo = sympy.primitive_element(irrational, a)
        theta = sum((k * c for k, c in zip(combo, irrational, strict=True)), sympy.S.Zero)
        field = sympy.QQ.algebraic_field(theta)
        minpoly = sympy.minimal_polynomial(field.ext.as_expr(), a)
        Fa = sympy.S.Zero
        for (e,), c in P.terms():
            rep = field.from_sympy(c).to_list()
            Fa += T**e * sum(
                (
                    sympy.Rational(int(q.numerator), int(q.denominator)) * a**i
                    for i, q in enumerate(reversed(rep))
                ),
                sympy.S.Zero,
            )
        norm = sympy.Poly(sympy.resultant(sympy.expand(Fa), minpoly, a), T)
    else:
        norm = P
    sqf = sympy.Poly(sympy.sqf_part(norm.as_expr()), T)
    if sqf.degree() <= 0:
        return [], True
    coeffs = _interval_coeffs(sympy.Poly(sympy.sqf_part(P.as_expr()), T) if not irrational else P)
    dcoeffs = (
        _interval_coeffs(P.diff(T))
        if irrational
        else _interval_coeffs(sympy.Poly(sympy.sqf_part(P.as_expr()), T).diff(T))
    )
    eps = sympy.Rational(1, 10 ** (dps + 3))
    roots, decided = [], True
    for (lo, hi), _m in sqf.intervals(eps=eps):
        lo, hi = sympy.Rational(lo), sympy.Rational(hi)
        if lo == hi:  # an exact rational root of the norm
            pad = sympy.Rational(1, 10 ** (dps + 3))
            lo, hi = lo - pad, hi + pad
        box = mpmath.iv.mpf([mpmath.mpf(lo.p) / lo.q, mpmath.mpf(hi.p) / hi.q])
        mid = (mpmath.mpf(lo.p) / lo.q + mpmath.mpf(hi.p) / hi.q) / 2
        value = _ipolyval(coeffs, box)
        if not (value.a <= 0 <= value.b):
            continue  # excluded: no root of F in this interval (a conjugate's root)
        slope = _ipolyval(dcoeffs, box)
        if slope.a <= 0 <= slope.b:
            decided = False
            continue
        newton = mpmath.iv.mpf(mid) - _ipolyval(coeffs, mpmath.iv.mpf(mid)) / slope
        if newton.a > box.a and newton.b < box.b:
            roots.append(mid)  # interval Newton: exactly one root of F in the box
        else:
            decided = False
    return roots, decided
