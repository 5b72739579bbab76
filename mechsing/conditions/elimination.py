"""Eliminating the passive joints of a linkage with its parameters kept as symbols.

A condition holds together with the closure equations; written in the input
alone it is a polynomial in the input's cosine and sine (or its slide).  The
equations of a planar linkage (:mod:`mechsing.conditions.planar`) are linear in
the cosine and sine of each body's angle, which this module exploits, one
unknown at a time:

* a slide that appears to the first power in an equation is solved from it and
  put into the others;
* an angle that appears in one equation only is dropped with it (the equation
  then fixes that angle);
* an angle that two equations hold linearly, ``a1 c + b1 s + e1 = 0`` and
  ``a2 c + b2 s + e2 = 0``, is solved (``c = Nc/D``, ``s = Ns/D`` by Cramer's
  rule), put into the other equations, and replaced by its circle relation
  ``Nc**2 + Ns**2 - D**2 = 0`` (the resultant of the three);
* otherwise, the resultants in ``t = tan(angle/2)`` of one equation with each
  other one.

After each step the equations are factored and their factors in the
parameters alone dropped (they vanish only for special dimensions), each factor
kept once.  Every step is exact; the parameters stay symbols.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import sympy

from mechsing.conditions.symbolic import JointSymbols, reduce_trig, tan_half
from mechsing.errors import EliminationTooLarge
from mechsing.numeric import CONDITION_ROOT_RTOL

#: two roots (rad or m) closer than this are one (a double root, or two factors' roots)
CONDITION_ROOT_MERGE = 1e-9

__all__ = [
    "RESULTANT_MAX_WORK",
    "angles",
    "distinct",
    "eliminate",
    "genuine",
    "groebner",
]

#: the largest resultant step attempted (an algorithm setting): an estimate of the size
#: of what it produces, the eliminant's degree in the other variables (Bezout:
#: ``deg_t f * deg g + deg_t g * deg f``) times the digits of its coefficients
#: (``deg_t g * digits f + deg_t f * digits g``).  The linkages of the suite stay below
#: 16,000; Jansen's leg (twelve-digit pivots: coefficients of 160+ digits) asks for
#: 130,000 at its output dyad, which sympy's subresultants do not finish in minutes
RESULTANT_MAX_WORK = 50_000


#: the most terms an equation of a step may hold before it is factored (an algorithm
#: setting): the suite's linkages stay below 1,100; the closure of Jansen's leg in
#: every variable but the output's reaches 5,107, whose factoring does not finish
ELIMINATION_MAX_TERMS = 3_000


def _degree_digits(f: Any, t: Any) -> tuple[int, int, int]:
    """The degree of ``f`` in ``t``, its total degree in its other symbols, and the most
    digits of a numerator or denominator of its rational coefficients."""
    others = sorted(f.free_symbols - {t}, key=str)
    P = sympy.Poly(f, t, *others)
    digits = max(
        (len(str(abs(n))) for c in P.coeffs() for n in sympy.fraction(sympy.Rational(c))),
        default=1,
    )
    rest = max((sum(m[1:]) for m in P.monoms()), default=0)
    return P.degree(t), rest, digits


def _has(e: Any, js: JointSymbols) -> bool:
    if js.c is None:
        return e.has(js.q)
    return e.has(js.c) or e.has(js.s)


def _names(js: JointSymbols) -> tuple[Any, ...]:
    return (js.q,) if js.c is None else (js.q, js.c, js.s)


def _size(e: Any) -> int:
    return len(sympy.Add.make_args(e))


def _clean(e: Any, syms: list[JointSymbols]) -> Any | None:
    """``e`` reduced on the circles, without its factors free of the variables, each
    factor once; None when nothing is left (a constant)."""
    e = reduce_trig(e, syms)
    if e == 0:
        return sympy.Integer(0)
    names: set[Any] = set()
    for js in syms:
        names |= {js.q} | ({js.c, js.s} if js.c is not None else set())
    _, factors = sympy.factor_list(e)
    kept = [f for f, _ in factors if f.free_symbols & names]
    if not kept:
        return None
    out = sympy.Integer(1)
    for f in kept:
        out *= f
    return reduce_trig(out, syms)


def _substitute(f: Any, js: JointSymbols, nc: Any, ns: Any, den: Any) -> Any:
    """``f`` with ``c = nc/den``, ``s = ns/den``, times ``den**k`` (k: f's degree)."""
    poly = sympy.Poly(f, js.c, js.s)
    k = poly.total_degree()
    out = sympy.Integer(0)
    for (i, j), coeff in poly.terms():
        out += coeff * nc**i * ns**j * den ** (k - i - j)
    return sympy.expand(out)


def _linear(e: Any, js: JointSymbols) -> tuple[Any, Any, Any] | None:
    poly = sympy.Poly(e, js.c, js.s)
    if poly.total_degree() != 1:
        return None
    a = poly.coeff_monomial(js.c)
    b = poly.coeff_monomial(js.s)
    return a, b, poly.coeff_monomial(1)


def eliminate(
    equations: list[Any], unknowns: list[JointSymbols], keep: JointSymbols
) -> list[Any] | None:
    """Polynomials in ``keep`` alone whose common zeros are the values of ``keep`` where
    ``equations`` have a (complex) solution in ``unknowns``; None when they have none for
    generic parameters; [] when every value of ``keep`` has one."""
    syms = [*unknowns, keep]
    eqs: list[Any] = []
    for e in equations:
        c = _clean(e, syms)
        if c is None:
            return None
        if c != 0:
            eqs.append(c)
    todo = list(unknowns)
    while True:
        todo = [u for u in todo if any(_has(e, u) for e in eqs)]
        if not todo:
            break
        step = _slide_step(eqs, todo) or _single_step(eqs, todo) or _pair_step(eqs, todo, keep)
        if step is None:
            step = _resultant_step(eqs, todo)
        new: list[Any] = []
        terms = max((_size(e) for e in step), default=0)
        if terms > ELIMINATION_MAX_TERMS:
            raise EliminationTooLarge(
                f"to factor an equation of {terms:,} terms (past {ELIMINATION_MAX_TERMS:,})"
            )
        for e in step:
            c = _clean(e, syms)
            if c is None:
                return None
            if c != 0 and all(sympy.expand(c - x) != 0 for x in new):
                new.append(c)
        eqs = new
    return eqs


def _slide_step(eqs: list[Any], todo: list[JointSymbols]) -> list[Any] | None:
    best = None
    for u in todo:
        if u.c is not None:
            continue
        for i, e in enumerate(eqs):
            if sympy.degree(e, u.q) == 1:
                a = sympy.expand(e.coeff(u.q, 1))
                if a.has(u.q) or a == 0:
                    continue
                if best is None or _size(e) < _size(eqs[best[1]]):
                    best = (u, i, a, sympy.expand(e - a * u.q))
    if best is None:
        return None
    u, i, a, b = best
    out = []
    for j, f in enumerate(eqs):
        if j == i:
            continue
        if not f.has(u.q):
            out.append(f)
            continue
        poly = sympy.Poly(f, u.q)
        k = poly.degree()
        out.append(sympy.expand(sum(c * (-b) ** m * a ** (k - m) for (m,), c in poly.terms())))
    return out


def _single_step(eqs: list[Any], todo: list[JointSymbols]) -> list[Any] | None:
    for u in todo:
        holding = [i for i, e in enumerate(eqs) if _has(e, u)]
        if len(holding) == 1:
            return [e for i, e in enumerate(eqs) if i != holding[0]]
    return None


def _pair_step(eqs: list[Any], todo: list[JointSymbols], keep: JointSymbols) -> list[Any] | None:
    best = None
    for u in todo:
        if u.c is None:
            continue
        lin = [(i, _linear(e, u)) for i, e in enumerate(eqs) if _has(e, u)]
        lin = [(i, x) for i, x in lin if x is not None]
        for (i, (a1, b1, e1)), (j, (a2, b2, e2)) in _pairs(lin):
            den = sympy.expand(a1 * b2 - a2 * b1)
            if den == 0:
                continue
            # a determinant free of the unknowns brings no spurious zeros: first choice
            moving = any(den.has(*_names(w)) for w in todo) or den.has(*_names(keep))
            # then an angle the other equations do not hold (nothing to substitute)
            others = sum(1 for k, e in enumerate(eqs) if k not in (i, j) and _has(e, u))
            cost = (moving, others, _size(eqs[i]) * _size(eqs[j]))
            if best is None or cost < best[0]:
                best = (cost, u, i, j, (a1, b1, e1, a2, b2, e2, den))
    if best is None:
        return None
    _, u, i, j, (a1, b1, e1, a2, b2, e2, den) = best
    nc = sympy.expand(b1 * e2 - b2 * e1)
    ns = sympy.expand(a2 * e1 - a1 * e2)
    out = [sympy.expand(nc**2 + ns**2 - den**2)]
    for k, f in enumerate(eqs):
        if k in (i, j):
            continue
        out.append(_substitute(f, u, nc, ns, den) if _has(f, u) else f)
    return out


def _pairs(items: list[Any]) -> list[tuple[Any, Any]]:
    return [(items[i], items[j]) for i in range(len(items)) for j in range(i + 1, len(items))]


def _resultant_step(eqs: list[Any], todo: list[JointSymbols]) -> list[Any]:
    u = todo[0]
    t = sympy.Dummy("t")
    holding = [e for e in eqs if _has(e, u)]
    rest = [e for e in eqs if not _has(e, u)]
    if u.c is None:
        polys = sorted(holding, key=lambda e: (sympy.degree(e, u.q), _size(e)))
        var, forms = u.q, polys
    else:
        forms = sorted((tan_half(e, u, t) for e in holding), key=lambda p: sympy.degree(p, t))
        var = t
    first = forms[0]
    a = _degree_digits(first, var)
    for f in forms[1:]:
        b = _degree_digits(f, var)
        work = (a[0] * b[1] + b[0] * a[1]) * (b[0] * a[2] + a[0] * b[2])
        if work > RESULTANT_MAX_WORK:
            raise EliminationTooLarge(
                f"a resultant of estimated size {work:,} (past {RESULTANT_MAX_WORK:,}: "
                "estimated degree times coefficient digits)"
            )
    out = []
    for f in forms[1:]:
        res = sympy.expand(sympy.resultant(first, f, var))
        if u.c is not None:
            res = _without_isotropic(res, first, f, t)
        out.append(res)
    return rest + out


def _without_isotropic(res: Any, p: Any, q: Any, t: Any) -> Any:
    """``res`` without the factors where ``p`` and ``q`` share the root ``t = i`` (the
    circle's points at infinity, ``c = oo``): zeros of the resultant no real angle has."""
    if res == 0:
        return res
    norms = [_norm_at_i(f, t) for f in (p, q)]
    const, factors = sympy.factor_list(res)
    out = sympy.Integer(1)
    for g, e in factors:
        spurious = g.free_symbols and all(
            n != 0 and sympy.div(n, g, *sorted(n.free_symbols | g.free_symbols, key=str))[1] == 0
            for n in norms
        )
        if not spurious:
            out *= g**e
    return sympy.expand(out)


def _norm_at_i(f: Any, t: Any) -> Any:
    """``|f(i)|**2`` for a polynomial in ``t`` with real coefficients: with
    ``f(i) = sum a_k i**k``, its real part takes the even powers (sign ``(-1)**(k/2)``),
    its imaginary part the odd ones."""
    re, im = sympy.Integer(0), sympy.Integer(0)
    for (k,), a in sympy.Poly(f, t).terms():
        if k % 2 == 0:
            re += (-1) ** (k // 2) * a
        else:
            im += (-1) ** (k // 2) * a
    return sympy.expand(re**2 + im**2)


def groebner(equations: list[Any], gens: list[Any], order: str) -> Any:
    """:func:`sympy.groebner` of ``equations`` in ``gens``; where their coefficients are
    numbers with square roots (``sqrt(15)`` of a drawn pivot) and nothing else but
    ``gens``, computed over the number field of those roots (``QQ<sqrt(15)>``) rather
    than sympy's expression domain, whose every step simplifies.  The reduced basis is
    unique, so it is the same one (the double rocker's closure: 0.6 s against 4 s)."""
    plain = set(gens)
    irrational = any(
        a.is_number and not a.is_Rational
        for e in equations
        for a in sympy.sympify(e).atoms(sympy.Pow)
    )
    if irrational and all(sympy.sympify(e).free_symbols <= plain for e in equations):
        try:
            return sympy.groebner(equations, *gens, order=order, extension=True)
        except (sympy.polys.polyerrors.PolynomialError, NotImplementedError):  # pragma: no cover
            pass
    return sympy.groebner(equations, *gens, order=order)


def genuine(
    factors: list[Any],
    equations: list[Any],
    unknowns: list[JointSymbols],
    keep: JointSymbols,
    values: dict[Any, Any],
) -> list[bool]:
    """Which of ``factors`` (polynomials in ``keep`` and the parameters) have a zero
    where ``equations`` have a (complex) solution, with the parameters at ``values``: the
    resultants above can bring extra factors (where a Cramer determinant vanishes), which
    have none.  For each factor, the equations, the circles and the factor have a common
    zero unless their exact Groebner basis is [1] (Hilbert's Nullstellensatz); with the
    factor added the system has finitely many solutions, whose degree-ordered basis is
    quick (no elimination order needed)."""
    num = [sympy.expand(sympy.sympify(e).xreplace(values)) for e in equations]
    circles = [js.s**2 + js.c**2 - 1 for js in [*unknowns, keep] if js.c is not None]
    gens: list[Any] = []
    for js in [*unknowns, keep]:
        gens += [js.s, js.c] if js.c is not None else [js.q]
    out = []
    for f in factors:
        h = sympy.expand(sympy.sympify(f).xreplace(values))
        if not h.free_symbols:
            out.append(h == 0)
            continue
        G = groebner([*num, *circles, h], gens, "grevlex")
        out.append(G.exprs != [1])
    return out


def angles(g: Any, js: JointSymbols) -> list[float]:
    """Real values of a joint where a polynomial in its ``c``, ``s`` (or ``q``) vanishes."""
    if js.c is None:
        coeffs = [float(sympy.N(c, 30)) for c in sympy.Poly(g, js.q).all_coeffs()]
        return sorted(
            r.real for r in np.roots(coeffs) if abs(r.imag) < CONDITION_ROOT_RTOL * max(1.0, abs(r))
        )
    t = sympy.Dummy("t")
    k = int(sympy.Poly(g, js.c, js.s).total_degree())
    N = tan_half(g, js, t, k)
    if N == 0:
        return []
    coeffs = [float(sympy.N(c, 30)) for c in sympy.Poly(N, t).all_coeffs()]
    out = []
    if len(coeffs) - 1 < 2 * k:
        out.append(math.pi)
    for r in np.roots(coeffs) if len(coeffs) > 1 else []:
        if abs(r.imag) < CONDITION_ROOT_RTOL * max(1.0, abs(r)):
            out.append(2 * math.atan(r.real))
    return distinct(out)


def distinct(values: list[float]) -> list[float]:
    """Sorted values, each once (roots of different factors may meet)."""
    distinct: list[float] = []
    for a in sorted(values):
        if not distinct or abs(a - distinct[-1]) > CONDITION_ROOT_MERGE:
            distinct.append(a)
    return distinct
