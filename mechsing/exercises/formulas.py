"""Whether a student's formula is the key's: proved by sympy, or compared over the domain.

Two formulas are compared in two steps:

1. **symbolically**: sympy simplifies their difference (also with the trigonometric
   functions of sums and multiples expanded); zero is a proof.  Up to a factor (a
   condition ``det J = 0`` holds up to one), their quotient simplified to a non-zero
   constant is one;
2. **at points drawn over the whole domain of each variable**, from a fixed seed (grading
   is reproducible): an angle over a period, a positive length or parameter over
   ``1e-4 .. 1e4`` (log-uniform), any other variable over either sign of those
   magnitudes.  They agree at a point when they differ there by at most the relative
   tolerance times the larger of their values (up to a factor: when their ratio is the
   same at every point).  A sheet that differs at one point is wrong, with the point; a
   point where the key is not a real number is skipped.  The points are evaluated in
   floats, and a point where they disagree is evaluated again at :data:`_DIGITS` digits
   (so a cancellation in floating point never makes a right sheet wrong).

The key states the domain of each variable in ``variables`` (``angle``, ``positive``,
``real``); a variable it does not name is ``real``.
"""

from __future__ import annotations

import ast
import math
from collections.abc import Callable, Mapping
from typing import Any

import mpmath
import numpy as np
import sympy

from mechsing.errors import UserError

__all__ = ["DOMAINS", "formula_names", "same_formula"]

#: the domains a key may state for a formula's variable
DOMAINS = ("angle", "positive", "real")
#: points at which two formulas must agree when sympy proves nothing
_FORMULA_POINTS = 400
#: points drawn in all (points where the key is not real are skipped)
_DRAWN_POINTS = 4 * _FORMULA_POINTS
_FORMULA_SEED = 20240533
#: the magnitudes a length or another parameter takes (log-uniform), m
_MAGNITUDES = (1e-4, 1e4)
#: digits at which a point where the floats disagree is evaluated again
_DIGITS = 40
#: sympy simplifies a difference of formulas only up to this size (a sheet may hold a long
#: formula: past it, the points decide)
_SIMPLIFY_OPS = 120
_FUNCTION_NAMES = {"sqrt", "sin", "cos", "tan", "asin", "acos", "atan", "atan2", "pi"}


def formula_names(text: str) -> set[str]:
    """The variables a formula's text names (functions and ``pi`` left out)."""
    try:
        tree = ast.parse(text, mode="eval")
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return set()
    return {n.id for n in ast.walk(tree) if isinstance(n, ast.Name)} - _FUNCTION_NAMES


def _symbol(name: str, domain: str) -> sympy.Symbol:
    if domain == "positive":
        return sympy.Symbol(name, positive=True)
    return sympy.Symbol(name, real=True)


def _formula(text: str, symbols: dict[str, sympy.Symbol]) -> Any:
    """A whitelisted formula as a sympy expression of ``symbols`` (the file format's
    parser: numbers, + - * / **, the functions of the mechanism file; never code)."""
    from mechsing.model.expressions import parse_number
    from mechsing.model.parameters import ParameterSymbol

    # the parser checks that the formula is a finite real number at a probe point
    probe = {
        n: ParameterSymbol(n, sympy.Rational(1, 3) + k * sympy.Rational(1, 7))
        for k, n in enumerate(symbols)
    }
    value = parse_number(str(text), names=probe)
    return value.xreplace({probe[n]: s for n, s in symbols.items()})


def _proved(a: Any, b: Any, up_to_factor: bool) -> bool:
    """True when sympy proves ``b`` equal to ``a`` (up to a non-zero constant factor)."""
    if up_to_factor:
        if b == 0 or sympy.count_ops(a) + sympy.count_ops(b) > _SIMPLIFY_OPS:
            return False
        for q in (sympy.simplify(a / b), sympy.simplify(sympy.expand_trig(a / b))):
            if not q.free_symbols and q.is_zero is False and q.is_finite:
                return True
        return False
    d = a - b
    if sympy.count_ops(d) > _SIMPLIFY_OPS:
        return False
    return sympy.simplify(d) == 0 or sympy.simplify(sympy.expand_trig(d)) == 0


def _points(names: list[str], domains: Mapping[str, str]) -> np.ndarray:
    """The points (one row each) at which the formulas are compared."""
    rng = np.random.default_rng(_FORMULA_SEED)
    cols = []
    lo, hi = (math.log(m) for m in _MAGNITUDES)
    for n in names:
        domain = domains.get(n, "real")
        if domain == "angle":
            cols.append(rng.uniform(-math.pi, math.pi, _DRAWN_POINTS))
            continue
        col = np.exp(rng.uniform(lo, hi, _DRAWN_POINTS))
        if domain == "real":
            col = col * rng.choice((-1.0, 1.0), _DRAWN_POINTS)
        cols.append(col)
    return np.array(cols).T.reshape(_DRAWN_POINTS, len(names))


def _floats(f: Any, points: np.ndarray) -> np.ndarray:
    with np.errstate(all="ignore"):
        v = f(*points.T)
    v = np.broadcast_to(np.asarray(v), points.shape[:1])
    if np.iscomplexobj(v):
        v = np.where(np.abs(v.imag) <= 0, v.real, np.nan)
    return np.asarray(v, dtype=float)


