"""Exact mode against float on every bundled example: the README's "Precision" table.

usage: OPENBLAS_NUM_THREADS=1 python benchmarks/exact_ratio.py [--repeat 2] [EXAMPLE ...]

For each examples/*.yaml (or the names given), in one process: ``mechsing.analyze`` of
the whole file in float and in exact mode (time limit 900 s), one warm-up each (the
exact warm-up is reported as the first run: it pays for the primitive elements of the
number fields, cached afterwards), then ``--repeat`` alternating runs of each; the
table gives the best of them and their ratio, in Markdown.  A mode that refuses the
file is timed all the same (its refusal is what it does).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import mechsing
from mechsing.errors import MechsingError

ROOT = Path(__file__).resolve().parents[1]


def _run(path: Path, mode: str) -> float:
    t0 = time.perf_counter()
    try:
        if mode == "exact":
            mechsing.analyze(str(path), precision=mode, time_limit=900)
        else:
            mechsing.analyze(str(path), precision=mode)
    except MechsingError:
        pass  # a refused file: its refusal is timed
    return time.perf_counter() - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("examples", nargs="*", help="example names (default: all)")
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args()
    paths = sorted((ROOT / "examples").glob("*.yaml"))
    if args.examples:
        paths = [p for p in paths if p.stem in args.examples]
    print("| example | float (s) | exact (s) | exact / float | exact, first run (s) |")
    print("|---|---:|---:|---:|---:|")
    for path in paths:
        _run(path, "float")
        first = _run(path, "exact")
        tf, te = [], []
        for _ in range(args.repeat):
            tf.append(_run(path, "float"))
            te.append(_run(path, "exact"))
        f, e = min(tf), min(te)
        print(f"| {path.stem} | {f:.3f} | {e:.3f} | {e / f:.1f} | {first:.3f} |", flush=True)


if __name__ == "__main__":
    main()
