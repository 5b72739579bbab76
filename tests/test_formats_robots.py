"""Optional (an extra, not CI): every URDF of example-robot-data that mechsing can model
loads, and its joint screws equal Pinocchio's joint Jacobians on the same URDF.

Runs when pinocchio and the example-robot-data files are available: the package
``example_robot_data``, or a folder named by the environment variable
MECHSING_EXAMPLE_ROBOT_DATA (e.g. an unpacked example-robot-data wheel).  Pinocchio's
``data.J`` after ``computeJointJacobians`` holds each joint's motion subspace in the world
frame, linear part first (the velocity of the body point at the world origin); mechsing's
current screws are ``(omega, v)`` with the same ``v``: the two agree column for column after
swapping the halves.  URDFs mechsing refuses, or reads with couplings (mimic joints: the analysis
models them as constraints of the closure system, and Pinocchio may drop a mimic joint's
coordinate), are counted, not compared; a traceback or an internal error would fail.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

pin = pytest.importorskip("pinocchio")

CONFIGURATIONS = 1000


def _urdf_files() -> list[Path]:
    roots = []
    if os.environ.get("MECHSING_EXAMPLE_ROBOT_DATA"):
        roots.append(Path(os.environ["MECHSING_EXAMPLE_ROBOT_DATA"]))
    try:
        import example_robot_data  # type: ignore[import-not-found]

        roots.append(Path(example_robot_data.__file__).resolve().parents[1] / "cmeel.prefix")
    except ImportError:
        pass
    files = sorted({p for r in roots if r.is_dir() for p in r.rglob("robots/**/*.urdf")})
    return files


FILES = _urdf_files()
pytestmark = pytest.mark.skipif(not FILES, reason="example-robot-data not available")


def _pin_q(model: object, q: np.ndarray, names: list[str]) -> np.ndarray:
    """Pinocchio's configuration vector for mechsing's joint values (continuous joints are
    (cos, sin) in Pinocchio)."""
    out = pin.neutral(model)
    for name, x in zip(names, q, strict=True):
        jid = model.getJointId(name)
        j = model.joints[jid]
        if j.nq == 1:
            out[j.idx_q] = x
        else:
            out[j.idx_q : j.idx_q + 2] = (np.cos(x), np.sin(x))
    return out


def test_example_robot_data_jacobians_match_pinocchio() -> None:
    from mechsing.kinematics.model import KinematicModel
    from mechsing.model.mechanism import MechanismError
    from mechsing.reader import read_mechanism

    compared, refused, skipped = [], [], []
    rng = np.random.default_rng(16)
    for f in FILES:
        try:
            mech = read_mechanism(f)
        except MechanismError as exc:
            refused.append((f.name, str(exc).split(": ", 2)[-1][:80]))
            continue
        if mech.couplings:  # mimic joints: read and analysed as couplings, not compared here
            refused.append((f.name, f"couplings (mimic) of {len(mech.couplings)} joint(s)"))
            continue
        if any(j.type not in ("R", "P") for j in mech.joints) or not mech.joints:
            skipped.append(f.name)  # floating or planar joints: Pinocchio's coordinates differ
            continue
        model = pin.buildModelFromUrdf(str(f))
        data = model.createData()
        names = [j.name for j in mech.joints]
        if model.nv != len(names) or any(not model.existJointName(n) for n in names):
            skipped.append(f.name)
            continue
        km = KinematicModel(mech)
        cols = [model.joints[model.getJointId(n)].idx_v for n in names]
        worst = 0.0
        for _ in range(CONFIGURATIONS):
            q = rng.uniform(-np.pi, np.pi, len(names))
            ours = np.asarray(km.current_screws(q), dtype=float)
            pin.computeJointJacobians(model, data, _pin_q(model, q, names))
            theirs = np.asarray(data.J)[:, cols]
            theirs = np.vstack([theirs[3:], theirs[:3]])  # (v, omega) -> (omega, v)
            worst = max(worst, float(np.abs(ours - theirs).max()))
        assert worst < 1e-12, (f.name, worst)
        compared.append((f.name, len(names), worst))
    print(
        f"\nexample-robot-data: {len(FILES)} URDF files; {len(compared)} compared with "
        f"Pinocchio at {CONFIGURATIONS} configurations each (worst difference "
        f"{max((w for *_, w in compared), default=0):.2g}); {len(refused)} refused; "
        f"{len(skipped)} with floating/planar joints not compared"
    )
    for name, why in refused:
        print(f"  refused {name}: {why}")
    assert compared
