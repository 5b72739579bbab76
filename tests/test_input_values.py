"""Joint values as written in a file reach the analysis with their meaning, in every mode.

* A multi-dof joint value given as a displacement ``{rotation, translation}`` (decimals, or exact
  expressions) is accepted when it lies in the joint's subgroup *to the analysis mode's tolerance*
  (exactly only in exact mode); the coordinates that enter the analysis are its first-kind
  coordinates in the subgroup.  The expected coordinates here are derived independently of
  mechsing: the displacement of each test is built *from* chosen coordinates with the basis
  conventions of the mechanism file format (tests/reference) and mpmath's matrix
  exponential at 40 digits, then printed to 16 significant digits.
* A reference configuration may list values, when each is the identity.
* Unit trap: radian expressions (``pi``, inverse trigonometric functions) in a degree file are an
  error; a plain angle above a full turn in a radian file gets a warning.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import mpmath
import numpy as np
import pytest
import sympy
import yaml

import mechsing
from mechsing.cli import UserError, exit_status
from mechsing.kinematics import Closer, KinematicModel
from mechsing.model import MechanismError
from tests.cli import run_cli
from tests.reference.kinematics import J
from tests.reference.se3 import expm_mp, rotation_mp

from .mechanisms import EXAMPLES, _Dumper, _KeepNumbers, by_name, write

# ----------------------------------------------------------------------------- independent algebra

DIGITS = 40


def displacement(jtype: str, params: dict, q) -> np.ndarray:
    """exp(sum q_i e_i) of the joint at 40 digits (tests/reference: the format's basis screws,
    mpmath.expm of the 4x4 twist); the file's decimals are taken as the floats they parse to."""
    with mpmath.workdps(DIGITS):
        prm = {
            k: mpmath.mpf(v) if k == "pitch" else np.array([mpmath.mpf(x) for x in v])
            for k, v in params.items()
        }
        joint = J("J", jtype, "ground", "b", prm, mpmath.mpf(1))
        return joint.element([mpmath.mpf(x) for x in q], expm_mp)


def _text(x) -> str:
    return mpmath.nstr(x, 16, min_fixed=-30, max_fixed=30, strip_zeros=False)


def _yaml_list(xs) -> str:
    return "[" + ", ".join(f"'{x}'" if isinstance(x, str) else repr(x) for x in xs) + "]"


def one_joint_file(jtype: str, params: dict, value: str, extra: str = "") -> str:
    geo = ", ".join(
        f"{k}: {_yaml_list(v) if isinstance(v, list | tuple) else repr(v)}"
        for k, v in params.items()
    )
    return (
        f"mechanism: one-{jtype}\n"
        "bodies: [ground, b]\n"
        "joints:\n"
        f"  - {{name: J, type: {jtype}, between: [ground, b], {geo}}}\n"
        f"{extra}"
        "configurations:\n"
        f"  c1: {{J: {value}}}\n"
    )


def displacement_text(g, rotation: bool = True, translation: bool = True) -> str:
    parts = []
    if rotation:
        rows = ", ".join("[" + ", ".join(_text(g[i, k]) for k in range(3)) + "]" for i in range(3))
        parts.append(f"rotation: [{rows}]")
    if translation:
        parts.append("translation: [" + ", ".join(_text(g[i, 3]) for i in range(3)) + "]")
    return "{" + ", ".join(parts) + "}"


def given_matrix(g) -> mpmath.matrix:
    """The displacement exactly as the file writes it (16 significant digits)."""
    with mpmath.workdps(DIGITS):
        return mpmath.matrix([[mpmath.mpf(_text(g[i, k])) for k in range(4)] for i in range(4)])


def closed_q(path, precision: str) -> np.ndarray:
    """The coordinates of configuration c1 that enter an analysis at ``precision``."""
    mech = mechsing.load(path)
    km = KinematicModel(mech, precision)
    return Closer(km).solve("c1").q


