"""The speed/accuracy trade, measured (issue 7).

usage: python benchmarks/speed_accuracy.py [--quick] [--part families|throughput|memory|all]
                                           [--repeat 5] [--configs 100000] [--big 10000000]

1. families: configurations at distances 10^-k (k = 1 ... 14) from four known
   singular configurations -- a change-point four-bar fold (c-space), a UR5
   wrist (serial), a 3-RPR with concurrent legs (output, Type II) and a 3-UPU
   with coplanar constraint couples (constraint) -- analysed in each precision
   mode.  The truth at every distance is "regular".  Joint values are written with
   110 digits; float reads their float64 rounding, mp:N their N-digit one.  Per mode: the rate of
   correct verdicts, the relative error of the smallest singular value of the
   deciding test (against mechsing at mp:100 on the same file), the median
   time per configuration and the verdict at each k (R regular, S singular,
   U undecided, E error; for auto, the k it re-decided at mp:50); per family,
   auto's time over float's far from the singularity (k <= 4).  The four
   families are built from exact geometry (tests/families.py: closed forms,
   evaluated here at 130 digits).
2. throughput: float verdicts of a 6R arm (UR5) on --configs random
   configurations: mechsing.scan (array Jacobians, determinant screen, SVD only
   near singular), the same with the SVD everywhere, and -- when the `pin`
   package is installed -- Pinocchio's Jacobians (one call per configuration)
   followed by numpy's batched SVD and the same thresholds, with the number of
   verdicts on which they differ.
3. memory: --big configurations generated and scanned chunk by chunk in a
   child process; its peak resident memory (ru_maxrss) and time.

Medians over --repeat runs, ratios from the same run (the machine is noisy).
"""

from __future__ import annotations

import argparse
import math
import os
import resource
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from _timing import median_time, timed_median  # noqa: E402

import mechsing  # noqa: E402
from mechsing.numeric import Precision, rank_bounds, scale_screws  # noqa: E402
from mechsing.sweeps.scan import ChainScanner  # noqa: E402

MODES = ("float", "mp:30", "mp:50", "auto", "exact")
#: configurations 10^-k from singular with k up to this are "far from singular" (timing of auto)
FAR_K = 4


# =============================================================================== 1. families


def _families(ks: list[int]):
    """(name, deciding test, yaml text with one configuration per k, exact data?)."""
    import mpmath

    from tests import families as fam

    rng = np.random.default_rng(2026)
    out = []
    # 110 significant digits (computed at 130), so that the mp:100 reference closes them too
    mpmath.mp.dps = 130
    fam.d = lambda x: '"' + mpmath.nstr(mpmath.mpf(x), 110, min_fixed=-200, max_fixed=200) + '"'

    fb = fam.changepoint_fourbar(rng, 0)
    configs = {f"k{k}": fb.pushed_config(mpmath.mpf(10) ** -k, 1) for k in ks}
    out.append(("four-bar change point", "closure", fb.yaml(configs), False))

    ur5 = (ROOT / "examples" / "ur5.yaml").read_text().split("configurations:")[0]
    lines = [ur5 + "configurations:"]
    for k in ks:
        lines.append(
            f'  k{k}: {{J1: 0, J2: "-pi/4", J3: "pi/2", J4: "-pi/4", J5: "atan(1/10**{k})", J6: 0}}'
        )
    out.append(("UR5 wrist", "output chain", "\n".join(lines) + "\n", True))

    rpr = fam.rpr_concurrent(rng)
    configs = {f"k{k}": rpr.moved(mpmath.mpf(10) ** -k, (0, 0)) for k in ks}
    # legs concurrent: with the inputs locked the platform turns (output); the rank that
    # drops is that of the input rates over the motions, E N (impossible-input)
    out.append(("3-RPR concurrent legs", "impossible-input", rpr.yaml(configs), False))

    ts = fam.tsai_coplanar(rng)
    m = [mpmath.mpf(x.numerator) / x.denominator for x in ts.m]
    nm = mpmath.sqrt(sum(x * x for x in m))
    configs = {f"k{k}": ts.translated([x / nm * mpmath.mpf(10) ** -k for x in m]) for k in ks}
    out.append(("3-UPU coplanar couples", "constraint", ts.yaml(configs), False))
    return out


def _decision(c: dict, test: str) -> dict | None:
    for d in c.get("decisions", []):
        if d["test"] == test:
            return d
    return None


def _sigma_at(d: dict | None, g: int | None) -> float | None:
    """sigma_g / sigma_max of a decision, g the rank at regular configurations (from the
    mp:100 reference): the smallest kept value when the decision kept g or more, else
    the largest dropped one (which is sigma_g then)."""
    if d is None or g is None:
        return None
    m = d["margin"]
    if not m.get("sigma_max"):
        return None
    r = d["rank"] if d["rank"] is not None else d["rank_bounds"][0]
    s = m["kept"] if r >= g else m["dropped"]
    return None if s is None else s / m["sigma_max"]


