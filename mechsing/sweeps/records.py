"""The records of a sweep's work: located points, rows, refined points, brackets.

Owns the named records the sweep's modules pass each other (:class:`Located`,
:class:`RowResult`, :class:`PathTrace`, :class:`Refined`, :class:`RowSamples`,
:class:`RowPairs`, :class:`ColumnBrackets`), how a located point is made from the sweep's
coordinates (:func:`located_at`) and how the points of one row found by several tests
become one (:func:`merge_located`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from mechsing.kinematics.paths.trace import PathTrace
from mechsing.kinematics.settings import SWEEP_LOCATE_TOL
from mechsing.sweeps.settings import SWEEP_MERGE_FACTOR, SWEEP_MERGE_RTOL

if TYPE_CHECKING:
    from mechsing.sweeps.measures import PointMeasures

__all__ = [
    "ColumnBrackets",
    "Located",
    "PathTrace",
    "Refined",
    "RowPairs",
    "RowResult",
    "RowSamples",
    "located_at",
    "merge_located",
]


@dataclass
class Located:
    """A singularity located on a sweep, before its classification: the swept values
    (SI), how it was found (``fold``, ``crossing``, ``minimum``, ``sample``: a sample
    itself singular), the tests whose measure
    vanishes there, the refined measure, the configuration (joint coordinates), and for
    a grid the row and column it lies between (``edge``: "row" or "column")."""

    values: tuple[float, ...]
    kind: str
    tests: tuple[str, ...]
    ratio: float
    q: np.ndarray
    row: int = 0
    edge: str = "row"
    cell: tuple[int, int] = (0, 0)
    far_side: bool = False
    #: the sweep's coordinates there (joints, then the pose's for a pose sweep)
    z: np.ndarray | None = None


@dataclass
class RowResult:
    """One row of a sweep (the whole path for a path): the reached samples, each test's
    rank and measure there, the located points, and why the row stopped early."""

    index: int
    reached: np.ndarray
    rank: dict[str, np.ndarray]
    ratio: dict[str, np.ndarray]
    located: list[Located]
    stopped: list[str] = field(default_factory=list)
    newton: int = 0
    Z: np.ndarray | None = None
    measures: PointMeasures | None = None
    #: limited coordinate -> the samples beyond its limits (:mod:`mechsing.sweeps.limits`)
    outside: dict[str, np.ndarray] = field(default_factory=dict)


class Refined(NamedTuple):
    """A singular point placed by a refinement: the sweep's coordinates there and the
    test's measure (its smallest relative singular value) there."""

    z: np.ndarray
    ratio: float


class RowSamples(NamedTuple):
    """One row handed to the location along rows: its sweep coordinates ``Z`` (NaN rows
    where not reached), which samples are reached, where its reached samples start in
    the measured batch (``offset``), each test's measure per sample, the swept column
    and the row's index."""

    Z: np.ndarray
    reached: np.ndarray
    offset: int
    ratio: dict[str, np.ndarray]
    col: int
    index: int


class RowPairs(NamedTuple):
    """A row's neighbouring reached samples: the pairs (a, a + 1) by their first samples
    ``first`` (an array), those samples' rows in the measured batch (``rows``), and which
    samples have both neighbours reached (``inner``: the minima's candidates)."""

    first: np.ndarray
    rows: np.ndarray
    inner: np.ndarray


class ColumnBrackets(NamedTuple):
    """One test's sign changes between two rows of a grid: the samples of the row
    variable where it changes (``K``), the two rows' configurations there (``ZA``,
    ``ZB``) and row a's samples' rows in its measured batch (``ia``)."""

    K: np.ndarray
    ZA: np.ndarray
    ZB: np.ndarray
    ia: np.ndarray


def located_at(
    z: np.ndarray,
    kind: str,
    tests: tuple[str, ...],
    ratio: float,
    edge: str,
    cell: tuple[int, int],
    cols: list[int],
    n: int,
    far_side: bool = False,
) -> Located:
    """A located point at the sweep's coordinates z (``cols`` the swept ones, the first
    ``n`` the joints), on a row's or column's edge ``cell`` (row index first)."""
    z = np.array(z, dtype=float)
    return Located(
        tuple(float(z[c]) for c in cols),
        kind,
        tests,
        ratio,
        z[:n].copy(),
        cell[0],
        edge,
        cell,
        far_side,
        z,
    )


def merge_located(located: list[Located], scales: tuple[float, ...]) -> list[Located]:
    """Points of one row found by several tests (or a fold and a test) at the same value
    are one point: their tests together, placed by the fold if there is one, else by the
    closure's test (near a singular point of the closure the other tests' measures are
    blurred by its double root; the closure's own placement is not).  ``scales``: the
    commensurate unit of each swept coordinate."""
    order = {"fold": 0, "crossing": 1, "minimum": 2, "sample": 3}
    located = sorted(located, key=lambda p: (p.values, order[p.kind]))
    groups: list[list[Located]] = []
    for p in located:
        for g in groups:
            o = g[0]
            if o.edge == p.edge and all(
                abs(a - b) <= SWEEP_MERGE_FACTOR * SWEEP_LOCATE_TOL * s + SWEEP_MERGE_RTOL * s
                for a, b, s in zip(o.values, p.values, scales, strict=True)
            ):
                g.append(p)
                break
        else:
            groups.append([p])
    out = []
    for g in groups:
        best = min(g, key=lambda p: (order[p.kind] > 0, "closure" not in p.tests))
        best.tests = tuple(dict.fromkeys(t for p in [best, *g] for t in p.tests))
        out.append(best)
    return out
