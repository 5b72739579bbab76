"""mechsing modes on serial arms: every inverse-kinematics solution of a six-joint arm.

The expected postures come from tests/reference/serial_ik_independent.py, which imports no
mechsing code: the UR5's closed-form inverse kinematics from its DH table, and for the
PUMA 560 and a general 6R (no closed form) damped Newton from thousands of random starts on
the product of exponentials of the file's joint axes.  Each target pose is computed by that
independent forward kinematics; the command runs as a user runs it (``python -m mechsing``,
in an empty working directory); each mode's classification is compared with ``mechsing
analyze`` of the same joint values.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from tests.cli import run_cli, run_cli_subprocess
from tests.mechanisms import ROOT
from tests.reference.dh import UR5, dh_product
from tests.reference.expressions import num, vec
from tests.reference.serial_ik_independent import (
    angle_gap,
    numeric_ik,
    poe,
    rotation_vector,
    same_sets,
    ur5_ik,
)

pytest.importorskip("bertini")

EXAMPLES = ROOT / "examples"
JOINTS = [f"J{i}" for i in range(1, 7)]
#: generic, non-singular joint values (sin theta3, sin theta5 and the shoulder factor of the
#: UR5's det J far from 0), and those of the PUMA 560 (its det J factors likewise)
UR5_Q = np.array([0.3, -0.9, 1.2, -0.7, 1.1, 0.4])
PUMA_Q = np.array([0.7, -0.6, 0.4, 1.3, -0.9, 2.1])
#: a pose reproduced to this (rotation entries, and metres for arms of about 1 m)
POSE_TOL = 1e-12
#: the same posture as the independent solver's, joint by joint modulo 2 pi (rad)
ANGLE_TOL = 1e-9


class Arm:
    """A serial arm file read without mechsing: its joints' axes and points (in the file's
    order, ground to output), the output's reference point (the centroid of the points of
    the joints on the output body: docs/closure.md) and the forward kinematics."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.data = yaml.safe_load(path.read_text())
        joints = self.data["joints"]
        assert [j["name"] for j in joints] == JOINTS
        self.fk = poe([vec(j["axis"]) for j in joints], [vec(j["point"]) for j in joints])
        out = self.data["output"]["body"]
        self.point = np.mean([vec(j["point"]) for j in joints if out in j["between"]], axis=0)
        self.L = float(np.mean([np.linalg.norm(vec(j["point"])) for j in joints]))

    def pose(self, q: np.ndarray) -> np.ndarray:
        return self.fk(np.asarray(q, float)[None])[0]

    def values(self, config: str) -> np.ndarray:
        cfg = self.data["configurations"][config]
        return np.array([num(cfg.get(n, 0)) for n in JOINTS])


def _text(x: float) -> str:
    return repr(float(x))


def _with(path: Path, tmp: Path, name: str, entry: str) -> Path:
    """A copy of an example with one configuration added (its last key: configurations)."""
    text = path.read_text()
    assert text.rstrip().splitlines()[-1].startswith("  "), "configurations come last"
    out = tmp / path.name
    out.write_text(text.rstrip() + f"\n  {name}: {entry}\n")
    return out


def _joints_entry(q: np.ndarray) -> str:
    return "{" + ", ".join(f"{n}: {_text(x)}" for n, x in zip(JOINTS, q, strict=True)) + "}"


def _pose_entry(arm: Arm, G: np.ndarray, rotation: str) -> str:
    """The ``pose`` key of a target displacement G: the reference point's position, and the
    rotation as a matrix or a rotation vector."""
    pos = G[:3, :3] @ arm.point + G[:3, 3]
    if rotation == "matrix":
        rot = (
            "rotation: ["
            + ", ".join("[" + ", ".join(_text(x) for x in row) + "]" for row in G[:3, :3])
            + "]"
        )
    else:
        rot = "rotation_vector: [" + ", ".join(_text(x) for x in rotation_vector(G[:3, :3])) + "]"
    return "{pose: {position: [" + ", ".join(_text(x) for x in pos) + "], " + rot + "}}"


