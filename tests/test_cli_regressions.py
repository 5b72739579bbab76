"""Regressions found by an independent review, through the command line."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.cli import run_cli
from tests.mechanisms import FOURBAR_JOINTS

WRIST = """mechanism: zyz-wrist
bodies: [g, a, b, c]
joints:
  - {{name: W1, type: R, between: [g, a], axis: [0, 0, 1], point: [0, 0, 1]}}
  - {{name: W2, type: R, between: [a, b], axis: [0, 1, 0], point: [0, 0, 1]}}
  - {{name: W3, type: R, between: [b, c], axis: [0, 0, 1], point: [0, 0, 1]}}
configurations:
{configs}
"""

FOURBAR = (
    "mechanism: four-bar\n"
    + FOURBAR_JOINTS.replace("{", "{{").replace("}", "}}")
    + "configurations:\n{configs}\n"
)


def _run(tmp_path: Path, text: str, *args: str) -> tuple[int, str, str]:
    """``mechsing analyze`` (in-process) on TEXT written as a mechanism file."""
    p = tmp_path / "m.yaml"
    p.write_text(text)
    return run_cli(["analyze", str(p), *args])


@pytest.mark.parametrize("value", ["1.0e+300", "1e400", '"10**400"'])
def test_absurd_joint_values_are_bad_input_not_a_hang_or_traceback(tmp_path, value: str) -> None:
    text = WRIST.format(configs=f"  huge: {{W1: {value}}}")
    status, _out, err = _run(tmp_path, text, "--format", "json")
    assert status == 2
    assert "Traceback" not in err and "'huge'" in err and "'W1'" in err


def test_a_loop_driven_too_far_is_refused_with_the_way_out(tmp_path) -> None:
    text = FOURBAR.format(configs="  far: {A: 5000}")  # 800 turns of the crank
    status, _out, err = _run(tmp_path, text)
    assert status == 2
    assert "intermediate configurations" in err


def test_a_tree_is_not_continued_and_works_in_exact_mode(tmp_path) -> None:
    # only W2 given: W1 and W3 keep their start values (exactly 0); nothing is solved
    text = WRIST.format(configs='  bent: {W2: "pi/3"}\n  flat: {W2: 0}')
    status, out, err = _run(tmp_path, text, "--precision", "exact", "--format", "json")
    assert status == 0, err
    conf = {c["name"]: c for c in json.loads(out)["configurations"]}
    assert conf["bent"]["singular"] is False
    # W2 = 0: axes 1 and 3 collinear, decided exactly
    (f,) = conf["flat"]["singularities"]
    assert f["class"] == "serial" and f["precision"] == "exact" and f["joints"] == ["W1", "W3"]
    assert f["margin"]["tau_lo"] == f["margin"]["tau_hi"] == 0


def test_serial_rank_is_decided_at_the_requested_precision(tmp_path) -> None:
    # W2 = 1e-14 rad: axes 1 and 3 are not collinear, so the wrist is regular; float
    # cannot see it (sigma ~ 1e-14 < tau_lo), mp:50 can (tau_hi = 1e-25)
    configs = '  e11: {W2: "1e-11"}\n  e14: {W2: "1e-14"}'
    status, out, _ = _run(
        tmp_path,
        WRIST.format(configs=configs),
        "--precision",
        "mp:50",
        "--format",
        "json",
    )
    assert status == 0
    for c in json.loads(out)["configurations"]:
        assert c["singular"] is False and c["precision"] == "mp:50", c["name"]
    # auto: float cannot decide 1e-11 (between the thresholds) and re-decides it at mp:50
    status, out, _ = _run(tmp_path, WRIST.format(configs=configs), "--format", "json")
    e11 = next(c for c in json.loads(out)["configurations"] if c["name"] == "e11")
    assert e11["precision"] == "mp:50" and e11["singular"] is False


def test_a_failed_start_is_named_with_its_loop(tmp_path) -> None:
    configs = "  bad: {A: 30, B: 0, C: 0, D: 0}\n  next: {A: 40, start: bad}"
    status, out, err = _run(tmp_path, FOURBAR.format(configs=configs), "--format", "json")
    assert status == 3
    errors = {c["name"]: c.get("error", "") for c in json.loads(out)["configurations"]}
    assert "loop A-B-C-D" in errors["bad"]
    assert errors["next"].startswith(
        "configuration 'next' starts from 'bad', which could not be closed"
    )
    assert "Traceback" not in err


def test_reported_vectors_have_no_rounding_signs(tmp_path) -> None:
    text = """mechanism: planar-3R
