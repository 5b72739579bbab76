"""Newton on the group: the one iteration that closes the loops of a kinematic model.

Owns :func:`newton_on_group` and its pieces: the commensurate Newton system
(:func:`scaled_system`: closure Jacobian and chord residual twists, moved to the
centroid, lengths over L; :func:`scaled_jacobian`: the Jacobian alone), the map of a commensurate step back to joint
increments (:func:`increment`), applied on the group by
:meth:`KinematicModel.update`, and the linear solvers of the step (damped least
squares and truncated pseudo-inverse in float, minimum-norm SVD at mp:N).

What differs between its users is passed in: the solver (precision), the step
policy (the doubled step at a double root) and the stopping rules.  The
continuation corrector, the fold landing and the mp polish
(:mod:`mechsing.kinematics.closure`) and the re-closing of nearby samples
(:mod:`mechsing.screws.mobility`) all call it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing.kinematics.model import KinematicModel
from mechsing.kinematics.settings import NEWTON_DAMPING, POLISH_SLOW_RATIO
from mechsing.numeric import Precision, blocks, svd_r
from mechsing.numeric.backend import is_float64
from mechsing.numeric.blocks import block_factors, block_svd, issparse

__all__ = [
    "NewtonResult",
    "damped_least_squares",
    "increment",
    "mp_least_squares",
    "newton_on_group",
    "scaled_jacobian",
    "scaled_system",
    "truncated_least_squares",
]


@dataclass(frozen=True)
class NewtonResult:
    """Where Newton stopped: coordinates ``q`` and their residual (m); ``slow``: some step
    lowered the residual by less than POLISH_SLOW_RATIO (a multiple root);
    ``diverged``: the ``diverged`` rule stopped it (``q``, ``residual``: the last trial)."""

    q: np.ndarray
    residual: Any
    slow: bool = False
    diverged: bool = False


def scaled_system(m: KinematicModel, q: np.ndarray, sparse: bool = False) -> tuple[Any, np.ndarray]:
    """The closure Jacobian and the chord residual twists at q, commensurate (moved to
    the centroid, lengths over L): the system every Newton step on the group solves.
    With ``sparse`` (a big float model, :attr:`KinematicModel.sparse_closure`) the
    Jacobian is a :mod:`scipy.sparse` matrix of the same numbers."""
    r = m.chord_twists(m.chord_residuals(q))
    Js = scaled_jacobian(m, q, sparse)
    rs = m.frame.stacked(r)
    return Js, rs


def scaled_jacobian(m: KinematicModel, q: np.ndarray, sparse: bool = False) -> Any:
    """The commensurate closure Jacobian of :func:`scaled_system` alone (the same
    numbers), for a caller that does not use the residual: the residual twists (a
    logarithm per chord) cost several times the Jacobian."""
    if sparse:
        return m.sparse_closure_jacobian(q, m.frame)
    return m.scaled_closure_jacobian(q, m.frame)


def increment(m: KinematicModel, free: np.ndarray, du: np.ndarray) -> np.ndarray:
    """A commensurate step ``du`` of the free coordinates as joint increments (lengths
    times L, the other coordinates unmoved), in the model's numbers."""
    d = m.zeros()
    d[np.flatnonzero(free)] = du
    return m.frame.rates_back(d)


def _big(A: Any) -> bool:
    """A sparse matrix big enough to be solved block by block (a smaller one is made
    dense and solved as before)."""
    return (
        issparse(A)
        and not blocks.dense(A.shape[0] * A.shape[1])
        and bool(np.isfinite(A.data).all())
    )


def finite_system(A: Any, b: np.ndarray | None = None) -> bool:
    """Is a float system finite?  A coordinate that Newton sent far off (a rotation
    angle of 1e100) gives a residual that is still finite but a Jacobian whose series
    overflow: such a system is no step, Newton stops there as on a step that does not
    lower the residual.  Always True for mp and exact numbers."""
    data = A.data if issparse(A) else np.asarray(A)
    if not is_float64(data):
        return True
    return bool(np.isfinite(data).all()) and (
        b is None or bool(np.isfinite(np.asarray(b, dtype=float)).all())
    )


def damped_least_squares(A: Any, b: np.ndarray) -> np.ndarray:
    """Damped least squares (minimum norm), damping relative to sigma_max (float); ``A``
    dense or sparse (then block by block, :func:`mechsing.numeric.blocks.block_factors`)."""
    if _big(A):
        F = block_factors(A)
        if not len(F.s) or F.s[0] == 0:
            return np.zeros(A.shape[1])
        lam = NEWTON_DAMPING * F.s[0]
        return F.solve(b, lambda s: s / (s * s + lam * lam))
    if issparse(A):
        A = A.toarray()
    U, s, Vt = block_svd(A, full_matrices=False)
    if not len(s) or s[0] == 0:
        return np.zeros(A.shape[1])
    lam = NEWTON_DAMPING * s[0]
    f = s / (s * s + lam * lam)
    return Vt.T @ (f * (U.T @ b))


