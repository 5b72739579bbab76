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
* **Bounded by the machine, never left waiting.**  ``--workers`` is at most the CPUs this
  process may run on (:func:`usable_cpus`: ``os.sched_getaffinity``, else
  ``os.cpu_count``).  A ``--scheduler`` address is checked (``[tcp://|tls://]HOST:PORT``),
  then probed before Dask connects (:func:`probe_scheduler`): a TCP connection within
  ``connect_timeout`` seconds (:data:`CONNECT_TIMEOUT` unless the caller gives another),
  and for ``tcp://`` the first 8 bytes of the scheduler's handshake, which a Dask scheduler
  sends at once: the length of its first message, at most :data:`HANDSHAKE_MAX_BYTES`.  A
  refused connection, silence, or bytes that are not Dask's (an HTTP server's reply read
  as a length was an allocation of exabytes) are a UserError naming the address.
"""

from __future__ import annotations

import hashlib
import os
import pickle
import re
import socket
import struct
import threading
import uuid
from collections import OrderedDict
from collections.abc import Callable, Iterator
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass
from typing import Any

import numpy as np

from mechsing.errors import UserError
from mechsing.sweeps.engine import Sweep
from mechsing.sweeps.records import RowResult

__all__ = [
    "AHEAD_PER_THREAD",
    "CONNECT_TIMEOUT",
    "HANDSHAKE_MAX_BYTES",
    "MAX_CONNECT_TIMEOUT",
    "check_workers",
    "distributed_rows",
    "parse_scheduler",
    "probe_scheduler",
    "usable_cpus",
]

#: chunks of rows submitted ahead of the next to yield, per worker thread of the cluster
AHEAD_PER_THREAD = 4

#: recipes (sweeps) a worker process keeps built
_KEPT = 4

#: seconds a Dask scheduler has to accept the connection and to answer (--connect-timeout)
CONNECT_TIMEOUT = 5.0
#: the longest --connect-timeout accepted (seconds)
MAX_CONNECT_TIMEOUT = 600.0
#: largest first message a Dask scheduler's handshake may announce (its handshake is a few
#: hundred bytes): a longer one is not Dask's protocol
HANDSHAKE_MAX_BYTES = 1 << 20

_ADDRESS = re.compile(
    r"(?:(?P<scheme>[A-Za-z][A-Za-z0-9+.-]*)://)?"
    r"(?P<host>\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9_](?:[A-Za-z0-9_.-]*[A-Za-z0-9_])?)"
    r":(?P<port>[0-9]{1,5})",
    re.ASCII,
)


def usable_cpus() -> int:
    """The CPUs this process may run on (``os.sched_getaffinity``, else ``os.cpu_count``)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


def check_workers(workers: int) -> None:
    """A UserError unless ``1 <= workers <= usable_cpus()``: a worker is a process that
    computes rows, and more of them than CPUs only share the CPUs (1000 workers on 2
    cores were 70 processes and 4.4 GB before failing)."""
    limit = usable_cpus()
    if workers < 1:
        raise UserError(f"--workers must be at least 1 (got {workers})")
    if workers > limit:
        shown = f"{workers}" if workers < 10**9 else f"{str(workers)[:12]}..."
        raise UserError(
            f"--workers {shown}: this process may run on {limit} CPU{'s' if limit > 1 else ''} "
            f"(os.sched_getaffinity), so at most {limit} worker{'s' if limit > 1 else ''}; "
            "give --workers at most that, or --scheduler ADDRESS for a larger cluster"
        )


def parse_scheduler(address: str) -> tuple[str, str, int]:
    """``(scheme, host, port)`` of ``[tcp://|tls://]HOST:PORT``; a UserError saying what
    is wrong otherwise."""
    text = address.strip()
    shown = repr(address[:80])
    m = _ADDRESS.fullmatch(text)
    if m is None:
        raise UserError(
            f"--scheduler {shown} is not an address: give tcp://HOST:PORT (e.g. "
            "tcp://127.0.0.1:8786, or tls://HOST:PORT)"
        )
    scheme = (m.group("scheme") or "tcp").lower()
    if scheme not in ("tcp", "tls"):
        raise UserError(
            f"--scheduler {shown}: the protocol {scheme!r} is not read; give tcp://HOST:PORT "
            "or tls://HOST:PORT"
        )
    port = int(m.group("port"))
    if not 1 <= port <= 65535:
        raise UserError(f"--scheduler {shown}: the port {port} is not between 1 and 65535")
    return scheme, m.group("host"), port


def probe_scheduler(address: str, timeout: float = CONNECT_TIMEOUT) -> None:
    """Check that a Dask scheduler answers at ``address`` within ``timeout`` seconds (see
    the module's conventions); a UserError naming the address and the reason otherwise."""
    scheme, host, port = parse_scheduler(address)

    def fail(reason: str) -> UserError:
        return UserError(f"cannot reach the Dask scheduler at {address}: {reason}")

    try:
        sock = socket.create_connection((host.strip("[]"), port), timeout=timeout)
    except TimeoutError:
        raise fail(f"no connection within {timeout:g} s (--connect-timeout)") from None
    except ConnectionRefusedError:
        raise fail("the connection was refused (is the scheduler running on that port?)") from None
    except socket.gaierror as exc:
        raise fail(f"unknown host {host!r} ({exc.strerror})") from None
    except OSError as exc:
        raise fail(exc.strerror or str(exc)) from None
    with sock:
        if scheme == "tls":  # the TLS handshake comes first: Dask checks the rest
            return
        head = b""
        try:
            while len(head) < 8:
                got = sock.recv(8 - len(head))
                if not got:
                    break
                head += got
        except TimeoutError:
            raise fail(
                f"it accepted the connection but sent nothing within {timeout:g} s, as a Dask "
                "scheduler does at once: is it one? (--connect-timeout)"
            ) from None
        except OSError as exc:
            raise fail(exc.strerror or str(exc)) from None
    if len(head) < 8:
        raise fail("it closed the connection without a Dask handshake: not a Dask scheduler")
    (size,) = struct.unpack("Q", head)
    if not 0 < size <= HANDSHAKE_MAX_BYTES:
        raise fail(
            f"it answered {head!r}, which is not Dask's protocol (a first message of {size} "
            "bytes): not a Dask scheduler"
        )


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
    connect_timeout: float = CONNECT_TIMEOUT,
    client: Any = None,
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
    connect_timeout : seconds the scheduler has to accept the connection and answer
    client : a client already open (:func:`open_client`: one cluster for several
        sweeps, each assembly mode's of ``--modes all``); None: one opened and closed here

    Yields exactly what ``run.engine.rows(values, progress)`` yields.
    """
    if client is None:
        with open_client(workers, scheduler, connect_timeout) as opened:
            yield from distributed_rows(
                run, values, workers, scheduler, progress, connect_timeout, opened
            )
        return
    _, _, as_completed = _dask()
    eng = run.engine
    column = eng.first_column(values)
    recipe = _recipe(run, eng, values[0])
    (shared,) = client.scatter([recipe], broadcast=True, hash=False)
    threads = sum(client.nthreads().values())
    ahead = AHEAD_PER_THREAD * max(threads, 1)
    yield from _in_order(client, as_completed, shared, eng, column, values, ahead, progress)


@contextmanager
def open_client(
    workers: int | None, scheduler: str | None, connect_timeout: float = CONNECT_TIMEOUT
) -> Iterator[Any]:
    """A Dask client for grid sweeps: to a local cluster of ``workers`` processes, or to
    the scheduler at ``scheduler`` (checked first: exit 2 with the reason); closed after.
    Several sweeps share it (:func:`distributed_rows`'s ``client``): a worker keeps the
    engines it built, keyed by mechanism and variables, whatever mode a sweep starts on
    (a row's start is sent with it)."""
    client_cls, cluster_cls, _ = _dask()
    if workers is not None and scheduler:
        raise UserError("give --workers N (a local cluster) or --scheduler ADDRESS, not both")
    if workers is not None:
        check_workers(workers)
    if scheduler:
        probe_scheduler(scheduler, connect_timeout)
    with _client(client_cls, cluster_cls, workers, scheduler, connect_timeout) as client:
        yield client


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
    client_cls: Any,
    cluster_cls: Any,
    workers: int | None,
    scheduler: str | None,
    timeout: float = CONNECT_TIMEOUT,
) -> Iterator[Any]:
    """A Dask client to the scheduler at an address (connecting within ``timeout``
    seconds), or to a local cluster of ``workers`` processes (one thread each) on the
    loopback address; closed after."""
    with ExitStack() as stack:
        try:
            if scheduler:
                client = stack.enter_context(client_cls(scheduler, timeout=timeout))
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
