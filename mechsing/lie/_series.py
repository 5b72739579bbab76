"""Backend-generic power series used by the Lie formulas near angle 0.

Each coefficient function of the Lie layer (sin t / t, (1 - cos t)/t^2, ...)
is a power series in t^2.  Near t = 0 the closed forms cancel (or divide by
zero), so below a switch point they are evaluated from their series.  The
switch point and the number of terms belong to the formula (a formula's own switch to a Taylor series stays
beside it; decision tolerances live in mechsing.numeric):

* float and mp: the series is used for ``t^2 <= 1`` with as many terms as make
  the truncation error smaller than the backend's ``eps``; at ``t = 1`` the
  closed forms have lost at most a few ulps to cancellation, so both
  branches are accurate to a few eps on their side of the switch.
* exact: ``eps`` is 0 and the series is used only at exactly ``t = 0``,
  where its value (the first coefficient) is the exact limit.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Any

import numpy as np
import sympy

from mechsing.numeric import Backend

#: the closed forms are used above this value of t^2 (float and mp)
SWITCH_T2 = 1


def use_series(bk: Backend, t2: Any) -> np.ndarray:
    """Boolean mask: where the series (not the closed form) must be used."""
    limit = 0 if bk.name == "exact" else SWITCH_T2
    cond = np.asarray(t2 <= limit)
    return cond.astype(bool) if cond.dtype == object else cond


def safe(bk: Backend, mask: np.ndarray, x: Any, fill: Any = 1) -> Any:
    """``x`` with the masked entries replaced by ``fill`` (for denominators)."""
    return np.where(mask, bk.convert(fill), x)


def _eps_digits(bk: Backend) -> float:
    """-log10(eps) of the backend (15.65 in float, about N at mp:N; 0 in exact mode, where
    no series is truncated)."""
    return _digits_of(bk.name, _dps(bk))


@lru_cache(maxsize=64)
def _digits_of(name: str, dps: int) -> float:
    # from log10(eps), never float(eps): at N > 300 digits eps underflows to 0 in float
    if name == "exact":
        return 0.0
    if name == "float":
        return -math.log10(float(np.finfo(np.float64).eps))
    import mpmath

    with mpmath.workdps(dps):
        return float(-mpmath.log10(mpmath.mp.eps))


@lru_cache(maxsize=64)
def _n_terms_factorial(name: str, digits: float, shift: int) -> int:
    """Terms of sum (-1)^k t^(2k)/(2k+shift)! for |t| <= 1 to reach eps / 100 (eps =
    10^-digits): the first omitted term 1/(2k+shift)! is below it."""
    if name == "exact":
        return 1
    k = 0
    while math.lgamma(2 * k + shift + 1) / math.log(10) < digits + 2:
        k += 1
    return k + 1


def factorial_series(bk: Backend, t2: Any, shift: int) -> Any:
    """sum_k (-1)^k t2^k / (2k + shift)!   (Horner, backend-generic).

    shift = 1: sin t / t; 2: (1 - cos t)/t^2; 3: (t - sin t)/t^3; and so on.
    """
    n = _n_terms_factorial(bk.name, _eps_digits(bk), shift)
    return _horner(t2, _factorial_converted(bk.name, _dps(bk), shift, n))


@lru_cache(maxsize=64)
def _factorial_coeffs(name: str, shift: int, n: int) -> tuple[Any, ...]:
    return tuple(sympy.Rational((-1) ** k, math.factorial(2 * k + shift)) for k in range(n))


def _n_terms_bernoulli(bk: Backend) -> int:
    # terms decay like (t / 2pi)^(2k); at t = 1 that is (4 pi^2)^-k: enough to reach eps / 100
    if bk.name == "exact":
        return 1
    return int(math.ceil((_eps_digits(bk) + 2) / math.log10(4 * math.pi**2))) + 1


@lru_cache(maxsize=8)
def _bernoulli_coeffs(n: int) -> tuple[Any, ...]:
    # (1 - (t/2) cot(t/2)) / t^2 = sum_{k>=1} |B_2k| t^(2k-2) / (2k)!
    return tuple(abs(sympy.bernoulli(2 * k)) / sympy.factorial(2 * k) for k in range(1, n + 1))


def half_cot_series(bk: Backend, t2: Any) -> Any:
    """(1 - (t/2) cot(t/2)) / t^2 = 1/12 + t^2/720 + t^4/30240 + ...  (|t| < 2 pi)."""
    n = _n_terms_bernoulli(bk)
    return _horner(t2, _bernoulli_converted(bk.name, _dps(bk), n))


@lru_cache(maxsize=64)
def _factorial_converted(name: str, dps: int, shift: int, n: int) -> tuple[Any, ...]:
    return _converted(name, dps, _factorial_coeffs(name, shift, n))


@lru_cache(maxsize=64)
def _bernoulli_converted(name: str, dps: int, n: int) -> tuple[Any, ...]:
    return _converted(name, dps, _bernoulli_coeffs(n))


def _horner(x: Any, conv: tuple[Any, ...]) -> Any:
    if isinstance(x, np.ndarray) and x.ndim == 0:
        # one number: plain scalar arithmetic (an mpf times a 0-d array makes mpmath
        # try to convert the array, through its repr, before numpy takes over)
        x = x[()]
    acc = x * 0 + conv[-1]
    for c in reversed(conv[:-1]):
        acc = acc * x + c
    return acc


def horner(bk: Backend, x: Any, coeffs: tuple[Any, ...]) -> Any:
    """sum_k coeffs[k] x^k with coefficients converted to the backend."""
    return _horner(x, _converted(bk.name, _dps(bk), tuple(coeffs)))


def _dps(bk: Backend) -> int:
    if bk.name != "mp":
        return 0
    import mpmath

    return int(mpmath.mp.dps)


@lru_cache(maxsize=256)
def _converted(name: str, dps: int, coeffs: tuple[Any, ...]) -> tuple[Any, ...]:
    # cached per backend and working precision: converting rationals dominates otherwise
    if name == "exact":
        return coeffs
    if name == "float":
        return tuple(float(c) for c in coeffs)
    import mpmath

    with mpmath.workdps(dps):
        return tuple(mpmath.mpf(c.p) / c.q for c in coeffs)