def analysed_joint(path, precision: str) -> list[float]:
    res = mechsing.analyze(path, ["c1"], precision).to_json()
    (cfg,) = res["configurations"]
    assert "error" not in cfg or cfg["error"] is None, cfg
    return cfg["joints"]["J"]


# the joints of the issue, with geometry written as ordinary decimals, and chosen coordinates
# (angles below pi, so they are the principal ones)
CASES = {
    "S": ({"point": [0.1, -0.7, 1.3]}, [0.3, -0.4, 1.1]),
    "G": ({"normal": [0.3, 0.4, 1.2]}, [0.7, 0.25, -0.5]),
    "Y": ({"normal": [0.3, 0.4, 1.2], "pitch": 0.05}, [0.7, 0.25, -0.5]),
    "X": ({"axis": [0.3, 0.4, 1.2]}, [0.7, 0.25, -0.5, 0.4]),
    "T2": ({"normal": [0.3, 0.4, 1.2]}, [0.25, -0.5]),
}
MODES = ["float", "auto", "mp:30"]


# ----------------------------------------------------------------------------- defect 1


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("jtype", sorted(CASES))
def test_decimal_displacement_is_in_its_subgroup_in_every_mode(tmp_path, jtype, mode):
    params, q0 = CASES[jtype]
    g = displacement(jtype, params, q0)
    path = write(tmp_path, "d", one_joint_file(jtype, params, displacement_text(g)))
    # the coordinates entering the analysis are the chosen ones (data to 16 digits)
    q = closed_q(path, mode)
    tol = 1e-13 if mode != "mp:30" else 1e-14
    assert np.max(np.abs(np.asarray(q, dtype=float) - q0)) < tol
    # and the joint value reproduces the displacement as written, to the data's digits
    with mpmath.workdps(DIGITS):
        back = displacement(jtype, params, [mpmath.mpf(x) for x in q])
        given = given_matrix(g)
        err = max(abs(back[i, k] - given[i, k]) for i in range(3) for k in range(4))
    assert err < (1e-13 if mode != "mp:30" else 1e-15)
    # through the whole analysis (JSON, SI)
    assert analysed_joint(path, mode) == pytest.approx(q0, abs=1e-12)


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("jtype", ["S", "G", "Y", "X"])
def test_omitted_translation_is_completed_in_every_mode(tmp_path, jtype, mode):
    """Only the rotation given: the completed displacement is exp of the rotating basis screws
    with that rotation (no slide), so the coordinates are the rotation angle(s) and zeros."""
    params, q0 = CASES[jtype]
    q_rot = q0 if jtype == "S" else [q0[0]] + [0] * (len(q0) - 1)
    g = displacement(jtype, params, q_rot)
    path = write(
        tmp_path, "d", one_joint_file(jtype, params, displacement_text(g, translation=False))
    )
    q = np.asarray(closed_q(path, mode), dtype=float)
    assert np.max(np.abs(q - np.asarray(q_rot, dtype=float))) < 1e-13


@pytest.mark.parametrize("mode", MODES + ["exact"])
def test_s_joint_translation_completed_from_its_centre(tmp_path, mode):
    """The issue's example: S at (0, 1, 2), a quarter turn about x.  The completed translation
    is (I - R) c = (0, 3, 1); the coordinates are the rotation vector (pi/2, 0, 0)."""
    path = write(
        tmp_path,
        "s",
        one_joint_file("S", {"point": [0, 1, 2]}, "{rotation: [[1, 0, 0], [0, 0, -1], [0, 1, 0]]}"),
    )
    q = closed_q(path, mode)
    if mode == "exact":
        assert [sympy.simplify(x - y) for x, y in zip(q, [sympy.pi / 2, 0, 0], strict=True)] == [
            0,
            0,
            0,
        ]
    elif mode == "mp:30":  # exact data: the coordinates to the working precision
        with mpmath.workdps(DIGITS):
            assert abs(q[0] - mpmath.pi / 2) < 1e-28 and q[1] == 0 and q[2] == 0
    else:
        assert np.max(np.abs(np.asarray(q, dtype=float) - [np.pi / 2, 0, 0])) < 1e-14
    assert analysed_joint(path, mode) == pytest.approx([np.pi / 2, 0, 0], abs=1e-14)
    # the same with the translation written out
    path2 = write(
        tmp_path,
        "s2",
        one_joint_file(
            "S",
            {"point": [0, 1, 2]},
            "{rotation: [[1, 0, 0], [0, 0, -1], [0, 1, 0]], translation: [0, 3, 1]}",
        ),
    )
    assert analysed_joint(path2, mode) == pytest.approx([np.pi / 2, 0, 0], abs=1e-14)


