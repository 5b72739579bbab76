"""The quintic rest-to-rest time law (imports nothing from mechsing): a value moving from
v0 to v1 over T seconds as v(t) = v0 + (v1 - v0) h(t/T), h(x) = 10 x^3 - 15 x^4 + 6 x^5,
and its rate and acceleration at a given value (h inverted by numpy's polynomial roots)."""

from __future__ import annotations

import numpy as np

__all__ = ["law"]


def law(v: float, v0: float, v1: float, T: float) -> tuple[float, float, float]:
    """(t, v', v'') of the law at the value v."""
    u = (v - v0) / (v1 - v0)
    roots = np.clip(np.roots([6.0, -15.0, 10.0, 0.0, 0.0, -u]).real, 0.0, 1.0)
    x = float(min(roots, key=lambda r: abs(r**3 * (10 - 15 * r + 6 * r**2) - u)))
    vd = (v1 - v0) / T * 30 * x**2 * (1 - x) ** 2
    vdd = (v1 - v0) / T**2 * 60 * x * (1 - x) * (1 - 2 * x)
    return x * T, vd, vdd
