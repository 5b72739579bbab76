"""The inverse dynamics of a closed chain: the inputs' efforts for a motion of the inputs.

The mechanism's spanning tree carries the bodies (:class:`~mechsing.kinetics.tree.TreeDynamics`
on the tree's joints: a chord joint moves no body of its own); the loops close it.  With
``C`` the closure system at the configuration (each chord's block of six rows: the signed
current screws of its loop's joints, SI twists at the ground origin,
:meth:`mechsing.kinematics.KinematicModel.closure_jacobian`):

* velocity: ``C qd = 0`` with the inputs' rates given: ``[C; E] qd = [0; u]``;
* acceleration: ``C qdd + Cdot qd = 0``, where the rate of each column is the Lie bracket
  of the twist of the joint's first body with it (``s_k' = [xi_a, s_k]``: the closure
  written at acceleration level on the Lie algebra), with the inputs' accelerations given;
* efforts: the tree's efforts ``tau = M qdd + bias`` (zero on the chords' coordinates) are
  balanced by the inputs' efforts and the loops' constraint wrenches (the multipliers
  ``lambda``, one wrench per loop): ``E^T tau_in + C^T lambda = tau`` (virtual work), solved
  in the least-squares sense; a residual means the inputs cannot produce the motion's
  efforts (a Type II singularity), and its size is reported.

Forward dynamics (:func:`closed_forward`): with ``N`` the passive motions of unit input
rates (``[C; E] N = [0; 1]``) and ``qdd_0`` the acceleration of zero input accelerations,
every admissible acceleration is ``qdd_0 + N udd``, and virtual work along the admissible
motions (``N^T C^T = 0``, ``N^T E^T = 1``) gives the inputs' equation
``N^T M N udd = tau_in - N^T (M qdd_0 + bias)``: the mass matrix reduced to the inputs.

Owns :func:`closed_inverse` and :func:`closed_forward`, and their parts: the closure's
rate (:func:`closure_rate`), a motion driven by any rows of the rates
(:func:`driven_motion`: a sweep's timed motion drives its swept coordinate) and the
effort balance (:func:`balance`).  Float only.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing import lie

__all__ = [
    "ClosedMotion",
    "balance",
    "closed_forward",
    "closed_inverse",
    "closure_rate",
    "driven_motion",
]


@dataclass(frozen=True)
class ClosedMotion:
    """A closed chain's motion and efforts at one configuration (SI, coordinate order):
    every coordinate's rate and acceleration, every coordinate's effort (the inputs'
    efforts on the inputs, 0 on the passive joints), the loops' multipliers (a wrench per
    loop, at the ground origin) and the relative residual of the effort balance."""

    qd: np.ndarray
    qdd: np.ndarray
    efforts: np.ndarray
    multipliers: np.ndarray
    residual: float
    tree_efforts: np.ndarray


def _solve(A: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, float]:
    x, *_ = np.linalg.lstsq(A, b, rcond=None)
    scale = max(float(np.linalg.norm(b)), float(np.linalg.norm(A) * np.linalg.norm(x)), 1e-300)
    return x, float(np.linalg.norm(A @ x - b)) / scale


def _closure_and_inputs(
    model: Any, q: np.ndarray, inputs: list[int]
) -> tuple[np.ndarray, np.ndarray]:
    """The closure's Jacobian at ``q`` (float) and the rows selecting the inputs'
    coordinates ``inputs`` among the model's."""
    C = np.asarray(model.closure_jacobian(q), dtype=float)
    E = np.zeros((len(inputs), model.n))
    E[np.arange(len(inputs)), inputs] = 1.0
    return C, E


def closure_rate(td: Any, q: np.ndarray, C: np.ndarray, qd: np.ndarray) -> np.ndarray:
    """``Cdot qd``: the rate of the closure's rows along the motion ``qd`` at ``q``, each
    column's the Lie bracket of the twist of its joint's first body with it
    (``s_k' = [xi_a, s_k]``), times the column's rate."""
    _, xi, _, _ = td.motion(q, qd, None, False)
    rate = np.zeros(C.shape[0])
    for jk in td.model.joints:
        k = jk.columns.start
        col = C[:, k]
        if not np.any(col):
            continue
        twist = xi.get(jk.a)
        for b in range(0, C.shape[0], 6):
            rate[b : b + 6] += lie.bracket(twist, col[b : b + 6]) * qd[k]
    return rate


def driven_motion(
    td: Any,
    q: np.ndarray,
    C: np.ndarray,
    G: np.ndarray,
    v: np.ndarray,
    a: np.ndarray,
    drift: Any = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Every coordinate's rate and acceleration at the closed ``q`` when the rows ``G``
    of the rates are driven: ``[C; G] qd = [0; v]`` and
    ``[C; G] qdd = [-Cdot qd; a - drift(qd)]`` (``drift``: the part of the driven rows'
    second derivative that is not ``G qdd``, a function of the rates; None: rows of
    constant coefficients, the coordinates themselves)."""
    K = np.vstack([C, G])
    qd, _ = _solve(K, np.concatenate([np.zeros(C.shape[0]), v]))
    rhs = np.asarray(a, dtype=float) - (0.0 if drift is None else drift(qd))
    qdd, _ = _solve(K, np.concatenate([-closure_rate(td, q, C, qd), rhs]))
    return qd, qdd


def balance(C: np.ndarray, E: np.ndarray, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    """The inputs' efforts (every coordinate's: 0 off the inputs ``E`` selects), the
    loops' multipliers and the relative residual of ``E^T tau_in + C^T lambda = tau``
    (virtual work) for the tree's efforts ``tau``."""
    x, residual = _solve(np.hstack([E.T, C.T]), tau)
    m = E.shape[0]
    return E.T @ x[:m], x[m:], residual


def closed_inverse(
    td: Any, q: np.ndarray, inputs: list[int], u: np.ndarray, udd: np.ndarray
) -> ClosedMotion:
    """The motion and efforts of the closed chain of ``td`` (its model in float) at the
    closed configuration ``q`` for the inputs' coordinates ``inputs`` moving with the rates
    ``u`` and the accelerations ``udd``."""
    q = np.asarray(q, dtype=float)
    C, E = _closure_and_inputs(td.model, q, inputs)
    qd, qdd = driven_motion(td, q, C, E, u, udd)
    qd[inputs] = u  # the inputs' rates as given (the solve returns them to rounding)
    qdd[inputs] = udd
    tau = td.inverse(q, qd, qdd)
    efforts, multipliers, residual = balance(C, E, tau)
    return ClosedMotion(qd, qdd, efforts, multipliers, residual, tau)


def closed_forward(
    td: Any, q: np.ndarray, inputs: list[int], u: np.ndarray, tau_in: np.ndarray
) -> np.ndarray:
    """The inputs' accelerations under the inputs' efforts ``tau_in`` at the closed
    configuration ``q`` with the inputs' rates ``u`` (the reduced equation of the module
    docstring); every coordinate's acceleration."""
    q = np.asarray(q, dtype=float)
    C, E = _closure_and_inputs(td.model, q, inputs)
    K = np.vstack([C, E])
    rhs = np.vstack([np.zeros((C.shape[0], len(inputs))), np.eye(len(inputs))])
    N, *_ = np.linalg.lstsq(K, rhs, rcond=None)
    still = closed_inverse(td, q, inputs, u, np.zeros(len(inputs)))
    M = np.asarray(td.mass_matrix(q), dtype=float)
    reduced = N.T @ M @ N
    udd = np.linalg.solve(reduced, np.asarray(tau_in, dtype=float) - N.T @ still.tree_efforts)
    return still.qdd + N @ udd
