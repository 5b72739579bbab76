"""``mechsing condition``: each condition against a closed form that is not computed
with mechsing (published, or derived in this file), and against ``analyze`` at
configurations where it vanishes (singular) and where it does not (regular)."""

from __future__ import annotations

import json
import math
import random
from pathlib import Path

import numpy as np
import pytest
import sympy

from mechsing.conditions import condition
from tests.cli import ROOT, run_cli
from tests.mechanisms import CENTRED_SLIDER_CRANK_MM, ORTHOGONAL_3R

EXAMPLES = ROOT / "examples"

PLANAR_2R = """\
mechanism: planar-2r
parameters: {a1: 0.7, a2: 0.4}
bodies: [ground, link1, link2]
joints:
  - {name: A, type: R, between: [ground, link1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [link1, link2], axis: [0, 0, 1], point: [a1, 0, 0]}
output: {body: link2, point: [a1 + a2, 0, 0]}
configurations:
  bent: {A: 0.3, B: 1}
  folded: {A: 0.3, B: "pi"}
"""

# PUMA 560 with Craig's (modified) DH parameters as named parameters; the geometry of
# examples/puma560.yaml (joint values = the DH angles, zero pose = the drawn pose).
PUMA = """\
mechanism: puma560
parameters: {a2: 0.4318, a3: 0.0203, d3: 0.15005, d4: 0.4318}
bodies: [base, link1, link2, link3, link4, link5, link6]
joints:
  - {name: J1, type: R, between: [base, link1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J2, type: R, between: [link1, link2], axis: [0, 1, 0], point: [0, 0, 0]}
  - {name: J3, type: R, between: [link2, link3], axis: [0, 1, 0], point: [a2, d3, 0]}
  - {name: J4, type: R, between: [link3, link4], axis: [0, 0, -1], point: [a2 + a3, d3, -d4]}
  - {name: J5, type: R, between: [link4, link5], axis: [0, 1, 0], point: [a2 + a3, d3, -d4]}
  - {name: J6, type: R, between: [link5, link6], axis: [0, 0, -1], point: [a2 + a3, d3, -d4]}
output: {body: link6}
"""

# UR5 with the Universal Robots DH lengths as named parameters (a2, a3 the magnitudes of
# UR's negative a2, a3); the geometry of examples/ur5.yaml.
UR5 = """\
mechanism: ur5
parameters: {a2: 0.425, a3: 0.39225, d1: 0.089159, d4: 0.10915, d5: 0.09465}
bodies: [base, link1, link2, link3, link4, link5, link6]
joints:
  - {name: J1, type: R, between: [base, link1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J2, type: R, between: [link1, link2], axis: [0, -1, 0], point: [0, 0, d1]}
  - {name: J3, type: R, between: [link2, link3], axis: [0, -1, 0], point: [-a2, 0, d1]}
  - {name: J4, type: R, between: [link3, link4], axis: [0, -1, 0], point: [-a2 - a3, 0, d1]}
  - {name: J5, type: R, between: [link4, link5], axis: [0, 0, -1], point: [-a2 - a3, -d4, d1]}
  - {name: J6, type: R, between: [link5, link6], axis: [0, -1, 0], point: [-a2 - a3, -d4, d1 - d5]}
output: {body: link6}
"""


def _write(tmp_path: Path, text: str, name: str = "m.yaml") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def _ratio_is_constant(expr, closed, names, params, expected=None, samples=5):
    """expr / closed at random joint angles and parameter values: one constant."""
    rng = random.Random(3)
    symbols = {s.name: s for s in expr.free_symbols | closed.free_symbols}
    ratios = []
    for _ in range(samples):
        sub = {symbols[n]: rng.uniform(-3, 3) for n in names if n in symbols}
        sub.update({symbols[p]: rng.uniform(0.1, 1.0) for p in params if p in symbols})
        den = float(closed.xreplace(sub))
        assert abs(den) > 1e-6
        ratios.append(float(expr.xreplace(sub)) / den)
    assert max(ratios) - min(ratios) < 1e-9 * max(1.0, abs(ratios[0]))
    if expected is not None:
        assert abs(ratios[0]) == pytest.approx(expected, rel=1e-12)
    return ratios[0]