def _modes(path: Path, config: str, cwd: Path) -> dict:
    """``python -m mechsing modes PATH --config CONFIG --format json`` in the empty ``cwd``."""
    rc, out, err = run_cli_subprocess(
        ["modes", str(path), "--config", config, "--format", "json"], timeout=600, cwd=cwd
    )
    assert rc == 0, err
    assert "Warning" not in err, err
    assert list(cwd.iterdir()) == [], "modes wrote into the working directory"
    return json.loads(out)


def _postures(doc: dict) -> list[np.ndarray]:
    return [np.array([m["joints"][n][0] for n in JOINTS]) for m in doc["modes"]]


def _pose_gap(G: np.ndarray, T: np.ndarray) -> float:
    return float(np.max(np.abs(G[:3, :] - T[:3, :])))


UR5_ARM = Arm(EXAMPLES / "ur5.yaml")
PUMA_ARM = Arm(EXAMPLES / "puma560.yaml")
G6R_ARM = Arm(EXAMPLES / "general_6r.yaml")


# ----------------------------------------------------------------------------- the references


def test_the_ur5_file_is_its_dh_table_seen_from_the_reference_pose() -> None:
    """The file's joint values are the DH angles, its frame the reference pose: the output's
    displacement is FK(q) FK(0)^-1 (FK: the published DH table, tests/reference/dh.py)."""
    F0 = dh_product(UR5, np.zeros(6))
    rng = np.random.default_rng(3)
    for q in rng.uniform(-math.pi, math.pi, size=(20, 6)):
        D = dh_product(UR5, q) @ np.linalg.inv(F0)
        assert _pose_gap(UR5_ARM.pose(q), D) <= 1e-14


def test_the_closed_form_and_the_numeric_solver_agree_on_the_ur5() -> None:
    """The two independent solvers check each other: 8 postures at the generic pose, each
    reaching it, the same set from both."""
    T = dh_product(UR5, UR5_Q)
    closed = ur5_ik(T)
    assert len(closed) == 8
    assert all(_pose_gap(dh_product(UR5, q), T) <= POSE_TOL for q in closed)
    assert any(angle_gap(q, UR5_Q) <= 1e-12 for q in closed)  # the pose's own joints
    numeric = numeric_ik(UR5_ARM.fk, UR5_ARM.pose(UR5_Q), starts=1000, L=UR5_ARM.L)
    assert same_sets(numeric, closed, ANGLE_TOL)


# ----------------------------------------------------------------------------- UR5


@pytest.fixture(scope="module")
def ur5(tmp_path_factory: pytest.TempPathFactory) -> dict[str, dict]:
    """The modes of the UR5 at the generic pose, its configuration given by the six joints
    and (another file) by the output's pose with a rotation matrix."""
    tmp = tmp_path_factory.mktemp("ur5")
    (tmp / "joints").mkdir()
    (tmp / "pose").mkdir()
    by_joints = _with(UR5_ARM.path, tmp / "joints", "generic", _joints_entry(UR5_Q))
    entry = _pose_entry(UR5_ARM, UR5_ARM.pose(UR5_Q), "matrix")
    by_pose = _with(UR5_ARM.path, tmp / "pose", "generic", entry)
    return {
        "joints": _modes(by_joints, "generic", tmp_path_factory.mktemp("cwd")),
        "pose": _modes(by_pose, "generic", tmp_path_factory.mktemp("cwd")),
    }


@pytest.mark.parametrize("given", ["joints", "pose"])
def test_ur5_has_the_eight_postures_of_its_closed_form(ur5: dict, given: str) -> None:
    doc = ur5[given]
    assert doc["count"] == 8 and doc["complete"] == "maximal"
    assert doc["formulation"]["generic_count"] == 8
    assert all(m["certified"] for m in doc["modes"])
    T = UR5_ARM.pose(UR5_Q)
    found = _postures(doc)
    for q in found:
        assert _pose_gap(UR5_ARM.pose(q), T) <= POSE_TOL
    closed = ur5_ik(dh_product(UR5, UR5_Q))
    assert same_sets(found, closed, ANGLE_TOL)


# ----------------------------------------------------------------------------- PUMA 560


