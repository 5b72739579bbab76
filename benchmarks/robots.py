"""Every URDF of example-robot-data analysed through the CLI: CPU seconds per robot.

Run from the repository root (the ``bench`` extra installs example-robot-data)::

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/robots.py --timeout 120 \
        --tree before=/path/to/old/checkout --tree after=.

Each robot is analysed by ``python -m mechsing analyze FILE --format json`` in a child process, once per
tree (``NAME=PATH``: the checkout, the child's working folder and ``PYTHONPATH``), the trees in turn robot by
robot, so that a change of the machine's load falls on all of them alike.  The time is the
child's CPU time (user + system, from ``getrusage``), which other processes on a shared
machine do not inflate.  A child still running after ``--timeout`` seconds of wall clock is
stopped and counted as "timeout".  Exit 0 (a verdict, regular or singular) is "analysed"; any
other exit is "refused" with the first line of its message.

Prints, per tree, the table of robots (exit, CPU s, what was said) and the summary: how many
analysed and refused (with the reason), the median and the largest CPU time.  ``--json
OUT`` writes the rows.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import time
from importlib import metadata
from pathlib import Path


def urdfs() -> list[Path]:
    """Every URDF file installed by the example-robot-data package, sorted by name."""
    try:
        files = metadata.files("example-robot-data") or []
    except metadata.PackageNotFoundError:
        sys.exit(
            "robots.py: example-robot-data is not installed: pip install -e '.[bench]' "
            "(or pip install example-robot-data==6.0.0)"
        )
    found = [Path(f.locate()) for f in files if str(f).endswith(".urdf")]
    return sorted(found, key=lambda p: (p.name, str(p)))


def run_one(tree: Path, urdf: Path, timeout: float) -> dict:
    """Analyse ``urdf`` with the mechsing of ``tree``; its exit, CPU seconds, first line."""
    env = dict(os.environ, PYTHONPATH=str(tree), OPENBLAS_NUM_THREADS="1")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.Popen(
        [sys.executable, "-m", "mechsing", "analyze", str(urdf), "--format", "json"],
        env=env,
        cwd=tree,  # python -m puts the working folder first on the path: the tree's own
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    try:
        out, err = proc.communicate(timeout=timeout)
        code: int | str = proc.returncode
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, 9)
        out, err = proc.communicate()
        code = "timeout"
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    said = ""
    if code == 0:
        said = "; ".join(_verdict(c) for c in json.loads(out)["configurations"])
    elif code != "timeout":
        lines = [ln.strip() for ln in (err or out).splitlines() if ln.strip()]
        said = lines[0] if lines else ""
    return {
        "robot": urdf.name,
        "exit": code,
        "cpu_s": round(cpu, 3),
        "wall_s": round(time.perf_counter() - t0, 3),
        "said": said,
    }


def _verdict(c: dict) -> str:
    """A configuration's verdict in a few words: regular, or singular and its classes."""
    if c.get("error"):
        return f"not analysed: {c['error']}"
    if c.get("singular") is None:
        return "undecided"
    if not c["singular"]:
        return "regular"
    return "singular (" + ", ".join(sorted({s["class"] for s in c["singularities"]})) + ")"


def summary(rows: list[dict]) -> str:
    """Analysed/refused counts with the reasons, the median and the largest CPU time."""
    analysed = [r for r in rows if r["exit"] == 0]
    refused = [r for r in rows if r["exit"] != 0]
    cpu = [r["cpu_s"] for r in rows]
    worst = max(rows, key=lambda r: r["cpu_s"])
    lines = [
        f"analysed {len(analysed)}/{len(rows)}, refused {len(refused)}; CPU s median "
        f"{statistics.median(cpu):.2f}, max {worst['cpu_s']:.2f} ({worst['robot']})"
    ]
    lines += [f"  refused {r['robot']} (exit {r['exit']}): {r['said'][:160]}" for r in refused]
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    ap.add_argument("--tree", action="append", default=[], help="NAME=PATH (repeatable)")
    ap.add_argument("--timeout", type=float, default=300.0, help="wall seconds per robot")
    ap.add_argument("--only", action="append", default=[], help="robot file names to run")
    ap.add_argument("--json", help="write the rows to this file")
    args = ap.parse_args()
    trees = [t.split("=", 1) for t in (args.tree or ["this=."])]
    files = [p for p in urdfs() if not args.only or p.name in args.only]
    rows: dict[str, list[dict]] = {name: [] for name, _ in trees}
    for urdf in files:
        for name, path in trees:
            row = run_one(Path(path).resolve(), urdf, args.timeout)
            rows[name].append(row)
            print(
                f"{name:8} {row['robot']:38} exit {row['exit']!s:7} {row['cpu_s']:8.2f} s  "
                f"{row['said'][:90]}",
                flush=True,
            )
    for name, _ in trees:
        print(f"\n{name}: {summary(rows[name])}")
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
