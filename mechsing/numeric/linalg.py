"""Linear algebra on the numerical backends: SVD, singular values, symmetric
eigenproblems, orthonormal columns, norms, least squares (float: numpy; mp: mpmath at
the working precision, through :mod:`mechsing.numeric._mp`, so call these inside
``Precision.context()``); and, for batches of float matrices, the orthogonal complement
of each one's column space from its QR's Householder vectors (:func:`complement`).
Exact arrays are decided by the rank and definiteness decisions and factorised by the
exact backend's null/row spaces, not here.
"""

from __future__ import annotations

from typing import Any, cast

import numpy as np

from mechsing.numeric._mp import _mp_matrix, _object_array, eigsy, mp_svd, svd_r
from mechsing.numeric.backend import Backend, backend_of, to_float
from mechsing.numeric.blocks import block_svd, dense_svd
from mechsing.numeric.lazy import mpmath
from mechsing.numeric.tolerances import SUPPORT_RTOL


def _numerical_backend(*arrays: Any) -> Backend:
    bk = backend_of(*arrays)
    if bk.name == "exact":
        raise TypeError("exact arrays have no numerical factorisation; convert them to mp first")
    return bk


def svd(A: Any, full_matrices: bool = True) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``A = U diag(s) Vt`` in the backend of ``A``, singular values descending.

    float: :func:`numpy.linalg.svd`; mp: :func:`mechsing.numeric._mp.mp_svd` (mpmath's,
    with a Jacobi fallback) at the working precision, object arrays of ``mpf``.
    """
    arr = np.asarray(A)
    bk = _numerical_backend(arr)
    if bk.name == "float":
        factors = block_svd(to_float(arr), full_matrices=full_matrices)
        return cast(tuple[np.ndarray, np.ndarray, np.ndarray], factors)
    return mp_svd(arr, full_matrices)


def singular_values(A: Any) -> list[Any]:
    """Singular values (descending) of an mp array or matrix, at the working precision."""
    M = A if isinstance(A, mpmath.matrix) else _mp_matrix(np.asarray(A))
    sig = svd_r(M, compute_uv=False)
    return sorted((abs(sig[i]) for i in range(len(sig))), reverse=True)


def eigh(A: Any) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues (ascending) and orthonormal eigenvectors (columns) of the
    symmetric part of ``A``, in its backend (numpy ``eigh`` / :func:`eigsy`)."""
    arr = np.asarray(A)
    bk = _numerical_backend(arr)
    if bk.name == "float":
        F = to_float(arr)
        return np.linalg.eigh((F + F.T) / 2)
    n = arr.shape[0]
    if n == 0:
        return bk.zeros(0), bk.zeros((0, 0))
    S = _mp_matrix(arr)
    E, Q = eigsy((S + S.T) / 2)
    w = [E[i] for i in range(n)]
    order = sorted(range(n), key=lambda i: w[i])
    V = _object_array(Q, (n, n))[:, order]
    wv = np.empty(n, dtype=object)
    wv[:] = [w[i] for i in order]
    return wv, V


def orthonormal_columns(A: Any) -> np.ndarray:
    """Q of the thin QR decomposition of ``A`` (m x k, k <= m): an orthonormal
    basis of its columns' span when they are independent (numpy / mpmath QR)."""
    arr = np.asarray(A)
    bk = _numerical_backend(arr)
    if bk.name == "float":
        Q, _ = np.linalg.qr(to_float(arr))
        return Q
    m, k = arr.shape
    if k == 0:
        return bk.zeros((m, 0))
    Q, _ = mpmath.qr(_mp_matrix(arr))
    return _object_array(Q, (m, m))[:, :k]


def norm(A: Any) -> Any:
    """Euclidean norm of a vector, Frobenius norm of a matrix, in its backend."""
    arr = np.asarray(A)
    bk = _numerical_backend(arr)
    if bk.name == "float":
        return np.linalg.norm(to_float(arr))
    return mpmath.sqrt(mpmath.fsum(x * x for x in arr.flat))


def spectral_norm(A: Any) -> Any:
    """Largest singular value (0 for an empty matrix), in the array's backend."""
    arr = np.asarray(A)
    if arr.size == 0:
        return 0.0
    bk = _numerical_backend(arr)
    if bk.name == "float":
        # numpy.linalg.norm(A, 2): the largest of the values-only SVD's values
        return float(np.max(dense_svd(to_float(arr), compute_uv=False)))
    return singular_values(arr)[0]


