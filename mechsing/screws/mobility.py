"""Generic mobility: the nullity at regular points of the branch through q.

The closure system's nullity is upper semicontinuous: at configurations near
q on the same branch it can only be equal or smaller.  So mechsing moves a
small distance along kernel directions, closes the loops again (minimum-norm
Newton on the group, every joint free) and decides the nullity there; the
generic value is the smallest found.  No nearby closed configuration at all
means q is isolated (finite 0, generic null in the JSON).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechsing.kinematics import KinematicModel
from mechsing.kinematics.newton import newton_on_group, truncated_least_squares
from mechsing.numeric import (
    SAMPLE_CLOSURE_RTOL,
    SAMPLE_DISTINCT_RATIO,
    Precision,
    decide_rank,
    to_float,
)

_FLOAT = Precision("float")
#: relative distances (radians or multiples of L) of the sample points
SAMPLE_STEPS = (1e-3, 1e-2)
#: random kernel directions tried per step
SAMPLES_PER_STEP = 3
_NEWTON = 30


@dataclass(frozen=True)
class NearbySample:
    """A closed configuration near q and its decided nullity (None: undecided)."""

    q: np.ndarray
    nullity: int | None
    distance: float


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


def nearby_samples(
    model: KinematicModel, q: np.ndarray, kernel: np.ndarray, seed: int = 0
) -> list[NearbySample]:
    """Closed configurations at distances :data:`SAMPLE_STEPS` along random kernel
    directions (``kernel``: commensurate, n x d, float), with their nullities."""
    if kernel.shape[1] == 0 or not model.chords:
        return []
    rng = np.random.default_rng(seed)
    L = model.length_scale
    qf = to_float(q)
    out: list[NearbySample] = []
    for step in SAMPLE_STEPS:
        for _ in range(SAMPLES_PER_STEP):
            v = kernel @ rng.normal(size=kernel.shape[1])
            v /= np.linalg.norm(v)
            d = model.float_frame.rates_back(step * v)
            q1, res = reclose(model, model.update(qf, d))
            if res > SAMPLE_CLOSURE_RTOL * L:
                continue
            dist = float(np.linalg.norm(model.float_frame.rates(model.difference(q1, qf))))
            if dist < SAMPLE_DISTINCT_RATIO * step:
                continue  # Newton fell back onto q: not a nearby configuration
            dec = decide_rank(stacked_jacobian(model, q1), "float", L)
            null = None if dec.rank is None else model.n - dec.rank
            out.append(NearbySample(q1, null, dist))
    return out
