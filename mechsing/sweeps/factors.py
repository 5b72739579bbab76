"""The batched factorisations of a sweep's measures, in float.

Owns the kernels :class:`~mechsing.sweeps.measures.Measures` factorises its batches
with (beside the closure kernel formed from a QR's Householder vectors alone,
:func:`mechsing.numeric.linalg.complement`): the singular values of a triangular factor
from its Gram matrix (:func:`singular_values`), the largest singular value of each matrix
(:func:`largest_singular_value`), and the table ``sweep test factors`` of
:mod:`mechsing.numeric.dispatch`, whose form ``values first`` (:func:`values_first`)
gives a test's singular values without its vectors (``MECHSING_FAST=0``: numpy's thin
SVD with its vectors, the generic definition in ``Measures.__call__``).
"""

from __future__ import annotations

import numpy as np

from mechsing.numeric import Precision, dispatch
from mechsing.sweeps.settings import SWEEP_GRAM_RATIO

__all__ = [
    "NOISE",
    "VALUES",
    "largest_singular_value",
    "singular_values",
    "values_first",
]


#: a singular value this far below the largest (a tenth of float's tau_lo) is rounding
#: noise for both SVDs alike: its count against the thresholds cannot differ between them
NOISE = Precision("float").tolerances.tau_lo / 10

VALUES = dispatch.table(
    "sweep test factors",
    "numpy.linalg.svd of each test's matrices with their vectors (Measures.__call__)",
)


def largest_singular_value(A: np.ndarray) -> np.ndarray:
    """The largest singular value of each matrix of A (N, r, c): the square root of the
    largest eigenvalue of the smaller Gram matrix (A A^T or A^T A), a symmetric
    eigenproblem of that size instead of the SVD.  As accurate: the largest eigenvalue
    moves by at most the Gram matrix's rounding, a few eps |A|_F^2 <= a few eps
    min(r, c) sigma_1^2, so sigma_1 by a few eps min(r, c) / 2 relative (numpy's SVD's
    own is a few eps)."""
    At = np.swapaxes(A, 1, 2)
    G = A @ At if A.shape[1] <= A.shape[2] else At @ A
    if G.shape[1] == 0:
        return np.zeros(len(A))
    return np.sqrt(np.maximum(np.linalg.eigvalsh(G)[:, -1], 0.0))


def singular_values(R: np.ndarray) -> np.ndarray:
    """The singular values of square matrices R (N, k, k), descending: the square roots
    of the eigenvalues of R^T R (a symmetric eigenproblem, cheaper than the SVD) where
    the smallest relative one is at least SWEEP_GRAM_RATIO (there squaring loses at most
    a factor 1 / (2 rho^2) of the rounding), the SVD of R elsewhere (a matrix nearer its
    singularity, whose smallest singular values a Gram matrix would blur)."""
    lam = np.linalg.eigvalsh(np.swapaxes(R, 1, 2) @ R)
    s = np.sqrt(np.maximum(lam[:, ::-1], 0.0))
    near = np.flatnonzero(~(s[:, -1] >= SWEEP_GRAM_RATIO * s[:, 0]))
    if len(near):
        s[near] = np.linalg.svd(R[near], compute_uv=False)
    return s


@VALUES.register(
    "values first",
    "a batch of float matrices: the singular values alone (LAPACK's values-only SVD, "
    "about half the cost), the vectors later where they are read (the same thin SVD of "
    "the kept matrix, bit for bit); the rows near a rank decision take the thin SVD's "
    "values (bit for bit), the others agree with it to a few eps / SWEEP_GRAM_RATIO",
    # any batch size: a row's measures are bit for bit the same alone or with other rows
    accepts=lambda A, g, unit: dispatch.float64_arrays(A) and A.ndim == 3,
)
def values_first(A: np.ndarray, g: int, unit: bool) -> np.ndarray:
    """The singular values of each matrix of A (N, r, c), descending, without the vectors:
    where the g-th is at least SWEEP_GRAM_RATIO of the largest (and, ``unit``: of 1, the
    operator's norm the test is relative to) and each one after it is either that large or
    below :data:`NOISE` (relative), the two SVDs round differently by a few eps / ratio,
    and neither the measure nor any threshold's count can tell them apart; the other rows
    (nearer a rank decision) take the thin SVD's own values, as the generic definition."""
    s = np.linalg.svd(A, compute_uv=False)
    k = s.shape[1]
    if k == 0 or g < 1 or g > k:
        return np.linalg.svd(A, full_matrices=False)[1]
    top = s[:, :1]
    rel = s / np.where(top > 0, top, 1.0)
    ok = rel[:, g - 1] >= SWEEP_GRAM_RATIO
    if unit:
        ok &= s[:, g - 1] >= SWEEP_GRAM_RATIO
    if g < k:
        after = rel[:, g:]
        ok &= np.all((after <= NOISE) | (after >= SWEEP_GRAM_RATIO), axis=1)
    near = np.flatnonzero(~ok)
    if len(near):
        s[near] = np.linalg.svd(A[near], full_matrices=False)[1]
    return s