def max_abs(A: Any) -> Any:
    """Largest ``|entry|`` (0 for an empty array), in the array's backend."""
    arr = np.asarray(A)
    if arr.size == 0:
        return 0.0
    return np.max(np.abs(arr))


def lstsq(A: Any, b: Any) -> np.ndarray:
    """Minimum-norm least-squares solution of ``A x = b``; singular values below
    ``eps max(m, n)`` of the largest are dropped (numpy's ``rcond=None``)."""
    arr = np.asarray(A)
    bk = _numerical_backend(arr, b)
    if bk.name == "float":
        return np.linalg.lstsq(to_float(arr), to_float(b), rcond=None)[0]
    U, s, Vt = svd(arr, full_matrices=False)
    if len(s) == 0:
        return bk.zeros(arr.shape[1])
    cut = bk.eps * max(arr.shape) * s[0]
    keep = [i for i in range(len(s)) if s[i] > cut]
    c = np.array([(U[:, i] @ b) / s[i] for i in keep], dtype=object)
    return Vt[keep].T @ c if keep else bk.zeros(arr.shape[1])


def pinv_truncated(U: np.ndarray, s: np.ndarray, Vt: np.ndarray, r: int) -> np.ndarray:
    """Pseudo-inverse of the rank-``r`` truncation of ``U diag(s) Vt`` (any backend)."""
    return (Vt[:r].T / s[:r][None, :]) @ U[:, :r].T


def first_nonzero_sign(v: Any) -> float:
    """+1.0 or -1.0: the sign that makes the float vector ``v``'s first non-zero component
    positive (DESIGN's convention for a direction, a twist, a wrench, joint rates), +1.0
    for a zero vector.  A component is zero when at most :data:`SUPPORT_RTOL` times the
    largest ``|component|``, so rounding noise in the components that are zero (a
    direction (1e-17, -2e-17, -1), the sign of an SVD vector) never decides the sign."""
    x = np.asarray(to_float(v), dtype=float).ravel()
    big = float(np.max(np.abs(x))) if x.size else 0.0
    if not big > 0:
        return 1.0
    first = x[int(np.argmax(np.abs(x) > SUPPORT_RTOL * big))]
    return -1.0 if first < 0 else 1.0


def first_nonzero_positive(v: Any) -> np.ndarray:
    """The float vector ``v`` times :func:`first_nonzero_sign` (its first component above
    the rounding level positive)."""
    x = np.asarray(to_float(v), dtype=float)
    return first_nonzero_sign(x) * x + 0.0  # no -0.0


#: an orthogonal complement (:func:`complement`: a sweep's closure kernel, a leg's
#: constraint wrenches) is formed from its QR's Householder vectors this many at a time
#: (a block's reflectors applied at once, ``Y - W V``: three products of small matrices
#: per block instead of two per reflector), for this many configurations at a time (the
#: working set stays in cache): on the hexapod's 30 reflectors, 6 to 8 and 256 measured
#: fastest of 2 to 15 and 128 to 1024
KERNEL_BLOCK = 6
KERNEL_CHUNK = 256


