"""The size part of ``benchmarks/scale.py``: one configuration of a big mechanism, in float.

usage: python benchmarks/_scale_size.py [--quick] [--repeat 3]

Three families, each from about 100 to about 1,000 bodies, written as mechanism
files in a temporary folder:

- ``ladder``: planar parallelogram loops stacked on rungs (3 bodies and 4 R
  joints per loop; loops share rungs, not joints).  Configurations: the
  reference, and ``flat``: the middle loop folded flat (its verticals turned by
  -90 deg, a change point: the loop loses rank and two branches cross), given
  with every joint's value (``flat``) or with only that loop's four values and
  the rest solved by continuation (``flat-solved``).
- ``bennett``: Bennett linkages chained body to body (link 2 of one is the base
  of the next; the data of ``examples/bennett.yaml`` moved up by 2 m per loop).
- ``six-bar``: planar Watt six-bars (two loops sharing two joints) chained
  coupler to base: loops coupled in pairs.

Each analysis runs in a child process, which reports its time (reading the
file and the analysis; not the interpreter's start nor mechsing's import) and
its peak resident memory (wall and CPU seconds: under load the CPU seconds compare).  The
growth exponent is the least-squares slope of log(CPU seconds) against
log(bodies) over each family's sizes.
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

_CHILD = """
import json, resource, sys, time
import mechsing
import mechsing.analysis
t, c0 = time.perf_counter(), time.process_time()
res = mechsing.analyze(sys.argv[1], configs=[sys.argv[2]], precision="float")
dt, cpu = time.perf_counter() - t, time.process_time() - c0
c = res.to_json()["configurations"][0]
kinds = sorted({s["class"] for s in c.get("singularities", [])})
mob = c.get("mobility", {})
print(json.dumps({"seconds": dt, "cpu": cpu, "rss": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss,
                  "classes": kinds, "finite": mob.get("finite"),
                  "instantaneous": mob.get("instantaneous"), "error": c.get("error")}))