# exact data: (type, params, displacement text, exact coordinates derived by hand)
#  S at (1, 0, 0), a quarter... an eighth turn about z: rotation vector (0, 0, pi/4), translation
#    (I - R) c = (1 - sqrt(2)/2, -sqrt(2)/2, 0)
#  G normal z, the 3-4-5 rotation by atan(4/3) and translation (1, 2, 0): angle atan(4/3),
#    slides V(a)^-1 p with V = (sin a / a) I + ((1 - cos a) / a) J on the plane
#  Y normal z, pitch 1/10, a quarter turn: completed slide h a = pi/20 along z
#  X axis z, the 3-4-5 rotation, translation (1, 2, 3): as G, and the slide 3 along z
#  T2 normal z: identity rotation, translation (1, 2, 0)
_A = sympy.atan(sympy.Rational(4, 3))
_V = sympy.Matrix([[sympy.sin(_A), -(1 - sympy.cos(_A))], [1 - sympy.cos(_A), sympy.sin(_A)]]) / _A
_GV = list(_V.inv() * sympy.Matrix([1, 2]))
EXACT_CASES = {
    "S": (
        {"point": [1, 0, 0]},
        '{rotation: [["sqrt(2)/2", "-sqrt(2)/2", 0], ["sqrt(2)/2", "sqrt(2)/2", 0], [0, 0, 1]]}',
        [0, 0, sympy.pi / 4],
    ),
    "G": (
        {"normal": [0, 0, 1]},
        "{rotation: [[0.6, -0.8, 0], [0.8, 0.6, 0], [0, 0, 1]], translation: [1, 2, 0]}",
        [_A, *_GV],
    ),
    "Y": (
        {"normal": [0, 0, 1], "pitch": "1/10"},
        "{rotation: [[0, -1, 0], [1, 0, 0], [0, 0, 1]]}",
        [sympy.pi / 2, 0, 0],
    ),
    "X": (
        {"axis": [0, 0, 1]},
        "{rotation: [[0.6, -0.8, 0], [0.8, 0.6, 0], [0, 0, 1]], translation: [1, 2, 3]}",
        [_A, *_GV, 3],
    ),
    "T2": ({"normal": [0, 0, 1]}, "{translation: [1, 2, 0]}", [1, 2]),
}


@pytest.mark.parametrize("jtype", sorted(EXACT_CASES))
def test_exact_displacement_gives_exact_coordinates(tmp_path, jtype):
    params, value, expected = EXACT_CASES[jtype]
    path = write(tmp_path, "e", one_joint_file(jtype, params, value))
    q = closed_q(path, "exact")
    assert all(isinstance(x, sympy.Basic) for x in q)
    assert [sympy.simplify(sympy.expand_trig(x - y)) for x, y in zip(q, expected, strict=True)] == [
        0
    ] * len(expected)
    # in the other modes the same coordinates, numerically
    want = [float(sympy.N(x, 30)) for x in expected]
    for mode in MODES:
        assert np.max(np.abs(np.asarray(closed_q(path, mode), dtype=float) - want)) < 1e-13
    assert analysed_joint(path, "exact") == pytest.approx(want, abs=1e-14)


def _s_file_off(offset: str) -> str:
    return one_joint_file(
        "S",
        {"point": [0, 1, 2]},
        f"{{rotation: [[1, 0, 0], [0, 0, -1], [0, 1, 0]], translation: [0, 3, {offset}]}}",
    )


