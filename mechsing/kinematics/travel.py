"""Given values beyond a limit of travel: which value, and by how much.

A configuration whose given values lie just beyond a fold of the closure (a dead centre
of a slider, the limit of a rocker) has no solution: Newton on the unknown joints stops
at the fold, where the closure Jacobian in the unknowns loses rank, with a residual
left along its left kernel u.  To first order the residual's component ``u . r`` there
is what the given values add beyond the fold, ``u . J_g dg``: so each given value alone
is ``|u . r| / |u . J_g e_i|`` beyond its limit (commensurate units: lengths over L).

Owns :func:`beyond_travel`, the sentence that names the given value nearest to bringing
the configuration back (the one the residual is most sensitive to), how far beyond its
limit it is and where that limit is (SI units and radians).
"""

from __future__ import annotations

from typing import Any

import mpmath
import numpy as np

from mechsing.kinematics.newton import scaled_system
from mechsing.numeric import CONTINUATION_SINGULAR_RTOL, svd, to_float

__all__ = ["beyond_travel"]


def beyond_travel(m: Any, q: np.ndarray, gmask: np.ndarray) -> str | None:
    """Why configuration ``q`` of model ``m`` (its given coordinates ``gmask``, the others
    solved as far as they go) does not close, when it is beyond a limit of travel: the
    closure Jacobian in the unknown joints is singular there (relative smallest singular
    value below CONTINUATION_SINGULAR_RTOL).  None when it is not (or has no unknowns)."""
    free = ~np.asarray(gmask, dtype=bool)
    if not np.any(free) or not np.any(~free) or not m.chords:
        return None
    with m.precision.context():
        Js, rs = scaled_system(m, q, False)
        Js = Js.toarray() if hasattr(Js, "toarray") else Js
        U, s, _vt = svd(m.precision.asarray(Js)[:, free])
        s = [float(x) for x in s]
        if not s or not s[0] or s[-1] > CONTINUATION_SINGULAR_RTOL * s[0]:
            return None
        # the left singular vector of the smallest singular value: the direction the
        # unknowns cannot correct (structural zero rows, such as a planar loop's
        # out-of-plane ones, are further left kernel vectors that the residual and the
        # given columns have no part in)
        u = np.asarray(to_float(U[:, len(s) - 1]), dtype=float)
        r = float(u @ np.asarray(to_float(rs), dtype=float))
        g = u @ np.asarray(to_float(Js[:, ~free]), dtype=float)
    if not np.any(g):
        return None
    i = int(np.argmax(np.abs(g)))  # the given value the fold is most sensitive to
    col = int(np.flatnonzero(~free)[i])
    scale = m.length_scale if m.length_columns[col] else 1.0
    beyond = abs(r / g[i]) * scale
    with m.precision.context():  # the limit at the model's digits (q is given to them)
        limit = mpmath.nstr(mpmath.mpf(q[col]) - mpmath.mpf(r / g[i] * scale), 16)
    name, index = m.mech.coordinates()[col]
    unit = "m" if m.length_columns[col] else "rad"
    label = (
        name
        if m.joint(name).columns.stop - m.joint(name).columns.start == 1
        else f"{name}[{index}]"
    )
    return (
        f"its given values are beyond a limit of travel (a fold of the closure, where the "
        f"unknown joints lose a direction): {label} is {beyond:.3g} {unit} beyond its limit "
        f"at {label} = {limit} {unit}; give {label} within its travel"
    )