@pytest.fixture(scope="module")
def puma(tmp_path_factory: pytest.TempPathFactory) -> dict:
    """The modes of the PUMA 560 at a generic pose given by the output's pose (position and
    rotation vector, from the independent forward kinematics)."""
    tmp = tmp_path_factory.mktemp("puma")
    entry = _pose_entry(PUMA_ARM, PUMA_ARM.pose(PUMA_Q), "vector")
    path = _with(PUMA_ARM.path, tmp, "generic", entry)
    return _modes(path, "generic", tmp_path_factory.mktemp("cwd"))


def test_puma_has_the_eight_postures_the_numeric_solver_finds(puma: dict) -> None:
    assert puma["count"] == 8 and puma["complete"] == "maximal"
    assert all(m["certified"] for m in puma["modes"])
    T = PUMA_ARM.pose(PUMA_Q)
    found = _postures(puma)
    for q in found:
        assert _pose_gap(PUMA_ARM.pose(q), T) <= POSE_TOL
    numeric = numeric_ik(PUMA_ARM.fk, T, starts=2000, L=PUMA_ARM.L)
    assert len(numeric) == 8  # Pieper's bound is reached at this pose
    assert same_sets(found, numeric, ANGLE_TOL)


# ----------------------------------------------------------------------------- a general 6R


@pytest.fixture(scope="module")
def general(tmp_path_factory: pytest.TempPathFactory) -> dict:
    return _modes(G6R_ARM.path, "generic", tmp_path_factory.mktemp("cwd"))


def test_general_6r_file_has_no_two_consecutive_axes_parallel_or_meeting() -> None:
    joints = G6R_ARM.data["joints"]
    for a, b in zip(joints, joints[1:], strict=False):
        u, v = vec(a["axis"]), vec(b["axis"])
        n = np.cross(u, v)
        assert np.linalg.norm(n) > 0.1 * np.linalg.norm(u) * np.linalg.norm(v)  # not parallel
        distance = abs((vec(b["point"]) - vec(a["point"])) @ n) / np.linalg.norm(n)
        assert distance > 0.05  # skew: the common normal has a length


def test_general_6r_has_sixteen_solutions_and_the_real_ones_numeric_ik_finds(
    general: dict,
) -> None:
    """At most 16 complex solutions (Lee & Liang 1988, Raghavan & Roth 1993), all found; the
    real ones are the postures damped Newton reaches from 3000 random starts."""
    assert general["formulation"]["generic_count"] == 16
    assert general["paths"]["solutions"] == 16
    # all 16 certified distinct (real and complex): no real posture can be missing
    assert general["complete"] == "maximal"
    assert any("all 16 solutions" in n for n in general["notes"])
    T = G6R_ARM.pose(G6R_ARM.values("generic"))
    found = _postures(general)
    for q in found:
        assert _pose_gap(G6R_ARM.pose(q), T) <= POSE_TOL
    numeric = numeric_ik(G6R_ARM.fk, T, starts=3000, L=G6R_ARM.L)
    assert len(numeric) >= 4
    assert same_sets(found, numeric, ANGLE_TOL)
    assert general["count"] == len(numeric)


# ----------------------------------------------------------------------------- analyze


@pytest.mark.parametrize("which", ["ur5-joints", "ur5-pose", "puma", "general"], ids=lambda w: w)
def test_each_mode_is_classified_as_analyze_classifies_it(
    which: str, request: pytest.FixtureRequest
) -> None:
    if which.startswith("ur5"):
        doc, arm = request.getfixturevalue("ur5")[which[4:]], UR5_ARM
    else:
        doc = request.getfixturevalue(which)
        arm = PUMA_ARM if which == "puma" else G6R_ARM
    _classified_as_analyze(doc, arm.path)


