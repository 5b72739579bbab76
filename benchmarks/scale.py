"""Performance at scale: big mechanisms, exact mode against float, the scanner.

usage: python benchmarks/scale.py [--part size|exact|scanner|all] [--quick]
                                  [--repeat 3] [--configs 200000]

- size (``_scale_size.py``): one configuration of ladders of parallelograms,
  chains of Bennett linkages and chains of Watt six-bars from about 100 to
  about 1,000 bodies, in float: seconds and peak memory, the verdict, and the
  fitted growth exponent; and a ladder's sweep, time per point against loops;
- exact (``_scale_exact.py``): exact mode's time over float's on every bundled
  example and on random Bennett, Bricard and Stewart instances, against the
  degree of the number field their data live in, with the verdicts compared;
- scanner (``_scale_scanner.py``): ``mechsing.scan`` on 6R and 7R arms against
  Pinocchio's Jacobians followed by an SVD everywhere, and by the same
  determinant screen with an SVD only where it cannot decide; and the
  memory-bandwidth bound of the computation.

Run with one BLAS thread (``OPENBLAS_NUM_THREADS=1``); medians over
``--repeat`` runs, ratios from the same run.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--part", choices=("size", "exact", "scanner", "all"), default="all")
    ap.add_argument("--quick", action="store_true", help="small sizes and few instances")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--configs", type=int, default=200_000, help="scanner configurations")
    args = ap.parse_args(argv)
    parts = ("size", "exact", "scanner") if args.part == "all" else (args.part,)
    for part in parts:
        if part == "size":
            from _scale_size import part_size, part_sweep

            print("## Size\n\n" + part_size(args.repeat, args.quick) + "\n", flush=True)
            print(
                "## Sweeps as loops are added\n\n" + part_sweep(args.repeat, args.quick) + "\n",
                flush=True,
            )
        elif part == "exact":
            from _scale_exact import part_exact

            print(
                "## Exact mode against float\n\n" + part_exact(args.repeat, args.quick) + "\n",
                flush=True,
            )
        else:
            from _scale_scanner import part_scanner

            configs = min(args.configs, 20_000) if args.quick else args.configs
            print("## Scanner\n\n" + part_scanner(configs, args.repeat) + "\n", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
