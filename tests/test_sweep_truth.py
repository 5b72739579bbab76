"""Self-checks of the sweep tests' closed forms (tests/reference/sweep_truth.py), each against a
brute-force computation written here from the planar geometry: circle intersections sampled on fine
grids, finite-difference Jacobians of loop equations, leg lengths and a DH forward kinematics. The
geometry comes from the example files, read by the tests' reference implementation; nothing here
imports mechsing.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

from tests.reference.expressions import vec
from tests.reference.files import MechanismFile
from tests.reference.sweep_truth import (
    FIVE_BAR,
    RPR3,
    cross,
    five_bar_discriminant,
    five_bar_point,
    five_bar_type1_det,
    five_bar_type2_det,
    four_bar_flat_positions,
    four_bar_input_limits,
    four_bar_mode,
    four_bar_output_limits,
    rpr3_concurrency_det,
    slider_crank_dead_centres,
    ur5_det_j,
    wrap,
)

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
_FILES: dict[str, MechanismFile] = {}


def mech(name: str) -> MechanismFile:
    if name not in _FILES:
        _FILES[name] = MechanismFile(EXAMPLES / name)
    return _FILES[name]


def points(name: str, joints: str | list[str]) -> list[np.ndarray]:
    """The (x, y) of the named joints' points at the reference, in SI."""
    m = mech(name)
    return [vec(m.raw[j]["point"])[:2] * m.lf for j in joints]


def current(m: MechanismFile, q: np.ndarray, joint: str) -> np.ndarray:
    """Current (x, y) of an R joint's point, carried by the joint's first body."""
    j = m.joints[m.jidx[joint]]
    g = m.poses(q)[j.a]
    p = vec(m.raw[joint]["point"]) * m.lf
    return (g[:3, :3] @ p + g[:3, 3])[:2]


# ------------------------------------------------------------------------------------ four-bar

FOUR_BARS = ["fourbar.yaml", "fourbar_changepoint.yaml", "double_rocker.yaml"]


def _rot(v: np.ndarray, t: np.ndarray) -> np.ndarray:
    c, s = np.cos(t), np.sin(t)
    return np.stack([c * v[0] - s * v[1], s * v[0] + c * v[1]], axis=-1)


def _passive_slack(A, B0, C0, D, theta):
    """How far the passive chain B-C-D is inside its closing range at input theta (negative: the
    circles about B (radius |BC|) and D (radius |CD|) do not meet)."""
    b, c = np.linalg.norm(C0 - B0), np.linalg.norm(D - C0)
    bd = np.linalg.norm(A + _rot(B0 - A, theta) - D, axis=-1)
    return np.minimum(b + c - bd, bd - abs(b - c))


def _coupler_point(A, B0, C0, D, theta, mode):
    """C by circle intersection for the input at theta, on assembly mode ``mode`` (the sign of
    (D - B) x (C - B))."""
    B = A + _rot(B0 - A, theta)
    b, c = np.linalg.norm(C0 - B0), np.linalg.norm(D - C0)
    e = D - B
    dist = np.linalg.norm(e, axis=-1)
    along = (b * b - c * c + dist * dist) / (2 * dist)
    h = np.sqrt(np.maximum(b * b - along * along, 0.0))
    u = e / dist[..., None]
    n = np.stack([-u[..., 1], u[..., 0]], axis=-1)  # k x u: (D - B) x n > 0
    return B + along[..., None] * u + (mode * h)[..., None] * n


@pytest.mark.parametrize("name", FOUR_BARS)
def test_four_bar_input_limits_are_where_the_passive_chain_stops_closing(name: str) -> None:
    A, B0, C0, D = points(name, "ABCD")
    theta = np.linspace(-math.pi, math.pi, 400_001)
    slack = _passive_slack(A, B0, C0, D, theta)
    # sign changes between grid points clearly off zero (a bound touched, as at a change point's
    # flat position, is no limit: the slack is >= 0 on both sides)
    clear = np.nonzero(np.abs(slack) > 1e-12)[0]
    flips = [
        (i, k)
        for i, k in zip(clear[:-1], clear[1:], strict=True)
        if np.sign(slack[i]) != np.sign(slack[k])
    ]
    brute = sorted(
        brentq(lambda t: float(_passive_slack(A, B0, C0, D, t)), theta[i], theta[k], xtol=1e-14)
        for i, k in flips
    )
    limits = four_bar_input_limits(A, B0, C0, D)
    assert len(brute) == len(limits)
    assert np.allclose([v for v, _ in limits], brute, atol=1e-10)
    if name == "double_rocker.yaml":  # the header's law-of-cosines values
        assert np.allclose([v for v, _ in limits], [-2 * math.pi / 3, 2 * math.pi / 3], atol=1e-14)
        assert {k for _, k in limits} == {"stretched"}
        assert min(slack) < 0  # the input really stops: no closure beyond
    else:
        assert min(slack) >= -1e-12  # the crank turns fully


