"""Closing the samples between a path's closed points, many at a time.

Owns :func:`close_segments` (the samples between a path's nodes, every segment of
several traces in batched Newton from the cubic through the closed points around them,
in one or two passes of knots) and the samples near a fold (:func:`close_to_fold`,
:func:`near_fold`: the swept value is quadratic in the distance along the curve there).
A sample that does not close near its prediction is left NaN for continuation.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from mechsing.errors import ClosureError
from mechsing.kinematics.paths.problem import Problem
from mechsing.kinematics.settings import SWEEP_JUMP_RATIO, SWEEP_KNOT_STEP

if TYPE_CHECKING:
    from mechsing.kinematics.paths.trace import PathTrace

__all__ = ["close_segments"]

#: samples closed by one batched Newton call at most (bounds its working memory)
_FINE_CHUNK = 8192
#: fewer samples than this between the nodes of a row are closed in one pass (no knots)
_KNOTS_FROM = 1000
#: the samples between knots are predicted by the polynomial through this many closed
#: points around them: of degree 7, knots SWEEP_KNOT_STEP apart predict to about 1e-14
#: (the hexapod's turn: median residual 2e-14 m, 99% below 1e-12), within the closure
#: tolerance, so most samples take no Newton step, where a cubic's 1e-9 takes one (and a
#: quintic's 2e-12 one every other sample)
_STENCIL = 8


def close_segments(
    pb: Problem, traces: list[PathTrace], col: int, groups: list[list[int]] | None = None
) -> None:
    """The samples strictly between the nodes of each segment (i, j) of each trace, all
    segments of the traces together (the two directions of a path are one batch), in two
    passes of batched Newton (in chunks of _FINE_CHUNK rows):

    1. where the samples are closer together than SWEEP_KNOT_STEP, *knots*: every m-th
       sample of the segment, m the samples in that step; otherwise every sample;
    2. the samples between the knots.

    (One pass, every sample from the nodes' cubic, when the traces hold fewer than
    _KNOTS_FROM samples to close: a grid's short rows, where a second batched call costs
    more than the Newton steps it saves.)

    In the first pass each sample (or knot) is predicted by the cubic through the two
    nodes around it and the one before and after them (a quadratic at the ends of the
    path); in the second, by the polynomial through the _STENCIL closed knots nearest it
    (:func:`_stencil`), on the group, from the knot before it: knots a hundredth of a
    radian apart predict to about 1e-14, within the closure tolerance, so most samples
    take no Newton step where the nodes' cubic needs two or three.  A sample that does not close near its prediction is closed
    again by continuation from the previous one.  Fills each trace's Z and newton in
    place.

    ``groups``: the traces (indices) of each path, when several paths are closed together
    (the rows of a grid): whether a path's samples are closed in one pass or two is
    decided by its own traces, as when it is closed alone (default: one path)."""
    sc = pb.scale(col)
    first: list[tuple[int, int, int, list[int], list[int]]] = []
    later: list[tuple[int, list[int]]] = []  # (trace, its knots in order) per segment
    many_of = {}
    for group in groups if groups is not None else [list(range(len(traces)))]:
        many = sum(j - i - 1 for m in group for i, j in traces[m].segments) >= _KNOTS_FROM
        many_of.update({m: many for m in group})
    for m, tr in enumerate(traces):
        many = many_of[m]
        Z, values = tr.Z, tr.values
        assert values is not None
        for i, j in tr.segments:
            stride = _knot_stride(values, i, j, sc) if many else 1
            knots = [i, *range(i + stride, j - stride // 2, stride), j] if stride > 1 else [i, j]
            if len(knots) == 2:
                first.append((m, i, j, _cubic_knots(Z, i, j), list(range(i + 1, j))))
                continue
            first.append((m, i, j, _cubic_knots(Z, i, j), knots[1:-1]))
            later.append((m, knots))
    _close_between(pb, traces, col, first)
    second = []
    for m, knots in later:
        Z = traces[m].Z
        closed = [k for k in knots if not np.isnan(Z[k, 0])]
        # where a segment has too few knots, the nodes around it complete the stencils
        pool = sorted(set(closed) | set(_cubic_knots(Z, knots[0], knots[-1])))
        for p in range(len(closed) - 1):
            a, b = closed[p], closed[p + 1]
            if b - a < 2:
                continue
            second.append((m, a, b, _stencil(pool, a, b), list(range(a + 1, b))))
    _close_between(pb, traces, col, second)
    # the samples Newton did not close near their prediction: continuation, in order
    for tr in traces:
        Z, values = tr.Z, tr.values
        assert values is not None
        for i, j in tr.segments:
            # the samples left open (a sample is written only at its own turn below)
            for k in (i + 1 + np.flatnonzero(np.isnan(Z[i + 1 : j, 0]))).tolist():
                prev = Z[k - 1]
                if np.isnan(prev[0]):
                    continue
                try:
                    Z[k] = pb.reach(prev, col, values[k])
                except ClosureError:
                    continue
        tr.segments = []


def _knot_stride(values: np.ndarray, i: int, j: int, sc: float) -> int:
    """Samples per knot between nodes i and j: as many samples as SWEEP_KNOT_STEP holds
    (commensurate), at least 1."""
    spacing = abs(float(values[j]) - float(values[i])) / (j - i) / sc
    return max(1, int(SWEEP_KNOT_STEP / spacing)) if spacing > 0 else 1


def _cubic_knots(Z: np.ndarray, i: int, j: int) -> list[int]:
    """The closed points a segment (i, j) is interpolated through: its ends and the points
    as far before and after them, where closed."""
    return [k for k in (2 * i - j, i, j, 2 * j - i) if 0 <= k < len(Z) and not np.isnan(Z[k, 0])]


def _stencil(knots: list[int], a: int, b: int) -> list[int]:
    """The closed points the samples between the neighbouring knots a and b are
    interpolated through: a, b and the _STENCIL - 2 nearest others of the sorted
    ``knots`` (as many on each side where there are, the rest on the other side)."""
    at = knots.index(a)
    lo, hi = at, at + 1  # knots[lo : hi + 1] is the stencil
    while hi - lo + 1 < _STENCIL and (lo > 0 or hi + 1 < len(knots)):
        # the side whose next knot is nearer the interval (the one before a on a tie)
        before = a - knots[lo - 1] if lo > 0 else None
        after = knots[hi + 1] - b if hi + 1 < len(knots) else None
        if after is None or (before is not None and before <= after):
            lo -= 1
        else:
            hi += 1
    return knots[lo : hi + 1]


def _close_between(
    pb: Problem,
    traces: list[PathTrace],
    col: int,
    jobs: list[tuple[int, int, int, list[int], list[int]]],
) -> None:
    """One batched Newton over ``jobs``: (trace, a, b, knots, rows) closes the samples
    ``rows`` of a trace from the Lagrange interpolation through its closed samples
    ``knots`` (a among them), as increments on the group from sample a; a sample moved
    by Newton more than SWEEP_JUMP_RATIO times the distance from a to b is left NaN."""
    bc = pb.batch
    nb = bc.nb
    jobs = [job for job in jobs if job[4]]
    if not jobs:
        return
    # every knot's increment from its job's first point, in one call
    sizes = np.array([len(kn) for *_, kn, _ in jobs])
    firsts = np.stack([traces[m].Z[a] for m, a, *_ in jobs])
    K1 = np.concatenate([traces[m].Z[knots] for m, _, _, knots, _ in jobs])
    Dall = bc.difference(K1, firsts[np.repeat(np.arange(len(jobs)), sizes)])
    # per sample: its job, row, trace and swept value; per knot: its swept value
    counts = np.array([len(ks) for *_, ks in jobs])
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
    job_of = np.repeat(np.arange(len(jobs)), counts)
    rows_a = np.concatenate([np.asarray(ks, dtype=int) for *_, ks in jobs])
    which_a = np.repeat([m for m, *_ in jobs], counts)
    values_of = [traces[m].values for m, *_ in jobs]
    T = np.concatenate([v[ks] for v, (*_, ks) in zip(values_of, jobs, strict=True)])  # type: ignore[index]
    tk = np.concatenate([v[kn] for v, (*_, kn, _) in zip(values_of, jobs, strict=True)])  # type: ignore[index]
    A = firsts[job_of]
    # each job's span, from a to b, commensurate
    at_b = starts + np.array([kn.index(b) for _, _, b, kn, _ in jobs])
    span_a = np.linalg.norm(pb.cm.float_frame.rates(Dall[at_b]), axis=1)[job_of]
    # the Lagrange interpolation of the knots' increments at the samples, the samples
    # of stencils of one size together (the same operations, sample by sample, as one
    # job at a time)
    P = np.empty((len(rows_a), Dall.shape[1]))
    for size in np.unique(sizes):
        at = np.flatnonzero(sizes[job_of] == size)
        idx = starts[job_of[at]][:, None] + np.arange(size)  # the samples' knots
        tks, tv = tk[idx], T[at]
        W = np.ones((len(at), size))
        for p in range(size):
            for q in range(size):
                if p != q:
                    W[:, p] *= (tv - tks[:, q]) / (tks[:, p] - tks[:, q])
        acc = W[:, :1] * Dall[idx[:, 0]]
        for p in range(1, size):
            acc += W[:, p, None] * Dall[idx[:, p]]
        P[at] = acc
    for lo in range(0, len(rows_a), _FINE_CHUNK):
        sl = slice(lo, lo + _FINE_CHUNK)
        Qp = bc.update(A[sl], P[sl, :nb])
        Qp[:, nb:] = A[sl, nb:] + P[sl, nb:]
        Qp[:, col] = T[sl]
        # closed to the tolerance and no further: a sample read near a singularity is
        # closed again (polished) by the refinement that locates it
        Q, ok, it = pb.close_near(Qp, SWEEP_JUMP_RATIO * span_a[sl], polish=False)
        Q[~ok] = np.nan
        for m, tr in enumerate(traces):
            mine = which_a[sl] == m
            if not np.any(mine):
                continue
            tr.Z[rows_a[sl][mine]] = Q[mine]
            assert tr.newton is not None
            tr.newton[rows_a[sl][mine]] += it[mine]