def _exact_value(f: Any, point: np.ndarray) -> Any:
    """The value at ``point`` at :data:`_DIGITS` digits; None where it is not real."""
    with mpmath.workdps(_DIGITS):
        try:
            v = f(*(mpmath.mpf(float(x)) for x in point))
        except (ValueError, ZeroDivisionError, OverflowError, TypeError):
            return None
        v = mpmath.mpmathify(v)
        if isinstance(v, mpmath.mpc):
            if v.imag != 0:
                return None
            v = v.real
        return v if mpmath.isfinite(v) else None


def _where(names: list[str], point: np.ndarray) -> str:
    return ", ".join(f"{n}={x:.4g}" for n, x in zip(names, point, strict=True))


def same_formula(
    expected: str,
    given: str,
    rtol: float,
    up_to_factor: bool = False,
    domains: Mapping[str, str] | None = None,
) -> tuple[bool, str]:
    """Whether ``given`` is the formula ``expected`` (and why not): proved by sympy, or
    equal at points over each variable's domain (``domains``: name -> one of
    :data:`DOMAINS`); see the module's docstring."""
    domains = domains or {}
    want, got = formula_names(expected), formula_names(given)
    extra = sorted(got - want)
    if extra:
        return False, f"uses {', '.join(extra)}, which the expected formula does not"
    names = sorted(want | got)
    symbols = {n: _symbol(n, domains.get(n, "real")) for n in names}
    try:
        a = _formula(expected, symbols)
        b = _formula(given, symbols)
    except UserError as exc:
        return False, f"not a formula: {exc}"
    if _proved(a, b, up_to_factor):
        return True, ""
    args = [symbols[n] for n in names]
    points = _points(names, domains)
    va = _floats(sympy.lambdify(args, a, "numpy"), points)
    vb = _floats(sympy.lambdify(args, b, "numpy"), points)
    fa, fb = sympy.lambdify(args, a, "mpmath"), sympy.lambdify(args, b, "mpmath")
    usable = np.isfinite(va)
    if usable.sum() < _FORMULA_POINTS:
        # too few points in floats (overflow, a root of a negative number): count exactly
        usable = np.array([_exact_value(fa, p) is not None for p in points])
        if usable.sum() < _FORMULA_POINTS:
            return False, "cannot be evaluated at enough points to compare it"
    points, va, vb = points[usable], va[usable], vb[usable]
    if up_to_factor:
        return _proportional(names, points, va, vb, fa, fb, rtol)
    with np.errstate(all="ignore"):
        close = np.abs(va - vb) <= rtol * np.maximum(np.abs(va), np.abs(vb))

    def differ(x: Any, y: Any) -> str | None:
        return (
            "differs from the expected formula" if abs(x - y) > rtol * max(abs(x), abs(y)) else None
        )

    why = _first_disagreement(names, points, close, fa, fb, differ)
    return why is None, why or ""


def _first_disagreement(
    names: list[str],
    points: np.ndarray,
    close: np.ndarray,
    fa: Any,
    fb: Any,
    differ: Callable[[Any, Any], str | None],
) -> str | None:
    """Why the formulas differ at the first point the floats did not find ``close`` and
    that ``differ`` confirms at :data:`_DIGITS` digits (None: they agree everywhere)."""
    for i in np.flatnonzero(~close):
        x, y = _exact_value(fa, points[i]), _exact_value(fb, points[i])
        if x is None:
            continue  # the key is not real there: not in the domain
        why = "not a real number" if y is None else differ(x, y)
        if why:
            return f"{why} at {_where(names, points[i])}"
    return None


def _proportional(
    names: list[str],
    points: np.ndarray,
    va: np.ndarray,
    vb: np.ndarray,
    fa: Any,
    fb: Any,
    rtol: float,
) -> tuple[bool, str]:
    """Up to a factor: the same non-zero ratio at every point (zero where the key is)."""
    with np.errstate(all="ignore"):
        ratios = va / vb
    finite = np.isfinite(ratios) & (ratios != 0)
    if not finite.any():
        return False, "not a constant multiple of the expected formula"
    # the ratio at the point of the median one, exactly: the reference
    k = np.flatnonzero(finite)[np.argsort(ratios[finite])[finite.sum() // 2]]
    x, y = _exact_value(fa, points[k]), _exact_value(fb, points[k])
    if x is None or y is None or y == 0 or x == 0:
        return False, "not a constant multiple of the expected formula"
    ratio = x / y
    close = finite & (np.abs(ratios - float(ratio)) <= rtol * abs(float(ratio)))

    def differ(x: Any, y: Any) -> str | None:
        if x == 0 or y == 0:
            if x == y:
                return None
            return (
                "zero where the expected formula is not"
                if y == 0
                else ("not zero where the expected formula is")
            )
        if abs(x / y - ratio) > rtol * abs(ratio):
            return "not a constant multiple of the expected formula"
        return None

    why = _first_disagreement(names, points, close, fa, fb, differ)
    return why is None, why or ""
