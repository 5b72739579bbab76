"""Real URDF files that were refused or misread (issue 44, "Real files refused or misread").

Small URDFs written here, shaped as the example-robot-data files that showed each problem:

- ``<limit lower="-1e+16" upper="1e+16">`` (iris.urdf) is how URDF writers say "no
  limit", as are ``inf`` and a ``<limit>`` on a ``continuous`` joint: the joint is read
  without limits, with a note; geometry keeps the bound on absurd numbers.
- ``--output-body panda_hand_tcp``: a link joined rigidly (URDF ``fixed``) to another is
  merged into the body named after the link nearer the root; the option accepts its
  name, the output being that link's origin on that body (a tool centre point).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.cli import run_cli

ROTORS = """\
<?xml version="1.0" ?>
<robot name="rotors">
  <link name="base"/>
  <link name="rotor0"/>
  <link name="rotor1"/>
  <joint name="spin0" type="revolute">
    <parent link="base"/><child link="rotor0"/>
    <origin xyz="0.13 -0.22 0.023" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit effort="0" lower="{lower}" upper="{upper}" velocity="0"/>
  </joint>
  <joint name="spin1" type="{second}">
    <parent link="base"/><child link="rotor1"/>
    <origin xyz="{x1} 0.2 0.023" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit effort="0" lower="-1" upper="1" velocity="0"/>
  </joint>
</robot>
"""


def _rotors(tmp_path: Path, lower: str, upper: str, second: str = "revolute", x1="-0.13") -> Path:
    path = tmp_path / "rotors.urdf"
    path.write_text(ROTORS.format(lower=lower, upper=upper, second=second, x1=x1))
    return path


def _converted_limits(path: Path) -> tuple[str, str]:
    """The converted file's text and its ``limits:`` section."""
    rc, yaml_text, err = run_cli(["convert", path])
    assert rc == 0, err
    return yaml_text, yaml_text.split("\nlimits:", 1)[1].split("\ninputs:")[0]


@pytest.mark.parametrize(
    ("lower", "upper"), [("-1e+16", "1e+16"), ("-inf", "inf"), ("-1e16", "1.5")]
)
def test_a_limit_that_says_no_limit_is_read_as_none(tmp_path: Path, lower: str, upper: str) -> None:
    path = _rotors(tmp_path, lower, upper)
    rc, out, err = run_cli(["analyze", path, "--format", "json"])
    assert rc == 0, err
    c = json.loads(out)["configurations"][0]
    assert c["singular"] is False
    yaml_text, limits = _converted_limits(path)
    assert "spin0" not in limits  # no limit for the rotor
    assert '"spin1": [-1.0, 1.0]' in limits  # the other joint's limit is kept
    assert "joint 'spin0' (line 9) is read without limits" in yaml_text
    assert "says no limit" in yaml_text


def test_a_limit_on_a_continuous_joint_is_none_with_a_note(tmp_path: Path) -> None:
    path = _rotors(tmp_path, "-1", "1", second="continuous")
    yaml_text, limits = _converted_limits(path)
    assert "spin1" not in limits and '"spin0": [-1.0, 1.0]' in limits
    assert "joint 'spin1' (line 14) is read without limits" in yaml_text
    assert "is on a continuous joint, which has none" in yaml_text


def test_an_absurd_limit_on_its_wrong_side_and_absurd_geometry_are_refused(
    tmp_path: Path,
) -> None:
    rc, _, err = run_cli(["analyze", _rotors(tmp_path, "1e+16", "2e+16")])
    assert rc == 2 and "lower" in err and "too large" in err
    rc, _, err = run_cli(["analyze", _rotors(tmp_path, "-1", "1", x1="1e+16")])
    assert rc == 2 and "xyz" in err and "too large" in err


#: a planar 2R arm (shoulder at the origin, elbow at x = 1, both about z) whose tool link
#: is fixed to the forearm at x = 2 (1 m beyond the elbow), and a flange fixed to the
#: tool with no offset of its own but a turn
ARM = """\
<?xml version="1.0" ?>
<robot name="arm2r">
  <link name="base"/><link name="upper"/><link name="fore"/><link name="tool"/>
  <link name="flange"/>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
  <joint name="elbow" type="revolute">
    <parent link="upper"/><child link="fore"/><origin xyz="1 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
  <joint name="tool_fixed" type="fixed">
    <parent link="fore"/><child link="tool"/><origin xyz="1 0 0" rpy="0 0 0.5"/>
  </joint>
  <joint name="flange_fixed" type="fixed">
    <parent link="tool"/><child link="flange"/><origin xyz="0 0.5 0"/>
  </joint>
</robot>
"""


def _arm(tmp_path: Path) -> Path:
    path = tmp_path / "arm2r.urdf"
    path.write_text(ARM)
    return path


