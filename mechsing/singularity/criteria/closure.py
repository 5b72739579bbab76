"""The closure test, defined once for batches: the stacked loop screw systems (each
loop's current screws with its crossing signs, commensurate), then the couplings' rows.
Their singular values are those of the closure system the analysis of one configuration
decides (:func:`mechsing.screws.closure_system`: each loop's rows in an orthonormal basis
of its subgroup are an isometric image of its six-row screws; the closure is decided
there by :func:`mechsing.numeric.decide_rank`, and the nearby samples' kernels by
:func:`mechsing.numeric.batched_kernels`, below this package's layer).

Each loop is modelled only as far as the scene requires, here too: a loop whose
subgroup is the same at every configuration (its first body the ground:
:func:`mechsing.screws.fixed_loop_basis`) has its rows in that orthonormal basis (a
planar loop 3 rows, not 6), the same singular values at a fraction of the cost, and a
closure of full row rank where the six rows were not (its kernel then from a QR).

Reference: the largest singular value of the stacked system.
"""

from __future__ import annotations

import numpy as np

from mechsing.kinematics import KinematicModel
from mechsing.kinematics.couplings import coupling_rows
from mechsing.kinematics.protocol import ClosureModel
from mechsing.model import Mechanism
from mechsing.screws import fixed_loop_basis
from mechsing.singularity.criteria.base import Criterion

__all__ = ["ClosureTest"]


class ClosureTest(Criterion):
    """The closure test of one mechanism and (float) model; plan: each loop's crossing
    signs per coordinate, the couplings' commensurate rows and, without loops, the
    constant kernel of those rows (the joint rates they allow)."""

    name = "closure"
    reference = "the largest singular value of the stacked loop screw systems"

    def __init__(self, mech: Mechanism, model: ClosureModel) -> None:
        super().__init__(mech, model)
        n = model.n
        self.loop_signs = np.zeros((len(mech.loops), n))
        for i, loop in enumerate(mech.loops):
            for name, sign in zip(loop.joints, loop.signs, strict=True):
                self.loop_signs[i, model.joint(name).columns] = sign
        self.coupling_rows, self.coupling_kernel = coupling_rows(model, model.float_frame)
        if mech.loops:
            self.coupling_kernel = None
        # each loop's rows: its fixed subgroup's orthonormal basis (transposed), or None
        # for its six rows; one block-diagonal map of the stacked six-row systems
        # (a pose model's closure is its base model's and a pose's: six rows each)
        bases: list[np.ndarray | None] = [None] * len(mech.loops)
        if isinstance(model, KinematicModel):
            bases = [fixed_loop_basis(model, loop) for loop in mech.loops]
        self.reduction: np.ndarray | None = None
        if any(b is not None for b in bases):
            blocks = [np.eye(6) if b is None else b.T for b in bases]
            R = np.zeros((sum(b.shape[0] for b in blocks), 6 * len(blocks)))
            at = 0
            for i, b in enumerate(blocks):
                R[at : at + b.shape[0], 6 * i : 6 * i + 6] = b
                at += b.shape[0]
            self.reduction = R
        loop_rows = 6 * len(mech.loops) if self.reduction is None else self.reduction.shape[0]
        #: the rows of the stacked system
        self.rows = loop_rows + len(model.couplings)

    def matrices(self, Ss: np.ndarray) -> np.ndarray:
        """The stacked loop screw systems from commensurate screws ``Ss`` (B, 6, n), each
        loop's rows in its fixed subgroup's basis where it has one, then the couplings'
        rows: (B, rows, n)."""
        C = Ss[:, None, :, :] * self.loop_signs[None, :, None, :]
        C = C.reshape(Ss.shape[0], -1, self.model.n)
        if self.reduction is not None:
            C = self.reduction @ C
        if self.coupling_rows is None:
            return C
        R = np.broadcast_to(self.coupling_rows, (C.shape[0], *self.coupling_rows.shape))
        return np.concatenate([C, R], axis=1)
