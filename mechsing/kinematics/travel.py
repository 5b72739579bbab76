"""Given values beyond a limit of travel: which value, and by how much.

A configuration whose given values lie just beyond a fold of the closure (a dead centre
of a slider, the limit of a rocker) has no solution: Newton on the unknown joints stops
at the fold, where the closure Jacobian in the unknowns loses rank, with a residual
left along its left kernel u.  To first order the residual's component ``u . r`` there
is what the given values add beyond the fold, ``u . J_g dg``: so each given value alone
is ``|u . r| / |u . J_g e_i|`` beyond its limit (commensurate units: lengths over L).

Owns :func:`fold_excess` (which given value is nearest to bringing the configuration
back, the one the residual is most sensitive to, how far beyond its limit it is and where
that limit is) and :func:`beyond_travel`, the sentence that says so (in the file's units).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mechsing.kinematics.newton import damped_least_squares, newton_on_group, scaled_system
from mechsing.kinematics.protocol import ClosureModel
from mechsing.kinematics.settings import (
    CONTINUATION_SINGULAR_RTOL,
    POLISH_MAX_STEPS,
    TRAVEL_RESIDUAL_ALIGNMENT,
)
from mechsing.numeric import to_float
from mechsing.numeric.lazy import mpmath
from mechsing.numeric.linalg import svd

__all__ = ["Fold", "beyond_target", "beyond_travel", "fold_excess"]


@dataclass(frozen=True)
class Fold:
    """Given values beyond a limit of travel (:func:`fold_excess`): the coordinate ``col``
    the fold is most sensitive to, how far beyond its limit it is (``beyond``, SI: m or
    rad) and the sentence that says so in the file's units."""

    col: int
    beyond: float
    sentence: str


def beyond_travel(m: ClosureModel, q: np.ndarray, gmask: np.ndarray) -> str | None:
    """The sentence of :func:`fold_excess` (None when the configuration is not beyond a
    limit of travel)."""
    fold = fold_excess(m, q, gmask)
    return None if fold is None else fold.sentence


def fold_excess(m: ClosureModel, q: np.ndarray, gmask: np.ndarray) -> Fold | None:
    """Why configuration ``q`` of model ``m`` (its given coordinates ``gmask``, the others
    solved as far as they go) does not close, when it is beyond a limit of travel: the
    unknown joints' Jacobian is singular there (relative smallest singular value at most
    CONTINUATION_SINGULAR_RTOL), or the residual left lies along the direction they
    cannot correct (at least TRAVEL_RESIDUAL_ALIGNMENT of it along the left singular
    vector of their smallest singular value).  None otherwise (or without unknowns)."""
    free = ~np.asarray(gmask, dtype=bool)
    if not np.any(free) or not np.any(~free) or not m.chords:
        return None
    with m.precision.context():
        Js, rs = scaled_system(m, q, False)
        Js = Js.toarray() if hasattr(Js, "toarray") else Js
        U, s, _vt = svd(m.precision.asarray(Js)[:, free])
        sv = [float(x) for x in s]
        if not sv or not sv[0]:
            return None
        # the left singular vector of the smallest singular value: the direction the
        # unknowns cannot correct (structural zero rows, such as a planar loop's
        # out-of-plane ones, are further left kernel vectors that the residual and the
        # given columns have no part in)
        u = np.asarray(to_float(U[:, len(s) - 1]), dtype=float)
        F = np.asarray(to_float(rs), dtype=float)
        r = float(u @ F)
        g = u @ np.asarray(to_float(Js[:, ~free]), dtype=float)
    # stuck at a fold: the unknowns' Jacobian is singular there (Newton at N digits stops
    # within 10^(-N/2) of it), or what is left of the residual is what they cannot correct
    # (float's least squares stopping short of the fold)
    at_fold = sv[-1] <= CONTINUATION_SINGULAR_RTOL * sv[0]
    stuck = abs(r) >= TRAVEL_RESIDUAL_ALIGNMENT * float(np.linalg.norm(F))
    if not np.any(g) or not (at_fold or stuck):
        return None
    i = int(np.argmax(np.abs(g)))  # the given value the fold is most sensitive to
    col = int(np.flatnonzero(~free)[i])
    length = bool(m.length_columns[col])
    scale = m.length_scale if length else 1.0
    # in the file's units (as the continuation's messages are)
    units = m.mech.units
    factor = float(units.length_factor if length else units.angle_factor)
    unit = units.length if length else units.angle
    beyond_si = abs(r / g[i]) * scale
    beyond = beyond_si / factor
    with m.precision.context():  # the limit at the model's digits (q is given to them)
        limit = (mpmath.mpf(q[col]) - mpmath.mpf(r / g[i] * scale)) / mpmath.mpf(factor)
    # first order: the limit is known to about the square of the distance beyond it
    rel = max(beyond / max(abs(float(limit)), 1e-300), 1e-16)
    shown = mpmath.nstr(limit, max(3, min(16, int(-math.log10(rel)))))
    coords = m.mech.coordinates()
    if col < len(coords):
        label = m.mech.coordinate_label(*coords[col])
    else:  # a pose model's own coordinates follow the joints'
        from mechsing.kinematics.pose import POSE_COORDINATES

        label = POSE_COORDINATES[col - len(coords)]
    sentence = (
        f"its given values are beyond a limit of travel (a fold of the closure, where the "
        f"unknown joints lose a direction): {label} is {beyond:.3g} {unit} beyond its limit "
        f"at about {label} = {shown} {unit}; give {label} within its travel"
    )
    return Fold(col, float(beyond_si), sentence)


def beyond_target(
    fm: ClosureModel, q: np.ndarray, target: np.ndarray, gmask: np.ndarray
) -> str | None:
    """:func:`beyond_travel` for a continuation (float model ``fm``) that stalled at ``q``
    short of ``target``: the unknown joints are first brought as near closure as they go
    with the given values at the target (Newton, least squares: it stops at the fold
    when the target is beyond one)."""
    qn = np.asarray(q, dtype=float).copy()
    qn[gmask] = np.asarray(target, dtype=float)[gmask]
    landed = newton_on_group(
        fm, qn, ~gmask, solve=damped_least_squares, max_steps=POLISH_MAX_STEPS, doubling=True
    )
    return beyond_travel(fm, landed.q, gmask)
