"""Independent checks of the bundled example mechanisms (examples/*.yaml).

Nothing here imports mechsing: the files are read by the tests' reference implementation
(tests/reference: yaml.safe_load, a whitelisted AST walker for expressions, joint screws and poses
from the file geometry with numpy / scipy.linalg.expm, passive joints solved by continuation,
loops found with networkx). Each example also gets one check of a published fact.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from tests.reference.expressions import evaluate, vec
from tests.reference.files import MechanismFile
from tests.reference.se3 import revolute, unit

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
TOL = 1e-10


ALL = sorted(p.name for p in EXAMPLES.glob("*.yaml"))
EXPECTED = {
    "fourbar.yaml",
    "fourbar_changepoint.yaml",
    "parallelogram.yaml",
    "slider_crank_crank_input.yaml",
    "slider_crank_slider_input.yaml",
    "spherical_4r.yaml",
    "bennett.yaml",
    "bricard.yaml",
    "sarrus.yaml",
    "planar_3rpr.yaml",
    "tsai_3upu.yaml",
    "stewart_octahedral.yaml",
    "ur5.yaml",
    "puma560.yaml",
    "double_rocker.yaml",
    "five_bar.yaml",
}
_M: dict[str, MechanismFile] = {}


def mech(name) -> MechanismFile:
    if name not in _M:
        _M[name] = MechanismFile(EXAMPLES / name)
    return _M[name]


def test_all_examples_present():
    assert EXPECTED <= set(ALL)


@pytest.mark.parametrize("name", ALL)
def test_file_header_and_references(name):
    text = (EXAMPLES / name).read_text()
    assert text.startswith("#"), "each example starts with a comment block"
    assert "Source:" in text.split("\nmechanism:")[0]
    m = mech(name)
    names = {j.name for j in m.joints}
    assert len(names) == len(m.joints)
    for j in m.joints:
        assert j.a in m.bodies and j.b in m.bodies and j.a != j.b
    for i in m.data.get("inputs", []):
        assert str(i).split("[")[0] in names
    assert "reference" in m.data["configurations"]
    for cname, cfg in m.data["configurations"].items():
        cfg = cfg or {}
        assert set(cfg) - {"start"} <= names, cname
        if "start" in cfg:
            assert cfg["start"] in m.data["configurations"]
    # loop count invariant E - V + 1 (a U joint counts once)
    assert len(m.loops()) == len(m.joints) - len(m.bodies) + 1


@pytest.mark.parametrize("name", ALL)
def test_every_configuration_closes(name):
    m = mech(name)
    for cname in m.data["configurations"]:
        q = m.solve(cname)
        assert m.loop_residual(q) < TOL, (name, cname, m.loop_residual(q))


# ----------------------------------------------------------------------------- published facts


def planar_pts(m, q, jn):
    """current position (x, y) of an R joint's axis point."""
    j = m.joints[m.jidx[jn]]
    g = m.poses(q)[j.a]
    p = vec(m.raw[jn]["point"]) * m.lf
    return (g[:3, :3] @ p + g[:3, 3])[:2]


def rank(A, rel=1e-9):
    s = np.linalg.svd(A, compute_uv=False)
    return int((s > rel * s[0]).sum())


def test_fourbar_grashof_crank_rocker():
    m = mech("fourbar.yaml")
    P = [vec(m.data["joints"][i]["point"]) for i in range(4)]
    links = sorted(np.linalg.norm(P[(i + 1) % 4] - P[i]) for i in range(4))
    assert links[0] + links[3] < links[1] + links[2]  # Grashof
    assert np.isclose(np.linalg.norm(P[1] - P[0]), links[0])  # shortest = crank (on ground)
    for c in m.data["configurations"]:
        q = m.solve(c)
        assert rank(m.current_screws(q)) == 3  # regular everywhere
        # passive joints (B, C, D) keep full rank: no toggle
        assert rank(m.current_screws(q, {"B", "C", "D"})) == 3
    assert np.isclose(m.solve("crank-200")[0], math.radians(200))


def test_changepoint_flat_is_singular():
    m = mech("fourbar_changepoint.yaml")
    P = [vec(m.data["joints"][i]["point"]) for i in range(4)]
    links = sorted(np.linalg.norm(P[(i + 1) % 4] - P[i]) for i in range(4))
    assert np.isclose(links[0] + links[3], links[1] + links[2])  # change point
    assert np.allclose(np.array(P)[:, 1], 0)  # the reference is flat
    assert rank(m.current_screws(m.solve("reference"))) == 2
    for c in ("crank-up", "crank-120"):
        assert rank(m.current_screws(m.solve(c))) == 3


