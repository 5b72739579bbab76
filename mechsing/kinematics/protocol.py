"""What closure and Newton ask of a kinematic model: the protocol :class:`ClosureModel`.

Two classes answer it: :class:`~mechsing.kinematics.model.KinematicModel` (a
mechanism's joints, in one precision mode) and :class:`~mechsing.kinematics.pose.PoseModel`
(the same with the output's pose as six more given coordinates and one more closure
block).  Continuation, the mp polish, Newton on the group and the words of a stopped path
take either through this protocol; what only a mechanism's model has (its joints' list,
the sparse closure Jacobian, the exact field, the batched poses it keeps) is asked of a
:class:`KinematicModel` by name.

The coordinates ``q`` are one array of the model's numbers (float, mpf or sympy), the
closure residuals one 4x4 relative displacement per closure block (the chords' loops, then
the couplings, then a pose model's pose), in :attr:`ClosureModel.blocks` order.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol, runtime_checkable

import numpy as np

from mechsing.kinematics.plans import ModelPlans
from mechsing.model import Mechanism
from mechsing.numeric import CommensurateFrame, Precision

__all__ = ["ClosureModel"]


@runtime_checkable
class ClosureModel(Protocol):
    """A kinematic model as closure by continuation, the mp polish and Newton use it."""

    #: the mechanism modelled
    mech: Mechanism
    #: what depends only on this model, built when first asked and kept with it
    plans: ModelPlans
    #: the precision mode of its numbers, and that mode's backend
    precision: Precision
    backend: Any
    #: the characteristic length L (m) and the number of coordinates
    length_scale: Any
    n: int
    #: the chords (one closure block each, first), the couplings' blocks, and how many
    #: blocks in all
    chords: Sequence[Any]
    couplings: Sequence[Any]
    blocks: int
    #: the commensurate frame in the model's numbers and in float, and which
    #: coordinates are lengths
    frame: CommensurateFrame
    float_frame: CommensurateFrame
    length_columns: np.ndarray

    @property
    def sparse_closure(self) -> bool:
        """Whether the float closure Jacobian is built and solved block by block."""
        ...

    def float_twin(self) -> ClosureModel:
        """The same model in float (itself when float)."""
        ...

    def joint(self, name: str) -> Any:
        """The kinematics of the joint ``name`` (its columns, basis, subgroup)."""
        ...

    def zeros(self) -> np.ndarray:
        """All coordinates zero, in the model's numbers."""
        ...

    def asarray(self, q: Any) -> np.ndarray:
        """``q`` in the model's numbers."""
        ...

    def values(self, q: np.ndarray) -> dict[str, list[float]]:
        """The joint values (floats) of ``q``, by joint name."""
        ...

    def poses(self, q: np.ndarray) -> dict[str, np.ndarray]:
        """Each body's pose (4x4) at ``q``."""
        ...

    def current_screws(self, q: np.ndarray, poses: dict[str, np.ndarray] | None = None) -> Any:
        """The joints' current screws at ``q`` (6 x n)."""
        ...

    def closure_jacobian(self, q: np.ndarray, screws: np.ndarray | None = None) -> np.ndarray:
        """The closure Jacobian at ``q`` (6 rows per block x n)."""
        ...

    def scaled_closure_jacobian(
        self, q: np.ndarray, frame: Any, screws: np.ndarray | None = None
    ) -> np.ndarray:
        """The closure Jacobian in the commensurate ``frame``."""
        ...

    def chord_residuals(
        self, q: np.ndarray, poses: dict[str, np.ndarray] | None = None
    ) -> list[np.ndarray]:
        """One relative displacement (4x4) per closure block: the identity when it closes."""
        ...

    def residual_norm(self, deltas: list[np.ndarray], native: bool = False) -> Any:
        """The size (m) of the closure residuals ``deltas`` (float, or the model's numbers)."""
        ...

    def chord_twists(self, deltas: list[np.ndarray]) -> np.ndarray:
        """The residuals as twists (their logarithms), stacked."""
        ...

    def update(self, q: np.ndarray, delta: np.ndarray) -> np.ndarray:
        """``q`` moved by ``delta`` on the group (each joint in its own subalgebra)."""
        ...

    def difference(self, q1: np.ndarray, q0: np.ndarray) -> np.ndarray:
        """The coordinate change from ``q0`` to ``q1`` (the inverse of :meth:`update`)."""
        ...
