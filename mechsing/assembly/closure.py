"""A loop's closure equations in the general formulation: the directions of Study
coordinates its product spans, less ``1`` and ``eps``.

The product of a loop's joint displacements is linear in each joint's coordinates; its
eight components' coefficient vectors (one per monomial, with the vector of ``1``) span
the directions the loop's motions reach.  The closure equations are the product's
components along the directions ``w`` of that span with ``w_0 = w_4 = 0`` (``1`` and
``eps`` are the identity's and the scalar's own components).  Any basis of that space
gives the same solutions; :func:`closure_rows` takes one from its table's fast form
when it decides, else the generic definition's (two SVDs at the working digits).
"""

from __future__ import annotations

from typing import Any

import mpmath
import sympy

from mechsing.assembly.settings import MODE_SPAN_CLEAR_RTOL, MODE_SPAN_ROUNDING_RTOL
from mechsing.numeric import MODE_SPAN_RTOL, dispatch

#: the order the echelon form eliminates Study coordinates in: ``1`` and ``eps`` first,
#: so the rows pivoted on the others are zero there
_ORDER = (0, 4, 1, 2, 3, 5, 6, 7)

#: the fast forms of :func:`closure_rows`
_BASIS = dispatch.table(
    "closure basis",
    "mechsing.assembly.closure.closure_rows (an SVD of the span, then of its components "
    "along 1 and eps, at the working digits)",
)


def generators(product: list[Any], gens: list[sympy.Symbol]) -> Any:
    """The coefficient vectors of the product's monomials, with the vector of ``1``: the
    columns of an 8 x (k + 1) mpmath matrix at the working digits."""
    from mechsing.assembly.certify import poly_terms

    cols: dict[Any, list[Any]] = {}
    for k, comp in enumerate(product):
        terms = poly_terms(comp, gens) if gens else [((), comp)]
        for mono, coeff in terms:
            cols.setdefault(mono, [0] * 8)[k] = mpmath.mpf(sympy.N(coeff, mpmath.mp.dps))
    M = mpmath.matrix(8, len(cols) + 1)
    M[0, 0] = 1
    for j, col in enumerate(cols.values()):
        for k in range(8):
            M[k, j + 1] = col[k]
    return M


def span_basis(M: Any) -> Any:
    """An orthonormal basis (8 x r, mpmath) of the span of the columns of ``M``."""
    U, S, _ = mpmath.svd_r(M)
    r = sum(1 for x in S if x > MODE_SPAN_RTOL * S[0])
    return U[:, :r] if r < U.cols else U


def closure_rows(M: Any) -> list[list[Any]]:
    """A basis (8-vectors, mpmath) of the directions ``w`` in the span of ``M``'s columns
    with ``w_0 = w_4 = 0``."""
    form = _BASIS.pick(M)
    if form is not None:
        rows = form(M)
        if rows is not None:
            return list(rows)
    V = span_basis(M)
    r = V.cols
    A = mpmath.matrix(max(r, 2), r)  # the span's components along 1 and eps, padded square
    for k in range(r):
        A[0, k], A[1, k] = V[0, k], V[4, k]
    _, S, Vt = mpmath.svd_r(A)
    rank = sum(1 for x in S if x > MODE_SPAN_RTOL)
    return [[sum(V[n, k] * Vt[i, k] for k in range(r)) for n in range(8)] for i in range(rank, r)]


def _mpmath_matrix(M: Any) -> bool:
    return isinstance(M, mpmath.matrix) and M.rows == 8


@_BASIS.register(
    "echelon",
    "every loop: the reduced row echelon form of the span (1 and eps eliminated first), "
    "its rows off them as unit vectors; None (the SVDs decide) where a pivot is neither "
    "rounding nor clear of it",
    _mpmath_matrix,
)
def echelon_rows(M: Any) -> list[list[Any]] | None:
    """The rows of the span's reduced row echelon form (coordinates eliminated in the
    order ``1, eps, i, j, k, eps i, eps j, eps k``, partial pivoting) pivoted off ``1``
    and ``eps``, each scaled to unit length: unique, and zero on every other pivot.
    A column is a pivot where its largest remaining entry is above
    ``MODE_SPAN_CLEAR_RTOL`` of the generators' largest entry, none where it is below
    ``MODE_SPAN_ROUNDING_RTOL`` of it (rounding at the working digits, far below the
    SVDs' ``MODE_SPAN_RTOL``); between, None."""
    rows = [[M[n, j] for n in _ORDER] for j in range(M.cols)]
    scale = max(abs(x) for row in rows for x in row)
    zero, clear = MODE_SPAN_ROUNDING_RTOL * scale, MODE_SPAN_CLEAR_RTOL * scale
    pivots: list[int] = []
    r = 0
    for c in range(8):
        if r == len(rows):
            break
        i = max(range(r, len(rows)), key=lambda t: abs(rows[t][c]))
        best = abs(rows[i][c])
        if best <= zero:
            continue
        if best < clear:
            return None
        rows[r], rows[i] = rows[i], rows[r]
        p = rows[r][c]
        pr = rows[r] = [x / p for x in rows[r]]
        for t in range(len(rows)):
            if t != r and rows[t][c] != 0:
                f = rows[t][c]
                rows[t] = [a - f * b for a, b in zip(rows[t], pr, strict=True)]
        pivots.append(c)
        r += 1
    rest = [abs(x) for row in rows[r:] for x in row]
    if rest and max(rest) > zero:
        return None
    out = []
    for row, c in zip(rows, pivots, strict=False):
        if c < 2:  # pivoted on 1 or eps
            continue
        norm = mpmath.sqrt(sum(x * x for x in row))
        w = [mpmath.mpf(0)] * 8
        for x, n in zip(row, _ORDER, strict=True):
            w[n] = x / norm
        out.append(w)
    return out
