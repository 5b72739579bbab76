"""The sign tests of a sweep's measures: which tests changed sign between two points.

A singular value does not change sign, a determinant does.  For consecutive points ``a``,
``b`` of a path (or neighbouring points of a grid), :func:`compressed_of` compresses the
matrix at ``b`` onto the leading singular vectors of the one at ``a``:
``det(U_a^T A_b V_a)`` is positive at ``a`` and changes sign where the matrix passes
through a rank drop between them (the kernel basis of ``b`` is first turned to the one of
``a``, so that ``T N`` is continuous).  Where no singular vectors are needed it reads an
equal determinant without them: a closure of full row rank bordered by its kernel at
``a`` (:func:`bordered_closure`), the input and output tests of a closed chain bordered
by the closure (:func:`bordered`).  :func:`pairs` is the cheaper test between the
neighbours of one measured batch, screened by Weyl's bound.

Owns the sign tests (:func:`compressed_of`, :func:`bordered`, :func:`bordered_closure`,
:func:`pairs`) and the tests' kinds (:data:`SIGNED`, :data:`UNIT_REFERENCE`).  The
functions take the :class:`~mechsing.sweeps.measures.Measures` whose batches they
read (its tests and their plans); :class:`Measures` calls them from
:meth:`~mechsing.sweeps.measures.Measures.compressed`,
:meth:`~mechsing.sweeps.measures.Measures.compressed_measured` and
:meth:`~mechsing.sweeps.measures.Measures.compressed_pairs`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing.sweeps.settings import SWEEP_SCREEN_ROUNDING

# the measures and their batches (mechsing.sweeps.measures, which calls this module)
Measures = Any
PointMeasures = Any

__all__ = [
    "SCREEN_CHUNK",
    "SIGNED",
    "UNIT_REFERENCE",
    "bordered",
    "bordered_closure",
    "compressed_of",
    "pairs",
    "signed_key",
]

#: tests with a continuous matrix, whose compressed determinant has a meaningful sign
#: (the constraint wrenches are a basis found afresh at each point)
SIGNED = ("closure", "input", "output")

#: tests whose singular values are relative to the operator applied to the motion space
#: (T N over |T|, E N with |E| = 1), as the full analysis decides them; the others are
#: relative to their own largest singular value
UNIT_REFERENCE = ("input", "output")

#: pairs of samples screened at a time (bounds the working memory of the differences)
SCREEN_CHUNK = 512


def signed_key(k: str) -> bool:
    """Whether a kept matrix is read by the sign tests: a signed test's, or the rows a
    bordered one reads (not a test kept only for its vectors, which may be computed
    again where indexed)."""
    return k in SIGNED or k.endswith("_rows")


def turn(kb: np.ndarray, ka: np.ndarray) -> np.ndarray:
    """The orthogonal factor of ``kb^T ka``: turns the kernel basis kb onto ka."""
    u, _, vt = np.linalg.svd(np.swapaxes(kb, 1, 2) @ ka)
    out: np.ndarray = u @ vt
    return out


def compressed_of(
    measures: Measures, a: PointMeasures, ia: np.ndarray, mats: dict[str, np.ndarray], kernel: Any
) -> dict[str, np.ndarray]:
    """Per signed test, the determinant of the matrices ``mats`` at the points b (with
    their closure ``kernel``) compressed onto the leading singular vectors of the points
    ``ia`` of the measured batch ``a``: positive at a itself, negative where a rank drop
    was crossed."""
    out = {}
    for t in measures.tests:
        if t not in SIGNED:
            continue
        if a.matrices is not None and f"{t}_rows" in a.matrices and f"{t}_rows" in mats:
            at_a = {k: v[ia] for k, v in a.matrices.items() if signed_key(k)}
            out[t] = bordered(measures, t, a, ia, mats) * np.sign(
                bordered(measures, t, a, ia, at_a)
            )
            continue
        A = mats[t]
        if t == "closure" and a.kernel is not None and measures.full_row_rank():
            out[t] = bordered_closure(a, ia, A)
            continue
        if t in ("input", "output") and a.kernel is not None and kernel is not None:
            # b's kernel basis turned to a's (the orthogonal factor of kb^T ka), so
            # that the matrix (A = X kb, X the test's map) is continuous from a to b
            A = A @ turn(kernel, a.kernel[ia])
        U, V = a.basis(t, ia)
        C = np.swapaxes(U, 1, 2) @ A @ V
        out[t] = np.linalg.det(C)
    return out


def bordered(
    measures: Measures, t: str, a: PointMeasures, ia: np.ndarray, mats: dict[str, Any]
) -> np.ndarray:
    """The determinant of the square matrix [U_c^T C; U_t^T X] at the points of
    ``mats``: the closure matrix C and the test's rows X (T or E, before the kernel),
    compressed on the leading left singular vectors of the points ``ia`` of ``a``.  It
    vanishes exactly where X N loses rank (N the closure kernel), and, unlike X N, needs
    no basis of the kernel: it is continuous from a to b, so its sign is a sure test.
    Where the closure has full row rank, U_c is square and orthogonal: it only
    multiplies the determinant by det U_c = +-1 at every b of one a, which the sign's
    reading against a itself (:func:`compressed_of`) removes, so C is taken as it is; so
    are the rows X where U_t is square (:meth:`Measures.square_rows`)."""
    if measures.full_row_rank():
        top = mats["closure"]
    else:
        top = np.swapaxes(a.basis("closure", ia)[0], 1, 2) @ mats["closure"]
    low = mats[f"{t}_rows"]
    if not measures.square_rows(t):
        low = np.swapaxes(a.basis(t, ia)[0], 1, 2) @ low
    det: np.ndarray = np.linalg.det(np.concatenate([top, low], axis=1))
    return det


def bordered_closure(a: PointMeasures, ia: np.ndarray, Cb: np.ndarray) -> np.ndarray:
    """The compressed determinant of a closure of full row rank: ``det [C_b; N_a^T]``,
    N_a the closure kernel at a, signed to be positive at a.  With C_a = U S V^T and
    Q = [V N_a] orthogonal, ``[C_b; N_a^T] Q = [C_b V, C_b N_a; 0, I]``, so it is
    ``det(C_b V) det Q`` = ``+-det(U^T C_b V)``, the compressed determinant itself,
    with no singular vectors (a QR gave N_a)."""
    assert a.kernel is not None and a.matrices is not None
    Ka = np.swapaxes(a.kernel[ia], 1, 2)
    Ca = a.matrices["closure"][ia]
    at_a = np.linalg.det(np.concatenate([Ca, Ka], axis=1))
    det: np.ndarray = np.linalg.det(np.concatenate([Cb, Ka], axis=1)) * np.sign(at_a)
    return det


def pairs(pm: PointMeasures, ia: np.ndarray, ib: np.ndarray) -> dict[str, np.ndarray]:
    """The sign test between neighbours of one measured batch (rows ``ia`` and ``ib``),
    from the matrices it kept: the matrix at b projected on the weakest singular pair
    at a, ``u_g^T A_b v_g`` (``sigma_g`` at a itself).  It follows the weakest
    singular value through zero, and costs a product where :func:`compressed_of` costs a
    determinant of the generic rank's size; negative where a rank drop was crossed (the
    refinement then uses :func:`compressed_of`, whose zero is exact).

    A test measured without its singular vectors is screened first: where the matrix
    moved less from a to b (Frobenius norm) than ``sigma_g`` at a, less the
    roundings, ``u_g^T A_b v_g >= sigma_g - |A_b - A_a|`` is positive (Weyl), and that
    bound stands for it; the product is computed at the other pairs only.  So are the
    input and output tests of a closed chain, by how far the closure kernel moved
    (:func:`_turned_pairs`)."""
    assert pm.matrices is not None
    out = {}
    # b's kernel basis turned to a's, for the input and output tests, at the pairs
    # their screen leaves (the same turn for both)
    turns: dict[bytes, np.ndarray] = {}
    for t, M in pm.matrices.items():
        if t.endswith("_rows") or t not in SIGNED:
            continue
        if t in ("input", "output") and pm.kernel is not None:
            out[t] = _turned_pairs(pm, t, M, ia, ib, turns)
            continue
        if t in pm.deferred:
            out[t] = _screened_pairs(pm, t, M, ia, ib)
            continue
        U, V = pm.bases[t]
        u, v = U[ia][:, :, -1], V[ia][:, :, -1]
        out[t] = np.einsum("ni,nij,nj->n", u, M[ib], v)
    return out


def _turned_pairs(
    pm: PointMeasures,
    t: str,
    M: np.ndarray,
    ia: np.ndarray,
    ib: np.ndarray,
    turns: dict[bytes, np.ndarray],
) -> np.ndarray:
    """:func:`pairs` of the input or output test of a closed chain, whose
    matrix ``X N`` reads the closure kernel's basis N (X the output rows over their
    norm, or the input selection: ``|X| = 1``): ``u_g^T X N_b R v_g``, R the orthogonal
    factor of ``N_b^T N_a`` (b's basis turned to a's, :func:`turn`).  It differs from
    ``sigma_g`` at a by at most ``|N_b R - N_a|``, the largest ``2 sin(theta / 2)``
    over the principal angles theta between the two kernels.  That is at most
    ``|N_b - N_a|_F`` (R is the nearest turn, orthogonal Procrustes) and at most
    ``|P_b - P_a|_F = sqrt(2 k - 2 |N_a^T N_b|_F^2)`` (P the projectors; this one does
    not depend on the bases, which an SVD picks afresh at each point).  Where the
    smaller of the two, with the roundings, is below ``sigma_g`` the product is
    positive and the bound stands for it; the turn and the product are computed at
    the other pairs only."""
    assert pm.kernel is not None
    ia, ib = np.asarray(ia), np.asarray(ib)
    eps = np.finfo(float).eps
    rounding = SWEEP_SCREEN_ROUNDING * eps
    n, k = pm.kernel.shape[1:]
    # the rounding of |N_a^T N_b|_F^2 (k^2 dot products of length n, of unit vectors)
    # and of the bases' orthonormality, generously
    slack = SWEEP_SCREEN_ROUNDING * (n + k) * k * eps
    d = np.array(pm.ratio[t][ia], dtype=float)  # sigma_g at a (|X| = 1)
    for lo in range(0, len(ia), SCREEN_CHUNK):
        sl = slice(lo, lo + SCREEN_CHUNK)
        Na, Nb = pm.kernel[ia[sl]], pm.kernel[ib[sl]]
        D = Nb - Na
        W = np.swapaxes(Na, 1, 2) @ Nb
        apart = 2 * k - 2 * np.einsum("nij,nij->n", W, W)
        moved = np.minimum(
            np.sqrt(np.einsum("nij,nij->n", D, D)), np.sqrt(np.maximum(apart, 0.0) + slack)
        )
        Aa = M[ia[sl]]
        size = np.sqrt(np.einsum("nij,nij->n", Aa, Aa))
        d[sl] -= moved + rounding * size
    near = np.flatnonzero(~(d > 0))
    if len(near):
        key = near.tobytes()
        if key not in turns:
            turns.clear()
            turns[key] = turn(pm.kernel[ib[near]], pm.kernel[ia[near]])
        U, V = pm.basis(t, ia[near])
        u, v = U[:, :, -1], V[:, :, -1]
        d[near] = np.einsum("ni,nij,nj->n", u, M[ib[near]] @ turns[key], v)
    return d


def _screened_pairs(
    pm: PointMeasures, t: str, M: np.ndarray, ia: np.ndarray, ib: np.ndarray
) -> np.ndarray:
    """:func:`pairs` of a test measured without its singular vectors: the
    Weyl bound where it is positive, the product elsewhere (in chunks: the matrices'
    differences stay small in memory)."""
    g = pm.deferred[t]
    rounding = SWEEP_SCREEN_ROUNDING * np.finfo(float).eps
    # sigma_g at a (the input and output tests' ratio is sigma_g itself, |X| = 1)
    d: np.ndarray = pm.ratio[t][ia] * (1.0 if t in UNIT_REFERENCE else pm.top[t][ia])
    ia, ib = np.asarray(ia), np.asarray(ib)
    if t in pm.steps:
        # the norms the measures kept: of each matrix and of its step to the next row
        sizes, ahead = pm.steps[t]
        size = sizes[ia]
        moved = np.where(ib == ia + 1, ahead[ia], np.nan)
        known = np.isfinite(moved)
        d[known] -= moved[known] + rounding * size[known]
        rest = np.flatnonzero(~known)  # other pairs, and across the measured parts
    else:
        rest = np.arange(len(ia))
    for lo in range(0, len(rest), SCREEN_CHUNK):
        sl = rest[lo : lo + SCREEN_CHUNK]
        Aa, Ab = M[ia[sl]], M[ib[sl]]
        D = Ab - Aa
        moved = np.sqrt(np.einsum("nij,nij->n", D, D))
        size = np.sqrt(np.einsum("nij,nij->n", Aa, Aa))
        d[sl] -= moved + rounding * size
    near = np.flatnonzero(~(d > 0))
    if len(near):
        U, V = pm.basis(t, ia[near])
        u, v = U[:, :, g - 1], V[:, :, g - 1]
        d[near] = np.einsum("ni,nij,nj->n", u, M[ib[near]], v)
    return d
