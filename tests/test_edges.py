"""The edges of the input: every command reads every format the same way, symbolic
parameters wherever a number goes (a P joint's axis, a DH row), as a user runs them.

The expected conditions are closed forms derived by hand: the UR5's elbow and wrist
(sin(joint3) = 0, sin(joint5) = 0), a planar 2R arm's elbow (l1*l2*sin(theta2) = 0) and the
quick-return's dead centres (the crank perpendicular to the rocker).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import sympy

import mechsing
from mechsing.model import MechanismError, loads
from tests.cli import run_cli
from tests.mechanisms import ROOT

EXAMPLES = ROOT / "examples"

#: a Whitworth quick-return: crank O2-A of length r about the origin, a block pivoted at A
#: sliding along the rocker, the rocker pivoted at O4 = (0, -d); the slider's axis is the
#: rocker's direction at the drawn pose, A - O4 = (r, d), written with the parameters
QUICK_RETURN = """\
mechanism: quick_return
parameters: {r: 0.1, d: 0.3}
bodies: [ground, crank, block, rocker]
ground: ground
joints:
  - {name: O2, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: A, type: R, between: [crank, block], axis: [0, 0, 1], point: [r, 0, 0]}
  - {name: S, type: P, between: [rocker, block], axis: [r, d, 0]}
  - {name: O4, type: R, between: [ground, rocker], axis: [0, 0, 1], point: [0, -d, 0]}
inputs: [O2]
output: {body: rocker}
configurations:
  dead: {O2: "asin(-1/3)"}
"""

#: a planar 2R arm as a DH table whose link lengths are named parameters
DH_2R = """\
mechanism: planar_2r
parameters: {len1: 0.4, len2: 0.3}
dh:
  rows:
    - {theta: 0, d: 0, a: len1, alpha: 0}
    - {theta: 0, d: 0, a: len2, alpha: 0}
output: {body: L2, point: [len1 + len2, 0, 0]}
configurations:
  folded: {J1: 0.3, J2: pi}
  bent: {J1: 0.3, J2: 0.8}
