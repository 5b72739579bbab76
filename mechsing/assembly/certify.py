"""Certification of one solution: the Krawczyk test in mpmath interval arithmetic.

For a square system ``f(z) = 0`` (sympy expressions with algebraic coefficients, which
may hold ``sin`` and ``cos``), an approximate root ``m`` and the box ``Z = m + [-r, r]^n``:
with ``Y`` an approximate inverse of ``f'(m)``, ``K = m - Y f(m) + (I - Y f'(Z))(Z - m)``.
``K`` strictly inside ``Z`` proves that ``Z`` holds exactly one root of ``f``
(R. Krawczyk, Computing 4, 1969; R. E. Moore, Computing 19, 1977).  Constants are
enclosed at the working precision plus guard digits, so the proof holds for the exact
coefficients.

Owns :func:`krawczyk` (on an :class:`IntervalSystem`, by :func:`krawczyk_box`, whose
dispatch table ``"krawczyk test"`` holds the double-precision contraction bound of
:mod:`mechsing.assembly.contraction`; :func:`krawczyk_complex`, the same test on the
real and imaginary parts of a complex root; :func:`certified_roots`, every endpoint of a
solve refined and so certified; :func:`apart`, their boxes disjoint), :func:`newton`
(the refinement whose result it certifies; its first steps in double precision by the
table ``"newton start"``, the steps at the working digits by one double inverse of the
Jacobian where the table ``"newton steps"`` finds it well-conditioned), :func:`poly_terms` and :func:`polynomial_rows` (a
polynomial's terms without sympy's coefficient domains, and polynomials evaluated from
them in numpy) and :func:`singular_root` (a root no interval test can certify: a
multiple root, polished, or a point of a curve of solutions, found by a local dimension
test).
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from typing import Any

import mpmath
import numpy as np
import sympy

from mechsing.assembly import contraction as _contraction  # noqa: F401 (its dispatch form)
from mechsing.assembly.settings import (
    MODE_CERTIFY_RADIUS,
    MODE_CLOSURE_DIGITS,
    MODE_CURVE_STEP,
    MODE_ENDPOINT_SINGULAR_RTOL,
    MODE_SINGULAR_DIGITS,
)
from mechsing.numeric import dispatch

__all__ = [
    "IntervalSystem",
    "interval_function",
    "krawczyk",
    "apart",
    "certified_roots",
    "conditioning",
    "krawczyk_box",
    "krawczyk_complex",
    "local_dimension",
    "misses",
    "newton",
    "poly_terms",
    "polynomial_rows",
    "regular",
    "singular_root",
]


def interval_function(exprs: Sequence[sympy.Expr], gens: Sequence[sympy.Symbol]) -> Any:
    """The expressions as one function of intervals for ``gens`` (a list in, a list of
    intervals out); every constant that is not rational enclosed at the working digits
    (sympy's value padded by 10^-(digits - 5) relative)."""
    consts: dict[sympy.Symbol, Any] = {}
    pad = mpmath.mpf(10) ** (-(mpmath.mp.dps - 5))

    def constant(c: sympy.Expr) -> sympy.Symbol:
        sym = sympy.Symbol(f"k{len(consts)}")
        v = mpmath.mpf(sympy.N(c, mpmath.mp.dps + 10))
        consts[sym] = mpmath.iv.mpf([v - pad * (1 + abs(v)), v + pad * (1 + abs(v))])
        return sym

    def replace(e: sympy.Expr) -> sympy.Expr:
        if e.is_Rational or e.is_Symbol:
            return e
        if e.is_number:
            return constant(e)
        return e.func(*(replace(a) for a in e.args))

    fixed = [replace(sympy.expand(e)) for e in exprs]
    args = [*gens, *consts]
    module = {
        "sin": mpmath.iv.sin,
        "cos": mpmath.iv.cos,
        "sqrt": mpmath.iv.sqrt,
        "mpf": mpmath.iv.mpf,
    }
    fn = sympy.lambdify(args, fixed, modules=[module, "mpmath"])
    values = list(consts.values())

    def call(z: Sequence[Any]) -> list[Any]:
        return [mpmath.iv.mpf(0) + v for v in fn(*z, *values)]

    return call


def krawczyk(
    exprs: Sequence[sympy.Expr], gens: Sequence[sympy.Symbol], m: Sequence[Any], radius: Any
) -> bool:
    """True when the box ``m +- radius`` provably holds exactly one root of ``exprs``
    (the current mpmath precision; the interval context is set to the same)."""
    n = len(gens)
    if len(exprs) != n:
        raise ValueError(
            f"krawczyk takes a square system, not {len(exprs)} equations in {n} unknowns"
        )
    before = mpmath.iv.dps
    mpmath.iv.dps = mpmath.mp.dps
    try:
        return krawczyk_box(_interval_system(tuple(exprs), tuple(gens), mpmath.mp.dps), m, radius)
    finally:
        mpmath.iv.dps = before


class IntervalSystem:
    """A square system for the Krawczyk test: ``f`` and ``J``, the system and its
    Jacobian (row by row) as interval functions (each built on first use), ``arrays``,
    the Jacobian's terms as :class:`~mechsing.assembly.contraction.TermArrays` (None
    where the system is not given by its terms), and ``point``: the system at a point
    of the working digits (mpmath numbers) with its terms as
    :class:`~mechsing.assembly.contraction.TermArrays`, to bound that evaluation's error
    (built on first use; None where the system is not given by its terms)."""

    def __init__(self, make: Any, jacobian: Any, arrays: Any = None, point: Any = None) -> None:
        self._make = (make, jacobian, point)
        self._built: dict[int, Any] = {}
        self.arrays = arrays

    def _get(self, i: int) -> Any:
        if i not in self._built:
            self._built[i] = self._make[i]()
        return self._built[i]

    @property
    def f(self) -> Any:
        return self._get(0)

    @property
    def J(self) -> Any:
        return self._get(1)

    @property
    def point(self) -> tuple[Any, Any] | None:
        return None if self._make[2] is None else self._get(2)


#: the Krawczyk test's fast forms (:mod:`mechsing.assembly.contraction`)
_KRAWCZYK = dispatch.table("krawczyk test", "mechsing.assembly.certify.krawczyk_box")


def krawczyk_box(system: IntervalSystem, m: Sequence[Any], radius: Any) -> bool:
    """The Krawczyk test of ``system`` in the box ``m +- radius`` (the interval context's
    digits set): the table's fast form where it proves the box (it answers True or
    None), else every operation in interval arithmetic."""
    form = _KRAWCZYK.pick(system, m, radius)
    if form is not None and form(system, m, radius):
        return True
    f, J = system.f, system.J
    n = len(m)
    # Y: the inverse of the Jacobian at the midpoint (floating, any approximation works)
    jm = J([mpmath.iv.mpf(x) for x in m])
    Jmid = mpmath.matrix(n, n)
    for i in range(n):
        for k in range(n):
            Jmid[i, k] = jm[i * n + k].mid
    try:
        Yinv = mpmath.inverse(Jmid)
    except ZeroDivisionError:
        return False
    Z = [mpmath.iv.mpf([x - radius, x + radius]) for x in m]
    fm = f([mpmath.iv.mpf(x) for x in m])
    jz = J(Z)
    for i in range(n):
        acc = mpmath.iv.mpf(m[i])
        for k in range(n):
            acc -= mpmath.iv.mpf(Yinv[i, k]) * fm[k]
        for k in range(n):
            coeff = mpmath.iv.mpf(1 if i == k else 0)
            for l in range(n):
                coeff -= mpmath.iv.mpf(Yinv[i, l]) * jz[l * n + k]
            acc += coeff * (Z[k] - mpmath.iv.mpf(m[k]))
        if not (acc.a > Z[i].a and acc.b < Z[i].b):
            return False
    return True


@functools.lru_cache(maxsize=8)
def _interval_system(
    exprs: tuple[sympy.Expr, ...], gens: tuple[sympy.Symbol, ...], dps: int
) -> IntervalSystem:
    """The system and its Jacobian as interval functions (built once per system and
    working digits: every root of one solve is certified with the same)."""
    terms = _terms(exprs, gens)
    if terms is not None:
        return _interval_terms(terms, len(gens))
    return IntervalSystem(
        lambda: interval_function(exprs, gens),
        lambda: interval_function(_jacobian(exprs, gens), gens),
    )


def poly_terms(e: sympy.Expr, gens: Sequence[sympy.Symbol]) -> list[tuple[tuple[int, ...], Any]]:
    """The terms of ``e`` as a polynomial in ``gens`` (exponents, coefficient; the
    monomials in decreasing lexicographic order, as ``sympy.Poly(e, *gens).terms()``
    lists them) with the coefficients as they stand: no coefficient domain is built
    (a Float coefficient made sympy build a real field, and with it a new mpmath
    context, for every polynomial: most of a small system's build).  Raises
    ``sympy.PolynomialError`` where ``e`` is not a polynomial in ``gens``."""
    from sympy.polys.polyutils import dict_from_expr

    terms, _ = dict_from_expr(sympy.sympify(e), gens=tuple(gens))
    out = sorted(((m, c) for m, c in terms.items() if c != 0), reverse=True)
    return out or [((0,) * len(gens), sympy.Integer(0))]


@functools.lru_cache(maxsize=16)
def _terms(
    exprs: Sequence[sympy.Expr], gens: Sequence[sympy.Symbol]
) -> list[dict[tuple[int, ...], Any]] | None:
    """Each expression's terms (exponents: coefficient) where every one is a polynomial
    in ``gens`` with real numbers for coefficients; else None."""
    try:
        out = [dict(poly_terms(e, gens)) for e in exprs]
    except sympy.PolynomialError:
        return None
    if not gens or not all(c.is_number and c.is_extended_real for t in out for c in t.values()):
        return None
    return out


def polynomial_rows(rows: Sequence[Sequence[sympy.Expr]], gens: Sequence[sympy.Symbol]) -> Any:
    """A function of the values of ``gens`` (numpy numbers, float or complex) giving each
    row of polynomials at them: from their terms where each is a polynomial with real
    coefficients (no code generated), else by lambdify."""
    from mechsing.assembly.contraction import TermArrays

    arrays = []
    for row in rows:
        terms = _terms(tuple(row), tuple(gens))
        if terms is None:
            return sympy.lambdify(gens, [list(r) for r in rows], "numpy")
        arrays.append(TermArrays(terms, len(gens)))
    return lambda *z: [a.values(np.asarray(z)) for a in arrays]


def _interval_terms(terms: list[dict[tuple[int, ...], Any]], n: int) -> IntervalSystem:
    """The polynomials of ``terms`` and their Jacobian as interval functions, evaluated term
    by term (no code generated: printing a Jacobian for lambdify, and sympy's polynomials
    and back, were most of a small system's certificate); the coefficients enclosed as
    :func:`interval_function` encloses them."""
    from mechsing.assembly.contraction import TermArrays

    iv = mpmath.iv
    dps = mpmath.mp.dps
    pad = mpmath.mpf(10) ** (-(dps - 5))

    def enclose(c: Any) -> Any:
        if c.is_Rational:
            return iv.mpf(int(c.p)) / iv.mpf(int(c.q))
        v = _mp_coefficient(c, dps + 10)
        return iv.mpf([v - pad * (1 + abs(v)), v + pad * (1 + abs(v))])

    def rows(t: Any) -> Any:
        with mpmath.workdps(dps):
            return _term_rows(t, enclose, iv.mpf(0))

    def point() -> tuple[Any, Any]:
        with mpmath.workdps(dps + 10):
            return _term_rows(terms, lambda c: _mp_coefficient(c, dps + 10)), arrays

    arrays = TermArrays(terms, n, float(pad))
    return IntervalSystem(
        lambda: rows(terms), lambda: rows(_derivatives(terms, n)), arrays.jacobian(), point
    )


def _derivatives(
    terms: list[dict[tuple[int, ...], Any]], n: int
) -> list[dict[tuple[int, ...], Any]]:
    """The Jacobian's entries row by row, as terms."""
    out = []
    for t in terms:
        for k in range(n):
            d: dict[tuple[int, ...], Any] = {}
            for m, c in t.items():
                if m[k]:
                    dm = (*m[:k], m[k] - 1, *m[k + 1 :])
                    d[dm] = d.get(dm, 0) + c * m[k]
            out.append(d)
    return out


def _term_rows(terms: list[dict[tuple[int, ...], Any]], number: Any, zero: Any = 0) -> Any:
    """A function of a list of values: each polynomial of ``terms`` at them, summed term
    by term (``number``: a coefficient as the arithmetic's number), each power once."""
    rows = [
        [(number(c), [(k, e) for k, e in enumerate(m) if e]) for m, c in t.items()] for t in terms
    ]

    def call(z: Sequence[Any]) -> list[Any]:
        powers: dict[tuple[int, int], Any] = {}
        out = []
        for row in rows:
            acc = zero
            for c, mono in row:
                for k, e in mono:
                    if (k, e) not in powers:
                        powers[k, e] = z[k] ** e
                    c = c * powers[k, e]
                acc += c
            out.append(acc)
        return out

    return call


def _jacobian(exprs: Sequence[sympy.Expr], gens: Sequence[sympy.Symbol]) -> list[sympy.Expr]:
    """The Jacobian's entries row by row: a polynomial's derivatives as polynomials
    (sympy.diff on an expanded sum of hundreds of terms asks each term's assumptions: most
    of a system's build), any other expression's by sympy.diff."""
    out = []
    for e in exprs:
        try:
            p = sympy.Poly(e, *gens)
        except sympy.PolynomialError:  # not polynomial in gens (a sin or cos of one)
            out += [sympy.diff(e, g) for g in gens]
            continue
        out += [p.diff(g).as_expr() for g in gens]
    return out


def _mp_coefficient(c: Any, dps: int) -> Any:
    """A polynomial's real coefficient (a sympy number) as an mpmath number to ``dps``
    digits (the caller's working digits hold them): a float and a rational directly,
    anything else (an algebraic number written as an expression) by sympy's ``N``."""
    if isinstance(c, sympy.Float):
        return mpmath.mpf(c._mpf_)
    if isinstance(c, sympy.Rational):
        return mpmath.mpf(int(c.p)) / int(c.q)
    return mpmath.mpf(sympy.N(c, dps))


def _number(v: Any) -> Any:
    """An mpmath number of a start value (float, complex or mpmath)."""
    if isinstance(v, (mpmath.mpf, mpmath.mpc)):
        return v
    if isinstance(v, complex) and v.imag != 0:
        return mpmath.mpc(v)
    return mpmath.mpf(float(v.real if isinstance(v, complex) else v))


def krawczyk_complex(
    exprs: Sequence[sympy.Expr], gens: Sequence[sympy.Symbol], m: Sequence[Any], radius: Any
) -> bool:
    """:func:`krawczyk` for a complex root ``m`` of a system with real coefficients: the
    test on the real and imaginary parts (twice the unknowns), in the box ``m +- radius``
    in each part."""
    mid = [mpmath.re(v) for v in m] + [mpmath.im(v) for v in m]
    before = mpmath.iv.dps
    mpmath.iv.dps = mpmath.mp.dps
    try:
        system = _realified_system(tuple(exprs), tuple(gens), mpmath.mp.dps)
        if system is not None:
            return krawczyk_box(system, mid, radius)
    finally:
        mpmath.iv.dps = before
    real_exprs, real_gens = _realified(tuple(exprs), tuple(gens))
    return krawczyk(real_exprs, real_gens, mid, radius)


@functools.lru_cache(maxsize=8)
def _realified_system(
    exprs: tuple[sympy.Expr, ...], gens: tuple[sympy.Symbol, ...], dps: int
) -> IntervalSystem | None:
    """:func:`_realified`'s system and its Jacobian as interval functions, built from the
    polynomials' terms (each ``(a + i b)^e`` expanded: no sympy expansion); None where
    the expressions are not polynomials with real coefficients."""
    terms = _terms(exprs, gens)
    if terms is None:
        return None
    n = len(gens)
    out = []
    for t in terms:
        re: dict[tuple[int, ...], Any] = {}
        im: dict[tuple[int, ...], Any] = {}
        for mono, c in t.items():
            parts = {(0,) * (2 * n): (1, 0)}  # the product so far: exponents -> (re, im)
            for k, e in enumerate(mono):
                for _ in range(e):  # times (a_k + i b_k)
                    nxt: dict[tuple[int, ...], tuple[int, int]] = {}
                    for m, (r, i) in parts.items():
                        for at, (pr, pi) in ((k, (r, i)), (n + k, (-i, r))):
                            mm = (*m[:at], m[at] + 1, *m[at + 1 :])
                            qr, qi = nxt.get(mm, (0, 0))
                            nxt[mm] = (qr + pr, qi + pi)
                    parts = nxt
            for m, (r, i) in parts.items():
                if r:
                    re[m] = re.get(m, 0) + c * r
                if i:
                    im[m] = im.get(m, 0) + c * i
        out += [re, im]
    return _interval_terms(out, 2 * n)


def certified_roots(
    eqs: Sequence[sympy.Expr], gens: Sequence[sympy.Symbol], points: Sequence[Any], dps: int
) -> list[list[Any]] | None:
    """Every endpoint (complex) refined at ``dps`` digits and certified by the Krawczyk
    test on its real and imaginary parts (None: one is not).  A root refined to real
    values to half the digits is certified in a box centred on its real part: the box is
    symmetric under conjugation and holds one root, which is then its own conjugate, real
    (its centre is returned with zero imaginary parts); the others' boxes lie clear of
    the real space, so their roots are not real.

    Every endpoint is refined before any is tested, the most ill-conditioned in double
    precision first (:func:`conditioning`); one ill-conditioned there
    (``MODE_ENDPOINT_SINGULAR_RTOL``) and singular at the working digits
    (:func:`regular`: no interval test certifies it) ends the attempt before any
    interval system is built."""
    radius = mpmath.mpf(MODE_CERTIFY_RADIUS)
    refined: dict[int, list[Any]] = {}
    ratio = [conditioning(eqs, gens, w) for w in points]
    for i in sorted(range(len(points)), key=lambda i: ratio[i]):
        x = newton(eqs, gens, points[i], dps)
        if x is None:
            return None
        if ratio[i] <= MODE_ENDPOINT_SINGULAR_RTOL and not regular(eqs, gens, x):
            return None  # ill-conditioned in double precision, singular at the digits
        refined[i] = x
    roots = []
    for i in range(len(points)):
        x = refined[i]
        if all(abs(mpmath.im(v)) <= mpmath.mpf(10) ** (-(dps // 2)) for v in x):
            x = [mpmath.mpc(mpmath.re(v)) for v in x]  # a real centre: a box symmetric
        elif all(abs(mpmath.im(v)) <= radius for v in x):
            return None  # neither real nor clear of the real space
        if not krawczyk_complex(eqs, gens, x, radius):
            return None
        roots.append(x)
    return roots


def conditioning(
    eqs: Sequence[sympy.Expr], gens: Sequence[sympy.Symbol], z: Sequence[Any]
) -> float:
    """The Jacobian's least singular value over its largest at ``z`` (a continuation
    endpoint), in double precision."""
    arrays = _double_functions(tuple(eqs), tuple(gens))
    if arrays is not None:  # from the terms, in double precision
        n = len(gens)
        A = arrays[1].values(np.array([complex(v) for v in z])).reshape(n, n)
    else:
        _, J = _functions(eqs, gens)
        with mpmath.workdps(15):
            A = np.array(J([_number(v) for v in z]).tolist(), dtype=complex)
    s = np.linalg.svd(A, compute_uv=False)
    return float(s[-1] / s[0]) if s[0] > 0 else 0.0


def apart(roots: Sequence[Sequence[Any]]) -> bool:
    """Are the certified boxes (radius ``MODE_CERTIFY_RADIUS`` about each root, in the real
    and imaginary parts) pairwise disjoint: so many distinct roots?"""
    radius = mpmath.mpf(MODE_CERTIFY_RADIUS)
    for i, a in enumerate(roots):
        for b in roots[i + 1 :]:
            gap = max(
                max(abs(mpmath.re(u - v)), abs(mpmath.im(u - v))) for u, v in zip(a, b, strict=True)
            )
            if gap <= 2 * radius:
                return False
    return True


def every_solution(
    eqs: Sequence[sympy.Expr],
    gens: Sequence[sympy.Symbol],
    points: Sequence[Any],
    dps: int,
    real: int,
) -> bool:
    """Are ``points`` (every solution continuation found, as many as the most the system
    can have) each certified in its own box (:func:`certified_roots`, the boxes pairwise
    disjoint: :func:`apart`), ``real`` of them real?  Then none is missing, and the real
    ones are every mode."""
    roots = certified_roots(eqs, gens, list(points), dps)
    if roots is None or not apart(roots):
        return False
    return sum(1 for x in roots if all(mpmath.im(v) == 0 for v in x)) == real


@functools.lru_cache(maxsize=4)
def _realified(
    exprs: tuple[sympy.Expr, ...], gens: tuple[sympy.Symbol, ...]
) -> tuple[list[sympy.Expr], list[sympy.Symbol]]:
    re_parts = [sympy.Symbol(f"re_{g}", real=True) for g in gens]
    im_parts = [sympy.Symbol(f"im_{g}", real=True) for g in gens]
    sub = {g: a + sympy.I * b for g, a, b in zip(gens, re_parts, im_parts, strict=True)}
    out = []
    for e in exprs:
        re, im = sympy.expand(e.xreplace(sub)).as_real_imag()
        out += [sympy.expand(re), sympy.expand(im)]
    return out, [*re_parts, *im_parts]


#: Newton's most steps, and how much each small step must shrink the last (else the
#: iteration has reached the rounding of the working digits: stop, the 60 steps at 1e-47
#: were a Dietmaier platform's refinement's four seconds a root)
NEWTON_STEPS = 60
NEWTON_STALL = 10


def newton(
    eqs: Sequence[sympy.Expr], gens: Sequence[sympy.Symbol], z: Sequence[Any], dps: int
) -> list[Any] | None:
    """Newton's method at ``dps`` digits from ``z`` on a square system: the root to
    ``10^-dps`` (None when the Jacobian is singular on the way or the residual stays
    above ``10^-(dps/2)``: not a regular root)."""
    f, J = _functions(eqs, gens)
    arrays = _double_functions(tuple(eqs), tuple(gens))
    form = _NEWTON_START.pick(arrays, z)
    if form is not None:
        z = form(arrays, z)
    x = mpmath.matrix([_number(v) for v in z])
    steps = _NEWTON_STEPS_FORM.pick(arrays, f, x, dps, NEWTON_STEPS, NEWTON_STALL)
    reached = False
    if steps is not None:
        x, reached = steps(arrays, f, x, dps, NEWTON_STEPS, NEWTON_STALL)
    last = mpmath.inf
    for _ in range(0 if reached else NEWTON_STEPS):
        try:
            dx = mpmath.lu_solve(J(x), f(x))
        except ZeroDivisionError:
            return None
        x -= dx
        step = mpmath.norm(dx)
        if step <= mpmath.mpf(10) ** (-dps):
            break
        if step <= mpmath.mpf(10) ** (-(dps // 2)) and step > last / NEWTON_STALL:
            break  # no longer quadratic: at the working digits' rounding (the condition's)
        last = step
    if mpmath.norm(f(x)) > mpmath.mpf(10) ** (-(dps // 2)):
        return None
    return list(x)


#: Newton's start's fast forms (:mod:`mechsing.assembly.contraction`)
_NEWTON_START = dispatch.table(
    "newton start", "mechsing.assembly.certify.newton (from the endpoint as it is)"
)

#: the fast forms of Newton's steps at the working digits
#: (:mod:`mechsing.assembly.contraction`)
_NEWTON_STEPS_FORM = dispatch.table(
    "newton steps",
    "mechsing.assembly.certify.newton (each step solved at the working digits by mpmath's LU)",
)


@functools.lru_cache(maxsize=16)
def _double_functions(
    eqs: tuple[sympy.Expr, ...], gens: tuple[sympy.Symbol, ...]
) -> tuple[Any, Any] | None:
    """A square polynomial system and its Jacobian as term arrays (double precision;
    None: not square, or not polynomials with real coefficients)."""
    from mechsing.assembly.contraction import TermArrays

    terms = _terms(eqs, gens)
    if terms is None or len(eqs) != len(gens):
        return None
    f = TermArrays(terms, len(gens))
    return f, f.jacobian()


def _functions(eqs: Sequence[sympy.Expr], gens: Sequence[sympy.Symbol]) -> tuple[Any, Any]:
    """The system and its Jacobian as mpmath functions of a vector (built once per system:
    every endpoint of one solve refines in the same)."""
    return _compiled(tuple(eqs), tuple(gens), mpmath.mp.dps)


@functools.lru_cache(maxsize=16)
def _compiled(
    eqs: tuple[sympy.Expr, ...], gens: tuple[sympy.Symbol, ...], dps: int
) -> tuple[Any, Any]:
    terms = _terms(eqs, gens)
    if terms is not None:  # polynomials: term by term, coefficients at the digits + 10
        with mpmath.workdps(dps + 10):
            f = _term_rows(terms, lambda c: _mp_coefficient(c, dps + 10))
        n, m = len(gens), len(eqs)
        rows: list[Any] = []  # the Jacobian's, built when first asked for (seldom: the
        # steps at the working digits mostly run on a double inverse)

        def jacobian(x: Any) -> Any:
            if not rows:
                with mpmath.workdps(dps + 10):
                    rows.append(
                        _term_rows(
                            _derivatives(terms, len(gens)),
                            lambda c: _mp_coefficient(c, dps + 10),
                        )
                    )
            v = rows[0](list(x))
            return mpmath.matrix([v[i * n : (i + 1) * n] for i in range(m)])

        return (lambda x: mpmath.matrix(f(list(x)))), jacobian
    f = sympy.lambdify(gens, list(eqs), "mpmath")
    n = len(gens)
    jac = _jacobian(eqs, gens)
    J = sympy.lambdify(gens, [jac[i : i + n] for i in range(0, len(jac), n)], "mpmath")
    return (lambda x: mpmath.matrix(f(*x))), (lambda x: mpmath.matrix(J(*x)))


def regular(eqs: Sequence[sympy.Expr], gens: Sequence[sympy.Symbol], x: Sequence[Any]) -> bool:
    """Is the Jacobian at ``x`` (refined at the working digits N) far from singular: its
    singular values' ratio above ``10^(-N / MODE_SINGULAR_DIGITS)``?"""
    floor = mpmath.mpf(10) ** (-(mpmath.mp.dps // MODE_SINGULAR_DIGITS))
    arrays = _double_functions(tuple(eqs), tuple(gens))
    form = _REGULAR.pick(arrays, x, floor)
    if form is not None and form(arrays, x, floor):
        return True
    _, J = _functions(eqs, gens)
    s = mpmath.svd(J(list(x)), compute_uv=False)
    return bool(min(s) > floor * max(s))


#: the fast forms of :func:`regular` (:mod:`mechsing.assembly.contraction`)
_REGULAR = dispatch.table(
    "regular root",
    "mechsing.assembly.certify.regular (the Jacobian's singular values at the working digits)",
)


def _least_squares_newton(f: Any, J: Any, x: Any, dps: int, steps: int) -> Any:
    """Gauss-Newton with the Jacobian's pseudo-inverse (singular values below
    ``10^-(dps/2)`` of the largest dropped): onto a curve of roots quadratically, onto a
    multiple root linearly."""
    tiny = mpmath.mpf(10) ** (-(dps // 2))
    for _ in range(steps):
        U, S, V = mpmath.svd_r(J(x))
        fx = f(x)
        Utf = U.T * fx
        dx = mpmath.matrix(len(x), 1)
        for k in range(len(S)):
            if S[k] > tiny * S[0]:
                coef = Utf[k] / S[k]
                for i in range(len(x)):
                    dx[i] += V[k, i] * coef
        x = x - dx
        if mpmath.norm(dx) <= mpmath.mpf(10) ** (-dps):
            break
    return x


def misses(
    eqs: Sequence[sympy.Expr], gens: Sequence[sympy.Symbol], x: Sequence[Any], dps: int
) -> Any:
    """The residual of the system at ``x`` (a root refined at ``dps`` digits: the norm of
    its values) where it does not close (above ``10^(-dps / MODE_CLOSURE_DIGITS)``), else
    0: a root of a square system's combinations may miss the others."""
    f, _ = _functions(eqs, gens)
    return left_open(mpmath.norm(f(x)), dps)


def left_open(residual: Any, dps: int) -> Any:
    """``residual`` (the norm of closure equations' values at ``dps`` digits) where it
    does not close (above ``10^(-dps / MODE_CLOSURE_DIGITS)``), else 0."""
    return residual if residual > mpmath.mpf(10) ** (-(dps // MODE_CLOSURE_DIGITS)) else 0


def singular_root(
    eqs: Sequence[sympy.Expr], gens: Sequence[sympy.Symbol], z: Sequence[Any], dps: int
) -> tuple[list[Any] | None, bool]:
    """A root near ``z`` where the Jacobian is singular: (the root, polished, or None
    when none is near; whether it lies on a curve of roots).  The local dimension test
    steps ``MODE_CURVE_STEP`` along the Jacobian's null direction and corrects on the
    hyperplane at that distance: it closes to the working digits only on a curve."""
    f, J = _functions(eqs, gens)
    x = _least_squares_newton(f, J, mpmath.matrix([mpmath.mpf(float(v)) for v in z]), dps, 400)
    if misses(eqs, gens, x, dps):
        return None, False
    _, _, V = mpmath.svd_r(J(x), full_matrices=True)
    n = len(x)
    v = mpmath.matrix([V[n - 1, i] for i in range(n)])
    h = mpmath.mpf(MODE_CURVE_STEP)

    def fa(y: Any) -> Any:
        out = f(y)
        extra = (v.T * (y - x))[0] - h
        return mpmath.matrix([*out, extra])

    def Ja(y: Any) -> Any:
        Jy = J(y)  # (a system of more or fewer equations than unknowns: its rows)
        A = mpmath.matrix(Jy.rows + 1, n)
        for i in range(Jy.rows):
            for k in range(n):
                A[i, k] = Jy[i, k]
        for k in range(n):
            A[Jy.rows, k] = v[k]
        return A

    y = _least_squares_newton(fa, Ja, x + h * v, dps, 30)
    curve = mpmath.norm(fa(y)) <= mpmath.mpf(10) ** (-(dps // 2))
    return list(x), bool(curve)


def local_dimension(
    eqs: Sequence[sympy.Expr], gens: Sequence[sympy.Symbol], x: Sequence[Any], dps: int
) -> int:
    """The dimension of the solutions at ``x`` (a root, polished): 0 where it is isolated
    (:func:`singular_root` finds no curve); else the unknowns less the Jacobian's rank at
    a smooth point a step ``MODE_CURVE_STEP`` away along its null directions, corrected
    back onto the solutions (ranks to ``10^(-N / MODE_SINGULAR_DIGITS)``)."""
    root, curve = singular_root(eqs, gens, x, dps)
    if root is None or not curve:
        return 0
    f, J = _functions(eqs, gens)
    y = mpmath.matrix(root)
    floor = mpmath.mpf(10) ** (-(mpmath.mp.dps // MODE_SINGULAR_DIGITS))
    _, S, V = mpmath.svd_r(J(y), full_matrices=True)
    n = len(y)
    null = [k for k in range(n) if k >= len(S) or S[k] <= floor * S[0]]
    step = mpmath.matrix([sum(V[k, i] for k in null) for i in range(n)])
    step *= mpmath.mpf(MODE_CURVE_STEP) / mpmath.norm(step)
    y = _least_squares_newton(f, J, y + step, dps, 60)
    S = mpmath.svd_r(J(y), compute_uv=False)
    return n - sum(1 for s in S if s > floor * S[0])
