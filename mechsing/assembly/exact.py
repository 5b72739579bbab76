"""Elimination of a planar platform system to one univariate polynomial, and the
certified isolation of its real roots (the built-in method; no extra needed).

The polynomial ``F(t)`` has algebraic coefficients when the given angles' cosines are
algebraic (30 deg puts sqrt(3) in them), and transcendental ones otherwise (0.3 rad puts
cos(3/10)), or the earlier stages' symbols in a linkage solved in stages.  Its real
roots are isolated first by Smith's discs (:func:`_roots_of_enclosed`): the
coefficients enclosed in intervals, every complex root approximated, and a disc about
each that provably holds it; lone discs on the real axis are real roots, discs clear of
it are not.  That proves simple roots in any field.  Where discs touch (a double root:
two modes merging at a configuration given exactly) and the coefficients are
algebraic, the real roots are among those of the norm ``N(t) = res_a(F(t, a), m(a))``
over Q (``a`` a primitive element of the coefficients' field, ``m`` its minimal
polynomial), which sympy isolates exactly in rational intervals; in each, an interval
Newton step on ``F`` itself either proves one root of F there or an interval evaluation
proves there is none.  An interval neither proves leaves the count unproven.  So
``proven`` means: every real solution is listed, each exactly once.  With transcendental
coefficients ``F`` is formed in interval arithmetic from the start
(:func:`_enclosed_eliminant`).

Owns :class:`Eliminated`, :class:`Staged`, :func:`eliminate_planar` and
:func:`eliminate_stages`.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import mpmath
import sympy

from mechsing.assembly.certify import interval_function
from mechsing.assembly.planar import OFFSETS, C, PlanarSystem, S, X, Y
from mechsing.errors import FormulationError

__all__ = [
    "Eliminated",
    "Staged",
    "eliminant",
    "eliminant_of",
    "eliminate_planar",
    "eliminate_stages",
    "interval_digits",
]

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
    #: each pose's enclosure (intervals of cos, sin, x, y), for the stages after it
    boxes: tuple[tuple[Any, Any, Any, Any], ...] = ()


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


def _constants(*exprs: sympy.Expr) -> list[sympy.Expr]:
    """The irrational constants of the expressions (radicals, cos(3/10), the earlier
    stages' symbols): generators of sympy polynomials, whose products are far faster
    than expanding expressions (three decimal inputs of a 3-RRR took minutes)."""
    found: set[sympy.Expr] = set()
    for e in exprs:
        for a in sympy.preorder_traversal(e):
            if a.is_Symbol and a not in (X, Y, C, S, T):
                found.add(a)
            elif a.is_number and (
                isinstance(a, sympy.Function) or (a.is_Pow and not a.is_Rational)
            ):
                found.add(a)
            elif a in (sympy.pi, sympy.E):
                found.add(a)
    return sorted(found, key=sympy.default_sort_key)


def _in_t(F: sympy.Expr, r: Any) -> sympy.Expr:
    """F(cos, sin) as a polynomial in t, theta = theta0 + 2 atan t, tan(theta0/2) = r."""
    P = sympy.Poly(F, C, S)
    m = P.total_degree()
    tau_n, tau_d = r + T, 1 - r * T  # tan(theta/2) = tau_n / tau_d
    gens = [T, *_constants(F)]
    cn, sn, dn = (
        sympy.Poly(e, *gens) for e in (tau_d**2 - tau_n**2, 2 * tau_n * tau_d, tau_d**2 + tau_n**2)
    )
    out = sympy.Poly(0, *gens)
    for (i, j), coeff in P.terms():
        out += sympy.Poly(coeff, *gens) * cn**i * sn**j * dn ** (m - i - j)
    return out.as_expr()


def eliminate_planar(system: PlanarSystem, dps: int, at: dict | None = None) -> Eliminated:
    """Every real platform pose of ``system`` (see the module); ``at``: the values of
    the earlier stages' symbols (each an mpmath number and its interval enclosure)."""
    at = at or {}
    lins, base, k = _split(system)
    D, Dx, Dy = _cramer(lins)
    notes: list[str] = []
    if any(_transcendental(c) for c in _constants(D, Dx, Dy, base)):
        solved = _enclosed_eliminant(D, Dx, Dy, base, k, dps, at)
    else:
        solved = _exact_eliminant(D, Dx, Dy, base, k, dps, at)
    if solved[0] is None:
        return Eliminated(False, (), True, 0, OFFSETS[0], ("the solutions form a curve",))
    r, roots, radii, proven_roots, degree = solved
    Dt = _in_t(D, r) if D.has(C, S) else D
    with mpmath.workdps(dps + 20), interval_digits(dps + 20):
        proven = proven_roots
        if not proven_roots:
            notes.append("a real root of the eliminant could be neither certified nor excluded")
        tiny = mpmath.mpf(10) ** (-dps // 2)
        degenerate = []  # angles where Cramer's rule has 0/0: solved apart
        if Dt != 0 and sympy.sympify(Dt).has(T):
            for tr in _certified_real_roots(Dt, dps, at)[0]:
                if (
                    abs(_value(_in_t(Dx, r), tr, at)) < tiny
                    and abs(_value(_in_t(Dy, r), tr, at)) < tiny
                ):
                    degenerate.append(tr)
        poses, boxes = [], []
        theta0 = 2 * mpmath.atan(mpmath.mpf(r.p) / r.q)
        enclose = _pose_enclosure(D, Dx, Dy, r, at)
        for tr, rad in zip(roots, radii, strict=True):
            theta = theta0 + 2 * mpmath.atan(tr)
            c, s = mpmath.cos(theta), mpmath.sin(theta)
            d = _at(D, c, s, at)
            if abs(d) >= tiny:
                poses.append((c, s, _at(Dx, c, s, at) / d, _at(Dy, c, s, at) / d))
                boxes.append(enclose(tr, rad))
        for tr in degenerate:
            proven = False
            notes.append("Cramer's rule degenerates at a platform angle; solved there numerically")
            theta = theta0 + 2 * mpmath.atan(tr)
            extra = _degenerate_poses(lins, base, mpmath.cos(theta), mpmath.sin(theta), tiny, at)
            if extra is None:
                return Eliminated(
                    False,
                    (),
                    True,
                    degree,
                    r,
                    (
                        f"the closed configurations form a curve at the platform angle "
                        f"{mpmath.nstr(theta, 12)} rad",
                    ),
                )
            poses.extend(extra)
            boxes.extend(tuple(mpmath.iv.mpf([v - tiny, v + tiny]) for v in p) for p in extra)
    return Eliminated(True, tuple(poses), proven, degree, r, tuple(notes), tuple(boxes))


def _cramer(lins: list[sympy.Expr]) -> tuple[sympy.Expr, sympy.Expr, sympy.Expr]:
    """Cramer's rule on the two equations linear in (x, y): (D, Dx, Dy), x = Dx / D."""
    (a1, b1, e1), (a2, b2, e2) = (
        [sympy.expand(e).coeff(X), sympy.expand(e).coeff(Y), sympy.expand(e).subs({X: 0, Y: 0})]
        for e in lins
    )
    D = sympy.expand(a1 * b2 - a2 * b1)
    Dx = sympy.expand(-(e1 * b2 - e2 * b1))
    Dy = sympy.expand(-(a1 * e2 - a2 * e1))
    return D, Dx, Dy


def _homogenised(
    D: sympy.Expr, Dx: sympy.Expr, Dy: sympy.Expr, base: sympy.Expr, k: int
) -> sympy.Expr:
    """D^k base(Dx/D, Dy/D), each term homogenised by D (no division: sympy's cancel
    cannot always clear a denominator that holds radicals): a polynomial in (c, s)."""
    gens = [C, S, *_constants(D, Dx, Dy, base)]
    Dp, Dxp, Dyp = (sympy.Poly(e, *gens) for e in (D, Dx, Dy))
    return sum(
        (
            sympy.Poly(coeff, *gens) * Dxp**i * Dyp**j * Dp ** (k - i - j)
            for (i, j), coeff in sympy.Poly(base, X, Y).terms()
        ),
        sympy.Poly(0, *gens),
    ).as_expr()


def eliminant(
    system: PlanarSystem, r: Any = OFFSETS[0]
) -> tuple[sympy.Expr, tuple[sympy.Expr, sympy.Expr, sympy.Expr]]:
    """The univariate eliminant ``F(t)`` of ``system`` (t = tan((theta - theta0)/2),
    tan(theta0/2) = ``r``) and Cramer's (D, Dx, Dy) in (c, s) that give the platform's
    position at a root; the system's other symbols (given values left as symbols: a
    section of the input space, :mod:`~mechsing.assembly.cusps`) stay in both."""
    lins, base, k = _split(system)
    return eliminant_of(lins, base, k, r)


def eliminant_of(
    lins: list[sympy.Expr], base: sympy.Expr, k: int, r: Any = OFFSETS[0]
) -> tuple[sympy.Expr, tuple[sympy.Expr, sympy.Expr, sympy.Expr]]:
    """:func:`eliminant` of two equations ``lins`` linear in (x, y) and a third ``base``
    of degree ``k`` in them, every coefficient a polynomial in (c, s): the planar
    symbols :data:`~.planar.X`, :data:`~.planar.Y`, :data:`~.planar.C`,
    :data:`~.planar.S` (a 3R arm's inverse kinematics has this shape too: x, y the
    cosine and sine of one joint angle, c, s of another)."""
    D, Dx, Dy = _cramer(lins)
    return _in_t(_homogenised(D, Dx, Dy, base, k), r), (D, Dx, Dy)


def _exact_eliminant(
    D: sympy.Expr, Dx: sympy.Expr, Dy: sympy.Expr, base: sympy.Expr, k: int, dps: int, at: dict
) -> tuple:
    """The eliminant with algebraic coefficients, exactly: (offset, real roots, their
    radii, proven, degree), or (None, ...) for a curve."""
    F = _homogenised(D, Dx, Dy, base, k)
    if _is_zero(F, dps, at):  # every platform angle has a position (a point platform)
        return (None,)
    for r in OFFSETS:
        c0 = (1 - r**2) / (1 + r**2)
        s0 = 2 * r / (1 + r**2)
        if not _is_zero(F.subs({C: -c0, S: -s0}), dps, at):
            break
    else:
        raise FormulationError("every offset tried has a solution at theta0 + pi")
    Ft = _in_t(F, r)
    if _is_zero(Ft, dps, at):
        return (None,)
    with mpmath.workdps(dps + 20), interval_digits(dps + 20):
        roots, radii, proven = _certified_real_roots(Ft, dps, at)
    return r, roots, radii, proven, sympy.Poly(Ft, T).degree()


def _enclosed_eliminant(
    D: sympy.Expr, Dx: sympy.Expr, Dy: sympy.Expr, base: sympy.Expr, k: int, dps: int, at: dict
) -> tuple:
    """The eliminant whose coefficients hold transcendental values (cos(3/10)) or an
    earlier stage's symbols: the same polynomial, its coefficients enclosed and combined
    in interval arithmetic (no exact expansion: three decimal inputs of a 3-RRR took
    minutes in sympy); (offset, real roots, radii, proven, degree), or (None, ...) for
    a curve to the working digits."""
    with mpmath.workdps(dps + 20), interval_digits(dps + 20):
        Dp, Dxp, Dyp = (_enclosed_poly(e, at) for e in (D, Dx, Dy))
        F: dict[tuple[int, int], Any] = {}
        for (i, j), coeff in sympy.Poly(base, X, Y).terms():
            term = _enclosed_poly(coeff, at)
            for factor, n in ((Dxp, i), (Dyp, j), (Dp, k - i - j)):
                for _ in range(n):
                    term = _imul(term, factor)
            for m, v in term.items():
                F[m] = F[m] + v if m in F else v
        if all(v.a <= 0 <= v.b for v in F.values()):
            return (None,)
        for r in OFFSETS:
            c0 = (1 - r**2) / (1 + r**2)
            s0 = 2 * r / (1 + r**2)
            v = sum(
                (
                    a * (mpmath.iv.mpf(-c0.p) / c0.q) ** i * (mpmath.iv.mpf(-s0.p) / s0.q) ** j
                    for (i, j), a in F.items()
                ),
                mpmath.iv.mpf(0),
            )
            if not v.a <= 0 <= v.b:
                break
        else:
            raise FormulationError("every offset tried has a solution at theta0 + pi")
        m = max(i + j for i, j in F)
        tau_n, tau_d = r + T, 1 - r * T  # as in _in_t
        cn, sn, dn = (
            sympy.Poly(e, T) for e in (tau_d**2 - tau_n**2, 2 * tau_n * tau_d, tau_d**2 + tau_n**2)
        )
        Ft = [mpmath.iv.mpf(0)] * (2 * m + 1)  # lowest power first
        for (i, j), a in F.items():
            for (e,), q in (cn**i * sn**j * dn ** (m - i - j)).terms():
                Ft[e] += a * (mpmath.iv.mpf(q.p) / q.q)
        while len(Ft) > 1 and Ft[-1].a == 0 == Ft[-1].b:
            Ft.pop()
        if all(v.a <= 0 <= v.b for v in Ft):
            return (None,)
        roots, radii, proven = _roots_of_enclosed(Ft[::-1])
    return r, roots, radii, proven, len(Ft) - 1


def _enclosed_poly(expr: sympy.Expr, at: dict) -> dict[tuple[int, int], Any]:
    """A polynomial in (cos, sin) as {exponents: the enclosure of its coefficient}."""
    P = sympy.Poly(expr, C, S)
    return dict(zip(P.monoms(), _interval_coeffs_of(P.coeffs(), at), strict=True))


def _imul(p: dict, q: dict) -> dict:
    """The product of two polynomials with interval coefficients."""
    out: dict = {}
    for m1, a in p.items():
        for m2, b in q.items():
            m = (m1[0] + m2[0], m1[1] + m2[1])
            out[m] = out[m] + a * b if m in out else a * b
    return out


def _pose_enclosure(D: sympy.Expr, Dx: sympy.Expr, Dy: sympy.Expr, r: Any, at: dict) -> Any:
    """A function of a root ``t`` and its radius: the enclosure (interval cos, sin, x,
    y) of the platform pose it gives (Cramer's rule in interval arithmetic)."""
    syms = list(at)
    f = interval_function([Dx, Dy, D], [C, S, *syms])
    r = mpmath.iv.mpf(r.p) / r.q

    def enclose(t: Any, radius: Any) -> tuple[Any, Any, Any, Any]:
        tt = mpmath.iv.mpf([t - radius, t + radius])
        tau_n, tau_d = r + tt, 1 - r * tt  # tan(theta/2) = tau_n / tau_d, as in _in_t
        dn = tau_d**2 + tau_n**2
        c, s = (tau_d**2 - tau_n**2) / dn, 2 * tau_n * tau_d / dn
        dx, dy, d = f([c, s, *(box for _, box in at.values())])
        return c, s, dx / d, dy / d

    return enclose


@dataclass(frozen=True)
class Staged:
    """The stages' platform poses: ``branches``, one tuple of poses (a pose per stage)
    per closed configuration; ``finite``, ``proven``, ``degrees`` (each stage's largest
    eliminant degree), ``offset`` (the first stage's), ``notes``."""

    finite: bool
    branches: tuple[tuple[tuple[Any, Any, Any, Any], ...], ...]
    proven: bool
    degrees: tuple[int, ...]
    offset: Any
    notes: tuple[str, ...]


def eliminate_stages(stages: list[PlanarSystem], dps: int) -> Staged:
    """Every real closed configuration of the stages (:func:`~.planar.planar_stages`):
    the first stage's platform poses; for each, the next stage's, its eliminant's
    coefficients enclosed at that pose's enclosure; and so on."""
    branches: list[tuple[dict, tuple]] = [({}, ())]
    proven, notes = True, []
    degrees = [0] * len(stages)
    offset = None
    for k, system in enumerate(stages):
        grown = []
        for at, poses in branches:
            found = eliminate_planar(system, dps, at)
            offset = found.offset if offset is None else offset
            degrees[k] = max(degrees[k], found.degree)
            notes += [n for n in found.notes if n not in notes]
            if not found.finite:
                return Staged(False, (), found.proven, tuple(degrees), offset, tuple(notes))
            proven = proven and found.proven
            for pose, box in zip(found.poses, found.boxes, strict=True):
                more = dict(at)
                for sym, v, b in zip(system.symbols, pose, box, strict=False):
                    more[sym] = (v, b)
                grown.append((more, (*poses, pose)))
        branches = grown
    return Staged(True, tuple(p for _, p in branches), proven, tuple(degrees), offset, tuple(notes))


def _degenerate_poses(
    lins: list[sympy.Expr], base: sympy.Expr, c: Any, s: Any, tiny: Any, at: dict
) -> list[tuple[Any, Any, Any, Any]] | None:
    """The poses at a platform angle where both linear equations are dependent: the
    line they leave (rank 1) met with the third equation, or None when they vanish and
    the third leaves a curve (a circle of positive radius or a line)."""
    rows = [
        [_at(sympy.expand(e).coeff(v), c, s, at) for v in (X, Y)]
        + [_at(sympy.expand(e).subs({X: 0, Y: 0}), c, s, at)]
        for e in lins
    ]
    row = max(rows, key=lambda w: abs(w[0]) + abs(w[1]))
    b3 = sympy.Poly(sympy.expand(base), X, Y)
    q = {m: _at(k, c, s, at) for m, k in b3.terms()}
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


def _number(c: sympy.Expr, at: dict) -> Any:
    """An mpmath value of a coefficient (a number, or a polynomial in the earlier
    stages' symbols, at their values ``at``)."""
    if c.free_symbols:
        syms = sorted(c.free_symbols, key=str)
        return sympy.lambdify(syms, c, "mpmath")(*(at[v][0] for v in syms))
    return mpmath.mpf(sympy.N(c, mpmath.mp.dps + 5))


def _at(expr: sympy.Expr, c: Any, s: Any, at: dict) -> Any:
    """An mpmath value of a polynomial in (cos, sin)."""
    total = mpmath.mpf(0)
    for (i, j), coeff in sympy.Poly(expr, C, S).terms():
        total += _number(coeff, at) * c**i * s**j
    return total


def _value(expr: sympy.Expr, t: Any, at: dict) -> Any:
    """An mpmath value of a polynomial in t."""
    P = sympy.Poly(expr, T)
    return mpmath.polyval([_number(c, at) for c in P.all_coeffs()], t)


def _interval_coeffs(P: sympy.Poly, at: dict | None = None) -> list[Any]:
    """Enclosures (mpmath intervals) of the coefficients of ``P`` (highest first)."""
    return _interval_coeffs_of(P.all_coeffs(), at)


def _interval_coeffs_of(coeffs: list[sympy.Expr], at: dict | None = None) -> list[Any]:
    """Enclosures (mpmath intervals) of numbers: rationals exactly, the others (radicals,
    cos(3/10)) evaluated by sympy to the working digits and padded by 10^-(digits - 5)
    relative; polynomials in the earlier stages' symbols in interval arithmetic at their
    enclosures ``at``."""
    if at and any(c.free_symbols for c in coeffs):
        syms = list(at)
        return interval_function(coeffs, syms)([box for _, box in at.values()])
    out = []
    dps = mpmath.mp.dps
    pad = mpmath.mpf(10) ** (-(dps - 5))
    for c in coeffs:
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


def _transcendental(c: sympy.Expr) -> bool:
    """Does the coefficient hold a function's value (cos(3/10) of a given angle of 0.3
    rad) or an earlier stage's symbol, known only to digits, not as an algebraic
    number?"""
    return bool(c.free_symbols or c.has(sympy.Function) or c.has(sympy.pi) or c.has(sympy.E))


def _is_zero(expr: sympy.Expr, dps: int, at: dict) -> bool:
    """Is ``expr`` (a number or a polynomial) zero: proved where its coefficients are
    algebraic; where they hold a transcendental value, zero to ``dps`` digits (every
    coefficient's enclosure holds 0: the elimination then takes the next offset, or
    calls the set a curve to those digits, and says so)."""
    expr = sympy.expand(expr)
    gens = [v for v in (T, C, S) if expr.has(v)]
    coeffs = sympy.Poly(expr, *gens).coeffs() if gens else [expr]
    if not any(_transcendental(c) for c in coeffs):
        return expr == 0 if expr.has(T, C, S) else sympy.simplify(expr) == 0
    with mpmath.workdps(dps + 20), interval_digits(dps + 20):
        return all(v.a <= 0 <= v.b for v in _interval_coeffs_of(coeffs, at))


def _certified_real_roots(F: sympy.Expr, dps: int, at: dict) -> tuple[list[Any], list[Any], bool]:
    """The real roots of ``F`` (mpmath numbers at ``dps`` digits), the radius of an
    interval about each that holds it, and whether each interval of the isolation was
    decided (root certified or excluded)."""
    P = sympy.Poly(F, T)
    # Smith's discs first: they prove simple roots in any field, fast; the norm over Q
    # (slow in a field of high degree: cos(pi/5) with sqrt(15)) only where they cannot
    # decide and the coefficients are algebraic (a double root: two modes merging)
    enclosed = _enclosed_real_roots(P, at)
    if enclosed[2] or any(_transcendental(c) for c in P.coeffs()):
        return enclosed
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
        return [], [], True
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
    return roots, [mpmath.mpf(eps.p) / eps.q] * len(roots), decided


def _enclosed_real_roots(P: sympy.Poly, at: dict) -> tuple[list[Any], list[Any], bool]:
    """:func:`_roots_of_enclosed` of ``P``'s coefficients enclosed (``at``: the symbols'
    enclosures)."""
    return _roots_of_enclosed(_interval_coeffs(P, at))


def _roots_of_enclosed(coeffs: list[Any]) -> tuple[list[Any], list[Any], bool]:
    """The real roots of ``P`` whose coefficients are known only by their enclosures
    (a given angle of 0.3 rad puts cos(3/10) in them), and whether the count is proven.

    Every complex root is approximated (mpmath's ``polyroots`` at the working digits on
    the enclosures' midpoints); those real to half the digits are put on the real axis.
    Smith's theorem (B. T. Smith, SIAM J. Numer. Anal. 7, 1970) bounds where the roots
    lie: the discs centred at the approximations ``z_i`` of radius ``n |p(z_i)| / |a_n
    prod_(j != i) (z_i - z_j)|`` hold every root, a component of k discs exactly k.  With
    ``|p(z_i)|`` bounded over the coefficients' enclosures (interval arithmetic) the
    bound holds for the exact polynomial.  Pairwise disjoint discs each hold one root:
    one centred on the real axis holds a real root (its conjugate is in the same disc),
    one clear of the axis a root that is not real.  Discs that touch (a double root: two
    modes merging) leave the count unproven; the near roots are then kept once.
    ``coeffs``: the enclosures, highest power first."""
    n = len(coeffs) - 1
    if n <= 0:
        return [], [], True
    lead = coeffs[0]
    if lead.a <= 0 <= lead.b:
        return [], [], False  # the degree itself is not known to these digits
    mids = [mpmath.mpf(c.mid.a) for c in coeffs]
    try:
        zs = mpmath.polyroots(mids, maxsteps=ROOT_STEPS, extraprec=mpmath.mp.prec)
    except mpmath.NoConvergence:
        zs = _companion_roots(mids)
    zs = [z if isinstance(z, mpmath.mpc) else mpmath.mpc(z) for z in zs]
    half = mpmath.mpf(10) ** (-(mpmath.mp.dps // 2))
    zs = [mpmath.mpc(z.real) if abs(z.imag) <= half * max(1, abs(z)) else z for z in zs]
    low = min(abs(mpmath.mpf(lead.a)), abs(mpmath.mpf(lead.b)))
    radii = []
    for i, z in enumerate(zs):
        gaps = mpmath.mpf(1)
        for k, w in enumerate(zs):
            if k != i:
                gaps *= abs(z - w)
        if gaps == 0:
            radii.append(mpmath.inf)
            continue
        # twice the bound: room for the rounding of the product of the gaps
        radii.append(2 * n * _sup_abs_value(coeffs, z) / (low * gaps))
    # the components of overlapping discs: each holds as many roots as discs
    part = list(range(n))

    def root(i: int) -> int:
        while part[i] != i:
            i = part[i]
        return i

    for i in range(n):
        for k in range(i + 1, n):
            if abs(zs[i] - zs[k]) <= radii[i] + radii[k]:
                part[root(i)] = root(k)
    components: dict[int, list[int]] = {}
    for i in range(n):
        components.setdefault(root(i), []).append(i)
    # decided: a lone disc on the real axis (one real root), or discs all clear of it
    proven = all(
        (len(c) == 1 and zs[c[0]].imag == 0) or all(abs(zs[i].imag) > radii[i] for i in c)
        for c in components.values()
    )
    roots: list[Any] = []
    spans: list[Any] = []
    for z, r in sorted(((z.real, r) for z, r in zip(zs, radii, strict=True) if z.imag == 0)):
        if not roots or abs(z - roots[-1]) > half * max(1, abs(z)):
            roots.append(z)
            spans.append(r if proven else half)
    return roots, spans, proven


#: Durand-Kerner steps of mpmath's polyroots before the companion matrix's eigenvalues
ROOT_STEPS = 200


def _companion_roots(coeffs: list[Any]) -> list[Any]:
    """The eigenvalues of the companion matrix of the polynomial (highest first)."""
    n = len(coeffs) - 1
    M = mpmath.matrix(n, n)
    for k in range(n):
        M[0, k] = -coeffs[k + 1] / coeffs[0]
        if k + 1 < n:
            M[k + 1, k] = 1
    return list(mpmath.eig(M, left=False, right=False))


def _sup_abs_value(coeffs: list[Any], z: Any) -> Any:
    """An upper bound of |p(z)| over every polynomial whose coefficients lie in the
    enclosures ``coeffs`` (Horner on the real and imaginary parts in intervals)."""
    x, y = mpmath.iv.mpf(z.real), mpmath.iv.mpf(z.imag)
    re, im = mpmath.iv.mpf(0), mpmath.iv.mpf(0)
    for c in coeffs:
        re, im = re * x - im * y + c, re * y + im * x
    top = [max(abs(mpmath.mpf(v.a)), abs(mpmath.mpf(v.b))) for v in (re, im)]
    return mpmath.sqrt(top[0] ** 2 + top[1] ** 2)
