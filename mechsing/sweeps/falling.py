"""What else vanishes along a sweep's rows: every singular value that can fall between two
samples, not the weakest alone, and the samples that are themselves singular.

Owns :func:`others_fall` (at the pairs of neighbouring samples where a test's singular
value other than the weakest can reach zero, the sign of its whole compressed
determinant: a UR5's elbow just past its shoulder, where the weakest pair rises again
while the next one falls through zero), :func:`singular_samples` (a row's samples whose
measure is itself at rounding level next to a regular one, listed as located: there the
sign between neighbours reads a vanishing value's rounding) and :func:`column_samples`
(the same between two rows of a grid: a locus along a sampled row, such as a 3-RPR's type
II line rz = 0, crosses the columns at samples).  Each works for a
:class:`~mechsing.sweeps.locate.Locator`, whose tests, measures and refiner it reads.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing.kinematics.settings import SWEEP_LOCATE_TOL
from mechsing.numeric import Precision
from mechsing.sweeps.measures import PointMeasures
from mechsing.sweeps.records import Located, RowResult, RowSamples
from mechsing.sweeps.settings import SWEEP_MERGE_FACTOR, SWEEP_SCREEN_ROUNDING
from mechsing.sweeps.signs import SIGNED

__all__ = ["column_samples", "others_fall", "singular_samples"]

_TAU_HI = Precision("float").tolerances.tau_hi
_TAU_LO = Precision("float").tolerances.tau_lo
#: pairs screened at a time (bounds the working memory of the kernels' products)
_CHUNK = 4096


def singular_samples(loc: Any, t: str, row: RowSamples, out: list[Located]) -> None:
    """A row's samples that are themselves singular for test ``t`` (its rank decided
    below the generic one: the measure at most float's tau_lo) next to a reached
    sample where it is not (above tau_hi): located at the sample (kind ``sample``)
    unless a point found there already zeroes the test.  A sign test between such a
    sample and its neighbour reads a vanishing value whose sign is rounding."""
    Z, reached, rho, col = row.Z, row.reached, row.ratio[t], row.col
    K = len(Z)
    with np.errstate(invalid="ignore"):
        zero = reached & (rho <= _TAU_LO)
        regular = reached & (rho > _TAU_HI)
    beside = np.zeros(K, dtype=bool)
    beside[1:] |= regular[:-1]
    beside[:-1] |= regular[1:]
    for k in np.flatnonzero(zero & beside).tolist():
        v, w = float(Z[k, col]), SWEEP_MERGE_FACTOR * SWEEP_LOCATE_TOL * loc.problem.scale(col)
        if loc.holds(out, t, v - w, v + w, col):
            continue
        out.append(loc.at(Z[k], "sample", (t,), float(rho[k]), "row", (row.index, k)))


def column_samples(loc: Any, ra: RowResult, rb: RowResult, got: list[Located]) -> None:
    """The samples of two neighbouring rows of a grid that are singular for a test
    (measure at most float's tau_lo) where the other row's sample is regular (above
    tau_hi): located at the sample (kind ``sample``, between the rows; added to
    ``got``, the pair's points), unless a point found along its row or between these
    rows lies there and zeroes the test.  A locus along a sampled row (a 3-RPR's type
    II line rz = 0) crosses the columns at samples, where the sign between the rows
    reads a vanishing value's rounding.  Each sample is listed once: the pairs of a
    grid come in row order, and the samples listed are kept per row."""
    assert ra.Z is not None and rb.Z is not None
    cx, cy = loc.cols[0], loc.cols[-1]
    wx = SWEEP_MERGE_FACTOR * SWEEP_LOCATE_TOL * loc.problem.scale(cx)
    wy = SWEEP_MERGE_FACTOR * SWEEP_LOCATE_TOL * loc.problem.scale(cy)
    for t in loc.tests:
        for sing, other in ((rb, ra), (ra, rb)):
            assert sing.Z is not None
            with np.errstate(invalid="ignore"):
                zero = (
                    sing.reached
                    & other.reached
                    & (sing.ratio[t] <= _TAU_LO)
                    & (other.ratio[t] > _TAU_HI)
                )
            listed = loc.listed.setdefault(sing.index, set())
            for k in np.flatnonzero(zero).tolist():
                if k in listed:
                    continue
                z = sing.Z[k]
                near = [
                    p
                    for p in [*got, *sing.located]
                    if p.z is not None and abs(p.z[cx] - z[cx]) <= wx and abs(p.z[cy] - z[cy]) <= wy
                ]
                if near and any(
                    t in p.tests or "closure" in p.tests or loc.refiner.ratio(t, p.z) <= _TAU_HI
                    for p in near
                ):
                    continue
                listed.add(k)
                got.append(
                    loc.at(z, "sample", (t,), float(sing.ratio[t][k]), "column", (ra.index, k))
                )


def others_fall(
    loc: Any, pm: PointMeasures, ia: np.ndarray, ib: np.ndarray
) -> dict[str, np.ndarray]:
    """Per signed test whose matrices the batch keeps, at the pairs (ia, ib) of the
    batch ``pm`` where a singular value other than the weakest can reach zero between
    a and b, the determinant of b's matrix compressed on a's leading singular vectors
    (:meth:`Measures.compressed_measured`, whose sign changes when any of them passes
    through zero); 1 at the other pairs.  Which can: ``sigma_(g-1)`` at a is at most
    how far the matrix moved from a to b (Weyl; for an input or output test of a
    closed chain, the operator's rows' move plus the closure kernel's, as
    :meth:`Measures.compressed_pairs` bounds it), with the roundings.  Not for a test
    whose rows the batch does not keep (a closure of full row rank: read again at
    every pair they would cost the kinematics again)."""
    out: dict[str, np.ndarray] = {}
    if pm.matrices is None or not len(ia):
        return out
    eps = float(np.finfo(float).eps)
    for t in loc.tests:
        g = loc.measures.generic[t]
        if t not in SIGNED or g is None or g < 2 or t not in pm.matrices:
            continue
        rows = pm.matrices.get(f"{t}_rows")
        if rows is not None and not isinstance(rows, np.ndarray):
            # rows not kept but computed again where read (a closure of full row
            # rank: a spatial parallel robot's); reading them at every pair would
            # cost the kinematics again: its second singular value is not screened
            continue
        M = pm.matrices[t]
        if not isinstance(M, np.ndarray):
            continue  # the matrices are computed again where read (as the rows above)
        Ma = M[ia]
        if t in pm.bases:
            U, V = pm.bases[t]
            u, v = U[ia, :, g - 2], V[ia, :, g - 2]
            second = np.abs(np.einsum("ni,ni->n", u, np.einsum("nij,nj->ni", Ma, v)))
        elif t in pm.second:
            # measured without its singular vectors (a path's tests): the value the
            # measure's own factorisation found
            second = pm.second[t][ia]
        else:
            second = np.linalg.svd(Ma, compute_uv=False)[:, g - 2]
        size = np.sqrt(np.einsum("nij,nij->n", Ma, Ma))
        moved = np.zeros(len(ia))
        for lo in range(0, len(ia), _CHUNK):
            sl = slice(lo, lo + _CHUNK)
            if t in ("input", "output") and pm.kernel is not None:
                Na, Nb = pm.kernel[ia[sl]], pm.kernel[ib[sl]]
                n, k = Na.shape[1:]
                W = np.swapaxes(Na, 1, 2) @ Nb
                apart = 2 * k - 2 * np.einsum("nij,nij->n", W, W)
                D = Nb - Na
                moved[sl] = np.minimum(
                    np.sqrt(np.einsum("nij,nij->n", D, D)),
                    np.sqrt(np.maximum(apart, 0.0) + SWEEP_SCREEN_ROUNDING * (n + k) * k * eps),
                )
                if rows is not None:
                    DX = rows[ib[sl]] - rows[ia[sl]]
                    moved[sl] += np.sqrt(np.einsum("nij,nij->n", DX, DX))
            else:
                D = M[ib[sl]] - Ma[sl]
                moved[sl] = np.sqrt(np.einsum("nij,nij->n", D, D))
        near = np.flatnonzero(~(second > moved + SWEEP_SCREEN_ROUNDING * eps * size))
        det = np.ones(len(ia))
        if len(near):
            det[near] = loc.measures.compressed_measured(pm, ia[near], pm, ib[near])[t]
        out[t] = det
    return out
