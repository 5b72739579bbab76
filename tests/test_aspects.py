"""The labelling of a grid's aspects (mechsing.sweeps.aspects.aspects_of) against an
independent breadth-first flood fill over the samples (tests/reference/aspects_flood.py):
random grids, random cuts placed by located points along and between rows, blocks of
rows from one sample to the whole grid; and its working memory (a few bytes a sample
beyond the grid's regular samples, the labels one byte a sample)."""

from __future__ import annotations

import tracemalloc
import types

import numpy as np
import pytest

from mechsing.sweeps import aspects as asp
from tests.reference import aspects_flood


def _grid(rng: np.random.Generator, rows: int, cols: int, cuts: int) -> tuple:
    """Samples, regular ones, located points half-way between neighbours and the cuts
    they make (right: along row j between columns i and i + 1; up: between rows j and
    j + 1 on column i)."""
    xs = np.linspace(-1.0, 1.0, cols) * rng.choice([1.0, -1.0])  # either direction
    ys = np.linspace(0.0, 2.0, rows)
    regular = rng.random((rows, cols)) < rng.uniform(0.3, 1.0)
    right = np.zeros((rows, max(cols - 1, 0)), dtype=bool)
    up = np.zeros((max(rows - 1, 0), cols), dtype=bool)
    located = []
    for _ in range(cuts):
        if rng.random() < 0.5 and cols > 1:
            j, i = int(rng.integers(rows)), int(rng.integers(cols - 1))
            x = 0.5 * (xs[i] + xs[i + 1])
            located.append(types.SimpleNamespace(values=(x, ys[j]), between="row"))
            right[j, i] = True
        elif rows > 1:
            j, i = int(rng.integers(rows - 1)), int(rng.integers(cols))
            y = 0.5 * (ys[j] + ys[j + 1])
            located.append(types.SimpleNamespace(values=(xs[i], y), between="column"))
            up[j, i] = True
    return xs, ys, regular, located, right, up


@pytest.mark.parametrize("seed", range(6))
def test_aspects_match_a_flood_fill(seed: int, monkeypatch: pytest.MonkeyPatch) -> None:
    rng = np.random.default_rng(seed)
    for _ in range(25):
        rows, cols = (int(n) for n in rng.integers(1, 30, 2))
        xs, ys, regular, located, right, up = _grid(rng, rows, cols, int(rng.integers(0, 40)))
        monkeypatch.setattr(asp, "ASPECT_BLOCK_SAMPLES", int(rng.integers(1, 2 * rows * cols)))
        got = asp.aspects_of(xs, ys, regular, located)
        want = aspects_flood.regions(
            regular.tolist(), right.tolist(), up.tolist(), xs.tolist(), ys.tolist()
        )
        assert [(a.cells, a.box) for a in got] == [(n, box) for n, box, _ in want]
        for a, (_, _, mask) in zip(got, want, strict=True):
            assert np.array_equal(a.mask, np.array(mask))


def test_aspects_working_memory_is_a_few_bytes_a_sample() -> None:
    """A 200 x 1000 grid cut into strips: the labelling's peak beyond its input under 8
    bytes a sample (the whole-grid graph of neighbour pairs it once built took about 150),
    its labels one byte a sample."""
    rows, cols = 200, 1000
    xs, ys = np.linspace(-1.0, 1.0, cols), np.linspace(0.0, 2.0, rows)
    regular = np.ones((rows, cols), dtype=bool)
    regular[:, ::100] = False  # ten strips
    asp.aspects_of(xs, ys, regular, [])
    tracemalloc.start()
    try:
        got = asp.aspects_of(xs, ys, regular, [])
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert [a.cells for a in got] == [99 * rows] * 10
    assert got[0].labels.itemsize == 1
    assert peak < 8 * rows * cols
