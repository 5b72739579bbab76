"""The edges of the input: every command reads every format the same way, symbolic
parameters wherever a number goes (a P joint's axis, a DH row), as a user runs them.

The expected conditions are closed forms derived by hand: the UR5's elbow and wrist
(sin(joint3) = 0, sin(joint5) = 0), a planar 2R arm's elbow (l1*l2*sin(theta2) = 0) and the
quick-return's dead centres (the crank perpendicular to the rocker).
"""

from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import pytest
import sympy

import mechsing
import mechsing.reader
from mechsing.model import MechanismError, loads
from tests.cli import run_cli, run_cli_subprocess
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


def test_the_yaml_reader_sends_a_dh_table_to_the_one_reader() -> None:
    with pytest.raises(MechanismError, match=r"<text>:3: dh: a DH table.*mechsing.load"):
        loads(DH_2R)
    assert mechsing.reader.mechanism_from_text(DH_2R).joint_names == ("J1", "J2")


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


def test_a_function_of_a_symbol_in_a_prismatic_axis(tmp_path: Path) -> None:
    """The slider's axis [cos(phi), sin(phi), 0] with phi symbolic: the crank (at angle A
    from the drawn pose) is perpendicular to the slider when A + phi = +-pi/2, i.e.
    cos(A + phi) = 0, and the constant is r = 1/10 (the axis has length 1)."""
    text = QUICK_RETURN.replace("{r: 0.1, d: 0.3}", "{r: 0.1, d: 0.3, phi: 0.3}").replace(
        "axis: [r, d, 0]", 'axis: ["cos(phi)", "sin(phi)", 0]'
    )
    path = _write(tmp_path, "quick_return.yaml", text)
    rc, out, err = run_cli(["condition", str(path), "--symbolic", "phi", "--format", "json"])
    assert rc == 0, err
    data = json.loads(out)
    a, phi = sympy.symbols("A phi")
    (type1,) = _factors(data, "input (type I)")
    assert _same_up_to_sign(type1, sympy.cos(a + phi)), type1
    cond = next(c for c in data["conditions"] if c["name"] == "input (type I)")
    assert abs(sympy.sympify(cond["constant"])) == sympy.Rational(1, 10)


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


# --------------------------------------------------------------------------- item 5 (of 27)

#: two hinged links; the equality element is put in EQUALITY
MJCF = """\
<mujoco model="m">
  <worldbody>
    <body name="a"><joint name="J1" type="hinge" axis="0 0 1"/>
      <site name="sa" pos="0.5 0 0"/>
      <body name="b" pos="1 0 0"><joint name="J2" type="hinge" axis="0 0 1"/>
        <site name="sb" pos="1 0 0"/>
      </body>
    </body>
    <site name="sw" pos="2 0 0"/>
  </worldbody>
  <equality>
    {equality}
  </equality>
</mujoco>
"""


@pytest.mark.parametrize(
    ("equality", "problem"),
    [
        ('<connect body1="b" body2="world"/>', "lacks 'anchor'"),
        ('<connect anchor="1 0 0" body2="world"/>', "lacks 'body1'"),
        ('<connect site1="sb"/>', "lacks 'site2'"),
        ('<connect body1="b" anchor="1 0 0" site1="sb" site2="sw"/>', "mixes"),
        ("<connect/>", "gives none of body1+anchor or site1+site2"),
        ('<weld body2="b"/>', "gives none of body1 or site1+site2"),
    ],
)
def test_mujoco_equality_needs_the_attributes_its_reference_requires(
    tmp_path: Path, equality: str, problem: str
) -> None:
    """MuJoCo's XML reference: a connect is body1 with anchor (in body1's frame) or site1
    with site2; a weld is body1 or site1 with site2.  A connect without anchor used to put
    the S joint at body1's origin, silently."""
    path = _write(tmp_path, "m.xml", MJCF.format(equality=equality))
    rc, out, err = run_cli(["analyze", str(path)])
    assert rc == 2 and out == "", err
    element = equality.split()[0].rstrip("/>")
    assert f"{path}:12: {element}>" in err and problem in err, err


def test_a_connect_by_sites_is_the_connect_by_body_and_anchor(tmp_path: Path) -> None:
    """site1 + site2 and body1 + anchor at the same point give the same loop (the anchor is
    site sb's position in b's frame)."""
    by_sites = _write(tmp_path, "s.xml", MJCF.format(equality='<connect site1="sb" site2="sw"/>'))
    by_body = _write(
        tmp_path, "b.xml", MJCF.format(equality='<connect body1="b" body2="world" anchor="1 0 0"/>')
    )
    a, b = mechsing.load(by_sites), mechsing.load(by_body)
    assert [j.params for j in a.joints] == [j.params for j in b.joints]


