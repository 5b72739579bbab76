"""``mechsing condition --symbolic`` on one-input linkages: the passive joints eliminated with
the named parameters kept as symbols, each condition in the input alone checked against a
derivation written here (law of cosines, the geometry of the dyads), never mechsing's."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import sympy

from tests.cli import ROOT, run_cli

EXAMPLES = ROOT / "examples"
#: the quick return with its crank r and centre distance d as named parameters
QUICK_RETURN = EXAMPLES / "exercises" / "16-quick-return-extremes" / "mechanism.yaml"
#: where the scans of the crank angle start (no root there)
START = 0.1234

# a four-bar with its crank r, ground d and the coupler-rocker pivot C = (cx, cy) named
FOUR_BAR = """\
mechanism: four-bar-named
parameters: {r: 1, d: 4, cx: 3, cy: 2}
bodies: [ground, crank, coupler, rocker]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, coupler], axis: [0, 0, 1], point: [r, 0, 0]}
  - {name: C, type: R, between: [coupler, rocker], axis: [0, 0, 1], point: [cx, cy, 0]}
  - {name: D, type: R, between: [rocker, ground], axis: [0, 0, 1], point: [d, 0, 0]}
inputs: [A]
output: {body: rocker}
"""

# a centred slider-crank, crank r and rod l, drawn at its outer dead centre
SLIDER_CRANK = """\
mechanism: slider-crank-named
parameters: {r: 1, l: 3}
bodies: [ground, crank, rod, slider]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, rod], axis: [0, 0, 1], point: [r, 0, 0]}
  - {name: C, type: R, between: [rod, slider], axis: [0, 0, 1], point: [r + l, 0, 0]}
  - {name: P, type: P, between: [ground, slider], axis: [1, 0, 0]}
