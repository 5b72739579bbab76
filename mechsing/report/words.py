"""Screws in words: a twist, a wrench, a point velocity or a subgroup as a phrase a
student reads ("a rotation about the axis through (4, 0, 0) along z").

Owns :func:`twist_words`, :func:`wrench_words`, :func:`velocity_words` and
:func:`subgroup_words`.  Conventions: SI at the ground origin; a twist is (omega, v)
(rad/s, m/s: ``v`` is the velocity of the body point at the origin), a wrench (f, m)
(N, N m: ``m`` the moment about the origin).  A twist with omega != 0 is a screw about
the axis through ``p = omega x v / |omega|^2`` along omega with pitch
``h = omega . v / |omega|^2`` (m/rad): a rotation when h = 0, a translation along v when
omega = 0 (infinite pitch).  A wrench with f != 0 is a force along f through
``p = f x m / |f|^2`` with pitch ``h = f . m / |f|^2`` (m): a pure force when h = 0, a
couple along m when f = 0.  "Zero" is decided relative to the screw's own size with
:data:`mechsing.numeric.MEMBERSHIP_RTOL_FLOAT` (angular parts times the length scale L,
so the decision does not depend on the unit of length).  Directions are shown as unit
vectors (``x``, ``-z`` when along a coordinate axis), numbers to 4 significant digits.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from mechsing.analysis.contract import subgroup_params
from mechsing.numeric import MEMBERSHIP_RTOL_FLOAT, first_nonzero_positive, unit_vector
from mechsing.subgroups import Subgroup

__all__ = [
    "subgroup_words",
    "twist_words",
    "velocity_space_words",
    "velocity_words",
    "wrench_words",
]

_AXES = ("x", "y", "z")


def _num(x: float, scale: float = 1.0) -> str:
    """``x`` to 4 significant digits; rounding-level values (next to ``scale``) as 0."""
    if abs(x) <= MEMBERSHIP_RTOL_FLOAT * max(scale, 1e-300):
        return "0"
    return f"{x:.4g}"


def _direction(u: np.ndarray) -> str:
    """A direction: ``x``, ``-y``, ... along a coordinate axis, else its unit vector."""
    u = unit_vector(u)
    for i, name in enumerate(_AXES):
        rest = np.delete(u, i)
        if np.all(np.abs(rest) <= MEMBERSHIP_RTOL_FLOAT):
            return name if u[i] > 0 else f"-{name}"
    return "(" + ", ".join(_num(float(c)) for c in u) + ")"


def _point(p: np.ndarray, length_scale: float) -> str:
    return "(" + ", ".join(_num(float(c), length_scale) for c in p) + ")"


def twist_words(twist: Sequence[float], length_scale: float = 1.0) -> str:
    """A twist (omega, v) in words: a rotation, a translation or a screw with its axis."""
    t = np.asarray(twist, dtype=float)
    w, v = t[:3], t[3:6]
    nw, nv = float(np.linalg.norm(w)), float(np.linalg.norm(v))
    L = float(length_scale)
    if nw * L <= MEMBERSHIP_RTOL_FLOAT * nv:
        if nv == 0.0:
            return "no motion"
        return f"a translation along {_direction(v)}"
    p = np.cross(w, v) / nw**2
    h = float(w @ v) / nw**2
    where = f"the axis through {_point(p, L)} m along {_direction(w)}"
    if abs(h) * nw <= MEMBERSHIP_RTOL_FLOAT * max(nv, nw * L):
        return f"a rotation about {where}"
    return f"a screw motion of pitch {h:.4g} m/rad about {where}"


def wrench_words(wrench: Sequence[float], length_scale: float = 1.0) -> str:
    """A wrench (f, m) in words: a force along a line, a couple, or a wrench with pitch."""
    x = np.asarray(wrench, dtype=float)
    f, m = x[:3], x[3:6]
    nf, nm = float(np.linalg.norm(f)), float(np.linalg.norm(m))
    L = float(length_scale)
    if nf * L <= MEMBERSHIP_RTOL_FLOAT * nm:
        if nm == 0.0:
            return "no load"
        return f"a couple about {_direction(m)}"
    p = np.cross(f, m) / nf**2
    h = float(f @ m) / nf**2
    where = f"along {_direction(f)} through {_point(p, L)} m"
    if abs(h) * nf <= MEMBERSHIP_RTOL_FLOAT * max(nm, nf * L):
        return f"a force {where}"
    return f"a force {where} with a couple along it (a wrench of pitch {h:.4g} m)"


def velocity_words(velocity: Sequence[float]) -> str:
    """A point's velocity in words (its direction)."""
    v = np.asarray(velocity, dtype=float)
    if not np.any(v):
        return "the point stays still"
    return f"the point moves along {_direction(v)}"


def velocity_space_words(velocities: Sequence[Sequence[float]]) -> str:
    """A space of point velocities (a basis) in words: still, along a line, in a plane
    (named by its normal), or in every direction."""
    V = [np.asarray(v, dtype=float) for v in velocities]
    if not V:
        return "stays still"
    if len(V) == 1:
        return f"moves along {_direction(V[0])} only"
    if len(V) == 2:
        n = np.cross(V[0], V[1])
        n = first_nonzero_positive(n)
        return f"moves in the plane normal to {_direction(n)}"
    return "moves in every direction"


def subgroup_words(sub: Subgroup) -> str:
    """A subgroup with its name and geometry: ``R (rotation about an axis (revolute)):
    axis z through (4, 0, 0) m``."""
    parts = []
    for k, val in subgroup_params(sub).items():
        kind = dict(sub.type.parameters)[k]
        if kind == "point":
            parts.append(f"{k} {_point(np.asarray(val, dtype=float), 1.0)} m")
        elif kind == "pitch":
            parts.append(f"pitch {float(val):.4g} m/rad")
        else:
            parts.append(f"{k} {_direction(np.asarray(val, dtype=float))}")
    tail = f": {', '.join(parts)}" if parts else ""
    return f"{sub.symbol} ({sub.type.name}, dimension {sub.dim}){tail}"


def describe(x: Any, kind: str, length_scale: float = 1.0) -> str:
    """``twist``, ``wrench`` or ``velocity`` in words (a 3-vector twist is a velocity)."""
    if kind == "wrench":
        return wrench_words(x, length_scale)
    if len(x) == 3:
        return velocity_words(x)
    return twist_words(x, length_scale)
