"""Generic mobility: the nullity at regular points of the branch through q.

The closure system's nullity is upper semicontinuous: at configurations near
q on the same branch it can only be equal or smaller.  So mechsing moves a
small distance along kernel directions, closes the loops again (minimum-norm
Newton on the group, every joint free) and decides the nullity there; the
generic value is the smallest found.  No nearby closed configuration at all
means q is isolated (finite 0, generic null in the JSON).

:func:`nearby_samples_many` gives the same samples of many configurations at once
(a sweep's located points): the same directions, every sample closed by one batched
minimum-norm Newton instead of one Newton each.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from mechsing.kinematics import KinematicModel, forward
from mechsing.kinematics.batch_newton import BatchClosure, truncated_steps
from mechsing.kinematics.newton import newton_on_group, truncated_least_squares
from mechsing.numeric import Precision, batched_kernels, decide_rank, to_float
from mechsing.numeric.blocks import dense

#: a nearby configuration found by sampling or by following a branch counts as
#: closed at this residual (times L)
SAMPLE_CLOSURE_RTOL = 1e-10

#: a sample that lands closer to q than this fraction of its step is q itself
#: (Newton fell back): not a nearby configuration
SAMPLE_DISTINCT_RATIO = 0.1

_FLOAT = Precision("float")
#: relative distances (radians or multiples of L) of the sample points
SAMPLE_STEPS = (1e-3, 1e-2)
#: random kernel directions tried per step
SAMPLES_PER_STEP = 3
_NEWTON = 30


@dataclass(frozen=True)
class NearbySample:
    """A closed configuration near q and its decided nullity (None: undecided);
    ``kernel``: an orthonormal basis of the closure system's kernel there (commensurate,
    the decision's), which the input/output tests at the sample start from."""

    q: np.ndarray
    nullity: int | None
    distance: float
    kernel: np.ndarray | None = field(default=None, compare=False, repr=False)


def stacked_jacobian(model: KinematicModel, q: np.ndarray) -> np.ndarray:
    """Commensurate chord closure Jacobian (float): rank and nullity as the stacked loop system."""
    J = to_float(model.closure_jacobian(q))
    return model.float_frame.blocks(J)


def reclose(
    model: KinematicModel, q: np.ndarray, fixed: np.ndarray | None = None
) -> tuple[np.ndarray, float]:
    """Minimum-norm Newton on the group from ``q`` (float), coordinates in ``fixed`` held.

    Returns the configuration reached and its residual (m).
    """
    # the float closure tolerance, also for an mp or exact model (this Newton is float)
    tol = _FLOAT.closure_tolerance(model.length_scale)
    free = np.ones(model.n, dtype=bool) if fixed is None else ~fixed
    out = newton_on_group(
        model,
        q,
        free,
        solve=truncated_least_squares,
        max_steps=_NEWTON,
        stop=lambda _it, res: res <= tol,
        keep=lambda _res, new: bool(np.isfinite(new)),
    )
    return out.q, out.residual


def _starts(
    model: KinematicModel, qf: np.ndarray, kernel: np.ndarray, seed: int
) -> list[tuple[float, np.ndarray]]:
    """The samples' starting points before closing: (step, q moved ``step`` along a
    random unit kernel direction), in the order :func:`nearby_samples` tries them."""
    draws = iter(_draws(seed, kernel.shape[1]))
    out = []
    for step in SAMPLE_STEPS:
        for _ in range(SAMPLES_PER_STEP):
            v = kernel @ next(draws)
            v /= np.linalg.norm(v)
            out.append((step, model.update(qf, model.float_frame.rates_back(step * v))))
    return out


def _draws(seed: int, d: int) -> list[np.ndarray]:
    """The kernel coefficients :func:`_starts` draws, in order: ``rng.normal(size=d)``
    once per start from a generator seeded with ``seed``, the same for every
    configuration with a kernel of dimension ``d`` (drawn once; read only)."""
    key = (seed, d)
    got = _DRAWS.get(key)
    if got is None:
        rng = np.random.default_rng(seed)
        got = [rng.normal(size=d) for _ in range(len(SAMPLE_STEPS) * SAMPLES_PER_STEP)]
        for g in got:
            g.flags.writeable = False
        _DRAWS[key] = got
    return got


#: :func:`_draws` by (seed, kernel dimension)
_DRAWS: dict[tuple[int, int], list[np.ndarray]] = {}


def _distance(
    model: KinematicModel, qf: np.ndarray, step: float, q1: np.ndarray, res: float
) -> float | None:
    """The distance from q of the sample a closed start gives (commensurate), or None:
    not closed, or fallen back onto q (not a nearby configuration)."""
    if not res <= SAMPLE_CLOSURE_RTOL * model.length_scale:
        return None
    dist = float(np.linalg.norm(model.float_frame.rates(model.difference(q1, qf))))
    return None if dist < SAMPLE_DISTINCT_RATIO * step else dist