"""


def ladder(loops: int) -> str:
    bodies = ["ground"]
    joints = []
    prev = "ground"
    for k in range(1, loops + 1):
        left, right, rung = f"left{k}", f"right{k}", f"rung{k}"
        bodies += [left, right, rung]
        for name, a, b, x, y in (
            ("A", prev, left, 0, k - 1),
            ("B", prev, right, 1, k - 1),
            ("C", left, rung, 0, k),
            ("D", right, rung, 1, k),
        ):
            joints.append(
                f"  - {{name: {name}{k}, type: R, between: [{a}, {b}], axis: [0, 0, 1], "
                f"point: [{x}, {y}, 0]}}"
            )
        prev = rung
    mid = (loops + 1) // 2
    fold = {f"A{mid}": -90, f"B{mid}": -90, f"C{mid}": 90, f"D{mid}": 90}
    every = {f"{x}{k}": 0 for k in range(1, loops + 1) for x in "ABCD"} | fold
    return (
        f"mechanism: ladder-{loops}\nunits: {{angle: deg}}\n"
        f"bodies: [{', '.join(bodies)}]\njoints:\n" + "\n".join(joints) + "\n"
        "configurations:\n  reference: {}\n"
        f"  flat: {_mapping(every)}\n  flat-solved: {_mapping(fold)}\n"
    )


_BENNETT = (
    ("J1", (0, 0, 1), ("0", "0", "0")),
    ("J2", ("12/25", "-9/25", "4/5"), ("3/5", "4/5", "0")),
    ("J3", ("-156/701", "429/701", "532/701"), ("-2353/3505", "-364/3505", "1248/3505")),
    ("J4", (0, "24/25", "7/25"), ("-8/5", "0", "0")),
)


def bennett(loops: int) -> str:
    bodies = ["ground"]
    joints = []
    base = "ground"
    for k in range(1, loops + 1):
        names = [base, f"l1_{k}", f"l2_{k}", f"l3_{k}"]
        bodies += names[1:]
        for i, (name, axis, point) in enumerate(_BENNETT):
            a, b = names[i], names[(i + 1) % 4]
            p = [point[0], point[1], f"{point[2]} + {2 * k}"]
            joints.append(
                f"  - {{name: {name}_{k}, type: R, between: [{a}, {b}], "
                f"axis: {_list(axis)}, point: {_list(p)}}}"
            )
        base = names[2]
    return (
        f"mechanism: bennett-chain-{loops}\nbodies: [{', '.join(bodies)}]\njoints:\n"
        + "\n".join(joints)
        + "\nconfigurations:\n  reference: {}\n"
    )


#: a Watt six-bar: (joint, body a, body b, x, y) with the base body "B" and the
#: coupler "C" that carries the next six-bar
_SIX_BAR = (
    ("A", "B", "L", 0.0, 0.0),
    ("Bj", "L", "C", 0.5, 2.0),
    ("Cj", "C", "R", 3.2, 2.2),
    ("D", "R", "B", 3.0, 0.0),
    ("E", "C", "M", 1.8, 2.6),
    ("G", "M", "N", 4.5, 1.6),
    ("F", "N", "B", 5.5, 0.3),
)


def six_bar(units: int) -> str:
    bodies = ["ground"]
    joints = []
    base = "ground"
    for k in range(1, units + 1):
        local = {"B": base, **{x: f"{x}{k}" for x in ("L", "C", "R", "M", "N")}}
        bodies += [local[x] for x in ("L", "C", "R", "M", "N")]
        ox, oy = 0.37 * k, 2.9 * k
        for name, a, b, x, y in _SIX_BAR:
            joints.append(
                f"  - {{name: {name}{k}, type: R, between: [{local[a]}, {local[b]}], "
                f"axis: [0, 0, 1], point: [{x + ox:.2f}, {y + oy:.2f}, 0]}}"
            )
        base = local["C"]
    return (
        f"mechanism: six-bar-chain-{units}\nbodies: [{', '.join(bodies)}]\njoints:\n"
        + "\n".join(joints)
        + "\nconfigurations:\n  reference: {}\n"
    )


def _list(xs: tuple | list) -> str:
    return "[" + ", ".join(f'"{x}"' if isinstance(x, str) else str(x) for x in xs) + "]"


def _mapping(d: dict) -> str:
    return "{" + ", ".join(f"{k}: {v}" for k, v in d.items()) + "}"


#: family -> (file writer, loop or unit counts giving about 100 ... 1,000 bodies, configurations)
FAMILIES = {
    "ladder": (ladder, (33, 66, 133, 333), ("reference", "flat", "flat-solved")),
    "bennett": (bennett, (33, 66, 133, 333), ("reference",)),
    "six-bar": (six_bar, (20, 40, 80, 200), ("reference",)),
}


def _run(path: Path, config: str) -> dict:
    out = subprocess.run(
        [sys.executable, "-c", _CHILD, str(path), config],
        capture_output=True,
        text=True,
        check=True,
        cwd=ROOT,
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def _exponent(xs: list[float], ys: list[float]) -> float:
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    mx, my = statistics.fmean(lx), statistics.fmean(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly, strict=True)) / sum(
        (a - mx) ** 2 for a in lx
    )


def part_size(repeat: int, quick: bool) -> str:
    """The size table (Markdown): bodies, loops, seconds (median), peak memory, verdict."""
    lines = [
        "| family | configuration | bodies | loops | seconds | CPU s | peak MiB | mobility (finite / instantaneous) | classes |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    fits = []
    with tempfile.TemporaryDirectory() as tmp:
        for family, (write, sizes, configs) in FAMILIES.items():
            if quick:
                sizes = sizes[:2]
            for config in configs:
                xs, ys = [], []
                for size in sizes:
                    path = Path(tmp) / f"{family}-{size}.yaml"
                    path.write_text(write(size))
                    per = 5 if family == "six-bar" else 3
                    n_bodies = 1 + per * size
                    n_loops = size if family != "six-bar" else 2 * size
                    runs = [_run(path, config) for _ in range(repeat)]
                    sec = statistics.median(r["seconds"] for r in runs)
                    cpu = statistics.median(r["cpu"] for r in runs)
                    rss = max(r["rss"] for r in runs) / 1024
                    r = runs[0]
                    verdict = r["error"] or ", ".join(r["classes"]) or "regular"
                    lines.append(
                        f"| {family} | {config} | {n_bodies} | {n_loops} | {sec:.2f} | {cpu:.2f} | {rss:.0f} "
                        f"| {r['finite']} / {r['instantaneous']} | {verdict} |"
                    )
                    xs.append(n_bodies)
                    ys.append(cpu)
                    print(lines[-1], file=sys.stderr, flush=True)
                if len(xs) >= 2:
                    fits.append(f"{family} {config}: {_exponent(xs, ys):.2f}")
    return (
        "\n".join(lines) + "\n\nFitted growth exponent (CPU seconds ~ bodies^k): " + "; ".join(fits)
    )


_SWEEP_CHILD = """
import sys, time
import mechsing
t = time.perf_counter()
res = mechsing.sweep(sys.argv[1], vary=["A1=0:60:0.25"], precision="float")
print(time.perf_counter() - t)
"""


def part_sweep(repeat: int, quick: bool) -> str:
    """Sweeps as the mechanism grows: a ladder's first crank over 0 ... 60 deg (241
    points, every A joint an input), time per point against the number of loops, and
    the issue's bound 2 x (one loop's time per point) x (loops ratio)."""
    sizes = (1, 3, 10, 30) if quick else (1, 3, 10, 30, 100)
    lines = [
        "| loops | seconds | ms per point | bound (ms per point) | within |",
        "|---|---|---|---|---|",
    ]
    base = None
    with tempfile.TemporaryDirectory() as tmp:
        for n in sizes:
            inputs = ", ".join(f"A{k}" for k in range(1, n + 1))
            text = ladder(n).replace("configurations:", f"inputs: [{inputs}]\nconfigurations:")
            path = Path(tmp) / f"sweep-{n}.yaml"
            path.write_text(text)
            times = []
            for _ in range(repeat):
                out = subprocess.run(
                    [sys.executable, "-c", _SWEEP_CHILD, str(path)],
                    capture_output=True,
                    text=True,
                    check=True,
                    cwd=ROOT,
                )
                times.append(float(out.stdout.strip().splitlines()[-1]))
            sec = statistics.median(times)
            per = 1000 * sec / 241
            base = per if base is None else base
            bound = 2 * base * n / sizes[0]
            lines.append(
                f"| {n} | {sec:.2f} | {per:.2f} | {bound:.1f} | {'yes' if per <= bound else 'no'} |"
            )
            print(lines[-1], file=sys.stderr, flush=True)
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--quick", action="store_true", help="the two smallest sizes only")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    print(part_size(args.repeat, args.quick))
    print()
    print(part_sweep(args.repeat, args.quick))
    return 0


if __name__ == "__main__":
    sys.exit(main())