def _classified_as_analyze(doc: dict, path: Path) -> None:
    """Each mode's verdict and singularity classes are analyze's of the same joints."""
    argv = ["analyze", str(path), "--format", "json"]
    for k, m in enumerate(doc["modes"], 1):
        for name, values in m["joints_text"].items():
            argv += ["--set", f"m{k}:{name}={values[0]}"]
    rc, out, err = run_cli(argv)
    assert rc == 0, err
    by_name = {c["name"]: c for c in json.loads(out)["configurations"]}
    for k, m in enumerate(doc["modes"], 1):
        ref = by_name[f"m{k}"]
        assert m["singular"] == ref["singular"]
        assert [s["class"] for s in m["singularities"]] == [
            s["class"] for s in ref["singularities"]
        ]


# ----------------------------------------------------------------------------- special poses

#: the tool's axis along the base's (J2 + J3 + J4 = -pi/2, J5 = pi/2): J6 and J1 taken past
#: the target are parallel, so no consecutive pair of the UR5 is skew; not singular
UR5_DOWN = np.array([0.3, -0.9, 1.2, -math.pi / 2 - 0.3, math.pi / 2, 0.4])
#: the wrist singularity (theta5 = 0): J2, J3, J4 and J6 parallel, a self-motion
UR5_WRIST = np.array([0.3, -0.9, 1.2, -0.7, 0.0, 0.4])


def test_ur5_with_its_tool_along_the_base_axis_has_the_postures_of_its_closed_form(
    tmp_path: Path,
) -> None:
    """No skew pair: the formulation stands on a parallel pair (its rank-one condition
    written out, 48 paths) and still finds every posture of the closed form."""
    (tmp_path / "f").mkdir()
    path = _with(UR5_ARM.path, tmp_path / "f", "down", _joints_entry(UR5_DOWN))
    (tmp_path / "cwd").mkdir()
    doc = _modes(path, "down", tmp_path / "cwd")
    assert doc["paths"]["tracked"] == 48
    closed = ur5_ik(dh_product(UR5, UR5_DOWN))
    assert len(closed) >= 2
    found = _postures(doc)
    assert same_sets(found, closed, ANGLE_TOL)
    assert doc["count"] == len(closed)
    T = UR5_ARM.pose(UR5_DOWN)
    assert all(_pose_gap(UR5_ARM.pose(q), T) <= POSE_TOL for q in found)


def test_ur5_at_its_wrist_singularity_has_no_count(tmp_path: Path) -> None:
    """theta5 = 0: the pose is reached along a curve of postures (J4 and J6 turn together
    with J2 and J3), so there is no count, never a wrong one."""
    (tmp_path / "f").mkdir()
    path = _with(UR5_ARM.path, tmp_path / "f", "wrist-generic", _joints_entry(UR5_WRIST))
    (tmp_path / "cwd").mkdir()
    doc = _modes(path, "wrist-generic", tmp_path / "cwd")
    assert doc["count"] is None and doc["complete"] == "infinite" and doc["modes"] == []
    assert any("curve" in n for n in doc["notes"])


def test_ur5_at_its_shoulder_singularity_lists_each_double_posture_once(tmp_path: Path) -> None:
    """The bundled shoulder configuration: the wrist centre on the plane through axis 1,
    so the postures merge in pairs (double roots: none certified, the count not proven);
    they are the closed form's distinct solutions, each singular as analyze says."""
    (tmp_path / "cwd").mkdir()
    doc = _modes(UR5_ARM.path, "shoulder", tmp_path / "cwd")
    q = UR5_ARM.values("shoulder")
    closed = ur5_ik(dh_product(UR5, q))
    distinct: list[np.ndarray] = []
    for c in closed:
        if all(angle_gap(c, d) > 1e-6 for d in distinct):
            distinct.append(c)
    found = _postures(doc)
    assert doc["complete"] == "not proven" and doc["count"] == len(distinct)
    # at a double root the closed form (a square root of a vanishing quantity) is itself
    # accurate only to about the square root of double precision: 3e-8 rad in theta1 here
    assert same_sets(found, distinct, 1e-6)
    assert all(m["singular"] and not m["certified"] for m in doc["modes"])


# ----------------------------------------------------------------------------- a 7R loop

G7R = EXAMPLES / "general_7r.yaml"