@pytest.mark.parametrize(("elbow", "singular"), [("0", True), ("pi", True), ("1", False)])
def test_output_body_names_a_link_merged_into_another_body(
    tmp_path: Path, elbow: str, singular: bool
) -> None:
    """The tool point of a planar 2R arm (links 1 and 1) moves in the plane with the
    Jacobian determinant a1 a2 sin(elbow): its positioning task is singular stretched
    (elbow 0) and folded (pi), regular between.  The forearm body's own twist (named by
    its own link) keeps two directions at every elbow angle."""
    path = _arm(tmp_path)
    c = _analyse(path, "tool", elbow)
    assert c["singular"] is singular
    if singular:
        assert "serial" in {s["class"] for s in c["singularities"]}
    assert _analyse(path, "fore", elbow)["singular"] is False


def _analyse(path: Path, body: str, elbow: str) -> dict:
    rc, out, err = run_cli(
        ["analyze", path, "--output-body", body, "--set", f"elbow={elbow}", "--format", "json"]
    )
    assert rc == 0, err
    return next(c for c in json.loads(out)["configurations"] if c["name"] == "cli")


def test_a_merged_links_origin_is_the_output_point(tmp_path: Path) -> None:
    """The flange's origin: the tool's (2, 0, 0) plus its offset (0, 0.5) turned by the
    tool's 0.5 rad, in the ground frame at the reference configuration."""
    import math

    path = _arm(tmp_path)
    rc, out, err = run_cli(["analyze", path, "--output-body", "flange", "-v", "--format", "json"])
    assert rc == 0, err
    assert "--output-body flange: the link is joined rigidly to body 'fore'" in err
    rc, yaml_text, err = run_cli(["convert", path, "--output-body", "flange"])
    assert rc == 0, err
    line = next(ln for ln in yaml_text.splitlines() if ln.startswith("output:"))
    assert '"fore"' in line
    x, y, z = (float(v) for v in line.split("point: [", 1)[1].split("]")[0].split(","))
    # the converted file writes geometry to 14 significant digits
    expected = (2 - 0.5 * math.sin(0.5), 0.5 * math.cos(0.5), 0)
    assert (x, y, z) == pytest.approx(expected, abs=1e-13)


def test_output_body_naming_no_link_is_still_refused(tmp_path: Path) -> None:
    rc, _, err = run_cli(["analyze", _arm(tmp_path), "--output-body", "gripper"])
    assert rc == 2
    assert "has no body 'gripper'" in err


HANDS = """\
<?xml version="1.0" ?>
<robot name="hands">
  <link name="base"/>
  <link name="Left_L1"/><link name="Left_L2"/><link name="Right_L1"/><link name="Right_L2"/>
  <joint name="Left_index_q1" type="revolute">
    <parent link="base"/><child link="Left_L1"/>
    <origin xyz="0 0.2 0" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit effort="1" lower="0" upper="2" velocity="1"/>
  </joint>
  <joint name="Left_index_q2" type="revolute">
    <parent link="Left_L1"/><child link="Left_L2"/>
    <origin xyz="0.04 0 0" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit effort="1" lower="0" upper="2.6" velocity="1"/>
    <mimic joint="{leader}" multiplier="1.05" offset="0.72"/>
  </joint>
  <joint name="Right_index_q1" type="revolute">
    <parent link="base"/><child link="Right_L1"/>
    <origin xyz="0 -0.2 0" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit effort="1" lower="0" upper="2" velocity="1"/>
  </joint>
  <joint name="Right_index_q2" type="revolute">
    <parent link="Right_L1"/><child link="Right_L2"/>
    <origin xyz="0.04 0 0" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit effort="1" lower="0" upper="2.6" velocity="1"/>
    <mimic joint="index_q1" multiplier="1.05" offset="0.72"/>
  </joint>
</robot>
"""


def _hands(tmp_path: Path, leader: str) -> Path:
    path = tmp_path / "hands.urdf"
    path.write_text(HANDS.format(leader=leader))
    return path


def test_a_mimic_naming_its_leader_without_the_hands_prefix(tmp_path: Path) -> None:
    """alex_psyonic_hands.urdf (example-robot-data): each finger's second joint mimics
    ``index_q1``, a name the robot does not define: its xacro prefixed the joints of each
    hand (``Left_index_q1``, ``Right_index_q1``) but not the mimics' names.  The leader is
    the one joint between the follower and the root named so after a prefix: the left
    finger follows ``Left_index_q1``, the right one ``Right_index_q1``, with a note."""
    path = _hands(tmp_path, "index_q1")
    run = run_cli(["analyze", path, "--format", "json"])
    assert run.status in (0, 1), run.err
    run = run_cli(["convert", path])
    assert run.status == 0, run.err
    assert "names 'index_q1', which the robot does not define; read as 'Left_index_q1'" in run.out
    assert "read as 'Right_index_q1'" in run.out
    couplings = run.out.split("\ncouplings:", 1)[1]
    assert "Left_index_q2" in couplings and "Left_index_q1" in couplings
    assert "Right_index_q2" in couplings and "Right_index_q1" in couplings


def test_a_mimic_naming_no_joint_on_its_branch_is_still_refused(tmp_path: Path) -> None:
    path = _hands(tmp_path, "thumb_q1")
    run = run_cli(["analyze", path])
    assert run.status == 2
    assert "thumb_q1" in run.err
