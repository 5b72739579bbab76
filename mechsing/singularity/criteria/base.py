"""What every singularity test shares: its plan (what depends only on the mechanism,
built once per model and kept by the test's class for the last few models,
:class:`PerModel`), its reference
(what its singular values are relative to) and the one batched rank rule
(:func:`mechsing.numeric.batched_rank_bounds`) through which every batch of its
matrices is decided (:meth:`Criterion.ranks`).

A test's matrices come for any leading batch shape (one configuration: shape ``()``);
the one-configuration decisions at the analysis precision (float, mp:N, exact) are
:func:`mechsing.numeric.decide_rank`'s, on the same matrices and against the same
reference.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Callable
from typing import Any, ClassVar, NamedTuple, Self, TypeVar

import numpy as np

from mechsing.kinematics.protocol import ClosureModel
from mechsing.model import Mechanism
from mechsing.numeric import Precision, batched_rank_bounds, rank_bounds

__all__ = ["Criterion", "PerModel", "RankBounds", "singular_values"]

T = TypeVar("T")

_FLOAT = Precision("float").tolerances

#: models whose plans each test keeps (an analysis holds two: its own and its float twin)
PLANS_KEPT = 8


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


class PerModel:
    """Plans kept per model, for the :data:`PLANS_KEPT` models asked for last (a bounded
    cache: a plan holds its model, so older ones are let go), nothing attached to the
    model itself."""

    def __init__(self) -> None:
        self._plans: OrderedDict[int, tuple[ClosureModel, Any]] = OrderedDict()
        self._lock = threading.Lock()  # a threaded sweep's workers share the cache

    def get(self, model: ClosureModel, build: Callable[[], T]) -> T:
        key = id(model)
        with self._lock:
            got = self._plans.get(key)
            if got is not None and got[0] is model:
                self._plans.move_to_end(key)
                kept: T = got[1]
                return kept
        plan = build()
        with self._lock:
            self._plans[key] = (model, plan)
            self._plans.move_to_end(key)
            while len(self._plans) > PLANS_KEPT:
                self._plans.popitem(last=False)
        return plan


class Criterion:
    """A singularity test: ``name``, ``reference`` (what its singular values are relative
    to, in words) and its plan for one model (``plan``, built once per model by
    :meth:`of`)."""

    name: ClassVar[str] = ""
    reference: ClassVar[str] = ""
    _plans: ClassVar[PerModel]

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        cls._plans = PerModel()

    def __init__(self, mech: Mechanism, model: ClosureModel) -> None:
        self.mech = mech
        self.model = model

    @classmethod
    def of(cls, mech: Mechanism, model: ClosureModel) -> Self:
        """The test of ``mech`` for ``model``, its plan built once per model."""
        got = cls._plans.get(model, lambda: cls(mech, model))
        if got.mech is not mech:  # the same model asked for another mechanism
            got = cls(mech, model)
        return got

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
