"""Linear algebra on the numerical backends: SVD, singular values, symmetric
eigenproblems, orthonormal columns, norms, least squares (float: numpy; mp: mpmath at
the working precision, through :mod:`mechsing.numeric._mp`, so call these inside
``Precision.context()``).  Exact arrays are decided by the rank and definiteness
decisions and factorised by the exact backend's null/row spaces, not here.
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
