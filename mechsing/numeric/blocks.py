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
    # blocks of one shape are factorised in one batched call
    shapes: dict[tuple[int, int], list[tuple[np.ndarray, np.ndarray]]] = {}
    lone_rows: list[int] = []
    lone_cols: list[int] = []
    for rows, cols in blocks:
        if len(rows) and len(cols):
            shapes.setdefault((len(rows), len(cols)), []).append((rows, cols))
        else:
            lone_rows.extend(rows.tolist())
            lone_cols.extend(cols.tolist())
    groups = []
    sigmas = []
    for members in shapes.values():
        R = np.stack([r for r, _ in members])
        C = np.stack([c for _, c in members])
        sub = A[R[:, :, None], C[:, None, :]]
        if compute_uv:
            Ub, sb, Vtb = np.linalg.svd(sub, full_matrices=True)
        else:
            Ub = Vtb = None
            sb = np.linalg.svd(sub, compute_uv=False)
        groups.append((R, C, Ub, Vtb, sb.shape[1]))
        sigmas.append(sb.reshape(-1))
    paired = np.concatenate(sigmas) if sigmas else np.zeros(0)
    order = np.argsort(-paired, kind="stable")
    s = np.zeros(k)
    s[: len(paired)] = paired[order]
    if not compute_uv:
        return s
    # output position of every paired singular value, then of every block's remaining
    # left (right) kernel vectors, then of the zero rows (columns)
    place = np.empty(len(paired), dtype=int)
    place[order] = np.arange(len(paired))
    ucols = m if full_matrices else k
    vrows = n if full_matrices else k
    U = np.zeros((m, ucols))
    Vt = np.zeros((vrows, n))
    u_next = v_next = len(paired)
    at = 0
    for R, C, Ub, Vtb, p in groups:
        count, r, c = len(R), R.shape[1], C.shape[1]
        pos = place[at : at + count * p].reshape(count, p)
        at += count * p
        u_pos = np.concatenate([pos, u_next + np.arange(count * (r - p)).reshape(count, r - p)], 1)
        v_pos = np.concatenate([pos, v_next + np.arange(count * (c - p)).reshape(count, c - p)], 1)
        u_next += count * (r - p)
        v_next += count * (c - p)
        keep = u_pos < ucols
        rows_b = np.broadcast_to(R[:, :, None], Ub.shape)
        cols_b = np.broadcast_to(u_pos[:, None, :], Ub.shape)
        mask = np.broadcast_to(keep[:, None, :], Ub.shape)
        U[rows_b[mask], cols_b[mask]] = Ub[mask]
        keep = v_pos < vrows
        rows_b = np.broadcast_to(v_pos[:, :, None], Vtb.shape)
        cols_b = np.broadcast_to(C[:, None, :], Vtb.shape)
        mask = np.broadcast_to(keep[:, :, None], Vtb.shape)
        Vt[rows_b[mask], cols_b[mask]] = Vtb[mask]
    for i in lone_rows:
        if u_next < ucols:
            U[i, u_next] = 1.0
        u_next += 1
    for j in lone_cols:
        if v_next < vrows:
            Vt[v_next, j] = 1.0
        v_next += 1
    return U, s, Vt