inputs: [A]
output: {body: slider}
"""


def _json(argv: list[str]) -> dict:
    run = run_cli(["condition", *argv, "--format", "json"])
    assert run.status == 0, run.err
    return json.loads(run.out)


def _named(doc: dict, name: str) -> dict:
    (c,) = [c for c in doc["conditions"] if c["name"] == name]
    return c


def _product(c: dict) -> sympy.Expr:
    out = sympy.Integer(1)
    for f in c["factors"]:
        out *= sympy.sympify(f["expression"]) ** f["power"]
    return out


def _proportional(expr: sympy.Expr, closed: sympy.Expr, variable: str) -> bool:
    """``expr / closed`` is free of the variable (a constant in the parameters)."""
    ratio = sympy.cancel(sympy.expand(expr) / sympy.expand(closed))
    return sympy.Symbol(variable) not in ratio.free_symbols and ratio != 0


def test_four_bar_limit_and_toggle_positions_with_symbols(tmp_path: Path) -> None:
    path = tmp_path / "fourbar.yaml"
    path.write_text(FOUR_BAR)
    doc = _json([str(path), "--symbolic", "r,d,cx,cy"])
    r, d, cx, cy, A, l = sympy.symbols("r d cx cy A l")
    l2 = (cx - r) ** 2 + cy**2  # coupler B-C squared
    b2 = (cx - d) ** 2 + cy**2  # rocker C-D squared
    # Hartenberg & Denavit: crank and coupler in line, C at r + l or r - l from A along the
    # crank, on the rocker's circle: (r +- l)^2 + d^2 - 2 d (r +- l) cos A = b^2
    limit = sympy.expand(
        ((r + l) ** 2 + d**2 - b2 - 2 * d * (r + l) * sympy.cos(A))
        * ((r - l) ** 2 + d**2 - b2 - 2 * d * (r - l) * sympy.cos(A))
    )
    limit = sympy.expand(limit.subs(l, sympy.sqrt(l2)))
    lim = _named(doc, "input (type I) in the input A")
    assert _proportional(_product(lim), limit, "A")
    assert {f["meaning"] for f in lim["factors"]} == {
        "crank and coupler in line (pivots A, B and C in line)"
    }
    # toggle: coupler and rocker in line, |BD|^2 = r^2 + d^2 - 2 r d cos A = (l +- b)^2
    bd2 = r**2 + d**2 - 2 * r * d * sympy.cos(A)
    toggle = sympy.expand((bd2 - l2 - b2) ** 2 - 4 * l2 * b2)
    tog = _named(doc, "output (type II) in the input A")
    assert _proportional(_product(tog), toggle, "A")
    assert {f["meaning"] for f in tog["factors"]} == {
        "coupler and rocker in line (pivots B, C and D in line)"
    }
    for c in (lim, tog):
        assert c["form"] == "eliminated" and c["variables"] == ["A"]
        assert all(f["latex"] for f in c["factors"]) and c["latex"]


def test_slider_crank_dead_centres_with_symbols(tmp_path: Path) -> None:
    path = tmp_path / "slider.yaml"
    path.write_text(SLIDER_CRANK)
    doc = _json([str(path), "--symbolic", "r,l"])
    r, l, A = sympy.symbols("r l A")
    # dead centres: crank and rod in line along the stroke, the crank pin on the line of
    # the slide (y = r sin A = 0); the rod perpendicular to the slide when r sin A = +- l
    dead = _named(doc, "input (type I) in the input A")
    assert _proportional(_product(dead), sympy.sin(A), "A")
    assert "crank and rod in line" in dead["factors"][0]["meaning"]
    notes = " ".join(doc["notes"])
    perpendicular = [c for c in doc["conditions"] if c["name"] == "output (type II) in the input A"]
    if perpendicular:  # r = 1 < l = 3: never reached at the file's values
        assert _proportional(_product(perpendicular[0]), r**2 * sympy.sin(A) ** 2 - l**2, "A")
    else:
        assert "output (type II): no configuration" in notes


def test_quick_return_extremes_of_the_lever() -> None:
    doc = _json([str(QUICK_RETURN), "--symbolic", "r,d"])
    r, d, A = sympy.symbols("r d A")
    ext = _named(doc, "input (type I) in the input A")
    # the lever is tangent to the crank circle: right angle at B in the triangle A B C,
    # cos(angle between AB and AC) = r/d with A measured away from C: d cos A + r = 0
    assert _proportional(_product(ext), d * sympy.cos(A) + r, "A")
    assert ext["factors"][0]["meaning"] == "crank (pivots A and B) perpendicular to the slide of S"
    md = run_cli(["condition", str(QUICK_RETURN), "--symbolic", "r,d", "--format", "md"])
    assert md.status == 0
    assert r"$d \cos{\left(A \right)} + r = 0$" in md.out


def _four_bar_branches(theta: float) -> list[tuple[float, float]]:
    """Angles (coupler, rocker) the bodies have turned from their drawn pose, for the four-bar
    A = (0, 0), B = (1, 0), C = (3, 2), D = (4, 0) at crank angle theta (circle intersection)."""
    B = np.array([math.cos(theta), math.sin(theta)])
    D = np.array([4.0, 0.0])
    l, b = math.sqrt(8.0), math.sqrt(5.0)
    v = D - B
    dist = np.linalg.norm(v)
    a = (l**2 - b**2 + dist**2) / (2 * dist)
    h2 = l**2 - a**2
    if h2 < 0:
        return []
    out = []
    for sign in (1, -1):
        C = B + a * v / dist + sign * math.sqrt(h2) * np.array([-v[1], v[0]]) / dist
        coupler = math.atan2(*(C - B)[::-1]) - math.atan2(2.0, 2.0)
        rocker = math.atan2(*(C - D)[::-1]) - math.atan2(2.0, -1.0)
        out.append((coupler, rocker))
    return out


def _rot(angle: float, v: tuple[float, float]) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def _toggles(E_of, F: np.ndarray, m: float, n: float) -> list[float]:
    """Crank angles where the output dyad E-G-F is in line: |E - F| = m + n or |m - n|, on a
    fine grid (sign changes, refined by bisection)."""

    def gap(theta: float, branch: int) -> float:
        poses = _four_bar_branches(theta)
        if len(poses) <= branch:
            return float("nan")
        dist = np.linalg.norm(E_of(theta, *poses[branch]) - F)
        return (dist - (m + n)) * (dist - abs(m - n))

    found = []
    grid = np.linspace(START, START + 2 * math.pi, 4001)
    for branch in (0, 1):
        vals = [gap(t, branch) for t in grid]
        for t0, t1, v0, v1 in zip(grid, grid[1:], vals, vals[1:], strict=False):
            if np.isfinite(v0) and np.isfinite(v1) and v0 * v1 < 0:
                lo, hi = t0, t1
                for _ in range(60):
                    mid = (lo + hi) / 2
                    if gap(lo, branch) * gap(mid, branch) <= 0:
                        hi = mid
                    else:
                        lo = mid
                found.append((lo + hi) / 2)
    return sorted(found)


def _real_roots(expr: sympy.Expr, values: dict[str, float]) -> list[float]:
    A = sympy.Symbol("A")
    f = sympy.lambdify(A, expr.subs({sympy.Symbol(k): v for k, v in values.items()}), "numpy")
    grid = np.linspace(START, START + 2 * math.pi, 20001)
    vals = f(grid)
    out = []
    for t0, t1, v0, v1 in zip(grid, grid[1:], vals, vals[1:], strict=False):
        if v0 * v1 < 0:
            out.append(float((t0 + t1) / 2))
    return out


def _dyad_factors(c: dict) -> sympy.Expr:
    out = sympy.Integer(1)
    for f in c["factors"]:
        if f["meaning"].startswith("link and output in line"):
            out *= sympy.sympify(f["expression"])
    return out


def test_watt_ii_toggles_of_the_output_dyad(tmp_path: Path) -> None:
    # the first four-bar's rocker carries E = (5, 1) about D = (4, 0); the output dyad E-G-F
    # has the lengths m (symbolic) and n = 2, F = (5 + m, 1 - n): examples/watt_ii.yaml with
    # its dyad's lengths named
    text = (
        (EXAMPLES / "watt_ii.yaml")
        .read_text()
        .replace("bodies: [ground", "parameters: {m: 2, n: 2}\nbodies: [ground")
        .replace("point: [7, 1, 0]", 'point: ["5 + m", 1, 0]')
        .replace("point: [7, -1, 0]", 'point: ["5 + m", "1 - n", 0]')
    )
    path = tmp_path / "watt_ii.yaml"
    path.write_text(text)
    doc = _json([str(path), "--symbolic", "m"])
    tog = _named(doc, "output (type II) in the input A")
    assert "m" in {str(s) for s in _dyad_factors(tog).free_symbols}
    reached = 0
    for m in (2.0, 2.4, 1.7):
        n = 2.0
        F = np.array([5 + m, 1 - n])

        def E_of(theta: float, coupler: float, rocker: float) -> np.ndarray:
            return np.array([4.0, 0.0]) + _rot(rocker, (1.0, 1.0))

        expected = _toggles(E_of, F, m, n)
        got = _real_roots(_dyad_factors(tog), {"m": m})
        assert len(got) == len(expected)
        assert np.allclose(got, expected, atol=1e-3)
        reached += len(expected)
    assert reached  # the toggles of the output dyad are reached at one of the values


def test_gough_stewart_constant_orientation_cubic() -> None:
    # Dietmaier's 6-6 platform at the generic orientation the file draws: the leg lines'
    # determinant (Plücker coordinates (u, b x u), u from base to platform pivot), computed
    # here with numpy from the file's points, at 20 random positions of the platform
    import yaml

    path = EXAMPLES / "stewart_dietmaier.yaml"
    doc = _json([str(path)])
    (c,) = doc["conditions"]
    x, y, z = sympy.symbols("x y z")
    expr = sympy.sympify(c["expression"])
    assert sympy.Poly(expr, x, y, z).total_degree() == 3
    f = sympy.lambdify((x, y, z), expr, "numpy")
    data = yaml.safe_load(path.read_text())
    joints = {j["name"]: j for j in data["joints"]}
    a = np.array([[float(v) for v in joints[f"U{i}"]["point"]] for i in range(1, 7)])
    b0 = np.array([[float(v) for v in joints[f"S{i}"]["point"]] for i in range(1, 7)])
    c0 = np.array([float(v) for v in data["output"]["point"]])
    rng = np.random.default_rng(5)
    mine, theirs = [], []
    for _ in range(20):
        t = c0 + rng.uniform(-1, 1, 3)
        b = b0 - c0 + t
        u = b - a
        theirs.append(np.linalg.det(np.hstack([u, np.cross(b, u)])))
        mine.append(float(f(*t)))
    scale = max(abs(v) for v in theirs)
    assert np.allclose(mine, theirs, rtol=1e-9, atol=1e-9 * scale)


def test_octahedral_platform_cubic_is_a_power_of_z() -> None:
    doc = _json([str(EXAMPLES / "stewart_octahedral.yaml")])
    (c,) = doc["conditions"]
    assert [(f["expression"], f["power"]) for f in c["factors"]] == [("z", 3)]
    assert c["latex"].endswith("z^{3}")


def test_stephenson_iii_toggles_of_the_output_dyad(tmp_path: Path) -> None:
    # the coupler B-C-E of the four-bar carries E = (2, 3); the output dyad E-G-F has the
    # lengths m (symbolic) and n = 2, F = (2 + m, 3 - n): examples/stephenson_iii.yaml with its
    # dyad's lengths named. The published toggle (Hartenberg & Denavit): the link E-G and the
    # output G-F in line, |E - F| = m + n or |m - n|, with E the coupler point of the four-bar
    text = (
        (EXAMPLES / "stephenson_iii.yaml")
        .read_text()
        .replace("bodies: [ground", "parameters: {m: 3, n: 2}\nbodies: [ground")
        .replace("point: [5, 3, 0]", 'point: ["2 + m", 3, 0]')
        .replace("point: [5, 1, 0]", 'point: ["2 + m", "3 - n", 0]')
    )
    path = tmp_path / "stephenson_iii.yaml"
    path.write_text(text)
    # the time limit only keeps a loaded machine's wall clock from cutting the elimination
    # short (about 35 s of one quiet core for both conditions)
    doc = _json([str(path), "--symbolic", "m", "--time-limit", "1200"])
    tog = _named(doc, "output (type II) in the input A")
    assert "m" in {str(s) for s in _dyad_factors(tog).free_symbols}
    reached = 0
    for m in (3.0, 0.6, 0.75):  # the file's m, and two where |m - n| is reached
        n = 2.0
        F = np.array([2 + m, 3 - n])

        def E_of(theta: float, coupler: float, rocker: float) -> np.ndarray:
            B = np.array([math.cos(theta), math.sin(theta)])
            return B + _rot(coupler, (1.0, 3.0))

        expected = _toggles(E_of, F, m, n)
        got = _real_roots(_dyad_factors(tog), {"m": m})
        assert len(got) == len(expected)
        assert np.allclose(got, expected, atol=1e-3)
        reached += len(expected)
    assert reached  # the toggles of the output dyad are reached at one of the values


def test_tsai_3upu_constraint_and_actuation_in_the_pose() -> None:
    # Tsai's 3-UPU: leg i from the ground pivot a_i (U, first axis s1 fixed in the ground) to
    # the platform pivot b_i = b_i0 + t - c0; its second axis s2 = s1 x u is normal to s1 and
    # to the leg u = b - a. Its constraint couple n_i = s1 x s2 (Zlatanov, Bonev, Gosselin
    # 2002), checked here to be reciprocal to the leg's five joint screws; the actuation
    # wrench is the force along the leg. Everything below is numpy on the file's numbers.
    import yaml

    path = EXAMPLES / "tsai_3upu.yaml"
    doc = _json([str(path)])
    constraint = _named(doc, "constraint")
    actuation = _named(doc, "output (type II)")
    x, y, z = sympy.symbols("x y z")
    f_con = sympy.lambdify((x, y, z), sympy.sympify(_product(constraint)), "numpy")
    f_act = sympy.lambdify((x, y, z), sympy.sympify(_product(actuation)), "numpy")
    data = yaml.safe_load(path.read_text())
    joints = {j["name"]: j for j in data["joints"]}

    def vec(v: list) -> np.ndarray:
        return np.array([float(sympy.sympify(c)) for c in v])

    legs = [
        (
            vec(joints[f"U{i}a"]["point"]),
            vec(joints[f"U{i}b"]["point"]),
            vec(joints[f"U{i}a"]["axes"][0]),
        )
        for i in (1, 2, 3)
    ]
    c0 = np.mean([b for _, b, _ in legs], axis=0)  # the output's reference point: the centroid

    def wrenches(t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        U, N, rows = [], [], []
        for a, b0, s1 in legs:
            b = b0 + t - c0
            u = b - a
            s2 = np.cross(s1, u)
            n = np.cross(s1, s2)
            # the leg's screws (omega, v): s1 and s2 through a, the slide, s2 and s1 through b
            screws = [
                np.r_[s1, np.cross(a, s1)],
                np.r_[s2, np.cross(a, s2)],
                np.r_[np.zeros(3), u],
                np.r_[s2, np.cross(b, s2)],
                np.r_[s1, np.cross(b, s1)],
            ]
            couple = np.r_[np.zeros(3), n]  # (force, moment)
            for s in screws:  # reciprocal: force . v + moment . omega = 0
                assert abs(couple[:3] @ s[3:] + couple[3:] @ s[:3]) < 1e-9 * np.linalg.norm(n)
            U.append(u)
            N.append(n)
            rows.append(np.r_[u, np.cross(a, u)])
        rows += [np.r_[np.zeros(3), n] for n in N]
        return np.array(U), np.array(N), np.array(rows)

    rng = np.random.default_rng(7)
    ratios_con, ratios_act = [], []
    for _ in range(20):
        t = c0 + rng.uniform(-1.5, 1.5, 3)
        _, N, W = wrenches(t)
        ratios_con.append(f_con(*t) / np.linalg.det(N))
        ratios_act.append(f_act(*t) / np.linalg.det(W))
    assert np.allclose(ratios_con, ratios_con[0], rtol=1e-9)
    assert np.allclose(ratios_act, ratios_act[0], rtol=1e-9)
    # the published singular pose: the flat one (platform in the base plane) is a
    # constraint singularity, where the couples lose rank; the raised pose (height 2) is not
    flat = c0 - np.array([0.0, 0.0, 1.0])
    assert np.linalg.matrix_rank(wrenches(flat)[1], tol=1e-9) < 3 and abs(f_con(*flat)) < 1e-12
    raised = c0 + np.array([0.0, 0.0, 1.0])
    assert np.linalg.matrix_rank(wrenches(raised)[2], tol=1e-9) == 6 and abs(f_act(*raised)) > 0.1
    # each factor carries its meaning
    assert all("constraint couples" in f["meaning"] for f in constraint["factors"])
    assert any("parallel to one plane" in f["meaning"] for f in actuation["factors"])
    assert all(f["latex"] for f in actuation["factors"])


# a slider-crank whose slide runs along [a, b] (symbols: the loader normalises the axis by
# sqrt(a^2 + b^2)), through C = (r + l, 0)
INCLINED = """\
mechanism: slider-crank-inclined
parameters: {r: 1, l: 3, a: 2, b: 1}
bodies: [ground, crank, rod, slider]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, rod], axis: [0, 0, 1], point: [r, 0, 0]}
  - {name: C, type: R, between: [rod, slider], axis: [0, 0, 1], point: [r + l, 0, 0]}
  - {name: P, type: P, between: [ground, slider], axis: [a, b, 0]}
