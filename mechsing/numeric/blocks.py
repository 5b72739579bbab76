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

A big matrix may also be given as a :mod:`scipy.sparse` matrix (the closure
Jacobian of a big mechanism, :meth:`KinematicModel.sparse_closure_jacobian`):
its blocks are found from its stored non-zero entries and each block is made
dense on its own, so nothing of the size of the whole matrix is built.
:func:`block_factors` keeps the factorisation block by block, and
:meth:`BlockFactors.solve` applies a filtered pseudo-inverse (least squares)
block by block: the work is linear in the number of blocks of a given size.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing.numeric.dispatch import table, threshold

try:  # numpy's private gufuncs (numpy 2's names); absent or renamed, the wrapper serves
    from numpy.linalg import _umath_linalg as _ul

    _GUFUNCS = all(hasattr(_ul, n) for n in ("svd", "svd_f", "svd_s"))
except ImportError:  # pragma: no cover - depends on the installed numpy
    _GUFUNCS = False

__all__ = [
    "BlockFactors",
    "block_factors",
    "block_svd",
    "blocks_of",
    "dense",
    "dense_svd",
    "issparse",
]

#: below this many entries the dense SVD is cheaper than finding blocks
DENSE_ENTRIES = 4096


def dense(entries: int) -> bool:
    """Is a float matrix of this many entries factorised whole (dense)?  Up to
    :data:`DENSE_ENTRIES`; above it the block-by-block factorisation is the fast path
    (the dispatch table ``factorisation``: :func:`mechsing.numeric.dispatch.threshold`,
    so that ``MECHSING_FAST=0`` factorises every matrix whole, and
    ``fast_paths("always")`` every one block by block)."""
    return entries <= threshold(DENSE_ENTRIES)


def issparse(A: Any) -> bool:
    """Whether ``A`` is a scipy sparse matrix.  scipy.sparse is imported only where a
    big mechanism needs it (it costs a fifth of a second at every start); before that,
    nothing can be one."""
    if type(A) is np.ndarray:  # the common case, at every rank decision: no lookup
        return False
    sparse = sys.modules.get("scipy.sparse")
    return sparse is not None and bool(sparse.issparse(A))


