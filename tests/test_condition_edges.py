"""``mechsing condition`` at its edges, through the command line.

Expected formulas are worked by hand from each file's geometry (named in each test), never
taken from mechsing.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

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


RRR = Path(__file__).resolve().parent / "data" / "planar_3rrr.yaml"


@pytest.mark.parametrize("signs", [(1, 1, 1), (-1, 1, 1), (1, -1, 1)])
def test_a_planar_3rrr_with_its_three_inputs(tmp_path: Path, signs: tuple[int, ...]) -> None:
    """Type II: the determinant of the legs' lines B_i C_i (each a force through the two
    passive pivots, with its moment about the origin), worked here from the file's pivots
    (A_i on the ground, B_i turned about A_i by the input, C_i on the platform, whose
    reference point is the centroid of C1, C2, C3: the origin); type I of leg 1: A1, B1
    and C1 in line.  A base joint whose axis is written -z (``signs``) turns its leg by
    minus its value about z (the first revolute's too: the plane's normal is then -z)."""
    import sympy

    text = RRR.read_text()
    for i, sign in enumerate(signs):
        if sign < 0:
            head = f"{{name: A{i + 1}, type: R, between: [ground, prox{i + 1}],   axis: [0, 0, "
            assert head + "1]" in text
            text = text.replace(head + "1]", head + "-1]")
    path = tmp_path / "planar_3rrr.yaml"
    path.write_text(text)
    run = run_cli(["condition", path, "--format", "json"])
    assert run.status == 0, run.err
    doc = json.loads(run.out)
    conds = {c["name"]: c for c in doc["conditions"]}
    s3, s7, s21 = sympy.sqrt(3), sympy.sqrt(7), sympy.sqrt(21)
    A = [sympy.Matrix([0, 2]), sympy.Matrix([-s3, -1]), sympy.Matrix([s3, -1])]
    B0 = [
        sympy.Matrix([s7 / 4, sympy.Rational(5, 4)]),
        sympy.Matrix([-s7 / 8 - 5 * s3 / 8, s21 / 8 - sympy.Rational(5, 8)]),
        sympy.Matrix([-s7 / 8 + 5 * s3 / 8, -s21 / 8 - sympy.Rational(5, 8)]),
    ]
    C0 = [
        sympy.Matrix([0, sympy.Rational(1, 2)]),
        sympy.Matrix([-s3 / 4, -sympy.Rational(1, 4)]),
        sympy.Matrix([s3 / 4, -sympy.Rational(1, 4)]),
    ]

    def rot(t: float) -> sympy.Matrix:
        return sympy.Matrix([[sympy.cos(t), -sympy.sin(t)], [sympy.sin(t), sympy.cos(t)]])

    def geometry(x, y, phi, q):
        B = [A[i] + rot(signs[i] * q[i]) * (B0[i] - A[i]) for i in range(3)]
        C = [sympy.Matrix([x, y]) + rot(phi) * C0[i] for i in range(3)]
        return B, C

    def value(cond: dict, at: dict) -> float:
        names = {n: sympy.Symbol(n, real=True) for n in ("x", "y", "phi", "A1", "A2", "A3")}
        e = sympy.sympify(cond["expression"], locals=names)
        return float(e.subs({names[k]: v for k, v in at.items()}))

    ratios = []
    for x, y, phi, q in ((0.1, 0.2, 0.3, (0.4, -0.2, 0.7)), (-0.3, 0.1, -0.5, (1.1, 0.2, -0.9))):
        B, C = geometry(x, y, phi, q)
        rows = []
        for b, c in zip(B, C, strict=True):
            f = c - b
            rows.append([f[0], f[1], b[0] * f[1] - b[1] * f[0]])
        det = float(sympy.Matrix(rows).det())
        at = {"x": x, "y": y, "phi": phi, "A1": q[0], "A2": q[1], "A3": q[2]}
        ratios.append(value(conds["output (type II)"], at) / det)
    assert abs(ratios[0] - ratios[1]) < 1e-9 * abs(ratios[0])
    # leg 1 in line: C1 on the line A1 B1, 1.5 times as far from A1 as B1
    q, phi = (0.3, 0.1, 0.2), 0.2
    B, _ = geometry(0, 0, phi, q)
    c1 = A[0] + sympy.Rational(3, 2) * (B[0] - A[0])
    x, y = c1 - rot(phi) * C0[0]
    at = {"x": float(x), "y": float(y), "phi": phi, "A1": q[0], "A2": q[1], "A3": q[2]}
    leg1 = conds["input (type I), leg A1"]
    assert abs(value(leg1, at)) < 1e-12
    at["x"] += 0.1
    assert abs(value(leg1, at)) > 1e-3


def test_a_planar_3prr_with_its_three_inputs() -> None:
    """Leg 1: B1 = (P1 - 1, 3) on the slide along x, C1 = (x, y) + Rot(phi) (0, 4/3) (C1 =
    (0, 1) from the centroid (0, -1/3)); the leg transmits a force along C1 - B1, which
    does no work on the slide (along x) when C1 is straight above B1:
    x - 4/3 sin(phi) - (P1 - 1) = 0."""
    import sympy

    path = Path(__file__).resolve().parent / "data" / "planar_3prr.yaml"
    run = run_cli(["condition", path, "--format", "json"])
    assert run.status == 0, run.err
    conds = {c["name"]: c for c in json.loads(run.out)["conditions"]}
    names = {n: sympy.Symbol(n, real=True) for n in ("x", "y", "phi", "P1")}
    got = sympy.sympify(conds["input (type I), leg P1"]["expression"], locals=names)
    x, phi, p1 = names["x"], names["phi"], names["P1"]
    want = x - sympy.Rational(4, 3) * sympy.sin(phi) - (p1 - 1)
    ratio = sympy.simplify(got / want)
    assert ratio.is_number and ratio != 0
    assert set(conds) >= {"output (type II)", "input (type I), leg P2", "input (type I), leg P3"}


def _dh_jacobian_det(rows: list[tuple[float, float, float]], q: list[float]) -> float:
    """det of the 6x6 Jacobian of joint twists (omega, o x omega) of a standard-DH arm
    (rows: d, a, alpha; every joint revolute), worked here with numpy."""
    import numpy as np

    T = np.eye(4)
    cols = []
    for (d, a, alpha), theta in zip(rows, q, strict=True):
        z, o = T[:3, 2], T[:3, 3]
        cols.append(np.concatenate([z, np.cross(o, z)]))
        ct, st, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)
        A = np.array(
            [
                [ct, -st * ca, st * sa, a * ct],
                [st, ct * ca, -ct * sa, a * st],
                [0, sa, ca, d],
                [0, 0, 0, 1],
            ]
        )
        T = T @ A
    return float(np.linalg.det(np.column_stack(cols)))


def test_a_kinova_jaco2_condition_is_derived() -> None:
    """The JACO2 (Kinova's published DH table, its 60 degree curved wrist): the
    determinant comes out (it ran for many minutes in sympy's expression domain), and at
    the file's configuration its value is the numeric Jacobian's determinant."""
    import math

    import sympy

    path = Path(__file__).resolve().parent / "data" / "jaco2_dh.yaml"
    run = run_cli(["condition", path, "--config", "wrist", "--format", "json"])
    assert run.status == 0, run.err
    (c,) = json.loads(run.out)["conditions"]
    value = float(sympy.sympify(c["constant"]))
    for f in c["factors"]:
        value *= f["value"] ** f["power"]
    aa = math.pi / 6
    k = math.sin(aa) / math.sin(2 * aa)
    d4b, d5b, d6b = 0.2073 + k * 0.0741, 2 * k * 0.0741, k * 0.0741 + 0.16
    rows = [
        (0.2755, 0, math.pi / 2),
        (0, 0.41, math.pi),
        (-0.0098, 0, math.pi / 2),
        (-d4b, 0, 2 * aa),
        (-d5b, 0, 2 * aa),
        (-d6b, 0, math.pi),
    ]
    want = _dh_jacobian_det(rows, [0.3, 2.9, 1.3, 4.2, 0, 1])
    assert abs(abs(value) - abs(want)) <= 1e-9 * abs(want), (value, want)


def test_the_jansen_leg_type_ii_dyads(monkeypatch) -> None:
    """Theo Jansen's leg (his holy numbers): its type II condition has a factor for each
    dyad whose pivots come in line, c sin(t) + s cos(t) in the angle t one link of the dyad
    has turned relative to the other, with c/s = (u . v)/(u x v), u and v the links' arms
    from the common pivot at the drawn pose (cross(u, R(t) v) = (u . v) sin t + (u x v) cos t).
    The eliminations get no wall-clock limit: this test checks what is eliminated or
    refused by its cost, not the machine's speed (at a load of 18 on two cores one
    elimination ran past the 60 s of wall clock it is given)."""
    import sympy

    from mechsing.conditions import derive

    monkeypatch.setattr(derive, "ELIMINATION_SECONDS", None)

    path = Path(__file__).resolve().parent / "data" / "jansen_leg.yaml"
    run = run_cli(["condition", path, "--format", "json"])
    assert run.status == 0, run.err
    doc = json.loads(run.out)
    (c,) = [
        c
        for c in doc["conditions"]
        if c["name"] == "output (type II)" and c["form"] != "eliminated"
    ]
    pts = {
        "A": (0.075, 0.129903810568),
        "B": (-0.38, -0.078),
        "C": (-0.380094685529, 0.336999989198),
        "D": (-0.197334955621, -0.42596908133),
        "E": (-0.780155732298, -0.0519925028342),
        "F": (-0.561405049492, -0.3796876947),
    }
    dyads = {  # (the first link's far pivot, the common pivot, the second link's far pivot)
        "pivots Ak, Dk and Bc in line": ("A", "D", "B"),
        "pivots Aj, C and Bb in line": ("A", "C", "B"),
        "pivots E, F and Dg in line": ("E", "F", "D"),
    }
    found = 0
    for f in c["factors"]:
        (key,) = [k for k in dyads if k in (f["meaning"] or "")] or [None]
        if key is None:
            continue
        p, o, q = (pts[n] for n in dyads[key])
        u = (p[0] - o[0], p[1] - o[1])
        v = (q[0] - o[0], q[1] - o[1])
        want = (u[0] * v[0] + u[1] * v[1]) / (u[0] * v[1] - u[1] * v[0])
        e = sympy.sympify(f["expression"])
        (s,) = e.atoms(sympy.sin)
        (co,) = e.atoms(sympy.cos)
        got = float(e.coeff(s) / e.coeff(co))
        assert abs(abs(got) - abs(want)) < 1e-9 * abs(want), (key, got, want)
        found += 1
    assert found == 3, c["factors"]
    # the elimination of the output dyad (E, F and Dg in line: all three loops together,
    # coefficients of 160+ digits from the twelve-digit pivots) is refused at once, by
    # what it would cost, not after minutes of sympy: no condition in the input is given,
    # and each determinant says why (issue 44)
    assert not [c for c in doc["conditions"] if c["form"] == "eliminated"]
    notes = " ".join(doc["notes"])
    assert "within" not in notes  # no time limit was reached
    assert "output (type II): the passive joints were not eliminated: for rod_f and dfg" in notes
    assert "input (type I): the passive joints were not eliminated" in notes


def test_a_spherical_wrist_jaco2_names_its_wrist_elbow_and_shoulder_factors() -> None:
    """The JACO2 with its spherical wrist (Kinova's j2s6s300 DH table): a Pieper arm, so
    its determinant is a wrist factor (J5), an elbow factor (J3) and a shoulder factor,
    each named so (the wrist's first and last axes coinciding had read "shoulder"), and
    exact (the table's frames had been taken in floats: one unfactored factor with
    70-digit radicals).  Checked against the arm's 6x6 joint-twist determinant worked
    with numpy from the DH table: the product at random joint values, and each factor's
    zero a zero of it."""
    import math
    import random

    import numpy as np
    import sympy

    path = Path(__file__).resolve().parent / "data" / "jaco2_spherical_dh.yaml"
    run = run_cli(["condition", path, "--config", "wrist", "--format", "json"])
    assert run.status == 0, run.err
    (c,) = json.loads(run.out)["conditions"]
    d1, d2, e2, d4, d6 = 0.2755, 0.41, 0.0098, 0.2073 + 0.1038, 0.1038 + 0.16
    rows = [
        (d1, 0, math.pi / 2),
        (0, d2, math.pi),
        (-e2, 0, math.pi / 2),
        (-d4, 0, math.pi / 2),
        (0, 0, math.pi / 2),
        (-d6, 0, math.pi),
    ]
    J = sympy.symbols("J1:7")
    names = {str(s): s for s in J}
    constant = sympy.sympify(c["constant"])
    factors = [(sympy.sympify(f["expression"], locals=names), f) for f in c["factors"]]
    rng = random.Random(3)
    for _ in range(3):
        q = [rng.uniform(-math.pi, math.pi) for _ in range(6)]
        got = float(constant) * math.prod(
            float(e.subs(dict(zip(J, q, strict=True)))) ** f["power"] for e, f in factors
        )
        want = _dh_jacobian_det(rows, q)
        assert abs(got - want) <= 1e-9 * abs(want), (got, want)
    by_name = {(f["meaning"] or "").split(":")[0]: e for e, f in factors}
    assert set(by_name) == {"wrist", "elbow", "shoulder"}, [f["meaning"] for _, f in factors]
    assert by_name["wrist"].free_symbols == {J[4]}
    assert by_name["elbow"].free_symbols == {J[2]}
    # each factor's zero (its first variable bisected, the others random) is the arm's
    samples = np.random.default_rng(1).uniform(-3, 3, (5, 6))
    scale = max(abs(_dh_jacobian_det(rows, list(p))) for p in samples)
    for e in by_name.values():
        var = sorted(e.free_symbols, key=str)[0]
        q = [rng.uniform(-math.pi, math.pi) for _ in range(6)]
        f = sympy.lambdify(var, e.subs({s: v for s, v in zip(J, q, strict=True) if s != var}))
        grid = np.linspace(-math.pi, math.pi, 721)
        k = next(i for i in range(720) if f(grid[i]) * f(grid[i + 1]) <= 0)
        lo, hi = grid[k], grid[k + 1]
        for _ in range(60):
            mid = (lo + hi) / 2
            lo, hi = (lo, mid) if f(lo) * f(mid) <= 0 else (mid, hi)
        q[J.index(var)] = lo
        assert abs(_dh_jacobian_det(rows, q)) < 1e-12 * scale
