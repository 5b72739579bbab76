"""The bodies' inertia in the file (issue 43): a mechanism file's ``mass`` entries with
``inertia``, URDF and MJCF ``<inertial>`` placed in the ground frame at the drawn pose and
merged over rigid joints (the parallel-axis theorem, checked against sums written here),
and the refusals of what no rigid body has, each naming the body."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mechsing.errors import MechanismError
from mechsing.model import loads
from mechsing.numeric import to_float
from mechsing.reader import mechanism_from_text
from tests.mechanisms import ARM_2R_JOINTS

ARM = (
    "mechanism: arm\nunits: {length: LEN}\n"
    + ARM_2R_JOINTS
    + """\
inputs: [A, B]
output: {body: fore}
mass:
  upper: {kg: 2, centre: [0.5, 0, 0], inertia: INERTIA}
  fore: {kg: 1}
"""
)


def _arm(inertia: str, length: str = "m", gravity: str = "") -> object:
    return loads(ARM.replace("INERTIA", inertia).replace("LEN", length) + gravity, path="arm.yaml")


def _inertia(mech: object, body: str) -> np.ndarray:
    got = dict(mech.weights.inertias)[body]  # type: ignore[attr-defined]
    return np.array(to_float(np.array(got, dtype=object)), dtype=float)


def test_six_numbers_and_a_matrix_give_the_same_inertia() -> None:
    six = _arm("[0.1, 0.2, 0.25, 0.01, 0, -0.02]")
    mat = _arm("[[0.1, 0.01, 0], [0.01, 0.2, -0.02], [0, -0.02, 0.25]]")
    want = np.array([[0.1, 0.01, 0], [0.01, 0.2, -0.02], [0, -0.02, 0.25]])
    assert np.array_equal(_inertia(six, "upper"), want)
    assert np.array_equal(_inertia(mat, "upper"), want)
    assert dict(six.weights.inertias).keys() == {"upper"}  # fore: a point mass


def test_inertia_is_scaled_by_the_length_unit_squared() -> None:
    mech = _arm("[1000, 2000, 2500, 0, 0, 0]", length="mm")
    assert np.allclose(_inertia(mech, "upper"), np.diag([1e-3, 2e-3, 2.5e-3]), rtol=1e-15)


def test_inertia_without_gravity_gives_masses_that_weigh_nothing() -> None:
    mech = _arm("[0.1, 0.2, 0.25, 0, 0, 0]")
    assert mech.weights.gravity is None and not mech.weights.weighs
    weighed = _arm("[0.1, 0.2, 0.25, 0, 0, 0]", gravity="gravity: [0, -9.81, 0]\n")
    assert weighed.weights.weighs


def test_mass_without_gravity_or_inertia_is_still_refused() -> None:
    text = ARM.replace(", inertia: INERTIA", "").replace("LEN", "m")
    with pytest.raises(MechanismError, match="mass needs gravity"):
        loads(text, path="arm.yaml")


@pytest.mark.parametrize(
    ("inertia", "words"),
    [
        ("[[0.1, 0.01, 0], [0, 0.2, 0], [0, 0, 0.25]]", "not symmetric"),
        ("[0.1, 0.1, 0.1, 0.2, 0, 0]", "negative principal moment"),
        ("[0.1, 0.1, 0.3, 0, 0, 0]", "triangle inequality"),
        ("[0.1, 0.1]", "6 numbers"),
    ],
)
def test_what_no_rigid_body_has_is_refused_naming_the_body(inertia: str, words: str) -> None:
    with pytest.raises(MechanismError, match=words) as exc:
        _arm(inertia)
    assert "'upper'" in str(exc.value)


def test_a_thin_rod_on_the_triangle_inequality_passes() -> None:
    _arm("[0, 0.1, 0.1, 0, 0, 0]")  # I1 = 0, I2 = I3: a rod along x


def test_negative_mass_is_refused() -> None:
    with pytest.raises(MechanismError, match="must not be negative"):
        loads(
            ARM.replace("kg: 2", "kg: -2")
            .replace("INERTIA", "[0, 0, 0, 0, 0, 0]")
            .replace("LEN", "m")
        )


URDF = """\
<robot name="t">
 <link name="base"><inertial><mass value="50"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
 <link name="l1"><inertial><origin xyz="0.5 0 0" rpy="0 0 1.5707963267948966"/><mass value="2"/>
   <inertia ixx="0.1" iyy="0.2" izz="0.25" ixy="0" ixz="0" iyz="0"/></inertial></link>
 <link name="l2"><inertial><origin xyz="0.1 0 0"/><mass value="1"/>
   <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
 <link name="l3"><inertial><mass value="1"/>
   <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
 <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.1"/><axis xyz="0 0 1"/></joint>
 <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="1 0 0"/><axis xyz="0 0 1"/></joint>
 <joint name="f" type="fixed"><parent link="l2"/><child link="l3"/><origin xyz="0.5 0 0"/></joint>
