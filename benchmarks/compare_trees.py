"""Speed of two checkouts of mechsing measured side by side (a restructuring must not slow
the analysis down).

usage:
    python benchmarks/compare_trees.py OLD_TREE NEW_TREE [--repeat 5] [--modes float auto]
                                       [--scanner] [--tests] [--test-args ...]

Each measurement runs in a fresh child process with ``PYTHONPATH`` set to one tree, the
two trees alternating (old, new, old, new, ...) so that the machine's load falls on both
alike.  It prints medians over ``--repeat`` runs and the ratio new / old:

1. ``analyze`` per configuration: for every bundled example (the NEW tree's examples/)
   and each mode, the wall time of ``mechsing.analyze`` divided by the number of
   configurations (the first run of each child is a warm-up and is not counted);
2. with ``--scanner``: the scanner's throughput against Pinocchio's pipeline, from
   ``benchmarks/speed_accuracy.py --part throughput`` of each tree (its own medians);
3. with ``--tests``: the wall time of each tree's test suite (``pytest -q -p no:cacheprovider``
   plus ``--test-args``), run in that tree.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import time
from pathlib import Path

_ANALYZE = r"""
import json, sys, time
from pathlib import Path
from mechsing import analyze
out = {}
for mode in sys.argv[2:]:
    for path in sorted(Path(sys.argv[1]).glob("*.yaml")):
        analyze(path, precision=mode)  # warm-up: imports, caches
        t = time.perf_counter()
        r = analyze(path, precision=mode)
        out[f"{mode} {path.stem}"] = (time.perf_counter() - t) / max(1, len(r.configurations))
print(json.dumps(out))
"""


def _env(tree: Path) -> dict[str, str]:
    return {
        **os.environ,
        "PYTHONPATH": str(tree),
        "OMP_NUM_THREADS": "1",
        "OPENBLAS_NUM_THREADS": "1",
    }


def _analyze_times(tree: Path, examples: Path, modes: list[str]) -> dict[str, float]:
    run = subprocess.run(
        [sys.executable, "-c", _ANALYZE, str(examples), *modes],
        env=_env(tree),
        capture_output=True,
        text=True,
        check=True,
    )
    return json.loads(run.stdout.strip().splitlines()[-1])


def _scanner_ratio(tree: Path, repeat: int) -> str:
    run = subprocess.run(
        [
            sys.executable,
            str(tree / "benchmarks" / "speed_accuracy.py"),
            "--part",
            "throughput",
            "--repeat",
            str(repeat),
        ],
        env=_env(tree),
        capture_output=True,
        text=True,
        cwd=tree,
    )
    return run.stdout + run.stderr[-2000:]


def _suite_time(tree: Path, extra: list[str]) -> float:
    t = time.perf_counter()
    subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", *extra],
        env=_env(tree),
        cwd=tree,
        capture_output=True,
    )
    return time.perf_counter() - t


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("old", type=Path)
    ap.add_argument("new", type=Path)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--modes", nargs="+", default=["float", "auto"])
    ap.add_argument("--scanner", action="store_true")
    ap.add_argument("--tests", action="store_true")
    ap.add_argument("--test-args", nargs=argparse.REMAINDER, default=[])
    args = ap.parse_args()
    trees = {"old": args.old.resolve(), "new": args.new.resolve()}
    examples = trees["new"] / "examples"

    times: dict[str, dict[str, list[float]]] = {"old": {}, "new": {}}
    for _ in range(args.repeat):
        for side, tree in trees.items():
            for key, t in _analyze_times(tree, examples, args.modes).items():
                times[side].setdefault(key, []).append(t)
    print(f"1. analyze, seconds per configuration (medians of {args.repeat}, alternating)")
    print(f"   {'mode example':44s} {'old':>9s} {'new':>9s} {'new/old':>8s}")
    ratios = []
    for key in times["old"]:
        o, n = statistics.median(times["old"][key]), statistics.median(times["new"][key])
        ratios.append(n / o)
        print(f"   {key:44s} {o:9.4f} {n:9.4f} {n / o:8.2f}")
    geo = statistics.geometric_mean(ratios)
    print(f"   geometric mean of new/old: {geo:.3f}")

    if args.scanner:
        print("2. scanner against Pinocchio (speed_accuracy.py --part throughput)")
        for side in ("old", "new", "old", "new"):
            text = _scanner_ratio(trees[side], args.repeat)
            found = re.findall(r"throughput ratio[^\n]*", text)
            print(f"   {side}: {found[0] if found else text[-600:]}")

    if args.tests:
        print("3. test suite wall time (s)")
        suite: dict[str, list[float]] = {"old": [], "new": []}
        for _ in range(args.repeat):
            for side, tree in trees.items():
                suite[side].append(_suite_time(tree, args.test_args))
        o, n = statistics.median(suite["old"]), statistics.median(suite["new"])
        print(f"   old {suite['old']}\n   new {suite['new']}")
        print(f"   medians: old {o:.1f} s, new {n:.1f} s, new/old {n / o:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
