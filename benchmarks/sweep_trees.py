"""mechsing's sweeps of ``sweep.py`` in two (or more) source trees, timed in turn.

    OPENBLAS_NUM_THREADS=1 python benchmarks/sweep_trees.py --tree before=/path/to/main \
        --tree after=. [--paths four,slider,hexapod,3rpr,five-bar] [--repeat 5]

One persistent process per tree (mechsing imported from that tree, every path swept once
untimed), then, round by round and path by path, each tree's sweep of the path timed by
the process's CPU time in turn, so that a change of the machine's speed falls on every
tree alike.  Prints each path's median CPU seconds per tree and their ratio to the first
tree's.  The paths are ``sweep.py``'s (density 10, and its five-bar grid); there is no
anchor here (``sweep.py`` gives the ratio to Pinocchio).  A tree named ``NAME-slow`` runs
with ``MECHSING_FAST=0``.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
from pathlib import Path

PATHS = ("four", "slider", "hexapod", "3rpr", "five-bar")

_CHILD = """
import sys, time
import numpy as np
root = sys.argv[1]
sys.path[:0] = [root, root + "/benchmarks"]
import mechsing
from sweep import _mechsing_cases, _spec
from pathlib import Path
ex = Path(root) / "examples"
cs = _mechsing_cases(10)
v = np.linspace(-0.4, 0.4, 41 * 3)
runs = {name: (lambda c=c: mechsing.sweep(ex / c[0], c[1], c[2]))
        for name, c in zip(("four", "slider", "hexapod", "3rpr"), cs)}
runs["five-bar"] = lambda: mechsing.sweep(ex / "five_bar.yaml", [_spec("A1", v), _spec("A2", v)])
for line in sys.stdin:
    names = line.split()
    if names[0] == "warm":
        for n in names[1:]:
            runs[n]()
        print("ok", flush=True)
        continue
    t0 = time.process_time()
    runs[names[0]]()
    print(time.process_time() - t0, flush=True)
"""


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--tree", action="append", required=True, help="NAME=PATH (in order)")
    ap.add_argument("--paths", default=",".join(PATHS))
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    paths = args.paths.split(",")
    procs = []
    for spec in args.tree:
        name, path = spec.split("=", 1)
        root = str(Path(path).resolve())
        env = {**os.environ, "PYTHONPATH": root, "OPENBLAS_NUM_THREADS": "1"}
        if name.endswith("-slow"):
            env["MECHSING_FAST"] = "0"
        p = subprocess.Popen(
            [sys.executable, "-c", _CHILD, root],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
            env=env,
        )
        procs.append((name, p))

    def ask(p: subprocess.Popen, line: str) -> str:
        assert p.stdin is not None and p.stdout is not None
        p.stdin.write(line + "\n")
        p.stdin.flush()
        return p.stdout.readline()

    for _, p in procs:
        ask(p, "warm " + " ".join(paths))
    times: dict[tuple[str, str], list[float]] = {(n, c): [] for n, _ in procs for c in paths}
    for _ in range(args.repeat):
        for c in paths:
            for name, p in procs:
                times[name, c].append(float(ask(p, c)))
    print(f"median CPU seconds of {args.repeat}, trees timed in turn (ratio to {procs[0][0]})")
    for c in paths:
        first = statistics.median(times[procs[0][0], c])
        cells = []
        for name, _ in procs:
            m = statistics.median(times[name, c])
            cells.append(f"{name} {m:.3f} s ({m / first:.2f})")
        print(f"  {c}: " + ", ".join(cells))
    for _, p in procs:
        assert p.stdin is not None
        p.stdin.close()
        p.wait()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
