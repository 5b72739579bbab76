"""Folds of a path: where the given values reach a limit of their travel.

At a fold (a dead centre, the end of a rocker's swing, a Type II pose given by the inputs)
the unknown joints' Jacobian loses a rank and the unknown joints move like the square root
of the given values: two assembly modes meet there.  This module is the one place that
says what the path engine does there:

* **landing** on a fold: :func:`land_on_fold` (continuation's target is the fold itself:
  Newton from just short of it, a slow step doubled), :func:`approach_fold` (the target
  lies just short of a fold, nearer it than continuation's shortest step: steps of half
  the way left) and :func:`fold_samples` (the samples
  of a path just short of a fold, predicted by the square-root law between the points of
  the curve traced to it; :func:`close_to_fold` and :func:`near_fold` ask it for many
  samples or one);
* **turning** at a fold: :func:`leave_fold`, one definition (along the kernel of the
  unknown joints' Jacobian, the given values moved a little, Newton closing on the side
  asked for): continuation's start drawn at a fold, a sweep's start at one
  (:func:`~mechsing.kinematics.paths.arc.off_singular`) and a swept path past a
  :class:`Fold` it located, onto the other assembly mode
  (:meth:`~mechsing.kinematics.paths.arc.Arc.other_side`, which then follows the curve
  by pseudo-arclength).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from mechsing.kinematics.newton import damped_least_squares, newton_on_group
from mechsing.kinematics.paths.steps import (
    Corrected,
    StepInfo,
    closure_matrix,
    correct,
    same_branch,
)
from mechsing.kinematics.protocol import ClosureModel
from mechsing.kinematics.settings import (
    CONTINUATION_APPROACH_HALVINGS,
    CONTINUATION_FOLD_GAP,
    CONTINUATION_FOLD_REACH,
    CONTINUATION_LEAVE_OFF,
    CONTINUATION_LEAVE_SIZES,
    CONTINUATION_SINGULAR_RTOL,
    POLISH_MAX_STEPS,
    SWEEP_JUMP_RATIO,
)
from mechsing.numeric.blocks import block_svd

if TYPE_CHECKING:
    from mechsing.kinematics.paths.problem import Problem

__all__ = [
    "Fold",
    "approach_fold",
    "close_to_fold",
    "fold_samples",
    "land_on_fold",
    "leave_fold",
    "near_fold",
]


@dataclass(frozen=True)
class Fold:
    """A limit of the swept value: where the path's curve turns back.  ``value`` (SI) is
    the limit, ``z`` the configuration there, ``direction`` +1 when the swept value was
    increasing, ``far_side`` True for a fold met on the other assembly mode (the limit
    the path comes back past)."""

    value: float
    z: np.ndarray
    direction: int
    far_side: bool = False


def land_on_fold(
    fm: ClosureModel, q: np.ndarray, qt: np.ndarray, gmask: np.ndarray
) -> Corrected | None:
    """The target, when continuation stalls just short of it because it is a fold
    (a limit of the given values: a dead centre, a Type II pose given by the inputs).

    There the unknown joints move like the square root of the given ones, so no
    step is short enough for the predictor, and Newton at the double root only
    halves the distance at each step.  From the last point reached, Newton with the
    given values at the target (a slow step is doubled, which converges at a double
    root) must close; the landing is accepted only where the two branches meet: the
    Jacobian in the unknown joints is singular there (relative smallest singular
    value below CONTINUATION_SINGULAR_RTOL) and the joints moved at most
    CONTINUATION_FOLD_REACH times the square root of what was left.  None otherwise
    (a target beyond the fold has no solution; one before it is not a fold)."""
    L = fm.length_scale

    def comm(d: np.ndarray) -> float:
        return float(np.linalg.norm(fm.float_frame.rates(d)))

    left = comm(np.where(gmask, qt - q, 0.0))
    free = ~gmask
    if left > CONTINUATION_FOLD_GAP or not np.any(free) or not fm.blocks:
        return None
    tol = fm.precision.closure_tolerance(L)
    qn = q.copy()
    qn[gmask] = qt[gmask]
    # the doubled step removes the halving at a double root
    landed = newton_on_group(
        fm, qn, free, solve=damped_least_squares, max_steps=POLISH_MAX_STEPS, doubling=True
    )
    qn, res = landed.q, landed.residual
    if res > tol or comm(fm.difference(qn, q)) > CONTINUATION_FOLD_REACH * math.sqrt(left):
        return None
    Js = closure_matrix(fm, qn)
    sigma = block_svd(Js[:, free], compute_uv=False)
    if not len(sigma) or sigma[-1] > CONTINUATION_SINGULAR_RTOL * sigma[0]:
        return None
    rank = int(np.sum(sigma > CONTINUATION_SINGULAR_RTOL * sigma[0]))
    info = StepInfo(res, rank, float(sigma[-1] / sigma[0]), False, qn)
    return Corrected(True, qn, info)


def approach_fold(
    fm: ClosureModel, q: np.ndarray, qt: np.ndarray, gmask: np.ndarray
) -> tuple[Corrected, int] | None:
    """The target and the steps taken to it, when continuation stalls short of a target
    that lies just short of a fold (a crank angle 1e-8 inside its limit): the fold is
    nearer than continuation's shortest step, which then overshoots it.

    From the last point reached, each step moves the given values half of their way left,
    so the fold (beyond the target) stays at least twice the step away, where the
    predictor and Newton stay on the branch; the whole way is tried first at every step,
    and taken once it closes on the same branch.  None when what is left is more than
    CONTINUATION_FOLD_GAP, or when a half step does not close (the target lies beyond
    the fold) or CONTINUATION_APPROACH_HALVINGS are spent."""
    left = float(np.linalg.norm(fm.float_frame.rates(np.where(gmask, qt - q, 0.0))))
    if left > CONTINUATION_FOLD_GAP or not np.any(~gmask) or not fm.blocks:
        return None
    for steps in range(CONTINUATION_APPROACH_HALVINGS):
        ok, qn, info = correct(fm, q, qt, gmask, True)
        if ok and same_branch(fm, q, qn, info, gmask):
            return Corrected(True, qn, info), steps + 1
        qg = q.copy()
        qg[gmask] = q[gmask] + 0.5 * (qt[gmask] - q[gmask])
        ok, qn, info = correct(fm, q, qg, gmask, False)
        if not ok or not same_branch(fm, q, qn, info, gmask):
            return None
        q = qn
    return None


def leave_fold(
    fm: ClosureModel,
    q0: np.ndarray,
    qt: np.ndarray,
    gmask: np.ndarray,
    t1: float,
    toward: np.ndarray | None = None,
) -> tuple[bool, np.ndarray | None]:
    """The turning at a fold, the one definition of the path engine: from ``q0`` at a fold
    of the given values (a dead centre, a toggle, a limit of a swept value's travel),
    whether it is one, and the configuration at ``t1`` of the way to ``qt`` on the side
    of the fold asked for (None when no landing closes there).

    At a fold the unknown joints' Jacobian loses one rank, and the closed
    configurations with the given values moved by d lie about sqrt(d) away along its
    kernel k, on both sides (the two assembly modes that meet there) when d points
    into the motion's range, on neither when it points out of it.  Newton from q0
    cannot find them (its linear step has no component along k), but from q0 + e k
    with e of the order of sqrt(d) it converges: a landing is kept when Newton closes
    and the joints moved off the fold (with ``toward``: on the side of k they were sent
    to).

    ``toward`` (commensurate rates of every coordinate; None: either side): the side to
    turn onto, the kernel direction nearest it.  Continuation leaving a start drawn at a
    fold and a sweep's start at one take either side, the + side of k first; a path that
    came into a fold along ``toward`` (the curve's tangent there, its swept component
    zero) turns onto the other assembly mode by going on along it (its fold located by
    the caller: the direction the Jacobian loses is then its smallest singular vector,
    and the kernel may have more directions, several chains reaching their limits
    together).  (False, None) when the start is not such a fold (without ``toward``: the
    Jacobian keeps its rank, or loses more than one); (True, None) when no landing closes
    (the target lies beyond the limit the fold is)."""
    free = ~gmask
    if not np.any(free) or not fm.blocks:
        return False, None
    Js = closure_matrix(fm, q0)
    A = Js[:, free]
    A = A.toarray() if hasattr(A, "toarray") else np.asarray(A)
    _, sigma, Vt = np.linalg.svd(A)
    if len(sigma) < int(np.sum(free)) or not sigma[0]:
        return False, None
    rel = sigma / sigma[0]
    lost = int(np.sum(rel <= CONTINUATION_SINGULAR_RTOL))
    if toward is None:
        if lost != 1:
            return False, None
        ku, sides = Vt[-1], (1.0, -1.0)
    else:
        K = Vt[len(sigma) - max(lost, 1) :]
        ku = K.T @ (K @ np.asarray(toward, dtype=float)[free])
        if not np.linalg.norm(ku):
            return False, None
        ku, sides = ku / np.linalg.norm(ku), (1.0,)
    k = np.zeros(fm.n)
    k[free] = ku
    kq = fm.float_frame.rates_back(k)
    qg = q0.copy()
    qg[gmask] = q0[gmask] + t1 * (qt[gmask] - q0[gmask])
    moved = float(np.linalg.norm(fm.float_frame.rates(np.where(gmask, qg - q0, 0.0))))
    if moved == 0.0:
        return False, None
    for sign in sides:
        for size in CONTINUATION_LEAVE_SIZES:
            e = sign * size * math.sqrt(moved)
            q1 = fm.update(q0, e * kq)
            ok, qn, _ = correct(fm, q1, qg, gmask, False)
            if not ok:
                continue
            off = fm.float_frame.rates(fm.difference(qn, q0))
            if float(np.linalg.norm(off)) > CONTINUATION_LEAVE_OFF * math.sqrt(moved) and (
                toward is None or float(off @ k) > 0
            ):
                return True, qn
    return True, None


def fold_samples(
    pb: Problem, trail: list[np.ndarray], col: int, values: np.ndarray, polish: bool = True
) -> tuple[np.ndarray, np.ndarray]:
    """The closed configurations at the swept ``values`` between the start of ``trail`` and
    the fold at ``trail[-1]`` (the points of the curve traced to it, in order), all
    together, and which of them closed: each predicted between the two points of the trail
    that bracket its value (by the square-root law in the last stretch, where the swept
    value is quadratic in the distance along the curve), then batched Newton, kept when it
    moved less than SWEEP_JUMP_RATIO times that stretch (``polish``: on to rounding)."""
    cm, bc = pb.cm, pb.batch
    tt = np.array([float(p[col]) for p in trail])
    sign = 1.0 if tt[-1] >= tt[0] else -1.0
    A, B, F, spans = [], [], [], []
    last = len(trail) - 2
    for v in values:
        v = float(v)
        m = int(np.clip(np.searchsorted(sign * tt, sign * v) - 1, 0, last))
        ta, tb = tt[m], tt[m + 1]
        if m == last and tb != ta:
            f = 1.0 - math.sqrt(max(0.0, (tb - v) / (tb - ta)))
        else:
            f = 0.0 if tb == ta else (v - ta) / (tb - ta)
        A.append(trail[m])
        B.append(trail[m + 1])
        F.append(f)
        spans.append(pb.comm(cm.difference(trail[m + 1], trail[m])))
    Qp = bc.between(np.array(A), np.array(B), np.array(F))
    Qp[:, col] = values
    Q, ok, _ = pb.close_near(Qp, SWEEP_JUMP_RATIO * np.array(spans), polish=polish)
    return Q, ok


def close_to_fold(
    pb: Problem, Z: np.ndarray, col: int, values: np.ndarray, ks: list[int], trail: list[np.ndarray]
) -> None:
    """The samples ``ks`` between a path's last node and the fold at ``trail[-1]``, all
    together (:func:`fold_samples`, closed to the tolerance and no further), written into
    Z; a sample that does not close near its prediction is left for the caller (NaN)."""
    idx = np.array(ks)
    Q, ok = fold_samples(pb, trail, col, values[idx], polish=False)
    Z[idx[ok]] = Q[ok]


def near_fold(
    pb: Problem, z: np.ndarray, zf: np.ndarray, col: int, value: float
) -> np.ndarray | None:
    """A sample between z and the fold zf (:func:`fold_samples` on the stretch from z to
    zf: the fraction ``1 - sqrt((t* - value) / (t* - t))`` of the way); None when
    ``value`` is not between them or Newton does not close near the prediction."""
    tz, tf = float(z[col]), float(zf[col])
    if (value - tz) * (tf - tz) <= 0 or (tf - value) * (tf - tz) < 0:
        return None
    Q, ok = fold_samples(pb, [z, zf], col, np.array([value], dtype=float))
    return Q[0] if ok[0] else None
