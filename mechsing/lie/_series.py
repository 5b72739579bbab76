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
from fractions import Fraction
from functools import lru_cache
from typing import Any

import numpy as np

from mechsing.numeric import Backend
from mechsing.numeric.backend import bool_mask

#: the closed forms are used above this value of t^2 (float and mp)
SWITCH_T2 = 1


def use_series(bk: Backend, t2: Any) -> np.ndarray:
    """Boolean mask: where the series (not the closed form) must be used."""
    cond = np.asarray(t2 <= bk.series_switch(SWITCH_T2))
    return bool_mask(cond)


def safe(bk: Backend, mask: np.ndarray, x: Any, fill: Any = 1) -> Any:
    """``x`` with the masked entries replaced by ``fill`` (for denominators)."""
    return np.where(mask, bk.convert(fill), x)


@lru_cache(maxsize=64)
def _n_terms_factorial(digits: float, shift: int) -> int:
    """Terms of sum (-1)^k t^(2k)/(2k+shift)! for |t| <= 1 to reach eps / 100 (eps =
    10^-digits): the first omitted term 1/(2k+shift)! is below it.  No digits (exact
    mode): the series is only evaluated at 0, where its first term is its value."""
    if not digits:
        return 1
    k = 0
    while math.lgamma(2 * k + shift + 1) / math.log(10) < digits + 2:
        k += 1
    return k + 1


def factorial_series(bk: Backend, t2: Any, shift: int) -> Any:
    """sum_k (-1)^k t2^k / (2k + shift)!   (Horner, backend-generic).

    shift = 1: sin t / t; 2: (1 - cos t)/t^2; 3: (t - sin t)/t^3; and so on.
    """
    key = (bk.key, "factorial", shift)
    conv = _CONVERTED.get(key)
    if conv is None:
        n = _n_terms_factorial(bk.digits, shift)
        conv = _CONVERTED[key] = _converted(bk, _factorial_coeffs(shift, n))
    return _horner(t2, conv)


@lru_cache(maxsize=64)
def _factorial_coeffs(shift: int, n: int) -> tuple[Any, ...]:
    return tuple(Fraction((-1) ** k, math.factorial(2 * k + shift)) for k in range(n))


def _n_terms_bernoulli(bk: Backend) -> int:
    # terms decay like (t / 2pi)^(2k); at t = 1 that is (4 pi^2)^-k: enough to reach eps / 100
    if not bk.digits:
        return 1  # exact: evaluated only at 0
    return int(math.ceil((bk.digits + 2) / math.log10(4 * math.pi**2))) + 1


@lru_cache(maxsize=8)
def _bernoulli_coeffs(n: int) -> tuple[Any, ...]:
    # (1 - (t/2) cot(t/2)) / t^2 = sum_{k>=1} |B_2k| t^(2k-2) / (2k)!
    b = _bernoulli_numbers(2 * n)
    return tuple(abs(b[2 * k]) / math.factorial(2 * k) for k in range(1, n + 1))


def _bernoulli_numbers(n: int) -> list[Fraction]:
    """B_0 ... B_n (B_1 = -1/2), exact, by the recurrence sum_{j<=m} C(m+1, j) B_j = 0."""
    b = [Fraction(1)]
    for m in range(1, n + 1):
        b.append(-sum((math.comb(m + 1, j) * b[j] for j in range(m)), Fraction(0)) / (m + 1))
    return b


def half_cot_series(bk: Backend, t2: Any) -> Any:
    """(1 - (t/2) cot(t/2)) / t^2 = 1/12 + t^2/720 + t^4/30240 + ...  (|t| < 2 pi)."""
    key = (bk.key, "bernoulli", 0)
    conv = _CONVERTED.get(key)
    if conv is None:
        conv = _CONVERTED[key] = _converted(bk, _bernoulli_coeffs(_n_terms_bernoulli(bk)))
    return _horner(t2, conv)


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
    return _horner(x, _converted(bk, tuple(coeffs)))


def _converted(bk: Backend, coeffs: tuple[Any, ...]) -> tuple[Any, ...]:
    """The rational coefficients in the backend's numbers, cached per backend and working
    precision (converting rationals dominates otherwise)."""
    key = (bk.key, coeffs)
    out = _CONVERTED.get(key)
    if out is None:
        out = _CONVERTED[key] = tuple(bk.rational(c.numerator, c.denominator) for c in coeffs)
    return out


#: converted coefficients by (backend key, coefficients) or (backend key, series, shift):
#: a few series at a few precisions
_CONVERTED: dict[tuple[Any, ...], tuple[Any, ...]] = {}
