"""The serial test, defined once: the rank of a chain's screw system, the matrix of its
joints' current screws (columns; a coupled follower folded into its leader's column),
or for a positioning task the velocities of its output point ``v + omega x x`` (3 rows),
commensurate.  It loses rank below its generic value where the chain resists, with zero
joint effort, wrenches it generically could not.

Reference: the chain's largest singular value.

:meth:`SerialTest.decide` decides one configuration at any precision (the
:class:`ChainSystem` with its margin); :meth:`SerialTest.batch_ranks` decides a batch of
float matrices by the one batched rank rule, and a scan may ask a compiled screen first
(:meth:`SerialTest.screen`, an optional backend: :mod:`mechsing.sweeps.scan_kernel`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from mechsing.kinematics.couplings import fold_columns
from mechsing.kinematics.protocol import ClosureModel
from mechsing.model import Mechanism
from mechsing.numeric import RankDecision, decide_rank
from mechsing.screws import chain_matrix
from mechsing.singularity.criteria.base import Criterion, RankBounds, singular_values

__all__ = ["ChainSystem", "SerialTest"]


@dataclass
class ChainSystem:
    """A chain's screw system at q: commensurate matrix, its rank decision and
    the maps back to SI quantities."""

    matrix: np.ndarray  # commensurate (rows: 6 twist or 3 point-velocity; cols: chain coordinates)
    rank: RankDecision
    columns: list[int]  # coordinate indices of the chain
    point: bool  # positioning task (3 rows)
    #: the positions (in ``columns``) of the matrix's columns: a coupled follower whose
    #: leader is in the chain is folded into its leader's column
    #: (:func:`mechsing.kinematics.couplings.fold_columns`); None: every column
    kept: list[int] | None = None
    #: the folded followers: (position, leader's position, commensurate factor)
    follows: list[tuple[int, int, Any]] = field(default_factory=list)


#: compiled screens of serial chains, registered by the modules that provide them
#: (:meth:`SerialTest.register_screen`); each has ``available()`` and
#: ``screen_bounds(chain, Q, err)``
_SCREENS: list[Any] = []


class SerialTest(Criterion):
    """The serial test of chains of one model (the output chain of an open mechanism, a
    leg of a parallel one); plan: whether the model has couplings to fold."""

    name = "serial"
    reference = "the chain's largest singular value"

    def __init__(self, mech: Mechanism, model: ClosureModel) -> None:
        super().__init__(mech, model)
        self.coupled = bool(getattr(model, "couplings", ()))

    def matrix(
        self,
        S: Any,
        columns: list[int],
        point_x: Any = None,
        scaled: Any = None,
    ) -> tuple[Any, list[int] | None, list[tuple[int, int, Any]]]:
        """The chain's commensurate screw matrix (..., rows, k) at current screws ``S``
        (any batch shape and backend; ``scaled``: ``model.frame.screws(S)`` when already
        computed, whose columns are then taken: the same numbers), with the kept columns
        and folded followers (:class:`ChainSystem`)."""
        if scaled is not None and point_x is None:
            Ms = scaled[..., list(columns)]
        else:
            Ms = chain_matrix(self.model, S, columns, point_x)
        kept: list[int] | None = None
        follows: list[tuple[int, int, Any]] = []
        if self.coupled:
            Ms, kept, follows = fold_columns(self.model, Ms, list(columns))
        return Ms, kept, follows

    def decide(
        self,
        S: Any,
        columns: list[int],
        point_x: Any,
        precision: Any,
        scaled: Any = None,
    ) -> ChainSystem:
        """The chain's screw system at one configuration and its rank decided at
        ``precision`` (with its margin)."""
        Ms, kept, follows = self.matrix(S, columns, point_x, scaled)
        dec = decide_rank(Ms, precision, self.model.length_scale)
        return ChainSystem(Ms, dec, columns, point_x is not None, kept, follows)

    @staticmethod
    def register_screen(backend: Any) -> None:
        """Register a compiled screen (an object with ``available()`` and
        ``screen_bounds(chain, Q, err)``): :meth:`screen` then serves through it."""
        if backend not in _SCREENS:
            _SCREENS.append(backend)

    @staticmethod
    def compiled_screen() -> Any:
        """The first registered compiled screen that is available here, or None."""
        return next((b for b in _SCREENS if b.available()), None)

    def screen(self, chain: Any, Q: np.ndarray, err: float) -> np.ndarray | None:
        """The certified lower bound of sigma_min / sigma_max of the serial chain ``chain``
        (a :class:`~mechsing.kinematics.forward.SerialJacobian`) at every row of Q, lowered
        by the determinant's backward error ``err``, by the compiled screen; None when no
        compiled screen is available (the caller's numpy screen then serves)."""
        backend = self.compiled_screen()
        return None if backend is None else backend.screen_bounds(chain, Q, err)

    def batch_ranks(self, M: np.ndarray) -> RankBounds:
        """The float rank bounds of a batch of the chain's matrices (..., rows, k)."""
        return self.ranks(singular_values(M))
