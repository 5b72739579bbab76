"""The names people give an arm's singularities (wrist, elbow, shoulder) and a leg's, the same
in ``analyze`` (text and JSON) and ``condition``: the bundled PUMA 560 and UR5 at the
configurations their files name after them, run as a user runs them."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import yaml

from mechsing.singularity.names import DISTAL, LEG, NAMES, singularity_name
from tests.cli import run_cli_subprocess

ROOT = Path(__file__).resolve().parents[1]
ARMS = [(arm, kind) for arm in ("puma560", "ur5") for kind in ("wrist", "elbow", "shoulder")]


def _run(*args: str) -> str:
    run = run_cli_subprocess(list(args))
    assert run.status in (0,), run.err
    return run.out


@pytest.mark.parametrize(("arm", "kind"), ARMS)
def test_analyze_names_the_arm_singularity_as_condition_does(arm: str, kind: str) -> None:
    path = f"examples/{arm}.yaml"
    doc = json.loads(_run("analyze", path, "--config", kind, "--format", "json"))
    (conf,) = doc["configurations"]
    serial = [f for f in conf["singularities"] if f["class"] == "serial"]
    assert [f["name"] for f in serial] == [kind]
    text = _run("analyze", path, "--config", kind)
    assert f"serial: {kind} singularity ({NAMES[kind]})" in text
    # condition's factors that vanish at the same configuration carry the same name
    cond = json.loads(_run("condition", path, "--config", kind, "--format", "json"))
    vanishing = {f["name"] for c in cond["conditions"] for f in c["factors"] if f["vanishes"]}
    assert vanishing == {kind}


def test_elbow_and_wrist_at_once_are_both_named() -> None:
    """The PUMA's elbow configuration with the wrist's J5 = 0 as well: J4 and J6 coincide
    (a loss of the wrist alone) while the arm is stretched (a loss of the arm's
    translations): two independent losses, rank 4 of 6, both named, the elbow first.  (On
    the UR5 the same values lose one direction only: J2, J3, J4 and J6 are then four
    parallel axes whose twists span 3 dimensions, as they do with the elbow alone.)"""
    path = "examples/puma560.yaml"
    elbow = yaml.safe_load((ROOT / path).read_text())["configurations"]["elbow"]
    values = [f"both:{j}={v}" for j, v in {**elbow, "J5": 0}.items()]
    args = ["analyze", path, "--config", "both"] + [a for v in values for a in ("--set", v)]
    doc = json.loads(_run(*args, "--format", "json"))
    (serial,) = [f for f in doc["configurations"][0]["singularities"] if f["class"] == "serial"]
    assert serial["rank"] == 4 and serial["corank"] == 2
    assert serial["name"] == "elbow and wrist"
    text = _run(*args)
    assert f"elbow and wrist singularity ({NAMES['elbow']}; {NAMES['wrist']})" in text


def test_regular_configuration_has_no_serial_finding_to_name() -> None:
    doc = json.loads(
        _run("analyze", "examples/ur5.yaml", "--config", "regular", "--format", "json")
    )
    assert doc["configurations"][0]["singularities"] == []


def _planar_lines(points: list[tuple[float, float]]) -> list:
    z = np.array([0.0, 0.0, 1.0])
    return [(f"R{i}", np.array([x, y, 0.0]), z) for i, (x, y) in enumerate(points, 1)]


def test_a_leg_with_its_pivots_in_line_is_named_stretched() -> None:
    # three parallel pivots of a planar RRR leg: on one line (stretched) here, a triangle at a
    # generic pose; every joint moves in the lost motion
    here = _planar_lines([(0, 0), (1, 0), (2.5, 0)])
    generic = _planar_lines([(0, 0), (1, 0), (1.7, 0.9)])
    moving = ("R1", "R2", "R3")
    assert singularity_name(here, generic, 1.0, leg=True, moving=moving) == LEG
    # the same geometry on an arm is an elbow
    assert singularity_name(here, generic, 1.0, moving=moving) == "elbow"


def test_no_pattern_no_name() -> None:
    # a fact about a joint that does not move in the lost motion names nothing
    here = _planar_lines([(0, 0), (1, 0), (2.5, 0)])
    generic = _planar_lines([(0, 0), (1, 0), (1.7, 0.9)])
    assert singularity_name(here, generic, 1.0, leg=True, moving=("R1", "R2")) is None
    # nor does a pose with no special fact
    assert singularity_name(generic, generic, 1.0, moving=("R1", "R2", "R3")) is None


ANTHROPOMORPHIC = """\
mechanism: anthropomorphic-3r
bodies: [base, link1, link2, link3]
joints:
  - {name: J1, type: R, between: [base, link1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J2, type: R, between: [link1, link2], axis: [0, 1, 0], point: [0, 0, 1]}
  - {name: J3, type: R, between: [link2, link3], axis: [0, 1, 0], point: [2, 0, 1]}
inputs: [J1, J2, J3]
output: {body: link3, point: ["7/2", 0, 1]}
configurations:
  stretched: {J1: 0.3, J2: 0.5, J3: 0}
  shoulder: {J1: 0.3, J2: 1.2, J3: "acos(-4*cos(6/5)/3) - 6/5"}
"""


def test_a_positioning_arm_stretched_is_an_elbow(tmp_path: Path) -> None:
    """An anthropomorphic 3R arm (J1 vertical, J2 and J3 parallel and horizontal, the
    output point on the forearm) stretched: the output point lies in the plane of the
    parallel axes of J2 and J3, its elbow singularity (det J = 3/2 sin J3 (4 cos J2 +
    3 cos(J2 + J3)) by the arm's lengths 2 and 3/2; the factor sin J3 is the elbow),
    named so by analyze and by condition."""
    path = tmp_path / "arm.yaml"
    path.write_text(ANTHROPOMORPHIC)
    doc = json.loads(_run("analyze", str(path), "--config", "stretched", "--format", "json"))
    (conf,) = doc["configurations"]
    assert [f["name"] for f in conf["singularities"] if f["class"] == "serial"] == ["elbow"]
    cond = json.loads(_run("condition", str(path), "--config", "stretched", "--format", "json"))
    named = {f["expression"]: f["name"] for c in cond["conditions"] for f in c["factors"]}
    assert named.get("sin(J3)") == "elbow", named


def test_a_positioning_arm_with_its_point_on_the_first_axis_is_a_shoulder(tmp_path: Path) -> None:
    """The same arm with its output point on J1's axis: its distance from the axis in the
    arm's plane, 2 cos J2 + 3/2 cos(J2 + J3) (J2 and J3 turn x towards -z), is zero at
    the file's ``shoulder``, the factor 4 cos J2 + 3 cos(J2 + J3) of det J.  J1 then
    turns the arm about the point: the shoulder, named so by analyze and by condition."""
    j2 = 1.2
    j3 = np.arccos(-4 * np.cos(6 / 5) / 3) - 6 / 5
    assert abs(2 * np.cos(j2) + 1.5 * np.cos(j2 + j3)) < 1e-15
    path = tmp_path / "arm.yaml"
    path.write_text(ANTHROPOMORPHIC)
    doc = json.loads(_run("analyze", str(path), "--config", "shoulder", "--format", "json"))
    (conf,) = doc["configurations"]
    (serial,) = [f for f in conf["singularities"] if f["class"] == "serial"]
    assert serial["name"] == "shoulder" and serial["joints"] == ["J1"], serial
    cond = json.loads(_run("condition", str(path), "--config", "shoulder", "--format", "json"))
    vanishing = {f["name"] for c in cond["conditions"] for f in c["factors"] if f["vanishes"]}
    assert vanishing == {"shoulder"}
    # and stretched, the point is off that plane: no shoulder there
    doc = json.loads(_run("analyze", str(path), "--config", "stretched", "--format", "json"))
    assert "shoulder" not in json.dumps(doc["configurations"][0]["singularities"])


def _five_bar_pivots(a1: float, b1: float, a2: float, b2: float) -> dict[str, np.ndarray]:
    """The five-bar's pivots (examples/five_bar.yaml: A1 (-3/2, 0), B1 (-3/2, 2), P (0, 4),
    B2 (3/2, 2), A2 (3/2, 0), all axes z) turned by plane rotations, by hand."""

    def rot(t: float, v: np.ndarray) -> np.ndarray:
        c, s = np.cos(t), np.sin(t)
        return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])

    A1, B1, P, B2, A2 = (
        np.array(p, dtype=float) for p in [(-1.5, 0), (-1.5, 2), (0, 4), (1.5, 2), (1.5, 0)]
    )
    b1p = A1 + rot(a1, B1 - A1)
    b2p = A2 + rot(a2, B2 - A2)
    return {"A1": A1, "B1": b1p, "P": b1p + rot(a1 + b1, P - B1), "B2": b2p, "A2": A2}


def test_a_five_bar_type_ii_is_named_for_its_distal_links_a_slider_crank_s_dead_centre_for_its_leg():
    """At the five-bar's Type II configuration (its file's `type2`) the distal links are in
    line (B1, P, B2 collinear, worked out here from the file's angles) and neither crank is
    stretched: the output singularity's moving joints B1, P and B2 touch no ground pivot,
    so it is named for the distal links, not a leg.  The slider-crank driven by its slider
    keeps its dead centre's name: the crank's ground pivot A is among the moving joints."""
    a1, a2 = np.pi / 6, -np.pi / 6
    b1 = 2 * np.arctan(2 - 5 * np.sqrt(3) / 3)
    b2 = 2 * np.arctan(-2 + 5 * np.sqrt(3) / 3)
    p = _five_bar_pivots(a1, b1, a2, b2)

    def cross(u: np.ndarray, v: np.ndarray) -> float:
        return float(u[0] * v[1] - u[1] * v[0])

    assert abs(cross(p["P"] - p["B1"], p["B2"] - p["B1"])) < 1e-12  # distal links in line
    assert abs(cross(p["B1"] - p["A1"], p["P"] - p["B1"])) > 0.5  # leg 1 not stretched
    assert abs(cross(p["B2"] - p["A2"], p["P"] - p["B2"])) > 0.5  # leg 2 not stretched
    doc = json.loads(
        _run("analyze", "examples/five_bar.yaml", "--config", "type2", "--format", "json")
    )
    (conf,) = doc["configurations"]
    out = [f for f in conf["singularities"] if f["class"] == "output"]
    assert [(f["joints"], f["name"]) for f in out] == [(["B1", "P", "B2"], DISTAL)]
    assert f"output: {DISTAL} ({NAMES[DISTAL]})" in _run(
        "analyze", "examples/five_bar.yaml", "--config", "type2"
    )
    doc = json.loads(
        _run(
            "analyze",
            "examples/slider_crank_slider_input.yaml",
            "--config",
            "dead-centre",
            "--format",
            "json",
        )
    )
    (conf,) = doc["configurations"]
    assert [f["name"] for f in conf["singularities"] if f["class"] == "output"] == [LEG]