@pytest.mark.parametrize("mode", MODES + ["exact"])
def test_displacement_outside_the_subgroup_is_a_clear_error(tmp_path, mode):
    path = write(tmp_path, "off", _s_file_off("1.001"))  # 1 mm off (L = |c| = 2.24 m)
    with pytest.raises(UserError) as exc:
        mechsing.analyze(path, ["c1"], mode)
    msg = str(exc.value)
    assert exit_status(exc.value) == 2
    assert "configuration 'c1'" in msg and "joint 'J'" in msg and "line 6" in msg
    assert "not in the joint's S subgroup" in msg
    rc, out, err = run_cli(["analyze", str(path), "--precision", mode])
    assert rc == 2 and "configuration 'c1'" in err and "Traceback" not in err


def test_membership_tolerance_is_the_modes(tmp_path):
    """1e-12 m off the subgroup: inside float's tolerance (1e-9 relative), outside mp:30's
    (1e-15) and exact mode's (0)."""
    path = write(tmp_path, "off", _s_file_off("1.000000000001"))
    assert analysed_joint(path, "float") == pytest.approx([np.pi / 2, 0, 0], abs=1e-11)
    for mode in ("mp:30", "exact"):
        with pytest.raises(UserError, match="not in the joint's S subgroup"):
            mechsing.analyze(path, ["c1"], mode)


def test_rotation_outside_a_planar_subgroup_is_a_clear_error(tmp_path):
    # a quarter turn about x is no rotation of G(z), with or without a translation
    for value in (
        "{rotation: [[1, 0, 0], [0, 0, -1], [0, 1, 0]]}",
        "{rotation: [[1, 0, 0], [0, 0, -1], [0, 1, 0]], translation: [0, 0, 0]}",
    ):
        path = write(tmp_path, "g", one_joint_file("G", {"normal": [0, 0, 1]}, value))
        for mode in MODES:
            with pytest.raises(UserError, match=r"configuration 'c1', joint 'J' \(line 6\)"):
                mechsing.analyze(path, ["c1"], mode)


def test_auto_keeps_its_tolerance_when_it_re_decides_at_mp50(tmp_path):
    """An S joint written to 16 digits, then an R joint whose axis passes 1e-10 m from the S
    centre (and one more R, 1 m away, so that the mechanism's size is about 1 m): the output's
    smallest singular value is about 1e-10 of the largest, undecided in float, so auto re-decides
    the configuration at mp:50.  The displacement, accepted by auto,
    stays accepted there (its coordinates, exactly in the subgroup, enter the mp:50 analysis)."""
    params, q0 = {"point": [0, 0, 0]}, [0.3, -0.4, 1.1]
    g = displacement("S", params, q0)
    text = (
        "mechanism: s-r\n"
        "bodies: [ground, b1, b2, b3]\n"
        "joints:\n"
        "  - {name: J, type: S, between: [ground, b1], point: [0, 0, 0]}\n"
        "  - {name: K, type: R, between: [b1, b2], axis: [0, 0, 1], point: [1e-10, 0, 0]}\n"
        "  - {name: M, type: R, between: [b2, b3], axis: [0, 0, 1], point: [1, 0, 0]}\n"
        "output: {body: b3}\n"
        "configurations:\n"
        f"  c1: {{J: {displacement_text(g)}, K: 0.2}}\n"
    )
    path = write(tmp_path, "sr", text)
    res = mechsing.analyze(path, ["c1"], "auto").to_json()
    cfg = by_name(res)["c1"]
    assert cfg["precision"] == "mp:50"
    assert cfg["joints"]["J"] == pytest.approx(q0, abs=1e-14)
    # asked for mp:50, 16 digits are not a rotation (nor in S) to 25 digits
    with pytest.raises(UserError, match=r"joint 'J' \(line 9\): .* to 1e-25 .* at mp:50"):
        mechsing.analyze(path, ["c1"], "mp:50")


