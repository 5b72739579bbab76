"""Configurations given by the output body's pose (the ``pose`` key of a configuration).

The answers come from outside mechsing: the leg lengths of the planar 3-RPR and of the
Stewart platform in closed form (distances between base and moved platform attachment
points), the UR5's forward kinematics from :mod:`tests.reference.files`, rotations from
Rodrigues' formula written here.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from tests.cli import run_cli
from tests.mechanisms import TWO_LEAVES
from tests.reference.files import MechanismFile

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"


def rodrigues(axis: list[float], angle: float) -> np.ndarray:
    u = np.asarray(axis, dtype=float)
    u = u / np.linalg.norm(u)
    K = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * (K @ K)


def with_configurations(example: str, configurations: str, tmp_path: Path, name: str) -> Path:
    """The example file with its configurations replaced by ``configurations`` (YAML text)."""
    text = (EXAMPLES / example).read_text()
    head = text[: text.index("\nconfigurations:")]
    path = tmp_path / name
    path.write_text(head + "\nconfigurations:\n" + configurations)
    return path


def analyze(path: Path, precision: str = "float") -> tuple[int, dict, str]:
    run = run_cli(["analyze", path, "--format", "json", "--precision", precision])
    return run.status, (json.loads(run.out) if run.out else {}), run.err


def configuration(doc: dict, name: str) -> dict:
    return next(c for c in doc["configurations"] if c["name"] == name)


def fmt(v: object) -> str:
    return json.dumps(np.asarray(v, dtype=float).tolist())


# ---------------------------------------------------------------------------- 3-RPR


#: base pivots (Rb_i), platform pivots (Rp_i) of examples/planar_3rpr.yaml
RPR_BASE = np.array([[0, 0, 0], [4, 0, 0], [0, 4, 0]], dtype=float)
RPR_PLATFORM = np.array([[0.9, 0.3, 0], [2.5, 1.5, 0], [-0.3, 1.9, 0]], dtype=float)


def leg_changes(base: np.ndarray, platform: np.ndarray, R: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Closed form: each leg's length at the pose minus its length at the reference (the P
    joint's value), the pose turning the platform by R about its pivots' centroid moved to p."""
    c = platform.mean(axis=0)
    moved = (R @ (platform - c).T).T + p
    return np.linalg.norm(moved - base, axis=1) - np.linalg.norm(platform - base, axis=1)


@pytest.mark.parametrize("precision", ["float", "mp:30"])
def test_3rpr_leg_lengths_at_a_platform_pose(tmp_path, precision):
    path = with_configurations(
        "planar_3rpr.yaml",
        "  moved:\n    pose: {position: [1.1, 0.9, 0], axis: [0, 0, 1], angle: 0.1}\n",
        tmp_path,
        "rpr.yaml",
    )
    status, doc, err = analyze(path, precision)
    assert status == 0, err
    c = configuration(doc, "moved")
    legs = [c["joints"][f"P{i}"][0] for i in (1, 2, 3)]
    expected = leg_changes(RPR_BASE, RPR_PLATFORM, rodrigues([0, 0, 1], 0.1), [1.1, 0.9, 0])
    np.testing.assert_allclose(legs, expected, rtol=0, atol=1e-12)
    assert c["pose"]["position"] == [1.1, 0.9, 0.0]
    np.testing.assert_allclose(c["pose"]["point"], RPR_PLATFORM.mean(axis=0), atol=1e-15)
    assert c["closure_residual"] < 1e-12


def rpr_file(scale: float, pose: str, tmp_path: Path) -> Path:
    """The 3-RPR written with every length times ``scale`` (floats) and one pose."""
    joints = []
    for i in range(3):
        a, b = RPR_BASE[i] * scale, RPR_PLATFORM[i] * scale
        joints += [
            {"name": f"Rb{i + 1}", "type": "R", "between": ["ground", f"cyl{i + 1}"],
             "axis": [0, 0, 1], "point": a.tolist()},
            {"name": f"P{i + 1}", "type": "P", "between": [f"cyl{i + 1}", f"pis{i + 1}"],
             "axis": (b - a).tolist()},
            {"name": f"Rp{i + 1}", "type": "R", "between": [f"pis{i + 1}", "platform"],
             "axis": [0, 0, 1], "point": b.tolist()},
        ]  # fmt: skip
    doc = {
        "mechanism": "rpr-scaled",
        "bodies": ["ground", "cyl1", "pis1", "cyl2", "pis2", "cyl3", "pis3", "platform"],
        "joints": joints,
        "inputs": ["P1", "P2", "P3"],
        "output": {"body": "platform"},
        "configurations": {"moved": {"pose": yaml.safe_load(pose)}},
    }
    path = tmp_path / f"rpr_{scale:g}.yaml"
    path.write_text(yaml.safe_dump(doc))
    return path


