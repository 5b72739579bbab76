"""MJCF: closed chains through <equality><connect>, frames, defaults and units as MuJoCo
defines them.

A connect constraint is a spherical joint at its anchor: the four-bar and the 3-RPR written
as MJCF must give the same verdicts (mobility, ranks, singularity classes) as YAML files
written here by hand with an S joint at each anchor.  Frame conventions are checked on
axes worked out by hand (rotations by quarter turns).
"""

from __future__ import annotations

import json

import pytest

from mechsing.reader import mechanism_from_text
from tests.cli import run_cli

FOURBAR_YAML = """\
mechanism: fourbar-s
units: {angle: deg}
bodies: [world, crank, coupler, rocker]
joints:
  - {name: A, type: R, between: [world, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, coupler], axis: [0, 0, 1], point: [1, 0, 0]}
  - {name: D, type: R, between: [world, rocker], axis: [0, 0, 1], point: [4, 0, 0]}
  - {name: C, type: S, between: [coupler, rocker], point: [3, 2, 0]}
inputs: [A]
configurations: {reference: {}}
"""

RPR_MJCF = """\
<mujoco model="3rpr">
  <compiler angle="radian"/>
  <worldbody>
    <body name="cyl1"><joint name="Rb1" type="hinge" axis="0 0 1"/>
      <body name="pis1"><joint name="P1" type="slide" axis="0.9 0.3 0"/>
        <body name="platform"><joint name="Rp1" pos="0.9 0.3 0" axis="0 0 1"/></body>
      </body>
    </body>
    <body name="cyl2" pos="4 0 0"><joint name="Rb2" axis="0 0 1"/>
      <body name="pis2" pos="-4 0 0"><joint name="P2" type="slide" axis="-1.5 1.5 0"/></body>
    </body>
    <body name="cyl3" pos="0 2 0"><joint name="Rb3" pos="0 2 0" axis="0 0 1"/>
      <body name="pis3" pos="0 -2 0"><joint name="P3" type="slide" axis="-0.3 -2.1 0"/></body>
    </body>
  </worldbody>
  <equality>
    <connect name="Rp2" body1="platform" body2="pis2" anchor="2.5 1.5 0"/>
    <connect name="Rp3" body1="pis3" body2="platform" anchor="-0.3 1.9 0"/>
  </equality>
  <actuator><motor joint="P1"/><motor joint="P2"/><motor joint="P3"/></actuator>
</mujoco>
"""

RPR_YAML = """\
mechanism: 3rpr-s
bodies: [world, cyl1, pis1, platform, cyl2, pis2, cyl3, pis3]
joints:
  - {name: Rb1, type: R, between: [world, cyl1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: P1, type: P, between: [cyl1, pis1], axis: [0.9, 0.3, 0]}
  - {name: Rp1, type: R, between: [pis1, platform], axis: [0, 0, 1], point: [0.9, 0.3, 0]}
  - {name: Rb2, type: R, between: [world, cyl2], axis: [0, 0, 1], point: [4, 0, 0]}
  - {name: P2, type: P, between: [cyl2, pis2], axis: [-1.5, 1.5, 0]}
  - {name: Rb3, type: R, between: [world, cyl3], axis: [0, 0, 1], point: [0, 4, 0]}
  - {name: P3, type: P, between: [cyl3, pis3], axis: [-0.3, -2.1, 0]}
  - {name: Rp2, type: S, between: [platform, pis2], point: [2.5, 1.5, 0]}
  - {name: Rp3, type: S, between: [pis3, platform], point: [-0.3, 1.9, 0]}
inputs: [P1, P2, P3]
configurations: {reference: {}}
"""


def _verdicts(path: str, sets: list[str]) -> list[dict]:
    argv = ["analyze", path, "--format", "json"]
    for s in sets:
        argv += ["--set", s]
    r = run_cli(argv)
    assert r.status == 0, r.err
    out = []
    for c in json.loads(r.out)["configurations"]:
        out.append(
            {
                "name": c["name"],
                "mobility": c["mobility"],
                "closure_rank": c["closure_rank"]["rank"],
                "loops": sorted((lp["rank"], lp["subgroup"]["type"]) for lp in c["loops"]),
                "classes": sorted(s["class"] for s in c["singularities"]),
            }
        )
    return out


