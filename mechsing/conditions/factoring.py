"""Factoring trigonometric polynomials of joint angles.

A condition is first a polynomial in ``c_J = cos(J)``, ``s_J = sin(J)`` (and
the values of prismatic joints and symbolic parameters).  Such polynomials
live on the torus ``c_J**2 + s_J**2 = 1``, where ordinary polynomial
factoring misses factors (``(d4*c3 - a3*s3)*(a2*c2 + a3*c23 - d4*s23)``
no longer factors once ``s3**2`` is replaced by ``1 - c3**2``).  So this
module takes each revolute joint in turn to its half-angle variable
``t = tan(J/2)`` (``c = (1-t**2)/(1+t**2)``, ``s = 2t/(1+t**2)``), where
factoring is complete, splits off the factors in that joint alone (written
back as ``a*cos(J) + b*sin(J) + e``, a root at ``t = oo`` being ``J = pi``),
and factors what is left as a polynomial.  Every step is exact.

Public: :func:`factor_condition` -> (constant, [(factor, power), ...]) with
factors polynomials in the ``c``, ``s`` symbols.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import sympy
from sympy.polys.domains import QQ
from sympy.polys.orderings import lex
from sympy.polys.rings import PolyRing

from mechsing.conditions.symbolic import JointSymbols, reduce_trig, tan_half

__all__ = ["factor_condition", "to_circle"]


def _cs_degree(expr: Any, js: JointSymbols) -> int:
    if not (expr.has(js.c) or expr.has(js.s)):
        return 0
    return int(sympy.Poly(expr, js.c, js.s).total_degree())


def to_circle(P: Any, t: Any, k: int, js: JointSymbols) -> Any:
    """``P(t) / (1 + t**2)**k`` with ``t = tan(J/2)`` written in ``c``, ``s`` (exact;
    needs ``deg P <= 2k``)."""
    poly = sympy.Poly(sympy.expand(P), t)
    out = sympy.Integer(0)
    for (j,), coeff in poly.terms():
        out += coeff * js.s ** (j % 2) * (1 - js.c) ** (j // 2) * (1 + js.c) ** (k - (j + 1) // 2)
    return sympy.expand(out / 2**k)


def _split_joint(
    expr: Any, js: JointSymbols, params: set[Any]
) -> tuple[list[tuple[Any, int]], Any]:
    """Factors of ``expr`` in joint ``js`` alone (with their powers) and the cofactor.

    Computed in a polynomial ring over the rationals (:func:`_split_in_ring`); where that
    ring cannot hold ``expr`` or the factors, in sympy's expressions
    (:func:`_split_in_expressions`), which give the same answer more slowly."""
    if not (expr.has(js.c) or expr.has(js.s)) or expr.has(js.q):
        return [], expr
    try:
        return _split_in_ring(expr, js, params)
    except _NotInRing:
        return _split_in_expressions(expr, js, params)


class _NotInRing(Exception):
    """``expr`` or one of its factors is not a polynomial of the ring (a power of a
    number that is not one of its generators ...)."""


def _ring_of(expr: Any, js: JointSymbols, t: Any) -> tuple[Any, Any]:
    """``QQ[gens, c, s, t]`` with ``gens`` the generators sympy takes for ``expr`` (its
    symbols, and numbers like ``sqrt(3)``, as :func:`sympy.factor_list` takes them), and
    ``expr`` in it."""
    try:
        P = sympy.Poly(expr)
    except sympy.PolynomialError as exc:  # pragma: no cover - not a polynomial
        raise _NotInRing from exc
    gens = list(P.gens)
    if not (P.domain.is_ZZ or P.domain.is_QQ) or any(
        g not in (js.c, js.s) and g.has(js.c, js.s, js.q) for g in gens
    ):
        raise _NotInRing
    extra = [x for x in (js.c, js.s) if x not in gens]
    R = PolyRing((*gens, *extra, t), QQ, lex)
    pad = (0,) * (len(extra) + 1)
    return R, R.from_dict({m + pad: c for m, c in P.rep.to_dict().items()}, P.domain)


def _in_ring(R: Any, f: Any) -> Any:
    try:
        return R.from_expr(f)
    except (ValueError, sympy.polys.polyerrors.CoercionFailed) as exc:
        raise _NotInRing from exc


def _tan_half_ring(E: Any, ic: int, is_: int, it: int, k: int) -> Any:
    """:func:`.symbolic.tan_half` of a ring element: ``E(c, s) * (1 + t**2)**k`` with
    ``c = (1 - t**2)/(1 + t**2)``, ``s = 2 t/(1 + t**2)``."""
    R = E.ring
    groups: dict[tuple[int, int], dict[tuple[int, ...], Any]] = {}
    for m, coeff in E.terms():
        mm = list(m)
        mm[ic] = mm[is_] = 0
        groups.setdefault((m[ic], m[is_]), {})[tuple(mm)] = coeff
    T = R.gens[it]
    bases = (1 - T**2, 2 * T, 1 + T**2)
    powers: dict[tuple[int, int], Any] = {}

    def power(which: int, n: int) -> Any:
        if (which, n) not in powers:
            powers[(which, n)] = bases[which] ** n
        return powers[(which, n)]

    out = R.zero
    for (i, j), d in groups.items():
        out += R.from_dict(d) * power(0, i) * power(1, j) * power(2, k - i - j)
    return out


def _circle_ring(P: Any, ic: int, is_: int, it: int, k: int) -> Any:
    """:func:`to_circle` of a ring element: ``P(t) / (1 + t**2)**k`` in ``c``, ``s``."""
    R = P.ring
    c, s = R.gens[ic], R.gens[is_]
    groups: dict[int, dict[tuple[int, ...], Any]] = {}
    for m, coeff in P.terms():
        mm = list(m)
        mm[it] = 0
        groups.setdefault(m[it], {})[tuple(mm)] = coeff
    out = R.zero
    for j, d in groups.items():
        out += R.from_dict(d) * s ** (j % 2) * (1 - c) ** (j // 2) * (1 + c) ** (k - (j + 1) // 2)
    return sympy.expand((out * QQ(1, 2**k)).as_expr())


def _content_factors(N: Any, it: int, params: set[Any]) -> list[tuple[Any, int]] | None:
    """The factors of ``N`` in ``t`` (and the parameters and numbers) alone, from the
    content of ``N`` as a polynomial in its other variables (Gauss's lemma: the factors
    of a polynomial free of some variables are those of its content in them); None when
    there are two or more, whose order only factoring ``N`` itself gives."""
    R = N.ring
    others = [
        i
        for i, g in enumerate(R.symbols)
        if i != it and g.free_symbols and not g.free_symbols <= params
    ]
    groups: dict[tuple[int, ...], dict[tuple[int, ...], Any]] = {}
    for m, coeff in N.terms():
        mm = list(m)
        for i in others:
            mm[i] = 0
        groups.setdefault(tuple(m[i] for i in others), {})[tuple(mm)] = coeff
    coeffs = [R.from_dict(d) for d in groups.values()]
    if any(f.degree(it) <= 0 for f in coeffs):
        return []
    content = coeffs[0]
    for f in sorted(coeffs[1:], key=len):
        content = content.gcd(f)
        if content.degree(it) <= 0:
            return []
    t = R.symbols[it]
    _, factors = sympy.factor_list(content.as_expr())
    alone = [(f, e) for f, e in factors if f.has(t)]
    return alone if len(alone) < 2 else None


def _split_in_ring(
    expr: Any, js: JointSymbols, params: set[Any]
) -> tuple[list[tuple[Any, int]], Any]:
    t = sympy.Dummy("t")
    R, E = _ring_of(expr, js, t)
    ic, is_, it = R.symbols.index(js.c), R.symbols.index(js.s), len(R.symbols) - 1
    k = max(m[ic] + m[is_] for m in E.monoms())
    N = _tan_half_ring(E, ic, is_, it, k)
    if not N:
        return [], expr
    alone = _content_factors(N, it, params)
    if alone is None:
        _, factors = sympy.factor_list(sympy.expand(N.as_expr()))
        alone = [(f, e) for f, e in factors if f.has(t) and f.free_symbols <= {t} | params]

    def divide(rest: Any, f: Any) -> Any:
        try:
            return rest.exquo(f)
        except sympy.polys.polyerrors.ExactQuotientFailed as exc:  # pragma: no cover
            raise _NotInRing from exc

    return _peel(
        expr,
        js,
        k,
        N,
        2 * k - N.degree(it),
        _by_degree(alone, t),
        convert=lambda f: _in_ring(R, f),
        divide=divide,
        circle=lambda P, kk: _circle_ring(P, ic, is_, it, kk),
        halve=lambda P: P * QQ(1, 2),
    )


def _split_in_expressions(
    expr: Any, js: JointSymbols, params: set[Any]
) -> tuple[list[tuple[Any, int]], Any]:
    k = _cs_degree(expr, js)
    if k == 0 or expr.has(js.q):
        return [], expr
    t = sympy.Dummy("t")
    N = tan_half(expr, js, t, k)
    if N == 0:
        return [], expr
    _, factors = sympy.factor_list(N)
    alone = [(f, e) for f, e in factors if f.has(t) and f.free_symbols <= {t} | params]
    return _peel(
        expr,
        js,
        k,
        N,
        2 * k - int(sympy.degree(N, t)),
        _by_degree(alone, t),
        convert=lambda f: f,
        divide=lambda rest, f: sympy.quo(rest, f, t),
        circle=lambda P, kk: to_circle(P, t, kk, js),
        halve=lambda P: P / 2,
    )


def _by_degree(alone: list[tuple[Any, int]], t: Any) -> list[tuple[Any, int, int]]:
    """The factors in ``t`` alone with their degrees in ``t``."""
    return [(f, e, int(sympy.degree(f, t))) for f, e in alone]


def _divides(g: Any, expr: Any) -> bool:
    """Whether ``g`` divides ``expr`` as polynomials (not only on the circle)."""
    gens = sorted(sympy.sympify(expr).free_symbols | sympy.sympify(g).free_symbols, key=str)
    return bool(sympy.div(sympy.Poly(expr, *gens), sympy.Poly(g, *gens))[1].is_zero)


def _peel(
    expr: Any,
    js: JointSymbols,
    k: int,
    N: Any,
    deficit: int,
    alone: list[tuple[Any, int, int]],
    *,
    convert: Callable[[Any], Any],
    divide: Callable[[Any, Any], Any],
    circle: Callable[[Any, int], Any],
    halve: Callable[[Any], Any],
) -> tuple[list[tuple[Any, int]], Any]:
    """The factors of joint ``js`` alone, taken from ``N(t) = expr * (1 + t**2)**k``.

    ``alone`` are the factors of ``N`` in ``t`` alone (factor, power, degree in ``t``);
    ``deficit = 2k - deg N`` counts the roots at ``t = oo`` (``J = pi``).  A factor of
    degree 2 is ``a*cos(J) + b*sin(J) + e``; one of degree 1 is such a factor with a root
    at infinity (one of the deficit), or, where none is left, with the next factor of
    degree 1 (``a**2 + b**2 - e**2`` a square: the quadratic's roots are rational), where
    the pair is not already a factor of ``expr`` as a polynomial (whose factoring then
    finds it, in its order); two roots left at infinity are the factor ``1 + cos(J)``.  ``convert``, ``divide``, ``circle`` (back to
    ``c``, ``s`` over ``(1 + t**2)**kk``) and ``halve`` are the operations of the domain
    ``N`` lives in: one polynomial ring over the rationals, or sympy's expressions."""
    if not alone and deficit < 2:
        return [], expr
    found: list[tuple[Any, int]] = []
    rest = N
    used = 0
    waiting: list[list[Any]] = []  # factors of degree 1 with no root at infinity left
    for f, e, d in alone:
        if d > 2:
            continue
        fd = convert(f)
        for n in range(e):
            if d == 1 and deficit < 1:
                waiting.append([fd, e - n])
                break
            deficit -= d == 1
            rest = divide(rest, fd)
            used += 1
            found.append((circle(fd, 1), 1))
    # two real roots in t: (3t + 1)(t - 3) is 3*cos(J) + 4*sin(J); distinct factors are
    # paired first ((3t + 1)**2 (t - 3)**2 is (3*cos(J) + 4*sin(J))**2)
    turns = []
    while any(w[1] for w in waiting):
        for w in waiting:
            if w[1]:
                turns.append(w[0])
                w[1] -= 1
    for first, second in zip(turns[0::2], turns[1::2], strict=False):
        factor = circle(first * second, 1)
        if _divides(factor, expr):
            continue  # a factor of the polynomial itself: its factoring finds it, in order
        rest = divide(rest, first * second)
        used += 1
        found.append((factor, 1))
    while deficit >= 2 and used < k:  # a double root at J = pi: the factor 1 + cos(J)
        deficit -= 2
        used += 1
        found.append((1 + js.c, 1))
        rest = halve(rest)
    if not found:
        return [], expr
    return found, circle(rest, k - used)


def factor_condition(
    expr: Any, joints: list[JointSymbols], params: set[Any]
) -> tuple[Any, list[tuple[Any, int]]]:
    """Exact factors of a condition: ``expr == constant * prod(f**e)`` on the torus.

    ``params`` are the free symbols that are not joint symbols (symbolic
    parameters).  Factors are primitive polynomials in the ``c``, ``s``
    symbols with a positive leading coefficient; equal factors are merged.
    A radical of parameters (the length ``sqrt(d**2 + r**2)`` by which an axis
    written with symbolic parameters is normalised) is factored as a positive
    symbol of its own, a function of parameters (``cos(phi)``) as a symbol of its
    own (:func:`_radicals`); both are written back in the results.
    """
    expr, back = _radicals(expr, joints)
    if not back:
        return _factor(expr, joints, params)
    # a radical in a denominator is a positive factor: the numerator holds the condition
    num, den = sympy.fraction(sympy.together(sympy.expand(expr)))
    const, factors = _factor(num, joints, params | set(back))
    const = (sympy.sympify(const) / den).xreplace(back)
    if const.has(sympy.sin, sympy.cos):  # sqrt(cos(phi)**2 + sin(phi)**2) is 1
        const = sympy.trigsimp(const)
    return const, [(sympy.sympify(f).xreplace(back), p) for f, p in factors]


def _radicals(expr: Any, joints: list[JointSymbols]) -> tuple[Any, dict[Any, Any]]:
    """``expr`` with every radical of symbolic parameters (``b**(p/q)``, ``b`` free of the
    joint symbols) replaced by ``rho**p``, ``rho`` a positive symbol standing for
    ``b**(1/q)``, and the map back.  The principal root of the parameters' (real,
    positive) data is positive, so a factor of ``rho`` alone never vanishes: it goes to
    the constant as a positive factor, and the rest is a polynomial again."""
    variables = {x for js in joints for x in (js.c, js.s, js.q) if x is not None}
    roots: dict[tuple[Any, int], Any] = {}
    back: dict[Any, Any] = {}
    sub: dict[Any, Any] = {}
    expr = sympy.sympify(expr)
    # a function of parameters alone (cos(phi) of an axis [cos(phi), sin(phi), 0]) is a
    # number of its own to the factoring: a real symbol, written back afterwards
    for i, f in enumerate(sorted(expr.atoms(sympy.Function), key=str)):
        if f.free_symbols and not f.free_symbols & variables:
            value = sympy.Dummy(f"value{i}", real=True)
            back[value] = f
            sub[f] = value
    functions = dict(back)
    if sub:
        expr = expr.xreplace(sub)
        sub = {}
    for a in expr.atoms(sympy.Pow):
        b, ex = a.args
        if not ex.is_Rational or ex.is_Integer or not b.free_symbols or b.free_symbols & variables:
            continue
        key = (b, int(ex.q))
        if key not in roots:
            rho = sympy.Dummy(f"root{len(roots)}", positive=True)
            roots[key] = rho
            back[rho] = (b ** sympy.Rational(1, ex.q)).xreplace(functions)
        sub[a] = roots[key] ** int(ex.p)
    return (expr.xreplace(sub) if sub else expr), back


def _factor(
    expr: Any, joints: list[JointSymbols], params: set[Any]
) -> tuple[Any, list[tuple[Any, int]]]:
    e = reduce_trig(sympy.expand(expr), joints)
    if e == 0:
        return sympy.Integer(0), []
    pieces: list[tuple[Any, int]] = []
    for js in joints:
        if js.c is None:
            continue
        found, e = _split_joint(e, js, params)
        pieces.extend(found)
        e = reduce_trig(e, joints)
    _, rest = sympy.factor_list(e)
    merged: dict[Any, int] = {}
    for f, p in pieces + list(rest):
        for g, q in sympy.factor_list(reduce_trig(f, joints))[1]:
            g = reduce_trig(g, joints)
            if not g.free_symbols - params:
                continue  # constants (and parameter-only factors) go to the constant
            gens = sorted(g.free_symbols, key=str)
            _, prim = sympy.Poly(g, *gens).primitive()
            prim_e = prim.as_expr()
            if sympy.Poly(prim_e, *gens).LC().could_extract_minus_sign():
                prim_e = -prim_e
            merged[prim_e] = merged.get(prim_e, 0) + p * q
    factors = list(merged.items())
    const = _constant(expr, factors, joints)
    if const is None:  # pragma: no cover - the factoring did not reproduce expr
        return sympy.Integer(1), [(e, 1)]
    return const, factors


def _constant(expr: Any, factors: list[tuple[Any, int]], joints: list[JointSymbols]) -> Any:
    """``expr / prod(f**e)``, checked to be the same at two points of the torus."""
    values = []
    for u in (sympy.Rational(2, 7), sympy.Rational(5, 11)):
        pt: dict[Any, Any] = {}
        for i, js in enumerate(joints):
            w = u + sympy.Rational(i, 13)
            if js.c is not None:
                pt[js.c] = (1 - w**2) / (1 + w**2)
                pt[js.s] = 2 * w / (1 + w**2)
            pt[js.q] = w
        den = sympy.Integer(1)
        for f, p in factors:
            den *= sympy.sympify(f).xreplace(pt) ** p
        if den == 0:
            return None
        values.append(sympy.factor(sympy.cancel(sympy.sympify(expr).xreplace(pt) / den)))
    if sympy.cancel(values[0] - values[1]) != 0:
        return None
    return values[0]
