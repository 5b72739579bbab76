"""Screws written to be read: which element of a space, or of a class modulo a space.

Only some screw objects are intrinsic: a span of twists, a system of wrenches.  A basis
of one, or a lost twist (any twist outside a span), is a choice, and these functions
make it the one a reader recognises.  Coordinates are SI at the ground origin: a twist
``(omega, v)``, a wrench ``(f, m)`` -- the "first half" is omega or f, the "second
half" v or m.  The elements with a zero first half (translations, couples) are the
ones that do not depend on the origin.

* :func:`echelon` -- a basis in reduced row echelon form (second halves divided by the
  characteristic length L so that the columns are commensurate): a planar chain's
  usual wrenches come out as the force along the normal and the couples about the two
  in-plane axes, a span's rotations before its translations.
* :func:`simplest` -- a representative of ``v`` modulo a span: the least first half,
  then the least second half (a dead centre's lost twist: the translation along the
  line of its pivots, not some screw about a far axis).
* :func:`readable_basis` -- a span's basis, rotations (forces) in echelon form with
  their second halves least modulo the span's translations (couples), then those.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing.numeric import SUPPORT_RTOL
from mechsing.numeric.blocks import dense_svd

#: a reduced row echelon form written to be read (screws.readable.echelon) takes its
#: pivots in column order, but not one below this fraction of the largest entry still
#: to eliminate: a smaller pivot would scale its row by more than 1e6 and bring the
#: data's rounding up to the digits shown (an axis tilted by 3e-8 rad out of a plane is
#: then read in the plane's own columns; the span is unchanged)
ECHELON_PIVOT_RTOL = 1e-6

__all__ = ["echelon", "readable_basis", "reduced_echelon", "simplest"]


def _scale(length_scale: float) -> np.ndarray:
    L = float(length_scale)
    return np.array([1.0, 1.0, 1.0, 1.0 / L, 1.0 / L, 1.0 / L])


def echelon(rows: np.ndarray, length_scale: float) -> tuple[np.ndarray, list[int]]:
    """Reduced row echelon form of ``rows`` (k, 6) with its pivot columns; the columns
    compared after dividing second halves by ``length_scale``.  A pivot is the largest
    remaining entry of the first column where one exceeds ECHELON_PIVOT_RTOL of the
    largest entry still to eliminate (the rows not yet pivoted, the columns from this
    one on), so no row is scaled by more than 1/ECHELON_PIVOT_RTOL; a column skipped that
    way keeps its entries (the span is the input's).  Rows whose entries are all of
    rounding level (SUPPORT_RTOL of the largest entry) are dropped."""
    scale = _scale(length_scale)
    A = np.array(rows, dtype=float).reshape(-1, 6) * scale
    out, pivots = reduced_echelon(A)
    return out / scale, pivots


def reduced_echelon(A: np.ndarray) -> tuple[np.ndarray, list[int]]:
    """Reduced row echelon form of the rows of ``A`` (k, m), any width, with its pivot
    columns (the rule of :func:`echelon`, whose columns are first made commensurate): a
    pivot is the largest remaining entry of the first column where one exceeds
    ECHELON_PIVOT_RTOL of the largest entry still to eliminate; rows of rounding level
    (SUPPORT_RTOL of the largest entry) are dropped.  The form of a span is the same
    whichever basis of it is given (a kernel's, from an SVD that picks any)."""
    A = np.array(A, dtype=float)
    m = A.shape[1] if A.ndim == 2 else 0
    if A.size == 0:
        return A.reshape(-1, m), []
    # in Python floats: a few short rows, where numpy's per-call cost would be most of
    # the work; a non-finite entry propagates as numpy's elimination would (a NaN is the
    # largest entry and the first such is the pivot)
    rows = A.tolist()
    k = len(rows)
    top = max if np.isfinite(A).all() else _largest
    tol = SUPPORT_RTOL * top(abs(x) for row in rows for x in row)
    pivots: list[int] = []
    r = 0
    for j in range(m):
        if r == k:
            break
        rest = top(abs(x) for row in rows[r:] for x in row[j:])
        if rest <= tol:
            break
        i, best = r, abs(rows[r][j])
        for t in range(r + 1, k):
            if best != best:  # NaN: the first one is the pivot
                break
            x = abs(rows[t][j])
            if x > best or x != x:
                i, best = t, x
        if best <= ECHELON_PIVOT_RTOL * rest:
            continue
        rows[r], rows[i] = rows[i], rows[r]
        p = rows[r][j]
        pr = rows[r] = [x / p for x in rows[r]]
        for t in range(k):
            if t != r:
                f = rows[t][j]
                rows[t] = [a - f * b for a, b in zip(rows[t], pr, strict=True)]
        pivots.append(j)
        r += 1
    return np.array(rows[:r], dtype=float).reshape(r, m), pivots


def _largest(values: Any) -> float:
    """The largest of non-negative numbers (0.0 for none), NaN if one is NaN."""
    top = 0.0
    for x in values:
        if x != x:
            return x
        if x > top:
            top = x
    return top


def _pure(R: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, float]:
    """The SVD of the first halves of ``R`` (U, singular values, Vt), the span's elements
    with a zero first half (rows), and the magnitude the rank is judged against."""
    U, sv, Vt = dense_svd(R[:, :3], full_matrices=True)
    big = max(float(np.max(np.abs(R))), float(sv.max(initial=0.0)))
    rank = int(np.sum(sv > SUPPORT_RTOL * big))
    return U[:, :rank], sv[:rank], Vt[:rank], U[:, rank:].T @ R, big


def simplest(v: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """``v`` (6,) modulo the span of ``rows`` (k, 6): the representative whose first
    half is least, and among those, whose second half is least."""
    R = np.asarray(rows, dtype=float).reshape(-1, 6)
    out = np.array(v, dtype=float)
    if len(R) == 0:
        return out
    # least squares on the first halves, their rounding-level singular values dropped
    U, sv, Vt, pure, big = _pure(R)
    first = out[:3] - Vt.T @ (Vt @ out[:3])
    out = out - (U @ ((Vt @ out[:3]) / sv)) @ R
    # the first half is the projection orthogonal to the first halves' span, taken as
    # such: through the combination of rows its rounding is amplified by the inverse of
    # the least singular value kept (up to 1/SUPPORT_RTOL)
    out[:3] = first
    if len(pure):
        Q, s2, _ = dense_svd(pure[:, 3:].T, full_matrices=False)
        Q = Q[:, s2 > SUPPORT_RTOL * big]
        out[3:] = out[3:] - Q @ (Q.T @ out[3:])
    return out


def _unit(row: np.ndarray, length_scale: float, pivot: int) -> np.ndarray:
    """A unit first half, or a unit second half when the first is of rounding level
    next to it (commensurate: at most SUPPORT_RTOL of the second half over L);
    components of rounding level set to 0: SUPPORT_RTOL of the smaller of the largest
    entry and the echelon pivot's (commensurate).  The pivot holds the row's unit of
    the data: a row scaled up by a small pivot (by as much as 1/ECHELON_PIVOT_RTOL) has
    entries far above the largest's SUPPORT_RTOL that are still the data's, and a basis
    of nearly parallel rows needs them to span the input."""
    scale = _scale(length_scale)
    first, second = np.linalg.norm(row[:3]), np.linalg.norm(row[3:] * scale[3:])
    if first <= SUPPORT_RTOL * second:
        row = np.r_[np.zeros(3), row[3:]]
        out = row / np.linalg.norm(row[3:])
    else:
        out = row / first
    size = np.abs(out * scale)
    big = min(float(np.max(size)), float(size[pivot]) or float(np.max(size)))
    return np.where(size > SUPPORT_RTOL * big, out, 0.0) + 0.0


def readable_basis(rows: np.ndarray, length_scale: float) -> np.ndarray:
    """A basis (rows) of the span of ``rows`` (k, 6): in echelon form (:func:`echelon`),
    each row with a first half then made least in its second half modulo the rows
    without one (a rotation's axis as near the origin as the span's translations allow);
    each row a unit rotation (force), or a unit translation (couple)."""
    E, pivots = echelon(rows, length_scale)
    pure = [i for i, j in enumerate(pivots) if j >= 3]
    out = E.copy()
    if pure:
        T = E[pure]
        pivot_at = [pivots[i] for i in pure]
        columns = [j - 3 for j in pivot_at]
        for i, j in enumerate(pivots):
            if j < 3:
                # the second half made least modulo T's, then the same combination of
                # T's whole rows taken off: each row of T is 0 at the others' pivots, so
                # the combination is read there; a first half T keeps at rounding level
                # goes with it (amplified by a small pivot, it is not negligible beside
                # the row's own unit first half)
                d = E[i, 3:] - simplest(np.r_[np.zeros(3), E[i, 3:]], T)[3:]
                out[i] = E[i] - (d[columns] / T[range(len(pure)), pivot_at]) @ T
    return np.array(
        [_unit(row, length_scale, j) for row, j in zip(out, pivots, strict=True)]
    ).reshape(-1, 6)
