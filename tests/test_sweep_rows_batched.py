"""The rows of a grid computed together give what each row gives alone, bit for bit.

A grid's rows are followed, measured and refined in chunks (``Sweep.rows_of``: their
first nodes in one batched Newton, the samples between their nodes in one, their
measures in one batch, the crossings along them refined together), and the crossings
between neighbouring rows of a chunk are refined together (``Sweep.between_many``).
Every batched step is per configuration, so each row must come out exactly as the
one-row call (``Sweep.row``, ``Sweep.between_many`` of one pair) makes it.  The grid is the
five-bar's two inputs over a range that reaches its Type II locus (folds of the rows)
and crosses its Type I locus (sign changes along and between the rows)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mechsing.kinematics import ClosureError
from mechsing.kinematics.paths.follow import first_nodes_of, follow, follow_together
from mechsing.kinematics.paths.segments import close_segments
from mechsing.numeric import dispatch
from mechsing.sweeps import SweepRun

ROOT = Path(__file__).resolve().parent.parent
FILE = str(ROOT / "examples" / "five_bar.yaml")
GRID = ["A1=-0.6:0.6:0.04", "A2=-0.6:0.6:0.04"]


@pytest.fixture(scope="module")
def grid():
    run = SweepRun(FILE, GRID, precision="float")
    eng = run.engine
    values = [v.values for v in run.vars]
    column = eng.first_column(values)
    return eng, values, column


def _bits(a: np.ndarray) -> bytes:
    return np.ascontiguousarray(a).tobytes()


def _same_located(ps, qs) -> None:
    assert len(ps) == len(qs)
    for p, q in zip(ps, qs, strict=True):
        assert (p.values, p.kind, p.tests, p.ratio, p.edge, p.cell, p.far_side) == (
            q.values,
            q.kind,
            q.tests,
            q.ratio,
            q.edge,
            q.cell,
            q.far_side,
        )
        assert _bits(p.q) == _bits(q.q)


# a pose grid of a planar parallel robot (prismatic joints) and of a spatial one
# (spherical joints, the legs' split Newton), both across their Type II locus
POSE_GRIDS = [
    ("planar_3rpr.yaml", ["pose.x=0.4:1.6:0.1", "pose.y=2.4:3.4:0.1"]),
    ("stewart_octahedral.yaml", ["pose.rz=-1.8:1.8:0.1", "pose.x=-0.04:0.04:0.04"]),
]


@pytest.mark.parametrize("file,spec", POSE_GRIDS, ids=[f for f, _ in POSE_GRIDS])
def test_pose_grid_rows_together_are_each_row_alone(file: str, spec: list[str]) -> None:
    run = SweepRun(str(ROOT / "examples" / file), spec, precision="float")
    values = [v.values for v in run.vars]
    column = run.engine.first_column(values)
    together = _same_rows(run.engine, values, column)
    assert sum(p.kind == "crossing" for r in together for p in r.located) >= 4


def test_rows_together_are_each_row_alone(grid) -> None:
    eng, values, column = grid
    together = _same_rows(eng, values, column)
    kinds = {p.kind for r in together for p in r.located}
    # the comparison means something: rows that stop at folds and rows that cross
    assert {"fold", "crossing"} <= kinds
    assert any(not r.reached.all() for r in together) and any(r.reached.all() for r in together)


def _same_rows(eng, values, column):
    """Every reached row of the grid together, each compared with the row alone."""
    starts = [(j, column.Z[j]) for j in range(len(values[1])) if column.reached[j]]
    together = eng.rows_of(starts, eng.cols[0], values[0])
    for (j, z), got in zip(starts, together, strict=True):
        alone = eng.row(j, eng.cols[0], values[0], z)
        assert got.index == alone.index == j
        assert _bits(got.reached) == _bits(alone.reached)
        assert _bits(got.Z) == _bits(alone.Z)
        for t in eng.tests:
            assert _bits(got.rank[t]) == _bits(alone.rank[t]), (j, t)
            assert _bits(got.ratio[t]) == _bits(alone.ratio[t]), (j, t)
        assert got.newton == alone.newton and got.stopped == alone.stopped
        _same_located(got.located, alone.located)
    return together


def test_crossings_between_rows_together_are_each_pair_alone(grid) -> None:
    eng, values, column = grid
    starts = [(j, column.Z[j]) for j in range(len(values[1])) if column.reached[j]]
    rows = eng.rows_of(starts, eng.cols[0], values[0])
    pairs = [(a, b) for a, b in zip(rows[:-1], rows[1:], strict=True) if b.index == a.index + 1]
    together = eng.between_many(pairs, eng.cols[1])
    assert sum(len(x) for x in together) >= 10  # the rows' neighbours cross the Type I locus
    for (a, b), got in zip(pairs, together, strict=True):
        _same_located(got, eng.between_many([(a, b)], eng.cols[1])[0])


def test_first_nodes_of_several_starts_are_each_alone(grid) -> None:
    eng, values, column = grid
    pb, col, xs = eng.problem, eng.cols[0], values[0]
    starts = []
    for j in range(0, len(values[1]), 3):
        if column.reached[j]:
            try:
                k0, zk = eng.start_of(col, xs, column.Z[j])
            except ClosureError:
                continue
            starts.append((zk, [xs[k0:], xs[k0::-1]]))
    together = first_nodes_of(pb, starts, col)
    assert len(starts) >= 5
    for (z0, paths), got in zip(starts, together, strict=True):
        (alone,) = first_nodes_of(pb, [(z0, paths)], col)
        assert [x is None for x in got] == [x is None for x in alone]
        for x, y in zip(got, alone, strict=True):
            if x is not None:
                assert _bits(x) == _bits(y)


def test_segments_of_several_paths_close_as_each_alone(grid) -> None:
    eng, values, column = grid
    pb, col, xs = eng.problem, eng.cols[0], values[0]

    def traces(j: int):
        k0, zk = eng.start_of(col, xs, column.Z[j])
        return [follow(pb, zk, col, v, fine=False) for v in (xs[k0:], xs[k0::-1])]

    js = [j for j in range(0, len(values[1]), 4) if column.reached[j]]
    many = [tr for j in js for tr in traces(j)]
    close_segments(pb, many, col, [[2 * r, 2 * r + 1] for r in range(len(js))])
    for r, j in enumerate(js):
        alone = traces(j)
        close_segments(pb, alone, col)
        for got, want in zip(many[2 * r : 2 * r + 2], alone, strict=True):
            assert _bits(got.Z) == _bits(want.Z)
            assert _bits(got.newton) == _bits(want.newton)


def test_paths_followed_in_lockstep_are_each_followed_alone(grid) -> None:
    eng, values, column = grid
    pb, col, xs = eng.problem, eng.cols[0], values[0]
    paths = []
    for j in range(len(values[1])):
        if column.reached[j]:
            k0, zk = eng.start_of(col, xs, column.Z[j])
            for v in (xs[k0:], xs[k0::-1]):
                ((first,),) = first_nodes_of(pb, [(zk, [v])], col)
                paths.append((zk, v, first))
    together = follow_together(pb, col, paths)
    # some paths leave the lockstep at a fold and are finished alone
    assert any(tr.folds for tr in together) and any(not tr.folds for tr in together)
    for (z0, v, first), got in zip(paths, together, strict=True):
        alone = follow(pb, z0, col, v, fine=False, first=first)
        assert _bits(got.Z) == _bits(alone.Z)
        assert got.segments == alone.segments and got.stopped == alone.stopped
        assert [(f.value, f.direction, f.far_side) for f in got.folds] == [
            (f.value, f.direction, f.far_side) for f in alone.folds
        ]


def test_rows_measured_row_by_row_where_measures_depend_on_their_batch(grid) -> None:
    # measures that take a rank over their batch (a leg's inner loops) are taken row by
    # row, as alone; the five-bar's are per configuration, so both ways agree exactly
    eng, values, column = grid
    starts = [(j, column.Z[j]) for j in range(0, len(values[1]), 5) if column.reached[j]]
    batched = eng.rows_of(starts, eng.cols[0], values[0])
    with dispatch.fast_paths(False):  # each row measured alone
        measured, _ = eng._measure_rows([r.Z for r in batched], [r.reached for r in batched])
    assert isinstance(measured, list) and len(measured) == len(batched)
    apart = eng.rows_of(starts, eng.cols[0], values[0])
    for a, b in zip(batched, apart, strict=True):
        assert _bits(a.Z) == _bits(b.Z)
        for t in eng.tests:
            assert _bits(a.ratio[t]) == _bits(b.ratio[t]) and _bits(a.rank[t]) == _bits(b.rank[t])
        _same_located(a.located, b.located)
        assert len(b.measures) == int(np.sum(b.reached))