def test_double_rocker_limit_configuration_is_the_closed_form() -> None:
    m = mech("double_rocker.yaml")
    q = m.solve("limit")
    assert m.loop_residual(q) < 1e-12
    A, B, C, D = (current(m, q, j) for j in "ABCD")
    assert abs(cross(C - B, D - B)) < 1e-12  # coupler and output aligned
    assert math.isclose(
        q[m.cidx[("A", 0)]], four_bar_input_limits(*points(m.path.name, "ABCD"))[1].value
    )
    assert four_bar_mode(*points("double_rocker.yaml", "ABCD")) == 1.0


@pytest.mark.parametrize("name", FOUR_BARS)
def test_four_bar_output_limits_are_the_output_angles_extrema(name: str) -> None:
    A, B0, C0, D = points(name, "ABCD")
    mode = four_bar_mode(A, B0, C0, D)

    def psi(t):  # the output link's direction on the reference mode
        C = _coupler_point(A, B0, C0, D, np.asarray(t, float), mode)
        return np.arctan2(C[..., 1] - D[1], C[..., 0] - D[0])

    limits = four_bar_output_limits(A, B0, C0, D)
    if name == "fourbar_changepoint.yaml":
        # the flat position: C on the axis; the output's rate there is zero on both branches
        assert [v for v, _ in limits] == [0.0]
        return
    theta = np.linspace(-math.pi, math.pi, 200_001)
    ok = _passive_slack(A, B0, C0, D, theta) > 1e-9
    dpsi = np.unwrap(psi(theta))
    rate = np.gradient(dpsi, theta)
    flips = [i for i in np.nonzero(np.diff(np.sign(rate)) != 0)[0] if ok[i] and ok[i + 1]]
    h = 1e-6

    def drate(t):
        return float(np.angle(np.exp(1j * (psi(t + h) - psi(t - h))))) / (2 * h)

    brute = sorted(brentq(drate, theta[i - 1], theta[i + 2], xtol=1e-13) for i in flips)
    assert len(brute) == len(limits) and len(limits) >= 1
    assert np.allclose([v for v, _ in limits], brute, atol=1e-7)


def test_double_rocker_output_limit_configuration_is_the_closed_form() -> None:
    m = mech("double_rocker.yaml")
    q = m.solve("output-limit")
    A, B, C = (current(m, q, j) for j in "ABC")
    assert abs(cross(B - A, C - A)) < 1e-12  # input and coupler aligned
    (lim,) = four_bar_output_limits(*points("double_rocker.yaml", "ABCD"))
    assert math.isclose(q[m.cidx[("A", 0)]], lim.value, rel_tol=1e-14)
    assert math.isclose(lim.value, 2 * math.atan(math.sqrt(3) / 9), rel_tol=1e-14)


@pytest.mark.parametrize("name", FOUR_BARS)
def test_four_bar_flat_positions(name: str) -> None:
    A, B0, C0, D = points(name, "ABCD")
    flat = four_bar_flat_positions(A, B0, C0, D)
    # brute force: the input values (on a grid) where B and C both lie on the line AD
    theta = np.linspace(-math.pi, math.pi, 100_001)
    seen = []
    for mode in (1.0, -1.0):
        C = _coupler_point(A, B0, C0, D, theta, mode)
        B = A + _rot(B0 - A, theta)
        ad = (D - A) / np.linalg.norm(D - A)
        off = np.abs(cross(ad, B - A)) + np.abs(cross(ad, C - A))
        ok = _passive_slack(A, B0, C0, D, theta) >= -1e-12
        seen.extend(theta[ok & (off < 1e-9)])
    if name == "fourbar_changepoint.yaml":
        assert flat == [0.0]  # the reference (crank along +x); crank along -x is not flat
        assert seen and np.allclose(seen, 0.0, atol=1e-12)
        slack = _passive_slack(A, B0, C0, D, np.array([-1e-3, 0.0, 1e-3]))
        assert abs(slack[1]) < 1e-12 and min(slack[0], slack[2]) > 0  # touched, not crossed
    else:
        assert flat == [] and not seen


