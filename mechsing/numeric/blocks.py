"""Block structure of sparse matrices: the float SVD of a matrix that splits into blocks.

A closure Jacobian has one block of rows per loop, and a row is non-zero only in
the columns of its loop's joints; loops that share no joint give blocks that
share no row and no column.  Up to a permutation of its rows and columns such a
matrix is block diagonal, and its singular values are the union of its blocks'
(exactly: the permutation is orthogonal).  :func:`block_svd` finds the blocks
(the connected components of the graph whose nodes are the rows and the columns
and whose edges are the non-zero entries: an entry is zero when it is exactly
0.0) and factorises each on its own, so the cost is the sum of the blocks'
cubes rather than the whole matrix's cube.  Its result has the shapes and the
order of :func:`numpy.linalg.svd` (singular values descending); the singular
vectors of a repeated or zero singular value are another basis of the same
space, as any SVD's are.
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

__all__ = ["block_svd", "blocks_of"]

#: below this many entries the dense SVD is cheaper than finding blocks
DENSE_ENTRIES = 4096


def blocks_of(A: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """The blocks of ``A``: (rows, columns) index arrays, one pair per connected
    component of its non-zero pattern, ordered by their first row (then column).
    A row or a column that is entirely zero is a block of its own with no
    columns or no rows."""
    m, n = A.shape
    r, c = np.nonzero(A)
    graph = coo_matrix((np.ones(len(r)), (r, m + c)), shape=(m + n, m + n))
    count, labels = connected_components(graph, directed=False)
    order = np.argsort(labels, kind="stable")
    bounds = np.searchsorted(labels[order], np.arange(count + 1))
    out = []
    for b in range(count):
        members = order[bounds[b] : bounds[b + 1]]
        out.append((members[members < m], members[members >= m] - m))
    return out


def block_svd(
    A: np.ndarray, full_matrices: bool = True, compute_uv: bool = True
) -> tuple[np.ndarray, np.ndarray, np.ndarray] | np.ndarray:
    """:func:`numpy.linalg.svd` of a float matrix, block by block when it splits (module docstring)."""
    A = np.asarray(A, dtype=float)
    m, n = A.shape
    if A.size <= DENSE_ENTRIES or not np.isfinite(A).all():
        return np.linalg.svd(A, full_matrices=full_matrices, compute_uv=compute_uv)
    blocks = blocks_of(A)
    if len(blocks) == 1:
        return np.linalg.svd(A, full_matrices=full_matrices, compute_uv=compute_uv)
    k = min(m, n)
    sigmas: list[np.ndarray] = []
    parts = []
    for rows, cols in blocks:
        if len(rows) and len(cols):
            sub = A[np.ix_(rows, cols)]
            if compute_uv:
                Ub, sb, Vtb = np.linalg.svd(sub, full_matrices=True)
                parts.append((rows, cols, Ub, Vtb, len(sb)))
            else:
                sb = np.linalg.svd(sub, compute_uv=False)
            sigmas.append(sb)
        else:
            parts.append((rows, cols, None, None, 0))
    paired = np.concatenate(sigmas) if sigmas else np.zeros(0)
    order = np.argsort(-paired, kind="stable")
    s = np.zeros(k)
    s[: len(paired)] = paired[order]
    if not compute_uv:
        return s
    # paired singular vectors first, in the order of their singular values, then
    # each block's remaining (left or right) kernel vectors, then the zero rows/columns
    left_paired, right_paired, left_rest, right_rest = [], [], [], []
    for rows, cols, Ub, Vtb, p in parts:
        if Ub is None:
            left_rest.extend((rows[i:i + 1], None) for i in range(len(rows)))
            right_rest.extend((cols[i:i + 1], None) for i in range(len(cols)))
            continue
        for i in range(p):
            left_paired.append((rows, Ub[:, i]))
            right_paired.append((cols, Vtb[i]))
        for i in range(p, Ub.shape[1]):
            left_rest.append((rows, Ub[:, i]))
        for i in range(p, Vtb.shape[0]):
            right_rest.append((cols, Vtb[i]))
    lefts = [left_paired[i] for i in order] + left_rest
    rights = [right_paired[i] for i in order] + right_rest
    ucols = m if full_matrices else k
    vrows = n if full_matrices else k
    U = np.zeros((m, ucols))
    for j, (idx, vec) in enumerate(lefts[:ucols]):
        U[idx, j] = 1.0 if vec is None else vec
    Vt = np.zeros((vrows, n))
    for j, (idx, vec) in enumerate(rights[:vrows]):
        Vt[j, idx] = 1.0 if vec is None else vec
    return U, s, Vt
