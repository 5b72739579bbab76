"""A class never depends on which of two mirror-image legs is hit (issue 27, item 15).

A leg's serial test follows the output chain's rule: the output point's velocities when
the output names a point, else the output body's twists.  Judged by body twists, a leg
that ends before the joint turning about the output point (A1-B1 of a five-bar whose
output point lies on P's axis) never loses rank, while its mirror image (A2-B2-P) does.

The mechanisms are symmetric about the plane x = 0 (tests/data/spherical_five_bar.yaml,
examples/five_bar.yaml): the mirror maps leg 1 onto leg 2, an input value a of one leg onto
-a of the other, and the output onto itself, so the classes at mirrored configurations are
the same.  Leg k's type I points are checked independently: the axes of Ak, Bk and P,
carried by Rodrigues' formula written here, are coplanar there.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from tests.cli import run_cli
from tests.reference.files import MechanismFile

ROOT = Path(__file__).resolve().parents[1]
SPHERICAL = ROOT / "tests" / "data" / "spherical_five_bar.yaml"
PLANAR = ROOT / "examples" / "five_bar.yaml"


def rot(axis: np.ndarray, angle: float) -> np.ndarray:
    u = axis / np.linalg.norm(axis)
    K = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * (K @ K)


def coplanarity(joints: dict[str, list[float]], leg: str) -> float:
    """det of the unit axes of A_leg, B_leg and P at the joint values (forward kinematics
    from the ground through leg ``leg``: A turns B's and P's axes, B turns P's)."""
    f = MechanismFile(SPHERICAL)
    ax = {
        j.name: np.asarray(j.prm["axis"], float) / np.linalg.norm(j.prm["axis"]) for j in f.joints
    }
    a, b = f"A{leg}", f"B{leg}"
    Ra = rot(ax[a], joints[a][0])
    ub = Ra @ ax[b]
    up = Ra @ rot(ax[b], joints[b][0]) @ ax["P"]
    return float(np.linalg.det(np.array([ax[a], ub, up])))


def type_one(spec: str) -> dict:
    """The located point of a path sweep where the input test drops (type I)."""
    r = run_cli(["sweep", SPHERICAL, "--vary", spec, "--format", "json", "--quiet"])
    assert r.status == 0, r.err
    (p,) = [p for p in json.loads(r.out)["located"] if "input" in p["tests"]]
    return p


def test_mirror_image_type_one_points_of_a_spherical_five_bar_have_one_class():
    one = type_one("A1=-1.5:-0.8:0.05")  # A2 held at 0
    two = type_one("A2=0.8:1.5:0.05")  # A1 held at 0: its mirror image
    assert math.isclose(one["values"][0], -two["values"][0], abs_tol=1e-10)
    assert abs(coplanarity(one["joints"], "1")) < 1e-12
    assert abs(coplanarity(two["joints"], "2")) < 1e-12
    assert set(one["classes"]) == set(two["classes"])
    assert {"input", "impossible-output", "serial"} <= set(one["classes"])
    legs = {
        k: [f.get("leg") for f in p["configuration"]["singularities"] if f["class"] == "serial"]
        for k, p in (("one", one), ("two", two))
    }
    assert legs == {"one": [1], "two": [2]}


def test_mirror_image_stretched_legs_of_the_planar_five_bar_have_one_class(tmp_path):
    """examples/five_bar.yaml's type1 stretches leg 1 (A1 = -2 atan(1/5), A2 = 0); its
    mirror image stretches leg 2 (A1 = 0, A2 = 2 atan(1/5)), solved from the inputs."""
    src = PLANAR.read_text()
    mirrored = tmp_path / "five_bar.yaml"
    mirrored.write_text(src + '  mirrored: {A1: 0, A2: "2*atan(1/5)"}\n')
    r = run_cli(
        ["analyze", mirrored, "--config", "type1", "--config", "mirrored", "--format", "json"]
    )
    assert r.status == 0, r.err
    confs = {c["name"]: c for c in json.loads(r.out)["configurations"]}
    classes = {k: {f["class"] for f in c["singularities"]} for k, c in confs.items()}
    assert classes["type1"] == classes["mirrored"], classes
    assert "serial" in classes["type1"]
