"""Rank-decided row and null spaces and coefficients of subalgebras (private).

A thin layer over :mod:`mechsing.numeric`: every rank is decided by
:func:`mechsing.numeric.decide_rank` (two thresholds, margin, or undecided), and the
bases and solutions are the backend's (:meth:`mechsing.numeric.Backend.row_space`,
``null_space``, ``solve``: numpy, mpmath or sympy).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing.numeric import Precision, RankDecision, decide_rank


def convert(x: Any, prec: Precision) -> np.ndarray:
    """Array of the precision's backend from any backend's array."""
    arr = np.asarray(x) if not isinstance(x, np.ndarray) else x
    with prec.context():
        return prec.backend.asarray(arr)


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
    with prec.context():
        return dec, prec.backend.row_space(M, dec.rank)


def null_space(A: Any, prec: Precision, length_scale: float = 1.0) -> tuple[RankDecision, Any]:
    """Rank decision and a basis (rows) of the right null space of ``A`` (m, n)."""
    A = np.asarray(A)
    dec = decide_rank(A, prec, length_scale)
    if dec.rank is None:
        return dec, None
    with prec.context():
        return dec, prec.backend.null_space(A, dec.rank)


def solve_coefficients(B: np.ndarray, x: np.ndarray, prec: Precision) -> np.ndarray:
    """Least-squares coefficients c with ``c @ B ~ x`` (B rows independent)."""
    with prec.context():
        return prec.backend.solve(np.asarray(B).T, x)