def test_scale_invariance(tmp_path):
    """The same file at 1e-3 and 1e3 times the size: lengths scaled, angles the same."""
    out = {}
    for s in (1e-3, 1.0, 1e3):
        pose = f"{{position: [{1.1 * s!r}, {0.9 * s!r}, 0], rotation_vector: [0, 0, -0.2]}}"
        status, doc, err = analyze(rpr_file(s, pose, tmp_path))
        assert status == 0, err
        out[s] = configuration(doc, "moved")["joints"]
    expected = leg_changes(RPR_BASE, RPR_PLATFORM, rodrigues([0, 0, 1], -0.2), [1.1, 0.9, 0])
    for s, joints in out.items():
        np.testing.assert_allclose(
            [joints[f"P{i}"][0] / s for i in (1, 2, 3)], expected, rtol=1e-10, atol=1e-12
        )
        for name in ("Rb1", "Rp1", "Rb2", "Rp2", "Rb3", "Rp3"):
            assert joints[name][0] == pytest.approx(out[1.0][name][0], abs=1e-10)


# ---------------------------------------------------------------------------- Stewart


def test_stewart_leg_lengths_at_a_translated_and_rotated_pose(tmp_path):
    f = MechanismFile(EXAMPLES / "stewart_octahedral.yaml")
    base = np.array([f.joints[f.jidx[f"U{k}"]].prm["point"] for k in range(1, 7)], dtype=float)
    top = np.array([f.joints[f.jidx[f"S{k}"]].prm["point"] for k in range(1, 7)], dtype=float)
    axis, angle, p = [1.0, 2.0, 3.0], 0.15, np.array([0.05, -0.03, 1.1])
    path = with_configurations(
        "stewart_octahedral.yaml",
        f"  moved:\n    pose: {{position: {fmt(p)}, axis: {axis}, angle: {angle}}}\n",
        tmp_path,
        "stewart.yaml",
    )
    status, doc, err = analyze(path)
    assert status == 0, err
    c = configuration(doc, "moved")
    legs = [c["joints"][f"P{k}"][0] for k in range(1, 7)]
    # the platform's reference point: the centroid of its S joints' points, (0, 0, 1)
    np.testing.assert_allclose(c["pose"]["point"], [0, 0, 1], atol=1e-15)
    expected = leg_changes(base, top, rodrigues(axis, angle), p)
    np.testing.assert_allclose(legs, expected, rtol=0, atol=1e-11)


# ---------------------------------------------------------------------------- UR5


UR5_START = [0.0, -math.pi / 4, math.pi / 2, -math.pi / 4, math.pi / 2, 0.0]
UR5_TARGET = [0.2, -0.6, 1.3, -0.5, 1.4, 0.3]
#: the output link6's reference point: the point of its only joint, J6
UR5_POINT = np.array([-0.81725, -0.10915, -0.005491])


def ur5_pose_of(q: list[float]) -> np.ndarray:
    f = MechanismFile(EXAMPLES / "ur5.yaml")
    return f.poses(np.asarray(q, dtype=float))["link6"]


def ur5_file(tmp_path: Path, poses: dict[str, str]) -> Path:
    start = ", ".join(f"J{i + 1}: {x!r}" for i, x in enumerate(UR5_START))
    text = f"  start6: {{{start}}}\n" + "".join(
        f"  {name}:\n    start: start6\n    pose: {pose}\n" for name, pose in poses.items()
    )
    return with_configurations("ur5.yaml", text, tmp_path, "ur5.yaml")


def test_serial_arm_reaches_the_pose_by_continuation(tmp_path):
    g = ur5_pose_of(UR5_TARGET)
    R, x = g[:3, :3], g[:3, :3] @ UR5_POINT + g[:3, 3]
    # the rotation about the reference point, relative to the reference configuration
    status, doc, err = analyze(
        ur5_file(tmp_path, {"target": f"{{position: {fmt(x)}, rotation: {fmt(R)}}}"})
    )
    assert status == 0, err
    c = configuration(doc, "target")
    q = [c["joints"][f"J{i}"][0] for i in range(1, 7)]
    reached = ur5_pose_of(q)
    np.testing.assert_allclose(reached[:3, :3], R, atol=1e-10)
    np.testing.assert_allclose(reached[:3, :3] @ UR5_POINT + reached[:3, 3], x, atol=1e-10)


