"""The rows of a grid sweep computed on a Dask ``distributed`` cluster.

Owns :func:`distributed_rows`, the distributed twin of :meth:`.engine.Sweep.rows` for a
grid, and the work a Dask worker does for it (:func:`_rows_task`).

Conventions:

* **The serial result, bit for bit.**  This process (the driver) computes the grid's
  first column itself (:meth:`.engine.Sweep.first_column`, as the serial run does);
  each chunk of rows (:meth:`.engine.Sweep.row_chunks`, the chunks the serial run
  computes together) is then one task on a worker, the very call the serial run makes,
  ``Sweep.rows_of([(j, column.Z[j]) ...], cx, values[0])``, whose inputs travel
  pickled (exact floats).  Rows are independent once the first column is known, so the
  same computations in the same order per chunk give the same arrays.
* **Row order.**  Results come back in any order; they are buffered and yielded in row
  order, so the caller (:class:`mechsing.sweeps.SweepRun`) sees the serial sequence and
  computes the crossings between neighbouring rows as it does serially.  An error in a
  chunk is raised when that chunk's turn comes (the chunks before it are yielded
  first).  At most :data:`AHEAD_PER_THREAD` chunks per worker thread are submitted ahead
  of the next chunk to yield (bounded memory on a long grid).
* **Workers build the sweep once per process.**  A task carries the row's start
  configuration and a reference to one scattered recipe: the pickled mechanism (a
  :class:`~mechsing.model.Mechanism` pickles; the engine itself is never sent), the
  resolved swept variables, the start configuration's name and the mechsing version.
  A worker unpickles it and builds its :class:`~.engine.Sweep` on the first row, and
  keeps it (a few recipes at most) keyed by the mechanism's file path, the SHA-256 of
  the pickled mechanism (its content: an edited file is a new key), the ``--vary``
  specs and the ``--from`` configuration.  Rows on one worker process run one at a
  time (the arbitrary precision context is process-global), so a worker with several
  threads gains nothing: start workers with one thread each.
* ``progress`` is called with the row's number of samples when a row is yielded.
* Dask is the optional extra ``mechsing[dask]``; without it a distributed sweep is a
  :class:`~mechsing.errors.UserError` that says how to install it.
"""

from __future__ import annotations

import hashlib
import pickle
import threading
import uuid
from collections import OrderedDict
from collections.abc import Callable, Iterator
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing.errors import UserError
from mechsing.sweeps.engine import RowResult, Sweep

__all__ = ["AHEAD_PER_THREAD", "distributed_rows"]

#: chunks of rows submitted ahead of the next to yield, per worker thread of the cluster
AHEAD_PER_THREAD = 4

#: recipes (sweeps) a worker process keeps built
_KEPT = 4


@dataclass(frozen=True)
class _Recipe:
    """What a worker needs to build the sweep: the cache key, the pickled
    ``(mechanism, variables, from_config)``, the row variable's samples (SI) and the
    driver's mechsing version (a worker with another version refuses the row)."""

    key: tuple[Any, ...]
    blob: bytes
    row_values: np.ndarray
    version: str


def distributed_rows(
    run: Any,  # a mechsing.sweeps.SweepRun (which imports this module)
    values: list[np.ndarray],
    workers: int | None,
    scheduler: str | None,
    progress: Callable[[int], None] | None = None,
) -> Iterator[RowResult]:
    """The rows of a grid sweep, in row order, computed on a Dask cluster.

    Parameters
    ----------
    run : the sweep (its engine computes the first column here; its mechanism, swept
        variables and ``--from`` configuration make the workers' recipe)
    values : the samples (SI) of the two swept variables, as ``Sweep.rows`` takes them
    workers : start a local cluster of this many worker processes (one thread each)
    scheduler : or use the Dask scheduler at this address (``tcp://host:8786``)
    progress : called with the number of samples of each finished row

    Yields exactly what ``run.engine.rows(values, progress)`` yields.
    """
    client_cls, cluster_cls, as_completed = _dask()
    if workers is not None and scheduler:
        raise UserError("give --workers N (a local cluster) or --scheduler ADDRESS, not both")
    if workers is not None and workers < 1:
        raise UserError(f"--workers must be at least 1 (got {workers})")
    eng = run.engine
    with _client(client_cls, cluster_cls, workers, scheduler) as client:  # fails fast
        column = eng.first_column(values)
        recipe = _recipe(run, eng, values[0])
        (shared,) = client.scatter([recipe], broadcast=True, hash=False)
        threads = sum(client.nthreads().values())
        ahead = AHEAD_PER_THREAD * max(threads, 1)
        yield from _in_order(client, as_completed, shared, eng, column, values, ahead, progress)