def test_planar_2r_point_output_is_a1_a2_sin_b(tmp_path: Path) -> None:
    # Closed form (e.g. Murray, Li, Sastry, A Mathematical Introduction to Robotic
    # Manipulation, 1994, the planar two-link arm): det J = a1 a2 sin(theta2).
    r = condition(_write(tmp_path, PLANAR_2R), symbolic="a1,a2")
    (c,) = r.conditions
    a1, a2, B = sympy.symbols("a1 a2 B", real=True)
    assert c.form == "determinant"
    assert sympy.simplify(c.expression**2 - (a1 * a2 * sympy.sin(B)) ** 2) == 0
    assert [sympy.sstr(f.expression) for f in c.factors] == ["sin(B)"]
    assert "in line" in c.factors[0].meaning
    # numeric parameters: the exact value 0.7 * 0.4 = 7/25
    (n,) = condition(_write(tmp_path, PLANAR_2R)).conditions
    assert abs(n.constant) == sympy.Rational(7, 25)


TILTED_2R = """\
mechanism: tilted-2r
bodies: [ground, upper, fore]
joints:
  - {name: S, type: R, between: [ground, upper], axis: [1, 2, 2], point: [0, 0, 0]}
  - {name: E, type: R, between: [upper, fore], axis: [1, 2, 2], point: [2, -1, 0]}
inputs: [S, E]
output: {body: fore, point: [2, -3, 2]}
configurations:
  reference: {}
"""


def test_a_2r_arm_in_a_tilted_plane_has_the_planes_own_determinant(tmp_path: Path) -> None:
    """A 2R arm in the plane normal to n = (1, 2, 2): links a = (2, -1, 0) and
    b = (0, -2, 2), both normal to n.  Its determinant in an orthonormal basis of the plane
    is n/|n| . (a x b(E)), b(E) = b cos E + (n/|n| x b) sin E (computed here with numpy):
    the same amplitude l1 l2 = sqrt(40) as in any plane, not the 2/3 of it that the
    plane's projection on x and y keeps."""
    (c,) = condition(_write(tmp_path, TILTED_2R)).conditions
    E = sympy.Symbol("E", real=True)
    n = np.array([1.0, 2.0, 2.0]) / 3.0
    a, b = np.array([2.0, -1.0, 0.0]), np.array([0.0, -2.0, 2.0])
    for e in (0.0, 0.4, 1.3, -2.2):
        be = b * math.cos(e) + np.cross(n, b) * math.sin(e)
        want = float(n @ np.cross(a, be))
        got = float(c.expression.subs(E, e))
        assert abs(got) == pytest.approx(abs(want), rel=1e-12, abs=1e-12)
    # and the sign is one sign for the whole circle: the same function up to a constant
    ratios = []
    for e in (0.1, 0.9, 2.0):
        be = b * math.cos(e) + np.cross(n, b) * math.sin(e)
        ratios.append(float(c.expression.subs(E, e)) / float(n @ np.cross(a, be)))
    assert max(ratios) == pytest.approx(min(ratios), rel=1e-12)


TILTED_FOUR_BAR = """\
mechanism: four-bar-122
bodies: [ground, crank, coupler, rocker]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [1, 2, 2], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, coupler], axis: [1, 2, 2], point: ["2/3", "-2/3", "1/3"]}
  - {name: C, type: R, between: [coupler, rocker], axis: [1, 2, 2], point: ["4/3", "2/3", "-4/3"]}
  - {name: D, type: R, between: [rocker, ground], axis: [1, 2, 2], point: ["8/3", "-8/3", "4/3"]}
inputs: [A]
output: {body: rocker}
configurations:
  reference: {}
"""


def _amplitude(expr: sympy.Expr, name: str) -> float:
    """The largest |value| of a condition in one angle ``name`` (a*sin + b*cos), sampled."""
    q = sympy.Symbol(name, real=True)
    f = sympy.lambdify(q, expr, "numpy")
    return float(np.max(np.abs(f(np.linspace(-math.pi, math.pi, 20001)))))


def test_a_loop_in_a_tilted_plane_has_the_conditions_it_has_in_the_xy_plane(
    tmp_path: Path,
) -> None:
    """A four-bar in the plane normal to (1, 2, 2): the planar twists' determinant without
    D is twice the area of triangle ABC, |AB| |BC| sin(angle at B), whose amplitude over
    the coupler angle is |AB| |BC| = sqrt(5); without A, |BC| |CD| = 10 (lengths from the
    pivots, computed here): not the 2/3 or 4/9 of them a projection on x and y keeps."""
    conds = {c.name: c for c in condition(_write(tmp_path, TILTED_FOUR_BAR)).conditions}
    P = {
        k: np.array(v)
        for k, v in {"A": (0, 0, 0), "B": (2, -2, 1), "C": (4, 2, -4), "D": (8, -8, 4)}.items()
    }
    P = {k: v / 3.0 for k, v in P.items()}
    ab, bc, cd = (float(np.linalg.norm(P[b] - P[a])) for a, b in ("AB", "BC", "CD"))
    typ1, typ2 = conds["input (type I)"], conds["output (type II)"]
    assert _amplitude(typ1.expression, "B") == pytest.approx(ab * bc, rel=1e-6)
    assert _amplitude(typ2.expression, "C") == pytest.approx(bc * cd, rel=1e-6)