def test_rotation_given_three_ways_gives_the_same_joints(tmp_path):
    from scipy.spatial.transform import Rotation

    g = ur5_pose_of([-0.1, -0.9, 1.6, -0.4, 1.2, 0.5])
    R, x = g[:3, :3], fmt(g[:3, :3] @ UR5_POINT + g[:3, 3])
    rv = Rotation.from_matrix(R).as_rotvec()
    angle = float(np.linalg.norm(rv))
    u = rv / angle
    axis = 2.5 * u  # any length
    np.testing.assert_allclose(rodrigues(axis, angle), R, atol=1e-14)
    status, doc, err = analyze(
        ur5_file(
            tmp_path,
            {
                "matrix": f"{{position: {x}, rotation: {fmt(R)}}}",
                "vector": f"{{position: {x}, rotation_vector: {fmt(u * angle)}}}",
                "axis-angle": f"{{position: {x}, axis: {fmt(axis)}, angle: {angle!r}}}",
            },
        )
    )
    assert status == 0, err
    q = {
        n: [configuration(doc, n)["joints"][f"J{i}"][0] for i in range(1, 7)]
        for n in ("matrix", "vector", "axis-angle")
    }
    np.testing.assert_allclose(q["vector"], q["matrix"], atol=1e-10)
    np.testing.assert_allclose(q["axis-angle"], q["matrix"], atol=1e-10)
    # and that pose is where the output is
    g = ur5_pose_of(q["matrix"])
    np.testing.assert_allclose(g[:3, :3], R, atol=1e-10)


def test_pose_out_of_reach_says_how_far_it_got(tmp_path):
    status, doc, err = analyze(ur5_file(tmp_path, {"far": "{position: [3, 0, 0.5]}"}))
    assert status == 3
    c = configuration(doc, "far")
    assert c["singular"] is None
    message = c["error"]
    assert "'far'" in message and "from the target pose" in message
    # the distance still left, in m and rad, is the distance of the arm's reach from the target
    dist = float(message.split("the output 'link6' is ")[1].split(" m")[0])
    assert 1.0 < dist < 3.5


@pytest.mark.parametrize(
    ("name", "pose"),
    [
        ("lifted", "{position: [1.0, 1.2, 0.5]}"),
        ("tilted", "{position: [1.0, 1.2, 0], rotation_vector: [0.3, 0, 0]}"),
    ],
)
def test_a_pose_off_the_plane_of_a_planar_robot_is_not_reachable(
    tmp_path: Path, name: str, pose: str
) -> None:
    """The bundled 3-RPR's joints turn about z and slide in xy: every body moves in the
    plane motions G normal to z, so a pose lifted 0.5 m along z, or turned about x, is
    reached by no assembly mode, and the error says so, not that continuation stopped
    (the same pose in the plane closes)."""
    text = (ROOT / "examples" / "planar_3rpr.yaml").read_text()
    path = tmp_path / "posed.yaml"
    path.write_text(
        text + f"  {name}: {{pose: {pose}}}\n  inside: {{pose: {{position: [1.0, 1.2, 0]}}}}\n"
    )
    run = run_cli(["solve", path, "--config", name])
    assert run.status == 3, run.err
    assert f"configuration {name!r}: the output's pose is not reachable" in run.err
    assert "the planar motions G across the normal [0.0, 0.0, 1.0]" in run.err
    assert "stopped" not in run.err
    assert run_cli(["solve", path, "--config", "inside"]).status == 0


# ---------------------------------------------------------------------------- bad input


