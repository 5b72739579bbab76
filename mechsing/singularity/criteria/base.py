"""What every singularity test shares: its plan (what depends only on the mechanism,
built once per model and kept in the model's own plans,
:class:`~mechsing.kinematics.plans.ModelPlans`), its reference
(what its singular values are relative to) and the one batched rank rule
(:func:`mechsing.numeric.batched_rank_bounds`) through which every batch of its
matrices is decided (:meth:`Criterion.ranks`).

A test's matrices come for any leading batch shape (one configuration: shape ``()``);
the one-configuration decisions at the analysis precision (float, mp:N, exact) are
:func:`mechsing.numeric.decide_rank`'s, on the same matrices and against the same
reference.
"""

from __future__ import annotations

from typing import Any, ClassVar, NamedTuple, Self

import numpy as np

from mechsing.kinematics.protocol import ClosureModel
from mechsing.model import Mechanism
from mechsing.numeric import Precision, batched_rank_bounds, rank_bounds

__all__ = ["Criterion", "RankBounds", "singular_values"]

_FLOAT = Precision("float").tolerances


class RankBounds(NamedTuple):
    """The two-threshold rank bounds of a batch of matrices (integer arrays of the batch
    shape): decided where ``lo == hi``.  (A named tuple: made for every batch decided.)"""

    lo: np.ndarray
    hi: np.ndarray

    @property
    def decided(self) -> np.ndarray:
        """The decided rank, ``-1`` where undecided."""
        return np.where(self.lo == self.hi, self.lo, -1)

    @property
    def taken(self) -> np.ndarray:
        """The rank taken where a basis must be cut: the decided one, else the highest the
        bounds allow."""
        return np.where(self.lo == self.hi, self.lo, self.hi)

    def ranks(self) -> list[int | None]:
        """The decided ranks of a one-axis batch as Python ints (None: undecided)."""
        return [
            int(a) if a == b else None
            for a, b in zip(self.lo.tolist(), self.hi.tolist(), strict=True)
        ]

    def pair(self, i: int) -> tuple[int, int]:
        """(lowest, highest) of the ``i``-th matrix of a one-axis batch."""
        return int(self.lo[i]), int(self.hi[i])


def singular_values(A: np.ndarray) -> np.ndarray:
    """The singular values (..., min(m, n)) of a stack of float matrices (..., m, n)."""
    if A.shape[-2] == 0 or A.shape[-1] == 0:
        return np.zeros((*A.shape[:-2], 0))
    s: np.ndarray = np.linalg.svd(A, compute_uv=False)
    return s


class Criterion:
    """A singularity test: ``name``, ``reference`` (what its singular values are relative
    to, in words) and its plan for one model (``plan``, built once per model by
    :meth:`of`)."""

    name: ClassVar[str] = ""
    reference: ClassVar[str] = ""

    def __init__(self, mech: Mechanism, model: ClosureModel) -> None:
        self.mech = mech
        self.model = model

    @classmethod
    def of(cls, mech: Mechanism, model: ClosureModel) -> Self:
        """The test of ``mech`` for ``model``, its plan built once per model and kept in
        the model's plans (``model.plans``)."""
        kept = model.plans.tests
        got = kept.get(cls)
        if got is None:
            got = kept.setdefault(cls, cls(mech, model))
        if got.mech is not mech:  # the same model asked for another mechanism
            return cls(mech, model)
        plan: Self = got
        return plan

    @staticmethod
    def ranks(s: np.ndarray, reference: Any = None) -> RankBounds:
        """The float rank bounds of a batch of matrices from their singular values ``s``
        (..., k), descending, relative to the largest of each or to ``reference`` where
        it is larger: the one rule (:func:`mechsing.numeric.batched_rank_bounds`)."""
        return RankBounds(*batched_rank_bounds(s, _FLOAT, reference))

    @staticmethod
    def ranks_of_relative(rel: np.ndarray) -> RankBounds:
        """The float rank bounds of singular values already relative to the test's
        reference (a matrix divided by its operator's norm)."""
        return RankBounds(*rank_bounds(rel, _FLOAT))