def test_a_planar_3r_arm_in_a_tilted_plane_has_l1_l2_sin_of_its_twists(tmp_path: Path) -> None:
    """A 3R arm about (1, 2, 2) with the body's twist as output: the planar twists'
    determinant is l1 l2 sin(angle at the second joint), l1 and l2 the distances between
    the axes (C is drawn off the plane of A and B, along its axis: l2 is |BC| projected
    on the plane), as in the xy plane."""
    text = (
        TILTED_FOUR_BAR.replace("four-bar-122", "arm-3r-122")
        .replace(
            "  - {name: D, type: R, between: [rocker, ground], axis: [1, 2, 2], point: "
            '["8/3", "-8/3", "4/3"]}\n',
            "",
        )
        .replace("inputs: [A]", "inputs: [A, B, C]")
    )
    text = text.replace('point: ["4/3", "2/3", "-4/3"]', 'point: ["8/3", "4/3", "-10/3"]')
    (c,) = condition(_write(tmp_path, text)).conditions
    n = np.array([1.0, 2.0, 2.0]) / 3.0

    def across(d: np.ndarray) -> float:
        return float(np.linalg.norm(d - (d @ n) * n))

    l1 = across(np.array([2.0, -2.0, 1.0]) / 3)
    l2 = across(np.array([8.0 - 2, 4 + 2, -10 - 1]) / 3)
    assert c.form == "determinant"
    assert _amplitude(c.expression, "B") == pytest.approx(l1 * l2, rel=1e-6)


def test_puma_560_det_j_factors_as_published(tmp_path: Path) -> None:
    # Craig, Introduction to Robotics (PUMA 560 Jacobian): det J = a2 (d4 c3 - a3 s3)
    # (a2 c2 + a3 c23 - d4 s23) s5 up to the signs of theta2, theta3, which depend on the
    # axis directions; with this file's axes (those of the DH frames) it reads
    # a2 (a3 s3 + d4 c3)(a2 c2 + a3 c23 - d4 s23) s5 -- d3 does not appear.
    r = condition(_write(tmp_path, PUMA), symbolic="a2,a3,d3,d4")
    (c,) = r.conditions
    a2, a3, d3, d4 = sympy.symbols("a2 a3 d3 d4", real=True)
    J2, J3, J5 = sympy.symbols("J2 J3 J5", real=True)
    s, co = sympy.sin, sympy.cos
    closed = (
        a2 * (a3 * s(J3) + d4 * co(J3)) * (a2 * co(J2) + a3 * co(J2 + J3) - d4 * s(J2 + J3)) * s(J5)
    )
    joints = [f"J{i}" for i in range(1, 7)]
    _ratio_is_constant(c.expression, closed, joints, ["a2", "a3", "d3", "d4"], expected=1.0)
    assert d3 not in c.expression.free_symbols
    assert c.constant == a2  # a parameter alone is part of the constant
    meaning = {sympy.sstr(f.expression): f.meaning for f in c.factors}
    assert len(meaning) == 3
    assert meaning["sin(J5)"] == "wrist: vanishes when the axes of J4 and J6 coincide"
    assert meaning["a3*sin(J3) + d4*cos(J3)"].startswith("elbow: ")
    (shoulder,) = [m for e, m in meaning.items() if "J2" in e]
    assert shoulder.startswith("shoulder: ") and "axis of J1" in shoulder


