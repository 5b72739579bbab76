"""URDF and DH tables: robot arms written from their published DH parameters.

The URDF texts and the DH products come from tests/reference/dh.py (no mechsing code);
the forward kinematics of the converted mechanism (mechsing's product of exponentials,
KinematicModel.poses) must equal the DH product, the DH table in a mechanism file must
give the same joint screws as the URDF, and the singular configurations known for the
arms must be found by `analyze --set`.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from mechsing.kinematics.model import KinematicModel
from mechsing.reader import mechanism_from_text
from tests.cli import run_cli
from tests.reference.dh import (
    IIWA14,
    PANDA,
    PANDA_FLANGE,
    PUMA560,
    UR5,
    dh_product,
    urdf_from_dh,
)

ARMS = {
    "ur5": (UR5, "standard", 0.0),
    "puma560": (PUMA560, "standard", 0.0),
    "iiwa14": (IIWA14, "standard", 0.0),
    "panda": (PANDA, "modified", PANDA_FLANGE),
}


def _dh_yaml(name: str, rows: list, convention: str) -> str:
    body = "\n".join(
        f"    - {{theta: 0, d: {d!r}, a: {a!r}, alpha: {alpha!r}}}" for _, d, a, alpha in rows
    )
    return f"mechanism: {name}\ndh:\n  convention: {convention}\n  rows:\n{body}\n"


@pytest.mark.parametrize("arm", ARMS)
def test_forward_kinematics_matches_the_dh_product(arm: str) -> None:
    rows, convention, flange = ARMS[arm]
    mech = mechanism_from_text(urdf_from_dh(arm, rows, convention, flange), path=f"{arm}.urdf")
    assert mech.output is not None and len(mech.joints) == len(rows)
    km = KinematicModel(mech)
    tool0 = dh_product(rows, np.zeros(len(rows)), convention, flange)
    rng = np.random.default_rng(16)
    for _ in range(50):
        q = rng.uniform(-math.pi, math.pi, len(rows))
        g = km.poses(q)[mech.output.body]
        assert np.abs(g @ tool0 - dh_product(rows, q, convention, flange)).max() < 1e-12


@pytest.mark.parametrize("arm", ARMS)
def test_dh_table_gives_the_same_mechanism_as_the_urdf(arm: str) -> None:
    rows, convention, flange = ARMS[arm]
    from_urdf = mechanism_from_text(urdf_from_dh(arm, rows, convention, flange), path=f"{arm}.urdf")
    from_dh = mechanism_from_text(_dh_yaml(arm, rows, convention), path=f"{arm}.yaml")
    assert [j.name for j in from_dh.joints] == [f"J{i}" for i in range(1, len(rows) + 1)]
    assert from_dh.bodies == tuple(f"L{i}" for i in range(len(rows) + 1))
    a, b = KinematicModel(from_urdf), KinematicModel(from_dh)
    q = np.zeros(len(rows))
    sa, sb = np.asarray(a.current_screws(q), float), np.asarray(b.current_screws(q), float)
    assert sa.shape == sb.shape
    assert np.abs(sa - sb).max() < 1e-12
    # and the same poses away from the reference
    q = np.random.default_rng(5).uniform(-2, 2, len(rows))
    pa, pb = a.poses(q), b.poses(q)
    assert np.abs(pa[from_urdf.output.body] - pb[from_dh.output.body]).max() < 1e-12


def _jacobian_det(rows: list, q: np.ndarray) -> float:
    """det of the 6x6 spatial Jacobian of the DH product by central differences (reference)."""
    h = 1e-6
    cols = []
    t0 = dh_product(rows, q)
    for i in range(6):
        dq = np.zeros(6)
        dq[i] = h
        dt = (dh_product(rows, q + dq) - dh_product(rows, q - dq)) / (2 * h)
        w = dt[:3, :3] @ t0[:3, :3].T
        cols.append(np.r_[w[2, 1], w[0, 2], w[1, 0], dt[:3, 3]])
    return float(np.linalg.det(np.array(cols).T))


def _serial(path: str, sets: dict[str, float]) -> bool:
    argv = ["analyze", path, "--config", "cli", "--format", "json"]
    for k, v in sets.items():
        argv += ["--set", f"{k}={v!r}"]
    r = run_cli(argv)
    assert r.status == 0, r.err
    (conf,) = json.loads(r.out)["configurations"]
    return any(s["class"] == "serial" for s in conf["singularities"])


UR5_CASES = {  # (theta1..theta6, singular?) after the published det J of the UR5
    "regular": ((0, -0.7, 1.1, -0.4, 1.2, 0), False),
    "wrist": ((0, -0.7, 1.1, -0.4, 0.0, 0), True),
    "elbow": ((0, -0.7, 0.0, -0.4, 1.2, 0), True),
    "shoulder": (
        (
            0,
            math.atan(1700 / 1569),
            math.pi / 2,
            -math.atan(1700 / 1569) - math.pi / 2,
            math.pi / 2,
            0,
        ),
        True,
    ),
}
A3, D4 = 0.0203, 0.4318
PUMA_CASES = {  # Corke's PUMA 560: wrist s5 = 0; elbow d4 c3 + a3 s3 = 0 (the wrist centre on the
    # line of the upper arm: the arm stretched), i.e. tan(theta3) = -d4/a3
    "regular": ((0, 0.3, 0.4, 0, 0.9, 0), False),
    "wrist": ((0, 0.3, 0.4, 0, 0.0, 0), True),
    "elbow": ((0, 0.3, -math.atan2(D4, A3), 0, 0.9, 0), True),
}


@pytest.mark.parametrize("case", UR5_CASES)
def test_ur5_singular_configurations_are_found(case: str, tmp_path) -> None:
    q, singular = UR5_CASES[case]
    f = tmp_path / "ur5.urdf"
    f.write_text(urdf_from_dh("ur5", UR5))
    det = _jacobian_det(UR5, np.array(q, float))
    assert (abs(det) < 1e-8) == singular  # the reference agrees with the published det J
    assert _serial(str(f), {f"joint{i + 1}": x for i, x in enumerate(q)}) == singular


@pytest.mark.parametrize("case", ["regular", "wrist", "elbow"])
def test_puma_singular_configurations_are_found(case: str, tmp_path) -> None:
    q, singular = PUMA_CASES[case]
    f = tmp_path / "puma.urdf"
    f.write_text(urdf_from_dh("puma560", PUMA560))
    det = _jacobian_det(PUMA560, np.array(q, float))
    assert (abs(det) < 1e-8) == singular
    assert _serial(str(f), {f"joint{i + 1}": x for i, x in enumerate(q)}) == singular


def test_convert_round_trips(tmp_path) -> None:
    src = tmp_path / "arm.xml"  # recognised by content, not by the extension
    src.write_text(urdf_from_dh("ur5", UR5, limits=3.0))
    out = tmp_path / "arm.yaml"
    r = run_cli(["convert", str(src), "-o", str(out)])
    assert r.status == 0, r.err
    text = out.read_text()
    assert text.startswith("# Converted by mechsing from the URDF file")
    assert "limits:" in text
    direct = run_cli(["analyze", str(src), "--format", "json", "--set", "joint5=0"])
    again = run_cli(["analyze", str(out), "--format", "json", "--set", "joint5=0"])
    assert direct.status == again.status == 0
    assert json.loads(direct.out) == json.loads(again.out)
    assert json.loads(direct.out)["limits"]["joint2"] == [[-3.0, 3.0]]


def test_dh_with_joints_is_refused(tmp_path) -> None:
    f = tmp_path / "bad.yaml"
    f.write_text(
        "dh: {rows: [{theta: 0, d: 1, a: 0, alpha: 0}]}\nbodies: [a, b]\n"
        "joints: [{name: J, type: R, between: [a, b], axis: [0, 0, 1], point: [0, 0, 0]}]\n"
    )
    r = run_cli(["analyze", str(f)])
    assert r.status == 2 and "both dh and" in r.err and "Traceback" not in r.err


def test_dh_degrees_and_expressions(tmp_path) -> None:
    """A table in degrees with an exact expression equals the same table in radians."""
    deg = mechanism_from_text(
        "units: {angle: deg}\ndh: {rows: [{theta: 0, d: 0.3, a: 0.1, alpha: 90},"
        " {theta: 0, d: 0, a: 0.2, alpha: 0}]}\n"
    )
    rad = mechanism_from_text(
        "dh: {rows: [{theta: 0, d: 0.3, a: 0.1, alpha: pi/2},"
        " {theta: 0, d: 0, a: 0.2, alpha: 0}]}\n"
    )
    assert [j.params for j in deg.joints] == [j.params for j in rad.joints]
    # standard DH: joint 2 turns about z1 = Rx(90 deg) z = -y, at the origin of frame 1
    assert tuple(float(c) for c in rad.joints[1].params["axis"]) == (0.0, -1.0, 0.0)
    assert tuple(float(c) for c in rad.joints[1].params["point"]) == (0.1, 0.0, 0.3)


def test_the_bundled_urdf_gives_the_verdicts_of_the_bundled_yaml() -> None:
    """examples/ur5.urdf at the configurations of examples/ur5.yaml (written by hand from the
    same table): same ranks, mobility and singularity classes."""
    from mechsing.model import load

    yaml_mech = load("examples/ur5.yaml")

    def verdict(conf: dict) -> tuple:
        return (
            conf["mobility"],
            sorted((s["class"], s.get("rank"), s.get("corank")) for s in conf["singularities"]),
        )

    for name in ("regular", "wrist", "elbow", "shoulder"):
        want = run_cli(["analyze", "examples/ur5.yaml", "--config", name, "--format", "json"])
        assert want.status == 0, want.err
        argv = ["analyze", "examples/ur5.urdf", "--config", "cli", "--format", "json"]
        for joint, value in yaml_mech.configurations[name].values.items():
            argv += ["--set", f"joint{joint[1:]}={value[0]}"]  # exact values as expressions
        got = run_cli(argv)
        assert got.status == 0, got.err
        (w,) = json.loads(want.out)["configurations"]
        (g,) = json.loads(got.out)["configurations"]
        assert verdict(g) == verdict(w), name
