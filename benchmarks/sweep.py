"""Sweep benchmark: mechsing's sweeps against the pipeline a user would otherwise write.

For each path (the four-bar's crank turn, the slider-crank between its dead centres, the
6-UPS hexapod's platform turn through its Type II poses, a 3-RPR platform (x, y) grid, a
5R five-bar grid of its two inputs), in one run and one core:

* **mechsing**: :func:`mechsing.sweep` over the same samples, timed whole: the start's
  analysis, the continuation and batched Newton, the float measures at every sample, and
  the located singularities refined and classified by the full analysis (``auto``);
* **anchor**: Pinocchio plus a warm-started Newton projection onto the loop constraints and
  numpy's SVD at each point (``benchmarks/_pinocchio_sweep.py``, the ``bench`` extra),
  which measures but neither locates nor classifies.

Printed per path: points, points/s of each (median of ``--repeat`` runs after one untimed
run of each, which loads what a first call loads once; mechsing and the anchor are timed
in turn, round by round, so that a change of the machine's speed during the run falls on
both), the ratio,
Newton iterations per point of each, and how far the located singularities are from their
closed forms (tests/reference/sweep_truth.py; for the paths of the timing that never
reach a singularity, a second mechsing sweep across one).  ``--million`` also runs
``mechsing sweep`` on a 10^6-point five-bar grid in a child process and reports its time
and peak resident memory.

``--cpu`` times by the process's CPU time instead of the wall clock (both sides: on a
shared machine the others' load then does not count; one BLAS thread, one core).

    OPENBLAS_NUM_THREADS=1 python benchmarks/sweep.py [--repeat 3] [--density 10] [--cpu] [--million]
"""

from __future__ import annotations

import argparse
import math
import os
import resource
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from _pinocchio_sweep import PinocchioAnchor, cases, pin, prepare  # noqa: E402
from _timing import timed_medians_interleaved  # noqa: E402

import mechsing  # noqa: E402
from tests.reference import sweep_truth as truth  # noqa: E402


def _spec(name: str, values: np.ndarray, factor: float = 1.0) -> str:
    """A --vary spec whose samples are ``values`` (evenly spaced), in the file's units."""
    v = np.asarray(values, dtype=float) / factor
    step = (v[-1] - v[0]) / (len(v) - 1)
    return f"{name}={float(v[0])!r}:{float(v[-1] + step / 4)!r}:{float(step)!r}"


def _mechsing_cases(density: int) -> list[tuple[str, list[str], str | None]]:
    """The mechsing sweep of each anchor case (same samples, the file's units)."""
    out = []
    for case in cases(density):
        mech = mechsing.load(ROOT / "examples" / case.file)
        af = float(mech.units.angle_factor)
        if case.held is not None:
            joint = mech.joint(case.held)
            factor = af if joint.units[0] == "rad" else float(mech.units.length_factor)
            out.append((case.file, [_spec(case.held, case.values, factor)], None))
        elif np.ndim(case.positions) == 2:  # the hexapod's turn about z
            rz = case.rotation_vectors[:, 2]
            out.append((case.file, [_spec("pose.rz", rz, af)], None))
        else:  # the 3-RPR (x, y) grid about the reference point
            c = [float(x) for x in mech.output_reference_point()]
            xs = c[0] + case.positions[:, 0, 0]
            ys = c[1] + case.positions[0, :, 1]
            out.append((case.file, [_spec("pose.y", ys), _spec("pose.x", xs)], None))
    return out


def _accuracy(file: str) -> str:
    """Distance of the located singularities from their closed forms, on a sweep that
    crosses them."""
    ex = ROOT / "examples"
    if file == "fourbar.yaml":
        r = mechsing.sweep(ex / file, ["A=0:360:0.5"])
        want = sorted(
            x.value % (2 * math.pi)
            for x in truth.four_bar_output_limits((0, 0), (1, 0), (3, 2), (4, 0))
        )
        got = sorted(p.values[0] for p in r.located)
        return _err("rocker limits", got, want)
    if file == "slider_crank_slider_input.yaml":
        r = mechsing.sweep(ex / file, ["P=-4:4:0.01"])
        dead = truth.slider_crank_dead_centres((0, 0), (0, -1), (3.2, 1.4), (1, 0))
        return _err("dead centres", sorted(p.values[0] for p in r.located), sorted(dead.values()))
    if file == "stewart_octahedral.yaml":
        r = mechsing.sweep(ex / file, ["pose.rz=-1.8:1.8:0.01"])
        got = sorted(p.values[0] for p in r.located if "output" in p.tests)
        return _err("Type II turns", got, [-math.pi / 2, math.pi / 2])
    if file == "planar_3rpr.yaml":
        r = mechsing.sweep(ex / file, ["pose.x=0.4:1.6:0.05", "pose.y=2.4:3.4:0.05"])
        dets = [
            abs(
                float(
                    truth.rpr3_concurrency_det(
                        np.array(p.values[0]), np.array(p.values[1]), np.array(0.0), unit=False
                    )
                )
            )
            for p in r.located
            if "output" in p.tests
        ]
        return f"{len(dets)} Type II points, concurrency det at most {max(dets, default=0):.1e}; {len(r.loci)} locus"
    return ""


