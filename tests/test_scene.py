"""The scene options: --output-body, --output-point, --relative-to and --inputs on every
command that reads a mechanism, and the branches they leave out.

tests/data/two_arm_mimic.urdf is a torso with two planar 2R arms (links 1 and 0.5, every
axis z; left shoulder at (0, 0.5, 0), left tip at (1.5, 0.5, 0)), a head and, on the right
arm, a gripper whose second finger mimics the first (multiplier -1).  Its left tip point
is a planar 2R's: the point Jacobian's determinant is l1 l2 sin(theta2) = sin(l_elbow)/2,
so the arm has mobility 2 and is singular exactly where sin(l_elbow) = 0.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pytest

from mechsing.model import loads
from mechsing.model.scene import relevant_part
from tests.cli import ROOT, cli_json, run_cli

URDF = ROOT / "tests" / "data" / "two_arm_mimic.urdf"
LEFT_TIP = ["--output-body", "l_fore", "--output-point", "1.5,0.5,0"]
RIGHT_ARM = ["r_shoulder", "r_elbow", "r_finger_b_slide", "r_finger_a_slide"]


def _mimic_line() -> int:
    lines = URDF.read_text().splitlines()
    return next(i for i, t in enumerate(lines, 1) if "<mimic" in t)


@pytest.mark.parametrize("elbow", ["0", "0.5", "pi", "-2", "1e-3"])
def test_an_arm_of_a_two_arm_robot_is_a_planar_2r(elbow: str) -> None:
    theta2 = {"pi": math.pi}.get(elbow) or float(elbow)
    doc = cli_json(
        ["analyze", URDF, *LEFT_TIP, "--set", f"l_elbow={elbow}", "--config", "cli"]
        + ["--format", "json"]
    )
    (c,) = doc["configurations"]
    assert sorted(c["joints"]) == ["l_elbow", "l_shoulder"]
    assert c["mobility"]["finite"] == 2 and c["mobility"]["instantaneous"] == 2
    classes = {f["class"] for f in c["singularities"]}
    # the closed form: the point Jacobian's determinant is sin(theta2) / 2
    singular = abs(math.sin(theta2) / 2) < 1e-12
    assert c["singular"] is singular, (elbow, c["singularities"])
    assert classes == ({"serial"} if singular else set())
    scene = doc["scene"]
    assert scene["output"] == {"body": "l_fore", "relative_to": "base", "point": [1.5, 0.5, 0]}
    assert scene["left_out"] == [
        {"bodies": ["r_upper", "r_fore", "r_finger_b", "r_finger_a"], "joints": RIGHT_ARM},
        {"bodies": ["head"], "joints": ["head_pan"]},
    ]
    assert scene["dropped_couplings"] == ["r_finger_b_slide"]
    assert scene["inputs"] == ["l_shoulder", "l_elbow"]


def test_the_text_names_the_branches_left_out() -> None:
    r = run_cli(["analyze", URDF, *LEFT_TIP])
    assert r.status == 0, r.err
    said = next(line for line in r.out.splitlines() if line.startswith("Left out"))
    for joint in [*RIGHT_ARM, "head_pan"]:
        assert joint in said
    assert "l_elbow" not in said and "l_shoulder" not in said
    assert "Coupling (mimic) left out with its branch: r_finger_b_slide." in r.out
    assert "serial" in r.out  # the reference configuration: sin(0) = 0


def test_a_mimic_on_the_analysed_part_is_modelled_as_a_coupling() -> None:
    # the whole robot, a solve and a sweep of the leader: each runs, the follower at -1 x
    # its leader; the follower's own branch without its leader's: the follower is free
    line = _mimic_line()
    r = run_cli(["analyze", URDF])
    assert r.status == 0, r.err
    assert f"coupling r_finger_b_slide = -1 x r_finger_a_slide (<mimic>, line {line})" in r.out
    r = run_cli(["analyze", URDF, "--output-body", "r_finger_b"])
    assert r.status == 0 and "coupling r_finger_b_slide" not in r.out, r.err
    assert "whose leader is left out, now moving freely" in r.out
    assert "r_finger_b_slide (leader r_finger_a_slide)" in r.out
    r = run_cli(["solve", URDF, "--set", "r_finger_a_slide=0.01"])
    assert r.status == 0 and "r_finger_b_slide: -0.01 m" in r.out, (r.out, r.err)
    r = run_cli(["sweep", URDF, "--vary", "r_finger_a_slide=0:0.04:0.02", "--quiet"])
    assert r.status == 0 and "3 reached" in r.out, (r.out, r.err)
    assert (
        "held at the start's values: r_shoulder, l_shoulder, head_pan, l_elbow, r_elbow\n" in r.out
    )


def test_relative_motion_keeps_the_path_through_the_torso() -> None:
    doc = cli_json(
        ["analyze", URDF, "--output-body", "r_fore", "--relative-to", "l_fore"]
        + ["--format", "json", "--set", "l_elbow=0.3", "--set", "r_elbow=0.7", "--config", "cli"]
    )
    (c,) = doc["configurations"]
    assert sorted(c["joints"]) == ["l_elbow", "l_shoulder", "r_elbow", "r_shoulder"]
    assert c["mobility"]["finite"] == 4
    assert doc["scene"]["ground"] == "base"
    # each finger hangs from the hand on its own: two branches
    assert [b["joints"] for b in doc["scene"]["left_out"]] == [
        ["head_pan"],
        ["r_finger_b_slide"],
        ["r_finger_a_slide"],
    ]


def test_an_output_whose_path_avoids_the_ground_is_analysed_relative_to_its_base() -> None:
    doc = cli_json(
        ["analyze", URDF, "--output-body", "r_finger_a", "--relative-to", "r_fore"]
        + ["--format", "json"]
    )
    (c,) = doc["configurations"]
    assert list(c["joints"]) == ["r_finger_a_slide"]
    assert c["mobility"]["finite"] == 1
    assert doc["scene"]["ground"] == "r_fore"
    assert doc["scene"]["dropped_couplings"] == ["r_finger_b_slide"]
    assert any("is the ground of the analysis" in n for n in doc["scene"]["notes"])


def test_a_loop_closing_with_the_path_is_kept_and_a_loop_hanging_off_it_is_not() -> None:
    # a four-bar A-B-C-D whose coupler carries the output through E, and a second
    # four-bar F-G-H-K hanging from the crank at one body only
    mech = loads(
        """