def families(ks: list[int], repeat: int) -> None:
    print(f"1. families at 10^-k from singular, k = {ks[0]} ... {ks[-1]}; truth: regular")
    print("   correct = decided regular (not singular, not undecided); sigma error against mp:100")
    header = f"   {'family':24s} {'mode':6s} {'correct':>8s} {'first wrong k':>13s} {'max sigma rel. err':>19s} {'median s/config':>16s}  verdicts k = {ks[0]} ... {ks[-1]}"
    print(header)
    with tempfile.TemporaryDirectory() as tmp:
        for name, test, text, exact_ok in _families(ks):
            path = Path(tmp) / "family.yaml"
            path.write_text(text)
            ref, rank100 = {}, {}
            res100 = mechsing.analyze(path, precision="mp:100").to_json()
            for c in res100["configurations"]:
                d = _decision(c, test)
                rank100[c["name"]] = None if d is None else d["rank"]
                ref[c["name"]] = _sigma_at(d, rank100[c["name"]])
            far: dict[str, list[float]] = {}
            for mode in MODES:
                if mode == "exact" and not exact_ok:
                    print(
                        f"   {name:24s} {mode:6s} {'refused (decimal data is not exact data)':>50s}"
                    )
                    continue
                times, correct, first_wrong, errs = [], 0, None, []
                verdicts, redone = [], []
                for k in ks:
                    cfg = f"k{k}"
                    t, res = timed_median(
                        lambda cfg=cfg, mode=mode, path=path: mechsing.analyze(
                            path, configs=[cfg], precision=mode
                        ),
                        repeat,
                    )
                    times.append(t)
                    if k <= FAR_K:
                        far.setdefault(mode, []).append(t)
                    (c,) = res.to_json()["configurations"]
                    undecided = any(f["class"] == "undecided" for f in c["singularities"])
                    ok = c.get("error") is None and not c["singular"] and not undecided
                    if c.get("error"):
                        verdicts.append("E")
                    elif undecided or c["singular"] is None:
                        verdicts.append("U")
                    else:
                        verdicts.append("S" if c["singular"] else "R")
                    if mode == "auto" and c["precision"] != "float":
                        redone.append(k)
                    correct += ok
                    if not ok and first_wrong is None:
                        first_wrong = k
                    s = _sigma_at(_decision(c, test), rank100.get(cfg))
                    if s is not None and ref.get(cfg):
                        errs.append(abs(s - ref[cfg]) / ref[cfg])
                err = f"{max(errs):.1e}" if errs else "n/a"
                fw = "-" if first_wrong is None else str(first_wrong)
                again = f" (mp:50 at k = {','.join(map(str, redone))})" if redone else ""
                print(
                    f"   {name:24s} {mode:6s} {correct:>4d}/{len(ks):<3d} {fw:>13s} {err:>19s} {statistics.median(times):16.3f}  {''.join(verdicts)}{again}"
                )
            if far.get("float") and far.get("auto"):
                ratio = sum(far["auto"]) / sum(far["float"])
                print(f"   {name:24s} auto / float time at k <= {FAR_K}: {ratio:.2f}")


# =============================================================================== 2. throughput


def _pin_model(mech, scanner: ChainScanner):
    """A Pinocchio model of the output chain (revolute and prismatic joints), its joint frames
    at the reference axis points with the ground's orientation, so its q is mechsing's."""
    import pinocchio as pin

    model = pin.Model()
    parent = 0
    prev = np.zeros(3)
    for plan in scanner._chain_joints:
        j = next(j for j in mech.joints if j.name == plan.name)
        axis = np.array([float(x) for x in j.params["axis"]])
        if j.type == "R":
            point = np.array([float(x) for x in j.params["point"]])
            jm = pin.JointModelRevoluteUnaligned(axis / np.linalg.norm(axis))
        elif j.type == "P":
            point = prev
            jm = pin.JointModelPrismaticUnaligned(axis / np.linalg.norm(axis))
        else:
            raise ValueError(f"the Pinocchio comparison covers R and P joints, not {j.type}")
        parent = model.addJoint(parent, jm, pin.SE3(np.eye(3), point - prev), plan.name)
        prev = point
    return model


def _decide_svd(J: np.ndarray) -> np.ndarray:
    """Float two-threshold rule (tau_lo 1e-12, tau_hi 1e-9 of sigma_max) on batched sigmas."""
    s = np.linalg.svd(J, compute_uv=False)
    lo_rank, hi_rank = rank_bounds(s / s[:, :1], Precision("float").tolerances)
    return np.where(lo_rank == hi_rank, lo_rank, -1)


