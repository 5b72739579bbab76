"""One step of a path in the given coordinates: predict, correct, keep it on its mode.

Owns the tangent predictor every path takes (:func:`tangent_increment`), the step the
continuation of a named configuration takes (:func:`correct`: that predictor, then damped
Newton on the group in the unknown coordinates) and the
assembly-mode jump check that accepts it (:func:`same_branch`: a correction small next to
the predicted step, and near a singularity a step that can be taken back), with what a
step finds (:class:`StepInfo`, :class:`Corrected`) and the closure Jacobian they read
(:func:`closure_matrix`).  The sweeps' nodes (:mod:`.nodes`) take the same kind of step
batched (their first step predicted by the same :func:`tangent_increment`), with the same
jump test: a correction bounded by a multiple of the step.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from mechsing.kinematics.model import KinematicModel
from mechsing.kinematics.newton import damped_least_squares, finite_system, newton_on_group
from mechsing.kinematics.protocol import ClosureModel
from mechsing.kinematics.settings import (
    CONTINUATION_CORRECTOR_RATIO,
    CONTINUATION_JUMP_FLOOR,
    CONTINUATION_RETURN_RATIO,
    CONTINUATION_REVERSE_RTOL,
    CONTINUATION_STEP_RTOL,
)
from mechsing.numeric import decide_rank

__all__ = [
    "Corrected",
    "StepInfo",
    "closure_matrix",
    "correct",
    "same_branch",
    "tangent_increment",
]

#: largest predicted step of all coordinates together (commensurate norm)
_MAX_PREDICTED_STEP = 0.15
_NEWTON_ITERATIONS = 12


@dataclass
class StepInfo:
    """What a step of continuation found: the residual (m) it closed to, the rank of the
    closure Jacobian in the unknown coordinates there (None: not decided) with its
    smallest kept relative singular value, whether the unknowns are underdetermined, and
    where the predictor put the step."""

    residual: float
    rank: int | None
    smin: float
    underdetermined: bool
    predicted: np.ndarray


class Corrected(NamedTuple):
    """A corrected step: whether it closed (``ok``), where it ended (``q``), what it found."""

    ok: bool
    q: np.ndarray
    info: StepInfo


def same_branch(
    fm: ClosureModel, q: np.ndarray, qn: np.ndarray, info: StepInfo, gmask: np.ndarray
) -> bool:
    """Did the step stay on the assembly mode it started from?

    Newton's correction must be small next to the predictor step, and near a
    singularity (where two modes are close) the step must be reversible:
    stepping back from ``qn`` returns to ``q``.
    """

    def comm(d: np.ndarray) -> float:
        return float(np.linalg.norm(fm.float_frame.rates(d)))

    step = comm(fm.difference(info.predicted, q))
    if step == 0.0:
        return True
    # the whole predicted step, passive joints included, stays short: a path on
    # which the passive joints move much faster than the given ones is cut finer
    if step > _MAX_PREDICTED_STEP:
        return False
    if comm(fm.difference(qn, info.predicted)) > max(
        CONTINUATION_CORRECTOR_RATIO * step, CONTINUATION_JUMP_FLOOR
    ):
        return False
    # with a continuum of solutions (underdetermined) stepping back may land
    # elsewhere on it: reversibility only means something for a determined step
    if info.smin < CONTINUATION_REVERSE_RTOL and not info.underdetermined:
        back_target = qn.copy()
        back_target[gmask] = q[gmask]
        ok, qb, _ = correct(fm, qn, back_target, gmask, False)
        if not ok or comm(fm.difference(qb, q)) > max(
            CONTINUATION_RETURN_RATIO * step, CONTINUATION_JUMP_FLOOR
        ):
            return False
    return True


def correct(
    fm: ClosureModel, q_prev: np.ndarray, qg: np.ndarray, gmask: np.ndarray, final: bool
) -> Corrected:
    """Predictor (tangent) + damped Newton on the unknown coordinates."""
    free = ~gmask
    L = fm.length_scale
    # the float stage accepts at float's tolerance (an mp model polishes afterwards)
    tol_final = fm.precision.closure_tolerance(L)
    tol = tol_final if final else max(tol_final, CONTINUATION_STEP_RTOL * L)
    # predictor: the tangent step at the previous point
    dg = np.where(gmask, qg - q_prev, 0.0)
    q = fm.update(q_prev, tangent_increment(fm, closure_matrix(fm, q_prev), dg, gmask))
    q[gmask] = qg[gmask]
    predicted = q.copy()
    res = fm.residual_norm(fm.chord_residuals(q))
    info = StepInfo(res, None, 1.0, False, predicted)
    polish = 0

    def stop(it: int, res: float) -> bool:
        nonlocal polish
        if res <= tol and it > 0:
            # at the target, keep iterating while Newton still gains (rounding level)
            if not final or polish >= 2:
                return True
            polish += 1
        return not fm.blocks or not np.any(free)

    out = newton_on_group(
        fm,
        q,
        free,
        solve=damped_least_squares,
        max_steps=_NEWTON_ITERATIONS,
        residual=res,
        stop=stop,
        # polishing at the target stops when it no longer gains
        keep=lambda res, new: not (res <= tol and new >= res),
        diverged=lambda it, res, new: not np.isfinite(new) or new > 10 * max(res, tol) and it > 2,
    )
    info.residual = out.residual
    if out.diverged:
        return Corrected(False, out.q, info)
    q, res = out.q, out.residual
    if res > tol:
        return Corrected(False, q, info)
    if np.any(free) and fm.blocks:
        Js = closure_matrix(fm, q)
        if not finite_system(Js):
            # closed, but at coordinates so far off that the Jacobian's series
            # overflow (a degenerate loop whose S joint turned without end): no step
            return Corrected(False, q, info)
        dec = decide_rank(Js[:, free], "float", L)
        rank = dec.rank if dec.rank is not None else dec.rank_bounds[0]
        info.rank = rank
        s = [x / dec.sigma[0] for x in dec.sigma] if dec.sigma and dec.sigma[0] > 0 else [0.0]
        info.smin = s[min(rank, len(s)) - 1] if rank else 0.0
        info.underdetermined = rank < int(np.sum(free))
    return Corrected(True, q, info)


def tangent_increment(fm: ClosureModel, Js: Any, dg: np.ndarray, gmask: np.ndarray) -> np.ndarray:
    """The tangent predictor, the one every path of the engine takes: the increment of
    every coordinate (the model's numbers) that moves the given ones by ``dg`` (zero
    elsewhere) and the unknown ones by du with J_u du = -J_g dg, the closure Jacobian
    ``Js`` (commensurate, :func:`closure_matrix`) kept to first order.  du is the damped
    least-squares solution (minimum norm; damping NEWTON_DAMPING relative to the largest
    singular value), bounded near a singularity where J_u loses rank."""
    free = ~gmask
    dgs = fm.float_frame.rates(dg)
    if not (np.any(free) and Js.shape[0]):
        return np.asarray(dg, dtype=float)
    du = damped_least_squares(Js[:, free], -Js[:, gmask] @ dgs[gmask])
    dus = np.zeros(fm.n)
    dus[free] = du
    return np.where(gmask, dg, fm.float_frame.rates_back(dus))


def closure_matrix(fm: ClosureModel, q: np.ndarray) -> Any:
    """The commensurate closure Jacobian of the float model at q: sparse for a big
    mechanism (:attr:`KinematicModel.sparse_closure`: built from each loop's own
    joints and factorised block by block; only a mechanism's model is), dense otherwise."""
    if isinstance(fm, KinematicModel) and fm.sparse_closure:
        return fm.sparse_closure_jacobian(q, fm.float_frame)
    return fm.scaled_closure_jacobian(q, fm.float_frame)
