"""A path's kinematic problem (a sweep's): what it holds fixed, what it solves, and how
it closes.

Owns :class:`Problem`: the float model a sweep closes (the mechanism's, or its pose model
when the output's pose is swept), which coordinates are given (held at the start's values
or swept), the closure tolerance, the tools that close (continuation of a named
configuration's closure, batched Newton).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from mechsing.kinematics.batch_newton import BatchClosure
    from mechsing.kinematics.model import KinematicModel

__all__ = ["Problem"]


@dataclass
class Problem:
    """A sweep's kinematic problem: the float model it closes (the mechanism's, or its
    pose model when the output's pose is swept), which coordinates are given (held at
    the start's values or swept), the closure tolerance, and the tools that close."""

    model: KinematicModel
    cm: Any  # the model continuation works in (a PoseModel for a pose sweep)
    given: np.ndarray  # bool over cm.n
    #: the :class:`~mechsing.kinematics.closure.Closer` whose continuation :meth:`reach` asks
    #: (typed loosely: the closure's continuation is built on this package)
    closer: Any
    batch: BatchClosure
    tolerance: float
    #: which columns of cm are revolute angles (a value and itself plus 2 pi are one pose)
    periodic: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=bool))
    #: the tangents asked last (:func:`~mechsing.kinematics.paths.arc.curve_tangent` keeps them), by
    #: (column, configuration's bytes)
    tangents: dict[tuple[int, bytes], np.ndarray | None] = field(
        default_factory=dict, repr=False, compare=False
    )
    #: the tangent predictor's unit steps asked last (:func:`~mechsing.kinematics.paths.nodes.tangent_step`
    #: keeps them), by (column, configuration's bytes)
    predictors: dict[tuple[int, bytes], np.ndarray] = field(
        default_factory=dict, repr=False, compare=False
    )

    @property
    def n(self) -> int:
        return int(self.cm.n)

    def scale(self, col: int) -> float:
        """The commensurate unit of column ``col``: 1 for an angle, L for a length."""
        return float(self.cm.float_frame.rates_back(np.ones(1), [col])[0])

    def comm(self, d: np.ndarray) -> float:
        return float(np.linalg.norm(self.cm.float_frame.rates(d)))

    def close_near(
        self, Qp: np.ndarray, bound: Any, polish: bool = True
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Batched Newton from the predicted rows Qp (the given coordinates held): the
        closed rows, which of them closed to the tolerance within ``bound`` of their
        prediction (commensurate; a scalar or one per row: farther, a row may have jumped
        to another assembly mode), and the Newton iterations per row."""
        Q, res, its = self.batch.newton(
            Qp, ~self.given[: self.batch.nb], self.tolerance, polish=polish
        )
        moved = np.linalg.norm(self.cm.float_frame.rates(Q - Qp), axis=1)
        ok = (res <= self.tolerance) & np.isfinite(res) & (moved <= bound)
        return Q, ok, its

    def reach(self, z: np.ndarray, col: int, value: float) -> np.ndarray:
        """From the closed z, the configuration with coordinate ``col`` at ``value`` (the
        other given coordinates kept), by the careful continuation of a named
        configuration's closure; raises :class:`ClosureError` where it cannot go."""
        target = np.array(z, dtype=float)
        target[col] = value
        given = tuple(int(i) for i in np.flatnonzero(self.given))
        pose = self.cm if self.cm is not self.model else None
        return np.asarray(self.closer.follow(z, target, given, pose).q, dtype=float)
