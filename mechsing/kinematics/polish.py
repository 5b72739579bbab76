"""The mp polish of a float closure: Newton on the group at N digits.

:func:`newton_mp` closes the loops at the model's digits from a float (or mp) point,
the given coordinates held; :class:`MpPolisher` polishes a continuation's landing to
working precision and, at a multiple root, again at 2N + 10 digits.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from mechsing.kinematics.given import GivenValues
from mechsing.kinematics.model import KinematicModel
from mechsing.kinematics.newton import mp_least_squares, newton_on_group
from mechsing.kinematics.protocol import ClosureModel
from mechsing.model import Configuration
from mechsing.numeric import POLISH_DIGITS_SPARE, POLISH_MAX_STEPS, Precision

__all__ = ["MpPolisher", "Polished", "newton_mp"]


class Polished(NamedTuple):
    """Newton's result at N digits: the coordinates, their residual (m, the model's
    numbers), and whether a step was slow (a multiple root)."""

    q: np.ndarray
    residual: Any
    slow: bool


class MpPolisher:
    """Polishes float closures of one mp model (``tolerance``: its closure tolerance);
    keeps the model at 2N + 10 digits once built."""

    def __init__(self, model: KinematicModel, tolerance: Any) -> None:
        self.model = model
        self.mech = model.mech
        self.tolerance = tolerance
        self._deep: KinematicModel | None = None

    def polish(
        self,
        m: ClosureModel,
        q: np.ndarray,
        target: np.ndarray,
        gmask: np.ndarray,
        cfg: Configuration | None = None,
    ) -> tuple[np.ndarray, Any]:
        """Newton at N digits from the float solution (given values at full precision).

        Polished to the working precision (10^(5-N) L), not merely to the acceptance
        tolerance 10^(15-N) L: at mp:30 the float solution (1e-16 L) is already
        accepted, and the rank decisions that follow need the screws to N digits (a
        dropped singular value of 1e-17 lies between mp:30's thresholds).

        A target that is itself singular (a change point, a flat parallelogram reached
        from its input) is a multiple root: the residual is quadratic in the distance d
        along the kernel, so N digits of residual place the configuration only to
        d = 10^(-N/2), where its rank cannot be decided at N digits (the kernel's
        singular value is d).  Such a root shows itself by slow steps (see
        :func:`newton_mp`); it is then polished again at 2N + 10 digits (the model
        rebuilt from the file's numbers at those digits) and rounded back to N digits.
        """
        qm, res, slow = newton_mp(m, q, target, gmask)
        if slow and cfg is not None:
            import mpmath

            deep = self._deeper_model()
            with deep.precision.context():
                dtarget, _ = GivenValues(deep).of(cfg)
                qd, _rd, _ = newton_mp(deep, qm, dtarget, gmask)
            with m.precision.context():
                qn = np.array([+mpmath.mpf(x) for x in qd], dtype=object)
                rn = m.residual_norm(m.chord_residuals(qn), native=True)
            if rn <= max(res, self.tolerance):
                qm, res = qn, rn
        return qm, res

    def _deeper_model(self) -> KinematicModel:
        """The model at 2N + 10 digits (built once), for multiple roots."""
        if self._deep is None:
            digits = self.model.precision.digits
            self._deep = KinematicModel(self.mech, Precision("mp", 2 * digits + 10))
        return self._deep


def newton_mp(m: ClosureModel, q: np.ndarray, target: np.ndarray, gmask: np.ndarray) -> Polished:
    """Newton on the group at the model's digits: (coordinates, residual, whether a
    step was slow).  A step is slow when it lowers the residual by less than
    POLISH_SLOW_RATIO (Newton at a multiple root halves the distance, so lowers the
    residual by 4); the doubled step is then tried too, which for a double root
    converges quadratically again.  Goes on until the correction itself is below
    working precision (at a multiple root a small residual still leaves d =
    sqrt(residual)), and stops when a step no longer lowers the residual."""
    import mpmath

    with m.precision.context():
        if np.asarray(q).dtype == object:
            qm = np.array([mpmath.mpf(x) for x in q], dtype=object)
        else:
            qm = m.asarray([repr(float(x)) for x in q])
        qm[gmask] = target[gmask]
        small = mpmath.mpf(10) ** (POLISH_DIGITS_SPARE - mpmath.mp.dps)
        goal = small * m.length_scale
        out = newton_on_group(
            m,
            qm,
            ~gmask,
            solve=mp_least_squares,
            max_steps=POLISH_MAX_STEPS,
            native=True,
            stop=lambda _it, _res: not m.blocks,
            # closed, and what is left to correct is below working precision
            converged=lambda res, du: res <= goal and max((abs(x) for x in du), default=0) <= small,
            doubling=True,
        )
        return Polished(out.q, out.residual, out.slow)