def test_wrap_half_open() -> None:
    assert wrap(-math.pi) == math.pi and wrap(3 * math.pi) == math.pi
    assert math.isclose(wrap(-4 * math.pi / 3), 2 * math.pi / 3)


# -------------------------------------------------------------------------------- slider-crank


@pytest.mark.parametrize(
    "name", ["slider_crank_slider_input.yaml", "slider_crank_crank_input.yaml"]
)
def test_slider_crank_dead_centres_are_the_slider_travel_ends(name: str) -> None:
    A, B0, C0 = points(name, "ABC")
    m = mech(name)
    s = vec(m.raw["P"]["axis"])[:2]
    s = s / np.linalg.norm(s)
    l = np.linalg.norm(C0 - B0)  # rod length
    n = np.array([-s[1], s[0]])
    e = float((C0 - A) @ n)  # offset of the slide line from A

    def slider(t):  # slider joint value for crank turn t (the branch of the reference)
        B = A + _rot(B0 - A, np.asarray(t, float))
        along = (B - A) @ s
        across = e - (B - A) @ n
        return along + np.sqrt(l * l - across**2) - (C0 - A) @ s

    truth = slider_crank_dead_centres(A, B0, C0, s)
    lo = minimize_scalar(
        lambda t: slider(t), bounds=(-math.pi, math.pi), method="bounded", options={"xatol": 1e-12}
    )
    hi = minimize_scalar(
        lambda t: -slider(t), bounds=(-math.pi, math.pi), method="bounded", options={"xatol": 1e-12}
    )
    grid = slider(np.linspace(-math.pi, math.pi, 100_001))
    assert math.isclose(truth["outer"], max(grid.max(), -hi.fun), abs_tol=1e-10)
    assert math.isclose(truth["inner"], min(grid.min(), lo.fun), abs_tol=1e-10)
    assert math.isclose(truth["outer"], 8 / 5, abs_tol=1e-15)  # header: x = 24/5 from 16/5
    assert math.isclose(truth["inner"], 4 * math.sqrt(11) / 5 - 16 / 5, abs_tol=1e-15)
    assert math.isclose(m.solve("dead-centre")[m.cidx[("P", 0)]], truth["outer"], abs_tol=1e-15)


# ------------------------------------------------------------------------------------ five-bar


def test_five_bar_geometry_is_the_files() -> None:
    a1, b1, p, b2, a2 = points("five_bar.yaml", ["A1", "B1", "P", "B2", "A2"])
    for mine, theirs in zip(
        (FIVE_BAR.a1, FIVE_BAR.a2, FIVE_BAR.b1, FIVE_BAR.b2, FIVE_BAR.p),
        (a1, a2, b1, b2, p),
        strict=True,
    ):
        assert np.allclose(mine, theirs, atol=0)
    assert FIVE_BAR.reference_mode() == 1.0


@pytest.mark.parametrize("config", ["reference", "inputs", "type1", "type2"])
def test_five_bar_point_follows_the_files_joint_values(config: str) -> None:
    m = mech("five_bar.yaml")
    q = m.solve(config)
    t1, t2 = q[m.cidx[("A1", 0)]], q[m.cidx[("A2", 0)]]
    g = m.poses(q)["dist1"]
    p = (g[:3, :3] @ vec(m.raw["P"]["point"]) + g[:3, 3])[:2]
    assert np.allclose(five_bar_point(t1, t2, 1.0), p, atol=1e-9 if config == "type2" else 1e-12)
    b1, b2 = FIVE_BAR.elbows(t1, t2)
    assert np.allclose(b1, current(m, q, "B1"), atol=1e-12)
    assert np.allclose(b2, current(m, q, "B2"), atol=1e-12)
    t1d, t2d = five_bar_type1_det(t1, t2, 1.0), five_bar_type2_det(t1, t2, 1.0)
    if config == "type1":
        assert abs(t1d) < 1e-12 and abs(t2d) > 1
    elif config == "type2":
        assert abs(t2d) < 1e-6 and abs(five_bar_discriminant(t1, t2)) < 1e-12
    else:
        assert abs(t1d) > 1 and abs(t2d) > 1


def _loop(x: np.ndarray) -> np.ndarray:
    """The five-bar's loop equations F(P, theta) = |P - B_i(theta_i)|^2 - l_i^2, x = (P, theta)."""
    A = [np.asarray(FIVE_BAR.a1), np.asarray(FIVE_BAR.a2)]
    B0 = [np.asarray(FIVE_BAR.b1), np.asarray(FIVE_BAR.b2)]
    P0 = np.asarray(FIVE_BAR.p)
    out = []
    for i in range(2):
        B = A[i] + _rot(B0[i] - A[i], x[2 + i])
        out.append(np.sum((x[:2] - B) ** 2) - np.sum((P0 - B0[i]) ** 2))
    return np.array(out)


