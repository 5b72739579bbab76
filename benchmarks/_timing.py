"""Wall-clock medians shared by the benchmark scripts (run as ``python benchmarks/X.py``,
which puts this folder on the import path)."""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable
from typing import Any


def timed_median(
    f: Callable[[], Any], repeat: int, warmup: int = 0, cpu: bool = False
) -> tuple[float, Any]:
    """Median wall time of ``repeat`` calls of ``f`` (seconds), and the last call's result;
    ``warmup`` untimed calls first (what a first call loads once: modules, caches).
    ``cpu``: the process's CPU time instead (on a shared machine, what one core spent:
    other processes' load does not count)."""
    clock = time.process_time if cpu else time.perf_counter
    ts = []
    out = None
    for _ in range(warmup):
        f()
    for _ in range(repeat):
        t0 = clock()
        out = f()
        ts.append(clock() - t0)
    return statistics.median(ts), out


def timed_medians_interleaved(
    fs: list[Callable[[], Any]], repeat: int, warmup: int = 0, cpu: bool = False
) -> list[tuple[float, Any]]:
    """:func:`timed_median` of several functions timed in turn: each round calls every
    ``f`` once, in order, so that a change of the machine's speed during the run (other
    processes, clocks, caches shared with a busy neighbour) falls on all of them alike,
    and their ratio is measured under the same conditions.  ``warmup`` untimed rounds
    first."""
    clock = time.process_time if cpu else time.perf_counter
    ts: list[list[float]] = [[] for _ in fs]
    outs: list[Any] = [None] * len(fs)
    for _ in range(warmup):
        for f in fs:
            f()
    for _ in range(repeat):
        for i, f in enumerate(fs):
            t0 = clock()
            outs[i] = f()
            ts[i].append(clock() - t0)
    return [(statistics.median(t), out) for t, out in zip(ts, outs, strict=True)]


def median_time(f: Callable[[], Any], repeat: int) -> float:
    """Median wall time of ``repeat`` calls of ``f`` (seconds)."""
    return timed_median(f, repeat)[0]