@pytest.mark.parametrize(
    ("change", "problem"),
    [
        (('<axis xyz="0 0 1"/>', "<axis/>"), "<axis> lacks 'xyz'"),
        (('<robot name="arm">', "<robot>"), "<robot> lacks 'name'"),
        (('type="revolute"', ""), "unknown joint type None"),
        (('<child link="b"/>', ""), 'needs <child link="..."/>'),
    ],
)
def test_urdf_elements_need_the_attributes_the_specification_requires(
    tmp_path: Path, change: tuple[str, str], problem: str
) -> None:
    """The URDF specification (wiki.ros.org/urdf/XML): a robot and a joint have a name, a
    joint a type, a parent and a child link; an <axis> element has its xyz."""
    text = (
        '<robot name="arm"><link name="a"/><link name="b"/>\n'
        '<joint name="J1" type="revolute"><parent link="a"/><child link="b"/>'
        '<axis xyz="0 0 1"/></joint></robot>\n'
    )
    path = _write(tmp_path, "arm.urdf", text.replace(*change))
    rc, out, err = run_cli(["analyze", str(path)])
    assert rc == 2 and out == "", err
    assert str(path) in err and problem in err, err


# --------------------------------------------------------------------------- item 11, 28.7

COMMANDS_READING = ("analyze", "solve", "sweep", "report", "condition", "modes")


def _option_help(command: str, option: str) -> str:
    from mechsing.cli import build_parser

    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command").choices[command]  # type: ignore[attr-defined]
    return next(a.help for a in sub._actions if option in a.option_strings)


@pytest.mark.parametrize("option", ["--time-limit", "--precision", "-v", "--set"])
def test_shared_options_have_one_declaration(option: str) -> None:
    """--time-limit, -v and --set say the same on every command that reads a mechanism
    (declared once, in cli/options.py); --precision names the modes each command takes."""
    helps = {
        c: _option_help(c, option)
        for c in COMMANDS_READING
        if c != "condition" or option != "--precision"
    }
    if option == "--precision":
        assert all("mp:N" in h for h in helps.values()), helps
    else:
        assert len(set(helps.values())) == 1, helps


@pytest.mark.parametrize(
    "value", ["1e308", "1e-6", "0", "-5", "inf", "nan", "1_000", "３０", "abc"]
)
@pytest.mark.parametrize("command", COMMANDS_READING)
def test_a_time_limit_out_of_range_is_refused(command: str, value: str) -> None:
    """The accepted range is 0.01 s to 1e6 s (1e308 overflowed the timer: exit 4; 1e-6 killed
    the process with SIGALRM, exit 142); ASCII decimal numbers only."""
    argv = [command, str(EXAMPLES / "fourbar.yaml"), "--time-limit", value]
    argv += {"solve": ["--config", "reference"], "sweep": ["--vary", "A=0:10:1"]}.get(command, [])
    with pytest.raises(SystemExit) as exc:
        run_cli(argv)
    assert exc.value.code == 2


def test_a_stopped_solve_is_exit_3_not_a_killed_process() -> None:
    """`solve --precision mp:N --time-limit S` stops with exit 3 and says so (as the user
    runs it: a process of its own, where a stray SIGALRM would kill it)."""
    rc, out, err = run_cli_subprocess(
        [
            "solve",
            EXAMPLES / "bricard.yaml",
            "--config",
            "reference",
            "--precision",
            "mp:3000",
            "--time-limit",
            "0.01",
        ]
    )
    assert rc == 3, (rc, err)
    assert "stopped by the time limit after 0.01 s" in err and out == ""


def test_a_short_time_limit_stops_exact_analysis_with_exit_3() -> None:
    """Stopped while preparing the exact geometry or while analysing a configuration: exit
    3 (not analysed) with the reason, never a process killed by its alarm."""
    rc, _out, err = run_cli_subprocess(
        ["analyze", EXAMPLES / "bricard.yaml", "--precision", "exact", "--time-limit", "0.01"]
    )
    assert rc == 3, (rc, err)
    assert "within 0.01 s" in err or "stopped after 0.01 s" in err, err