"""


def _write(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def _factors(data: dict, name: str) -> list[sympy.Expr]:
    cond = next(c for c in data["conditions"] if c["name"] == name)
    # the joint S is not sympy's S
    return [sympy.sympify(f["expression"], {"S": sympy.Symbol("S")}) for f in cond["factors"]]


def _same_up_to_sign(a: sympy.Expr, b: sympy.Expr) -> bool:
    return sympy.simplify(a - b) == 0 or sympy.simplify(a + b) == 0


# --------------------------------------------------------------------------- item 1


def test_condition_reads_a_urdf_file_as_analyze_does() -> None:
    """`condition` on the bundled URDF (it used to exit 4, "malformed YAML"): the UR5's
    singularities are the elbow sin(q3) = 0 and the wrist sin(q5) = 0, with a shoulder
    factor (Hawkins, "Analytic inverse kinematics for the Universal Robots")."""
    rc, out, err = run_cli(["condition", str(EXAMPLES / "ur5.urdf"), "--format", "json"])
    assert rc == 0, err
    factors = _factors(json.loads(out), "output Jacobian (output twist)")
    q3, q5 = sympy.symbols("joint3 joint5")
    assert any(_same_up_to_sign(f, sympy.sin(q3)) for f in factors), factors
    assert any(_same_up_to_sign(f, sympy.sin(q5)) for f in factors), factors
    assert len(factors) == 3


def test_condition_of_an_mjcf_file_is_read_by_the_same_reader() -> None:
    """The bundled MJCF four-bar names no output: the same exit 2 as any file without one."""
    rc, out, err = run_cli(["condition", str(EXAMPLES / "fourbar_mjcf.xml")])
    assert rc == 2 and out == ""
    assert "fourbar_mjcf.xml" in err and "no output" in err


def test_the_python_api_reads_every_format() -> None:
    """mechsing.load, analyze and condition take a URDF path as the commands do."""
    mech = mechsing.load(EXAMPLES / "ur5.urdf")
    assert len(mech.joints) == 6 and mech.warnings == ()
    result = mechsing.analyze(EXAMPLES / "ur5.urdf", precision="float")
    assert not result.failed
    cond = mechsing.condition(str(EXAMPLES / "ur5.urdf"))
    assert cond.method == "open chain"


def test_the_yaml_reader_sends_xml_to_the_one_reader() -> None:
    """mechsing.model reads mechsing YAML and JSON only; XML text gets a message naming the
    reader that takes it (not "malformed YAML")."""
    text = (EXAMPLES / "ur5.urdf").read_text()
    with pytest.raises(MechanismError, match="mechsing.load"):
        loads(text, path="ur5.urdf")


def test_warnings_of_a_file_reach_condition_as_analyze(tmp_path: Path) -> None:
    """A likely mistake (an angle above a full turn in a file in radians) is warned about by
    `condition` as by `analyze`: the same reader, the same warnings."""
    text = DH_2R.replace("bent: {J1: 0.3, J2: 0.8}", "bent: {J1: 0.3, J2: 45}")
    path = _write(tmp_path, "arm.yaml", text)
    warnings = []
    for command in ("analyze", "condition"):
        rc, _out, err = run_cli([command, str(path)])
        assert rc == 0, err
        warnings.append([line for line in err.splitlines() if "warning" in line])
    assert warnings[0] and warnings[0] == warnings[1]


# --------------------------------------------------------------------------- item 2


def test_symbols_in_a_prismatic_axis(tmp_path: Path) -> None:
    """`condition --symbolic r,d` with the slider's axis [r, d, 0] (normalised by
    sqrt(r**2 + d**2), a positive factor; it used to exit 4 with a PolynomialError).

    By hand: the rocker stands still (type I) when the crank is perpendicular to the rocker;
    the relative angle A of crank and block is then pi/2 - atan2(d, r) from the drawn pose,
    i.e. d*sin(A) - r*cos(A) = 0.  The passive joints stop being determined (type II) when
    the block reaches the rocker's pivot, S = -|A - O4| = -sqrt(r**2 + d**2)."""
    path = _write(tmp_path, "quick_return.yaml", QUICK_RETURN)
    rc, out, err = run_cli(["condition", str(path), "--symbolic", "r,d", "--format", "json"])
    assert rc == 0, err
    data = json.loads(out)
    r, d, a, s = sympy.symbols("r d A S")
    (type1,) = _factors(data, "input (type I)")
    assert _same_up_to_sign(type1, d * sympy.sin(a) - r * sympy.cos(a)), type1
    (type2,) = _factors(data, "output (type II)")
    assert type2.free_symbols == {r, d, s}
    assert sympy.simplify(type2.subs(s, -sympy.sqrt(r**2 + d**2))) == 0
    # at the dead centre of the file (sin O2 = -r/d) the type I factor vanishes
    rc, out, err = run_cli(["condition", str(path), "--symbolic", "r,d", "--config", "dead"])
    assert rc == 0, err
    assert "at dead: " in out and "(vanishes)" in out.split("type II")[0]


# --------------------------------------------------------------------------- item 3


def test_named_parameters_in_a_dh_row(tmp_path: Path) -> None:
    """A DH row may use the file's parameters; `condition --symbolic` keeps them: the planar
    2R arm's Jacobian determinant is l1*l2*sin(theta2)."""
    path = _write(tmp_path, "arm.yaml", DH_2R)
    rc, out, err = run_cli(["analyze", str(path), "--precision", "float"])
    assert rc == 0, err
    assert "Configuration folded" in out and "Configuration bent" in out
    rc, out, err = run_cli(["condition", str(path), "--symbolic", "len1,len2", "--format", "json"])
    assert rc == 0, err
    data = json.loads(out)
    cond = data["conditions"][0]
    l1, l2, q2 = sympy.symbols("len1 len2 J2")
    expr = sympy.sympify(cond["expression"])
    assert _same_up_to_sign(expr, l1 * l2 * sympy.sin(q2)), expr
    rc, out, err = run_cli(["condition", str(path), "--config", "folded"])
    assert rc == 0, err
    assert "(vanishes)" in out


def test_a_parameter_may_not_take_a_name_the_dh_table_gives(tmp_path: Path) -> None:
    """The table names its joints J1, J2 and bodies L0..L2: a parameter called J2 clashes."""
    path = _write(tmp_path, "arm.yaml", DH_2R.replace("len2: 0.3}", "len2: 0.3, J2: 1}"))
    rc, out, err = run_cli(["analyze", str(path)])
    assert rc == 2 and out == ""
    assert "parameter 'J2'" in err and "clashes with the joint 'J2'" in err
