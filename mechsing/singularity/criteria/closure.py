"""The closure test, defined once for batches: the stacked loop screw systems (each
loop's current screws with its crossing signs, commensurate), then the couplings' rows.
Their singular values are those of the closure system the analysis of one configuration
decides (:func:`mechsing.screws.closure_system`: each loop's rows in an orthonormal basis
of its subgroup are an isometric image of its six-row screws; the closure is decided
there by :func:`mechsing.numeric.decide_rank`, and the nearby samples' kernels by
:func:`mechsing.numeric.batched_kernels`, below this package's layer).

Reference: the largest singular value of the stacked system.
"""

from __future__ import annotations

import numpy as np

from mechsing.kinematics.couplings import coupling_rows
from mechsing.kinematics.protocol import ClosureModel
from mechsing.model import Mechanism
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
        #: the rows of the stacked system
        self.rows = 6 * len(mech.loops) + len(model.couplings)

    def matrices(self, Ss: np.ndarray) -> np.ndarray:
        """The stacked loop screw systems from commensurate screws ``Ss`` (B, 6, n), then
        the couplings' rows: (B, 6 loops + couplings, n)."""
        C = Ss[:, None, :, :] * self.loop_signs[None, :, None, :]
        C = C.reshape(Ss.shape[0], -1, self.model.n)
        if self.coupling_rows is None:
            return C
        R = np.broadcast_to(self.coupling_rows, (C.shape[0], *self.coupling_rows.shape))
        return np.concatenate([C, R], axis=1)