bodies: [ground, crank, coupler, rocker, tool, p, q, s]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, coupler], axis: [0, 0, 1], point: [1, 0, 0]}
  - {name: C, type: R, between: [coupler, rocker], axis: [0, 0, 1], point: [3, 2, 0]}
  - {name: D, type: R, between: [rocker, ground], axis: [0, 0, 1], point: [4, 0, 0]}
  - {name: E, type: R, between: [coupler, tool], axis: [0, 0, 1], point: [2, 1, 0]}
  - {name: F, type: R, between: [crank, p], axis: [0, 0, 1], point: [0.5, 0, 0]}
  - {name: G, type: R, between: [p, q], axis: [0, 0, 1], point: [0.5, 1, 0]}
  - {name: H, type: R, between: [q, s], axis: [0, 0, 1], point: [0.8, 1, 0]}
  - {name: K, type: R, between: [s, crank], axis: [0, 0, 1], point: [0.8, 0, 0]}
"""
    )
    bodies, joints = relevant_part(mech.bodies, mech.joints, "ground", "tool")
    assert joints == {"A", "B", "C", "D", "E"}
    assert bodies == {"ground", "crank", "coupler", "rocker", "tool"}


def test_the_options_replace_the_files_output_and_inputs_and_say_so_with_v() -> None:
    r = run_cli(
        ["analyze", "examples/fourbar.yaml", "--output-body", "coupler", "--inputs", "D", "-v"]
        + ["--format", "json"]
    )
    assert r.status == 0, r.err
    assert "replaces the file's output {body: rocker}" in r.err
    assert "inputs [D] from the command line replace the file's [A]" in r.err
    doc = json.loads(r.out)
    assert doc["scene"]["output"]["body"] == "coupler" and doc["scene"]["inputs"] == ["D"]
    assert doc["scene"]["left_out"] == []  # the coupler closes the loop: nothing left out
    # --output-point alone changes the file's output: its body stays
    doc = cli_json(
        ["analyze", "examples/fourbar.yaml", "--output-point", "1,0,0", "--format", "json"]
    )
    assert doc["scene"]["output"] == {"body": "rocker", "relative_to": "ground", "point": [1, 0, 0]}


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["--output-body", "l_nope"], "has no body 'l_nope'"),
        (["--output-body", "l_fore", "--relative-to", "l_fore"], "relative to"),
        (["--output-body", "l_fore", "--output-point", "1,2"], "three comma-separated"),
        (["--output-body", "l_fore", "--output-point", "1,2,x"], "--output-point"),
        (["--output-point", "1,2,3"], "names no output; name its body with --output-body"),
        (["--output-body", "l_fore", "--inputs", "r_elbow"], "on a branch left out"),
        (["--output-body", "l_fore", "--inputs", "l_elbow,l_elbow"], "given twice"),
        (["--output-body", "l_fore", "--inputs", "l_elbow[1]"], "out of range"),
        (["--output-body", "l_fore", "--inputs", "nope"], "unknown joint 'nope'"),
        (["--output-body", "base"], "the body it is measured relative to (the ground)"),
        (["--output-body", "l_fore", "--set", "r_elbow=1"], "'r_elbow' is on a branch left out"),
    ],
)
def test_bad_scene_options_are_exit_2(argv: list[str], words: str) -> None:
    r = run_cli(["analyze", URDF, *argv])
    assert r.status == 2, (r.status, r.err)
    assert words in r.err and "Traceback" not in r.err


@pytest.mark.parametrize("command", ["solve", "sweep", "report", "condition", "convert"])
def test_every_command_that_reads_a_mechanism_takes_the_options(command: str, tmp_path) -> None:
    out = tmp_path / "out.html"
    extra = {
        "solve": ["--set", "l_elbow=0.5"],
        "sweep": ["--vary", "l_elbow=0.2:0.6:0.2", "--quiet", "--format", "json"],
        "report": ["--set", "l_elbow=0.5", "-o", out],
        "condition": ["--format", "json"],
        "convert": [],
    }[command]
    source = URDF
    if command == "condition":  # condition reads a mechanism file: the converted robot
        source = tmp_path / "two_arm_mimic.yaml"
        assert run_cli(["convert", URDF, "-o", source]).status == 0
    r = run_cli([command, source, *LEFT_TIP, "--inputs", "l_elbow", *extra])
    assert r.status == 0, (command, r.err)
    if command == "solve":
        assert set(re.findall(r"^  (\w+):", r.out, re.M)) == {"l_shoulder", "l_elbow"}
    elif command == "sweep":
        assert any("r_finger_b_slide" in n for n in json.loads(r.out)["notes"])
    elif command == "report":
        assert "Left out of the analysis" in out.read_text()
    elif command == "condition":
        doc = json.loads(r.out)
        (cond,) = doc["conditions"]
        # the closed form: l1 l2 sin(theta2) with l1 = 1, l2 = 1/2
        assert cond["expression"] == "1/2*sin(l_elbow)"
        assert any("head_pan" in n for n in doc["notes"])
    else:
        mech = loads(r.out)
        assert mech.joint_names == ("l_shoulder", "l_elbow")
        assert [str(i) for i in mech.inputs] == ["l_elbow"]
        assert mech.output is not None and mech.output.body == "l_fore"
        assert [float(x) for x in mech.output.point] == [1.5, 0.5, 0]
        assert not mech.couplings
        assert "left out of the analysis" in r.out


def test_the_converted_scene_analyses_as_the_robot_with_the_options(tmp_path: Path) -> None:
    conv = tmp_path / "left.yaml"
    r = run_cli(["convert", URDF, *LEFT_TIP, "-o", conv])
    assert r.status == 0, r.err
    common = ["--set", "l_elbow=0.5", "--config", "cli", "--format", "json", "--precision", "float"]
    direct = cli_json(["analyze", URDF, *LEFT_TIP, *common])
    converted = cli_json(["analyze", conv, *common])
    assert direct["configurations"] == converted["configurations"]


def test_the_left_tip_link_is_the_left_tip_point() -> None:
    """``--output-body l_tip`` names the link fixed to the left forearm at its tip: the
    output is the forearm's point (1.5, 0.5, 0) (issue 44), the same analysis as
    ``LEFT_TIP`` written out."""
    by_link = cli_json(["analyze", URDF, "--output-body", "l_tip", "--format", "json"])
    by_point = cli_json(["analyze", URDF, *LEFT_TIP, "--format", "json"])
    assert by_link["configurations"] == by_point["configurations"]