def test_general_7r_loop_has_sixteen_modes_and_the_real_ones_numeric_ik_finds(
    tmp_path: Path,
) -> None:
    """A single loop of seven revolutes with J1 given: J2..J7 must reach exp(-q1 xi1) (the
    loop's product of exponentials is the identity), the general 6R problem: 16 complex
    solutions (Lee & Liang 1988), all certified distinct, so the real ones are complete; they
    are the solutions damped Newton finds from 3000 random starts, each closing the loop."""
    data = yaml.safe_load(G7R.read_text())
    joints = data["joints"]
    assert [j["between"] for j in joints][-1] == ["l6", "ground"]  # written around the loop
    axes = [vec(j["axis"]) for j in joints]
    points = [vec(j["point"]) for j in joints]
    q1 = num(data["configurations"]["turned"]["J1"])
    first = poe(axes[:1], points[:1])(np.array([[q1]]))[0]
    rest = poe(axes[1:], points[1:])
    target = np.linalg.inv(first)
    L = float(np.mean([np.linalg.norm(p) for p in points]))
    (tmp_path / "cwd").mkdir()
    doc = _modes(G7R, "turned", tmp_path / "cwd")
    assert doc["formulation"]["name"] == "half-angle pairs of a single loop"
    assert doc["paths"]["solutions"] == 16 and doc["complete"] == "maximal"
    names = [j["name"] for j in joints]
    found = [np.array([m["joints"][n][0] for n in names]) for m in doc["modes"]]
    for q in found:
        assert abs(q[0] - q1) <= 1e-15
        closure = poe(axes, points)(q[None])[0]
        assert _pose_gap(closure, np.eye(4)) <= POSE_TOL
    numeric = numeric_ik(rest, target, starts=3000, L=L)
    assert same_sets([q[1:] for q in found], numeric, ANGLE_TOL)
    assert doc["count"] == len(numeric) >= 4
    assert sum(m["reached_by_continuation"] for m in doc["modes"]) == 1
    _classified_as_analyze(doc, G7R)


def test_ur5_wrist_singularity_given_by_its_pose_has_no_count(tmp_path: Path) -> None:
    """The bundled wrist configuration's self-motion given by the output's pose, exactly:
    the homotopy's endpoints on the curve are complex, but continuation from the reference
    closes on it, and the local dimension test there finds the curve.  (A pose rounded to
    float is 1e-16 off the singular pose, where the curve breaks into isolated postures.)"""
    q = UR5_ARM.values("wrist")
    position = ["-3269*sqrt(2)/8000", "-0.10915", "-5491/1000000 + 131*sqrt(2)/8000"]
    G = UR5_ARM.pose(q)
    assert _pose_gap(G[:3, :3], np.eye(3)) <= 1e-15  # J2 + J3 + J4 = J5 = J6 = J1 = 0
    reached = G[:3, :3] @ UR5_ARM.point + G[:3, 3]
    assert np.max(np.abs(reached - [num(x) for x in position])) <= 1e-15
    entry = "{pose: {position: [" + ", ".join(f'"{x}"' for x in position) + "]}}"
    (tmp_path / "f").mkdir()
    path = _with(UR5_ARM.path, tmp_path / "f", "wrist-pose", entry)
    (tmp_path / "cwd").mkdir()
    doc = _modes(path, "wrist-pose", tmp_path / "cwd")
    assert doc["count"] is None and doc["complete"] == "infinite"


def test_a_rotation_that_is_not_orthonormal_is_refused_as_solve_refuses_it(tmp_path: Path) -> None:
    """A rotation matrix rounded to 7 digits (R^T R - I about 1e-7, above float's 1e-9)."""
    entry = (
        "{pose: {position: [-0.3, -0.4, 0.5], rotation: [[0.7071068, -0.7071068, 0], "
        "[0.7071068, 0.7071068, 0], [0, 0, 1]]}}"
    )
    path = _with(UR5_ARM.path, tmp_path, "rounded", entry)
    for command in ("modes", "solve"):
        rc, _, err = run_cli([command, str(path), "--config", "rounded"])
        assert rc in (2, 3) and "not a rotation matrix" in err, err