def _entries(A: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Rows, columns and values of the non-zero entries of a dense or sparse matrix
    (an explicitly stored 0.0 is not an entry), rows ascending, then columns."""
    if issparse(A):
        C = A.tocoo()
        keep = C.data != 0
        r, c, v = C.row[keep], C.col[keep], C.data[keep]
        order = np.lexsort((c, r))
        return r[order].astype(np.intp), c[order].astype(np.intp), v[order]
    r, c = np.nonzero(A)
    return r, c, A[r, c]


@dataclass(frozen=True)
class _Structure:
    """The connected components of a pattern: ``labels`` of the rows then the columns
    (m + n nodes; components numbered by their first node), the nodes in component
    order (``order``, ``bounds``), and each component's row and column counts."""

    m: int
    n: int
    labels: np.ndarray
    order: np.ndarray
    bounds: np.ndarray
    nrows: np.ndarray
    ncols: np.ndarray


def _structure(m: int, n: int, r: np.ndarray, c: np.ndarray) -> _Structure:
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    graph = coo_matrix((np.ones(len(r)), (r, m + c)), shape=(m + n, m + n))
    count, labels = connected_components(graph, directed=False)
    order = np.argsort(labels, kind="stable")
    bounds = np.searchsorted(labels[order], np.arange(count + 1))
    nrows = np.bincount(labels[:m], minlength=count)
    ncols = np.bincount(labels[m:], minlength=count)
    return _Structure(m, n, labels, order, bounds, nrows, ncols)


def blocks_of(A: Any) -> list[tuple[np.ndarray, np.ndarray]]:
    """The blocks of ``A`` (dense or sparse): (rows, columns) index arrays, one pair per
    connected component of its non-zero pattern, ordered by their first row (then
    column).  A row or a column that is entirely zero is a block of its own with no
    columns or no rows."""
    m, n = A.shape
    r, c, _ = _entries(A)
    st = _structure(m, n, r, c)
    out = []
    for b in range(len(st.nrows)):
        members = st.order[st.bounds[b] : st.bounds[b + 1]]
        out.append((members[members < m], members[members >= m] - m))
    return out


@dataclass
class BlockFactors:
    """The SVD of a matrix block by block.

    ``groups``: one per block shape (r, c) with r, c > 0, in the order of the first
    block of that shape: ``(R, C, U, s, Vt)`` with ``R`` (count, r) and ``C`` (count,
    c) the blocks' rows and columns, ``U`` (count, r, r), ``s`` (count, min(r, c)),
    ``Vt`` (count, c, c) their full SVDs (``U`` and ``Vt`` None without vectors);
    ``lone_rows`` and ``lone_cols``: the zero rows and columns; ``s``: every singular
    value, descending, padded with zeros to min(m, n) (those of
    :func:`numpy.linalg.svd`)."""

    shape: tuple[int, int]
    groups: list[tuple[np.ndarray, np.ndarray, Any, np.ndarray, Any]]
    lone_rows: list[int]
    lone_cols: list[int]
    s: np.ndarray
    #: the position in ``s`` of each group's singular values, concatenated
    order: np.ndarray

    def solve(self, b: np.ndarray, weight: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
        """``sum_i w(s_i) v_i (u_i . b)`` over the paired singular triplets, block by
        block: a filtered pseudo-inverse applied to ``b`` (``weight`` maps singular
        values to their factors: ``1/s`` kept, 0 dropped; damped ``s/(s^2+lam^2)``)."""
        x = np.zeros(self.shape[1])
        for R, C, U, s, Vt in self.groups:
            p = s.shape[1]
            y = np.einsum("kri,kr->ki", U[:, :, :p], b[R]) * weight(s)
            x[C] = np.einsum("kic,ki->kc", Vt[:, :p, :], y)
        return x


def block_factors(A: Any, compute_uv: bool = True) -> BlockFactors:
    """The block SVD of a float matrix (dense or sparse), every block factorised on its
    own; blocks of one shape in one batched call."""
    m, n = A.shape
    r, c, v = _entries(A)
    return _factor(A, r, c, v, _structure(m, n, r, c), compute_uv)


def _factor(
    A: Any, r: np.ndarray, c: np.ndarray, v: np.ndarray, st: _Structure, compute_uv: bool
) -> BlockFactors:
    m, n = st.m, st.n
    is_paired = (st.nrows > 0) & (st.ncols > 0)
    paired = np.flatnonzero(is_paired)
    # the zero rows and columns (blocks of one node), in block order
    lone_nodes = st.order[~is_paired[st.labels[st.order]]].tolist()
    # shapes in the order of their first block
    key = st.nrows[paired] * (n + 1) + st.ncols[paired]
    _, first = np.unique(key, return_index=True)
    dense = not issparse(A)
    if not dense:
        # each entry's place in its block: its row's (column's) rank among the block's
        rank = np.empty(m + n, dtype=np.intp)
        rank[st.order] = np.arange(m + n)
        rank -= st.bounds[st.labels]
        rank[m:] -= st.nrows[st.labels[m:]]
        entry_block = st.labels[r]
        slot = np.full(len(st.nrows), -1)
    groups = []
    sigmas = []
    for f in np.sort(first):
        members = paired[key == key[f]]
        nr, nc = int(st.nrows[members[0]]), int(st.ncols[members[0]])
        start = st.bounds[members][:, None]
        R = st.order[start + np.arange(nr)]
        C = st.order[start + nr + np.arange(nc)] - m
        if dense:
            sub = A[R[:, :, None], C[:, None, :]]
        else:
            slot[:] = -1
            slot[members] = np.arange(len(members))
            at = slot[entry_block]
            sel = at >= 0
            sub = np.zeros((len(members), nr, nc))
            sub[at[sel], rank[r[sel]], rank[m + c[sel]]] = v[sel]
        Ub: np.ndarray | None = None
        Vtb: np.ndarray | None = None
        if compute_uv:
            Ub, sb, Vtb = np.linalg.svd(sub, full_matrices=True)
        else:
            sb = np.linalg.svd(sub, compute_uv=False)
        groups.append((R, C, Ub, sb, Vtb))
        sigmas.append(sb.reshape(-1))
    paired_s = np.concatenate(sigmas) if sigmas else np.zeros(0)
    order = np.argsort(-paired_s, kind="stable")
    s = np.zeros(min(m, n))
    s[: len(paired_s)] = paired_s[order]
    return BlockFactors(
        (m, n),
        groups,
        [i for i in lone_nodes if i < m],
        [i - m for i in lone_nodes if i >= m],
        s,
        order,
    )


_DENSE = table(
    "dense factorisation",
    "numpy.linalg.svd of a dense float matrix (mechsing.numeric.blocks.dense_svd)",
)


def _small_finite(A: Any, full_matrices: bool, compute_uv: bool) -> bool:
    """A non-empty finite float64 matrix of at most DENSE_ENTRIES entries (the rank
    decisions' matrices: a few to a few hundred entries), where the installed numpy has
    the gufuncs its wrapper calls under numpy 2's names (numpy 1 names them by shape)."""
    return (
        _GUFUNCS
        and type(A) is np.ndarray
        and A.dtype == np.float64
        and A.ndim == 2
        and 0 < A.size <= DENSE_ENTRIES
        and bool(np.isfinite(A).all())
    )


@_DENSE.register(
    "lapack",
    "a small finite float64 matrix: the LAPACK routine numpy.linalg.svd calls (its "
    "gufunc, gesdd) called directly, bit for bit the same factors, without the wrapper's "
    "type checks and error-state switch (about half of a 6 x 6 matrix's 25 us; the "
    "analysis of one configuration takes some 40 of them)",
    accepts=_small_finite,
)
def _lapack_svd(
    A: np.ndarray, full_matrices: bool, compute_uv: bool
) -> tuple[np.ndarray, np.ndarray, np.ndarray] | np.ndarray:
    if compute_uv:
        gufunc = _ul.svd_f if full_matrices else _ul.svd_s
        U, s, Vt = gufunc(A, signature="d->ddd")
        if s[0] == s[0]:  # converged (else NaN: numpy's wrapper raises its error)
            return U, s, Vt
    else:
        s = _ul.svd(A, signature="d->d")
        if s[0] == s[0]:
            return s
    return _numpy_svd(A, full_matrices, compute_uv)


def dense_svd(
    A: np.ndarray, full_matrices: bool = True, compute_uv: bool = True
) -> tuple[np.ndarray, np.ndarray, np.ndarray] | np.ndarray:
    """:func:`numpy.linalg.svd` of a dense float matrix (its factors, or its singular
    values), the same numbers bit for bit: a small finite one by the table ``dense
    factorisation``'s form, any other by numpy's wrapper."""
    form = _DENSE.pick(A, full_matrices, compute_uv)
    if form is not None:
        return form(A, full_matrices, compute_uv)
    return _numpy_svd(A, full_matrices, compute_uv)


def _numpy_svd(
    A: np.ndarray, full_matrices: bool, compute_uv: bool
) -> tuple[np.ndarray, np.ndarray, np.ndarray] | np.ndarray:
    if compute_uv:
        U, s, Vt = np.linalg.svd(A, full_matrices=full_matrices)
        return U, s, Vt
    return np.linalg.svd(A, compute_uv=False)


def block_svd(
    A: Any, full_matrices: bool = True, compute_uv: bool = True
) -> tuple[np.ndarray, np.ndarray, np.ndarray] | np.ndarray:
    """:func:`numpy.linalg.svd` of a float matrix (dense or sparse), block by block when it
    splits (module docstring)."""
    if type(A) is np.ndarray and A.dtype == np.float64 and dense(A.size):
        return dense_svd(A, full_matrices, compute_uv)  # a small one: whole, at once
    m, n = A.shape
    if issparse(A):
        if dense(m * n) or not np.isfinite(A.data).all():
            A = A.toarray()
    else:
        A = np.asarray(A, dtype=float)
    if not issparse(A) and (dense(A.size) or not np.isfinite(A).all()):
        return dense_svd(A, full_matrices, compute_uv)
    r, c, v = _entries(A)
    st = _structure(m, n, r, c)
    if len(st.nrows) == 1:
        D = A.toarray() if issparse(A) else A
        return dense_svd(D, full_matrices, compute_uv)
    F = _factor(A, r, c, v, st, compute_uv)
    if not compute_uv:
        return F.s
    k = min(m, n)
    paired = F.s[: len(F.order)]
    # output position of every paired singular value, then of every block's remaining
    # left (right) kernel vectors, then of the zero rows (columns)
    place = np.empty(len(paired), dtype=int)
    place[F.order] = np.arange(len(paired))
    ucols = m if full_matrices else k
    vrows = n if full_matrices else k
    U = np.zeros((m, ucols))
    Vt = np.zeros((vrows, n))
    u_next = v_next = len(paired)
    at = 0
    for R, C, Ub, sb, Vtb in F.groups:
        count, r_, c_ = len(R), R.shape[1], C.shape[1]
        p = sb.shape[1]
        pos = place[at : at + count * p].reshape(count, p)
        at += count * p
        u_pos = np.concatenate(
            [pos, u_next + np.arange(count * (r_ - p)).reshape(count, r_ - p)], 1
        )
        v_pos = np.concatenate(
            [pos, v_next + np.arange(count * (c_ - p)).reshape(count, c_ - p)], 1
        )
        u_next += count * (r_ - p)
        v_next += count * (c_ - p)
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
    for i in F.lone_rows:
        if u_next < ucols:
            U[i, u_next] = 1.0
        u_next += 1
    for j in F.lone_cols:
        if v_next < vrows:
            Vt[v_next, j] = 1.0
        v_next += 1
    return U, F.s, Vt


table("factorisation", "numpy.linalg.svd of the whole matrix").register(
    "blocks",
    "a float matrix of more than DENSE_ENTRIES entries, or sparse: block by block "
    "(the whole matrix's singular values; its vectors another basis of each space)",
)(block_svd)