def throughput(n: int, repeat: int) -> None:
    mech = mechsing.load(ROOT / "examples" / "ur5.yaml")
    sc = ChainScanner(mech)
    sc.generic_rank  # noqa: B018 -- once, outside the timings
    rng = np.random.default_rng(0)
    Q = rng.uniform(-math.pi, math.pi, size=(n, 6))
    # a few configurations near and at the published singular sets, so that both paths decide some
    Q[: n // 100, 4] = 10.0 ** -rng.integers(0, 16, size=n // 100)
    Q[n // 100 : n // 50, 2] = 0.0
    print(f"2. float verdicts of UR5 on {n} configurations (1% near the wrist, 1% elbow-singular)")
    t_scan = median_time(lambda: sc.scan(Q), repeat)
    res = sc.scan(Q)
    t_mat = median_time(lambda: sc.matrices(Q[:4096]), repeat) * n / min(n, 4096)
    t_all = median_time(lambda: sc.scan(Q, all_sigma=True), repeat)
    rows = [
        ("mechsing.scan (screen + SVD near singular)", t_scan),
        ("mechsing.scan, SVD everywhere", t_all),
        ("  of which the Jacobians alone", t_mat),
    ]
    pin_line = None
    try:
        import pinocchio as pin
    except ImportError:
        pin = None
    if pin is not None:
        pm = _pin_model(mech, sc)
        data = pm.createData()
        swap = np.r_[3:6, 0:3]

        def pin_jacobians() -> np.ndarray:
            J = np.empty((n, 6, 6))
            for i in range(n):
                J[i] = pin.computeJointJacobians(pm, data, Q[i])
            return J

        def pin_pipeline() -> np.ndarray:
            J = pin_jacobians()[:, swap, :]  # Pinocchio's (v, omega) -> (omega, v)
            Js = scale_screws(J, sc.length_scale, sc.centroid, sc.length_columns)
            return _decide_svd(Js)

        J0 = pin_jacobians()[:200][:, swap, :]
        J0 = scale_screws(J0, sc.length_scale, sc.centroid, sc.length_columns)
        agree = float(np.max(np.abs(J0 - sc.matrices(Q[:200]))))
        t_pin = median_time(pin_pipeline, repeat)
        t_pinj = median_time(pin_jacobians, repeat)
        verdicts = pin_pipeline()
        differ = int(np.count_nonzero(verdicts != res.rank))
        rows += [
            (f"Pinocchio {pin.__version__} Jacobians + numpy batched SVD", t_pin),
            ("  of which the Pinocchio Jacobians (Python loop)", t_pinj),
        ]
        pin_line = (
            f"   verdicts differing from Pinocchio's pipeline: {differ} of {n}; "
            f"largest Jacobian difference {agree:.1e} (commensurate)\n"
            f"   throughput ratio mechsing.scan / Pinocchio pipeline: {t_pin / t_scan:.2f}x"
        )
    for label, t in rows:
        print(f"   {label:58s} {t:8.3f} s  {t / n * 1e6:7.2f} us/config  {n / t:12,.0f} configs/s")
    summary = res.summary()
    print(
        f"   screened {summary['screened']} of {n}; singular {summary['singular']}, "
        f"undecided {summary['undecided']} (generic rank {summary['generic_rank']})"
    )
    if pin_line:
        print(pin_line)
    else:
        print("   (Pinocchio comparison skipped: `pip install pin` to run it)")


# =============================================================================== 3. memory

_CHILD = """
import math, os, resource, sys, time
import numpy as np
import mechsing
from mechsing.sweeps.scan import ChainScanner
n, chunk = int(sys.argv[1]), int(sys.argv[2])
sc = ChainScanner(mechsing.load(sys.argv[3]))
def gen():
    rng = np.random.default_rng(1)
    left = n
    while left:
        k = min(chunk, left)
        yield rng.uniform(-math.pi, math.pi, size=(k, 6))
        left -= k
t0 = time.perf_counter()
res = sc.scan(gen())
t = time.perf_counter() - t0
s = res.summary()
print(t, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, s["singular"], s["undecided"], s["screened"])
"""


def memory(n: int) -> None:
    chunk = 65536
    r = subprocess.run(
        [sys.executable, "-c", _CHILD, str(n), str(chunk), str(ROOT / "examples" / "ur5.yaml")],
        capture_output=True,
        text=True,
        check=True,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )
    t, rss_kb, sing, und, scr = r.stdout.split()
    print(f"3. {n:,} UR5 configurations generated {chunk} at a time and scanned (default chunk)")
    print(
        f"   {float(t):.1f} s ({float(t) / n * 1e6:.2f} us/config), peak resident memory "
        f"{int(rss_kb) / 1024:.0f} MiB; screened {int(scr):,}, singular {sing}, undecided {und}"
    )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument(
        "--quick", action="store_true", help="k = 2, 6, 10, 14; 20 000 and 10^6 configurations"
    )
    ap.add_argument("--part", default="all", choices=["families", "throughput", "memory", "all"])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--configs", type=int, default=None)
    ap.add_argument("--big", type=int, default=None)
    a = ap.parse_args()
    ks = [2, 6, 10, 14] if a.quick else list(range(1, 15))
    n = a.configs or (20000 if a.quick else 100000)
    big = a.big or (10**6 if a.quick else 10**7)
    print(f"mechsing {mechsing.__version__}, numpy {np.__version__}, one BLAS thread")
    if a.part in ("throughput", "all"):
        throughput(n, a.repeat)
    if a.part in ("memory", "all"):
        memory(big)
    if a.part in ("families", "all"):
        families(ks, 1 if a.quick else a.repeat)
    _ = resource  # the child measures its own peak


if __name__ == "__main__":
    main()