inputs: [A]
output: {body: slider}
"""


def test_slide_axis_with_symbols_is_eliminated(tmp_path: Path) -> None:
    path = tmp_path / "inclined.yaml"
    path.write_text(INCLINED)
    doc = _json([str(path), "--symbolic", "r,l,a,b"])
    r, l, a, b, A = sympy.symbols("r l a b A")
    c, s = sympy.cos(A), sympy.sin(A)
    # dead centres: crank and rod in line, C = (r +- l)(cos A, sin A), on the slide's line
    # through (r + l, 0) along (a, b): the cross product with (a, b) vanishes
    dead = sympy.Integer(1)
    for k in (r + l, r - l):
        dead *= b * (k * c - (r + l)) - a * k * s
    # the rod perpendicular to the slide: C = B +- l (-b, a)/|(a, b)| on the slide's line
    perpendicular = (b * (r * c - r - l) - a * r * s) ** 2 - l**2 * (a**2 + b**2)
    perpendicular = sympy.expand(perpendicular).subs(s**2, 1 - c**2)  # on the circle
    assert _proportional(_product(_named(doc, "input (type I) in the input A")), dead, "A")
    assert _proportional(
        _product(_named(doc, "output (type II) in the input A")), perpendicular, "A"
    )
    assert any("P joint P (axis [a, b])" in n for n in doc["notes"])