def test_ur5_det_j_has_wrist_elbow_and_shoulder_factors(tmp_path: Path) -> None:
    # With UR's DH table (a2, a3 < 0): det J = a2 a3 s3 s5 (a2 c2 + a3 c23 + d5 s234)
    # (the singular sets of K. P. Hawkins, "Analytic inverse kinematics for the Universal
    # Robots UR-5/UR-10 arms", Georgia Tech, 2013); d1, d4, d6 do not appear.  Here a2, a3
    # are the magnitudes, so the shoulder factor is -a2 c2 - a3 c23 + d5 s234.
    r = condition(_write(tmp_path, UR5), symbolic="a2,a3,d1,d4,d5")
    (c,) = r.conditions
    a2, a3, d5 = sympy.symbols("a2 a3 d5", real=True)
    J2, J3, J4, J5 = sympy.symbols("J2 J3 J4 J5", real=True)
    s, co = sympy.sin, sympy.cos
    closed = a2 * a3 * s(J3) * s(J5) * (-a2 * co(J2) - a3 * co(J2 + J3) + d5 * s(J2 + J3 + J4))
    joints = [f"J{i}" for i in range(1, 7)]
    _ratio_is_constant(c.expression, closed, joints, ["a2", "a3", "d1", "d4", "d5"], expected=1.0)
    names = {str(x) for x in c.expression.free_symbols}
    assert not names & {"d1", "d4", "J1", "J6"}


@pytest.mark.parametrize(
    ("example", "singular", "regular"),
    [
        ("ur5.yaml", ["reference", "wrist", "elbow", "shoulder"], ["regular"]),
        ("puma560.yaml", ["reference", "wrist", "elbow", "shoulder"], ["regular"]),
    ],
)
def test_serial_conditions_agree_with_analyze(example, singular, regular) -> None:
    path = EXAMPLES / example
    for config in singular + regular:
        (c,) = condition(path, config=config).conditions
        run = run_cli(["analyze", path, "--config", config, "--format", "json"])
        verdict = json.loads(run.out)["configurations"][0]
        assert c.vanishes is (config in singular), config
        assert verdict["singular"] is c.vanishes, config


def _turn_mod(a: float) -> float:
    return math.remainder(a, 2 * math.pi)


def test_slider_crank_dead_centres(tmp_path: Path) -> None:
    # Offset slider-crank of examples/slider_crank_crank_input.yaml: crank r = 1 (B at
    # (0, -1) in the drawn pose, so the crank's absolute angle is A - pi/2), rod l = 4,
    # offset e = 7/5.  Dead centres: crank and rod in line, |C| = l + r with
    # alpha = asin(e/(l + r)), and |C| = l - r with alpha = pi - asin(-e/(l - r)) ...
    # i.e. the crank pointing away from the pin: alpha = pi + asin(e/(l - r)).
    r_, l_, e_ = 1.0, 4.0, 7 / 5
    outer = math.asin(e_ / (l_ + r_)) + math.pi / 2
    inner = math.pi + math.asin(e_ / (l_ - r_)) + math.pi / 2
    res = condition(EXAMPLES / "slider_crank_crank_input.yaml")
    elim = [c for c in res.conditions if c.name == "input (type I) in the input A"]
    assert elim, [c.name for c in res.conditions]
    roots = [_turn_mod(x) for x in elim[0].roots]
    for want in (outer, inner):
        assert min(abs(_turn_mod(want - x)) for x in roots) < 1e-9
    # the output (type II) toggle needs a rod perpendicular to the slide: l < r + e fails
    toggle = [c for c in res.conditions if c.name == "output (type II) in the input A"]
    assert toggle and toggle[0].roots == ()
    # and at the file's dead centre the input condition vanishes, as analyze finds
    at = condition(EXAMPLES / "slider_crank_crank_input.yaml", config="dead-centre")
    det = [c for c in at.conditions if c.name == "input (type I)"][0]
    assert det.vanishes is True
    run = run_cli(
        [
            "analyze",
            EXAMPLES / "slider_crank_crank_input.yaml",
            "--config",
            "dead-centre",
            "--format",
            "json",
        ]
    )
    classes = [s["class"] for s in json.loads(run.out)["configurations"][0]["singularities"]]
    assert "input" in classes
    regular = condition(EXAMPLES / "slider_crank_crank_input.yaml", config="crank-60")
    assert [c.vanishes for c in regular.conditions if c.form == "determinant"] == [False, False]