def complement(h: np.ndarray, tau: np.ndarray) -> np.ndarray:
    """The last ``n - k`` columns of the orthogonal factor Q of the QR factorisations
    ``A = Q R`` of matrices A (N, n, k), k <= n, given in LAPACK's raw form (numpy's
    ``qr(A, mode="raw")``: ``h`` (N, k, n), row j holding the j-th Householder vector
    after its diagonal, and ``tau`` (N, k)): an orthonormal basis of the orthogonal
    complement of each A's column space, the same columns as the complete Q's (which
    LAPACK forms with the same reflectors).  Only ``Q [0; I]`` is formed,
    ``H_1 ... H_k [0; I]``: the reflectors are applied KERNEL_BLOCK at a time (the
    block's product at once, ``Y - W V``, W from ``Y V^T`` and the vectors' products),
    each block to the rows it touches, KERNEL_CHUNK configurations at a time.
    Products of reflectors, like LAPACK's, so as accurate however near A is to losing
    rank."""
    N, k, n = h.shape
    d = n - k
    out = np.zeros((N, d, n))  # the transposed basis, Y = (Q [0; I])^T
    out[:, :, k:] = np.eye(d)
    if d == 0 or k == 0:
        return np.swapaxes(out, 1, 2)
    after = np.triu(np.ones((k, n)), 1)
    diagonal = np.arange(k)
    for lo in range(0, N, KERNEL_CHUNK):
        t, Y = tau[lo : lo + KERNEL_CHUNK], out[lo : lo + KERNEL_CHUNK]
        # the Householder vectors as rows: 1 on the diagonal, h after it, 0 before it
        V_ = h[lo : lo + KERNEL_CHUNK] * after
        V_[:, diagonal, diagonal] = 1.0
        hi = k
        while hi > 0:  # the last block first: Y <- Y H_hi-1 ... H_a
            a = max(hi - KERNEL_BLOCK, 0)
            V = V_[:, a:hi, a:]  # (m, b, n - a): the block's vectors, from row a on
            Ya = Y[:, :, a:]
            W = Ya @ np.swapaxes(V, 1, 2)  # (m, d, b): Y v_j
            G = V @ np.swapaxes(V, 1, 2)  # v_i . v_j
            # w_j = tau_j (Y H_hi-1 ... H_j+1) v_j = tau_j (Y v_j - sum_{i > j} w_i v_i . v_j)
            for j in range(hi - a - 1, -1, -1):
                if j < hi - a - 1:
                    W[:, :, j] -= (W[:, :, j + 1 :] @ G[:, j + 1 :, j, None])[:, :, 0]
                W[:, :, j] *= t[:, a + j, None]
            Ya -= W @ V
            hi = a
    return np.swapaxes(out, 1, 2)


#: a matrix whose smallest singular value is at least this fraction of its largest has
#: full column rank under every precision's thresholds, and R^T R's eigenvalues tell so
#: (their rounding, a few eps sigma_1^2, moves that ratio by a few eps / ratio^2); the
#: same ratio above which a sweep takes a triangular factor's singular values from its
#: Gram matrix (``mechsing.sweeps.settings.SWEEP_GRAM_RATIO``)
CLEAR_RANK_RATIO = 0.05


def clear_row_rank(A: np.ndarray) -> np.ndarray:
    """For float matrices A (N, n, k), k >= n: which are clearly of full row rank (the
    smallest singular value at least :data:`CLEAR_RANK_RATIO` of the largest, from the
    eigenvalues of A A^T, each A scaled to entries at most 1; at that ratio the Gram
    matrix's rounding, a few eps of its largest eigenvalue, cannot change the answer):
    the orthogonal complement of their column space is then empty, with no SVD."""
    top = np.max(np.abs(A), axis=(1, 2), keepdims=True)
    As = A / np.where(top > 0, top, 1.0)
    lam = np.linalg.eigvalsh(As @ np.swapaxes(As, 1, 2))  # ascending
    clear: np.ndarray = (lam[:, 0] >= CLEAR_RANK_RATIO**2 * lam[:, -1]) & (lam[:, -1] > 0)
    return clear


def clear_complements(A: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For float matrices A (N, n, k), 0 < k < n: which are clearly of full column rank
    (the smallest singular value at least :data:`CLEAR_RANK_RATIO` of the largest, from
    the eigenvalues of R^T R, R their QR's triangular factor) and, for those, an
    orthonormal basis of their column space's orthogonal complement, (N, n, n - k)
    (:func:`complement`; the others' columns are not a complement, the caller factorises
    them otherwise).  About a third of the cost of their complete SVDs."""
    k = A.shape[2]
    h, tau = np.linalg.qr(A, mode="raw")  # h (N, k, n): R^T is its first k columns' lower part
    Rt = h[:, :, :k] * np.tri(k)
    # each R scaled to entries at most 1 (the ratio is scale-free; no Gram entry overflows)
    top = np.max(np.abs(Rt), axis=(1, 2), keepdims=True)
    Rt = Rt / np.where(top > 0, top, 1.0)
    lam = np.linalg.eigvalsh(Rt @ np.swapaxes(Rt, 1, 2))  # R^T R's eigenvalues, ascending
    clear = (lam[:, 0] >= CLEAR_RANK_RATIO**2 * lam[:, -1]) & (lam[:, -1] > 0)
    return clear, complement(h, tau)
