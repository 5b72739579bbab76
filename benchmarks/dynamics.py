"""Batched inverse dynamics: mechsing's recursive Newton-Euler on twists and wrenches of D
(``mechsing.kinetics.tree.TreeDynamics.inverse`` on all the samples at once) against a
Python loop over ``pinocchio.rnea``, one call per sample: 10,000 random samples (joint
values, rates and accelerations) of the UR5 of ``examples/ur5.urdf``, of a 7-joint arm
(the one of tests/test_dynamics_tree.py: synthetic inertials) and of example-robot-data's
Panda (its URDF with the published inertials; the two finger joints, a prismatic joint and
its mimic, are made fixed in both models: mechsing's dynamics takes no coupled joints; the
row is left out, with a note, when example-robot-data is not installed), with gravity.  Both are
timed in turn, round by round, CPU time, medians; the efforts must agree to 1e-10
relative (checked and printed).

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/dynamics.py [--samples 10000] [--repeat 5]

Needs the ``bench`` extra (Pinocchio).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from _timing import timed_medians_interleaved  # noqa: E402

from mechsing.kinematics import KinematicModel  # noqa: E402
from mechsing.kinetics.tree import TreeDynamics  # noqa: E402
from mechsing.reader import mechanism_from_text  # noqa: E402

GRAVITY = (0.0, 0.0, -9.81)


def arm7() -> str:
    """The 7-joint arm's URDF (as tests/test_dynamics_tree.py writes it)."""
    from tests.test_dynamics_tree import ARM7

    return ARM7


def panda() -> str | None:
    """example-robot-data's Panda URDF with its fingers fixed, or None when the package is
    not installed (the ``bench`` extra installs it)."""
    import re

    from robots import urdfs

    try:
        found = [p for p in urdfs() if p.name == "panda.urdf" and "panda_description" in str(p)]
    except SystemExit:
        return None
    text = found[0].read_text()
    text = re.sub(r'(<joint name="panda_finger_joint[12]" type=)"prismatic"', r'\1"fixed"', text)
    return re.sub(r"<mimic[^>]*/>", "", text)


def run(name: str, text: str, samples: int, repeat: int) -> dict:
    import pinocchio as pin

    td = TreeDynamics(
        KinematicModel(mechanism_from_text(text, path=f"{name}.urdf"), "float"), GRAVITY
    )
    pm = pin.buildModelFromXML(text)
    pm.gravity.linear = np.array(GRAVITY)
    pd = pm.createData()
    names = [jk.name for jk in td.model.joints]
    order = [pm.joints[pm.getJointId(n)].idx_q for n in names]
    rng = np.random.default_rng(2026)
    Q, V, A = (rng.uniform(-np.pi, np.pi, size=(samples, td.n)) for _ in range(3))
    Qp, Vp, Ap = (np.empty_like(X) for X in (Q, V, A))
    for X, Xp in ((Q, Qp), (V, Vp), (A, Ap)):
        Xp[:, order] = X

    def ours() -> np.ndarray:
        return td.inverse(Q, V, A)

    def theirs() -> np.ndarray:
        out = np.empty((samples, td.n))
        for i in range(samples):
            out[i] = pin.rnea(pm, pd, Qp[i], Vp[i], Ap[i])
        return out[:, order]

    (t_ours, tau), (t_pin, tau_pin) = timed_medians_interleaved(
        [ours, theirs], repeat, warmup=1, cpu=True
    )
    err = np.linalg.norm(tau - tau_pin, axis=1) / np.maximum(np.linalg.norm(tau_pin, axis=1), 1.0)
    return {
        "name": name,
        "joints": td.n,
        "samples": samples,
        "mechsing_per_s": samples / t_ours,
        "pinocchio_per_s": samples / t_pin,
        "ratio": t_pin / t_ours,
        "worst_relative": float(err.max()),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, default=10_000)
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    rows = [
        run("ur5", (ROOT / "examples" / "ur5.urdf").read_text(), args.samples, args.repeat),
        run("arm7", arm7(), args.samples, args.repeat),
    ]
    text = panda()
    if text is None:
        print("no Panda row: example-robot-data is not installed (pip install -e '.[bench]')")
    else:
        rows.append(run("panda", text, args.samples, args.repeat))
    print(
        "| arm | joints | samples | mechsing samples/s | pinocchio loop samples/s | ratio | worst relative difference |"
    )
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        print(
            f"| {r['name']} | {r['joints']} | {r['samples']:,} | {r['mechsing_per_s']:,.0f} | "
            f"{r['pinocchio_per_s']:,.0f} | {r['ratio']:.2f} | {r['worst_relative']:.1e} |"
        )
        assert r["worst_relative"] < 1e-10, r


if __name__ == "__main__":
    main()
