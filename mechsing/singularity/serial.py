"""Rank loss of an open chain's screw system (open-chain singularities; the class ``serial``).

The screw system of a chain at q is the matrix of its joints' current screws
(columns).  For the output of a positioning task (a body point) it is the
velocity of that point, ``v + omega x x`` (3 rows).  Its rank is compared
with the generic rank (the largest found at random configurations); where it
is lower the chain now *resists*, with zero joint effort, wrenches it
generically could not: the reciprocal system grows.

Reported keys (SI, (f, m) at the ground origin): ``wrenches`` -- a basis of the
whole reciprocal system, each with unit force (unit moment for a couple) and
first non-zero component positive; ``corank``; ``twist`` -- a lost twist with
non-zero power against a new wrench; ``null_joint_rates`` -- a kernel vector
(largest entry 1) and its support ``joints`` (entries above
:data:`mechsing.numeric.SUPPORT_RTOL` of the largest).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing.numeric import (
    MEMBERSHIP_RTOL_FLOAT,
    SUPPORT_RTOL,
    CommensurateFrame,
    RankDecision,
    decide_rank,
    to_float,
)
from mechsing.screws import chain_matrix
from mechsing.singularity.findings import SerialFinding

#: random configurations sampled to find a chain's generic rank
GENERIC_SAMPLES = 8


@dataclass
class ChainSystem:
    """A chain's screw system at q: commensurate matrix, its rank decision and
    the maps back to SI quantities."""

    matrix: np.ndarray  # commensurate (rows: 6 twist or 3 point-velocity; cols: chain coordinates)
    rank: RankDecision
    columns: list[int]  # coordinate indices of the chain
    point: bool  # positioning task (3 rows)


def _unit_first_positive(v: np.ndarray) -> np.ndarray:
    """First non-zero component positive (the README's conventions), with components at rounding
    level (below SUPPORT_RTOL of the largest) reported as 0."""
    v = np.asarray(v, dtype=float)
    big = max(1.0, float(np.max(np.abs(v)))) if v.size else 1.0
    v = np.where(np.abs(v) > SUPPORT_RTOL * big, v, 0.0)
    nz = np.flatnonzero(v)
    if len(nz) and v[nz[0]] < 0:
        v = -v
    return v + 0.0  # no -0.0


def wrenches_of(frame: CommensurateFrame, null_rows: np.ndarray, point: bool) -> list[list[float]]:
    """SI wrenches (f, m) at the ground origin from commensurate left-null vectors
    (columns of ``null_rows``), each a unit force (a unit moment for a couple), first
    non-zero component positive."""
    out = []
    for y in null_rows.T:
        if point:
            # a force through the point: f with f . v_point = 0 for all joint motions
            f = y / np.linalg.norm(y)
            # the force acts at the point x: moment about the origin x x f (filled by caller)
            out.append(np.concatenate([f, np.zeros(3)]))
            continue
        w = frame.wrench_back(y)  # (f, m): f . v + m . omega = y . (commensurate twist)
        f, m = w[:3], w[3:]
        nf = np.linalg.norm(f)
        # a couple when the force is zero next to the moment (unit moment, else unit force)
        couple = nf <= MEMBERSHIP_RTOL_FLOAT * np.linalg.norm(m)
        w = w / np.linalg.norm(m) if couple else w / nf
        out.append(w)
    return [_unit_first_positive(np.asarray(x)).tolist() for x in out]


def serial_finding(
    model: Any,
    system: ChainSystem,
    generic_rank: int,
    joints_of_columns: list[str],
    label: dict[str, Any],
    point_x: np.ndarray | None = None,
) -> SerialFinding | None:
    """The ``serial`` finding of a chain whose rank is below ``generic_rank`` (else None);
    ``label``: ``chain`` ("output" with ``body`` and ``relative_to``, or "leg" with ``leg``)."""
    dec = system.rank
    if dec.rank is None or dec.rank >= generic_rank:
        return None
    # the rank was decided at the analysis precision; the vectors that describe
    # the loss (wrenches, lost twist, null rates) come from a float SVD
    Ms = np.asarray(to_float(system.matrix), dtype=float)
    U, s, Vt = np.linalg.svd(Ms)
    r = dec.rank
    left_null = U[:, r:]
    fr = model.float_frame
    wr = wrenches_of(fr, left_null, system.point)
    if system.point and point_x is not None:
        wr = [
            _unit_first_positive(
                np.concatenate([np.array(w[:3]), np.cross(point_x, w[:3])])
            ).tolist()
            for w in wr
        ]
    lost = U[:, r]
    if system.point:
        twist = np.concatenate([np.zeros(3), fr.velocity_back(lost)]).tolist()
    else:
        twist = fr.twist_back(lost).tolist()
    kernel = Vt[r:].T if Vt.shape[0] > r else np.zeros((Ms.shape[1], 0))
    rates = kernel[:, 0] if kernel.shape[1] else np.zeros(Ms.shape[1])
    rates = fr.rates_back(rates, system.columns)
    big = float(np.max(np.abs(rates))) if len(rates) else 0.0
    if big > 0:
        rates = _unit_first_positive(rates / big)
    support = sorted(
        {joints_of_columns[i] for i, x in enumerate(rates) if big > 0 and abs(x) > SUPPORT_RTOL},
        key=joints_of_columns.index,
    )
    return SerialFinding(
        chain=label["chain"],
        joints=tuple(support),
        rank=r,
        generic_rank=generic_rank,
        wrenches=tuple(tuple(w) for w in wr),
        twist=tuple(_unit_first_positive(np.asarray(twist)).tolist()),
        null_joint_rates=tuple(float(x) for x in rates),
        margin=dec.margin,
        precision=dec.precision,
        body=label.get("body"),
        relative_to=label.get("relative_to"),
        leg=label.get("leg"),
    )


def chain_system(
    model: Any, S: np.ndarray, columns: list[int], point_x: np.ndarray | None, precision: Any
) -> ChainSystem:
    Ms = chain_matrix(model, S, columns, point_x)
    dec = decide_rank(Ms, precision, model.length_scale)
    return ChainSystem(Ms, dec, columns, point_x is not None)