def test_the_time_limit_stops_condition_and_the_classification_of_a_sweep() -> None:
    rc, out, err = run_cli(["condition", str(EXAMPLES / "ur5.urdf"), "--time-limit", "0.01"])
    assert rc == 3 and out == "", err
    assert "stopped by the time limit after 0.01 s" in err
    rc, out, err = run_cli(
        [
            "sweep",
            str(EXAMPLES / "fourbar.yaml"),
            "--vary",
            "A=0:360:2",
            "--quiet",
            "--precision",
            "mp:200",
            "--time-limit",
            "0.01",
        ]
    )
    assert rc == 3, err
    assert "not analysed: configuration 'located-1': stopped by the time limit" in out
    assert "stopped by the time limit after 0.01 s" in err


def test_report_sweeps_a_joint_over_its_limits_as_sweep_does(tmp_path: Path) -> None:
    """`report FILE.urdf --vary joint3` (no range: the joint's limits, as for `sweep`)."""
    out_path = tmp_path / "r.md"
    rc, _out, err = run_cli(
        [
            "report",
            str(EXAMPLES / "ur5.urdf"),
            "--vary",
            "joint3",
            "-o",
            str(out_path),
            "--precision",
            "float",
        ]
    )
    assert rc == 0, err
    text = out_path.read_text()
    assert "joint3" in text and "-6.283" in text


# --------------------------------------------------------------------------- item 14


def test_a_radian_looking_range_in_a_degree_file_is_warned_about(tmp_path: Path) -> None:
    """In a degree file, -3.14 is pi written in radians: warned about (as analyze warns
    about a plain angle above a full turn in a radian file), with the range in degrees."""
    path = ROOT / "tests" / "data" / "fourbar_deg.yaml"
    vary = ["--vary", "A=-3.14:1.5:0.01", "--precision", "float"]
    for argv in (
        ["sweep", path, *vary, "--quiet"],
        ["report", path, *vary, "--config", "reference", "-o", tmp_path / "r.md"],
    ):
        rc, _out, err = run_cli(argv)
        assert rc == 0, err
        assert "warning: --vary A=-3.14:1.5:0.01: the range looks like radians" in err, err
        assert "--vary A=-179.909:85.9437:0.572958" in err
    rc, _out, err = run_cli(["sweep", str(path), "--vary", "A=0:90:1", "--quiet"])
    assert rc == 0 and "warning" not in err, err


def test_a_sweep_beyond_a_joints_limits_says_so_per_sample_and_in_its_notes(
    tmp_path: Path,
) -> None:
    """limits {A: [-30, 60]} (degrees): of the samples 0, 10, ..., 90 deg, those above 60
    (70, 80, 90) are beyond them."""
    text = (ROOT / "tests" / "data" / "fourbar_deg.yaml").read_text()
    path = _write(
        tmp_path,
        "f.yaml",
        text.replace("configurations:", "limits: {A: [-30, 60]}\nconfigurations:"),
    )
    data = json.loads(
        run_cli(
            [
                "sweep",
                str(path),
                "--vary",
                "A=0:90:10",
                "--quiet",
                "--precision",
                "float",
                "--format",
                "json",
            ]
        ).out
    )
    from mechsing.sweeps.schema import sweep_schema

    jsonschema.validate(data, sweep_schema())
    beyond = [p["outside_limits"] for p in data["points"]]
    assert beyond == [[]] * 7 + [["A"]] * 3
    assert any("leaves the limits of A ([-30, 60] deg) at 3 of its 10" in n for n in data["notes"])
    rc, out, _err = run_cli(
        ["sweep", str(path), "--vary", "A=0:90:10", "--quiet", "--format", "csv"]
    )
    lines = out.splitlines()
    assert lines[0].endswith(",outside limits")
    assert [ln.rsplit(",", 1)[1] for ln in lines[1:11]] == [""] * 7 + ["A"] * 3


def test_condition_takes_set_as_the_other_commands(tmp_path: Path) -> None:
    """`condition --set O2=asin(-1/3)` evaluates the factors at that ad-hoc configuration
    (cli), symbols kept: the quick-return's dead centre, sin(O2) = -r/d."""
    path = _write(tmp_path, "quick_return.yaml", QUICK_RETURN)
    rc, out, err = run_cli(
        ["condition", str(path), "--symbolic", "r,d", "--set", "O2=asin(-1/3)", "--format", "json"]
    )
    assert rc == 0, err
    data = json.loads(out)
    assert data["configuration"] == "cli"
    vanish = {c["name"]: [f["vanishes"] for f in c["factors"]] for c in data["conditions"]}
    # the joint-variable conditions, and (the slide's symbolic axis now eliminated) the
    # input's condition in the input O2 alone, which vanishes at the dead centre too
    assert vanish == {
        "input (type I)": [True],
        "output (type II)": [False],
        "input (type I) in the input O2": [True],
    }
    assert _option_help("condition", "--set") == _option_help("analyze", "--set")