bodies: [g, a, b, c]
joints:
  - {name: J1, type: R, between: [g, a], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J2, type: R, between: [a, b], axis: [0, 0, 1], point: [1, 0, 0]}
  - {name: J3, type: R, between: [b, c], axis: [0, 0, 1], point: [2, 0, 0]}
configurations:
  reference: {}
"""
    status, out, _ = _run(tmp_path, text, "--format", "json")
    assert status == 0
    (f,) = json.loads(out)["configurations"][0]["singularities"]
    for vec in [*f["wrenches"], f["twist"]]:
        nz = [x for x in vec if x != 0]
        assert nz and nz[0] > 0  # first non-zero component positive, noise reported as 0
        assert all(x == 0 or abs(x) > 1e-9 * max(map(abs, vec)) for x in vec)
    # three collinear joints: the null rates are (1, -2, 1) / 2, up to normalisation
    rates = f["null_joint_rates"]
    assert rates == pytest.approx([0.5, -1.0, 0.5], abs=1e-12)


# ---------------------------------------------------------------------------- review of issue 7

#: a 3-RPR whose third leg line is moved off the common point of the other two by
#: 10^-k / 2 (exact): the three leg lines meet within about 1e-k (legs concurrent: the
#: Type II singularity of Gosselin & Angeles 1990), so the input map E N has sigma_min /
#: sigma_max of order 10^-k
RPR_NEAR_CONCURRENT = """mechanism: rpr-near-concurrent
bodies: [ground, cyl1, pis1, cyl2, pis2, cyl3, pis3, platform]
joints:
  - {{name: Rb1, type: R, between: [ground, cyl1],   axis: [0, 0, 1], point: [0, 0, 0]}}
  - {{name: P1, type: P, between: [cyl1, pis1],     axis: ["9/10", "3/10", 0]}}
  - {{name: Rp1, type: R, between: [pis1, platform], axis: [0, 0, 1], point: ["9/10", "3/10", 0]}}
  - {{name: Rb2, type: R, between: [ground, cyl2],   axis: [0, 0, 1], point: [4, 0, 0]}}
  - {{name: P2, type: P, between: [cyl2, pis2],     axis: ["-3/2", "3/2", 0]}}
  - {{name: Rp2, type: R, between: [pis2, platform], axis: [0, 0, 1], point: ["5/2", "3/2", 0]}}
  - {{name: Rb3, type: R, between: [ground, cyl3],   axis: [0, 0, 1], point: [0, 4, 0]}}
  - {{name: P3, type: P, between: [cyl3, pis3],     axis: ["3/2", "-3/2 + 10**-{k}/2", 0]}}
  - {{name: Rp3, type: R, between: [pis3, platform], axis: [0, 0, 1], point: ["3/2", "5/2 + 10**-{k}/2", 0]}}
inputs: [P1, P2, P3]
output: {{body: platform}}
configurations:
  reference: {{}}
"""


def _json(tmp_path, text, *args):
    status, out, err = _run(tmp_path, text, "--format", "json", *args)
    assert status == 0, err
    (c,) = json.loads(out)["configurations"]
    return c


def test_an_output_singularity_resting_on_an_undecided_rank_is_undecided(tmp_path) -> None:
    """1e-10 from concurrent legs, the input map's sigma ratio lies between float's
    thresholds: the output motion space built on it is undecided too (it was reported as a
    decided `output` singularity), and auto re-decides the configuration at mp:50: regular."""
    text = RPR_NEAR_CONCURRENT.format(k=10)
    c = _json(tmp_path, text, "--precision", "float")
    assert c["singular"] is None
    assert {f["class"] for f in c["singularities"]} == {"undecided"}
    tests = {d["test"]: d for d in c["decisions"]}
    assert tests["impossible-input"]["rank"] is None and tests["output"]["rank"] is None
    c = _json(tmp_path, text)
    assert c["precision"] == "mp:50" and c["singular"] is False and c["singularities"] == []


def test_mp_below_20_digits_is_refused(tmp_path) -> None:
    """mp:N's thresholds 10^(10-N) and 10^(-N/2) cross below N = 20."""
    status, _out, err = _run(
        tmp_path, FOURBAR.format(configs="  q: {A: 10}"), "--precision", "mp:16"
    )
    assert status == 2 and "20 <= N" in err


