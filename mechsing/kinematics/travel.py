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
between the value continuation reached and the target, where the fold must be.  Else the
given values are moved only a little past the value reached (a millionth of the way
left, then ten times more, up to a tenth), where the first landing that does not close
is near the fold again and places it (the target's excess is then measured from it);
where none does, the sentence says the interval instead.  The estimate is first order
in where the landing stops along the unknowns' weak direction, which converges slowly
at a fold: right to about a fifth of the distance past the limit it was read at, which
the digits it is written to allow for.

Owns :func:`fold_excess` (which given value is nearest to bringing the configuration
back, the one the residual is most sensitive to, how far beyond its limit it is and where
that limit is), :func:`beyond_travel`, the sentence that says so (in the file's units),
:func:`beyond_target`, the same for a continuation stalled short of its target, and
:func:`coordinate_words`, a coordinate's label and unit in those messages.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

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


def fold_excess(
    m: ClosureModel, q: np.ndarray, gmask: np.ndarray, gate: bool = True
) -> Fold | None:
    """Why configuration ``q`` of model ``m`` (its given coordinates ``gmask``, the others
    solved as far as they go) does not close, when it is beyond a limit of travel: the
    unknown joints' Jacobian is singular there (relative smallest singular value at most
    CONTINUATION_SINGULAR_RTOL), or the residual left lies along the direction they
    cannot correct (at least TRAVEL_RESIDUAL_ALIGNMENT of it along the left singular
    vector of their smallest singular value).  None otherwise (or without unknowns).
    ``gate=False``: the estimate along that direction whatever the two tests say, for a
    caller with its own evidence of a fold (:func:`_fold_past`)."""
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
    if not np.any(g) or (gate and not (at_fold or stuck)):
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
    return Fold(
        col, float(beyond_si), _sentence(label, unit, beyond, beyond, limit), float(limit_si)
    )


def _sentence(label: str, unit: str, beyond: float, known: float, limit: Any) -> str:
    """The sentence of a value ``beyond`` its ``limit`` (the file's units), the limit
    written to the digits of the distance ``known`` past it that its first-order
    estimate was read at (it is right to about a fifth of that distance: the module
    docstring; its last digit may be off by one)."""
    rel = max(known / max(abs(float(limit)), 1e-300), 1e-16)
    shown = mpmath.nstr(limit, max(3, min(16, int(-math.log10(rel)))))
    return (
        f"{_LEAD}: {label} is {beyond:.3g} {unit} beyond its limit "
        f"at about {label} = {shown} {unit}; give {label} within its travel"
    )


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
    landed = _landed(fm, qn, gmask)
    fold = fold_excess(fm, landed.q, gmask)
    if fold is not None:
        reached, goal = float(q[fold.col]), float(qn[fold.col])
        if min(reached, goal) <= fold.limit <= max(reached, goal):
            return fold.sentence
    # the least squares at a target far beyond the fold need not land near it: the fold
    # placed again from just past the value reached (where the estimate is sound), the
    # target's excess measured from it
    near = _fold_past(fm, np.asarray(q, dtype=float), qn, gmask)
    if near is not None:
        label, unit, factor, _ = coordinate_words(fm, near.col)
        beyond = abs(float(qn[near.col]) - near.limit) / factor
        limit = mpmath.mpf(near.limit) / mpmath.mpf(factor)
        return _sentence(label, unit, beyond, near.beyond / factor, limit)
    if fold is None:
        return None
    reached, goal = float(q[fold.col]), float(qn[fold.col])
    label, unit, factor, _ = coordinate_words(fm, fold.col)
    if reached == goal:  # the fold is most sensitive to a value the path does not change
        return f"{_LEAD}, between the given values continuation reached and the target"
    return (
        f"{_LEAD}: {label} is at most {abs(goal - reached) / factor:.3g} {unit} beyond its "
        f"limit, which lies past {label} = {reached / factor:.10g} {unit}, the value "
        f"continuation reached; give {label} within its travel"
    )


#: the fractions of the way from the value continuation reached to its target at which
#: :func:`_fold_past` lands, nearest first (continuation stalls within about 1e-5 of a
#: fold; a probe just past it places the fold to about a fifth of its distance past it)
_PROBES = tuple(10.0**-k for k in range(6, 0, -1))


def _fold_past(
    fm: ClosureModel, q: np.ndarray, target: np.ndarray, gmask: np.ndarray
) -> Fold | None:
    """The fold between the configuration ``q`` continuation reached and the given
    values ``target`` beyond it: the given values moved a fraction of the way
    (:data:`_PROBES`, nearest first), the unknowns landed by least squares there.  The
    first landing that does not close is the evidence: its first-order estimate
    (:func:`fold_excess` ungated: the landing minimises another norm of the residual
    than the one it is read in, so the residual's alignment with the weakest direction
    is no sure test this near the fold) gives the fold when it lies between ``q`` and
    the probe.  None otherwise (a probe that closes is still within the travel)."""
    tol = fm.precision.closure_tolerance(fm.length_scale)
    for f in _PROBES:
        qp = q.copy()
        qp[gmask] = q[gmask] + f * (target[gmask] - q[gmask])
        landed = _landed(fm, qp, gmask)
        if landed.residual <= tol:
            continue
        fold = fold_excess(fm, landed.q, gmask, gate=False)
        if fold is None:
            return None
        reached, probe = float(q[fold.col]), float(qp[fold.col])
        goal = float(target[fold.col])
        between = min(reached, probe) <= fold.limit <= max(reached, probe)
        ahead = (goal - probe) * (probe - reached) >= 0  # the target lies past the probe
        return fold if between and ahead else None
    return None


def _landed(fm: ClosureModel, q: np.ndarray, gmask: np.ndarray) -> Any:
    """The unknown joints of ``q`` brought as near closure as they go with its given
    values held: Newton by damped least squares, a slow step doubled (it stops at the
    fold when the given values are beyond one)."""
    return newton_on_group(
        fm, q, ~gmask, solve=damped_least_squares, max_steps=POLISH_MAX_STEPS, doubling=True
    )