def test_a_number_brought_out_by_combining_angles_goes_to_the_constant(tmp_path: Path) -> None:
    # Crank 10 mm drawn straight down, rod 20 mm to the pin at (10*sqrt(3), 0) mm.  The
    # input condition is the determinant of the planar twists (1, y, -x) of the pivots A,
    # B, C (metres).  Drawn pose: A = (0, 0), B = (0, -0.01), C = (0.01*sqrt(3), 0), so
    # det = 0.01 * 0.01*sqrt(3) = sqrt(3)/10000.  The rod turns by B about the crank: it
    # is folded onto the crank at B = pi/3 (rod at 30 deg, crank at -90 deg) and stretched
    # at B = -2*pi/3.  The factor cos(B + pi/6) carries no number of its own.
    res = condition(_write(tmp_path, CENTRED_SLIDER_CRANK_MM))
    det = [c for c in res.conditions if c.name == "input (type I)"][0]
    (factor,) = det.factors
    number, _ = factor.expression.as_coeff_Mul()
    assert number == 1, factor.expression
    (b,) = factor.expression.free_symbols
    value = lambda x: det.constant * factor.expression.xreplace({b: x}) ** factor.power  # noqa: E731
    assert abs(float(value(0))) == pytest.approx(math.sqrt(3) / 10000, rel=1e-12)
    for in_line in (sympy.pi / 3, -2 * sympy.pi / 3):
        assert sympy.simplify(value(in_line)) == 0


def test_four_bar_toggle_and_limit_positions() -> None:
    # examples/fourbar.yaml: crank a = 1, coupler b = 2 sqrt(2), rocker c = sqrt(5),
    # ground d = 4; the crank lies along the ground line in the drawn pose.  Limit
    # positions of the rocker (crank and coupler in line, Hartenberg & Denavit, Kinematic
    # Synthesis of Linkages, 1964): cos(A) = ((b+a)^2 + d^2 - c^2) / (2 d (b+a)) and
    # cos(A - pi) = ((b-a)^2 + d^2 - c^2) / (2 d (b-a)).  Toggle (coupler and rocker in
    # line): cos(A) = (a^2 + d^2 - (b +- c)^2) / (2 a d), outside [-1, 1] for this
    # crank-rocker: never reached.
    a, b, c, d = 1.0, 2 * math.sqrt(2), math.sqrt(5), 4.0
    ext = math.acos(((b + a) ** 2 + d**2 - c**2) / (2 * d * (b + a)))
    fold = math.pi - math.acos(((b - a) ** 2 + d**2 - c**2) / (2 * d * (b - a)))
    for bc in (b + c, b - c):
        assert abs((a**2 + d**2 - bc**2) / (2 * a * d)) > 1
    res = condition(EXAMPLES / "fourbar.yaml")
    names = [x.name for x in res.conditions]
    (lim,) = [x for x in res.conditions if x.name == "input (type I) in the input A"]
    (tog,) = [x for x in res.conditions if x.name == "output (type II) in the input A"]
    assert sorted(abs(x) for x in lim.roots) == pytest.approx(sorted([ext, ext, fold, fold]))
    assert tog.roots == (), names
    assert lim.units == ("rad",)
    # the file's angles are in degrees: the text shows them too
    assert "rad (-168.686, -33.101, 33.101, 168.686 deg)" in res.text()


def _concurrency(A: np.ndarray, B: np.ndarray) -> float:
    """Distance from the meeting point of leg lines 1 and 2 to leg line 3 (planar)."""
    d1, d2 = B[0] - A[0], B[1] - A[1]
    t = np.linalg.solve(np.column_stack([d1, -d2]), A[1] - A[0])
    P = A[0] + t[0] * d1
    d3 = (B[2] - A[2]) / np.linalg.norm(B[2] - A[2])
    w = P - A[2]
    return abs(w[0] * d3[1] - w[1] * d3[0])


