"""The nodes of a path: predicting the next closed configuration and keeping it.

Owns the node step of :func:`~mechsing.kinematics.paths.follow.follow`: which sample is the next
node (:func:`node_index`: at most :data:`~mechsing.numeric.SWEEP_NODE_STEP` on), its
prediction (the tangent at a first step, the secant or the polynomial through the last
nodes after that), and :func:`reach_node`: one batched Newton from the prediction, kept
when the correction is small next to the step and the step itself not too long
(:func:`node_bounds`; the step halved when it is not).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing.kinematics.paths.problem import Problem
from mechsing.kinematics.paths.steps import closure_matrix, tangent_increment
from mechsing.kinematics.settings import SWEEP_NODE_CORRECTION, SWEEP_NODE_STEP, SWEEP_NODE_SWING

__all__ = [
    "node_bounds",
    "node_index",
    "polynomial_prediction",
    "reach_node",
    "tangent_points",
    "tangent_step",
]

#: unit predictor steps a Problem keeps (by column and configuration; a grid's rows are
#: started together, each asking once per direction)
_PREDICTORS_KEPT = 4096
#: a badly predicted node is tried again in this many halvings of its step
_NODE_HALVINGS = 3


def node_index(values: np.ndarray, i: int, sc: float) -> int:
    """The next node after sample i: the farthest sample at most SWEEP_NODE_STEP away
    (and at least the next one)."""
    j = i + 1
    while j + 1 < len(values) and abs(values[j + 1] - values[i]) / sc <= SWEEP_NODE_STEP:
        j += 1
    return j


def reach_node(
    pb: Problem,
    z: np.ndarray,
    z_prev: np.ndarray | None,
    col: int,
    value: float,
    older: list[np.ndarray] | None = None,
) -> np.ndarray | None:
    """The next node by :func:`_node`, in halved steps when the whole one is not well
    predicted (at most _NODE_HALVINGS times), before the careful continuation.
    ``older``: the nodes before z_prev on the same stretch of the path (oldest first)."""
    parts = 1
    for attempt in range(_NODE_HALVINGS + 1):
        # the previous nodes' extrapolation, then the tangent (a secant from a point just
        # behind): a far previous node predicts a short step no better than a long one
        here, prev = z, (z_prev if attempt == 0 else None)
        start = float(z[col])
        for k in range(1, parts + 1):
            nxt = _node(
                pb,
                here,
                prev,
                col,
                start + (value - start) * k / parts,
                older if attempt == 0 and k == 1 else None,
            )
            if nxt is None:
                break
            here, prev = nxt, here
        else:
            return here
        parts *= 2
    return None


def _node(
    pb: Problem,
    z: np.ndarray,
    z_prev: np.ndarray | None,
    col: int,
    value: float,
    older: list[np.ndarray] | None = None,
) -> np.ndarray | None:
    """The next node by one batched Newton from the secant predictor (the last step
    repeated, scaled to the new one; with ``older`` nodes before z_prev, the polynomial
    through them all, extrapolated on the group; a first step from the tangent at z);
    None when it does not close there or its correction is not small next to the step
    (the careful continuation then takes it)."""
    bc = pb.batch
    if z_prev is None or z_prev[col] == z[col]:
        # a first step: the tangent predictor at z (no Newton) predicts it
        zp = _tangent_prediction(pb, z, col, value)
        if zp is not None:
            Q, ok, _ = pb.close_near(zp[None, :], node_bounds(pb, zp[None, :], z[None, :]))
            if ok[0]:
                return Q[0]
        # where the tangent's step is not kept: a point a thousandth of it behind,
        # closed from z itself, gives the secant (the tangent, to first order)
        zq = np.array(z, dtype=float)
        zq[col] = z[col] - 1e-3 * (value - z[col])
        Q, ok, _ = pb.close_near(zq[None, :], np.inf)
        if not ok[0]:
            return None
        z_prev = Q[0]
    zp = polynomial_prediction(pb, z, z_prev, col, value, older)
    if zp is None:
        # the last step repeated, scaled to the new one: z_prev -> z continued past z
        f = (value - z[col]) / (z[col] - z_prev[col])
        zp = bc.between(z[None, :], z_prev[None, :], np.array([-f]))[0]
    zp[col] = value
    Q, ok, _ = pb.close_near(zp[None, :], node_bounds(pb, zp[None, :], z[None, :]))
    return Q[0] if ok[0] else None


def node_bounds(pb: Problem, preds: np.ndarray, Z: np.ndarray) -> np.ndarray:
    """How far Newton may move each predicted node (the rows of ``preds``, predicted from
    the rows of Z) for it to be kept: SWEEP_NODE_CORRECTION of its predicted step.  A
    prediction that swings further than SWEEP_NODE_SWING (passive joints included) is not
    kept at all (bound -1), however small its correction: the step is halved."""
    swing = np.linalg.norm(pb.cm.float_frame.rates(preds - Z), axis=1)
    return np.where(swing <= SWEEP_NODE_SWING, SWEEP_NODE_CORRECTION * swing, -1.0)


def polynomial_prediction(
    pb: Problem,
    z: np.ndarray,
    z_prev: np.ndarray,
    col: int,
    value: float,
    older: list[np.ndarray] | None,
) -> np.ndarray | None:
    """:func:`_node`'s prediction through the older nodes: the polynomial through them,
    z_prev and z (increments on the group from z), at ``value``; None when there are no
    older nodes of distinct values (the secant predicts then)."""
    bc = pb.batch
    knots = [p for p in (older or []) if p[col] != z[col]]
    if not (knots and len({float(p[col]) for p in [*knots, z_prev, z]}) == len(knots) + 2):
        return None
    pts = np.array([*knots, z_prev])
    D = bc.difference(pts, np.repeat(np.asarray(z, dtype=float)[None, :], len(pts), 0))
    tk = np.concatenate([pts[:, col], [z[col]]])
    D = np.concatenate([D, np.zeros((1, D.shape[1]))])
    w = np.ones(len(tk))
    for a in range(len(tk)):
        for b in range(len(tk)):
            if a != b:
                w[a] *= (value - tk[b]) / (tk[a] - tk[b])
    d = w @ D
    zp = bc.update(np.asarray(z, dtype=float)[None, :], d[None, : bc.nb])[0]
    zp[bc.nb :] = z[bc.nb :] + d[bc.nb :]
    return zp


def _tangent_prediction(pb: Problem, z: np.ndarray, col: int, value: float) -> np.ndarray | None:
    """The point of the tangent predictor at z where coordinate ``col`` is ``value`` (on
    the group, as :meth:`BatchClosure.update` moves), or None where it is not finite."""
    d = tangent_step(pb, z, col, value)
    if d is None:
        return None
    return tangent_points(pb, np.asarray(z, dtype=float)[None, :], d[None, :], col, [value])[0]


def tangent_step(pb: Problem, z: np.ndarray, col: int, value: float) -> np.ndarray | None:
    """The increment of the tangent predictor (:func:`~.steps.tangent_increment`, the one
    continuation's steps take) at z that takes coordinate ``col`` to ``value``, the other
    given coordinates held (None where it is not finite).  The predictor is linear in the
    step: the one of a unit step is kept (in ``pb.predictors``): a row's start asks for it
    once per direction."""
    key = (col, np.asarray(z, dtype=float).tobytes())
    unit = pb.predictors.get(key)
    if unit is None:
        z = np.asarray(z, dtype=float)
        dg = np.zeros(pb.n)
        dg[col] = pb.scale(col)
        unit = tangent_increment(pb.cm, closure_matrix(pb.cm, z), dg, pb.given)
        if len(pb.predictors) >= _PREDICTORS_KEPT:
            pb.predictors.pop(next(iter(pb.predictors)))
        pb.predictors[key] = unit
    d = unit * ((value - float(z[col])) / pb.scale(col))
    return d if np.all(np.isfinite(d)) else None


def tangent_points(pb: Problem, Z: np.ndarray, D: np.ndarray, col: int, values: Any) -> np.ndarray:
    """The points reached from the rows of Z by the increments D (:func:`tangent_step`),
    on the group, with ``col`` set to ``values``: one batched update for every row."""
    bc = pb.batch
    zp = bc.update(Z, D[:, : bc.nb])
    zp[:, bc.nb :] = Z[:, bc.nb :] + D[:, bc.nb :]
    zp[:, col] = values
    return zp
