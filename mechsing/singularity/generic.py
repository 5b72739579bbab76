"""The generic values of the input/output, constraint and leg tests at a configuration's
regular nearby samples, computed for many samples at once.

The local analysis (:mod:`mechsing.singularity.local`) decides each test at q and
measures it against its values at the regular nearby samples of q's branch: the five
ZFB dimensions (:func:`mechsing.singularity.zfb.io_quantities`), the rank of the legs'
combined constraint wrenches (:func:`~mechsing.singularity.zfb.leg_constraint_rank`)
and the rank of each leg's own screw system (``serial`` per leg).  At the samples these
are float decisions, the same ones as those functions take one sample at a time: the
same matrices, singular values by the same LAPACK routine (numpy's batched SVD runs it
matrix by matrix) and the ranks by the same two-threshold rule
(:func:`mechsing.numeric.rank_bounds`, relative to the same references as
:func:`~mechsing.numeric.decide_rank`).  Only the Python work is shared: the poses and
screws of all the samples come from one batched product of exponentials
(:mod:`mechsing.kinematics.forward`, the analysis's own exponential), each test's
matrices are stacked and factorised together, and what depends only on the mechanism
(the input rows, the output chain, the legs' columns and paths) is built once per model.

A mechanism with a leg that holds loops of its own (a parallelogram in a leg) has its
legs' twist systems over those loops' solutions: their constraint rank at each sample is
taken one sample at a time, from the sample's closure system, as before.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing import lie
from mechsing.kinematics import forward
from mechsing.kinematics.chains import tree_chain
from mechsing.kinematics.couplings import fold_columns
from mechsing.numeric import Precision, decide_rank, rank_bounds
from mechsing.numeric.blocks import dense
from mechsing.screws import chain_matrix, closure_system
from mechsing.screws.mobility import NearbySample, stacked_jacobian
from mechsing.singularity.serial import chain_system
from mechsing.singularity.zfb import (
    input_rows,
    io_quantities,
    leg_constraint_rank,
    leg_path,
    tests_run,
)

__all__ = [
    "LegPlan",
    "MechanismPlan",
    "SampleValues",
    "mechanism_plan",
    "one_sample_values",
    "sample_values",
]

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


@dataclass(frozen=True)
class LegPlan:
    """A leg of a parallel mechanism, as its tests use it: its coordinate columns, the
    joint of each column, the signs of its path from the base to the output body (one
    per coordinate), and whether loops of its own lie inside it."""

    columns: list[int]
    names: list[str]
    path_signs: np.ndarray
    inner_loops: bool


@dataclass(frozen=True)
class MechanismPlan:
    """What the tests at any configuration of one (float) model share: the input rows E,
    the output chain's signs and point, and the legs (empty with fewer than two)."""

    E: np.ndarray | None
    out_signs: np.ndarray | None
    out_point: np.ndarray | None
    legs: tuple[LegPlan, ...]


def mechanism_plan(mech: Any, model: Any) -> MechanismPlan:
    """The :class:`MechanismPlan` of ``mech`` for ``model`` (built once per model)."""
    plan = getattr(model, "_tests_plan", None)
    if plan is not None and plan[0] is mech:
        return plan[1]
    out = mech.output
    E = input_rows(mech, model)
    signs = point = None
    legs: list[LegPlan] = []
    if out is not None:
        signs = tree_chain(model, out.body, out.relative_to).signs
        if out.point is not None:
            point = np.array([float(x) for x in out.point])
        mech_legs = mech.legs
        if len(mech_legs) >= 2:
            for leg in mech_legs:
                legset = set(leg.joints)
                cols, names = [], []
                for j in leg.joints:
                    jk = model.joint(j)
                    cols.extend(range(jk.columns.start, jk.columns.stop))
                    names.extend([jk.name] * (jk.columns.stop - jk.columns.start))
                coef = np.zeros(model.n)
                for jn, sg in leg_path(mech, leg, out.relative_to, out.body):
                    coef[model.joint(jn).columns] = sg
                inner = any(set(lp.joints) <= legset for lp in mech.loops)
                legs.append(LegPlan(cols, names, coef, inner))
    built = MechanismPlan(E, signs, point, tuple(legs))
    model._tests_plan = (mech, built)
    return built


def _ranks(s: np.ndarray, reference: np.ndarray | float | None = None) -> tuple[Any, Any]:
    """The two-threshold rank bounds (lowest, highest) of each row of singular values
    ``s`` (B, k), descending, as :func:`mechsing.numeric.decide_rank` decides them: relative
    to the largest, or to ``reference`` where it is larger."""
    B, k = s.shape
    if k == 0:
        zero = np.zeros(B, dtype=int)
        return zero, zero
    smax = s[:, 0].copy()
    if reference is not None:
        ref = np.broadcast_to(np.asarray(reference, dtype=float), (B,))
        smax = np.where(ref > smax, ref, smax)
    positive = smax > 0
    rel = np.where(positive[:, None], s / np.where(positive, smax, 1.0)[:, None], 0.0)
    return rank_bounds(rel, _FLOAT.tolerances)


