"""Distributed sweeps bounded by the machine and never left waiting, run as a user runs them.

``--workers`` is at most the CPUs the process may run on; a ``--scheduler`` address is
checked, and an endpoint that refuses, stays silent or answers bytes that are not Dask's is
exit 2 within the connect timeout, naming the address and the reason.  Each command runs in a
child process under hard caps (address space 1 GB, a wall-clock limit); the endpoints are
servers on 127.0.0.1 that this test starts, each serving for at most a few seconds and
closed at the end; no test starts a worker.
"""

from __future__ import annotations

import os
import resource
import socket
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest

from mechsing.errors import UserError
from mechsing.sweeps.distributed import check_workers, parse_scheduler, usable_cpus
from tests.cli import ROOT

FILE = ROOT / "examples" / "planar_3rpr.yaml"
GRID = ["--vary", "pose.x=0.5:1.5:0.2", "--vary", "pose.y=-0.3:0.7:0.2"]
#: hard caps of the child process: address space (bytes) and wall clock (s)
ADDRESS_SPACE = 1 << 30
WALL_CLOCK = 60


def _capped() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_SPACE, ADDRESS_SPACE))


def _sweep(args: list[str], cwd: Path) -> tuple[int, str, float]:
    """``mechsing sweep FILE GRID ARGS`` in a capped child: (status, stderr, seconds)."""
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1"}
    argv = [sys.executable, "-m", "mechsing", "sweep", str(FILE), *GRID, "--quiet"]
    t0 = time.monotonic()
    r = subprocess.run(
        [*argv, "--precision", "float", *args],
        cwd=cwd,
        env=env,
        preexec_fn=_capped,
        capture_output=True,
        text=True,
        timeout=WALL_CLOCK,
    )
    return r.returncode, r.stderr, time.monotonic() - t0


@contextmanager
def _server(answer: bytes | None) -> Iterator[int]:
    """A TCP server on 127.0.0.1 (its port is yielded) that accepts connections and sends
    ``answer`` on each (None: stays silent), for at most WALL_CLOCK seconds."""
    listener = socket.socket()
    listener.bind(("127.0.0.1", 0))
    listener.listen(4)
    listener.settimeout(0.2)
    stop = threading.Event()
    held: list[socket.socket] = []

    def serve() -> None:
        deadline = time.monotonic() + WALL_CLOCK
        while not stop.is_set() and time.monotonic() < deadline:
            try:
                conn, _ = listener.accept()
            except TimeoutError:
                continue
            held.append(conn)
            if answer is not None:
                conn.sendall(answer)

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    try:
        yield listener.getsockname()[1]
    finally:
        stop.set()
        thread.join(timeout=5)
        for c in held:
            c.close()
        listener.close()


def _free_port() -> int:
    """A loopback port nothing listens on (bound, then released)."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.mark.parametrize(
    ("answer", "words"),
    [
        (None, "accepted the connection but sent nothing within 2 s"),  # hung > 150 s before
        # an HTTP reply read as a Dask frame length: an allocation of exabytes before
        (b"HTTP/1.1 400 Bad Request\r\n\r\n", "answered b'HTTP/1.1', which is not Dask's protocol"),
        (b"", "closed the connection without a Dask handshake"),
    ],
)
def test_an_endpoint_that_is_not_a_scheduler(answer: bytes | None, words: str, tmp_path) -> None:
    if answer == b"":  # accepts, then closes at once
        with socket.socket() as listener:
            listener.bind(("127.0.0.1", 0))
            listener.listen(1)
            port = listener.getsockname()[1]
            closer = threading.Thread(target=lambda: listener.accept()[0].close(), daemon=True)
            closer.start()
            status, err, seconds = _sweep(
                ["--scheduler", f"tcp://127.0.0.1:{port}", "--connect-timeout", "2"], tmp_path
            )
            closer.join(timeout=5)
    else:
        with _server(answer) as port:
            status, err, seconds = _sweep(
                ["--scheduler", f"tcp://127.0.0.1:{port}", "--connect-timeout", "2"], tmp_path
            )
    assert status == 2, err
    assert f"cannot reach the Dask scheduler at tcp://127.0.0.1:{port}: " in err
    assert words in err and "Traceback" not in err
    assert seconds < 30
    assert list(tmp_path.iterdir()) == []


def test_a_refused_connection_is_reported_at_once(tmp_path) -> None:
    port = _free_port()
    status, err, seconds = _sweep(["--scheduler", f"tcp://127.0.0.1:{port}"], tmp_path)
    assert status == 2, err
    assert f"tcp://127.0.0.1:{port}: the connection was refused" in err
    assert seconds < 20  # 31 s before (Dask's retries until its own 30 s timeout)


@pytest.mark.parametrize(
    ("address", "words"),
    [
        ("tcp://", "is not an address"),
        ("::::", "is not an address"),
        ("tcp://127.0.0.1", "is not an address"),
        ("ftp://127.0.0.1:21", "the protocol 'ftp' is not read"),
        ("tcp://127.0.0.1:99999", "the port 99999 is not between 1 and 65535"),
        ("tcp://127.0.0.1:0", "the port 0 is not between 1 and 65535"),
    ],
)
def test_a_malformed_address_is_bad_input(address: str, words: str, tmp_path) -> None:
    status, err, _ = _sweep(["--scheduler", address], tmp_path)
    assert status == 2, err  # exit 4 before
    assert words in err and "Traceback" not in err


@pytest.mark.parametrize("count", ["1000", "12345678901234567890"])
def test_workers_are_bounded_by_the_machine(count: str, tmp_path) -> None:
    status, err, _ = _sweep(["--workers", count], tmp_path)
    assert status == 2, err
    n = usable_cpus()
    assert f"this process may run on {n} CPU" in err and f"at most {n} worker" in err


def test_connect_timeout_range(tmp_path) -> None:
    for bad in ("0", "-1", "1e9", "nan", "\uff13"):
        status, err, _ = _sweep(
            ["--scheduler", "tcp://127.0.0.1:9", "--connect-timeout", bad], tmp_path
        )
        assert status == 2 and "--connect-timeout" in err, (bad, err)


def test_the_bounds_in_the_library() -> None:
    n = len(os.sched_getaffinity(0))
    assert usable_cpus() == n
    check_workers(n)
    with pytest.raises(UserError, match=f"at most {n} worker"):
        check_workers(n + 1)
    with pytest.raises(UserError, match="at least 1"):
        check_workers(0)
    assert parse_scheduler("127.0.0.1:8786") == ("tcp", "127.0.0.1", 8786)
    assert parse_scheduler("tls://sched.example:8786") == ("tls", "sched.example", 8786)
    assert parse_scheduler("tcp://[::1]:8786") == ("tcp", "[::1]", 8786)
