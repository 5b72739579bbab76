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
        return self.labels == self.label

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


def _cuts(
    shape: tuple[int, int], xs: np.ndarray, ys: np.ndarray, located: Any
) -> tuple[np.ndarray, np.ndarray]:
    """The neighbour pairs a located point separates: ``right[j, i]`` cuts sample (j, i)
    from (j, i + 1) (a point found along row j), ``up[j, i]`` cuts (j, i) from (j + 1, i)
    (a point found between rows j and j + 1, on column i)."""
    rows, cols = shape
    right = np.zeros((rows, max(cols - 1, 0)), dtype=bool)
    up = np.zeros((max(rows - 1, 0), cols), dtype=bool)

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
            j, i = int(np.argmin(np.abs(ys - y))), between(xs, x)
            if i is not None and cols > 1:
                right[j, i] = True
        else:
            i, j = int(np.argmin(np.abs(xs - x))), between(ys, y)
            if j is not None and rows > 1:
                up[j, i] = True
    return right, up


def aspects_of(
    xs: np.ndarray,
    ys: np.ndarray,
    regular: np.ndarray,
    located: Any,
) -> tuple[Aspect, ...]:
    """The connected singularity-free regions of a grid over ``xs`` (columns) and ``ys``
    (rows), SI: ``regular`` (rows by columns) its regular samples, ``located`` the
    singularities located on it (each with ``values`` and ``between``), largest region
    first (ties: the one with the lowest first sample, row by row)."""
    shape = regular.shape
    rows, cols = shape
    right, up = _cuts(shape, np.asarray(xs, float), np.asarray(ys, float), located)
    idx = np.arange(rows * cols).reshape(shape)
    # neighbours joined: both regular, nothing located between them
    h = regular[:, :-1] & regular[:, 1:] & ~right
    v = regular[:-1, :] & regular[1:, :] & ~up
    a = np.concatenate([idx[:, :-1][h], idx[:-1, :][v]])
    b = np.concatenate([idx[:, 1:][h], idx[1:, :][v]])
    n = rows * cols
    graph = coo_matrix((np.ones(len(a)), (a, b)), shape=(n, n))
    _, labels = connected_components(graph, directed=False)
    labels = np.where(regular, labels.reshape(shape), -1)
    flat = labels.ravel()
    regions, first = np.unique(flat[flat >= 0], return_index=True)
    if not len(regions):
        return ()
    where = np.flatnonzero(flat >= 0)
    lab = np.searchsorted(regions, flat[where])  # each regular sample's region, 0..k-1
    jj, ii = np.divmod(where, cols)
    x = np.asarray(xs, float)[ii]
    y = np.asarray(ys, float)[jj]
    k = len(regions)
    cells = np.bincount(lab, minlength=k)
    lo_x, hi_x = np.full(k, np.inf), np.full(k, -np.inf)
    lo_y, hi_y = np.full(k, np.inf), np.full(k, -np.inf)
    np.minimum.at(lo_x, lab, x)
    np.maximum.at(hi_x, lab, x)
    np.minimum.at(lo_y, lab, y)
    np.maximum.at(hi_y, lab, y)
    # largest first; ties: the one whose first sample (row by row) comes first
    first_at = where[first]
    order = sorted(range(k), key=lambda r: (-int(cells[r]), int(first_at[r])))
    out_labels = np.full(shape, -1, dtype=np.int64)
    out_labels[regular] = np.searchsorted(regions, labels[regular])
    return tuple(
        Aspect(
            int(cells[r]),
            ((float(lo_x[r]), float(hi_x[r])), (float(lo_y[r]), float(hi_y[r]))),
            r,
            out_labels,
        )
        for r in order
    )