@pytest.mark.parametrize("mode", MODES)
def test_stewart_platform_with_s_joints_given_as_16_digit_rotations(tmp_path, mode):
    """The issue's 6-UPS case: examples/stewart_octahedral.yaml at 'rotated+90' with each S joint
    given as its rotation matrix to 16 digits (translation completed), the other joints as in the
    example.  Accepted in every mode; the S coordinates are the example's rotation vectors."""
    doc = yaml.load((EXAMPLES / "stewart_octahedral.yaml").read_text(), Loader=_KeepNumbers)
    cfg = doc["configurations"]["rotated+90"]
    vectors = {f"S{k}": [float(x) for x in cfg[f"S{k}"]] for k in range(1, 7)}
    for name in vectors:
        with mpmath.workdps(DIGITS):
            R = rotation_mp(cfg[name])
        cfg[name] = {"rotation": [[_text(R[i, k]) for k in range(3)] for i in range(3)]}
    doc["configurations"] = {"rotated+90": cfg}
    path = write(tmp_path, "stewart16", yaml.dump(doc, Dumper=_Dumper, sort_keys=False))
    res = by_name(mechsing.analyze(path, ["rotated+90"], mode).to_json())["rotated+90"]
    assert res.get("error") is None
    for name, v in vectors.items():
        assert res["joints"][name] == pytest.approx(v, abs=1e-14)


# ----------------------------------------------------------------------------- defect 2

RSSR = """\
mechanism: rssr
bodies: [ground, crank, coupler, rocker]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: S1, type: S, between: [crank, coupler], point: [1, 0, 0]}
  - {name: S2, type: S, between: [coupler, rocker], point: [1, 2, 1]}
  - {name: D, type: R, between: [rocker, ground], axis: [1, 0, 0], point: [0, 2, 0]}
inputs: [A]
output: {body: rocker}
configurations:
"""


def _reference_result(path, mode: str) -> dict:
    res = mechsing.analyze(path, ["reference"], mode).to_json()
    return by_name(res)["reference"]


@pytest.mark.parametrize("mode", MODES + ["exact"])
def test_reference_listing_identity_values_is_the_reference(tmp_path, mode):
    identity = "{rotation: [[1, 0, 0], [0, 1, 0], [0, 0, 1]], translation: [0, 0, 0]}"
    given = write(
        tmp_path,
        "given",
        RSSR + f"  reference: {{A: 0, S1: {identity}, S2: [0.0, 0, 0], D: '0'}}\n",
    )
    implicit = write(tmp_path, "implicit", RSSR + "  reference: {}\n")
    got, want = _reference_result(given, mode), _reference_result(implicit, mode)
    # every joint at identity: all coordinates zero, closed exactly
    assert got["joints"] == {"A": [0.0], "S1": [0.0] * 3, "S2": [0.0] * 3, "D": [0.0]}
    assert got["closure_residual"] == 0.0
    assert got["mobility"] == want["mobility"] and got["loops"] == want["loops"]
    assert got["singularities"] == want["singularities"]
    # a displacement with one key only is the identity too (the other is completed)
    for value in ("{rotation: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}", "{translation: [0, 0, 0]}"):
        path = write(tmp_path, "one", RSSR + f"  reference: {{S1: {value}}}\n")
        assert _reference_result(path, mode)["joints"]["S1"] == [0.0] * 3


def test_reference_value_is_decided_in_the_modes_sense(tmp_path):
    """A rotation vector of 1e-12 rad is the identity to float's tolerance (1e-9), not to
    mp:30's (1e-15) nor exactly."""
    path = write(tmp_path, "tiny", RSSR + "  reference: {S1: [0, 0, 1e-12]}\n")
    assert _reference_result(path, "float")["joints"]["S1"] == [0.0] * 3
    for mode in ("mp:30", "exact"):
        with pytest.raises(UserError) as exc:
            mechsing.analyze(path, ["reference"], mode)
        msg = str(exc.value)
        assert msg.startswith(f"{path}:11: ") and "joint 'S1'" in msg
        assert "the reference configuration has every joint at identity" in msg
        rc, _out, err = run_cli(["analyze", str(path), "--precision", mode])
        assert rc == 2 and "identity" in err and "Traceback" not in err


