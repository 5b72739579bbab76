"""Certification of one solution: the Krawczyk test in mpmath interval arithmetic.

For a square system ``f(z) = 0`` (sympy expressions with algebraic coefficients, which
may hold ``sin`` and ``cos``), an approximate root ``m`` and the box ``Z = m + [-r, r]^n``:
with ``Y`` an approximate inverse of ``f'(m)``, ``K = m - Y f(m) + (I - Y f'(Z))(Z - m)``.
``K`` strictly inside ``Z`` proves that ``Z`` holds exactly one root of ``f``
(R. Krawczyk, Computing 4, 1969; R. E. Moore, Computing 19, 1977).  Constants are
enclosed at the working precision plus guard digits, so the proof holds for the exact
coefficients.

Owns :func:`krawczyk`.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import mpmath
import sympy

__all__ = ["krawczyk"]


def _interval_function(exprs: Sequence[sympy.Expr], gens: Sequence[sympy.Symbol]) -> Any:
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
        jac = [[sympy.diff(e, g) for g in gens] for e in exprs]
        f = _interval_function(exprs, gens)
        J = _interval_function([x for row in jac for x in row], gens)
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
    finally:
        mpmath.iv.dps = before
