"""Batched exp/log throughput and accuracy at the extremes, per precision mode.

usage: python benchmarks/bench_lie.py [--n 100000] [--repeat 7]

Reports medians over --repeat runs (this machine is noisy: compare ratios
measured in one run, never absolute numbers across runs), and the worst
errors of the float path against 50-digit references at angles near 0 and pi
and translations from 1e-9 to 1e9.
"""

from __future__ import annotations

import argparse

import numpy as np
from _timing import median_time

from mechsing import lie
from mechsing.numeric import Precision


def _extreme_twists() -> list[tuple[str, np.ndarray]]:
    u = np.array([1.0, 2.0, 3.0]) / np.sqrt(14)
    d = np.array([0.3, -0.4, 0.5]) / np.linalg.norm([0.3, -0.4, 0.5])
    out = []
    for th in (
        0.0,
        1e-16,
        1e-12,
        1e-8,
        1e-4,
        1.0,
        np.pi - 1e-4,
        np.pi - 1e-8,
        np.pi - 1e-12,
        np.pi,
    ):
        for t in (1e-9, 1.0, 1e9):
            out.append((f"theta={th:.3g} |p|={t:.0e}", np.concatenate([th * u, t * d])))
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=100_000)
    ap.add_argument("--repeat", type=int, default=7)
    args = ap.parse_args()
    rng = np.random.default_rng(0)
    xi = rng.normal(size=(args.n, 6)) * [0.8, 0.8, 0.8, 2, 2, 2]
    g = lie.exp(xi)
    t_exp = median_time(lambda: lie.exp(xi), args.repeat)
    t_log = median_time(lambda: lie.log(g), args.repeat)
    print(
        f"float batched, n={args.n}: exp {t_exp / args.n * 1e9:.0f} ns/element "
        f"({args.n / t_exp:.3g}/s), log {t_log / args.n * 1e9:.0f} ns/element ({args.n / t_log:.3g}/s)"
    )
    one = xi[0]
    t1 = median_time(lambda: lie.exp(one), args.repeat * 20)
    print(f"float single: exp {t1 * 1e6:.1f} us")
    P = Precision("mp", 50)
    with P.context():
        xm = P.asarray([repr(float(v)) for v in one])
        t_mp = median_time(lambda: lie.log(lie.exp(xm)), args.repeat)
    print(
        f"mp:50 single exp+log: {t_mp * 1e3:.2f} ms  (ratio to float single exp: {t_mp / t1:.0f}x)"
    )
    E = Precision("exact")
    xe = E.asarray([0, 0, "1/2", 1, 2, 3])
    t_ex = median_time(lambda: lie.exp(xe), 3)
    print(f"exact single exp (angle 1/2 rad, symbolic sin/cos): {t_ex * 1e3:.1f} ms")
    # accuracy at the extremes against 50 digits
    worst_rt, worst_exp = (0.0, ""), (0.0, "")
    for name, x in _extreme_twists():
        gf = lie.exp(x)
        with P.context():
            gm = lie.exp(P.asarray([repr(float(v)) for v in x]))
            ref = np.array([[float(v) for v in row] for row in gm])
        scale = max(1.0, float(np.linalg.norm(x[3:])))
        e_exp = float(np.max(np.abs(gf - ref))) / scale / np.finfo(float).eps
        e_rt = float(np.max(np.abs(lie.exp(lie.log(gf)) - gf))) / scale / np.finfo(float).eps
        worst_exp = max(worst_exp, (e_exp, name))
        worst_rt = max(worst_rt, (e_rt, name))
    print(
        f"float exp vs mp:50, worst over extremes: {worst_exp[0]:.1f} eps*max(1,|p|) at {worst_exp[1]}"
    )
    print(
        f"float exp(log g) - g, worst over extremes: {worst_rt[0]:.1f} eps*max(1,|p|) at {worst_rt[1]}"
    )


if __name__ == "__main__":
    main()
