"""Real URDF files that were refused or misread (issue 44, "Real files refused or misread").

Small URDFs written here, shaped as the example-robot-data files that showed each problem:

- ``<limit lower="-1e+16" upper="1e+16">`` (iris.urdf) is how URDF writers say "no
  limit", as are ``inf`` and a ``<limit>`` on a ``continuous`` joint: the joint is read
  without limits, with a note; geometry keeps the bound on absurd numbers.
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


@pytest.mark.parametrize(
    ("lower", "upper"), [("-1e+16", "1e+16"), ("-inf", "inf"), ("-1e16", "1.5")]
)
def test_a_limit_that_says_no_limit_is_read_as_none(tmp_path: Path, lower: str, upper: str) -> None:
    path = _rotors(tmp_path, lower, upper)
    rc, out, err = run_cli(["analyze", path, "--format", "json"])
    assert rc == 0, err
    c = json.loads(out)["configurations"][0]
    assert c["singular"] is False
    rc, yaml_text, err = run_cli(["convert", path])
    assert rc == 0, err
    limits = yaml_text.split("\nlimits:", 1)[1].split("\ninputs:")[0]
    assert "spin0" not in limits  # no limit for the rotor
    assert '"spin1": [-1.0, 1.0]' in limits  # the other joint's limit is kept
    assert "joint 'spin0' (line 9) is read without limits" in yaml_text
    assert "says no limit" in yaml_text


def test_a_limit_on_a_continuous_joint_is_none_with_a_note(tmp_path: Path) -> None:
    path = _rotors(tmp_path, "-1", "1", second="continuous")
    rc, yaml_text, err = run_cli(["convert", path])
    assert rc == 0, err
    limits = yaml_text.split("\nlimits:", 1)[1].split("\ninputs:")[0]
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
