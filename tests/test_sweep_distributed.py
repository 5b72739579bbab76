"""A grid sweep distributed with Dask gives the serial result, bit for bit.

A local Dask cluster on the loopback address (two worker processes, one thread each, no
dashboard) runs the rows of a 6 x 6 grid of the planar 3-RPR's platform position (at the
reference orientation, below the reference point, so that the grid crosses its Type II
locus); the serial run of the same grid is the reference: the same reached, rank and
measure arrays (compared as bits), the same located points and loci, the same JSON
document.  The tests that need a cluster are skipped without Dask distributed (the
``dask`` extra); the error a user gets without it is checked either way.
"""

from __future__ import annotations

import importlib.util
import math
import pickle
import sys
from pathlib import Path

import numpy as np
import pytest

from mechsing.errors import UserError
from mechsing.kinematics.closure import ClosureError
from mechsing.sweeps import SweepResult, SweepRun, sweep

ROOT = Path(__file__).resolve().parent.parent
FILE = str(ROOT / "examples" / "planar_3rpr.yaml")
GRID = ["pose.x=0.5:1.5:0.2", "pose.y=-0.3:0.7:0.2"]
# the measures and the located points do not depend on the classification's precision;
# float keeps the module fast
PRECISION = "float"

needs_dask = pytest.mark.skipif(
    importlib.util.find_spec("distributed") is None,
    reason="Dask distributed is not installed (pip install 'mechsing[dask]')",
)


@pytest.fixture(scope="module")
def cluster():
    from distributed import LocalCluster

    with LocalCluster(
        host="127.0.0.1",
        n_workers=2,
        threads_per_worker=1,
        processes=True,
        dashboard_address=None,
        # no dashboard; the HTTP server on any free port, not 8787
        scheduler_kwargs={"dashboard_address": ":0"},
    ) as c:
        yield c


@pytest.fixture(scope="module")
def serial() -> SweepResult:
    r = sweep(FILE, GRID, precision=PRECISION)
    # the comparison means something: the grid reaches everything and crosses a locus
    assert r.reached.shape == (6, 6) and r.reached.all()
    assert len(r.located) >= 4 and r.loci
    return r


def _bits(a: np.ndarray) -> bytes:
    return a.dtype.str.encode() + np.ascontiguousarray(a).tobytes()


def _same(serial: SweepResult, other: SweepResult) -> None:
    assert _bits(other.reached) == _bits(serial.reached)
    assert other.tests == serial.tests
    for t in serial.tests:
        assert _bits(other.rank[t]) == _bits(serial.rank[t]), t
        assert _bits(other.ratio[t]) == _bits(serial.ratio[t]), t
    assert len(other.located) == len(serial.located)
    for p, q in zip(other.located, serial.located, strict=True):
        assert (p.values, p.kind, p.tests, p.ratio, p.joints, p.far_side, p.between) == (
            q.values,
            q.kind,
            q.tests,
            q.ratio,
            q.joints,
            q.far_side,
            q.between,
        )
        assert p.classes == q.classes
    assert len(other.loci) == len(serial.loci)
    for a, b in zip(other.loci, serial.loci, strict=True):
        assert (a.test, a.classes, a.closed) == (b.test, b.classes, b.closed)
        assert _bits(a.vertices) == _bits(b.vertices)
    assert other.notes == serial.notes
    assert other.newton_iterations == serial.newton_iterations
    assert other.to_json() == serial.to_json()


@needs_dask
def test_scheduler_gives_the_serial_result(cluster, serial: SweepResult) -> None:
    done: list[int] = []
    run = SweepRun(FILE, GRID, precision=PRECISION)
    order = list(run.rows(done.append, scheduler=cluster.scheduler_address))
    assert order == list(range(6))  # yielded in row order, whatever order they finished in
    assert done == [6] * 6  # progress: each row's samples, once
    _same(serial, run.result())
    # a second sweep on the same workers (their sweeps are built already) is the same
    _same(serial, sweep(FILE, GRID, precision=PRECISION, scheduler=cluster.scheduler_address))


@needs_dask
def test_workers_start_a_local_cluster(serial: SweepResult) -> None:
    # two workers, or one on a one-CPU machine (--workers is bounded by the CPUs)
    from mechsing.sweeps.distributed import usable_cpus

    _same(serial, sweep(FILE, GRID, precision=PRECISION, workers=min(2, usable_cpus())))


@needs_dask
def test_unreachable_scheduler_is_a_user_error() -> None:
    import dask
    import distributed  # noqa: F401  (its defaults in dask's config before the set below:
    # on leaving, the set removes the keys it found missing, all of "distributed" when this
    # test is a process's first to import it, as under pytest-xdist)

    with (
        dask.config.set({"distributed.comm.timeouts.connect": "2s"}),
        pytest.raises(UserError, match="cannot reach the Dask scheduler at tcp://127.0.0.1:9"),
    ):
        sweep(FILE, GRID, precision=PRECISION, scheduler="tcp://127.0.0.1:9")


def test_without_dask_the_error_says_what_to_install(monkeypatch) -> None:
    monkeypatch.setitem(sys.modules, "distributed", None)  # import distributed fails
    with pytest.raises(UserError, match=r"mechsing\[dask\]"):
        sweep(FILE, GRID, precision=PRECISION, workers=2)


def test_a_path_is_not_distributed() -> None:
    with pytest.raises(UserError, match="rows of a grid"):
        sweep(FILE, ["pose.x=0.5:1.5:0.2"], precision=PRECISION, workers=2)


def test_a_rows_closure_error_reaches_the_driver_whole() -> None:
    # a row's error is raised on a worker and pickled back to the driver
    e = pickle.loads(pickle.dumps(ClosureError("row 3 does not close", "reference", 1.5e-3)))
    assert isinstance(e, ClosureError)
    assert (str(e), e.configuration, e.residual) == ("row 3 does not close", "reference", 1.5e-3)


@needs_dask
def test_a_closure_not_kept_travels_whole_and_gives_the_serial_result(cluster) -> None:
    """The hexapod's closure of full row rank is measured without keeping its matrices
    (they are computed again where read): a row sent back from a worker carries them
    whole, and the crossings between rows found from them are the serial ones."""
    hexapod = str(ROOT / "examples" / "stewart_octahedral.yaml")
    grid = ["pose.x=-0.04:0.04:0.04", "pose.rz=-1.8:1.8:0.1"]
    run = SweepRun(hexapod, grid, precision=PRECISION)
    assert "closure" in run.engine.measures(run.engine.z0[None, : run.engine.model.n]).deferred
    serial = sweep(hexapod, grid, precision=PRECISION)
    # Fichter's Type II turns (rz = +-pi/2), crossed between the rows (refined from the
    # received rows' matrices)
    turns = [p for p in serial.located if p.between == "column" and "output" in p.tests]
    assert len(turns) == 6
    assert all(abs(abs(p.values[1]) - math.pi / 2) <= 1e-12 for p in turns)
    _same(serial, sweep(hexapod, grid, precision=PRECISION, scheduler=cluster.scheduler_address))
