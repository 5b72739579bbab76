"""``scale.py --part exact``'s measurement in two source trees, case by case in turn (exact
mode against float before and after a change, on the same loaded machine).

usage:
    python benchmarks/exact_trees.py OLD_TREE NEW_TREE [--cases NAME ...] [--repeat 3]
                                     [--extra PATH]

For each case (``_scale_exact.cases``: the bundled examples, then the random instances;
``--cases`` keeps those named), each tree's ``benchmarks/_scale_exact.py`` ``measure`` runs
in a child process of its own (``PYTHONPATH`` that tree, and ``--extra`` after it: a
directory holding gmpy2 or python-flint, e.g. from ``pip install --target``), OLD then NEW:
float and exact alternating on the configurations exact mode analyses, medians of
``--repeat``, CPU seconds, sympy's cache cleared before each run.  Prints one Markdown
row per case: each tree's float s, exact s, exact / float, and exact NEW / OLD.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent

_MEASURE = r"""
import json, sys
from pathlib import Path
import _scale_exact as se
row = se.measure(Path(sys.argv[1]), int(sys.argv[2]), se.TIME_LIMIT)
print(json.dumps({k: row[k] for k in ("degree", "exact", "float_s", "exact_s", "disagree")}))
"""


def _measure(tree: Path, path: Path, repeat: int, extra: str | None) -> dict:
    paths = [str(tree), str(tree / "benchmarks"), *([extra] if extra else [])]
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(paths), "OPENBLAS_NUM_THREADS": "1"}
    run = subprocess.run(
        [sys.executable, "-c", _MEASURE, str(path), str(repeat)],
        env=env,
        cwd=tree,
        capture_output=True,
        text=True,
        check=True,
    )
    return json.loads(run.stdout.strip().splitlines()[-1])


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("old", type=Path)
    ap.add_argument("new", type=Path)
    ap.add_argument("--cases", nargs="*", default=None)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--extra", default=None)
    args = ap.parse_args(argv)
    sys.path.insert(0, str(HERE))
    from _scale_exact import cases

    print(
        "| case | field degree | configurations | old: float s | exact s | exact / float "
        "| new: float s | exact s | exact / float | exact new / old | verdicts agree |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for name, path in cases(Path(tmp), False):
            if args.cases and name not in args.cases:
                continue
            old = _measure(args.old.resolve(), path, args.repeat, args.extra)
            new = _measure(args.new.resolve(), path, args.repeat, args.extra)
            if not new["exact"]:
                continue
            agree = "yes" if not (old["disagree"] or new["disagree"]) else "no"
            print(
                f"| {name} | {new['degree']} | {new['exact']} "
                f"| {old['float_s']:.3f} | {old['exact_s']:.3f} "
                f"| {old['exact_s'] / old['float_s']:.1f} "
                f"| {new['float_s']:.3f} | {new['exact_s']:.3f} "
                f"| {new['exact_s'] / new['float_s']:.1f} "
                f"| {new['exact_s'] / old['exact_s']:.2f} | {agree} |",
                flush=True,
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