@pytest.mark.parametrize(
    ("mjcf", "yaml_text", "sets"),
    [
        ("examples/fourbar_mjcf.xml", FOURBAR_YAML, ["A=30"]),
        ("examples/fourbar_mjcf.xml", FOURBAR_YAML, ["A=200"]),
        (None, RPR_YAML, ["P1=0.1", "P2=-0.1", "P3=0.05"]),
    ],
)
def test_connect_is_a_spherical_joint(mjcf: str | None, yaml_text: str, sets, tmp_path) -> None:
    if mjcf is None:
        mjcf = str(tmp_path / "rpr.xml")
        (tmp_path / "rpr.xml").write_text(RPR_MJCF)
    y = tmp_path / "s.yaml"
    y.write_text(yaml_text)
    got, want = _verdicts(mjcf, sets), _verdicts(str(y), sets)
    assert got == want
    assert got[0]["mobility"]["finite"] >= 1


def test_the_four_bar_closes_like_the_yaml_four_bar() -> None:
    """Crank at 30 deg: the coupler angle B of examples/fourbar.yaml (written independently)."""
    a = run_cli(["solve", "examples/fourbar_mjcf.xml", "--set", "A=30", "--format", "json"])
    b = run_cli(["solve", "examples/fourbar.yaml", "--config", "crank-30", "--format", "json"])
    assert a.status == b.status == 0, a.err + b.err
    ja, jb = json.loads(a.out)["joints"], json.loads(b.out)["joints"]
    assert abs(ja["B"][0] - jb["B"][0]) < 1e-9
    assert abs(ja["D"][0] + jb["D"][0]) < 1e-9  # D is [world, rocker] here, [rocker, ground] there


def _axis(xml_body: str, compiler: str = "") -> tuple[float, ...]:
    text = f"<mujoco>{compiler}<worldbody>{xml_body}</worldbody></mujoco>"
    mech = mechanism_from_text(text, path="frames.xml")
    return tuple(round(float(c), 12) + 0.0 for c in mech.joints[0].params["axis"])


@pytest.mark.parametrize(
    ("body", "compiler", "axis"),
    [
        ('<body euler="0 0 90"><joint axis="1 0 0"/></body>', "", (0, 1, 0)),  # degrees default
        (
            '<body euler="0 0 1.5707963267948966"><joint axis="1 0 0"/></body>',
            '<compiler angle="radian"/>',
            (0, 1, 0),
        ),
        ('<body quat="0.7071067811865476 0 0.7071067811865476 0"><joint/></body>', "", (1, 0, 0)),
        ('<body axisangle="1 0 0 90"><joint/></body>', "", (0, -1, 0)),
        ('<body xyaxes="0 1 0 -1 0 0"><joint axis="1 0 0"/></body>', "", (0, 1, 0)),
        ('<body zaxis="1 0 0"><joint/></body>', "", (1, 0, 0)),
        # intrinsic x then y: Rx(90) Ry(90) z = x; extrinsic: Ry(90) Rx(90) z = -y
        ('<body euler="90 90 0"><joint/></body>', "", (1, 0, 0)),
        ('<body euler="90 90 0"><joint/></body>', '<compiler eulerseq="XYZ"/>', (0, -1, 0)),
        # a quaternion or direction is normalised without overflow or underflow: scaled by
        # its largest component first (the plain norm of these is 0, or of 1e11-sized ones
        # fine, and must give the same frame as the unit ones above)
        ('<body quat="7e-201 0 7e-201 0"><joint/></body>', "", (1, 0, 0)),
        ('<body quat="7e10 0 7e10 0"><joint/></body>', "", (1, 0, 0)),
        ('<body zaxis="1e-300 0 0"><joint/></body>', "", (1, 0, 0)),
        ('<body xyaxes="0 1e-300 0 -1e-300 0 0"><joint axis="1 0 0"/></body>', "", (0, 1, 0)),
        ('<body axisangle="1e-300 0 0 90"><joint/></body>', "", (0, -1, 0)),
        # nested bodies compose their frames
        ('<body euler="0 0 90"><body euler="90 0 0"><joint/></body></body>', "", (1, 0, 0)),
    ],
)
def test_frames(body: str, compiler: str, axis: tuple[int, ...]) -> None:
    assert _axis(body, compiler) == tuple(float(a) for a in axis)