def test_parallelogram_two_branches_cross_at_flat():
    m = mech("parallelogram.yaml")
    assert rank(m.current_screws(m.solve("flat"))) == 2
    for c, parallel in (("reference", True), ("crank-30", True), ("anti-parallelogram", False)):
        q = m.solve(c)
        assert rank(m.current_screws(q)) == 3
        B, C = planar_pts(m, q, "B"), planar_pts(m, q, "C")
        assert np.isclose(C[1] - B[1], 0) == parallel  # coupler parallel to ground?


@pytest.mark.parametrize(
    "name,inp", [("slider_crank_crank_input.yaml", "A"), ("slider_crank_slider_input.yaml", "P")]
)
def test_slider_crank_dead_centre(name, inp):
    m = mech(name)
    assert m.data["inputs"] == [inp]
    q = m.solve("dead-centre")
    A, B, C = (planar_pts(m, q, j) for j in "ABC")
    assert abs((B - A)[0] * (C - A)[1] - (B - A)[1] * (C - A)[0]) < 1e-12  # crank and rod collinear
    J = m.current_screws(q)
    assert rank(J) == 3  # c-space regular
    passive = {"B", "C", "P"} if inp == "A" else {"A", "B", "C"}
    # crank input: passive system fine, slider rate zero (type I); slider input: passive rank drops (type II)
    assert rank(m.current_screws(q, passive)) == (3 if inp == "A" else 2)
    ker = np.linalg.svd(J)[2][-1]
    assert abs(ker[m.cidx[("P", 0)]]) < 1e-12 * np.max(np.abs(ker))
    for c in m.data["configurations"]:
        if c != "dead-centre":
            assert rank(m.current_screws(m.solve(c), passive)) == 3


def test_double_rocker_non_grashof_limits():
    m = mech("double_rocker.yaml")
    P = [vec(m.data["joints"][i]["point"]) for i in range(4)]
    links = sorted(np.linalg.norm(P[(i + 1) % 4] - P[i]) for i in range(4))
    assert links[0] + links[3] > links[1] + links[2]  # non-Grashof: no link turns fully
    for c in m.data["configurations"]:
        q = m.solve(c)
        A, B, C, D = (planar_pts(m, q, j) for j in "ABCD")
        passive = rank(m.current_screws(q, {"B", "C", "D"}))
        assert rank(m.current_screws(q)) == 3  # c-space regular everywhere
        if c == "limit":  # coupler and output stretched: the input's limit, at 120 deg
            assert np.isclose(q[0], 2 * math.pi / 3)
            assert np.isclose(np.linalg.norm(D - B), 7) and passive == 2
        else:
            assert passive == 3
        # input and coupler aligned (the output's limit) only at output-limit
        aligned = abs((B - A)[0] * (C - A)[1] - (B - A)[1] * (C - A)[0]) < 1e-12
        assert aligned == (c == "output-limit")


def test_five_bar_type1_and_type2():
    m = mech("five_bar.yaml")

    def cross(u, v):
        return u[0] * v[1] - u[1] * v[0]

    for c in m.data["configurations"]:
        q = m.solve(c)
        A1, B1, P, B2, A2 = (planar_pts(m, q, j) for j in ("A1", "B1", "P", "B2", "A2"))
        type1 = cross(P - B1, B1 - A1) * cross(P - B2, B2 - A2)
        type2 = cross(P - B1, P - B2)
        assert rank(m.current_screws(q)) == 3
        assert (abs(type1) < 1e-12) == (c == "type1")  # leg 1 stretched
        assert (abs(type2) < 1e-12) == (c == "type2")  # distal links aligned
        # the passive joints lose rank exactly at the Type II pose
        assert rank(m.current_screws(q, {"B1", "P", "B2"})) == (2 if c == "type2" else 3)


def test_spherical_4r_concurrent_rank3():
    m = mech("spherical_4r.yaml")
    for c in m.data["configurations"]:
        J = m.current_screws(m.solve(c))
        assert np.allclose(J[3:], 0, atol=1e-12)  # all axes through O
        assert rank(J) == 3
        assert rank(m.current_screws(m.solve(c), {"B", "C", "D"})) == 3