def truncated_least_squares(A: Any, b: np.ndarray) -> np.ndarray:
    """Minimum-norm least squares (float), singular values below float's ``tau_lo``
    relative to sigma_max dropped; ``A`` dense or sparse (then block by block)."""
    tau = Precision("float").tolerances.tau_lo
    if _big(A):
        F = block_factors(A)
        floor = tau * (F.s[0] if len(F.s) else 0)
        return F.solve(b, lambda s: np.where(s > floor, 1 / np.where(s > floor, s, 1), 0.0))
    if issparse(A):
        A = A.toarray()
    U, s, Vt = block_svd(A, full_matrices=False)
    keep = s > tau * (s[0] if len(s) else 0)
    return Vt[keep].T @ ((U[:, keep].T @ b) / s[keep])


def mp_least_squares(A: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Minimum-norm least squares at the working precision (mpmath SVD), singular values
    below 10^(-N/2) relative to sigma_max dropped; an object array."""
    import mpmath

    Am = mpmath.matrix(A.tolist())
    bm = mpmath.matrix(list(b))
    U, S, V = svd_r(Am)
    smax = max(abs(x) for x in S) if len(S) else 0
    out = mpmath.matrix(Am.cols, 1)
    for i in range(len(S)):
        if S[i] > smax * mpmath.mpf(10) ** (-(mpmath.mp.dps // 2)):
            ui = U.column(i)
            coef = sum(ui[k] * bm[k] for k in range(Am.rows)) / S[i]
            for k in range(Am.cols):
                out[k] += coef * V[i, k]
    return np.array([out[k] for k in range(Am.cols)], dtype=object)


def newton_on_group(
    m: KinematicModel,
    q: np.ndarray,
    free: np.ndarray,
    *,
    solve: Callable[[np.ndarray, np.ndarray], np.ndarray],
    max_steps: int,
    residual: Any = None,
    native: bool = False,
    stop: Callable[[int, Any], bool] | None = None,
    converged: Callable[[Any, np.ndarray], bool] | None = None,
    doubling: bool = False,
    keep: Callable[[Any, Any], bool] | None = None,
    diverged: Callable[[int, Any, Any], bool] | None = None,
) -> NewtonResult:
    """Newton on the group from ``q``, moving the coordinates in ``free``.

    Each step solves the commensurate system (:func:`scaled_system`) for the free
    coordinates with ``solve(A, b)`` (the precision and the kind of least squares),
    and applies the increments on the group (:meth:`KinematicModel.update`).

    Parameters
    ----------
    residual
        The residual at q when known (else computed).
    native
        Residuals in the model's own numbers (an ``mpf`` at mp:N), else floats.
    stop
        ``stop(step, residual)``: stop before building the system of this step.
    converged
        ``converged(residual, du)``: stop once the step ``du`` is known (not applied).
    doubling
        When a step lowers the residual by less than POLISH_SLOW_RATIO, the doubled step
        is tried too and the better kept (a double root).
    keep
        ``keep(residual, new)``: take the step only if True, else stop (default: the new
        residual is lower).
    diverged
        ``diverged(step, residual, new)``: give up (``diverged`` in the result, with the
        trial).
    """

    def closure(qx: np.ndarray) -> Any:
        return m.residual_norm(m.chord_residuals(qx), native=native)

    res = closure(q) if residual is None else residual
    slow = False
    sparse = m.sparse_closure
    for step in range(max_steps):
        if stop is not None and stop(step, res):
            break
        Js, rs = scaled_system(m, q, sparse)
        if not finite_system(Js, rs):
            break  # a coordinate ran off to where the exponential's series overflow
        du = solve(Js[:, free], -rs)
        if converged is not None and converged(res, du):
            break
        d = increment(m, free, du)
        qn = m.update(q, d)
        rn = closure(qn)
        if doubling and rn * POLISH_SLOW_RATIO > res:
            slow = True
            q2 = m.update(q, d * 2)
            r2 = closure(q2)
            if r2 < rn:
                qn, rn = q2, r2
        if diverged is not None and diverged(step, res, rn):
            return NewtonResult(qn, rn, slow, True)
        if not (rn < res if keep is None else keep(res, rn)):
            break
        q, res = qn, rn
    return NewtonResult(q, res, slow)