</robot>
"""


def test_urdf_inertials_are_placed_in_ground_axes_and_merged_over_fixed_joints() -> None:
    mech = mechanism_from_text(URDF, path="t.urdf")
    masses = {
        b: (float(kg), np.array(to_float(np.array(c, dtype=object)), dtype=float))
        for b, kg, c in mech.weights.masses
    }
    assert set(masses) == {"l1", "l2"}  # the root link is the ground: left out
    assert masses["l1"][0] == 2 and np.allclose(masses["l1"][1], [0.5, 0, 0.1])
    # the inertial frame turned 90 deg about z: ixx and iyy exchange
    assert np.allclose(_inertia(mech, "l1"), np.diag([0.2, 0.1, 0.25]), atol=1e-15)
    # l2 and l3 (fixed): 1 kg at x = 1.1 and 1 kg at x = 1.5 -> 2 kg at 1.3, and each
    # 0.01 plus 1 kg at 0.2 m about y and z: 0.01 + 0.04
    assert masses["l2"][0] == 2 and np.allclose(masses["l2"][1], [1.3, 0, 0.1])
    assert np.allclose(_inertia(mech, "l2"), np.diag([0.02, 0.1, 0.1]), atol=1e-15)
    assert not mech.weights.weighs  # a URDF gives no gravity


def test_a_negative_urdf_mass_is_refused_with_the_link_and_line() -> None:
    with pytest.raises(MechanismError) as exc:
        mechanism_from_text(
            URDF.replace('<mass value="2"/>', '<mass value="-2"/>', 1), path="t.urdf"
        )
    assert str(exc.value).startswith("t.urdf:3: <mass>: link 'l1': the mass is -2")


def test_a_urdf_inertia_no_rigid_body_has_is_a_point_mass_with_a_note(tmp_path) -> None:
    """Moments 0.1, 0.1, 0.25 break the triangle inequality (0.25 > 0.1 + 0.1): no mass
    distribution has them.  URDF files in use carry such inertias (a dummy izz alone:
    anymal, go1, b1, hyq, pr2, the allegro hands of example-robot-data), so the link is
    kept as its 2 kg at its centre of mass, with a note naming link, line and problem,
    not the robot refused."""
    from tests.cli import run_cli

    text = URDF.replace('ixx="0.1" iyy="0.2" izz="0.25"', 'ixx="0.1" iyy="0.1" izz="0.25"', 1)
    mech = mechanism_from_text(text, path="t.urdf")
    masses = {b: (kg, c) for b, kg, c in mech.weights.masses}
    assert masses["l1"][0] == 2
    assert np.allclose(_inertia(mech, "l1"), np.zeros((3, 3)), atol=0)
    path = tmp_path / "t.urdf"
    path.write_text(text)
    run = run_cli(["analyze", path])
    assert run.status in (0, 1), run.err
    run = run_cli(["convert", path])
    assert run.status == 0, run.err
    assert "link 'l1' (line 4): the <inertia> has principal moments" in run.out
    assert "read as a point mass of 2 kg at its centre of mass" in run.out


MJCF = """\
<mujoco model="m">
  <compiler angle="radian"/>
  <worldbody>
    <body name="a" pos="0 0 1" quat="0.7071067811865476 0 0 0.7071067811865476">
      <joint name="A" type="hinge" axis="0 0 1"/>
      <inertial pos="1 0 0" mass="3" diaginertia="0.1 0.2 0.3"/>
      <body name="b" pos="2 0 0">
        <joint name="B" type="hinge" axis="0 0 1"/>
        <inertial pos="0 0 0" mass="1" fullinertia="0.1 0.2 0.25 0.01 0 0"/>
      </body>
    </body>
  </worldbody>
</mujoco>
"""


def test_mjcf_inertials_in_the_body_frames() -> None:
    mech = mechanism_from_text(MJCF, path="m.xml")
    masses = {
        b: np.array(to_float(np.array(c, dtype=object)), dtype=float)
        for b, _, c in mech.weights.masses
    }
    # body a turned 90 deg about z at (0, 0, 1): its centre (1, 0, 0) is at (0, 1, 1)
    assert np.allclose(masses["a"], [0, 1, 1]) and np.allclose(masses["b"], [0, 2, 1])
    assert np.allclose(_inertia(mech, "a"), np.diag([0.2, 0.1, 0.3]), atol=1e-15)
    # a full inertia turned by 90 deg about z: (x, y) -> (-y, x)
    R = np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1.0]])
    full = np.array([[0.1, 0.01, 0], [0.01, 0.2, 0], [0, 0, 0.25]])
    assert np.allclose(_inertia(mech, "b"), R @ full @ R.T, atol=1e-15)


def test_mjcf_inertia_from_geoms_is_not_written_and_the_conversion_says_why() -> None:
    from mechsing.formats import xml_to_yaml

    text = (Path(__file__).resolve().parents[1] / "examples" / "fourbar_mjcf.xml").read_text()
    yaml = xml_to_yaml(text, "fourbar_mjcf.xml")
    assert "inertiafromgeom" in yaml and "\nmass:" not in yaml
    assert mechanism_from_text(text, path="fourbar_mjcf.xml").weights is None