def _decided(lo: Any, hi: Any) -> list[int | None]:
    return [int(a) if a == b else None for a, b in zip(lo.tolist(), hi.tolist(), strict=True)]


def _difference(a: tuple[int, int], b: tuple[int, int]) -> int | None:
    """:func:`mechsing.numeric.rank_difference` of two rank bounds: the decided rank of
    ``a - b`` (None: undecided)."""
    lo, hi = max(0, a[0] - b[1]), max(0, a[1] - b[0])
    return lo if lo == hi else None


def _singular_values(A: np.ndarray) -> np.ndarray:
    """The singular values (B, min(m, n)) of a stack of matrices (B, m, n)."""
    if A.shape[1] == 0 or A.shape[2] == 0:
        return np.zeros((A.shape[0], 0))
    return np.linalg.svd(A, compute_uv=False)


def sample_values(mech: Any, model: Any, samples: list[NearbySample]) -> list[SampleValues]:
    """The float values of the tests at each of ``samples`` (closed float configurations
    with their closure kernels), as :func:`mechsing.singularity.local` measures its tests
    against them (``model``: the float model)."""
    if not samples:
        return []
    plan = mechanism_plan(mech, model)
    samples = [_with_kernel(model, s) for s in samples]
    if not dense(6 * model.n) or model.sparse_closure:
        # a big mechanism: its matrices are factorised block by block (decide_rank's
        # block_svd), one sample at a time
        return [one_sample_values(mech, model, s) for s in samples]
    Q = np.array([s.q for s in samples], dtype=float)
    P = forward.poses(model, Q)
    S = forward.current_screws(model, Q, P)
    has_io = bool(tests_run(mech))
    io = _io_values(mech, model, plan, samples, S, P) if has_io else [None] * len(samples)
    constraint: list[int | None] = [None] * len(samples)
    legs: list[tuple[tuple[np.ndarray, int | None], ...]] = [()] * len(samples)
    if plan.legs:
        Ss = model.frame.screws(S)
        constraint = _constraint_values(mech, model, plan, samples, Ss)
        legs = _leg_values(mech, model, plan, S, P)
    return [SampleValues(a, b, c) for a, b, c in zip(io, constraint, legs, strict=True)]


def _with_kernel(model: Any, s: NearbySample) -> NearbySample:
    """The sample with its closure kernel (decided again when it came without one)."""
    if s.kernel is not None:
        return s
    dec = decide_rank(stacked_jacobian(model, s.q), "float", model.length_scale, want_spaces=True)
    return NearbySample(s.q, s.nullity, s.distance, dec.null_space)


def one_sample_values(mech: Any, model: Any, s: NearbySample) -> SampleValues:
    """:class:`SampleValues` of one sample (with its kernel), by the functions that decide
    the tests at q: :func:`~mechsing.singularity.zfb.io_quantities`,
    :func:`~mechsing.singularity.zfb.leg_constraint_rank` on the sample's closure system and
    :func:`~mechsing.singularity.serial.chain_system` per leg."""
    plan = mechanism_plan(mech, model)
    S = model.current_screws(s.q)
    io = None
    if tests_run(mech):
        g = io_quantities(mech, model, s.q, s.kernel, screws=S)
        io = None if g is None else g.values()
    constraint = None
    legs: tuple[tuple[np.ndarray, int | None], ...] = ()
    if plan.legs:
        r = leg_constraint_rank(mech, model, s.q, closure_system(model, s.q))
        constraint = None if r is None else r[0].rank
        x = None
        if plan.out_point is not None:
            x = lie.act_point(model.poses(s.q)[mech.output.body], plan.out_point)
        systems = [chain_system(model, S, leg.columns, x, "float") for leg in plan.legs]
        legs = tuple((c.matrix, c.rank.rank) for c in systems)
    return SampleValues(io, constraint, legs)


