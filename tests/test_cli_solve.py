"""``mechsing solve FILE --config NAME [--format json]``: every joint value of
the closed configuration, in SI units and radians, checked independently."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from mechsing.model import load
from tests.cli import cli_json, run_cli, run_cli_subprocess
from tests.reference.kinematics import (
    J,
    assert_closes,
    fourbar_closed_form,
    joints_from_model,
    poses,
)

ROOT = Path(__file__).resolve().parents[1]
FOURBAR = ROOT / "examples" / "fourbar.yaml"


def solve_json(*argv: object) -> dict:
    """``mechsing solve ARGV --format json`` in-process: its JSON (exit status 0)."""
    return cli_json(["solve", *map(str, argv), "--format", "json"])


def fourbar_expected(theta: float) -> dict[str, float]:
    """Closed form of the four-bar of examples/fourbar.yaml (A (0,0), B (1,0), C (3,2), D (4,0))."""
    A, B, C, D = (np.array(p, float) for p in ([0, 0], [1, 0], [3, 2], [4, 0]))
    (psi, phi, _), _ = fourbar_closed_form(A, B, C, D, theta)
    return {"A": theta, "B": psi - theta, "C": phi - psi, "D": -phi}


def test_fourbar_crank_30_in_radians():
    doc = solve_json(FOURBAR, "--config", "crank-30")
    assert doc["mechanism"] == "four-bar"
    assert doc["configuration"] == "crank-30"
    assert doc["precision"] == "float"
    assert doc["underdetermined"] is False
    joints = doc["joints"]
    assert list(joints) == ["A", "B", "C", "D"]
    assert all(isinstance(v, list) and len(v) == 1 for v in joints.values())
    # 30 deg in the file, radians out
    assert joints["A"][0] == pytest.approx(math.pi / 6, abs=1e-15)
    assert joints["B"][0] == pytest.approx(-0.712, abs=5e-4)
    assert joints["C"][0] == pytest.approx(0.0881, abs=5e-5)
    assert joints["D"][0] == pytest.approx(0.1003, abs=5e-5)
    for k, v in fourbar_expected(math.pi / 6).items():
        assert joints[k][0] == pytest.approx(v, abs=1e-10)
    # accepted at 1e-12 L; L = sqrt(3.25), the RMS distance of the pivots from their centroid
    assert 0 <= doc["closure_residual"] <= 1e-12 * math.sqrt(3.25)
    assert isinstance(doc["steps"], int) and doc["steps"] >= 1


def test_chained_configuration_crank_200():
    """crank-200 starts at crank-30: the crank-rocker's crank turns on, the
    rocker stays on the reference's assembly mode."""
    doc = solve_json(FOURBAR, "--config", "crank-200")
    joints = doc["joints"]
    assert joints["A"][0] == pytest.approx(math.radians(200), abs=1e-14)
    for k, v in fourbar_expected(math.radians(200)).items():
        d = (joints[k][0] - v + math.pi) % (2 * math.pi) - math.pi
        assert abs(d) < 1e-9, (k, joints[k][0], v)


def test_solve_text_format_lists_every_joint():
    status, out, err = run_cli(["solve", str(FOURBAR), "--config", "crank-30"])
    assert status == 0, err
    lines = out.strip().splitlines()
    assert "four-bar" in lines[0] and "crank-30" in lines[0]
    values = {}
    for line in lines[1:]:
        name, _, rest = line.strip().partition(":")
        # each value is followed by its unit (rad or m)
        values[name] = [float(x.split()[0]) for x in rest.split(",")]
        assert all(x.split()[1] in ("rad", "m") for x in rest.split(",")), line
    expected = fourbar_expected(math.pi / 6)
    assert set(values) == set(expected)
    for k, v in expected.items():
        assert values[k][0] == pytest.approx(v, abs=1e-10)