def test_more_digits_never_accept_what_float_refuses(tmp_path) -> None:
    """A four-bar with the crank turned 1 degree and the other joints left at 0 does not close
    (residual 0.048 m): float refuses it, and so must mp:20 (10^(15-N) L would accept it)."""
    text = FOURBAR.format(configs="  off: {A: 0.017453292519943295, B: 0, C: 0, D: 0}")
    for prec in ("float", "mp:20", "mp:30"):
        status, _out, err = _run(tmp_path, text, "--precision", prec)
        assert status == 3 and "does not close" in err, (prec, err)


@pytest.mark.parametrize("angle", ["pi*sqrt(2)", "atan(1/2) + 1", "pi**2", "1"])
def test_exact_refuses_angles_it_cannot_show_exact(angle: str, tmp_path) -> None:
    text = WRIST.format(configs=f'  w: {{W1: 0, W2: "{angle}", W3: 0}}')
    status, _out, err = _run(tmp_path, text, "--precision", "exact")
    # that configuration's error (the others would be reported): status 3
    assert status == 3 and "not exact data" in err and "'W2'" in err


@pytest.mark.parametrize("angle", ["2*atan(1/2)", "pi/7 + 3*atan(1/3)", "acos(sqrt(3)/3)"])
def test_exact_accepts_angles_with_algebraic_sine_and_cosine(angle: str, tmp_path) -> None:
    text = WRIST.format(configs=f'  w: {{W1: 0, W2: "{angle}", W3: 0}}')
    status, _out, err = _run(tmp_path, text, "--precision", "exact")
    assert status == 0, err


def test_exact_refuses_a_spherical_joint_turned_by_one_radian(tmp_path) -> None:
    text = """mechanism: r-s
bodies: [base, l1, l2]
joints:
  - {name: A, type: R, between: [base, l1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: S, between: [l1, l2], point: [1, 0, "1/2"]}
output: {body: l2, point: [2, 0, "1/2"]}
configurations:
  one: {A: 0, B: [1, 0, 0]}
  quarter: {A: 0, B: ["pi/2", 0, 0]}
"""
    status, _out, err = _run(tmp_path, text, "--precision", "exact", "--config", "one")
    assert status == 3 and "not exact data" in err and "'B'" in err
    status, _out, err = _run(tmp_path, text, "--precision", "exact", "--config", "quarter")
    assert status == 0, err


ARM_WITH_A_SIDE_BODY = """\
mechanism: arm-with-camera
bodies: [base, l1, l2, l3, l4, l5, l6, cam]
joints:
  - {name: J1, type: R, between: [base, l1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J2, type: R, between: [l1, l2], axis: [0, 1, 0], point: [0.1, 0, 0.5]}
  - {name: J3, type: R, between: [l2, l3], axis: [0, 1, 0], point: [0.1, 0, 0.9]}
  - {name: J4, type: R, between: [l3, l4], axis: [0, 0, 1], point: [0.15, 0.12, 1.25]}
  - {name: J5, type: R, between: [l4, l5], axis: [0, 1, 0], point: [0.15, 0.12, 1.25]}
  - {name: J6, type: R, between: [l5, l6], axis: [0, 0, 1], point: [0.15, 0.12, 1.25]}
  - {name: C1, type: R, between: [l2, cam], axis: [1, 0, 0], point: [0.1, 0, 0.7]}
output: {body: l6, point: [0.15, 0.12, 1.35]}
configurations:
  reference: {}
  far: {pose: {position: [3, 0, 0.5]}}
"""


def test_a_pose_out_of_reach_names_the_pose_coordinate_beyond_its_travel(tmp_path) -> None:
    """An arm with a joint off its chain (a camera), asked for a pose 2.6 m out of reach:
    the fold the continuation stops at is most sensitive to a pose coordinate, which the
    message names (it indexed the joints' coordinates with it: an internal error)."""
    path = tmp_path / "arm.yaml"
    path.write_text(ARM_WITH_A_SIDE_BODY)
    rc, _, err = run_cli(["solve", str(path), "--config", "far"])
    assert rc == 3, err
    assert "beyond a limit of travel" in err and "pose.x" in err
