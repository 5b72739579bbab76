"""The legs of a parallel mechanism and the output's motion type (typed results and JSON).

Expected answers come from the examples' published facts (their header comments) and from
hand-derived twists: a revolute-jointed rocker turns about its ground pivot, a
parallelogram's coupler translates perpendicular to its crank, Tsai's 3-UPU translates
(T3) and gains a rotation about the vertical at its flat constraint singularity, a 3-RPR
moves in the plane (G), a Stewart platform in all of SE(3) (D).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from mechsing.analysis import analyze

ROOT = Path(__file__).resolve().parents[1]
EX = ROOT / "examples"


def _motion(name: str, config: str, precision: str = "float"):
    res = analyze(EX / f"{name}.yaml", configs=[config], precision=precision)
    return res, res.configurations[0].output_motion


def test_legs_of_the_3upu_run_from_ground_to_platform():
    res = analyze(EX / "tsai_3upu.yaml", configs=["reference"], precision="float")
    assert [(leg.number, leg.joints) for leg in res.legs] == [
        (1, ("U1a", "P1", "U1b")),
        (2, ("U2a", "P2", "U2b")),
        (3, ("U3a", "P3", "U3b")),
    ]
    assert all(leg.base == "ground" and leg.body == "platform" for leg in res.legs)
    js = res.to_json()["legs"]
    assert js[1] == {
        "leg": 2,
        "base": "ground",
        "body": "platform",
        "joints": ["U2a", "P2", "U2b"],
        "other_joints": [],
        "bodies": ["cyl2", "pis2"],
    }


FIVE_BAR_REVERSED = """\
mechanism: five-bar-reversed
bodies: [ground, prox1, dist1, prox2, dist2]
joints:
  - {name: P,  type: R, between: [dist2, dist1],  axis: [0, 0, 1], point: [0, 4, 0]}
  - {name: B2, type: R, between: [prox2, dist2],  axis: [0, 0, 1], point: [1.5, 2, 0]}
  - {name: A2, type: R, between: [ground, prox2], axis: [0, 0, 1], point: [1.5, 0, 0]}
  - {name: B1, type: R, between: [prox1, dist1],  axis: [0, 0, 1], point: [-1.5, 2, 0]}
  - {name: A1, type: R, between: [ground, prox1], axis: [0, 0, 1], point: [-1.5, 0, 0]}
inputs: [A1, A2]
output: {body: dist1, point: [0, 4, 0]}
configurations:
  reference: {}