def test_five_bar_determinants_are_the_loop_jacobians_blocks() -> None:
    rng = np.random.default_rng(13)
    checked = 0
    while checked < 40:
        t1, t2 = rng.uniform(-math.pi, math.pi, 2)
        if five_bar_discriminant(t1, t2) <= 1e-3:
            continue
        for mode in (1.0, -1.0):
            P = five_bar_point(t1, t2, mode)
            x = np.r_[P, t1, t2]
            assert np.max(np.abs(_loop(x))) < 1e-12
            h = 1e-6
            jac = np.array([(_loop(x + h * e) - _loop(x - h * e)) / (2 * h) for e in np.eye(4)]).T
            da, db = np.linalg.det(jac[:, :2]), np.linalg.det(jac[:, 2:])
            assert math.isclose(
                da, 4 * five_bar_type2_det(t1, t2, mode), rel_tol=1e-7, abs_tol=1e-8
            )
            assert math.isclose(
                db, 4 * five_bar_type1_det(t1, t2, mode), rel_tol=1e-7, abs_tol=1e-8
            )
            # twice the signed area of B1 B2 P is mode sqrt(D)/2 (Heron)
            assert math.isclose(
                five_bar_type2_det(t1, t2, mode),
                mode * math.sqrt(five_bar_discriminant(t1, t2)) / 2,
                rel_tol=1e-10,
            )
        checked += 1


def test_five_bar_point_is_continuous_on_each_mode() -> None:
    # along a closed path inside the assembled region, P and the Type I determinant move continuously
    s = np.linspace(0, 2 * math.pi, 20_001)
    t1, t2 = 0.5 * np.cos(s), 0.5 * np.sin(s)
    assert np.all(five_bar_discriminant(t1, t2) > 0)
    for mode in (1.0, -1.0):
        P = five_bar_point(t1, t2, mode)
        assert np.max(np.linalg.norm(np.diff(P, axis=0), axis=1)) < 1e-3
        assert np.max(np.abs(np.diff(five_bar_type1_det(t1, t2, mode)))) < 1e-2
    assert np.all(np.isnan(five_bar_point(np.array([math.pi / 2]), np.array([-math.pi / 2]), 1.0)))


# ------------------------------------------------------------------------------------ 3-RPR


def _platform_pose(m: MechanismFile, q: np.ndarray) -> tuple[float, float, float]:
    """(x, y, phi) of the platform: its reference point's position and its turn from the reference."""
    g = m.poses(q)["platform"]
    c0 = np.mean([vec(m.raw[f"Rp{i}"]["point"]) for i in (1, 2, 3)], axis=0)
    c = g[:3, :3] @ c0 + g[:3, 3]
    return float(c[0]), float(c[1]), math.atan2(g[1, 0], g[0, 0])


def test_rpr3_geometry_is_the_files() -> None:
    assert np.allclose(RPR3.a, points("planar_3rpr.yaml", ["Rb1", "Rb2", "Rb3"]), atol=0)
    assert np.allclose(RPR3.b, points("planar_3rpr.yaml", ["Rp1", "Rp2", "Rp3"]), atol=1e-15)
    assert np.allclose(RPR3.centre(), [31 / 30, 37 / 30], atol=1e-15)


def test_rpr3_concurrency_det_at_the_files_configurations() -> None:
    m = mech("planar_3rpr.yaml")
    for config in m.data["configurations"]:
        q = m.solve(config)
        x, y, phi = _platform_pose(m, q)
        pivots = RPR3.platform_pivots(x, y, phi)
        for i in (1, 2, 3):
            assert np.allclose(pivots[i - 1], current(m, q, f"Rp{i}"), atol=1e-12)
        d = rpr3_concurrency_det(x, y, phi)
        if config == "concurrent":
            assert abs(d) < 1e-12
            assert np.allclose([x, y, phi], [7 / 6, 7 / 6, -2 * math.atan(1 / 3)], atol=1e-12)
        else:
            assert abs(d) > 1e-2, (config, d)


def _leg_lengths(z: np.ndarray) -> np.ndarray:
    B = RPR3.platform_pivots(z[0], z[1], z[2])
    return np.linalg.norm(B - np.asarray(RPR3.a), axis=-1)