@pytest.mark.parametrize(
    "example,config",
    [
        ("tsai_3upu.yaml", "lateral"),
        ("spherical_4r.yaml", "crank-60"),
        ("slider_crank_slider_input.yaml", "slider-4"),
        ("bricard.yaml", "q1-0.4"),
    ],
)
def test_solved_json_closes_by_an_independent_check(example, config):
    path = ROOT / "examples" / example
    doc = solve_json(path, "--config", config)
    mech = load(path)
    joints = joints_from_model(mech)
    vals = {k: np.array(v) for k, v in doc["joints"].items()}
    assert set(vals) == {j.name for j in mech.joints}
    for j in mech.joints:
        assert len(vals[j.name]) == j.dof
    # the given values come back in SI units and radians
    for jn, v in mech.configurations[config].values.items():
        np.testing.assert_allclose(vals[jn], [float(x) for x in v], rtol=1e-15, atol=1e-300)
    L = max(1.0, max(np.linalg.norm(j.prm["point"]) for j in joints if "point" in j.prm))
    assert_closes(joints, vals, L)


def test_units_mm_and_deg_come_out_in_si(tmp_path):
    """A serial arm in mm and deg: lengths in metres and angles in radians."""
    f = tmp_path / "arm.yaml"
    f.write_text(
        "units: {length: mm, angle: deg}\n"
        "bodies: [base, arm, hand]\n"
        "joints:\n"
        "  - {name: R1, type: R, between: [base, arm], axis: [0, 0, 1], point: [0, 0, 0]}\n"
        "  - {name: P1, type: P, between: [arm, hand], axis: [1, 0, 0]}\n"
        "configurations:\n"
        "  reference: {}\n"
        "  out: {R1: 90, P1: 250}\n"
    )
    doc = solve_json(f, "--config", "out")
    assert doc["joints"]["R1"][0] == pytest.approx(math.pi / 2, abs=1e-15)
    assert doc["joints"]["P1"][0] == pytest.approx(0.25, abs=1e-15)
    # independently: the hand's origin is at (0, 0.25, 0)
    joints = [
        J("R1", "R", "base", "arm", {"axis": np.array([0.0, 0, 1]), "point": np.zeros(3)}),
        J("P1", "P", "arm", "hand", {"axis": np.array([1.0, 0, 0])}),
    ]
    g = poses(joints, "base", {k: np.array(v) for k, v in doc["joints"].items()})["hand"]
    np.testing.assert_allclose(g[:3, 3], [0, 0.25, 0], atol=1e-15)


FIVE_BAR = """\
mechanism: five-bar
bodies: [ground, l1, l2, l3, l4]
joints:
  - {name: J0, type: R, between: [ground, l1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J1, type: R, between: [l1, l2], axis: [0, 0, 1], point: [1, 1, 0]}
  - {name: J2, type: R, between: [l2, l3], axis: [0, 0, 1], point: [2.5, 1.5, 0]}
  - {name: J3, type: R, between: [l3, l4], axis: [0, 0, 1], point: [4, 1, 0]}
  - {name: J4, type: R, between: [l4, ground], axis: [0, 0, 1], point: [4, 0, 0]}
inputs: [J0]
output: {body: l2}
configurations:
  reference: {}
  one-input: {J0: 0.2}
  two-inputs: {J0: 0.2, J4: -0.1}
"""


def test_underdetermined_five_bar(tmp_path):
    f = tmp_path / "five.yaml"
    f.write_text(FIVE_BAR)
    one = solve_json(f, "--config", "one-input")
    two = solve_json(f, "--config", "two-inputs")
    assert one["underdetermined"] is True
    assert two["underdetermined"] is False
    joints = joints_from_model(load(f))
    for doc in (one, two):
        assert doc["joints"]["J0"] == [0.2]
        assert_closes(joints, {k: np.array(v) for k, v in doc["joints"].items()}, 4.0)
    assert two["joints"]["J4"] == [-0.1]


def test_unknown_configuration_is_exit_2_naming_it():
    status, out, err = run_cli(["solve", str(FOURBAR), "--config", "crank-31"])
    assert status == 2
    assert out == ""
    assert "crank-31" in err
    assert str(FOURBAR) in err
    assert "crank-30" in err  # the message lists the configurations there are
    assert "Traceback" not in err


