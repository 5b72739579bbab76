"""``mechsing condition`` at its edges, through the command line.

Expected formulas are worked by hand from each file's geometry (named in each test), never
taken from mechsing.
"""

from __future__ import annotations

import json
from pathlib import Path

from tests.cli import run_cli

#: a four-bar whose rocker pivots lie at x = sqrt(a + 4), a radical of the symbolic a:
#: A at the origin, B = (0, 1), C = (sqrt(a + 4), 2), D = (sqrt(a + 4), 0)
FOURBAR_RADICAL = """\
mechanism: fourbar-radical
parameters: {a: 1}
bodies: [ground, crank, coupler, rocker]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, coupler], axis: [0, 0, 1], point: [0, 1, 0]}
  - {name: C, type: R, between: [coupler, rocker], axis: [0, 0, 1], point: ["sqrt(a + 4)", 2, 0]}
  - {name: D, type: R, between: [rocker, ground], axis: [0, 0, 1], point: ["sqrt(a + 4)", 0, 0]}
inputs: [A]
output: {body: rocker}
"""


def test_a_radical_in_a_joints_point_shows_the_parameters_name(tmp_path: Path) -> None:
    path = tmp_path / "fourbar.yaml"
    path.write_text(FOURBAR_RADICAL, encoding="utf-8")
    for fmt in ("text", "json", "md"):
        run = run_cli(["condition", path, "--symbolic", "a", "--format", fmt])
        assert run.status == 0, run.err
        assert "_a" not in run.out, run.out  # a sympy Dummy prints as _a
        assert "sqrt(a + 4)" in run.out or "\\sqrt{a + 4}" in run.out
    doc = json.loads(run_cli(["condition", path, "--symbolic", "a", "--format", "json"]).out)
    # the input condition: B - A = (0, 1) and C - B = (sqrt(a + 4), 1) rotated by the
    # crank's angle B about B: in line when cross((0, 1), (sqrt(a+4) cos B - sin B, ...)) = 0
    first = doc["conditions"][0]["factors"][0]["expression"]
    assert first.replace(" ", "") in ("sqrt(a+4)*cos(B)-sin(B)", "-sin(B)+sqrt(a+4)*cos(B)")


def _condition(tmp_path: Path, text: str, *extra: str) -> dict:
    path = tmp_path / "m.yaml"
    path.write_text(text, encoding="utf-8")
    run = run_cli(["condition", path, "--format", "json", *extra])
    assert run.status == 0, run.err
    return json.loads(run.out)


#: a U joint at the origin (first axis z, second y) carrying a slide along x: the output
#: point (1 + P) Rz(a) Ry(b) e_x is in spherical coordinates, the Jacobian's determinant
#: -(1 + P)**2 cos(b) (the radius squared times the cosine of the latitude)
U_ARM = """\
mechanism: u-slide-arm
bodies: [ground, arm, slider]
joints:
  - {name: U1, type: U, between: [ground, arm], axes: [[0, 0, 1], [0, 1, 0]], point: [0, 0, 0]}
  - {name: P, type: P, between: [arm, slider], axis: [1, 0, 0]}
inputs: [U1, P]
output: {body: slider, point: [1, 0, 0]}
configurations:
  up: {U1: [0.3, "pi/2"], P: 0.5}
"""


def test_a_u_joint_is_written_as_its_two_revolutes(tmp_path: Path) -> None:
    import sympy

    doc = _condition(tmp_path, U_ARM, "--config", "up")
    (c,) = doc["conditions"]
    b, p = sympy.symbols("b P", real=True)
    got = sympy.sympify(c["expression"].replace("U1[1]", "b"), locals={"b": b, "P": p})
    assert sympy.simplify(got - (-((1 + p) ** 2) * sympy.cos(b))) == 0
    # at U1 = (0.3, pi/2) the arm points along -z: the latitude's cosine vanishes
    assert abs(doc["values"]["U1[1]"] - sympy.pi.evalf() / 2) < 1e-12
    assert any(f["vanishes"] for f in c["factors"])
    assert any("U joint U1" in n for n in doc["notes"])


def test_a_c_joint_is_a_revolute_and_a_slide(tmp_path: Path) -> None:
    """Cylindrical coordinates: the point ((1 + P) cos t, (1 + P) sin t, z): det = 1 + P."""
    text = (
        U_ARM.replace(
            "{name: U1, type: U, between: [ground, arm], axes: [[0, 0, 1], [0, 1, 0]], point: [0, 0, 0]}",
            "{name: C1, type: C, between: [ground, arm], axis: [0, 0, 1], point: [0, 0, 0]}",
        )
        .replace("inputs: [U1, P]", "inputs: [C1, P]")
        .replace('U1: [0.3, "pi/2"], P: 0.5', "C1: [0.5, 0.2], P: -1")
    )
    doc = _condition(tmp_path, text, "--config", "up")
    (c,) = doc["conditions"]
    assert [f["expression"] for f in c["factors"]] == ["P + 1"]
    assert doc["values"] == {"C1[0]": 0.5, "C1[1]": 0.2, "P": -1.0}
    assert c["factors"][0]["vanishes"] is True


def test_an_s_joint_is_three_revolutes_without_their_own_singularity(tmp_path: Path) -> None:
    """A ball joint and a slide: the body turns freely and slides, a full rank 4 twist
    system everywhere (no codimension-1 condition); three revolutes Rx Ry Rz lose a
    direction at a right angle of the middle one, which is not the ball's and is left out."""
    text = (
        U_ARM.replace(
            "{name: U1, type: U, between: [ground, arm], axes: [[0, 0, 1], [0, 1, 0]], point: [0, 0, 0]}",
            "{name: S1, type: S, between: [ground, arm], point: [0, 0, 0]}",
        )
        .replace("inputs: [U1, P]", "inputs: [P]")
        .replace("output: {body: slider, point: [1, 0, 0]}", "output: {body: slider}")
    )
    text = text.replace('  up: {U1: [0.3, "pi/2"], P: 0.5}\n', "  reference: {}\n")
    doc = _condition(tmp_path, text)
    (c,) = doc["conditions"]
    assert c["factors"] == []
    assert any("left out: cos(S1[1])" in n for n in doc["notes"])