def test_rpr3_concurrency_det_is_the_inverse_kinematics_jacobian() -> None:
    rng = np.random.default_rng(3)
    for _ in range(30):
        z = np.r_[rng.uniform(0.2, 2.0, 2), rng.uniform(-math.pi, math.pi)]
        h = 1e-6
        jac = np.array(
            [(_leg_lengths(z + h * e) - _leg_lengths(z - h * e)) / (2 * h) for e in np.eye(3)]
        ).T
        assert math.isclose(
            np.linalg.det(jac), rpr3_concurrency_det(*z), rel_tol=1e-7, abs_tol=1e-9
        )
        # the unnormalised form differs by the positive product of the leg lengths
        raw = rpr3_concurrency_det(*z, unit=False)
        assert math.isclose(raw, np.prod(_leg_lengths(z)) * rpr3_concurrency_det(*z), rel_tol=1e-10)


def test_rpr3_unnormalised_locus_is_a_conic() -> None:
    # at fixed phi, det with raw directions is a polynomial of degree 2 in (x, y): a least-squares
    # fit on the six quadratic monomials reproduces it at other points to rounding
    rng = np.random.default_rng(5)
    xy = rng.uniform(-3, 3, (40, 2))

    def monomials(p):
        x, y = p[:, 0], p[:, 1]
        return np.stack([np.ones_like(x), x, y, x * x, x * y, y * y], axis=1)

    f = rpr3_concurrency_det(xy[:20, 0], xy[:20, 1], 0.3, unit=False)
    coef, *_ = np.linalg.lstsq(monomials(xy[:20]), f, rcond=None)
    g = rpr3_concurrency_det(xy[20:, 0], xy[20:, 1], 0.3, unit=False)
    assert np.allclose(monomials(xy[20:]) @ coef, g, atol=1e-10 * np.max(np.abs(g)))


# --------------------------------------------------------------------------------------- UR5

UR5_DH = {  # standard DH (alpha, a, d) of examples/ur5.yaml's header
    "alpha": (math.pi / 2, 0, 0, math.pi / 2, -math.pi / 2, 0),
    "a": (0, -0.425, -0.39225, 0, 0, 0),
    "d": (0.089159, 0, 0, 0.10915, 0.09465, 0.0823),
}


def _ur5_fk(theta: np.ndarray) -> np.ndarray:
    """The tool frame, T = prod_i Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i)."""
    T = np.eye(4)
    for t, al, a, d in zip(theta, UR5_DH["alpha"], UR5_DH["a"], UR5_DH["d"], strict=True):
        ct, st, ca, sa = math.cos(t), math.sin(t), math.cos(al), math.sin(al)
        T = T @ np.array(
            [
                [ct, -st * ca, st * sa, a * ct],
                [st, ct * ca, -ct * sa, a * st],
                [0, sa, ca, d],
                [0, 0, 0, 1],
            ]
        )
    return T


def _ur5_jacobian_fd(theta: np.ndarray, h: float = 1e-6) -> np.ndarray:
    """Columns (omega, v of the tool origin) by central differences of the forward kinematics."""
    cols = []
    for e in np.eye(6):
        Tp, Tm = _ur5_fk(theta + h * e), _ur5_fk(theta - h * e)
        W = (Tp[:3, :3] - Tm[:3, :3]) / (2 * h) @ _ur5_fk(theta)[:3, :3].T
        w = np.array([W[2, 1] - W[1, 2], W[0, 2] - W[2, 0], W[1, 0] - W[0, 1]]) / 2
        cols.append(np.r_[w, (Tp[:3, 3] - Tm[:3, 3]) / (2 * h)])
    return np.array(cols).T


def test_ur5_det_j_is_the_forward_kinematics_jacobian() -> None:
    rng = np.random.default_rng(7)
    for _ in range(20):
        t = rng.uniform(-math.pi, math.pi, 6)
        assert math.isclose(
            np.linalg.det(_ur5_jacobian_fd(t)), ur5_det_j(t), rel_tol=1e-6, abs_tol=1e-10
        )
    m = mech("ur5.yaml")  # the file's reference is the DH zero pose: the tool is d6 along J6's axis
    tool = vec(m.raw["J6"]["point"]) + 0.0823 * vec(m.raw["J6"]["axis"])
    assert np.allclose(_ur5_fk(np.zeros(6))[:3, 3], tool, atol=1e-12)
    for config in m.data["configurations"]:
        d = ur5_det_j(m.solve(config))
        assert (abs(d) > 1e-3) if config == "regular" else (abs(d) < 1e-12), (config, d)
