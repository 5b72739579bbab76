"""The scanner part of ``benchmarks/scale.py``: float verdicts of 6R and 7R arms.

usage: python benchmarks/_scale_scanner.py [--configs 200000] [--repeat 3]

Arms: the UR5 (``examples/ur5.yaml``) and the Franka Emika Panda (7R, modified DH
of the Franka Control Interface documentation, written here), on random
configurations with 1% near the wrist and 1% at q3 = 0 (for the Panda, 1% near
the alignment of joints 1, 3 and 5).  Pipelines, timed in the same run (median of
``--repeat``, after a warm-up):

- ``mechsing.scan``, compiled screen (the ``fast`` extra: numba), numpy matrices
  and SVD only where the screen cannot certify;
- ``mechsing.scan``, numpy path (the dispatch table ``serial screen`` without its
  form ``compiled``);
- Pinocchio's Jacobians (``computeJointJacobians``, one call per configuration,
  the only way its Python API offers), moved to mechsing's commensurate frame,
  then numpy's batched SVD everywhere and the two-threshold rule;
- the same Jacobians with the same determinant screen as mechsing (numpy's batched
  det of J or of J J^T, the same bound and factor) and the SVD only where it
  cannot certify: the best pipeline a user could write around Pinocchio.

The verdicts of every pipeline are compared with the compiled scan's.  The last
paragraph is the memory-bandwidth bound: the bytes a configuration must move (its
joint values in, 18 bytes of result out), over the bandwidth of a large numpy copy
measured here.
"""

from __future__ import annotations

import argparse
import math
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))

PANDA = """mechanism: panda
units: {length: m, angle: deg}
dh:
  convention: modified
  rows:
    - {theta: 0, d: 0.333, a: 0, alpha: 0}
    - {theta: 0, d: 0, a: 0, alpha: -90}
    - {theta: 0, d: 0.316, a: 0, alpha: 90}
    - {theta: 0, d: 0, a: 0.0825, alpha: 90}
    - {theta: 0, d: 0.384, a: -0.0825, alpha: -90}
    - {theta: 0, d: 0, a: 0, alpha: 90}
    - {theta: 0, d: 0, a: 0.088, alpha: 90}
output: {body: L7}
configurations:
  reference: {}
"""


def _median(fn, repeat: int) -> float:
    fn()
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return float(np.median(times))


def _configurations(n: int, joints: int, special: list[tuple[int, float | None]]) -> np.ndarray:
    rng = np.random.default_rng(0)
    Q = rng.uniform(-math.pi, math.pi, size=(n, joints))
    block = n // 100
    for i, (col, value) in enumerate(special):
        rows = slice(i * block, (i + 1) * block)
        Q[rows, col] = 10.0 ** -rng.integers(0, 16, size=block) if value is None else value
    return Q


def _bandwidth() -> float:
    """Bytes per second of a 256 MiB numpy copy (read + write), best of 5."""
    a = np.ones(32 * 1024 * 1024)
    b = np.empty_like(a)
    best = math.inf
    for _ in range(5):
        t = time.perf_counter()
        np.copyto(b, a)
        best = min(best, time.perf_counter() - t)
    return 2 * a.nbytes / best