def test_3rpr_type_ii_is_the_concurrency_of_the_leg_lines() -> None:
    # Base pivots and platform pivots of examples/planar_3rpr.yaml (its comment); the
    # reference point of the platform is the centroid of its pivots.
    A = np.array([[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]])
    B0 = np.array([[0.9, 0.3], [2.5, 1.5], [-0.3, 1.9]])
    c0 = B0.mean(axis=0)
    res = condition(EXAMPLES / "planar_3rpr.yaml")
    (t2,) = [c for c in res.conditions if c.name == "output (type II)"]
    x, y, phi = sympy.symbols("x y phi", real=True)
    f = sympy.lambdify((x, y, phi), t2.expression)

    def pivots(px: float, py: float, ang: float) -> np.ndarray:
        rot = np.array([[math.cos(ang), -math.sin(ang)], [math.sin(ang), math.cos(ang)]])
        return np.array([px, py]) + (B0 - c0) @ rot.T

    rng = random.Random(5)
    from scipy.optimize import brentq

    found = 0
    for _ in range(30):
        px, py = rng.uniform(0.5, 2.0), rng.uniform(0.5, 2.0)

        def g(ang: float, px: float = px, py: float = py) -> float:
            return f(px, py, ang)

        grid = np.linspace(-math.pi, math.pi, 73)
        vals = [g(a) for a in grid]
        for a0, a1, v0, v1 in zip(grid, grid[1:], vals, vals[1:], strict=False):
            if v0 * v1 < 0:
                root = brentq(g, a0, a1, xtol=1e-14)
                assert _concurrency(A, pivots(px, py, root)) < 1e-7
                found += 1
        # away from the zero set the lines are not concurrent
        ang = rng.uniform(-math.pi, math.pi)
        if abs(g(ang)) > 1e-3:
            assert _concurrency(A, pivots(px, py, ang)) > 1e-6
    assert found > 10
    at = condition(EXAMPLES / "planar_3rpr.yaml", config="concurrent")
    assert [c.vanishes for c in at.conditions] == [True, False, False, False]
    ref = condition(EXAMPLES / "planar_3rpr.yaml", config="reference")
    assert [c.vanishes for c in ref.conditions] == [False, False, False, False]


def test_a_redundant_chain_reports_the_gcd_of_its_minors(tmp_path: Path) -> None:
    # A planar 3R whose output is a point: the point Jacobian is 2x3; it loses rank only
    # when all three pivots and the point are in line (two equations): the gcd is 1.
    text = PLANAR_2R.replace(
        "output: {body: link2, point: [a1 + a2, 0, 0]}",
        "  - {name: C, type: R, between: [link2, link3], axis: [0, 0, 1], point: [a1 + a2, 0, 0]}\n"
        "output: {body: link3, point: [a1 + 2*a2, 0, 0]}",
    ).replace("[ground, link1, link2]", "[ground, link1, link2, link3]")
    text = text.replace('  bent: {A: 0.3, B: 1}\n  folded: {A: 0.3, B: "pi"}\n', "  {}\n")
    text = text.replace("configurations:\n  {}\n", "")
    result = condition(_write(tmp_path, text))
    (c,) = result.conditions
    assert c.form == "gcd of maximal minors"
    assert c.factors == ()
    assert "it is 1" in c.note
    # a constant is no equation: never written "1 = 0", in any format
    out = result.text()
    assert "1 = 0" not in out and "no equation: its product is 1, which never vanishes" in out
    assert "= 0$" not in result.markdown() and "No equation" in result.markdown()
    assert "= 0" not in result.latex() and r"\text{no equation" in result.latex()


def test_cli_formats_and_errors(tmp_path: Path) -> None:
    path = _write(tmp_path, PLANAR_2R)
    text = run_cli(["condition", path, "--symbolic", "a1,a2", "--config", "folded"])
    assert text.status == 0, text.err
    assert "a1*a2*sin(B)" in text.out
    assert "at folded:" in text.out and "(vanishes)" in text.out
    js = run_cli(["condition", path, "--format", "json", "--config", "bent"])
    doc = json.loads(js.out)
    assert doc["conditions"][0]["factors"][0]["vanishes"] is False
    assert doc["values"]["B"] == pytest.approx(1.0)
    tex = run_cli(["condition", path, "--symbolic", "a1,a2", "--format", "latex"])
    assert r"\sin{\left(B \right)}" in tex.out
    bad = run_cli(["condition", path, "--symbolic", "a9"])
    assert bad.status == 2 and "'a9'" in bad.err and "a1, a2" in bad.err
    nocfg = run_cli(["condition", path, "--config", "nowhere"])
    assert nocfg.status == 2 and "bent, folded" in nocfg.err
    # a 3-UPU whose first platform U has its axes swapped (not Tsai's translational
    # conditions): no pose-variable derivation applies (its U joints are written as their
    # revolutes, and a spatial parallel robot with three inputs is refused)
    upu = (EXAMPLES / "tsai_3upu.yaml").read_text()
    swapped = upu.replace(
        "axes: [[1, 0, 1], [0, 1, 0]], point: [1, 0, 1]",
        "axes: [[0, 1, 0], [1, 0, 1]], point: [1, 0, 1]",
    )
    assert swapped != upu
    other = tmp_path / "upu_swapped.yaml"
    other.write_text(swapped)
    sph = run_cli(["condition", other])
    assert sph.status == 2 and "several inputs" in sph.err


