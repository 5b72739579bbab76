"""Actuator efforts and constraint wrenches under a load, by virtual work on the motion
test's matrices (:mod:`mechsing.statics.matrices`).

With ``y`` the commensurate load (the wrench the environment applies to the output
body), ``tau`` the actuator efforts and ``lambda`` one wrench per loop (its coordinates
in the loop's subalgebra) the equilibrium of every joint coordinate is

    E^T tau + A^T lambda = -T^T y,

the passive coordinates carrying no effort.  For a serial chain (no A, E = I) this is
``tau = -J^T w``.  Its solvability is the Type II test: the system has a solution iff
the load does no power on the output twists T z of the motions z in K cap ker E (closure
kept, inputs locked).  A non-zero power makes the efforts unbounded; a zero power leaves
them bounded but not unique, and so do redundant actuators.  Among the solutions the
efforts of least (commensurate) norm are given; loop wrenches left free by the null
space are statically indeterminate (an overconstrained loop: only the part within the
loop's subgroup is carried by its rows, the rest is indeterminate).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from mechsing.numeric import SUPPORT_RTOL, Precision, RankDecision, decide_rank
from mechsing.numeric.linalg import first_nonzero_positive
from mechsing.statics.matrices import MotionMatrices

__all__ = ["Equilibrium", "EffortMap", "effort_map", "equilibrium", "load_wrench"]

_FLOAT = Precision("float")


def load_wrench(force: Any, moment: Any, point: np.ndarray) -> np.ndarray:
    """The SI wrench (f, m) at the ground origin of a force and a moment about ``point``."""
    f = np.asarray(force, dtype=float)
    m = np.asarray(moment, dtype=float) + np.cross(np.asarray(point, dtype=float), f)
    return np.concatenate([f, m])


@dataclass(frozen=True)
class EffortMap:
    """The linear map from an SI load wrench at the ground origin to the efforts, at one
    configuration: ``efforts = G w`` (SI; least-norm where not unique), bounded for the
    loads with no power on the uncontrolled output twists ``uncontrolled`` (SI, each a
    unit rotation or else a unit translation; empty when the inputs control the
    output)."""

    G: np.ndarray  # a x 6
    #: (lambda, tau) commensurate of a right-hand side b (n): ``solve @ b``
    solve: np.ndarray
    #: the loop wrench map (commensurate, per loop rows of lambda) and joint wrenches
    Lam: np.ndarray  # r x 6 (commensurate lambda per SI wrench)
    uncontrolled: np.ndarray  # k x 6 SI twists
    uncontrolled_commensurate: np.ndarray  # 6 x k commensurate twists T z
    non_unique: tuple[str, ...]
    indeterminate_loops: tuple[int, ...]
    #: per loop, how many dimensions of its wrench within its subgroup are free
    loop_freedom: tuple[int, ...]
    decision: RankDecision
    Tz_rows: np.ndarray = field(repr=False)  # k x n: the motions z (rows)


def _truncated_pinv(M: np.ndarray, rank: int) -> np.ndarray:
    U, s, Vt = np.linalg.svd(M, full_matrices=False)
    r = min(rank, len(s))
    if r == 0:
        return np.zeros((M.shape[1], M.shape[0]))
    return (Vt[:r].T / s[:r]) @ U[:, :r].T


def _si_twist(mm: MotionMatrices, t: np.ndarray) -> np.ndarray:
    tw = mm.twist_out(t)
    n = float(np.linalg.norm(tw[:3])) or float(np.linalg.norm(tw[3:])) or 1.0
    return np.asarray(first_nonzero_positive(tw / n), dtype=float)


def effort_map(mm: MotionMatrices, precision: Precision = _FLOAT) -> EffortMap:
    """The effort map at the configuration of ``mm`` (see the module)."""
    A, E, T = mm.A, mm.E, mm.T
    n = A.shape[1]
    r, a = A.shape[0], E.shape[0]
    AE = np.vstack([A, E]) if r + a else np.zeros((0, n))
    dec = decide_rank(AE, precision, mm.L, want_spaces=True)
    rank = dec.rank if dec.rank is not None else dec.rank_bounds[1]
    Z = dec.null_space if dec.null_space is not None else np.zeros((n, 0))
    M = AE.T  # unknowns (lambda, tau)
    P = _truncated_pinv(M, rank)  # (r + a) x n, least-norm least-squares
    W_in = np.linalg.inv(np.column_stack([mm.frame.wrench_back(e) for e in np.eye(6)]))
    B = -T.T @ W_in  # n x 6: right-hand side per SI wrench
    # the null space of M: (lambda, tau) with A^T lambda + E^T tau = 0
    if M.shape[1]:
        U, s, Vt = np.linalg.svd(M, full_matrices=True)
        Nm = Vt[rank:].T  # (r + a) x k
    else:
        Nm = np.zeros((0, 0))
    Nl, Nt = Nm[:r], Nm[r:]
    non_unique: list[str] = []
    if Nt.size:
        # least-norm efforts: move along the null directions that change tau (Nm is
        # orthonormal: a direction whose tau part is below the support threshold leaves
        # tau unique, its rounding is not a freedom)
        u, sv, vt = np.linalg.svd(Nt, full_matrices=False)
        k = int(np.sum(sv > SUPPORT_RTOL))
        if k:
            C = -(vt[:k].T / sv[:k]) @ (u[:, :k].T @ P[r:])
            P = P + Nm @ C
        sup = np.linalg.norm(Nt, axis=1)
        non_unique = [mm.inputs[i] for i in range(a) if sup[i] > SUPPORT_RTOL]
    indeterminate = []
    freedom = [0] * len(mm.loops)
    if Nl.size:
        for li, lp in enumerate(mm.loops):
            block = Nl[lp.rows]
            if block.size and np.linalg.norm(block) > SUPPORT_RTOL:
                indeterminate.append(li)
                freedom[li] = int(np.sum(np.linalg.svd(block, compute_uv=False) > SUPPORT_RTOL))
    X = P @ B  # (r + a) x 6
    G = mm.effort_scale()[:, None] * X[r:]
    Tz = T @ Z
    unc = [_si_twist(mm, Tz[:, i]) for i in range(Z.shape[1]) if np.linalg.norm(Tz[:, i]) > 0]
    return EffortMap(
        G,
        P,
        X[:r],
        np.array(unc).reshape(-1, 6),
        Tz,
        tuple(non_unique),
        tuple(indeterminate),
        tuple(freedom),
        dec,
        Z.T,
    )


@dataclass(frozen=True)
class Equilibrium:
    """The efforts for one load at one configuration.

    ``bounded``: False at a Type II configuration for a load with power on an
    uncontrolled output twist (then ``efforts`` are None), None when the rank that
    decides it is undecided; ``uncontrolled``: those twists (SI) with the load's power
    on each (``powers``: W per unit angular rate, or per m/s for a translation);
    ``joint_wrenches``: per joint, the wrench its ``between[0]`` body applies to its
    ``between[1]`` body (SI, (f, m) at the ground origin), None where indeterminate."""

    wrench: np.ndarray
    point: np.ndarray
    efforts: dict[str, float] | None
    bounded: bool | None
    uncontrolled: list[list[float]]
    powers: list[float]
    non_unique: tuple[str, ...]
    joint_wrenches: dict[str, list[float] | None]
    indeterminate_loops: list[tuple[str, ...]]
    margin: Any
    #: per loop: its joints, subgroup, the wrench it carries within its subgroup (SI at
    #: the ground origin; None when indeterminate) and how many wrench dimensions
    #: (those reciprocal to its subgroup) are statically indeterminate
    loop_wrenches: list[dict[str, Any]] = field(default_factory=list)


def equilibrium(
    mm: MotionMatrices,
    emap: EffortMap,
    wrench: np.ndarray,
    point: np.ndarray,
    weights: list[tuple[str, np.ndarray]] | None = None,
) -> Equilibrium:
    """The efforts for the SI load ``wrench`` at the ground origin (applied at ``point``,
    reported) from the configuration's effort map; ``weights``: more wrenches (SI, at the
    ground origin) each on a body (the bodies' weights)."""
    w = np.asarray(wrench, dtype=float)
    powers = [float(t @ np.concatenate([w[3:], w[:3]])) for t in emap.uncontrolled]
    # the power decision, on commensurate numbers relative to the load's generalised force
    W_in = np.linalg.inv(np.column_stack([mm.frame.wrench_back(e) for e in np.eye(6)]))
    y = W_in @ w
    b = -mm.T.T @ y
    extra = [(mm.body_signs(body), W_in @ wb) for body, wb in weights or ()]
    for signs, yb in extra:
        b = b - (mm.Ss * signs[None, :]).T @ yb
    p = emap.Tz_rows @ b if emap.Tz_rows.size else np.zeros(0)
    bounded: bool | None = True
    if p.size:
        d = decide_rank(p[:, None], _FLOAT, mm.L, reference=max(float(np.linalg.norm(b)), 1e-300))
        bounded = None if d.rank is None else d.rank == 0
    efforts = None
    if bounded is not False:
        x = emap.solve @ b
        tau = mm.effort_scale() * x[mm.A.shape[0] :]
        efforts = {name: float(v) for name, v in zip(mm.inputs, tau, strict=True)}
    jw: dict[str, list[float] | None] = {}
    lw: list[dict[str, Any]] = []
    if bounded is not False:
        lam = (emap.solve @ b)[: mm.A.shape[0]]
        bad = {j for li in emap.indeterminate_loops for j in mm.loops[li].joints}
        loopw = np.zeros((len(mm.loops), 6))
        for li, lp in enumerate(mm.loops):
            loopw[li] = lp.basis @ lam[lp.rows]
            lw.append(
                {
                    "joints": list(lp.joints),
                    "subgroup": lp.subgroup,
                    "wrench": None
                    if li in emap.indeterminate_loops
                    else [float(x) for x in mm.wrench_out(loopw[li])],
                    "indeterminate_dimensions": 6 - lp.basis.shape[1] + emap.loop_freedom[li],
                }
            )
        for jk in mm.model.joints:
            c = jk.columns.start
            Y = mm.chain_signs[c] * y
            for signs, yb in extra:
                Y = Y + signs[c] * yb
            for li, lp in enumerate(mm.loops):
                if jk.name in lp.joints:
                    Y = Y + _loop_sign(mm, li, jk.name) * loopw[li]
            jw[jk.name] = None if jk.name in bad else [float(x) for x in -mm.wrench_out(Y)]
    return Equilibrium(
        w,
        np.asarray(point, dtype=float),
        efforts,
        bounded,
        [list(map(float, t)) for t in emap.uncontrolled],
        powers,
        emap.non_unique,
        jw,
        [mm.loops[li].joints for li in emap.indeterminate_loops],
        emap.decision.margin,
        lw,
    )


def _loop_sign(mm: MotionMatrices, li: int, joint: str) -> float:
    loop = mm.model.mech.loops[li]
    for name, sign in zip(loop.joints, loop.signs, strict=True):
        if name == joint:
            return float(sign)
    return 0.0