def _arm(name: str, mech, Q: np.ndarray, repeat: int, rows: list[str]) -> dict:
    from mechsing.numeric import SCAN_ROUNDING_FACTOR, SCAN_SCREEN_FACTOR, dispatch, scale_screws
    from mechsing.sweeps.scan import ChainScanner

    sc = ChainScanner(mech)
    sc.generic_rank  # noqa: B018 -- once, outside the timings
    n = Q.shape[0]
    res = sc.scan(Q)
    t_compiled = _median(lambda: sc.scan(Q), repeat) if sc.compiled else math.nan
    with dispatch.table("serial screen").disabled("compiled"):
        t_numpy = _median(lambda: sc.scan(Q), repeat)
        res_numpy = sc.scan(Q)
    out = {"n": n, "compiled": t_compiled, "numpy": t_numpy}
    diff_numpy = int(np.count_nonzero(res_numpy.rank != res.rank))
    try:
        import pinocchio as pin
    except ImportError:
        pin = None
    line = f"| {name} | mechsing.scan, compiled screen | {_rate(n, t_compiled)} | 1.00 | - |"
    rows.append(line)
    rows.append(
        f"| {name} | mechsing.scan, numpy | {_rate(n, t_numpy)} | "
        f"{t_compiled / t_numpy:.2f} | {diff_numpy} |"
    )
    if pin is None:
        rows.append(f"| {name} | Pinocchio pipelines | skipped: `pip install pin` | | |")
        return out
    from speed_accuracy import _decide_svd, _pin_model

    pm = _pin_model(mech, sc)
    data = pm.createData()
    k = pm.nv
    swap = np.r_[3:6, 0:3]
    m = min(6, k)
    tau_hi = sc.tolerances.tau_hi

    def jacobians() -> np.ndarray:
        J = np.empty((n, 6, k))
        for i in range(n):
            J[i] = pin.computeJointJacobians(pm, data, Q[i])
        return scale_screws(J[:, swap, :], sc.length_scale, sc.centroid, sc.length_columns)

    def svd_everywhere() -> np.ndarray:
        return _decide_svd(jacobians())

    def screened() -> np.ndarray:
        J = jacobians()
        F2 = np.einsum("nij,nij->n", J, J)
        if k == 6:
            d = np.abs(np.linalg.det(J))
            err = SCAN_ROUNDING_FACTOR * m * np.finfo(float).eps
        else:
            d = np.sqrt(np.maximum(np.linalg.det(J @ np.swapaxes(J, 1, 2)), 0.0))
            err = math.sqrt(SCAN_ROUNDING_FACTOR * m * np.finfo(float).eps)
        with np.errstate(divide="ignore", invalid="ignore"):
            lb = np.where(F2 > 0, d / (F2 / (m - 1)) ** ((m - 1) / 2) / np.sqrt(F2), 0.0)
        ok = lb - err >= SCAN_SCREEN_FACTOR * tau_hi
        rank = np.full(n, m, dtype=np.int64)
        if np.any(~ok):
            rank[~ok] = _decide_svd(J[~ok])
        return rank

    t_svd = _median(svd_everywhere, repeat)
    t_screen = _median(screened, repeat)
    diff_svd = int(np.count_nonzero(svd_everywhere() != res.rank))
    diff_screen = int(np.count_nonzero(screened() != res.rank))
    out.update(pin_svd=t_svd, pin_screen=t_screen)
    rows.append(
        f"| {name} | Pinocchio {pin.__version__} Jacobians + SVD everywhere | {_rate(n, t_svd)} | "
        f"{t_compiled / t_svd:.2f} | {diff_svd} |"
    )
    rows.append(
        f"| {name} | Pinocchio Jacobians + the same screen + SVD where undecided | "
        f"{_rate(n, t_screen)} | {t_compiled / t_screen:.2f} | {diff_screen} |"
    )
    return out


def _rate(n: int, t: float) -> str:
    return "-" if math.isnan(t) else f"{n / t:,.0f}"


def part_scanner(configs: int, repeat: int) -> str:
    """The scanner table (Markdown) and the bandwidth paragraph."""
    import mechsing

    rows = [
        "| arm | pipeline | configurations/s | time relative to the compiled scan | verdicts differing |",
        "|---|---|---|---|---|",
    ]
    ur5 = mechsing.load(ROOT / "examples" / "ur5.yaml")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "panda.yaml"
        path.write_text(PANDA)
        panda = mechsing.load(path)
    results = {
        "UR5 (6R)": _arm(
            "UR5 (6R)", ur5, _configurations(configs, 6, [(4, None), (2, 0.0)]), repeat, rows
        ),
        "Panda (7R)": _arm(
            "Panda (7R)", panda, _configurations(configs, 7, [(1, None), (3, 0.0)]), repeat, rows
        ),
    }
    bw = _bandwidth()
    lines = ["\n".join(rows), ""]
    ratios = []
    for name, r in results.items():
        if "pin_screen" in r:
            ratios.append(
                f"{name}: {r['pin_screen'] / r['compiled']:.2f}x the screened Pinocchio pipeline, "
                f"{r['pin_svd'] / r['compiled']:.2f}x the SVD one"
            )
    if ratios:
        lines.append("Throughput of the compiled scan: " + "; ".join(ratios) + ".")
    for name, r in results.items():
        joints = 6 if "6R" in name else 7
        moved = 8 * joints + 18
        bound = bw / moved
        rate = r["n"] / r["compiled"] if not math.isnan(r["compiled"]) else r["n"] / r["numpy"]
        lines.append(
            f"{name}: {moved} bytes per configuration (its {joints} joint values in, rank, "
            f"screened flag, ratio and bound out); at the measured copy bandwidth of "
            f"{bw / 1e9:.1f} GB/s the bound is {bound:,.0f} configurations/s; the scan reaches "
            f"{rate:,.0f}/s, {bound / rate:.0f}x below it: the work is compute-bound (the "
            f"product of exponentials, sines and cosines and the determinant stay in registers)."
        )
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--configs", type=int, default=200_000)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    print(part_scanner(args.configs, args.repeat))
    return 0


if __name__ == "__main__":
    sys.exit(main())