def test_postures_1e13_from_the_wrist_singularity_are_regular_certified_and_as_analyze_says(
    tmp_path: Path,
) -> None:
    """J5 = 1e-13: det J is proportional to sin J5, not zero. At 50 digits the roots are
    well conditioned (1e-13), so each is certified, and auto decides them regular as analyze
    does (at mp:50)."""
    q = UR5_Q.copy()
    q[4] = 1e-13
    (tmp_path / "f").mkdir()
    path = _with(UR5_ARM.path, tmp_path / "f", "near-wrist", _joints_entry(q))
    (tmp_path / "cwd").mkdir()
    doc = _modes(path, "near-wrist", tmp_path / "cwd")
    mine = [m for m in doc["modes"] if angle_gap(_postures({"modes": [m]})[0], q) <= 1e-12]
    assert len(mine) == 1 and mine[0]["certified"] and mine[0]["singular"] is False
    assert all(m["certified"] for m in doc["modes"])
    _classified_as_analyze(doc, path)


# ----------------------------------------------------------------------------- a redundant arm

SRS_7R = """\
mechanism: srs-7r
bodies: [base, l1, l2, l3, l4, l5, l6, l7]
joints:
  - {name: J1, type: R, between: [base, l1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J2, type: R, between: [l1, l2], axis: [0, 1, 0], point: [0, 0, 0.34]}
  - {name: J3, type: R, between: [l2, l3], axis: [0, 0, 1], point: [0, 0, 0.34]}
  - {name: J4, type: R, between: [l3, l4], axis: [0, -1, 0], point: [0, 0, 0.74]}
  - {name: J5, type: R, between: [l4, l5], axis: [0, 0, 1], point: [0, 0, 0.74]}
  - {name: J6, type: R, between: [l5, l6], axis: [0, 1, 0], point: [0, 0, 1.14]}
  - {name: J7, type: R, between: [l6, l7], axis: [0, 0, 1], point: [0, 0, 1.14]}
output: {body: l7}
configurations:
  reference: {}
  reach: {J3: 0.4, pose: {position: [0.25, 0.3, 0.9], rotation_vector: [0.3, 2.0, 0.1]}}
"""


def test_a_seven_joint_arm_with_one_joint_given_has_the_postures_of_its_six(
    tmp_path: Path,
) -> None:
    """A 7R arm (shoulder, elbow, spherical wrist) with the pose and J3 given: the six other
    joints must reach it; J5, J6, J7 meet in a point, so at most 8 (Pieper); every one
    reproduces the pose, and they are damped Newton's set over the six unknown joints."""
    from scipy.spatial.transform import Rotation

    data = yaml.safe_load(SRS_7R)
    joints = data["joints"]
    axes = [vec(j["axis"]) for j in joints]
    points = [vec(j["point"]) for j in joints]
    fk7 = poe(axes, points)
    cfg = data["configurations"]["reach"]
    q3 = num(cfg["J3"])
    R = Rotation.from_rotvec(vec(cfg["pose"]["rotation_vector"])).as_matrix()
    c0 = points[6]  # the output's reference point: its one joint's point
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, vec(cfg["pose"]["position"]) - R @ c0

    def fk6(Q: np.ndarray) -> np.ndarray:
        Q = np.atleast_2d(Q)
        return fk7(np.insert(Q, 2, q3, axis=1))

    path = tmp_path / "srs.yaml"
    path.write_text(SRS_7R)
    (tmp_path / "cwd").mkdir()
    doc = _modes(path, "reach", tmp_path / "cwd")
    assert doc["formulation"]["joints"] == ["J1", "J2", "J4", "J5", "J6", "J7"]
    assert doc["formulation"]["generic_count"] == 8 and doc["complete"] == "maximal"
    names = [j["name"] for j in joints]
    found = [np.array([m["joints"][n][0] for n in names]) for m in doc["modes"]]
    for q in found:
        assert q[2] == q3
        assert _pose_gap(fk7(q[None])[0], T) <= POSE_TOL
    numeric = numeric_ik(fk6, T, starts=2000, L=0.5)
    assert same_sets([np.delete(q, 2) for q in found], numeric, ANGLE_TOL)
    assert doc["count"] == len(numeric) == 8
