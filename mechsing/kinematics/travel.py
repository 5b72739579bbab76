"""Given values beyond a limit of travel: which value, and by how much.

A configuration whose given values lie just beyond a fold of the closure (a dead centre
of a slider, the limit of a rocker) has no solution: Newton on the unknown joints stops
at the fold, where the closure Jacobian in the unknowns loses rank, with a residual
left along its left kernel u.  To first order the residual's component ``u . r`` there
is what the given values add beyond the fold, ``u . J_g dg``: so each given value alone
is ``|u . r| / |u . J_g e_i|`` beyond its limit (commensurate units: lengths over L).

The estimate is sound only near the fold.  A continuation that stalls short of a target
far beyond a limit (:func:`beyond_target`) lands the unknowns by least squares with the
given values at the target, far from the fold, where the first-order limit can be
anywhere (a rocker's limit 2 pi/3 read as -2.0): such a limit is kept only when it lies
between the value continuation reached and the target, where the fold must be; else the
sentence says that interval instead.

Owns :func:`fold_excess` (which given value is nearest to bringing the configuration
back, the one the residual is most sensitive to, how far beyond its limit it is and where
that limit is), :func:`beyond_travel`, the sentence that says so (in the file's units),
:func:`beyond_target`, the same for a continuation stalled short of its target, and
:func:`coordinate_words`, a coordinate's label and unit in those messages.
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

__all__ = ["Fold", "beyond_target", "beyond_travel", "coordinate_words", "fold_excess"]


@dataclass(frozen=True)
class Fold:
    """Given values beyond a limit of travel (:func:`fold_excess`): the coordinate ``col``
    the fold is most sensitive to, how far beyond its limit it is (``beyond``, SI: m or
    rad), the first-order limit itself (``limit``, SI) and the sentence that says so in
    the file's units."""

    col: int
    beyond: float
    sentence: str
    limit: float


_LEAD = (
    "its given values are beyond a limit of travel (a fold of the closure, where the "
    "unknown joints lose a direction)"
)


def coordinate_words(m: ClosureModel, col: int) -> tuple[str, str, float, float]:
    """Coordinate ``col``'s label, the file's unit for it, that unit's SI factor and the
    model's scale of it (L for a length, 1 for an angle)."""
    length = bool(m.length_columns[col])
    units = m.mech.units
    coords = m.mech.coordinates()
    if col < len(coords):
        label = m.mech.coordinate_label(*coords[col])
    else:  # a pose model's own coordinates follow the joints'
        from mechsing.kinematics.pose import POSE_COORDINATES

        label = POSE_COORDINATES[col - len(coords)]
    return (
        label,
        units.length if length else units.angle,
        float(units.length_factor if length else units.angle_factor),
        float(m.length_scale) if length else 1.0,
    )


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
    # in the file's units (as the continuation's messages are)
    label, unit, factor, scale = coordinate_words(m, col)
    beyond_si = abs(r / g[i]) * scale
    beyond = beyond_si / factor
    with m.precision.context():  # the limit at the model's digits (q is given to them)
        limit_si = mpmath.mpf(q[col]) - mpmath.mpf(r / g[i] * scale)
        limit = limit_si / mpmath.mpf(factor)
    # first order: the limit is known to about the square of the distance beyond it
    rel = max(beyond / max(abs(float(limit)), 1e-300), 1e-16)
    shown = mpmath.nstr(limit, max(3, min(16, int(-math.log10(rel)))))
    sentence = (
        f"{_LEAD}: {label} is {beyond:.3g} {unit} beyond its limit "
        f"at about {label} = {shown} {unit}; give {label} within its travel"
    )
    return Fold(col, float(beyond_si), sentence, float(limit_si))


def beyond_target(
    fm: ClosureModel, q: np.ndarray, target: np.ndarray, gmask: np.ndarray
) -> str | None:
    """:func:`beyond_travel` for a continuation (float model ``fm``) that stalled at ``q``
    short of ``target``: the unknown joints are first brought as near closure as they go
    with the given values at the target (Newton, least squares: it stops at the fold
    when the target is beyond one).  The first-order limit is kept only when it lies
    between the value reached at ``q`` and the target (module docstring); else the
    sentence names that interval."""
    qn = np.asarray(q, dtype=float).copy()
    qn[gmask] = np.asarray(target, dtype=float)[gmask]
    landed = newton_on_group(
        fm, qn, ~gmask, solve=damped_least_squares, max_steps=POLISH_MAX_STEPS, doubling=True
    )
    fold = fold_excess(fm, landed.q, gmask)
    if fold is None:
        return None
    reached, goal = float(q[fold.col]), float(qn[fold.col])
    if min(reached, goal) <= fold.limit <= max(reached, goal):
        return fold.sentence
    label, unit, factor, _ = coordinate_words(fm, fold.col)
    if reached == goal:  # the fold is most sensitive to a value the path does not change
        return f"{_LEAD}, between the given values continuation reached and the target"
    return (
        f"{_LEAD}: {label} is at most {abs(goal - reached) / factor:.3g} {unit} beyond its "
        f"limit, which lies past {label} = {reached / factor:.10g} {unit}, the value "
        f"continuation reached; give {label} within its travel"
    )