"""


def test_leg_joints_are_in_path_order_whatever_the_file_order(tmp_path):
    # the file lists each leg from the output back to the ground: the leg still reads
    # from the ground up (A2, B2, P), numbered by its first joint in file order
    f = tmp_path / "rev.yaml"
    f.write_text(FIVE_BAR_REVERSED)
    res = analyze(f, precision="float")
    assert [leg.joints for leg in res.legs] == [("A2", "B2", "P"), ("A1", "B1")]
    assert res.legs[0].bodies == ("prox2", "dist2")


def test_a_serial_arm_has_no_legs():
    res = analyze(EX / "ur5.yaml", configs=["regular"], precision="float")
    assert res.legs == ()
    assert res.to_json()["legs"] == []


def test_fourbar_rocker_turns_about_its_ground_pivot():
    # D joins rocker and ground at (4, 0, 0), axis z: the rocker's twists are the rotations
    # about that line, R with axis z through (4, 0, 0)
    _res, m = _motion("fourbar", "crank-30")
    assert m.dim == 1 and m.is_subgroup and m.type == "R"
    w, v = np.array(m.twists[0][:3]), np.array(m.twists[0][3:])
    w_hat = w / np.linalg.norm(w)
    assert abs(abs(w_hat[2]) - 1) < 1e-12
    # v = -omega x p at the origin for a rotation about the line through p
    assert np.allclose(v, -np.cross(w, [4.0, 0, 0]), atol=1e-12)


def test_parallelogram_coupler_translates_perpendicular_to_the_crank():
    # crank A-B from (0,0) to (0,1) turned by -30 deg: B = (1/2, sqrt(3)/2); the coupler
    # translates with B's velocity, along z x B = (-sqrt(3)/2, 1/2)
    _res, m = _motion("parallelogram", "crank-30")
    assert m.type == "P" and m.dim == 1
    axis = np.array(m.subgroup.canonical().params["axis"], dtype=float)
    assert abs(abs(axis @ [-math.sqrt(3) / 2, 0.5, 0]) - 1) < 1e-12


@pytest.mark.parametrize("precision", ["float", "mp:30"])
def test_3upu_translates_and_gains_a_rotation_about_z_when_flat(precision):
    res, m = _motion("tsai_3upu", "lateral", precision)
    assert (m.type, m.dim, m.is_subgroup) == ("T3", 3, True)
    assert m.precision == precision
    _res, flat = _motion("tsai_3upu", "flat", precision)
    # at the flat pose the three constraint couples (along the legs, horizontal) span only
    # the horizontal plane: the platform gains the rotation about z, Schoenflies X(z)
    assert (flat.type, flat.dim, flat.is_subgroup) == ("X", 4, True)
    axis = np.array([float(x) for x in flat.subgroup.canonical().params["axis"]])
    assert abs(abs(axis[2]) - 1) < 1e-12


def test_planar_3rpr_moves_in_the_plane_and_stewart_in_se3():
    _res, m = _motion("planar_3rpr", "reference")
    assert (m.type, m.dim) == ("G", 3)
    normal = np.array(m.subgroup.canonical().params["normal"], dtype=float)
    assert abs(abs(normal[2]) - 1) < 1e-12
    _res, m = _motion("stewart_octahedral", "reference")
    assert (m.type, m.dim) == ("D", 6)


def test_a_span_that_is_no_subgroup_says_so_and_gives_its_twists():
    # the five-bar's dist1 body: two planar twists whose bracket leaves their span
    res, m = _motion("five_bar", "reference")
    assert m.dim == 2 and m.is_subgroup is False and m.subgroup is None
    assert m.summary == "not a subgroup: dim 2"
    assert len(m.twists) == 2
    for t in m.twists:  # planar twists: omega along z, v in the plane
        assert abs(t[0]) < 1e-12 and abs(t[1]) < 1e-12 and abs(t[5]) < 1e-12
    js = res.to_json()["configurations"][0]["output_motion"]
    assert js["is_subgroup"] is False and js["type"] is None and js["dim"] == 2
    assert len(js["twists"]) == 2


def test_ur5_wrist_singularity_loses_a_dimension():
    _res, m = _motion("ur5", "wrist")
    assert m.dim == 5 and m.is_subgroup is False
    res = analyze(EX / "ur5.yaml", precision="float")
    # the generic motion type speaks for the mechanism: the first regular configuration
    assert res.output_motion is not None and res.output_motion.configuration == "regular"
    assert (res.output_motion.type, res.output_motion.dim) == ("D", 6)
    assert res.to_json()["output_motion"]["summary"] == "D (dimension 6)"


def test_exact_mode_decides_the_output_motion_exactly():
    # the rocker turns about its ground pivot D: axis z through (4, 0, 0), exactly
    _res, m = _motion("fourbar", "reference", "exact")
    assert (m.type, m.dim, m.precision) == ("R", 1, "exact")
    assert list(m.subgroup.params["axis"]) == [0, 0, 1]
    assert list(m.subgroup.params["point"]) == [4, 0, 0]
    assert (m.margin.tau_lo, m.margin.tau_hi, m.margin.sigma_max) == (0.0, 0.0, None)


def test_a_span_that_is_no_subgroup_names_the_subgroup_it_generates():
    # two planar twists generate the planar group G with normal z (their bracket is a
    # translation in the plane); an arm's five twists at a singularity generate D
    res, m = _motion("five_bar", "reference")
    assert m.generated is not None and m.generated.symbol == "G"
    normal = np.array(m.generated.canonical().params["normal"], dtype=float)
    assert abs(abs(normal[2]) - 1) < 1e-12
    js = res.to_json()["configurations"][0]["output_motion"]["generated"]
    assert js["type"] == "G" and js["dim"] == 3
    _res, m = _motion("ur5", "wrist")
    assert m.generated is not None and m.generated.symbol == "D"
    _res, m = _motion("tsai_3upu", "reference")
    assert m.generated is not None and m.generated.symbol == "T3"


def test_five_bar_point_at_an_input_singularity_moves_across_the_straight_leg():
    # examples/five_bar.yaml, type1: leg 1 (A1 = (-3/2, 0), proximal 2, distal 5/2) is
    # stretched straight, |A1 P| = 9/2: the output point can move only perpendicular to A1 P
    res, m = _motion("five_bar", "type1")
    p = m.point
    assert p is not None and p.dim == 1
    a1p = np.array(p.position) - [-1.5, 0, 0]
    assert np.linalg.norm(a1p) == pytest.approx(4.5, abs=1e-12)
    assert abs(np.dot(p.velocities[0], a1p)) < 1e-12
    assert abs(p.velocities[0][2]) < 1e-12
    js = res.to_json()["configurations"][0]["output_motion"]["point"]
    assert js["dim"] == 1 and len(js["velocities"]) == 1
    # at a regular pose the point moves in the plane of the mechanism
    _res, m = _motion("five_bar", "reference")
    assert m.point.dim == 2 and m.point.position == pytest.approx((0, 4, 0), abs=1e-12)