def _sample(
    model: KinematicModel, qf: np.ndarray, step: float, q1: np.ndarray, res: float
) -> NearbySample | None:
    """The sample a closed start gives (None: not closed, or fallen back onto q)."""
    dist = _distance(model, qf, step, q1, res)
    if dist is None:
        return None
    dec = decide_rank(stacked_jacobian(model, q1), "float", model.length_scale, want_spaces=True)
    null = None if dec.rank is None else model.n - dec.rank
    return NearbySample(q1, null, dist, dec.null_space)


def nearby_samples(
    model: KinematicModel, q: np.ndarray, kernel: np.ndarray, seed: int = 0
) -> list[NearbySample]:
    """Closed configurations at distances :data:`SAMPLE_STEPS` along random kernel
    directions (``kernel``: commensurate, n x d, float), with their nullities."""
    if kernel.shape[1] == 0 or not model.blocks:
        return []
    qf = to_float(q)
    out: list[NearbySample] = []
    for step, q0 in _starts(model, qf, kernel, seed):
        q1, res = reclose(model, q0)
        s = _sample(model, qf, step, q1, res)
        if s is not None:
            out.append(s)
    return out


def nearby_samples_many(
    model: KinematicModel, qs: list[np.ndarray], kernels: list[np.ndarray], seed: int = 0
) -> list[list[NearbySample]]:
    """:func:`nearby_samples` of each configuration ``qs[i]`` with its kernel
    ``kernels[i]`` (``model`` float): the same starting points, all closed together by
    :func:`reclose_many` (the same minimum-norm Newton, batched)."""
    if model.backend.name != "float" or model.sparse_closure:
        # a big model closes one sample at a time, block by block (sparse)
        return [nearby_samples(model, q, K, seed) for q, K in zip(qs, kernels, strict=True)]
    jobs: list[tuple[int, float, np.ndarray]] = []
    qfs = [to_float(q) for q in qs]
    for i, (qf, K) in enumerate(zip(qfs, kernels, strict=True)):
        if K.shape[1] == 0 or not model.blocks:
            continue
        jobs += [(i, step, q0) for step, q0 in _starts(model, qf, K, seed)]
    out: list[list[NearbySample]] = [[] for _ in qs]
    if not jobs:
        return out
    Q, res = reclose_many(model, np.array([q0 for _, _, q0 in jobs], dtype=float))
    kept = []
    for (i, step, _), q1, r in zip(jobs, Q, res, strict=True):
        dist = _distance(model, qfs[i], step, q1, float(r))
        if dist is not None:
            kept.append((i, q1, dist))
    Qk = np.array([q1 for _, q1, _ in kept], dtype=float).reshape(-1, model.n)
    for (i, q1, dist), (null, kernel) in zip(kept, _decided_many(model, Qk), strict=True):
        out[i].append(NearbySample(q1, null, dist, kernel))
    return out


def _decided_many(model: KinematicModel, Q: np.ndarray) -> list[tuple[int | None, np.ndarray]]:
    """The nullity and the kernel of the closure at each row of Q (closed samples), as
    :func:`_sample` decides them: the stacked Jacobians of all rows built from one batched
    product of exponentials (the analysis's own), their singular values and vectors by
    numpy's batched SVD (the same LAPACK routine, matrix by matrix) and the ranks by the same
    two-threshold rule."""
    n = model.n
    rows = 6 * model.blocks
    if not len(Q) or not dense(rows * n):
        # decide_rank factorises a big matrix block by block: one sample at a time
        out = []
        for q1 in Q:
            dec = decide_rank(
                stacked_jacobian(model, q1), "float", model.length_scale, want_spaces=True
            )
            out.append((None if dec.rank is None else n - dec.rank, dec.null_space))
        return out
    S = forward.current_screws(model, Q, forward.poses(model, Q))
    # stacked_jacobian of each: the chords' signed screws, each 6-row block commensurate
    J = model.closure_jacobian(Q, S).reshape(len(Q), model.blocks, 6, n)
    J = model.float_frame.screws(J).reshape(len(Q), rows, n)
    return batched_kernels(J, _FLOAT.tolerances)


def reclose_many(model: KinematicModel, Q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`reclose` of every row of Q (float, every joint free), all rows together:
    the same minimum-norm Newton step (the truncated pseudo-inverse of the commensurate
    closure Jacobian: singular values at or below float's ``tau_lo`` times the largest
    dropped, as :func:`~mechsing.kinematics.newton.truncated_least_squares`), the same
    rules per row (stop once the residual is within the float
    closure tolerance or after as many steps; a step is taken when its residual is finite,
    and a row whose system is not finite stops).  Returns (Q, residual (m) per row)."""
    bc = BatchClosure(model)
    free = np.ones(model.n, dtype=bool)
    tol = _FLOAT.closure_tolerance(model.length_scale)
    Q, res, _its = bc.newton(
        Q, free, tol, iterations=_NEWTON, polish=False, solve=truncated_steps, accept="finite"
    )
    return Q, res
