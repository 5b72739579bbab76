"""mpmath kernels of the mp backend: conversion to the working precision, the mp SVD
and symmetric eigensolver that always converge (:func:`svd_r`, :func:`eigsy`, with
one-sided Jacobi fallbacks), and the conversions between numpy object arrays and
``mpmath.matrix``.

This is the one mp SVD of mechsing: :func:`mp_svd` (object arrays in, object arrays
out) serves :func:`mechsing.numeric.linalg.svd`, the mp backend's null and row spaces and
the rank decisions.  Everything here works at the current ``mpmath.mp.dps``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing.numeric.lazy import mpmath, sympy
from mechsing.numeric.pirational import PiRational


def _mp_convert(x: Any) -> Any:
    if isinstance(x, mpmath.mpf | mpmath.mpc):
        return +x  # re-round at the current working precision
    if isinstance(x, PiRational):
        x = x._sympy_()  # the number as sympy evaluates it, as before PiRational
    if isinstance(x, sympy.Basic):
        return mpmath.mpf(sympy.N(x, mpmath.mp.dps + 5))
    if isinstance(x, bool | np.bool_):
        return mpmath.mpf(int(x))
    if isinstance(x, np.floating | np.integer):
        x = x.item()
    return mpmath.mpf(x)


def _object_array(M: Any, shape: tuple[int, ...]) -> np.ndarray:
    out = np.empty(shape, dtype=object)
    rows = M.tolist()
    for i in range(shape[0]):
        for j in range(shape[1]):
            out[i, j] = rows[i][j]
    return out


def _mp_matrix(arr: np.ndarray) -> Any:
    """An ``mpmath.matrix`` of a 2-d array, entries rounded to the working precision."""
    return mpmath.matrix([[_mp_convert(x) for x in row] for row in arr.tolist()])


#: most sweeps of the one-sided Jacobi SVD (it converges quadratically: about ten
#: sweeps reach 50 digits; the bound only guards against a pathological matrix)
_JACOBI_MAX_SWEEPS = 100
#: extra digits of the second attempt of mpmath's SVD
_SVD_RETRY_DIGITS = 10


def svd_r(A: Any, full_matrices: bool = False, compute_uv: bool = True) -> Any:
    """``mpmath.svd_r`` that always converges (same arguments and results).

    mpmath's Golub-Reinsch iteration declares a bidiagonal entry negligible only when
    adding it to the matrix norm does not change the norm (less than half an ulp).  With a
    repeated singular value (repeated rows, as stacked wrench systems often have) the
    implicit-shift QR step can leave that entry at about half an ulp of the norm, flipping
    its sign at every step, and mpmath gives up with ``RuntimeError: svd: no convergence``
    at some working precisions and not at others.  Then this tries again with a few more
    digits (which moves the last bits), and failing that computes the SVD by one-sided
    (Hestenes) Jacobi rotations, whose stopping test is relative (two columns are
    orthogonal when their inner product is below ``m eps`` times their norms): it always
    converges, and to high relative accuracy.
    """
    try:
        return mpmath.svd_r(A, full_matrices=full_matrices, compute_uv=compute_uv)
    except (RuntimeError, ZeroDivisionError):
        pass
    # the stall depends on the last bits: a few more digits usually break it (cheap) ...
    try:
        with mpmath.workdps(mpmath.mp.dps + _SVD_RETRY_DIGITS):
            out = mpmath.svd_r(A, full_matrices=full_matrices, compute_uv=compute_uv)
        return (+out) if not compute_uv else tuple(+x for x in out)
    except (RuntimeError, ZeroDivisionError):
        pass
    # ... and Jacobi always converges
    return _jacobi_svd(A, full_matrices, compute_uv)


def _dot(a: list[Any], b: list[Any]) -> Any:
    return mpmath.fdot(a, b)


def _jacobi_svd(A: Any, full_matrices: bool, compute_uv: bool) -> Any:
    """SVD by one-sided Jacobi rotations at the working precision, in the layout of
    ``mpmath.svd_r`` (``A = U diag(S) V``, singular values descending)."""
    m, n = A.rows, A.cols
    rows = [[A[i, j] for j in range(n)] for i in range(m)]
    # orthogonalise the columns of B = A (m >= n) or of B = A^T (m < n): k columns of length p
    transpose = m < n
    cols = (
        [list(r) for r in rows] if transpose else [[rows[i][j] for i in range(m)] for j in range(n)]
    )
    k, p = len(cols), (n if transpose else m)
    zero, one = mpmath.mpf(0), mpmath.mpf(1)
    W = [[one if i == j else zero for i in range(k)] for j in range(k)]  # columns of W
    tol = mpmath.mp.eps * p
    for _sweep in range(_JACOBI_MAX_SWEEPS):
        rotated = False
        for i in range(k - 1):
            for j in range(i + 1, k):
                a, b = cols[i], cols[j]
                gamma = _dot(a, b)
                if not gamma:
                    continue
                alpha, beta = _dot(a, a), _dot(b, b)
                if abs(gamma) <= tol * mpmath.sqrt(alpha * beta):
                    continue
                rotated = True
                zeta = (beta - alpha) / (2 * gamma)
                t = (1 if zeta >= 0 else -1) / (abs(zeta) + mpmath.sqrt(1 + zeta * zeta))
                c = 1 / mpmath.sqrt(1 + t * t)
                s = c * t
                cols[i] = [c * x - s * y for x, y in zip(a, b, strict=True)]
                cols[j] = [s * x + c * y for x, y in zip(a, b, strict=True)]
                wa, wb = W[i], W[j]
                W[i] = [c * x - s * y for x, y in zip(wa, wb, strict=True)]
                W[j] = [s * x + c * y for x, y in zip(wa, wb, strict=True)]
        if not rotated:
            break
    sig = [mpmath.sqrt(_dot(col, col)) for col in cols]
    order = sorted(range(k), key=lambda j: -sig[j])
    S = mpmath.matrix(k, 1)
    for r, j in enumerate(order):
        S[r] = sig[j]
    if not compute_uv:
        return S
    # B = Q diag(sig) W^T with Q's columns cols[j] / sig[j]; columns of (numerical) zero
    # singular values and the missing ones are completed to an orthonormal basis
    smax = sig[order[0]] if k else zero
    Q = [[x / sig[j] for x in cols[j]] for j in order if sig[j] > tol * smax and sig[j] > 0]
    Q = _complete_orthonormal(Q, p, p if (full_matrices or not transpose) else k)
    Wt = [W[j] for j in order]  # rows: right singular vectors of B
    if transpose:
        # A = B^T = W diag(sig) Q^T: U = W (m x m), V = Q^T (k' x n)
        U = mpmath.matrix([[Wt[c][r] for c in range(k)] for r in range(k)])
        V = mpmath.matrix(Q if full_matrices else Q[:k])
        return U, S, V
    # A = B = Q diag(sig) W^T: U = Q (m x m or m x n), V = W^T (n x n)
    U = mpmath.matrix([[Q[c][r] for c in range(len(Q) if full_matrices else k)] for r in range(p)])
    V = mpmath.matrix(Wt)
    return U, S, V


def _complete_orthonormal(Q: list[list[Any]], p: int, count: int) -> list[list[Any]]:
    """``count`` orthonormal vectors of length p: those of Q (orthonormal), then the
    coordinate vector least in their span, orthogonalised against them (Gram-Schmidt twice),
    and so on."""
    Q = [list(q) for q in Q]
    while len(Q) < count:
        # |e - P e|^2 = 1 - sum_q q[e]^2 for the coordinate vector e
        e = max(range(p), key=lambda i: (1 - mpmath.fsum(q[i] * q[i] for q in Q), -i))
        v = [mpmath.mpf(1) if i == e else mpmath.mpf(0) for i in range(p)]
        for _pass in range(2):
            for q in Q:
                d = _dot(q, v)
                v = [x - d * y for x, y in zip(v, q, strict=True)]
        nv = mpmath.sqrt(_dot(v, v))
        Q.append([x / nv for x in v])
    return Q[:count]


def eigsy(A: Any, eigvals_only: bool = False) -> Any:
    """``mpmath.eigsy`` that always converges (same arguments and results): when the QL
    iteration gives up, the cyclic Jacobi eigenvalue method (each rotation removes an
    off-diagonal pair, so the off-diagonal mass decreases until it is below ``eps`` of the
    matrix's norm)."""
    try:
        return mpmath.eigsy(A, eigvals_only=eigvals_only)
    except (RuntimeError, ZeroDivisionError):
        return _jacobi_eigsy(A, eigvals_only)


def _jacobi_eigsy(A: Any, eigvals_only: bool) -> Any:
    n = A.rows
    a = [[A[i, j] for j in range(n)] for i in range(n)]
    zero, one = mpmath.mpf(0), mpmath.mpf(1)
    V = [[one if i == j else zero for j in range(n)] for i in range(n)]
    fro = mpmath.sqrt(mpmath.fsum(x * x for row in a for x in row))
    for _sweep in range(_JACOBI_MAX_SWEEPS):
        off = mpmath.sqrt(mpmath.fsum(a[i][j] ** 2 for i in range(n) for j in range(n) if i != j))
        if off <= mpmath.mp.eps * fro:
            break
        for p in range(n - 1):
            for q in range(p + 1, n):
                apq = a[p][q]
                if abs(apq) <= mpmath.mp.eps * fro / n:
                    continue
                theta = (a[q][q] - a[p][p]) / (2 * apq)
                t = (1 if theta >= 0 else -1) / (abs(theta) + mpmath.sqrt(theta * theta + 1))
                c = 1 / mpmath.sqrt(t * t + 1)
                s = t * c
                for k in range(n):  # columns p, q
                    akp, akq = a[k][p], a[k][q]
                    a[k][p], a[k][q] = c * akp - s * akq, s * akp + c * akq
                for k in range(n):  # rows p, q
                    apk, aqk = a[p][k], a[q][k]
                    a[p][k], a[q][k] = c * apk - s * aqk, s * apk + c * aqk
                a[p][q] = a[q][p] = zero
                for k in range(n):
                    vkp, vkq = V[k][p], V[k][q]
                    V[k][p], V[k][q] = c * vkp - s * vkq, s * vkp + c * vkq
    order = sorted(range(n), key=lambda i: a[i][i])
    E = mpmath.matrix(n, 1)
    for r, i in enumerate(order):
        E[r] = a[i][i]
    if eigvals_only:
        return E
    return E, mpmath.matrix([[V[k][i] for i in order] for k in range(n)])


def mp_svd(
    arr: np.ndarray, full_matrices: bool = True
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``A = U diag(s) Vt`` of a 2-d array at the working precision (object arrays of
    ``mpf``), singular values descending; :func:`svd_r` underneath."""
    m, n = arr.shape
    k = min(m, n)
    if k == 0:
        U = _mp_eye(m) if full_matrices else _mp_zeros((m, 0))
        Vt = _mp_eye(n) if full_matrices else _mp_zeros((0, n))
        return U, _mp_zeros(0), Vt
    Um, S, Vm = svd_r(_mp_matrix(arr), full_matrices=full_matrices)
    s = [S[i] for i in range(k)]
    order = sorted(range(k), key=lambda i: -s[i])
    U = _object_array(Um, (Um.rows, Um.cols))
    Vt = _object_array(Vm, (Vm.rows, Vm.cols))
    if order != list(range(k)):
        U = U[:, order + list(range(k, U.shape[1]))]
        Vt = Vt[order + list(range(k, Vt.shape[0]))]
    sv = np.empty(k, dtype=object)
    sv[:] = [s[i] for i in order]
    return U, sv, Vt


def _mp_zeros(shape: tuple[int, ...] | int) -> np.ndarray:
    out = np.empty(shape, dtype=object)
    out.fill(mpmath.mpf(0))
    return out


def _mp_eye(n: int) -> np.ndarray:
    out = _mp_zeros((n, n))
    for i in range(n):
        out[i, i] = mpmath.mpf(1)
    return out
