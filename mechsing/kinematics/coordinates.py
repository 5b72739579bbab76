"""The coordinate updates of a kinematic model on the group.

Owns the moves between coordinate vectors of a
:class:`~mechsing.kinematics.model.KinematicModel`: a trivialised increment applied on
the group (:func:`update`), the increment between two configurations measured on the
group (:func:`difference`), and the first-kind coordinates of a joint's element
(:func:`coordinates_in`, refined at mp:N), with the float fast path that stacks the
non-abelian joints' exponentials and logarithms.  The model's methods of the same names
call these functions; the caches (the last elements, the commensurate bases) stay
attributes of the model.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing import lie
from mechsing.numeric import to_float
from mechsing.numeric.backend import is_float64
from mechsing.numeric.lazy import mpmath

#: a :class:`~mechsing.kinematics.model.KinematicModel` (which imports this module)
KinematicModel = Any
#: a :class:`~mechsing.kinematics.model.JointKinematics`
JointKinematics = Any

__all__ = ["coordinates_in", "difference", "update"]


def update(model: KinematicModel, q: np.ndarray, delta: np.ndarray) -> np.ndarray:
    """Apply trivialised increments ``delta`` (one per coordinate) on the group:
    ``M <- exp(sum d_i e_i) M`` (coordinates add for abelian joints and U)."""
    out = np.array(q, copy=True)
    # the abelian joints' coordinates add, all in one
    ab = model._abelian_columns
    out[ab] = np.asarray(q)[ab] + np.asarray(delta)[ab]
    if _float_joints(model, q, delta):
        return _update_float(model, q, np.asarray(delta), out)
    for jk in model._non_abelian:
        d = delta[jk.columns]
        # zero tested in the model's numbers: at mp:N beyond float's range (N > 300) a
        # correction of 1e-350 is not zero, and adding it to a non-abelian joint's
        # coordinates would be wrong at first order
        if not any(x != 0 for x in d):
            out[jk.columns] = q[jk.columns] + d
            continue
        M = lie.exp(d @ jk.basis) @ model.element(jk, q)
        out[jk.columns] = coordinates_in(model, jk, M)
    return out


def difference(model: KinematicModel, q1: np.ndarray, q0: np.ndarray) -> np.ndarray:
    """The increments ``d`` (one per coordinate) with ``update(q0, d) == q1``: measured on
    the group, so two coordinate vectors of the same joint pose are no distance apart.

    Coordinates of a non-abelian joint are first-kind coordinates read by the principal
    log (an S joint's rotation vector has norm at most pi); a path through a half-turn
    makes them jump by 2 pi although the joint barely moved.  Steps, corrections and
    distances along a path are therefore compared with this difference, never with
    ``q1 - q0``."""
    d = np.asarray(q1) - np.asarray(q0)
    if model._non_abelian and _float_joints(model, q1, q0):
        # every non-abelian joint at once: the same products, stacked
        M = _elements_of(model, q1) @ lie.inverse(_elements_of(model, q0))
        for jk, x in zip(model._non_abelian, lie.log(M), strict=True):
            d[jk.columns] = _float_coordinates(model, jk, x)
        return d
    for jk in model.joints:
        if jk.abelian:
            continue
        M = model.element(jk, q1) @ lie.inverse(model.element(jk, q0))
        d[jk.columns] = coordinates_in(model, jk, M)
    return d


def _float_joints(model: KinematicModel, *arrays: Any) -> bool:
    """Whether the non-abelian joints of a float model are updated at float
    coordinates (one configuration each): then all together, by stacked exponentials
    and logarithms (:func:`mechsing.lie.exp` and :func:`~mechsing.lie.log` give each
    row of a stack the numbers they give it alone)."""
    return model.backend.name == "float" and all(
        isinstance(a, np.ndarray) and a.ndim == 1 and is_float64(a) for a in arrays
    )


def _elements_of(model: KinematicModel, q: np.ndarray) -> np.ndarray:
    """The elements (k, 4, 4) of the non-abelian joints at the float configuration q:
    :meth:`KinematicModel.element`'s ``exp(q_j B_j)``, stacked (the last configuration's kept)."""
    key = q.tobytes()
    last = model._last_elements  # read once: another thread may replace it
    if last is None or last[0] != key:
        twists = np.stack([q[jk.columns] @ jk.basis for jk in model._non_abelian])
        last = model._last_elements = (key, lie.exp(twists))
    return last[1]


def _update_float(
    model: KinematicModel, q: np.ndarray, delta: np.ndarray, out: np.ndarray
) -> np.ndarray:
    """:func:`update` of the non-abelian joints of a float model, all at once: the
    same ``exp(d_j B_j) M_j`` and coordinates, the exponentials and logarithms stacked."""
    moving = []
    for i, jk in enumerate(model._non_abelian):
        d = delta[jk.columns]
        if not any(x != 0 for x in d):
            out[jk.columns] = q[jk.columns] + d
        else:
            moving.append(i)
    if not moving:
        return out
    joints = [model._non_abelian[i] for i in moving]
    steps = lie.exp(np.stack([delta[jk.columns] @ jk.basis for jk in joints]))
    M = steps @ _elements_of(model, q)[moving]
    for jk, x in zip(joints, lie.log(M), strict=True):
        out[jk.columns] = _float_coordinates(model, jk, x)
    return out


def _float_coordinates(model: KinematicModel, jk: JointKinematics, x: np.ndarray) -> np.ndarray:
    """:func:`coordinates_in` of a float model from the logarithm ``x`` of the element
    (the basis of the joint in the commensurate metric computed once)."""
    B = model._basis_twists.get(jk.name)
    if B is None:
        B = model._basis_twists[jk.name] = model.float_frame.twists(to_float(jk.basis).T)
    xs = model.float_frame.twists(to_float(x)[:, None])[:, 0]
    coef, *_ = np.linalg.lstsq(B, xs, rcond=None)
    return coef


def coordinates_in(model: KinematicModel, jk: JointKinematics, M: np.ndarray) -> np.ndarray:
    """First-kind coordinates of an element of the joint's subgroup (log, then the basis).

    Solved in the commensurate metric (screws moved to the centroid, v / L):
    in raw units a joint far from the origin mixes rows of very different
    sizes and loses the coordinates along its own axis to rounding.

    At mp:N the float solution is refined (iterative refinement: the residual
    ``x - c B`` at N digits, its correction solved in float, each pass gaining
    about 15 digits) until the correction is below the working precision, so
    the coordinates of a non-abelian joint (S, G, Y, X, D) carry N digits and
    Newton at N digits can close a loop to 10^(5-N) L.
    """
    x = lie.log(M)
    ff = model.float_frame
    B = ff.twists(to_float(jk.basis).T)
    xs = ff.twists(to_float(x)[:, None])[:, 0]
    coef, *_ = np.linalg.lstsq(B, xs, rcond=None)
    bk = model.backend
    if bk.name == "float":  # policy: float's solve is the answer; exact and mp refine
        return coef
    cm = bk.asarray(coef)
    if bk.name == "exact":
        # exact mode only checks given values: one refinement step
        r = x - cm @ jk.basis
        rs = ff.twists(to_float(r)[:, None])[:, 0]
        corr, *_ = np.linalg.lstsq(B, rs, rcond=None)
        return cm + bk.asarray(corr)
    for _pass in range(_refinement_passes()):
        r = x - cm @ jk.basis
        # normalised before the float solve: at N > 300 digits the residual itself
        # would underflow in float
        size = max(abs(v) for v in r)
        if not size:
            break
        rs = ff.twists(to_float(r / size)[:, None])[:, 0]
        corr, *_ = np.linalg.lstsq(B, rs, rcond=None)
        step = bk.asarray(corr) * size
        cm = cm + step
        if max(abs(v) for v in step) <= mpmath.mp.eps * max(1, max(abs(v) for v in cm)):
            break
    return cm


def _refinement_passes() -> int:
    """Most iterative-refinement passes of :func:`coordinates_in` at the
    working precision: a float solve gains at least 10 digits per pass (the commensurate
    bases are well conditioned), plus two to spare."""
    return mpmath.mp.dps // 10 + 2