@pytest.mark.parametrize(
    "value",
    [
        "{A: 1}",
        "{S1: {rotation: [[1, 0, 0], [0, 0, -1], [0, 1, 0]]}}",
        "{S1: {translation: [0, 0, 1]}}",
    ],
)
def test_reference_with_other_values_is_refused_as_before(tmp_path, value):
    path = write(tmp_path, "moved", RSSR + f"  reference: {value}\n")
    with pytest.raises(MechanismError) as exc:
        mechsing.load(path)
    msg = str(exc.value)
    assert msg.startswith(f"{path}:11: configuration 'reference'")
    assert ("joint 'A'" if "A:" in value else "joint 'S1'") in msg
    assert "the reference configuration has every joint at identity" in msg
    assert "new configuration" in msg


# ----------------------------------------------------------------------------- defect 3

CHAIN = """\
mechanism: chain
units: {{angle: {unit}}}
bodies: [ground, a, b]
joints:
  - {{name: J1, type: {type1}, between: [ground, a], {geo1}}}
  - {{name: J2, type: R, between: [a, b], axis: [0, 0, 1], point: [1, 0, 0]}}
configurations:
  c1: {{J1: {value}}}
"""
GEO = {
    "R": "axis: [0, 0, 1], point: [0, 0, 0]",
    "H": "axis: [0, 0, 1], point: [0, 0, 0], pitch: 0.001",
    "C": "axis: [0, 0, 1], point: [0, 0, 0]",
    "U": "axes: [[0, 0, 1], [1, 0, 0]], point: [0, 0, 0]",
    "S": "point: [0, 0, 0]",
    "G": "normal: [0, 0, 1]",
    "X": "axis: [0, 0, 1]",
    "D": "",
}


def chain(unit: str, jtype: str, value: str) -> str:
    geo = GEO[jtype] or "{}"
    text = CHAIN.format(unit=unit, type1=jtype, geo1=geo, value=value)
    return text.replace(", {}}", "}")


# (type, value written in a degree file, the radian expression in it, the same angle in degrees)
RADIAN_IN_DEG = [
    ("R", '"pi/6"', "pi/6", 30.0),
    ("H", '"pi/4"', "pi/4", 45.0),
    ("C", '["pi/3", 0.1]', "pi/3", 60.0),
    ("U", '[0, "atan(1/2)"]', "atan(1/2)", np.degrees(np.arctan(0.5))),
    ("S", '[0, "2*atan(1/3)", 0]', "2*atan(1/3)", np.degrees(2 * np.arctan(1 / 3))),
    ("G", '["asin(1/3)", 0, 0]', "asin(1/3)", np.degrees(np.arcsin(1 / 3))),
    ("X", '["acos(0.3)", 0, 0, 0]', "acos(0.3)", np.degrees(np.arccos(0.3))),
    ("D", '[0, 0, "atan2(1, 2)", 0, 0, 0]', "atan2(1, 2)", np.degrees(np.arctan2(1, 2))),
]


@pytest.mark.parametrize(("jtype", "value", "expr", "degrees"), RADIAN_IN_DEG)
def test_radian_expression_in_a_degree_file_is_an_error(tmp_path, jtype, value, expr, degrees):
    path = write(tmp_path, "deg", chain("deg", jtype, value))
    rc, out, err = run_cli(["analyze", str(path)])
    assert rc == 2 and out == "" and "Traceback" not in err
    assert err.startswith(f"mechsing: error: {path}:8: configuration 'c1': value of joint 'J1'")
    assert expr in err and "degrees" in err
    # both fixes: the value in degrees, or radians for the whole file
    m = re.search(r"e\.g\. (-?[0-9.]+)", err)
    assert m and float(m.group(1)) == pytest.approx(degrees, rel=1e-5)
    assert "units: {angle: rad}" in err
    with pytest.raises(MechanismError) as exc:
        mechsing.load(path)
    assert exc.value.line == 8 and exit_status(exc.value) == 2