def test_default_classes_and_childclass() -> None:
    text = """<mujoco><default><joint axis="0 1 0" range="-10 20"/>
      <default class="s"><joint type="slide"/></default></default>
      <worldbody><body name="a" pos="1 0 0"><joint name="J1"/>
        <body name="b" childclass="s"><joint name="J2"/>
          <body name="c"><joint name="J3" class="main" axis="0 0 1" pos="0 0 1"/></body>
      </body></body></worldbody></mujoco>"""
    mech = mechanism_from_text(text, path="d.xml")
    types = {j.name: j.type for j in mech.joints}
    assert types == {"J1": "R", "J2": "P", "J3": "R"}
    assert tuple(float(c) for c in mech.joint("J2").params["axis"]) == (0.0, 1.0, 0.0)
    assert tuple(float(c) for c in mech.joint("J3").params["point"]) == (1.0, 0.0, 1.0)
    assert mech.units.angle == "deg"  # MuJoCo's default compiler angle
    assert mech.limits["J1"][0] == pytest.approx(
        (-10 * 3.141592653589793 / 180, 20 * 3.141592653589793 / 180)
    )
    assert mech.limits["J2"] == ((-10.0, 20.0),)  # a slide's range is a length (m)


def test_weld_and_jointless_bodies_merge() -> None:
    text = """<mujoco><worldbody>
      <body name="a"><joint name="J1"/><body name="a2" pos="1 0 0"/></body>
      <body name="b" pos="2 0 0"><joint name="J2"/></body></worldbody>
      <equality><weld body1="a2" body2="b"/></equality></mujoco>"""
    mech = mechanism_from_text(text, path="w.xml")
    assert mech.bodies == ("world", "a")
    assert [j.between for j in mech.joints] == [("world", "a"), ("world", "a")]


def test_free_ball_and_site_connect() -> None:
    text = """<mujoco><compiler angle="radian"/><worldbody>
      <body name="a" pos="0 0 1"><freejoint name="F"/>
        <body name="b" pos="1 0 0"><joint name="S" type="ball"/><site name="s1" pos="0.5 0 0"/>
        </body></body>
      <body name="c" pos="2 0 1"><joint name="H" axis="0 1 0"/><site name="s2" pos="-0.5 0 0"/>
      </body></worldbody>
      <equality><connect site1="s1" site2="s2"/></equality></mujoco>"""
    mech = mechanism_from_text(text, path="m.xml")
    assert [(j.name, j.type, j.between) for j in mech.joints] == [
        ("F", "D", ("world", "a")),
        ("S", "S", ("a", "b")),
        ("H", "R", ("world", "c")),
        ("connect1", "S", ("b", "c")),
    ]
    # the site s1 sits 0.5 along x from b, which is 1 along x from a, at height 1
    assert tuple(float(c) for c in mech.joint("connect1").params["point"]) == (1.5, 0.0, 1.0)


def test_urdf_floating_and_planar() -> None:
    text = """<robot name="f"><link name="w"/><link name="a"/><link name="b"/>
      <joint name="F" type="floating"><parent link="w"/><child link="a"/></joint>
      <joint name="G" type="planar"><parent link="a"/><child link="b"/>
        <origin rpy="1.5707963267948966 0 0"/><axis xyz="0 0 1"/></joint></robot>"""
    mech = mechanism_from_text(text, path="f.urdf")
    assert [j.type for j in mech.joints] == ["D", "G"]
    # the plane's normal: z of the joint frame turned by roll 90 deg about x is -y
    assert tuple(float(c) for c in mech.joint("G").params["normal"]) == (0.0, -1.0, 0.0)


def test_ref_shifts_the_joint_value_and_its_limits() -> None:
    """MuJoCo draws the model at qpos = ref: mechsing measures from the drawn pose."""
    text = """<mujoco><worldbody><body><joint name="J" ref="30" range="-60 90"/></body>
      </worldbody></mujoco>"""
    mech = mechanism_from_text(text, path="r.xml")
    lo, hi = mech.limits["J"][0]
    assert (round(lo * 180 / 3.141592653589793, 9), round(hi * 180 / 3.141592653589793, 9)) == (
        -90.0,
        60.0,
    )
