"""Backend-generic power series used by the Lie formulas near angle 0.

Each coefficient function of the Lie layer (sin t / t, (1 - cos t)/t^2, ...)
is a power series in t^2.  Near t = 0 the closed forms cancel (or divide by
zero), so below a switch point they are evaluated from their series.  The
switch point and the number of terms belong to the formula (DESIGN.md:
"a formula's own switch to a Taylor series stays beside it"):

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


def _n_terms_factorial(bk: Backend, shift: int) -> int:
    """Terms of sum (-1)^k t^(2k)/(2k+shift)! for |t| <= 1 to reach eps."""
    if bk.name == "exact":
        return 1
    eps = float(bk.eps)
    k = 0
    while 1.0 / math.factorial(2 * k + shift) > eps * 1e-2:
        k += 1
    return k + 1


def factorial_series(bk: Backend, t2: Any, shift: int) -> Any:
    """sum_k (-1)^k t2^k / (2k + shift)!   (Horner, backend-generic).

    shift = 1: sin t / t; 2: (1 - cos t)/t^2; 3: (t - sin t)/t^3; and so on.
    """
    n = _n_terms_factorial(bk, shift)
    coeffs = _factorial_coeffs(bk.name, shift, n)
    return horner(bk, t2, coeffs)


@lru_cache(maxsize=64)
def _factorial_coeffs(name: str, shift: int, n: int) -> tuple[Any, ...]:
    return tuple(sympy.Rational((-1) ** k, math.factorial(2 * k + shift)) for k in range(n))


def _n_terms_bernoulli(bk: Backend) -> int:
    # terms decay like (t / 2pi)^(2k); at t = 1 that is 0.0253^k
    if bk.name == "exact":
        return 1
    eps = float(bk.eps)
    return int(math.ceil(math.log(eps * 1e-2) / math.log(1.0 / (4 * math.pi**2)))) + 1


@lru_cache(maxsize=8)
def _bernoulli_coeffs(n: int) -> tuple[Any, ...]:
    # (1 - (t/2) cot(t/2)) / t^2 = sum_{k>=1} |B_2k| t^(2k-2) / (2k)!
    return tuple(abs(sympy.bernoulli(2 * k)) / sympy.factorial(2 * k) for k in range(1, n + 1))


def half_cot_series(bk: Backend, t2: Any) -> Any:
    """(1 - (t/2) cot(t/2)) / t^2 = 1/12 + t^2/720 + t^4/30240 + ...  (|t| < 2 pi)."""
    return horner(bk, t2, _bernoulli_coeffs(_n_terms_bernoulli(bk)))


def horner(bk: Backend, x: Any, coeffs: tuple[Any, ...]) -> Any:
    """sum_k coeffs[k] x^k with coefficients converted to the backend."""
    conv = [_coef(bk, c) for c in coeffs]
    acc = x * 0 + conv[-1]
    for c in reversed(conv[:-1]):
        acc = acc * x + c
    return acc


def _coef(bk: Backend, c: Any) -> Any:
    if bk.name == "exact":
        return c
    if bk.name == "float":
        return float(c)
    return bk.convert(sympy.Rational(c))
