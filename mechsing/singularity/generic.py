"""The generic values of the input/output, constraint and leg tests at a configuration's
regular nearby samples, computed for many samples at once.

The local analysis (:mod:`mechsing.singularity.local`) decides each test at q and
measures it against its values at the regular nearby samples of q's branch: the five
ZFB dimensions, the rank of the legs' combined constraint wrenches and the rank of each
leg's own screw system (``serial`` per leg).  Each test is the one of
:mod:`mechsing.singularity.criteria` (:class:`~mechsing.singularity.criteria.MotionTest`,
:class:`~mechsing.singularity.criteria.ConstraintTest`,
:class:`~mechsing.singularity.criteria.SerialTest`), called here with a batch of float
samples: the poses and screws of all the samples come from one batched product of
exponentials (:mod:`mechsing.kinematics.forward`, the analysis's own exponential) and
each test's matrices are stacked and decided together.  What is this module's own: the
grouping of the samples by kernel width, and the fallback to one sample at a time (a big
mechanism factorised block by block; the constraint rank of a leg that holds loops of its
own, from the sample's closure system).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing.kinematics import forward
from mechsing.numeric import Precision, decide_rank
from mechsing.numeric.blocks import dense
from mechsing.screws import closure_system
from mechsing.screws.mobility import NearbySample, stacked_jacobian
from mechsing.singularity.criteria import ConstraintTest, MotionTest, SerialTest
from mechsing.singularity.zfb import io_quantities

__all__ = ["SampleValues", "one_sample_values", "sample_values"]

_FLOAT = Precision("float")


@dataclass(frozen=True)
class SampleValues:
    """The float values of the tests at one nearby sample.

    ``io``: the five ZFB dimensions (:meth:`IOQuantities.values`; None without inputs
    and output); ``constraint``: the decided rank of the legs' combined constraint
    wrenches (None: undecided, or not a parallel mechanism); ``legs``: per leg, its
    commensurate screw matrix at the sample and its decided rank (None: undecided)."""

    io: dict[str, int | None] | None
    constraint: int | None
    legs: tuple[tuple[np.ndarray, int | None], ...]


def sample_values(mech: Any, model: Any, samples: list[NearbySample]) -> list[SampleValues]:
    """The float values of the tests at each of ``samples`` (closed float configurations
    with their closure kernels), as :func:`mechsing.singularity.local` measures its tests
    against them (``model``: the float model)."""
    if not samples:
        return []
    samples = [_with_kernel(model, s) for s in samples]
    if not dense(6 * model.n) or model.sparse_closure:
        # a big mechanism: its matrices are factorised block by block (decide_rank's
        # block_svd), one sample at a time
        return [one_sample_values(mech, model, s) for s in samples]
    motion = MotionTest.of(mech, model)
    constraint = ConstraintTest.of(mech, model)
    Q = np.array([s.q for s in samples], dtype=float)
    P = forward.poses(model, Q)
    S = forward.current_screws(model, Q, P)
    io = _io_values(motion, samples, S, P) if motion.run else [None] * len(samples)
    ranks: list[int | None] = [None] * len(samples)
    legs: list[tuple[tuple[np.ndarray, int | None], ...]] = [()] * len(samples)
    if constraint.legs:
        if any(leg.inner_loops for leg in constraint.legs):
            # the legs' twists over their inner loops' solutions: from each closure system
            ranks = [_one_constraint(constraint, model, s.q) for s in samples]
        else:
            ranks = constraint.batch_values(model.frame.screws(S))
        legs = _leg_values(mech, model, constraint, motion, S, P)
    return [SampleValues(a, b, c) for a, b, c in zip(io, ranks, legs, strict=True)]


def _with_kernel(model: Any, s: NearbySample) -> NearbySample:
    """The sample with its closure kernel (decided again when it came without one)."""
    if s.kernel is not None:
        return s
    dec = decide_rank(stacked_jacobian(model, s.q), "float", model.length_scale, want_spaces=True)
    return NearbySample(s.q, s.nullity, s.distance, dec.null_space)


def _one_constraint(test: ConstraintTest, model: Any, q: np.ndarray) -> int | None:
    r = test.decide(closure_system(model, q), _FLOAT)
    return None if r is None else r[0].rank


def one_sample_values(mech: Any, model: Any, s: NearbySample) -> SampleValues:
    """:class:`SampleValues` of one sample (with its kernel), by the tests' decisions of
    one configuration: :func:`~mechsing.singularity.zfb.io_quantities`,
    :meth:`ConstraintTest.decide` on the sample's closure system and
    :meth:`SerialTest.decide` per leg."""
    constraint = ConstraintTest.of(mech, model)
    S = model.current_screws(s.q)
    io = None
    if MotionTest.of(mech, model).run:
        g = io_quantities(mech, model, s.q, s.kernel, screws=S)
        io = None if g is None else g.values()
    rank = None
    legs: tuple[tuple[np.ndarray, int | None], ...] = ()
    if constraint.legs:
        rank = _one_constraint(constraint, model, s.q)
        x = MotionTest.of(mech, model).output_point(model.poses(s.q), float_point=True)
        serial = SerialTest.of(mech, model)
        systems = [serial.decide(S, leg.columns, x, "float") for leg in constraint.legs]
        legs = tuple((c.matrix, c.rank.rank) for c in systems)
    return SampleValues(io, rank, legs)


def _io_values(
    motion: MotionTest, samples: list[NearbySample], S: np.ndarray, P: dict[str, np.ndarray]
) -> list[dict[str, int | None] | None]:
    """The input/output tests' values at each sample (its kernel the sample's), batched
    by kernel width."""
    T, nT = motion.batch_output_rows(S, P)
    out: list[dict[str, int | None] | None] = [None] * len(samples)
    widths: dict[int, list[int]] = {}
    for i, s in enumerate(samples):
        widths.setdefault(s.kernel.shape[1], []).append(i)
    for idx in widths.values():
        ix = np.array(idx)
        N = np.array([samples[i].kernel for i in idx], dtype=float)
        for i, v in zip(idx, motion.batch_values(T[ix], nT[ix], N), strict=True):
            out[i] = v
    return out


def _leg_values(
    mech: Any,
    model: Any,
    constraint: ConstraintTest,
    motion: MotionTest,
    S: np.ndarray,
    P: dict[str, np.ndarray],
) -> list[tuple[tuple[np.ndarray, int | None], ...]]:
    """Each leg's commensurate screw matrix (the output point's velocities when the
    output names a point, as for the output chain) and its decided rank at each sample."""
    x = motion.output_point(P, float_point=True)
    serial = SerialTest.of(mech, model)
    per_leg = []
    for leg in constraint.legs:
        M = serial.matrix(S, leg.columns, x)[0]
        per_leg.append((M, serial.batch_ranks(M).ranks()))
    return [tuple((M[b], ranks[b]) for M, ranks in per_leg) for b in range(S.shape[0])]
