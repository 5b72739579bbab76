"""The mp polish of a float closure: Newton on the group at N digits.

:func:`newton_mp` closes the loops at the model's digits from a float (or mp) point,
the given coordinates held; :class:`MpPolisher` polishes a continuation's landing to
working precision and, at a multiple root, again at 2N + 10 digits; :func:`fold_mp` places
a fold of one given coordinate (a limit of its travel) at the model's digits.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from mechsing.kinematics.given import GivenValues
from mechsing.kinematics.model import KinematicModel
from mechsing.kinematics.newton import mp_least_squares, newton_on_group, scaled_jacobian
from mechsing.kinematics.pose import PoseModel, pose_problem
from mechsing.kinematics.protocol import ClosureModel
from mechsing.kinematics.settings import POLISH_DIGITS_SPARE, POLISH_MAX_STEPS
from mechsing.model import Configuration
from mechsing.numeric import Precision
from mechsing.numeric.linalg import svd

__all__ = ["MpPolisher", "Polished", "fold_mp", "newton_mp"]

#: fold_mp's second point: y moved by 10^(-N / FOLD_FIRST_STEP_ROOT) from the first (a
#: fourth of the digits: far above rounding, well inside the fold's quadratic region)
FOLD_FIRST_STEP_ROOT = 4


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
        from its input, a slider's dead centre given by its pose) is a multiple root: the residual is quadratic in the distance d
        along the kernel, so N digits of residual place the configuration only to
        d = 10^(-N/2), where its rank cannot be decided at N digits (the kernel's
        singular value is d).  Such a root shows itself by slow steps (see
        :func:`newton_mp`); it is then polished again at 2N + 10 digits (the model
        rebuilt from the file's numbers at those digits; a pose model with it, in the same
        rotation coordinates) and rounded back to N digits.
        """
        qm, res, slow = newton_mp(m, q, target, gmask)
        # a pose model's deeper twin needs the configuration's pose (a sweep's node has none)
        pose_less = isinstance(m, PoseModel) and (cfg is None or cfg.pose is None)
        if slow and cfg is not None and not pose_less:
            import mpmath

            deep = self._deeper_model()
            with deep.precision.context():
                dtarget, _ = GivenValues(deep).of(cfg)
                dm: ClosureModel = deep
                if isinstance(m, PoseModel):
                    # the pose model at 2N + 10 digits, in the rotation coordinates of m's
                    dm, _, goal = pose_problem(deep, cfg, None, R0=m.R0)
                    dtarget = np.concatenate([dtarget, goal])
                qd, _rd, _ = newton_mp(dm, qm, dtarget, gmask)
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


def newton_mp(
    m: ClosureModel, q: np.ndarray, target: np.ndarray, gmask: np.ndarray, doubling: bool = True
) -> Polished:
    """Newton on the group at the model's digits: (coordinates, residual, whether a
    step was slow).  A step is slow when it lowers the residual by less than
    POLISH_SLOW_RATIO (Newton at a multiple root halves the distance, so lowers the
    residual by 4); the doubled step is then tried too, which for a double root
    converges quadratically again.  Goes on until the correction itself is below
    working precision (at a multiple root a small residual still leaves d =
    sqrt(residual)), and stops when a step no longer lowers the residual.  Without
    ``doubling``, plain Newton: near a fold with its roots a hair away (not a double
    root), a doubled step would cross the fold."""
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
            doubling=doubling,
        )
        return Polished(out.q, out.residual, out.slow)


def fold_mp(m: ClosureModel, q: np.ndarray, col: int) -> Polished | None:
    """The fold of coordinate ``col`` (a limit of its travel, where the other coordinates'
    closure Jacobian loses a direction) nearest the closed configuration ``q`` (mp, near
    it), at the model's digits; None when it is not found (``q`` is not near a fold of
    ``col``: a bifurcation, where the whole Jacobian loses rank, or no fold at all).

    Near a fold the closure is regular in the coordinates other than the one y the lost
    direction moves most (``col`` freed, y held), and ``col`` is extremal there: the
    secant method on y finds the zero of ``d col / d y`` (implicit function: the free
    coordinates' least-squares rates for a unit rate of y), each point closed by Newton
    at N digits.  The lost direction's singular value is linear in y's distance to the
    fold, so the fold is placed to the working precision, not its square root."""
    import mpmath

    with m.precision.context():
        n = len(q)
        others = np.ones(n, dtype=bool)
        others[col] = False
        Js = scaled_jacobian(m, q)
        _U, _s, Vt = svd(m.precision.asarray(Js)[:, others])
        lost = np.asarray([abs(float(x)) for x in Vt[-1]])
        y = int(np.flatnonzero(others)[int(np.argmax(lost))])
        free = np.ones(n, dtype=bool)
        free[y] = False
        at = int(np.flatnonzero(free).tolist().index(col))
        small = mpmath.mpf(10) ** (POLISH_DIGITS_SPARE - mpmath.mp.dps)
        goal = small * m.length_scale

        def closed(qy: np.ndarray) -> Polished:
            out = newton_on_group(
                m,
                qy,
                free,
                solve=mp_least_squares,
                max_steps=POLISH_MAX_STEPS,
                native=True,
                converged=lambda res, du: (
                    res <= goal and max((abs(x) for x in du), default=0) <= small
                ),
            )
            return Polished(out.q, out.residual, out.slow)

        def slope(qc: np.ndarray) -> Any:
            J = scaled_jacobian(m, qc)
            J = m.precision.asarray(J)
            return mp_least_squares(J[:, free], -J[:, y])[at]

        pts = [closed(np.array(q, dtype=object))]
        if pts[0].residual > goal:
            return None
        step = mpmath.mpf(10) ** (-mpmath.mp.dps // FOLD_FIRST_STEP_ROOT)
        q1 = np.array(pts[0].q, dtype=object)
        q1[y] = q1[y] + step
        pts.append(closed(q1))
        f = [slope(pts[0].q), slope(pts[1].q)]
        for _ in range(POLISH_MAX_STEPS):
            y0, y1 = pts[-2].q[y], pts[-1].q[y]
            if f[-1] == f[-2]:
                break
            y2 = y1 - f[-1] * (y1 - y0) / (f[-1] - f[-2])
            if abs(y2 - y1) <= small:
                break
            qn = np.array(pts[-1].q, dtype=object)
            qn[y] = y2
            pts.append(closed(qn))
            if pts[-1].residual > goal:
                return None
            f.append(slope(pts[-1].q))
        best = pts[-1]
        # a fold: col's rate along the curve vanishes there and the residual closes
        if best.residual > goal or abs(f[-1]) > mpmath.sqrt(small):
            return None
        return best
