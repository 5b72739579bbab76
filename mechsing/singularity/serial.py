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
non-zero power against a new wrench; ``null_joint_rate_basis`` -- the whole kernel in a
canonical basis (reduced row echelon form, each row largest entry 1: the same whatever
basis an SVD picks), ``null_joint_rates`` its first row, and ``joints`` the kernel's
support (the joints with an entry above :data:`mechsing.numeric.SUPPORT_RTOL` of its
row's largest in some row).

Which basis, and which lost twist, is a choice (theory: only the reciprocal system is
intrinsic); it is made to be read (:mod:`mechsing.screws.readable`).  When the chain's
screws stay in one space E at every configuration (a chain of a subgroup: a planar
leg's E is its plane's g(u)), the lost twist is taken in E and the new wrenches
(reciprocal to the chain here but not to E) are listed first, then the ones every
configuration resists.  The lost twist is the simplest modulo the chain's twists here,
each new wrench the simplest modulo the usual ones (least rotation or force, then least
translation or couple), and the usual ones, and the new ones among themselves, are in
reduced row echelon form.  A dead centre's lost twist thus reads as the translation
along the line of its pivots and its new wrench as the force along that line.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from mechsing.kinematics.couplings import expand_rates
from mechsing.numeric import (
    MEMBERSHIP_RTOL_FLOAT,
    SUPPORT_RTOL,
    CommensurateFrame,
    decide_rank,
    to_float,
)
from mechsing.numeric.blocks import dense_svd
from mechsing.numeric.linalg import first_nonzero_positive
from mechsing.numeric.scaling import cross3
from mechsing.screws.readable import echelon, reduced_echelon, simplest
from mechsing.singularity.criteria.serial import ChainSystem
from mechsing.singularity.findings import SerialFinding
from mechsing.singularity.names import DISTAL, LEG, lines_of_screws, singularity_name

#: random configurations sampled to find a chain's generic rank
GENERIC_SAMPLES = 8


def _unit_first_positive(v: np.ndarray) -> np.ndarray:
    """First non-zero component positive (the README's conventions), with components at rounding
    level (below SUPPORT_RTOL of the largest) reported as 0."""
    v = np.asarray(v, dtype=float)
    big = max(1.0, float(np.max(np.abs(v)))) if v.size else 1.0
    return first_nonzero_positive(np.where(np.abs(v) > SUPPORT_RTOL * big, v, 0.0))


def _si_wrenches(
    frame: CommensurateFrame, null_rows: np.ndarray, point_x: np.ndarray | None, point: bool
) -> list[np.ndarray]:
    """SI wrenches (f, m) at the ground origin (not normalised) of commensurate left-null
    vectors (columns of ``null_rows``); for a point's velocities, forces through the
    point ``point_x`` (None: moments left 0, the caller's)."""
    out = []
    for y in null_rows.T:
        if point:
            # a force through the point: f with f . v_point = 0 for all joint motions
            f = np.asarray(y, dtype=float)
            m = np.zeros(3) if point_x is None else cross3(point_x, f)
            out.append(np.concatenate([f, m]))
        else:
            out.append(frame.wrench_back(y))  # f . v + m . omega = y . (commensurate twist)
    return out


def _unit_wrench(w: np.ndarray) -> list[float]:
    """A unit force (a unit moment for a couple), first non-zero component positive."""
    f, m = w[:3], w[3:]
    nf = np.linalg.norm(f)
    # a couple when the force is zero next to the moment (unit moment, else unit force)
    couple = nf <= MEMBERSHIP_RTOL_FLOAT * np.linalg.norm(m)
    return _unit_first_positive(w / np.linalg.norm(m) if couple else w / nf).tolist()


def _unit_twist(t: np.ndarray) -> list[float]:
    """A unit rotation (a unit translation when omega is zero next to v), first non-zero
    component positive."""
    w, v = t[:3], t[3:]
    nw = np.linalg.norm(w)
    translation = nw <= MEMBERSHIP_RTOL_FLOAT * np.linalg.norm(v)
    return _unit_first_positive(t / np.linalg.norm(v) if translation else t / nw).tolist()


def wrenches_of(frame: CommensurateFrame, null_rows: np.ndarray, point: bool) -> list[list[float]]:
    """SI wrenches (f, m) at the ground origin from commensurate left-null vectors
    (columns of ``null_rows``), each a unit force (a unit moment for a couple), first
    non-zero component positive."""
    return [_unit_wrench(w) for w in _si_wrenches(frame, null_rows, None, point)]


def _split_new(left_null: np.ndarray, span: np.ndarray | None) -> tuple[np.ndarray, np.ndarray]:
    """Commensurate left-null columns split into the new ones (inside the chain's generic
    span E, orthonormal columns ``span``; None: all are new) and the usual ones
    (orthogonal to E: reciprocal to the chain at every configuration)."""
    if span is None:
        return left_null, left_null[:, :0]
    new = left_null.shape[1] - (left_null.shape[0] - span.shape[1])
    if new <= 0:
        return left_null[:, :0], left_null
    U, _, Vt = dense_svd(span.T @ left_null)
    return span @ U[:, :new], left_null @ Vt[new:].T


def generic_span(matrices: list[np.ndarray], generic_rank: int) -> np.ndarray | None:
    """Orthonormal columns of the one space E of dimension ``generic_rank`` that the
    chain's commensurate screw matrices ``matrices`` (at several configurations) all lie
    in, or None when together they span more (the chain moves its span around)."""
    M = np.hstack([np.asarray(to_float(m), dtype=float) for m in matrices])
    dec = decide_rank(M, "float")
    if dec.rank != generic_rank or generic_rank == M.shape[0]:
        return None
    U = dense_svd(M)[0]
    return U[:, :generic_rank]


def null_rates_basis(kernel_rows: np.ndarray, frame: CommensurateFrame, system: Any) -> np.ndarray:
    """The whole kernel of a chain's commensurate screw matrix (rows: an orthonormal
    basis of it, from an SVD, which picks any where its dimension is 2 or more) in one
    canonical basis: its reduced row echelon form (pivots decided with
    ECHELON_PIVOT_RTOL, :func:`mechsing.screws.readable.reduced_echelon`), each row then
    in SI joint rates (the couplings' followers expanded), largest entry 1, first
    non-zero positive, rounding-level entries 0.  The same kernel gives the same rows
    however it was computed (the fast paths on or off)."""
    K = np.asarray(kernel_rows, dtype=float)
    if K.shape[0] == 0:
        return np.zeros((0, len(system.columns)))
    rows, _ = reduced_echelon(K)
    out = []
    for v in rows:
        if system.kept is not None:
            v = expand_rates(v, len(system.columns), system.kept, system.follows)
        v = frame.rates_back(v, system.columns)
        big = float(np.max(np.abs(v))) if len(v) else 0.0
        if big > 0:
            out.append(_unit_first_positive(v / big))
    return np.array(out).reshape(len(out), len(system.columns))


def serial_finding(
    model: Any,
    system: ChainSystem,
    generic_rank: int,
    joints_of_columns: list[str],
    label: dict[str, Any],
    point_x: np.ndarray | None = None,
    span: np.ndarray | None = None,
) -> SerialFinding | None:
    """The ``serial`` finding of a chain whose rank is below ``generic_rank`` (else None);
    ``label``: ``chain`` ("output" with ``body`` and ``relative_to``, or "leg" with ``leg``);
    ``span``: the space the chain's screws stay in (:func:`generic_span`), if one."""
    dec = system.rank
    if dec.rank is None or dec.rank >= generic_rank:
        return None
    # the rank was decided at the analysis precision; the vectors that describe
    # the loss (wrenches, lost twist, null rates) come from a float SVD
    Ms = np.asarray(to_float(system.matrix), dtype=float)
    U, s, Vt = dense_svd(Ms)
    r = dec.rank
    new, usual = _split_new(U[:, r:], span)
    fr = model.float_frame
    L = float(model.length_scale)
    # the wrenches every configuration resists, in their simplest form; then the new
    # ones, each modulo those and in their own simplest form
    usual_si, _ = echelon(
        np.array(_si_wrenches(fr, usual, point_x, system.point)).reshape(-1, 6), L
    )
    new_si = [simplest(w, usual_si) for w in _si_wrenches(fr, new, point_x, system.point)]
    new_si, _ = echelon(np.array(new_si).reshape(-1, 6), L)
    wr = [_unit_wrench(w) for w in list(new_si) + list(usual_si)]

    def si_twist(t: np.ndarray) -> np.ndarray:
        if system.point:
            return np.concatenate([np.zeros(3), fr.velocity_back(t)])
        return fr.twist_back(t)

    # a lost twist: in E, with non-zero power against the first new wrench (a commensurate
    # left-null vector pairs with itself), in its simplest form modulo the chain's twists
    here = np.array([si_twist(u) for u in U[:, :r].T]).reshape(-1, 6)
    twist = _unit_twist(simplest(si_twist(new[:, 0]), here))
    basis = null_rates_basis(Vt[r:], fr, system)
    rates = basis[0] if len(basis) else np.zeros(len(joints_of_columns))
    # the moving joints: the support of the whole kernel (any of its rates)
    support = sorted(
        {joints_of_columns[i] for row in basis for i, x in enumerate(row) if abs(x) > SUPPORT_RTOL},
        key=joints_of_columns.index,
    )
    return SerialFinding(
        chain=label["chain"],
        joints=tuple(support),
        rank=r,
        generic_rank=generic_rank,
        wrenches=tuple(tuple(w) for w in wr),
        twist=tuple(twist),
        null_joint_rates=tuple(float(x) for x in rates),
        null_joint_rate_basis=tuple(tuple(float(x) for x in row) for row in basis),
        margin=dec.margin,
        precision=dec.precision,
        body=label.get("body"),
        relative_to=label.get("relative_to"),
        leg=label.get("leg"),
    )


def moving_name(
    joints: Sequence[str],
    columns: list[str],
    here: Any,
    generic: Any,
    scale: float,
    on_base: Sequence[str] = (),
) -> str | None:
    """The name of an output singularity whose moving ``joints`` (each one column
    of the screws ``here`` and at a generic configuration, named ``columns``) show a
    pattern, as a leg's would: a dead centre, the pivots of the moving joints come in
    line (:data:`~mechsing.singularity.names.LEG`; where none of them is one of the
    joints ``on_base``, those on the base body, they are the distal links of two legs,
    a five-bar's: :data:`~mechsing.singularity.names.DISTAL`); None where none fits."""
    cols = [i for i, n in enumerate(columns) if n in joints]
    if generic is None or len(cols) != len(joints) or len(cols) < 3:
        return None
    moving = [columns[i] for i in cols]
    here_lines = lines_of_screws(moving, np.asarray(to_float(here), dtype=float)[:, cols])
    generic_lines = lines_of_screws(moving, np.asarray(generic, dtype=float)[:, cols])
    name = singularity_name(here_lines, generic_lines, scale, leg=True, moving=joints)
    if name == LEG and on_base and not set(joints) & set(on_base):
        return DISTAL
    return name


def named(
    f: SerialFinding | None,
    columns: list[str],
    here: Any,
    generic: Any,
    scale: float,
    point: Any = None,
    generic_point: Any = None,
) -> SerialFinding | None:
    """``f`` with the name people give it (:mod:`mechsing.singularity.names`), from the
    chain's SI screws ``here`` and at a generic configuration (columns named ``columns``;
    ``point``: the output point, if the task is one); None stays None."""
    if f is None or generic is None:
        return f
    here_lines = lines_of_screws(columns, np.asarray(to_float(here), dtype=float))
    generic_lines = lines_of_screws(columns, np.asarray(generic, dtype=float))
    name = singularity_name(
        here_lines,
        generic_lines,
        scale,
        point,
        generic_point,
        f.chain == "leg",
        f.joints,
        f.corank,
    )
    return replace(f, name=name)