def test_missing_config_option_is_exit_2():
    # --config is optional since --set (which implies --config cli); without either: exit 2
    status, _, err = run_cli(["solve", str(FOURBAR)])
    assert status == 2
    assert "--config" in err and "Traceback" not in err


def test_bad_precision_is_exit_2():
    status, _, err = run_cli(["solve", str(FOURBAR), "--config", "crank-30", "--precision", "fast"])
    assert status == 2
    assert "--precision" in err and "Traceback" not in err


def test_configuration_that_does_not_close_is_exit_3(tmp_path):
    f = tmp_path / "open.yaml"
    f.write_text(
        FIVE_BAR.replace("  two-inputs: {J0: 0.2, J4: -0.1}\n", "")
        + "  given: {J0: 0.2, J1: 0, J2: 0, J3: 0, J4: 0}\n"
    )
    status, out, err = run_cli(["solve", str(f), "--config", "given", "--format", "json"])
    assert status == 3
    assert out == ""
    assert "given" in err and "Traceback" not in err


def test_solve_mp_precision():
    doc = solve_json(FOURBAR, "--config", "crank-30", "--precision", "mp:30")
    assert doc["precision"] == "mp:30"
    for k, v in fourbar_expected(math.pi / 6).items():
        assert doc["joints"][k][0] == pytest.approx(v, abs=1e-12)
    assert doc["closure_residual"] <= 1e-14


def test_solve_as_a_subprocess():
    proc = run_cli_subprocess(["solve", FOURBAR, "--config", "crank-30", "--format", "json"])
    assert proc.status == 0, proc.err
    doc = json.loads(proc.out)
    for k, v in fourbar_expected(math.pi / 6).items():
        assert doc["joints"][k][0] == pytest.approx(v, abs=1e-10)
    proc = run_cli_subprocess(["solve", FOURBAR, "--config", "nope"])
    assert proc.status == 2
    assert "nope" in proc.err and "Traceback" not in proc.err
    assert proc.out == ""


def test_given_values_the_loop_ties_together_are_named_as_such():
    """The four-bar has one degree of freedom (planar Gruebler: 3 (4 - 1) - 2 * 4 = 1), so
    crank A and the coupler's turn B are tied by one relation: given both, even values that
    close together (B from the closed form at A = 30 deg), a straight path between the
    reference and the target leaves the mechanism's motion.  The error says why, not that
    a singularity lies on the path."""
    b = math.degrees(fourbar_expected(math.pi / 6)["B"])
    status, out, err = run_cli(["solve", FOURBAR, "--set", "A=30", "--set", f"B={b:.6f}"])
    assert status == 3 and out == ""
    assert "A, B are not independent" in err and "1 relation" in err, err
    assert "only 1 of the 2 can be chosen" in err
    assert "a singularity or a limit of motion" not in err


def test_given_values_tied_linearly_still_close():
    """The parallelogram's coupler translates, so the rocker turns with the crank: C = A,
    B = D = -A.  Given A and C equal, the straight path in them stays on the motion."""
    doc = solve_json(ROOT / "examples" / "parallelogram.yaml", "--set", "A=0.5", "--set", "C=0.5")
    for k, v in {"A": 0.5, "B": -0.5, "C": 0.5, "D": -0.5}.items():
        assert doc["joints"][k][0] == pytest.approx(v, abs=1e-12)


def test_a_target_beyond_a_limit_of_travel_is_not_called_tied():
    """The double rocker's input A stops at 2 pi / 3 (law of cosines in triangle ABD with
    |BD| = b + c = 7: cos A = (3^2 + 5^2 - 7^2) / (2 * 3 * 5) = -1/2).  From that limit,
    A = 2.3 is beyond it: the one given value is not tied to anything, and the error says
    that the start is a limit of motion and the target beyond it."""
    assert 2.3 > 2 * math.pi / 3
    status, _, err = run_cli(
        ["solve", ROOT / "examples" / "double_rocker.yaml", "--from", "limit", "--set", "A=2.3"]
    )
    assert status == 3
    # the start is that limit (a fold of A): the message says so, and that A lies beyond it
    assert "'limit' is a fold of the given values (a limit of their travel" in err, err
    assert "the target lies beyond it" in err and "not independent" not in err, err
