"""The input/output tests (Zlatanov, Fenton, Benhabib 1995), defined once: the output
map ``T`` (commensurate twists of the output body relative to ``relative_to``, or the
output point's velocities), the input selection ``E``, and their products with an
orthonormal basis ``N`` of the closure kernel (the motion space K).

* ``input``: dim E(K cap ker T) = rank [T N; E N] - rank T N;
* ``output``: dim T(K cap ker E) = rank [T N; E N] - rank E N;
* ``passive-motion``: dim (K cap ker E cap ker T) = m - rank [T N; E N];
* ``impossible-input``: rank E N;  ``impossible-output``: rank T N.

Reference: ``T N`` is decided relative to |T| (the operator's norm: N is orthonormal,
so a product that vanishes is rank 0, not its own rounding), ``E N`` relative to
|E| = 1, the stacked ``[T N / |T|; E N]`` relative to 1.  Every dimension is a
difference of ranks each decided on its own singular values (a kernel of T N taken near
a singularity would carry its error into a false motion).

:meth:`MotionTest.decide` decides one configuration at any precision (with margins and
the kernels that witness the motions); :meth:`MotionTest.batch_values` decides a batch
of float configurations by the one batched rank rule.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing import lie
from mechsing.kinematics.chains import tree_chain
from mechsing.kinematics.protocol import ClosureModel
from mechsing.model import Mechanism
from mechsing.numeric import Precision, RankDecision, decide_rank, rank_difference
from mechsing.numeric.linalg import spectral_norm
from mechsing.screws import chain_matrix
from mechsing.singularity.criteria.base import Criterion, singular_values

__all__ = ["IO_TESTS", "IOQuantities", "MotionTest", "input_rows", "tests_run"]

#: the input/output tests, in the order every output lists them
IO_TESTS = ("input", "output", "passive-motion", "impossible-input", "impossible-output")
#: the tests that need the output (the constraint test and the legs' serial test too)
NEED_OUTPUT = ("input", "output", "passive-motion", "impossible-output", "constraint", "serial")
#: the tests that need inputs
NEED_INPUTS = ("input", "output", "passive-motion", "impossible-input")


def tests_run(mech: Mechanism) -> tuple[str, ...]:
    """The input/output tests (:data:`IO_TESTS`) whose ingredients the mechanism has:
    all five with inputs and an output; ``impossible-input`` with inputs alone (the rank
    of the inputs on the motion space: where an input loses its independent rate);
    ``impossible-output`` with an output alone."""
    has_in, has_out = bool(mech.inputs), mech.output is not None
    return tuple(
        t
        for t in IO_TESTS
        if (has_in or t not in NEED_INPUTS) and (has_out or t not in NEED_OUTPUT)
    )


def input_rows(mech: Mechanism, model: ClosureModel) -> np.ndarray | None:
    """Selection E of the actuated coordinates (rows), commensurate (lengths / L)."""
    coords = mech.input_coordinates()
    if not coords:
        return None
    E = np.zeros((len(coords), model.n))
    for i, (j, k) in enumerate(coords):
        E[i, model.joint(j).columns.start + k] = 1.0
    return E


@dataclass
class IOQuantities:
    """Dimensions of the ZFB subspaces at one configuration, decided at one
    precision (float, or mp:N with every space an N-digit object array)."""

    input_motion: RankDecision  # E applied to K cap ker T
    output_motion: RankDecision  # T applied to K cap ker E
    passive_motion: int | None  # dim K cap ker E cap ker T
    input_rank: RankDecision  # rank E N
    output_rank: RankDecision  # rank T N
    spaces: dict[str, Any]
    #: the tests these quantities answer (:func:`tests_run`: all five unless the
    #: mechanism has no output or no inputs)
    run: tuple[str, ...] = IO_TESTS

    def values(self) -> dict[str, int | None]:
        """The dimensions of the tests run; None where undecided.  K cap ker T rests on
        the decision of rank T N and K cap ker E on that of rank E N: when those are
        undecided, so are the motion spaces built on them (their kernel was taken at a
        guessed rank)."""
        return _values(
            self.output_rank.rank,
            self.input_rank.rank,
            self.input_motion.rank,
            self.output_motion.rank,
            self.passive_motion,
            self.run,
        )


def _values(
    rT: int | None,
    rE: int | None,
    input_motion: int | None,
    output_motion: int | None,
    passive: int | None,
    run: tuple[str, ...],
) -> dict[str, int | None]:
    """The tests' values from the decided ranks of T N and E N (None: undecided) and the
    motions' dimensions: a motion resting on an undecided rank is undecided."""
    out_ok, in_ok = rT is not None, rE is not None
    every = {
        "input": input_motion if out_ok else None,
        "output": output_motion if in_ok else None,
        "passive-motion": passive if (in_ok and out_ok) else None,
        "impossible-input": rE,
        "impossible-output": rT,
    }
    return {t: every[t] for t in run}


