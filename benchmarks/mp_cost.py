"""What mp:50 costs next to float, per configuration.

usage: python benchmarks/mp_cost.py [--repeat 3] [--only NAME ...]

For every bundled example (examples/*.yaml) and for a serial T3-S chain with its
S joint turned by pi/2 about its middle axis (where Euler angles would lock),
the median wall time of ``mechsing.analyze`` over all the file's configurations
in ``float`` and in ``mp:50`` (medians of --repeat runs, measured in one run:
the machine is noisy, compare the ratios), divided by the number of
configurations, and the ratio mp:50 / float.  The target is a ratio below 20.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from _timing import timed_median

from mechsing.analysis import analyze
from mechsing.model import load

ROOT = Path(__file__).resolve().parents[1]

#: a T3 joint then an S joint, the S joint turned by pi/2 about its middle axis (and more)
T3_S_CHAIN = ROOT / "tests" / "data" / "t3_s_chain.yaml"


def cases() -> list[tuple[str, Path]]:
    out = [(p.stem, p) for p in sorted((ROOT / "examples").glob("*.yaml"))]
    out.append(("t3-s chain", T3_S_CHAIN))
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--only", nargs="*", help="case names (file stems, 't3-s chain')")
    args = ap.parse_args()
    print(f"{'case':30s} {'configs':>7s} {'float s/cfg':>12s} {'mp:50 s/cfg':>12s} {'ratio':>7s}")
    worst = 0.0
    for name, path in cases():
        if args.only and name not in args.only:
            continue
        mech = load(path)
        n = len(analyze(mech, None, "float").configurations)  # also warms the caches
        t_f, _ = timed_median(lambda m=mech: analyze(m, None, "float"), args.repeat)
        t_m, res = timed_median(lambda m=mech: analyze(m, None, "mp:50"), args.repeat)
        errors = [c.name for c in res.configurations if c.error is not None]
        ratio = t_m / t_f if t_f > 0 else float("inf")
        worst = max(worst, ratio)
        note = f"  errors: {', '.join(errors)}" if errors else ""
        print(f"{name:30s} {n:7d} {t_f / n:12.4f} {t_m / n:12.4f} {ratio:7.1f}{note}")
    print(f"largest ratio mp:50 / float: {worst:.1f} (target: below 20)")


if __name__ == "__main__":
    main()
