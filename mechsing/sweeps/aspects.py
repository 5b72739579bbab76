"""The aspects of a grid sweep: its connected singularity-free regions (Wenger & Chablat).

Owns :class:`Aspect` and :func:`aspects_of`.  A sample of the grid is *regular* when it
was reached and every test has its generic rank there.  Two neighbouring samples (along a
row or between rows) are in one region when both are regular and no singularity was
located between them (a sign change, a minimum or a limit of travel: past a limit of
travel a revolute sweep resumes on another assembly mode).  Each connected set of
regular samples is an aspect of the assembly mode the grid was followed on: its number of
samples and its bounding box over the two swept variables (SI).

The regions are those of the samples: a singular curve that passes between two samples
and back again within one cell, unseen by the locator, does not separate them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

__all__ = ["Aspect", "aspects_of", "regular_samples"]


@dataclass(frozen=True)
class Aspect:
    """A connected singularity-free region of a grid: ``cells`` samples, its bounding box
    ``box`` ((x_min, x_max), (y_min, y_max)) over the two swept variables (SI, first
    variable first); ``labels`` (the grid's shape, rows by columns, shared by the grid's
    regions) holds ``label`` at its samples."""

    cells: int
    box: tuple[tuple[float, float], tuple[float, float]]
    label: int = field(default=0, repr=False, compare=False)
    labels: np.ndarray = field(
        default_factory=lambda: np.zeros((0, 0), int), repr=False, compare=False
    )

    @property
    def mask(self) -> np.ndarray:
        """The region's samples (rows by columns)."""
        mask: np.ndarray = self.labels == self.label
        return mask

    def to_json(self) -> dict[str, Any]:
        """The region as an entry of the sweep JSON's ``aspects``."""
        (x0, x1), (y0, y1) = self.box
        return {"cells": self.cells, "box": [[x0, x1], [y0, y1]]}


def regular_samples(
    reached: np.ndarray, rank: dict[str, np.ndarray], generic: dict[str, int]
) -> np.ndarray:
    """The samples reached with every test at its generic rank (an undecided rank is not
    regular)."""
    ok = np.asarray(reached, dtype=bool).copy()
    for t, r in rank.items():
        if t in generic:
            ok &= np.asarray(r) == generic[t]
    return ok


#: samples of the grid labelled at once (a block of whole rows): the working arrays of
#: the labelling are a block's, not the grid's
ASPECT_BLOCK_SAMPLES = 8192


def _cuts(
    shape: tuple[int, int], xs: np.ndarray, ys: np.ndarray, located: Any
) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
    """The neighbour pairs a located point separates, as (rows, columns) of their first
    samples, each sorted by row: ``right`` cuts sample (j, i) from (j, i + 1) (a point
    found along row j), ``up`` cuts (j, i) from (j + 1, i) (a point found between rows j
    and j + 1, on column i)."""
    rows, cols = shape
    right: list[tuple[int, int]] = []
    up: list[tuple[int, int]] = []

    def between(values: np.ndarray, v: float) -> int | None:
        """k with v between values[k] and values[k + 1] (either order), else None."""
        d = np.sign(values - v)
        for k in range(len(values) - 1):
            if d[k] == 0 or d[k + 1] == 0 or d[k] != d[k + 1]:
                return k
        return None

    for p in located:
        x, y = float(p.values[0]), float(p.values[1])
        if p.between == "row":
            along = between(xs, x)
            if along is not None and cols > 1:
                right.append((int(np.argmin(np.abs(ys - y))), along))
        else:
            across = between(ys, y)
            if across is not None and rows > 1:
                up.append((across, int(np.argmin(np.abs(xs - x)))))

    def by_row(pairs: list[tuple[int, int]]) -> tuple[np.ndarray, np.ndarray]:
        a = np.array(sorted(pairs), dtype=np.int64).reshape(-1, 2)
        return a[:, 0], a[:, 1]

    return by_row(right), by_row(up)


def _block_cuts(
    cut: tuple[np.ndarray, np.ndarray], j0: int, j1: int
) -> tuple[np.ndarray, np.ndarray]:
    """The cuts of rows j0 ... j1 - 1, rows counted from j0."""
    jj, ii = cut
    lo, hi = np.searchsorted(jj, [j0, j1])
    return jj[lo:hi] - j0, ii[lo:hi]


