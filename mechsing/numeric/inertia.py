"""Whether a 3x3 matrix is a rigid body's inertia (the loader and the importers ask it).

Owns :func:`inertia_problem`, the one test of a body's inertia about its centre of mass,
with its tolerance :data:`mechsing.numeric.tolerances.INERTIA_RTOL`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing.numeric.backend import to_float
from mechsing.numeric.tolerances import INERTIA_RTOL

__all__ = ["inertia_problem"]


def inertia_problem(rows: Any) -> str | None:
    """Why a 3x3 inertia (about the centre of mass) is not a rigid body's, None when it
    is one: not symmetric, a negative principal moment, or principal moments breaking the
    triangle inequality I1 <= I2 + I3, each beyond :data:`mechsing.numeric.tolerances.INERTIA_RTOL`
    times the trace (the importers ask it too)."""
    a = np.array(to_float(np.array(rows, dtype=object)), dtype=float).reshape(3, 3)
    scale = max(abs(float(np.trace(a))), float(np.abs(a).max()), 1e-300)
    tol = INERTIA_RTOL * scale
    if not np.all(np.isfinite(a)):
        return "is not finite"
    if np.abs(a - a.T).max() > tol:
        return "is not symmetric; give a symmetric matrix (or the six numbers ixx, iyy, izz, ixy, ixz, iyz)"
    ev = np.linalg.eigvalsh((a + a.T) / 2)
    if ev[0] < -tol:
        return (
            f"has a negative principal moment ({ev[0]:.6g}): it is not positive "
            "semi-definite; check the signs of the products of inertia"
        )
    if ev[2] > ev[0] + ev[1] + tol:
        return (
            f"has principal moments {ev[0]:.6g}, {ev[1]:.6g}, {ev[2]:.6g}: the largest "
            "exceeds the sum of the other two (the triangle inequality of a rigid body's "
            "moments); no mass distribution has it"
        )
    return None
