"""Row spaces, null spaces and rank decisions on every backend (private).

float: numpy SVD; mp:N: mpmath SVD at N digits; exact: sympy row reduction.
Every rank is decided by :func:`mechsing.numeric.decide_rank` (two thresholds,
margin, or undecided).
"""

from __future__ import annotations

from typing import Any

import mpmath
import numpy as np
import sympy

from mechsing.numeric import Backend, Precision, RankDecision, decide_rank, svd, to_float


def backend(prec: Precision) -> Backend:
    return prec.backend


def convert(x: Any, prec: Precision) -> np.ndarray:
    """Array of the precision's backend from any backend's array."""
    arr = np.asarray(x) if not isinstance(x, np.ndarray) else x
    if prec.mode in ("float", "auto"):
        return np.asarray(to_float(arr), dtype=np.float64)
    with prec.context():
        return prec.backend.asarray(arr)


def _svd_mp(M: np.ndarray, prec: Precision) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Full SVD at the precision's digits (:func:`mechsing.numeric.svd`: mpmath's, with a
    fallback that always converges), singular values descending."""
    with prec.context():
        return svd(prec.backend.asarray(M))


def simplify(x: Any) -> Any:
    """A normal form of an exact value: expanded and with rationalised
    denominators; ``sympy.simplify`` only when functions (atan2 ...) remain."""
    if not isinstance(x, sympy.Basic) or x.is_Rational:
        return x
    y = sympy.expand(x)
    if y.has(sympy.Function):
        y = sympy.simplify(y)
    return sympy.radsimp(y)


def row_space(M: Any, prec: Precision, length_scale: float = 1.0) -> tuple[RankDecision, Any]:
    """Rank decision and a basis (rows) of the row space of ``M`` (m, n).

    The basis is orthonormal in float and mp, the reduced row echelon rows in
    exact mode; it is None when the rank is undecided.
    """
    M = np.asarray(M)
    n = M.shape[1]
    if M.shape[0] == 0:
        dec = decide_rank(np.zeros((0, n)), prec, length_scale)
        return dec, convert(np.zeros((0, n)), prec)
    dec = decide_rank(M, prec, length_scale)
    if dec.rank is None:
        return dec, None
    k = dec.rank
    if prec.mode == "exact":
        R, piv = sympy.Matrix(M.tolist()).rref(simplify=True)
        rows = [[simplify(x) for x in R.row(i)] for i in range(len(piv))]
        return dec, np.array(rows, dtype=object).reshape(len(piv), n)
    if prec.mode == "mp":
        _U, _s, V = _svd_mp(M, prec)
        return dec, V[:k]
    _u, _s, Vt = np.linalg.svd(to_float(M))
    return dec, Vt[:k].copy()


def null_space(A: Any, prec: Precision, length_scale: float = 1.0) -> tuple[RankDecision, Any]:
    """Rank decision and a basis (rows) of the right null space of ``A`` (m, n)."""
    A = np.asarray(A)
    n = A.shape[1]
    dec = decide_rank(A, prec, length_scale)
    if dec.rank is None:
        return dec, None
    k = dec.rank
    if prec.mode == "exact":
        ker = sympy.Matrix(A.tolist()).nullspace(simplify=True)
        rows = [[simplify(x) for x in v] for v in ker]
        return dec, np.array(rows, dtype=object).reshape(len(rows), n)
    if prec.mode == "mp":
        _U, _s, V = _svd_mp(A, prec)
        return dec, V[k:]
    _u, _s, Vt = np.linalg.svd(to_float(A))
    return dec, Vt[k:].copy()


def solve_coefficients(B: np.ndarray, x: np.ndarray, prec: Precision) -> np.ndarray:
    """Least-squares coefficients c with ``c @ B ~ x`` (B rows independent)."""
    if B.shape[0] == 0:
        return convert(np.zeros(0), prec)
    if prec.mode == "exact":
        Bm = sympy.Matrix(B.tolist())
        c = (Bm * Bm.T).LUsolve(Bm * sympy.Matrix(list(x)))
        return np.array([simplify(v) for v in c], dtype=object)
    if prec.mode == "mp":
        with prec.context():
            Bm = mpmath.matrix(B.tolist())
            G = Bm * Bm.T
            c = mpmath.lu_solve(G, Bm * mpmath.matrix(list(x)))
            return np.array([c[i] for i in range(B.shape[0])], dtype=object)
    c, *_ = np.linalg.lstsq(to_float(B).T, to_float(x), rcond=None)
    return c


def is_zero(x: Any) -> bool:
    """Exact zero test of a sympy number."""
    return bool(sympy.simplify(x) == 0)