def _runs(
    regular: np.ndarray, right: tuple[np.ndarray, np.ndarray], up: tuple[np.ndarray, np.ndarray]
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The grid's runs (regular samples joined along a row, maximal), row by row, and the
    pairs of runs joined between rows: each run's row, first and last column, and the
    joined pairs (a, b) of run numbers (distinct pairs, b in the row after a's).  A block
    of rows at a time: no array over the whole grid."""
    rows, cols = regular.shape
    step = max(1, ASPECT_BLOCK_SAMPLES // max(cols, 1))
    row_of, first, last, pa, pb = [], [], [], [], []
    done = 0  # runs numbered so far
    above: np.ndarray | None = None  # the run numbers of the row above the block (-1: none)
    for j0 in range(0, rows, step):
        j1 = min(rows, j0 + step)
        blk = regular[j0:j1]
        join = blk[:, :-1] & blk[:, 1:]
        join[_block_cuts(right, j0, j1)] = False
        start = blk.copy()
        start[:, 1:] &= ~join
        end = blk.copy()
        end[:, :-1] &= ~join
        s = np.flatnonzero(start)
        e = np.flatnonzero(end)
        row_of.append((j0 + s // cols).astype(np.int32))
        first.append((s % cols).astype(np.int32))
        last.append((e % cols).astype(np.int32))
        # each regular sample's run number (-1 elsewhere)
        ids = np.cumsum(start, axis=None, dtype=np.int64).reshape(blk.shape) + (done - 1)
        ids[~blk] = -1
        done += len(s)
        # joined between rows: both regular, no cut between them
        lower = blk
        upper = ids[:-1]
        if above is not None:
            upper = np.concatenate([above[None, :], upper])
        else:
            lower = blk[1:]
        lower_ids = ids[len(ids) - len(upper) :]
        k0 = j1 - len(upper) - 1  # the row of upper[0]
        v = (upper >= 0) & lower
        v[_block_cuts(up, k0, j1 - 1)] = False
        a, b = upper[v], lower_ids[v]
        if len(a):
            pair = np.unique(a * done + b)
            pa.append(pair // done)
            pb.append(pair % done)
        above = ids[-1]
    cat = np.concatenate
    empty = np.zeros(0, np.int64)
    return (
        cat(row_of),
        cat(first),
        cat(last),
        cat(pa) if pa else empty,
        cat(pb) if pb else empty,
    )


def aspects_of(
    xs: np.ndarray,
    ys: np.ndarray,
    regular: np.ndarray,
    located: Any,
) -> tuple[Aspect, ...]:
    """The connected singularity-free regions of a grid over ``xs`` (columns) and ``ys``
    (rows), SI: ``regular`` (rows by columns) its regular samples, ``located`` the
    singularities located on it (each with ``values`` and ``between``), largest region
    first (ties: the one with the lowest first sample, row by row).

    The regions are unions of runs (a row's regular samples joined along it): the runs
    are labelled block by block and joined between rows, so the memory beyond the
    result's labels (one byte a sample up to 127 regions) is the runs' and a block's."""
    xs = np.asarray(xs, float)
    ys = np.asarray(ys, float)
    regular = np.asarray(regular, dtype=bool)
    shape = regular.shape
    cols = shape[1]
    right, up = _cuts(shape, xs, ys, located)
    row_of, first, last, a, b = _runs(regular, right, up)
    n = len(row_of)
    if not n:
        return ()
    graph = coo_matrix((np.ones(len(a), np.int8), (a, b)), shape=(n, n))
    _, comp = connected_components(graph, directed=False)
    # regions numbered by their first sample, row by row (their first run's number)
    k = int(comp.max()) + 1
    first_run = np.full(k, n, dtype=np.int64)
    np.minimum.at(first_run, comp, np.arange(n))
    number = np.empty(k, dtype=np.int64)
    number[np.argsort(first_run, kind="stable")] = np.arange(k)
    lab = number[comp]  # each run's region, 0..k-1
    lengths = (last - first + 1).astype(np.int64)
    cells = np.zeros(k, dtype=np.int64)
    np.add.at(cells, lab, lengths)
    # each run's extent along the row: the least and greatest x over its columns
    ext = np.append(xs, xs[-1])
    bounds = np.stack([first, last + 1], axis=1).ravel()
    run_lo_x = np.minimum.reduceat(ext, bounds)[::2]
    run_hi_x = np.maximum.reduceat(ext, bounds)[::2]
    y = ys[row_of]
    lo_x, hi_x = np.full(k, np.inf), np.full(k, -np.inf)
    lo_y, hi_y = np.full(k, np.inf), np.full(k, -np.inf)
    np.minimum.at(lo_x, lab, run_lo_x)
    np.maximum.at(hi_x, lab, run_hi_x)
    np.minimum.at(lo_y, lab, y)
    np.maximum.at(hi_y, lab, y)
    # each region's first sample (row by row): its first run's
    head = np.sort(first_run)  # region r's first run
    first_at = row_of[head].astype(np.int64) * cols + first[head]
    # largest first; ties: the one whose first sample (row by row) comes first
    order = sorted(range(k), key=lambda r: (-int(cells[r]), int(first_at[r])))
    dtype = next(t for t in (np.int8, np.int16, np.int32, np.int64) if k <= np.iinfo(t).max)
    out_labels = np.full(shape, -1, dtype=dtype)
    # the runs, in row-major order, are the regular samples in that order
    out_labels[regular] = np.repeat(lab.astype(dtype), lengths)
    return tuple(
        Aspect(
            int(cells[r]),
            ((float(lo_x[r]), float(hi_x[r])), (float(lo_y[r]), float(hi_y[r]))),
            r,
            out_labels,
        )
        for r in order
    )
