"""Where a scalar read along a path crosses a value: one locator for every such question.

:func:`locate_crossing` places the point of a bracket where a scalar read along a path
changes sign, by Brent's method (inverse quadratic interpolation, safeguarded by
bisection: it converges to a sign change of any function, smooth or not).  The readings
are the caller's: the swept component of a path's tangent (a fold,
:meth:`~mechsing.kinematics.paths.arc.Arc.fold_between`), an actuator's effort less its
limit (:meth:`mechsing.statics.along.SweepStatics.locate_limits`), a singular value less
a level, a discriminant.  Each reading closes the path at the trial point; a reading that
cannot (the path lost there) ends the search.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

__all__ = ["locate_crossing"]


class _Lost(Exception):
    """A reading could not be taken (the path was lost at the trial point)."""


def locate_crossing(
    read: Callable[[float], float | None], lo: float, hi: float, xtol: float
) -> float | None:
    """The value between ``lo`` and ``hi`` where ``read`` (a scalar along the path, None
    where it cannot be read) changes sign, to ``xtol`` (and four units of rounding
    relative); None when the readings at the ends have the same sign or a reading is
    lost on the way."""
    from scipy.optimize import brentq

    def f(v: float) -> float:
        r = read(v)
        if r is None:
            raise _Lost
        return r

    try:
        return float(brentq(f, lo, hi, xtol=xtol, rtol=4 * np.finfo(float).eps))
    except (_Lost, ValueError):
        return None