def _dask() -> tuple[Any, Any, Any]:
    try:
        from distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise UserError(
            "distributing a sweep (--workers, --scheduler) needs Dask distributed: "
            "pip install 'mechsing[dask]' (or run the sweep without them, serially)"
        ) from None
    return Client, LocalCluster, as_completed


@contextmanager
def _client(
    client_cls: Any, cluster_cls: Any, workers: int | None, scheduler: str | None
) -> Iterator[Any]:
    """A Dask client to the scheduler at an address, or to a local cluster of
    ``workers`` processes (one thread each) on the loopback address; closed after."""
    with ExitStack() as stack:
        try:
            if scheduler:
                client = stack.enter_context(client_cls(scheduler))
            else:
                cluster = stack.enter_context(
                    cluster_cls(
                        n_workers=workers,
                        threads_per_worker=1,
                        processes=True,
                        host="127.0.0.1",
                        dashboard_address=None,
                        # no dashboard; the HTTP server on any free port, not 8787
                        scheduler_kwargs={"dashboard_address": ":0"},
                    )
                )
                client = stack.enter_context(client_cls(cluster))
        except (OSError, TimeoutError) as exc:
            where = f"the Dask scheduler at {scheduler}" if scheduler else "a local Dask cluster"
            raise UserError(f"cannot reach {where}: {exc}") from None
        yield client


def _recipe(run: Any, eng: Sweep, row_values: np.ndarray) -> _Recipe:
    from mechsing import __version__

    blob = pickle.dumps((run.mechanism, eng.variables, eng.from_config))
    key = (
        run.mechanism.path,
        hashlib.sha256(blob).hexdigest(),
        tuple((v.name, v.start, v.stop, v.step) for v in run.varies),
        eng.from_config,
    )
    return _Recipe(key, blob, np.asarray(row_values), __version__)


def _in_order(
    client: Any,
    as_completed: Any,
    shared: Any,
    eng: Sweep,
    column: RowResult,
    values: list[np.ndarray],
    ahead: int,
    progress: Callable[[int], None] | None,
) -> Iterator[RowResult]:
    """Submit the chunks of rows (at most ``ahead`` past the next to yield), yield their
    rows in order."""
    assert column.Z is not None
    k = len(values[0])
    chunks = eng.row_chunks(values)
    tag = uuid.uuid4().hex
    finished = as_completed()
    pending: dict[Any, tuple[int, Any]] = {}  # future key -> (chunk, future)
    done: dict[int, tuple[list[RowResult] | None, BaseException | None]] = {}
    submitted = 0
    try:
        for c in range(len(chunks)):
            while submitted < len(chunks) and submitted <= c + ahead:
                i = submitted
                submitted += 1
                starts = [(j, column.Z[j]) for j in chunks[i] if column.reached[j]]
                if not starts:  # nothing to compute: as the serial run does
                    done[i] = ([eng.unreached_row(j, k) for j in chunks[i]], None)
                    continue
                fut = client.submit(
                    _rows_task,
                    shared,
                    starts,
                    key=f"mechsing-rows-{tag}-{i}",
                    pure=False,
                )
                pending[fut.key] = (i, fut)
                finished.add(fut)
            while c not in done:
                fut = next(finished)
                i, _ = pending.pop(fut.key)
                try:
                    got = {r.index: r for r in fut.result()}
                    rows = [got.get(j) or eng.unreached_row(j, k) for j in chunks[i]]
                    done[i] = (rows, None)
                except Exception as exc:  # raised in row order, below
                    done[i] = (None, exc)
                del fut
            rows, error = done.pop(c)
            if error is not None:
                raise error
            assert rows is not None
            for row in rows:
                if progress:  # before the row is yielded: its consumer may stop there
                    progress(k)
                yield row
    finally:
        finished.clear()
        if pending:
            client.cancel([f for _, f in pending.values()])


# --------------------------------------------------------------------- on the worker

_built: OrderedDict[tuple[Any, ...], Sweep] = OrderedDict()
_lock = threading.Lock()


def _rows_task(recipe: _Recipe, starts: list[tuple[int, np.ndarray]]) -> list[RowResult]:
    """The rows of one chunk of the grid from their first-column configurations (on a
    worker): ``Sweep.rows_of``, as the serial run computes that chunk."""
    from mechsing import __version__

    if recipe.version != __version__:
        raise UserError(
            f"the Dask worker runs mechsing {__version__}, the sweep mechsing {recipe.version}: "
            "install the same version on the workers"
        )
    with _lock:
        sweep = _built.get(recipe.key)
        if sweep is None:
            mech, variables, from_config = pickle.loads(recipe.blob)
            sweep = Sweep(mech, variables, from_config)
            _built[recipe.key] = sweep
            while len(_built) > _KEPT:
                _built.popitem(last=False)
        _built.move_to_end(recipe.key)
        return sweep.rows_of(starts, sweep.cols[0], recipe.row_values)