FOURBAR_3_1_SQRT10_2 = """\
mechanism: fourbar
bodies: [ground, crank, coupler, rocker]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, coupler], axis: [0, 0, 1], point: [0, 1, 0]}
  - {name: C, type: R, between: [coupler, rocker], axis: [0, 0, 1], point: [3, 2, 0]}
  - {name: D, type: R, between: [rocker, ground], axis: [0, 0, 1], point: [3, 0, 0]}
inputs: [A]
output: {body: rocker}
configurations:
  reference: {}
"""


def test_latex_document_writes_each_condition_as_its_json_latex(tmp_path: Path) -> None:
    """``--format latex`` writes each condition as the JSON's ``latex`` (one definition):
    a factor that is a sum, times a constant, is in parentheses (it once printed
    ``-2 \\cdot \\sin(C) + 3\\cos(C)`` for -2 (sin C + 3 cos C))."""
    path = _write(tmp_path, FOURBAR_3_1_SQRT10_2)
    doc = json.loads(run_cli(["condition", path, "--format", "json"]).out)
    tex = run_cli(["condition", path, "--format", "latex"])
    assert tex.status == 0, tex.err
    for c in doc["conditions"]:
        assert f"&& {c['latex']} = 0" in tex.out
        sums = [f for f in c["factors"] if "+" in f["expression"] or " - " in f["expression"]]
        if sums and (len(c["factors"]) > 1 or c["constant"] not in (1, "1")):
            assert r"\left(" in c["latex"]


def test_the_python_function_is_public() -> None:
    import mechsing

    res = mechsing.condition(EXAMPLES / "ur5.yaml", config="wrist")
    assert res.conditions[0].vanishes is True


@pytest.mark.parametrize(
    ("example", "config"),
    [
        ("fourbar.yaml", "crank-30"),
        ("planar_3rpr.yaml", None),
        ("parallelogram.yaml", None),
        ("ur5.yaml", "wrist"),
        ("quick_return.yaml", "crank-60"),
        ("watt_ii.yaml", None),
        ("stewart_octahedral.yaml", None),
        ("tsai_3upu.yaml", None),
    ],
)
def test_json_follows_its_schema(example: str, config: str | None) -> None:
    jsonschema = pytest.importorskip("jsonschema")
    schema = json.loads(run_cli(["schema", "--condition"]).out)
    argv = ["condition", EXAMPLES / example, "--format", "json"]
    run = run_cli(argv + (["--config", config] if config else []))
    assert run.status == 0, run.err
    jsonschema.validate(json.loads(run.out), schema)


def test_honest_messages_where_elimination_gives_nothing(tmp_path: Path) -> None:
    # the parallelogram's output is its coupler, not joined to the ground: only type II,
    # whose double root (the change point, all four pivots in line) is listed once
    res = condition(EXAMPLES / "parallelogram.yaml")
    assert any("only the output (type II)" in n for n in res.notes)
    (elim,) = [c for c in res.conditions if c.form == "eliminated"]
    assert [f.power for f in elim.factors] == [2]
    assert sorted(elim.roots) == pytest.approx([-math.pi / 2, math.pi / 2])
    # a symbolic crank: eliminated by resultants; at r = 1 the same condition as the
    # exact Groebner elimination with the file's numbers
    text = (
        (EXAMPLES / "fourbar.yaml")
        .read_text()
        .replace("bodies: [ground", "parameters: {r: 1}\nbodies: [ground")
        .replace("point: [1, 0, 0]", "point: [r, 0, 0]")
    )
    sym = condition(_write(tmp_path, text), symbolic="r")
    assert [c.form for c in sym.conditions] == ["determinant"] * 2 + ["eliminated"] * 2
    num = condition(EXAMPLES / "fourbar.yaml")
    r = sympy.Symbol("r", real=True)
    for name in ("input (type I) in the input A", "output (type II) in the input A"):
        (a,) = [c.expression for c in sym.conditions if c.name == name]
        (b,) = [c.expression for c in num.conditions if c.name == name]
        ratio = sympy.simplify(a.subs(r, 1) / b)
        assert ratio.is_number and ratio != 0