def test_bennett_rank3_and_relation():
    m = mech("bennett.yaml")
    tan_a, tan_b = 1 / 3, 3 / 4
    K = (tan_b + tan_a) / (tan_b - tan_a)
    th1_ref, th2_ref = 2 * math.atan(1 / 2), 2 * math.atan(26 / 5)
    for c in m.data["configurations"]:
        q = m.solve(c)
        s = np.linalg.svd(m.current_screws(q), compute_uv=False)
        assert s[2] > 1e-3 and s[3] < 1e-10  # rank 3 along the motion
        t1, t2 = math.tan((th1_ref + q[0]) / 2), math.tan((th2_ref + q[1]) / 2)
        assert math.isclose(t1 * t2, K, rel_tol=1e-9)  # Bennett relation
        assert np.allclose(
            [q[2], q[3]], [-q[0], -q[1]], atol=1e-9
        )  # theta3 = -theta1, theta4 = -theta2
    # exact metric data: b = a sin(beta)/sin(alpha), and the relation's constant 13/5
    assert math.isclose(K, 13 / 5)


def test_bennett_closes_exactly():
    sp = pytest.importorskip("sympy")
    m = mech("bennett.yaml")
    funcs = {"sqrt": sp.sqrt, "atan": sp.atan, "sin": sp.sin, "cos": sp.cos, "tan": sp.tan}

    def ex(x):  # exact value: integers and decimals as rationals
        return evaluate(x, funcs, const=lambda v: sp.Rational(str(v)), pi=sp.pi)

    for c in ("theta1-90", "q1-half"):
        M = sp.eye(4)
        for j, (jn, v) in zip(m.data["joints"], m.data["configurations"][c].items(), strict=True):
            assert j["name"] == jn
            u = sp.Matrix([ex(x) for x in j["axis"]])
            p = sp.Matrix([ex(x) for x in j["point"]])
            th = ex(v)
            cth = sp.simplify(sp.expand_trig(sp.cos(th)))
            sth = sp.simplify(sp.expand_trig(sp.sin(th)))
            Kx = sp.Matrix([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
            R = sp.eye(3) + sth * Kx + (1 - cth) * Kx * Kx
            T = sp.eye(4)
            T[:3, :3] = R
            T[:3, 3] = (sp.eye(3) - R) * p
            M = M * T
        assert sp.simplify(M - sp.eye(4)) == sp.zeros(4)


def test_bricard_rank5_and_line_symmetry():
    m = mech("bricard.yaml")
    for c in m.data["configurations"]:
        q = m.solve(c)
        s = np.linalg.svd(m.current_screws(q), compute_uv=False)
        assert s[4] > 1e-3 and s[5] < 1e-10
        assert np.allclose(q[3:], q[:3], atol=1e-8)  # q4 = q1, q5 = q2, q6 = q3
    assert abs(m.solve("q1-0.4")[0] - 0.4) < 1e-14


def test_sarrus_translation_and_rank():
    m = mech("sarrus.yaml")
    ranks = {}
    for c in m.data["configurations"]:
        q = m.solve(c)
        g = m.poses(q)["top"]
        assert np.allclose(g[:3, :3], np.eye(3), atol=1e-10) and np.allclose(
            g[:2, 3], 0, atol=1e-10
        )
        ranks[c] = rank(m.current_screws(q))
    assert ranks == {"reference": 5, "raised": 5, "lowered": 5, "stretched": 4}
    assert np.isclose(m.poses(m.solve("stretched"))["top"][2, 3], 2 * math.sqrt(2) - 2)


def _leg_lines_3rpr(m, q):
    lines = []
    for i in (1, 2, 3):
        a, b = planar_pts(m, q, f"Rb{i}"), planar_pts(m, q, f"Rp{i}")
        lines.append(np.r_[b - a, a[0] * b[1] - a[1] * b[0]])  # planar line coordinates
    return np.array(lines)


def test_3rpr_legs_concurrent_at_output_singularity():
    m = mech("planar_3rpr.yaml")
    det = {c: np.linalg.det(_leg_lines_3rpr(m, m.solve(c))) for c in m.data["configurations"]}
    assert abs(det["concurrent"]) < 1e-12
    assert abs(det["reference"]) > 1e-2 and abs(det["stroke"]) > 1e-2
    # the platform pivots are the base halved about c = (1, 1) at the concurrent pose
    q = m.solve("concurrent")
    for i in (1, 2, 3):
        a, b = planar_pts(m, q, f"Rb{i}"), planar_pts(m, q, f"Rp{i}")
        assert np.allclose(b, (a + np.array([1.0, 1.0])) / 2)


def _tsai_det_n(m, q):
    g = m.poses(q)
    ns = []
    for i in (1, 2, 3):
        raw = m.raw[f"U{i}a"]
        s1 = unit(vec(raw["axes"][0]))  # fixed in ground
        s2 = g[f"cyl{i}"][:3, :3] @ unit(vec(raw["axes"][1]))  # carried by the cylinder
        ns.append(np.cross(s1, s2))
    return np.linalg.det(np.array(ns))


def test_tsai_3upu_translational_and_constraint_singularity():
    m = mech("tsai_3upu.yaml")
    for c in m.data["configurations"]:
        q = m.solve(c)
        assert np.allclose(m.poses(q)["platform"][:3, :3], np.eye(3), atol=1e-10)  # T3
        d = _tsai_det_n(m, q)
        if c == "flat":
            assert abs(d) < 1e-12
        else:
            assert abs(d) > 1e-2, (c, d)
    assert np.isclose(m.poses(m.solve("raised"))["platform"][2, 3], 1.0)


def test_stewart_octahedral_rotation_singularity():
    m = mech("stewart_octahedral.yaml")
    for c in m.data["configurations"]:
        q = m.solve(c)
        g = m.poses(q)
        lines = []
        for k in range(1, 7):
            a = g[f"cyl{k}"] @ np.r_[vec(m.raw[f"U{k}"]["point"]), 1]
            b = g[f"pis{k}"] @ np.r_[vec(m.raw[f"S{k}"]["point"]), 1]
            lines.append(revolute(b[:3] - a[:3], a[:3]))
        s = np.linalg.svd(np.array(lines), compute_uv=False)
        if c == "reference":
            assert s[5] / s[0] > 1e-2
        else:
            R = g["platform"][:3, :3]
            phi = math.pi / 2 if c.endswith("+90") else -math.pi / 2
            assert np.allclose(
                R,
                [[math.cos(phi), -math.sin(phi), 0], [math.sin(phi), math.cos(phi), 0], [0, 0, 1]],
                atol=1e-12,
            )
            assert s[5] / s[0] < 1e-12  # leg lines dependent


def _detJ_formula_ur5(t):
    a2, a3, d5 = -0.425, -0.39225, 0.09465
    return (
        -a2
        * a3
        * math.sin(t[2])
        * math.sin(t[4])
        * (a2 * math.cos(t[1]) + a3 * math.cos(t[1] + t[2]) + d5 * math.sin(t[1] + t[2] + t[3]))
    )


def _detJ_formula_puma(t):
    a2, a3, d4 = 0.4318, 0.0203, 0.4318
    return (
        a2
        * (a3 * math.sin(t[2]) + d4 * math.cos(t[2]))
        * (a2 * math.cos(t[1]) + a3 * math.cos(t[1] + t[2]) - d4 * math.sin(t[1] + t[2]))
        * math.sin(t[4])
    )


@pytest.mark.parametrize(
    "name,formula", [("ur5.yaml", _detJ_formula_ur5), ("puma560.yaml", _detJ_formula_puma)]
)
def test_serial_arm_det_J(name, formula):
    m = mech(name)
    # the published closed form agrees with det of our spatial Jacobian (up to sign) at random poses
    rng = np.random.default_rng(0)
    for _ in range(5):
        t = rng.uniform(-math.pi, math.pi, 6)
        dj = np.linalg.det(m.current_screws(t))
        assert math.isclose(abs(dj), abs(formula(t)), rel_tol=1e-9, abs_tol=1e-14)
    for c in m.data["configurations"]:
        t = m.solve(c)
        dj, f = np.linalg.det(m.current_screws(t)), formula(t)
        if c == "regular":
            assert abs(f) > 1e-3 and abs(dj) > 1e-3
        else:  # reference and the singular poses
            assert abs(f) < 1e-12 and abs(dj) < 1e-12, (c, f, dj)
    # which factor vanishes where: the shoulder pose is not also a wrist pose
    t = m.solve("shoulder")
    assert abs(math.sin(t[4])) > 0.1
    assert abs(math.sin(m.solve("wrist")[4])) < 1e-15
