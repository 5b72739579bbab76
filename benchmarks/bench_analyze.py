"""Speed against accuracy of the analysis, per precision mode.

usage: python benchmarks/bench_analyze.py [--repeat 3] [--quick]

1. Median wall time of ``mechsing.analyze`` on every bundled example (auto).
2. The same configuration decided in float, mp:30, mp:50 and exact: time,
   closure rank and verdict.
3. A parallelogram four-bar placed 10^-k rad from its flat (bifurcation)
   configuration, k = 1 ... 14, with the exact joint values of the
   parallelogram branch: which precision still decides "rank 3, regular",
   which says "undecided", which is wrong.

Medians over --repeat runs; compare ratios measured in one run (the machine is
noisy).
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

from _timing import median_time

from mechsing.analysis import analyze
from mechsing.model import load

ROOT = Path(__file__).resolve().parents[1]

PARALLELOGRAM = """mechanism: parallelogram-near-flat
bodies: [ground, crank, coupler, rocker]
joints:
  - {{name: A, type: R, between: [ground, crank],   axis: [0, 0, 1], point: [0, 0, 0]}}
  - {{name: B, type: R, between: [crank, coupler],  axis: [0, 0, 1], point: [1, 0, 0]}}
  - {{name: C, type: R, between: [coupler, rocker], axis: [0, 0, 1], point: [3, 0, 0]}}
  - {{name: D, type: R, between: [rocker, ground],  axis: [0, 0, 1], point: [2, 0, 0]}}
configurations:
{configs}
"""


def examples(repeat: int) -> None:
    print("1. analyze (auto) per example, median wall time")
    for path in sorted((ROOT / "examples").glob("*.yaml")):
        mech = load(path)
        t = median_time(lambda mech=mech: analyze(mech), repeat)
        n = len(analyze(mech).configurations)
        print(f"   {path.stem:28s} {t:7.2f} s  ({n} configurations, {t / n:.2f} s each)")


def modes(repeat: int) -> None:
    print("2. one configuration in each precision mode (fully given exactly)")
    cases = [
        ("fourbar.yaml", "reference"),
        ("bennett.yaml", "theta1-90"),
        ("sarrus.yaml", "stretched"),
    ]
    for file, cfg in cases:
        mech = load(ROOT / "examples" / file)
        base = None
        for mode in ("float", "mp:30", "mp:50", "exact"):
            t = median_time(
                lambda m=mode, me=mech, cf=cfg: analyze(me, [cf], m),
                1 if mode == "exact" else repeat,
            )
            c = analyze(mech, [cfg], mode).to_json()["configurations"][0]
            verdict = (c["closure_rank"]["rank"], sorted(s["class"] for s in c["singularities"]))
            base = base or t
            print(
                f"   {file:14s} {cfg:10s} {mode:6s} {t:8.3f} s  x{t / base:6.1f}  rank {verdict[0]}  {verdict[1]}"
            )


def distance_sweep() -> None:
    print("3. parallelogram 10^-k rad from its flat bifurcation (exact parallelogram branch)")
    ks = list(range(1, 15))
    configs = "\n".join(
        f'  k{k}: {{A: "1e-{k}", B: "-1e-{k}", C: "1e-{k}", D: "-1e-{k}"}}' for k in ks
    )
    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "near.yaml"
        p.write_text(PARALLELOGRAM.format(configs=configs))
        mech = load(p)
        rows = {}
        for mode in ("float", "mp:30", "mp:50", "auto"):
            res = analyze(mech, [f"k{k}" for k in ks], mode).to_json()["configurations"]
            for k, c in zip(ks, res, strict=True):
                if "error" in c:
                    v = "error"
                elif c["closure_rank"]["rank"] is None:
                    v = "undecided"
                elif c["closure_rank"]["rank"] == 3 and not c["singular"]:
                    v = "regular" + ("" if mode != "auto" else f"({c['precision']})")
                else:
                    v = f"WRONG rank {c['closure_rank']['rank']}"
                rows.setdefault(k, []).append(v)
    print(f"   {'k':>3s}  {'float':18s} {'mp:30':18s} {'mp:50':18s} auto")
    for k in ks:
        print(f"   {k:3d}  " + " ".join(f"{v:18s}" for v in rows[k]))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="skip the per-example timings")
    args = ap.parse_args()
    if not args.quick:
        examples(args.repeat)
    modes(args.repeat)
    distance_sweep()


if __name__ == "__main__":
    main()
