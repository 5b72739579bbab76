"""A sweep's kinematic problem: what it holds fixed, what it solves, and how it closes.

Owns :class:`Problem`: the float model a sweep closes (the mechanism's, or its pose model
when the output's pose is swept), which coordinates are given (held at the start's values
or swept), the closure tolerance, the tools that close (continuation of a named
configuration's closure, batched Newton), and the path's tangent at a closed point.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from mechsing.kinematics import Closer, KinematicModel
from mechsing.kinematics.batch import BatchClosure
from mechsing.sweeps.arc import Arc

__all__ = ["Problem"]

#: tangents a Problem keeps (a row's start asks for the same one up to three times, and
#: the rows of a grid are started together: a chunk of rows' starts, then their first
#: nodes; a tangent is a few hundred bytes)
_TANGENTS_KEPT = 4096


@dataclass
class Problem:
    """A sweep's kinematic problem: the float model it closes (the mechanism's, or its
    pose model when the output's pose is swept), which coordinates are given (held at
    the start's values or swept), the closure tolerance, and the tools that close."""

    model: KinematicModel
    cm: Any  # the model continuation works in (a PoseModel for a pose sweep)
    given: np.ndarray  # bool over cm.n
    closer: Closer
    batch: BatchClosure
    tolerance: float
    #: which columns of cm are revolute angles (a value and itself plus 2 pi are one pose)
    periodic: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=bool))
    #: the tangents asked last (:meth:`tangent`), by (column, configuration's bytes)
    _tangents: dict[tuple[int, bytes], np.ndarray | None] = field(
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

    def tangent(self, z: np.ndarray, col: int) -> np.ndarray | None:
        """The unit commensurate tangent of the path's curve at the closed z (every
        coordinate of cm, zero on the given ones but ``col``; its sign arbitrary), or None
        where the curve is not one-dimensional.  The last ones are kept: a row's start
        asks for it once to check that it can leave and once per direction."""
        key = (col, np.asarray(z, dtype=float).tobytes())
        if key in self._tangents:
            return self._tangents[key]
        arc = Arc(self, col, 1)
        t = arc.tangent(np.asarray(z, dtype=float))
        out = None
        if t is not None:
            out = np.zeros(self.n)
            out[arc.free] = t
        if len(self._tangents) >= _TANGENTS_KEPT:
            self._tangents.pop(next(iter(self._tangents)))
        self._tangents[key] = out
        return out

    def reach(self, z: np.ndarray, col: int, value: float) -> np.ndarray:
        """From the closed z, the configuration with coordinate ``col`` at ``value`` (the
        other given coordinates kept), by the careful continuation of a named
        configuration's closure; raises :class:`ClosureError` where it cannot go."""
        target = np.array(z, dtype=float)
        target[col] = value
        given = tuple(int(i) for i in np.flatnonzero(self.given))
        pose = self.cm if self.cm is not self.model else None
        return np.asarray(self.closer.follow(z, target, given, pose).q, dtype=float)
