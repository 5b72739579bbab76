"""Laws of D = SE(3) and its Lie algebra, at the branch points and in every precision."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import scipy.linalg
import sympy
from hypothesis import given, settings
from scipy.spatial.transform import Rotation

from mechsing import lie
from mechsing.numeric import Precision
from tests.strategies import angles, bounded_twists, displacements, lengths, twists, unit_axes

EPS = np.finfo(float).eps
SET = settings(max_examples=200, deadline=None)


def _scale(g: np.ndarray) -> float:
    return max(1.0, float(np.linalg.norm(g[..., :3, 3])))


def _random_twists(n: int, seed: int = 0) -> np.ndarray:
    # angular parts below pi (so that log inverts exp), translations of a few units
    return np.random.default_rng(seed).normal(size=(n, 6)) * [0.5, 0.5, 0.5, 3, 3, 3]


# --------------------------------------------------------------------------- exp


def test_exp_matches_scipy_expm_batched() -> None:
    xi = _random_twists(50)
    g = lie.exp(xi)
    ref = np.array([scipy.linalg.expm(lie.hat(x)) for x in xi])
    assert g.shape == (50, 4, 4)
    assert np.max(np.abs(g - ref)) < 1e-13 * np.max(np.abs(ref))


@pytest.mark.parametrize("shape", [(), (1,), (3, 1, 2)])
def test_batch_shapes(shape: tuple[int, ...]) -> None:
    xi = _random_twists(int(np.prod(shape)) or 1, 3).reshape(shape + (6,))
    g = lie.exp(xi)
    assert g.shape == shape + (4, 4)
    assert lie.log(g).shape == shape + (6,)
    assert lie.Ad(g).shape == shape + (6, 6)
    assert lie.left_jacobian(xi).shape == shape + (6, 6)
    np.testing.assert_allclose(lie.log(g), xi, atol=1e-12)


@SET
@given(twists())
def test_exp_is_a_displacement(xi: np.ndarray) -> None:
    g = lie.exp(xi)
    R = g[:3, :3]
    assert np.max(np.abs(R.T @ R - np.eye(3))) <= 10 * EPS
    assert abs(np.linalg.det(R) - 1) <= 10 * EPS
    np.testing.assert_array_equal(g[3], [0, 0, 0, 1])


def test_exp_beyond_pi_wraps() -> None:
    u = np.array([1.0, 2.0, 3.0]) / math.sqrt(14)
    for th in (3.5, 2 * math.pi, 7.0, 20.0):
        R = lie.exp_so3(th * u)
        R2 = lie.exp_so3((th - 2 * math.pi) * u)
        np.testing.assert_allclose(R, R2, atol=1e-14)
        np.testing.assert_allclose(R, Rotation.from_rotvec(th * u).as_matrix(), atol=1e-14)


def test_pure_translation_is_exact() -> None:
    v = np.array([1e9, -3.0, 1e-9])
    g = lie.exp(np.concatenate([np.zeros(3), v]))
    np.testing.assert_array_equal(g[:3, 3], v)
    np.testing.assert_array_equal(g[:3, :3], np.eye(3))


# --------------------------------------------------------------------------- log


@SET
@given(displacements())
def test_exp_log_is_identity(g: np.ndarray) -> None:
    back = lie.exp(lie.log(g))
    assert np.max(np.abs(back - g)) <= 16 * EPS * _scale(g)


@SET
@given(twists(max_angle=math.pi - 1e-12))
def test_log_exp_is_identity_below_pi(xi: np.ndarray) -> None:
    back = lie.log(lie.exp(xi))
    # Shepperd's method keeps the rotation vector accurate up to pi; the
    # translation part is compared relative to the size of the twist
    size = max(1.0, float(np.linalg.norm(xi[3:])))
    assert np.max(np.abs(back[:3] - xi[:3])) <= 64 * EPS
    assert np.max(np.abs(back[3:] - xi[3:])) <= 64 * EPS * size


@SET
@given(unit_axes(), lengths, unit_axes())
def test_log_at_exactly_pi_up_to_axis_sign(u: np.ndarray, t: float, d: np.ndarray) -> None:
    xi = np.concatenate([math.pi * u, t * d])
    g = lie.exp(xi)
    back = lie.log(g)
    assert abs(np.linalg.norm(back[:3]) - math.pi) < 1e-12
    # exp(log g) = g always; the rotation vector is +-pi u
    np.testing.assert_allclose(lie.exp(back), g, atol=16 * EPS * _scale(g))
    assert min(np.abs(back[:3] - math.pi * u).max(), np.abs(back[:3] + math.pi * u).max()) < 1e-7


def test_half_turn_axis_sign_is_deterministic() -> None:
    # exact half-turns given as matrices: the axis has its largest component positive
    for axis in ([1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 0], [-1, 2, -2], [-3, 0, 4]):
        u = np.array(axis, float) / np.linalg.norm(axis)
        R = 2 * np.outer(u, u) - np.eye(3)
        w = lie.log_so3(R)
        assert abs(np.linalg.norm(w) - math.pi) < 1e-14
        k = int(np.argmax(np.abs(w)))
        assert w[k] > 0
        np.testing.assert_allclose(lie.exp_so3(w), R, atol=1e-15)


@pytest.mark.parametrize("k", range(1, 13))
def test_log_near_pi(k: int) -> None:
    th = math.pi - 10.0**-k
    u = np.array([0.3, -0.4, 0.5]) / np.linalg.norm([0.3, -0.4, 0.5])
    xi = np.concatenate([th * u, [1.0, -2.0, 0.25]])
    back = lie.log(lie.exp(xi))
    np.testing.assert_allclose(back, xi, atol=1e-12)


@pytest.mark.parametrize("th", [0.0, 1e-16, 1e-12, 1e-8, 1e-4, 1e-2, 0.999999, 1.0, 1.000001])
def test_log_near_zero_and_at_the_series_switch(th: float) -> None:
    u = np.array([1.0, 2.0, 3.0]) / math.sqrt(14)
    xi = np.concatenate([th * u, [1.0, -2.0, 0.25]])
    back = lie.log(lie.exp(xi))
    np.testing.assert_allclose(back, xi, rtol=0, atol=4 * EPS * 3)


def test_log_so3_matches_scipy() -> None:
    rots = Rotation.random(100, random_state=1)
    np.testing.assert_allclose(lie.log_so3(rots.as_matrix()), rots.as_rotvec(), atol=1e-13)


# --------------------------------------------------------------------------- group laws


@SET
@given(displacements(), displacements(), displacements())
def test_group_axioms(g: np.ndarray, h: np.ndarray, k: np.ndarray) -> None:
    s = _scale(g) * _scale(h) * _scale(k)
    np.testing.assert_allclose(
        lie.compose(lie.compose(g, h), k), lie.compose(g, lie.compose(h, k)), atol=64 * EPS * s
    )
    np.testing.assert_allclose(lie.compose(g, lie.inverse(g)), np.eye(4), atol=16 * EPS * _scale(g))
    x = np.array([0.3, -1.0, 2.0])
    np.testing.assert_allclose(
        lie.act_point(lie.compose(g, h), x),
        lie.act_point(g, lie.act_point(h, x)),
        atol=64 * EPS * s,
    )


# --------------------------------------------------------------------------- Ad, ad, bracket


@SET
@given(bounded_twists(), bounded_twists(), bounded_twists())
def test_bracket_is_commutator_and_jacobi(x: np.ndarray, y: np.ndarray, z: np.ndarray) -> None:
    X, Y = lie.hat(x), lie.hat(y)
    np.testing.assert_allclose(lie.hat(lie.bracket(x, y)), X @ Y - Y @ X, atol=1e-12)
    np.testing.assert_allclose(lie.ad(x) @ y, lie.bracket(x, y), atol=1e-12)
    jac = (
        lie.bracket(x, lie.bracket(y, z))
        + lie.bracket(y, lie.bracket(z, x))
        + lie.bracket(z, lie.bracket(x, y))
    )
    assert np.max(np.abs(jac)) < 1e-11


@SET
@given(displacements(), bounded_twists(), bounded_twists())
def test_ad_of_bracket_is_bracket_of_ads(g: np.ndarray, x: np.ndarray, y: np.ndarray) -> None:
    s = _scale(g) ** 2
    lhs = lie.act_screw(g, lie.bracket(x, y))
    rhs = lie.bracket(lie.act_screw(g, x), lie.act_screw(g, y))
    assert np.max(np.abs(lhs - rhs)) <= 1e-12 * s * 30
    # Ad(g) xi = vee(g hat(xi) g^-1) and Ad matrix agrees with act_screw
    np.testing.assert_allclose(
        lie.vee(g @ lie.hat(x) @ lie.inverse(g)), lie.Ad(g) @ x, atol=1e-12 * s * 10
    )
    np.testing.assert_allclose(lie.Ad(g) @ x, lie.act_screw(g, x), atol=1e-12 * s * 10)


@SET
@given(displacements(), displacements())
def test_Ad_is_a_homomorphism(g: np.ndarray, h: np.ndarray) -> None:  # noqa: N802
    s = (_scale(g) * _scale(h)) ** 1
    np.testing.assert_allclose(
        lie.Ad(lie.compose(g, h)), lie.Ad(g) @ lie.Ad(h), atol=64 * EPS * s * s
    )
    # Ad(g^-1) Ad(g) = Ad(e) = I: the law itself, not numpy's inverse of a matrix whose
    # condition number grows as |p|^2 (at |p| ~ 7e7 inv's rounding exceeded any fixed bound)
    np.testing.assert_allclose(
        lie.Ad(lie.inverse(g)) @ lie.Ad(g), np.eye(6), atol=64 * EPS * _scale(g) ** 2
    )


def test_Ad_exp_is_exp_ad() -> None:  # noqa: N802
    for x in _random_twists(10, 5):
        np.testing.assert_allclose(lie.Ad(lie.exp(x)), scipy.linalg.expm(lie.ad(x)), atol=1e-12)


@SET
@given(displacements(), bounded_twists(), bounded_twists())
def test_klein_and_killing_are_Ad_invariant(g: np.ndarray, x: np.ndarray, y: np.ndarray) -> None:  # noqa: N802
    s = _scale(g)
    gx, gy = lie.act_screw(g, x), lie.act_screw(g, y)
    assert abs(lie.klein(gx, gy) - lie.klein(x, y)) <= 1e-12 * s * 50
    assert abs(lie.killing(gx, gy) - lie.killing(x, y)) <= 1e-12 * 50
    ad_x, ad_y = lie.ad(x), lie.ad(y)
    assert abs(np.trace(ad_x @ ad_y) - lie.killing(x, y)) < 1e-10
    if np.linalg.norm(x[:3]) > 1e-3:
        assert abs(lie.pitch(gx) - lie.pitch(x)) <= 1e-9 * s * max(1.0, abs(lie.pitch(x)))


def test_klein_is_power_and_line_reciprocity() -> None:
    # two lines: K = -d sin(alpha); zero iff they meet or are parallel
    u1, p1 = np.array([1.0, 0, 0]), np.array([0.0, 0, 0])
    u2, p2 = np.array([0.0, 1, 0]), np.array([0.0, 0, 2.0])  # skew at distance 2, 90 degrees
    L1 = np.concatenate([u1, np.cross(p1, u1)])
    L2 = np.concatenate([u2, np.cross(p2, u2)])
    assert abs(abs(lie.klein(L1, L2)) - 2.0) < 1e-15
    L3 = np.concatenate([u2, np.cross(np.array([5.0, 0, 0]), u2)])  # meets L1
    assert lie.klein(L1, L3) == 0
    # power of a wrench (f, m) on a twist (w, v) = f.v + m.w
    tw, wr = np.array([1.0, 2, 3, 4, 5, 6]), np.array([0.5, -1, 2, 3, 0, -2])
    assert lie.klein(tw, wr) == pytest.approx(wr[:3] @ tw[3:] + wr[3:] @ tw[:3])


# --------------------------------------------------------------------------- screws and Chasles


def test_pitch_axis_magnitude() -> None:
    u = np.array([0.0, 0.0, 1.0])
    N = np.array([1.0, 2.0, 5.0])
    h = 0.3
    xi = 2.0 * np.concatenate([u, np.cross(N, u) + h * u])
    assert lie.pitch(xi) == pytest.approx(h)
    d, r0 = lie.axis(xi)
    np.testing.assert_allclose(d, u)
    np.testing.assert_allclose(r0, [1.0, 2.0, 0.0])
    assert lie.magnitude(xi) == pytest.approx(2.0)
    assert lie.classify_screw(xi) == "helical"
    assert lie.classify_screw(np.concatenate([u, np.cross(N, u)])) == "rotation"
    assert lie.classify_screw(np.array([0, 0, 0, 1.0, 0, 0])) == "translation"
    assert lie.classify_screw(np.zeros(6)) == "zero"
    assert lie.pitch(np.array([0, 0, 0, 1.0, 0, 0])) == np.inf


@SET
@given(twists())
def test_chasles_rebuilds_the_displacement(xi: np.ndarray) -> None:
    g = lie.exp(xi)
    L = _scale(g)
    c = lie.classify_displacement(g)
    if c.kind == "identity":
        assert np.max(np.abs(g - np.eye(4))) < 1e-8 * L
        return
    if c.kind == "translation":
        back = lie.exp(np.concatenate([np.zeros(3), c.slide * c.axis]))
    else:
        twist = np.concatenate([c.angle * c.axis, np.cross(c.point, c.angle * c.axis)])
        twist[3:] += c.slide * c.axis
        back = lie.exp(twist)
        assert abs(c.point @ c.axis) < 1e-6 * L  # the point nearest the origin
    assert np.max(np.abs(back - g)) < 1e-7 * L


def test_chasles_fixed_cases() -> None:
    g = lie.exp(np.array([0, 0, math.pi / 2, 1.0, 0, 0.5]))
    c = lie.classify_displacement(g)
    assert c.kind == "screw"
    np.testing.assert_allclose(c.point, [0, 2 / math.pi, 0], atol=1e-15)
    assert c.slide == pytest.approx(0.5)
    assert lie.classify_displacement(np.eye(4)).kind == "identity"
    t = np.eye(4)
    t[:3, 3] = [0, 3, 4]
    c = lie.classify_displacement(t)
    assert c.kind == "translation" and c.slide == pytest.approx(5)
    half = np.diag([1.0, -1, -1, 1])
    half[:3, 3] = [0, 2, 0]
    c = lie.classify_displacement(half)
    assert c.kind == "rotation" and c.angle == pytest.approx(math.pi)
    np.testing.assert_allclose(c.point, [0, 1, 0], atol=1e-15)


# --------------------------------------------------------------------------- Jacobians


def _series_jl(x: np.ndarray) -> np.ndarray:
    A = lie.ad(x)
    return sum(np.linalg.matrix_power(A, k) / math.factorial(k + 1) for k in range(60))


@pytest.mark.parametrize("th", [0.0, 1e-8, 1e-3, 0.5, 0.999999, 1.0, 1.000001, 2.0, math.pi])
def test_left_jacobian_closed_form_series_and_switch(th: float) -> None:
    u = np.array([1.0, -2.0, 2.0]) / 3
    x = np.concatenate([th * u, [0.4, 1.0, -0.7]])
    J = lie.left_jacobian(x)
    np.testing.assert_allclose(J, _series_jl(x), atol=4e-15)
    np.testing.assert_allclose(lie.left_jacobian_inv(x) @ J, np.eye(6), atol=4e-15)
    Jr = lie.right_jacobian(x)
    np.testing.assert_allclose(J, lie.Ad(lie.exp(x)) @ Jr, atol=4e-15)
    np.testing.assert_allclose(lie.right_jacobian_inv(x) @ Jr, np.eye(6), atol=4e-15)


def test_jacobian_series_agrees_with_closed_form_at_the_switch() -> None:
    # the two branches meet at t = 1 (float): evaluate both sides to mp:50
    from mechsing.lie import _series

    for th in (1.0 - 1e-12, 1.0 + 1e-12):
        x = np.concatenate([th * np.array([0.0, 0.6, 0.8]), [0.4, 1.0, -0.7]])
        with Precision("mp", 50).context():
            xm = Precision("mp", 50).asarray([repr(float(v)) for v in x])
            ref = lie.left_jacobian(xm)
        np.testing.assert_allclose(lie.left_jacobian(x), ref.astype(float), atol=4e-16)
    assert _series.SWITCH_T2 == 1


@SET
@given(twists(max_angle=3.0))
def test_dexp_against_finite_differences(xi: np.ndarray) -> None:
    if np.linalg.norm(xi[3:]) > 1e3:  # finite differences need a moderate scale
        xi = np.concatenate([xi[:3], xi[3:] / np.linalg.norm(xi[3:])])
    h = 1e-6
    J = np.zeros((6, 6))
    g0inv = lie.inverse(lie.exp(xi))
    for k in range(6):
        e = np.zeros(6)
        e[k] = h
        gp, gm = lie.exp(xi + e), lie.exp(xi - e)
        J[:, k] = lie.vee((gp - gm) @ g0inv) / (2 * h)
    # central differences: truncation h^2 and roundoff eps |g| / h, both scale with |v|
    size = max(1.0, float(np.linalg.norm(xi[3:])))
    np.testing.assert_allclose(J, lie.left_jacobian(xi), atol=1e-8 * size)


# --------------------------------------------------------------------------- precision modes


def test_exp_log_Ad_bracket_at_50_digits() -> None:  # noqa: N802
    P = Precision("mp", 50)
    with P.context():
        xi = P.asarray(["0.3", "-1.2", "0.7", "1", "2", "3"])
        eta = P.asarray(["-0.5", "0.25", "2", "0.125", "-1", "4"])
        g = lie.exp(xi)
        H = mpmath.matrix(lie.hat(xi).tolist())
        E = mpmath.expm(H)
        assert (
            max(abs(E[i, j] - g[i, j]) for i in range(4) for j in range(4)) < mpmath.mpf(10) ** -48
        )
        back = lie.log(g)
        assert max(abs(a - b) for a, b in zip(back, xi, strict=True)) < mpmath.mpf(10) ** -48
        # Ad of a bracket is the bracket of the Ads, to 48 digits
        lhs = lie.act_screw(g, lie.bracket(xi, eta))
        rhs = lie.bracket(lie.act_screw(g, xi), lie.act_screw(g, eta))
        assert max(abs(a - b) for a, b in zip(lhs, rhs, strict=True)) < mpmath.mpf(10) ** -47
        # near pi at 50 digits
        u = P.asarray(["1", "2", "3"]) / mpmath.sqrt(14)
        x = np.concatenate([(mpmath.pi - mpmath.mpf("1e-30")) * u, P.asarray(["0.5", "0", "-1"])])
        assert (
            max(abs(a - b) for a, b in zip(lie.log(lie.exp(x)), x, strict=True))
            < mpmath.mpf(10) ** -45
        )


def test_exp_log_Ad_bracket_exactly() -> None:  # noqa: N802
    P = Precision("exact")
    xi = P.asarray([0, 0, sympy.pi / 2, 1, 0, sympy.Rational(1, 2)])
    g = lie.exp(xi)
    assert g[0, 0] == 0 and g[1, 0] == 1 and g[2, 3] == sympy.Rational(1, 2)
    assert sympy.simplify(g[1, 3] - 2 / sympy.pi) == 0
    back = lie.log(g)
    assert all(sympy.simplify(a - b) == 0 for a, b in zip(back, xi, strict=True))
    # a rational displacement (rotation by the rational Cayley matrix) and its Ad
    R = sympy.Matrix(
        [
            [sympy.Rational(3, 5), -sympy.Rational(4, 5), 0],
            [sympy.Rational(4, 5), sympy.Rational(3, 5), 0],
            [0, 0, 1],
        ]
    )
    gq = lie.pose(np.array(R.tolist(), dtype=object), P.asarray(["1/2", 3, "-2/7"]))
    x = P.asarray([1, 2, 3, 4, 5, 6])
    y = P.asarray(["1/3", 0, -1, 2, "5/4", 1])
    lhs = lie.act_screw(gq, lie.bracket(x, y))
    rhs = lie.bracket(lie.act_screw(gq, x), lie.act_screw(gq, y))
    assert all(sympy.simplify(a - b) == 0 for a, b in zip(lhs, rhs, strict=True))
    A = sympy.Matrix(lie.Ad(gq).tolist())
    assert A * sympy.Matrix(x.tolist()) == sympy.Matrix(lie.act_screw(gq, x).tolist())
    assert (
        sympy.simplify(lie.klein(lie.act_screw(gq, x), lie.act_screw(gq, y)) - lie.klein(x, y)) == 0
    )
    # exact half-turn: log picks +pi about x
    half = P.asarray([[1, 0, 0, 0], [0, -1, 0, 0], [0, 0, -1, 0], [0, 0, 0, 1]])
    assert list(lie.log(half)) == [sympy.pi, 0, 0, 0, 0, 0]
    # exact identity and translation take the series branch at exactly 0
    assert list(lie.log(lie.exp(P.asarray([0, 0, 0, 1, 2, 3])))) == [0, 0, 0, 1, 2, 3]


def test_exact_jacobian_at_zero_is_identity_plus_half_ad() -> None:
    P = Precision("exact")
    x = P.asarray([0, 0, 0, 1, 2, 3])
    J = sympy.Matrix(lie.left_jacobian(x).tolist())
    ad = sympy.Matrix(lie.ad(x).tolist())
    assert J == sympy.eye(6) + ad / 2


@given(angles)
@settings(max_examples=50, deadline=None)
def test_so3_against_scipy_rotation(th: float) -> None:
    u = np.array([0.3, -0.4, 0.5]) / np.linalg.norm([0.3, -0.4, 0.5])
    np.testing.assert_allclose(
        lie.exp_so3(th * u), Rotation.from_rotvec(th * u).as_matrix(), atol=4 * EPS
    )