def _err(what: str, got: list[float], want: list[float]) -> str:
    if len(got) != len(want):
        return f"{what}: found {len(got)}, expected {len(want)}"
    return f"{what} within {max(abs(a - b) for a, b in zip(got, want, strict=True)):.1e}"


def _five_bar(repeat: int, density: int, cpu: bool = False) -> None:
    """The five-bar grid of its two inputs: mechsing and the anchor's grid of held inputs."""
    v = np.linspace(-0.4, 0.4, 41 * max(1, round(density**0.5)))
    spec = [_spec("A1", v), _spec("A2", v)]

    def run() -> Any:
        return mechsing.sweep(ROOT / "examples" / "five_bar.yaml", spec)

    timed: list[Callable[[], Any]] = [run]
    if pin is not None:
        anchor = PinocchioAnchor(mechsing.load(ROOT / "examples" / "five_bar.yaml"))
        q0 = anchor.approach(pin.neutral(anchor.model), ["A1", "A2"], [v[0], v[0]])
        timed.append(lambda: anchor.grid(["A1", "A2"], v, v, q0))
    # mechsing and the anchor in turn, round by round (the same conditions for both)
    (t, r), *rest = timed_medians_interleaved(timed, repeat, 1, cpu)
    n = r.points()
    mode = truth.FIVE_BAR.reference_mode()
    size = max(truth.FIVE_BAR.lengths()) ** 2
    d1 = [
        abs(float(truth.five_bar_type1_det(np.array(p.values[0]), np.array(p.values[1]), mode)))
        / size**2
        for p in r.located
        if p.kind != "fold" and "input" in p.tests
    ]
    d2 = [
        abs(float(truth.five_bar_type2_det(np.array(p.values[0]), np.array(p.values[1]), mode)))
        / size
        for p in r.located
        if p.kind == "fold"
    ]
    line = f"  five-bar, inputs A1 x A2 {len(v)} x {len(v)} grid: {n} points, mechsing {n / t:,.0f} points/s"
    if rest:
        ta, pa = rest[0]
        line += f", anchor {n / ta:,.0f} points/s, ratio {ta / t:.2f}; anchor Newton {pa.iterations.mean():.2f}/point"
    print(line)
    print(
        f"    located: {len(d1)} Type I points, |det| / size^2 at most {max(d1, default=0):.1e}; "
        f"{len(d2)} folds, Type II |det| / size at most {max(d2, default=0):.1e}; "
        f"{len(r.loci)} loci; Newton {r.newton_iterations / n:.2f}/point (batched)"
    )


def _million() -> None:
    """A 10^6-point grid through the command line, streamed to a CSV file: time and peak
    resident memory of the child process."""
    out = Path("/tmp/mechsing-million.csv")
    cmd = [
        sys.executable,
        "-m",
        "mechsing",
        "sweep",
        str(ROOT / "examples" / "five_bar.yaml"),
        "--vary",
        "A1=-0.6:0.6:0.0012012012012012",
        "--vary",
        "A2=-0.6:0.6:0.0012012012012012",
        "--format",
        "csv",
        "-o",
        str(out),
        "--quiet",
        "--max-classified",
        "50",
    ]
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, env={**os.environ, "PYTHONPATH": str(ROOT)})
    t = time.perf_counter() - t0
    peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    lines = sum(1 for _ in out.open())
    print(
        f"  10^6-point five-bar grid: {lines - 1:,} CSV rows in {t:.0f} s, peak resident {peak:.0f} MB"
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument(
        "--density",
        type=int,
        default=10,
        help="points of each path times this (grids: about as much)",
    )
    parser.add_argument("--million", action="store_true", help="also the 10^6-point grid")
    parser.add_argument(
        "--cpu", action="store_true", help="time by CPU time (a shared machine), not wall time"
    )
    args = parser.parse_args(argv)
    for var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        if os.environ.get(var) != "1":
            print(f"note: {var} is not 1; numpy may use several cores")
    if pin is None:
        print("note: Pinocchio is not installed (pip install 'mechsing[bench]'): mechsing only")
    clock = "CPU time" if args.cpu else "wall time"
    print(f"mechsing {mechsing.__version__} sweeps (auto), median {clock} of {args.repeat}")
    for case, (file, spec, start) in zip(
        cases(args.density), _mechsing_cases(args.density), strict=True
    ):
        timed: list[Callable[[], Any]] = [
            lambda f=file, s=spec, st=start: mechsing.sweep(ROOT / "examples" / f, s, st)
        ]
        if pin is not None:
            timed.append(prepare(case, ROOT)[1])
        # mechsing and the anchor in turn, round by round (the same conditions for both)
        (t, r), *rest = timed_medians_interleaved(timed, args.repeat, 1, args.cpu)
        n = r.points()
        line = f"  {case.name}: {n} points, mechsing {n / t:,.0f} points/s"
        if rest:
            ta, pa = rest[0]
            na = case.points
            line += (
                f", anchor {na / ta:,.0f} points/s, ratio {(n / t) / (na / ta):.2f}; "
                f"Newton per point: mechsing {r.newton_iterations / n:.2f} (batched), "
                f"anchor {pa.iterations.mean():.2f}"
            )
        print(line)
        print(f"    located on a crossing sweep: {_accuracy(file)}")
    _five_bar(args.repeat, args.density, args.cpu)
    if args.million:
        _million()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