BAD = {
    "non_orthonormal": (
        "  c:\n    pose: {rotation: [[1, 0, 0], [0, 1, 0.5], [0, 0, 1]]}\n",
        ["configuration 'c'", "not a rotation matrix", "orthonormal"],
    ),
    "unknown_key": (
        "  c:\n    pose: {positon: [0, 0, 0]}\n",
        ["configuration 'c'", "unknown key 'positon'", "position"],
    ),
    "both_forms": (
        "  c:\n    pose: {rotation_vector: [0, 0, 1], axis: [0, 0, 1], angle: 1}\n",
        ["configuration 'c'", "one way", "rotation_vector", "axis"],
    ),
    "axis_without_angle": (
        "  c:\n    pose: {axis: [0, 0, 1]}\n",
        ["configuration 'c'", "axis needs angle"],
    ),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_pose_is_bad_input(tmp_path, case):
    text, words = BAD[case]
    path = with_configurations("ur5.yaml", text, tmp_path, f"{case}.yaml")
    run = run_cli(["analyze", path, "--format", "json"])
    assert run.status == 2, run.err
    assert run.out == "" and "Traceback" not in run.err
    assert run.err.startswith("mechsing: error: ")
    assert f"{path}:" in run.err  # the file and the line
    for w in words:
        assert w in run.err, (w, run.err)


def test_a_joint_named_pose_is_refused(tmp_path):
    path = tmp_path / "named_pose.yaml"
    path.write_text(
        "bodies: [ground, a]\njoints:\n"
        "  - {name: pose, type: R, between: [ground, a], axis: [0, 0, 1], point: [0, 0, 0]}\n"
    )
    run = run_cli(["analyze", path])
    assert run.status == 2 and "'pose' is reserved" in run.err and "rename" in run.err


def test_pose_needs_an_output(tmp_path):
    path = tmp_path / "no_output.yaml"
    path.write_text(TWO_LEAVES + "configurations:\n  c: {pose: {position: [0, 0, 0]}}\n")
    run = run_cli(["analyze", path])
    assert run.status == 2 and "no output" in run.err and "output: {body:" in run.err


def test_text_report_shows_the_given_pose(tmp_path):
    """The text report says which pose a configuration gave, as the JSON's pose key does."""
    path = with_configurations(
        "planar_3rpr.yaml",
        "  moved:\n    pose: {position: [1.1, 0.9, 0], axis: [0, 0, 1], angle: 0.1}\n",
        tmp_path,
        "rpr.yaml",
    )
    run = run_cli(["analyze", path, "--config", "moved"])
    assert run.status == 0, run.err
    line = next(ln for ln in run.out.splitlines() if "given pose" in ln)
    assert "given pose of platform" in line
    assert "(1.1, 0.9, 0)" in line and "(0, 0, 0.1)" in line


@pytest.mark.parametrize(
    ("pose", "where"),
    [
        ('{rotation_vector: [0, 0, "pi/36"]}', "rotation_vector[2]"),
        ('{axis: [0, 0, 1], angle: "pi/36"}', "angle"),
    ],
)
def test_a_radian_angle_in_a_degree_files_pose_is_refused_with_both_fixes(tmp_path, pose, where):
    """In a file whose angles are in degrees, ``pi/36`` is 5 degrees written in radians:
    read as degrees it would be a 0.087-degree turn, so it is refused, as it is for joint
    values, with the value in degrees; the same pose written in degrees is the radian
    file's pose."""
    text = (EXAMPLES / "planar_3rpr.yaml").read_text()
    head = text[: text.index("\nconfigurations:")].replace(
        "\nbodies:", "\nunits: {angle: deg}\nbodies:", 1
    )
    bad = tmp_path / "deg.yaml"
    bad.write_text(head + f"\nconfigurations:\n  turned:\n    pose: {pose}\n")
    run = run_cli(["analyze", bad, "--format", "json"])
    assert run.status == 2 and "Traceback" not in run.err
    assert f"{bad}:" in run.err and where in run.err
    assert "write the value in degrees (e.g. 5)" in run.err and "units: {angle: rad}" in run.err
    good = tmp_path / "deg-ok.yaml"
    good.write_text(head + "\nconfigurations:\n  turned:\n    pose: {rotation_vector: [0, 0, 5]}\n")
    rad = with_configurations(
        "planar_3rpr.yaml",
        '  turned:\n    pose: {rotation_vector: [0, 0, "pi/36"]}\n',
        tmp_path,
        "rad.yaml",
    )
    _, deg_doc, err = analyze(good)
    _, rad_doc, _ = analyze(rad)
    assert "joints" in configuration(deg_doc, "turned"), err
    for j, v in configuration(rad_doc, "turned")["joints"].items():
        np.testing.assert_allclose(configuration(deg_doc, "turned")["joints"][j], v, atol=1e-12)