def _io_values(
    mech: Any,
    model: Any,
    plan: MechanismPlan,
    samples: list[NearbySample],
    S: np.ndarray,
    P: dict[str, np.ndarray],
) -> list[dict[str, int | None] | None]:
    """:meth:`IOQuantities.values` of :func:`~mechsing.singularity.zfb.io_quantities` at each
    sample (its kernel the sample's), batched: the same products and decisions."""
    B = S.shape[0]
    if mech.output is not None:
        x = None
        if plan.out_point is not None:
            x = lie.act_point(P[mech.output.body], plan.out_point)
        T = chain_matrix(model, S, None, x, plan.out_signs)
        # |T|: the largest singular value of each T, the reference of T N's decision
        nT = _singular_values(T)[:, 0]
    else:  # no output: no rows (rank 0), only the inputs' test is read
        T, nT = np.zeros((B, 0, model.n)), np.ones(B)
    # no inputs: no rows, only the output's test is read
    E = plan.E if plan.E is not None else np.zeros((0, model.n))
    run = tests_run(mech)
    out: list[dict[str, int | None] | None] = [None] * len(samples)
    widths: dict[int, list[int]] = {}
    for i, s in enumerate(samples):
        widths.setdefault(s.kernel.shape[1], []).append(i)
    for k, idx in widths.items():
        ix = np.array(idx)
        if k == 0:
            # no motion: every rank 0, nothing passive
            for i in idx:
                out[i] = _io_dict((0, 0), (0, 0), (0, 0), 0, run)
            continue
        N = np.array([samples[i].kernel for i in idx], dtype=float)
        TN = T[ix] @ N
        EN = E @ N
        rT = _ranks(_singular_values(TN), nT[ix])
        rE = _ranks(_singular_values(EN), 1.0)
        both = np.concatenate([TN / np.maximum(nT[ix], 1e-300)[:, None, None], EN], axis=1)
        rB = _ranks(_singular_values(both), 1.0)
        for j, i in enumerate(idx):
            bT = (int(rT[0][j]), int(rT[1][j]))
            bE = (int(rE[0][j]), int(rE[1][j]))
            bB = (int(rB[0][j]), int(rB[1][j]))
            passive = k - bB[0] if bB[0] == bB[1] else None
            out[i] = _io_dict(bT, bE, bB, passive, run)
    return out


def _io_dict(
    rT: tuple[int, int],
    rE: tuple[int, int],
    rB: tuple[int, int],
    passive: int | None,
    run: tuple[str, ...],
) -> dict[str, int | None]:
    """:meth:`IOQuantities.values` from the rank bounds of T N, E N and [T N; E N], for
    the tests ``run``."""
    out_ok = rT[0] == rT[1]
    in_ok = rE[0] == rE[1]
    every = {
        "input": _difference(rB, rT) if out_ok else None,
        "output": _difference(rB, rE) if in_ok else None,
        "passive-motion": passive if (in_ok and out_ok) else None,
        "impossible-input": rE[0] if in_ok else None,
        "impossible-output": rT[0] if out_ok else None,
    }
    return {t: every[t] for t in run}


def _constraint_values(
    mech: Any, model: Any, plan: MechanismPlan, samples: list[NearbySample], Ss: np.ndarray
) -> list[int | None]:
    """The decided rank of the legs' combined constraint wrenches at each sample
    (:func:`~mechsing.singularity.zfb.leg_constraint_rank`), batched when no leg holds
    loops of its own."""
    if any(leg.inner_loops for leg in plan.legs):
        out: list[int | None] = []
        for s in samples:
            r = leg_constraint_rank(mech, model, s.q, closure_system(model, s.q))
            out.append(None if r is None else r[0].rank)
        return out
    B = Ss.shape[0]
    wrenches = []
    keep = []
    for leg in plan.legs:
        # the leg's twists through its path (no inner loop: its kernel is the identity)
        Tl = (Ss * leg.path_signs[None, None, :])[:, :, leg.columns]
        lo, hi = _ranks(_singular_values(Tl))
        U = np.linalg.svd(Tl, full_matrices=True)[0]
        # the rank taken: the decided one, else the highest the bounds allow
        r = np.where(lo == hi, lo, hi)
        wrenches.append(U)
        keep.append(r)
    out = [None] * B
    groups: dict[tuple[int, ...], list[int]] = {}
    for b in range(B):
        groups.setdefault(tuple(int(r[b]) for r in keep), []).append(b)
    for ranks, idx in groups.items():
        ix = np.array(idx)
        Wc = np.concatenate([U[ix][:, :, r:] for U, r in zip(wrenches, ranks, strict=True)], axis=2)
        if Wc.shape[2] == 0:
            for b in idx:
                out[b] = 0
            continue
        lo, hi = _ranks(_singular_values(np.swapaxes(Wc, 1, 2)))
        for b, v in zip(idx, _decided(lo, hi), strict=True):
            out[b] = v
    return out


def _leg_values(
    mech: Any, model: Any, plan: MechanismPlan, S: np.ndarray, P: dict[str, np.ndarray]
) -> list[tuple[tuple[np.ndarray, int | None], ...]]:
    """Each leg's commensurate screw matrix (the output point's velocities when the
    output names a point, as for the output chain) and its decided rank at each sample
    (the float twin of :func:`mechsing.singularity.serial.chain_system`)."""
    x = None
    if plan.out_point is not None:
        x = lie.act_point(P[mech.output.body], plan.out_point)
    per_leg = []
    for leg in plan.legs:
        M = chain_matrix(model, S, leg.columns, x)
        if model.couplings:  # a follower folded into its leader's column, as chain_system
            M = fold_columns(model, M, list(leg.columns))[0]
        lo, hi = _ranks(_singular_values(M))
        per_leg.append((M, _decided(lo, hi)))
    return [tuple((M[b], ranks[b]) for M, ranks in per_leg) for b in range(S.shape[0])]