def _difference(a: tuple[int, int], b: tuple[int, int]) -> int | None:
    """:func:`mechsing.numeric.rank_difference` of two rank bounds: the decided rank of
    ``a - b`` (None: undecided)."""
    lo, hi = max(0, a[0] - b[1]), max(0, a[1] - b[0])
    return lo if lo == hi else None


def _decided(b: tuple[int, int]) -> int | None:
    """The rank of bounds (lowest, highest): decided when they agree."""
    return b[0] if b[0] == b[1] else None


def _null(A: np.ndarray, L: float, prec: Precision, reference: Any = None) -> np.ndarray | None:
    if A.shape[0] == 0:
        return prec.backend.eye(A.shape[1])
    dec = decide_rank(A, prec, L, want_spaces=True, reference=reference, native_spaces=True)
    return dec.null_space


def _kernel(
    A: np.ndarray, dec: RankDecision, L: float, prec: Precision, reference: Any
) -> np.ndarray | None:
    """:func:`_null` of ``A`` whose decision without spaces is ``dec``: a decided full
    column rank has an empty kernel (no second SVD)."""
    if dec.rank is not None and dec.rank == A.shape[1]:
        return prec.backend.zeros((A.shape[1], 0))
    return _null(A, L, prec, reference)


class MotionTest(Criterion):
    """The input/output tests of one mechanism and model; plan: ``E`` (None without
    inputs), the output chain's signs and point (None without an output), the tests run."""

    name = "motion"
    reference = "T N relative to |T|; E N relative to |E| = 1; [T N / |T|; E N] relative to 1"

    def __init__(self, mech: Mechanism, model: ClosureModel) -> None:
        super().__init__(mech, model)
        self.run = tests_run(mech)
        self.E = input_rows(mech, model)
        out = mech.output
        self.out_signs = None
        #: the output point in floats (the batches) and in the model's numbers
        self.out_point = self.point = None
        if out is not None:
            self.out_signs = tree_chain(model, out.body, out.relative_to).signs
            if out.point is not None:
                self.out_point = np.array([float(x) for x in out.point])
                self.point = model.asarray(list(out.point))

    # ------------------------------------------------------------------ matrices

    def output_point(self, poses: dict[str, Any], float_point: bool = False) -> Any:
        """The output point at the poses (any batch shape; None without one): in the
        model's numbers, or from the float point with ``float_point``."""
        if self.point is None:
            return None
        x0 = self.out_point if float_point else self.point
        out = self.mech.output
        assert out is not None  # a point is an output's
        return lie.act_point(poses[out.body], x0)

    def output_rows(self, S: Any, x: Any = None) -> np.ndarray:
        """The commensurate output map T at current screws ``S`` (..., 6, n): twists, or the
        velocities of the output point ``x`` over L."""
        return chain_matrix(self.model, S, None, x, self.out_signs)

    # ------------------------------------------------------------------ one configuration

    def decide(
        self,
        T: np.ndarray,
        E: np.ndarray,
        N: np.ndarray,
        prec: Precision,
        products: tuple[np.ndarray, np.ndarray] | None = None,
    ) -> IOQuantities:
        """The tests at one configuration, decided at ``prec`` with margins: ``T`` and
        ``E`` (no rows for a missing side) and ``N`` in the numbers of ``prec``;
        ``products``: ``(T N, E N)`` when formed more exactly by the caller."""
        L = self.model.length_scale
        bk = prec.backend
        m = N.shape[1]
        TN, EN = products if products is not None else (T @ N, E @ N)
        nT = spectral_norm(T)
        nE = 1.0
        if prec.mode == "float" and m:
            # the ranks with their kernels (below): in float a decision with spaces has the
            # singular values, rank and margin of the one without
            rT = decide_rank(TN, prec, L, want_spaces=True, reference=nT)
            rE = decide_rank(EN, prec, L, want_spaces=True, reference=nE)
        else:
            rT = decide_rank(TN, prec, L, reference=nT)
            rE = decide_rank(EN, prec, L, reference=nE)
        both = np.vstack([TN / max(nT, 1e-300), EN]) if m else np.zeros((0, 0))
        if m:
            rB = decide_rank(both, prec, L, reference=1.0)
            passive = None if rB.rank is None else m - rB.rank
        else:
            rB = decide_rank(np.zeros((T.shape[0] + E.shape[0], 0)), prec, L)
            passive = 0
        # witnesses of the motions (for the joint rates of a finding): the kernels at the
        # decided (or guessed) ranks
        if prec.mode == "float" and m:
            zT, zE = rT.null_space, rE.null_space
        else:
            zT = _kernel(TN, rT, L, prec, nT) if m else bk.zeros((0, 0))
            zE = _kernel(EN, rE, L, prec, nE) if m else bk.zeros((0, 0))
        return IOQuantities(
            rank_difference(rB, rT),  # dim E(K cap ker T) = rank [TN; EN] - rank TN
            rank_difference(rB, rE),  # dim T(K cap ker E) = rank [TN; EN] - rank EN
            passive,
            rE,
            rT,
            {"T": T, "E": E, "N": N, "zT": zT, "zE": zE, "nT": nT},
            self.run,
        )

    # ------------------------------------------------------------------ batches

    def batch_values(
        self, T: np.ndarray, nT: np.ndarray, N: np.ndarray
    ) -> list[dict[str, int | None]]:
        """The tests' values at a batch of float configurations (B) with kernels of one
        width: ``T`` (B, r, n) and its norms ``nT`` (B), ``N`` (B, n, k); the same
        products, references and rule as :meth:`decide`."""
        B, k = N.shape[0], N.shape[2]
        if k == 0:  # no motion: every rank 0, nothing passive
            return [_values(0, 0, 0, 0, 0, self.run) for _ in range(B)]
        E = self.E if self.E is not None else np.zeros((0, self.model.n))
        TN = T @ N
        EN = E @ N
        rT = self.ranks(singular_values(TN), nT)
        rE = self.ranks(singular_values(EN), 1.0)
        both = np.concatenate([TN / np.maximum(nT, 1e-300)[:, None, None], EN], axis=1)
        rB = self.ranks(singular_values(both), 1.0)
        return [self._one(rT.pair(b), rE.pair(b), rB.pair(b), k) for b in range(B)]

    def _one(
        self, bT: tuple[int, int], bE: tuple[int, int], bB: tuple[int, int], k: int
    ) -> dict[str, int | None]:
        """The values from the rank bounds of T N, E N and [T N; E N] (kernel width k)."""
        passive = k - bB[0] if bB[0] == bB[1] else None
        return _values(
            _decided(bT), _decided(bE), _difference(bB, bT), _difference(bB, bE), passive, self.run
        )

    def batch_output_rows(self, S: np.ndarray, P: dict[str, np.ndarray]) -> tuple[Any, Any]:
        """T at a batch of float configurations (screws ``S`` (B, 6, n), poses ``P``) and its
        norms |T| (the largest singular value of each); without an output, no rows and
        norms 1 (only the inputs' test is read)."""
        B = S.shape[0]
        if self.mech.output is None:
            return np.zeros((B, 0, self.model.n)), np.ones(B)
        T = self.output_rows(S, self.output_point(P, float_point=True))
        return T, singular_values(T)[:, 0]