@pytest.mark.parametrize(
    ("value", "radians"),
    [
        ("30", sympy.pi / 6),
        ('"asin(1/2)*180/pi"', sympy.pi / 6),  # a radian value converted to degrees
        ('"pi/6 * 180/pi"', sympy.pi / 6),
        ('"cos(pi/3)"', sympy.pi / 360),  # a pure number (1/2) of degrees
        ('"sqrt(3)/2"', sympy.sqrt(3) * sympy.pi / 360),
    ],
)
def test_degree_values_in_a_degree_file_are_read_in_degrees(tmp_path, value, radians):
    mech = mechsing.load(write(tmp_path, "deg", chain("deg", "R", value)))
    assert sympy.simplify(mech.configurations["c1"].values["J1"][0] - radians) == 0
    assert mech.warnings == ()


@pytest.mark.parametrize(
    ("jtype", "value", "expected"),
    [
        ("R", "30", (30,)),
        ("C", "[30, 0.1]", (30, sympy.Rational(1, 10))),
        ("U", "[0, -7]", (0, -7)),
        ("S", "[0, 0, 7]", (0, 0, 7)),
        ("G", "[20, 0, 0]", (20, 0, 0)),
    ],
)
def test_plain_angle_above_a_full_turn_in_a_radian_file_warns(tmp_path, jtype, value, expected):
    path = write(tmp_path, "rad", chain("rad", jtype, value))
    mech = mechsing.load(path)
    (warning,) = mech.warnings
    assert warning.startswith(f"{path}:8: configuration 'c1': value of joint 'J1'")
    assert "units: {angle: deg}" in warning
    # the angle is taken as written, in radians
    assert mech.configurations["c1"].values["J1"] == expected
    # the CLI prints the warning without -v and goes on with the analysis
    rc, out, err = run_cli(["analyze", str(path), "--format", "json"])
    assert rc == 0
    assert by_name(json.loads(out))["c1"]["joints"]["J1"] == pytest.approx(
        [float(x) for x in expected]
    )
    assert f"mechsing: warning: {warning}" in err.splitlines()


@pytest.mark.parametrize(
    ("jtype", "value"),
    [
        ("R", "6"),  # below a full turn
        ("R", '"10*pi"'),  # an expression: meant in radians
        ("H", "30"),  # a screw turns many times: no warning for pitched joints
        ("S", "[3, 3, 3]"),  # rotation vector of norm 5.2 < 2 pi
    ],
)
def test_no_warning_for_ordinary_radian_values(tmp_path, jtype, value):
    path = write(tmp_path, "rad", chain("rad", jtype, value))
    assert mechsing.load(path).warnings == ()
    rc, _out, err = run_cli(["analyze", str(path), "--format", "json"])
    assert rc == 0 and "warning" not in err


# ----------------------------------------------------------------------------- messages point to
# what users have


def test_empty_file_message_points_to_the_schema_and_readme(tmp_path):
    path = write(tmp_path, "empty", "")
    rc, out, err = run_cli(["analyze", str(path)])
    assert rc == 2 and out == ""
    assert "mechsing schema" in err and "README" in err
    assert "DESIGN" not in err


def test_model_and_kinematics_texts_name_no_internal_document():
    """Messages and docstrings of the model and kinematics layers point to ``mechsing schema``
    and the README, never to design notes users do not have."""
    root = Path(mechsing.__file__).parent
    for sub in ("model", "kinematics"):
        for path in sorted((root / sub).glob("*.py")):
            text = path.read_text()
            for word in ("DESIGN", "theory" + ".md", "../" + "shared", "shared/"):
                assert word not in text, f"{path.name} mentions {word}"