def test_spherical_four_bar_limit_positions() -> None:
    # examples/spherical_4r.yaml: all axes through the origin, u_A = z, u_B, u_C, u_D as
    # drawn.  The input (type I) singularity: the axes of A, B, C in one plane (crank and
    # coupler in line on the sphere).  Independent check: at each crank angle given, some
    # unit vector u_C in the plane of u_A and u_B(A), at the coupler's angle from u_B, is
    # at the rocker's angle from u_D; at the mirror angle -A (not a root: the linkage is
    # not symmetric) none is.
    uA = np.array([0.0, 0.0, 1.0])
    uB0 = np.array([0.0, 5 / 13, 12 / 13])
    uC0 = np.array([4 / 9, 8 / 9, 1 / 9])
    uD = np.array([15 / 17, 0.0, 8 / 17])
    cos_bc, cos_cd = uB0 @ uC0, uC0 @ uD

    def reachable(a: float) -> float:
        rot = np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])
        uB = rot @ uB0
        w = uA - (uA @ uB) * uB
        w /= np.linalg.norm(w)
        sin_bc = math.sqrt(1 - cos_bc**2)
        return min(abs((cos_bc * uB + sg * sin_bc * w) @ uD - cos_cd) for sg in (1, -1))

    res = condition(EXAMPLES / "spherical_4r.yaml")
    (lim,) = [c for c in res.conditions if c.name == "input (type I) in the input A"]
    assert len(lim.roots) == 4
    for a in lim.roots:
        assert reachable(a) < 1e-9
        assert reachable(-a) > 1e-3


@pytest.mark.parametrize(
    "example",
    [
        "fourbar.yaml",
        "fourbar_changepoint.yaml",
        "double_rocker.yaml",
        "slider_crank_crank_input.yaml",
        "slider_crank_slider_input.yaml",
    ],
)
def test_loop_conditions_agree_with_analyze(example: str) -> None:
    # type I vanishes exactly where analyze finds an input singularity, type II where it
    # finds an output singularity, in every configuration of the file
    path = EXAMPLES / example
    run = run_cli(["analyze", path, "--format", "json"])
    found = {
        c["name"]: {s["class"] for s in c["singularities"]}
        for c in json.loads(run.out)["configurations"]
    }
    for config, classes in found.items():
        res = condition(path, config=config)
        verdict = {c.name: c.vanishes for c in res.conditions if c.form == "determinant"}
        assert verdict["output (type II)"] is ("output" in classes), config
        if "input (type I)" in verdict:
            assert verdict["input (type I)"] is ("input" in classes), config


def test_double_rocker_limits_are_its_singular_configurations(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # examples/double_rocker.yaml gives its output-limit pose at A = 2*atan(sqrt(3)/9)
    # (input singular) and its limit at A = 2*pi/3 (output singular), exactly.  The
    # elimination's Groebner basis takes about 6 s of a quiet core: this test checks the
    # eliminant, not the machine's speed, so the elimination gets no wall-clock limit
    # (a loaded machine once took it past 150 s of the 300 s the test gave)
    from mechsing.conditions import derive

    monkeypatch.setattr(derive, "ELIMINATION_SECONDS", None)
    res = condition(EXAMPLES / "double_rocker.yaml")
    roots = {c.name: c.roots for c in res.conditions if c.form == "eliminated"}
    a_in = 2 * math.atan(math.sqrt(3) / 9)
    assert roots["input (type I) in the input A"] == pytest.approx([-a_in, a_in])
    assert roots["output (type II) in the input A"] == pytest.approx(
        [-2 * math.pi / 3, 2 * math.pi / 3]
    )


def test_a_factor_with_no_real_zero_is_said_never_to_vanish(tmp_path: Path) -> None:
    """An arm whose second axis is orthogonal to the other two: one factor of its output
    Jacobian's determinant depends on J3 alone and never vanishes (3 cos J3 + 4 >= 1, by
    hand; checked here on a grid of J3): it says so instead of saying nothing.  A factor
    with real zeros keeps its geometric meaning or its generic sentence."""
    result = condition(_write(tmp_path, ORTHOGONAL_3R))
    factors = [f for c in result.conditions for f in c.factors]
    alone = [f for f in factors if {s.name for s in f.expression.free_symbols} == {"J3"}]
    assert len(alone) == 1
    (f,) = alone
    fn = sympy.lambdify(sympy.Symbol("J3"), f.expression, "math")
    grid = [-math.pi + k * 2 * math.pi / 2000 for k in range(2001)]
    assert min(abs(fn(x)) for x in grid) > 0.5  # no zero anywhere
    assert f.meaning == "never vanishes: no real value of J3 makes it zero"
    assert "never vanishes: no real value of J3" in result.text()
    for other in factors:
        if other is not f:
            assert other.meaning is None or "never vanishes" not in other.meaning
