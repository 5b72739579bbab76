"""Dual numbers, dual quaternions, dual angle, dual Rodrigues and the dual rank
(mechsing.lie.dual).  Independent references: scipy.linalg.expm of the 4x4
hat, mpmath.diff, closest points of two lines by least squares, and exact
ranks of the real representation [[A, B], [0, A]] of a dual matrix (sympy)."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import scipy.linalg
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st

from mechsing.lie.dual import (
    Dual,
    displacement_from_dual_matrix,
    dual_angle,
    dual_atan2,
    dual_cos,
    dual_cross,
    dual_dot,
    dual_matmul,
    dual_matrix_from_displacement,
    dual_quat_conjugate,
    dual_quat_from_displacement,
    dual_quat_multiply,
    dual_quat_to_displacement,
    dual_rank,
    dual_rodrigues,
    dual_sin,
    dual_sqrt,
    dual_to_screw,
    screw_displacement,
    screw_to_dual,
)
from mechsing.numeric import Precision, decide_rank
from tests.reference.se3 import adjoint, hat, skew
from tests.reference.se3 import screw_motion as screw_reference
from tests.strategies import angles, screw_displacements, unit_axes
from tests.strategies import length_scales as lengths
from tests.strategies import scaled_points as points

EPS = float(np.finfo(float).eps)
SETTINGS = settings(max_examples=100, deadline=None)
MP50 = Precision("mp", 50)


def expm_screw(u, N, theta, d):
    """Rotation theta about the line (N, u) and slide d along it, by expm."""
    return scipy.linalg.expm(hat(np.concatenate([theta * u, np.cross(N, theta * u) + d * u])))


def close_disp(g, h, k=16):
    """Rotation to k eps, translation to k eps relative to the lengths involved."""
    L = 1 + np.abs(g[:3, 3]).max() + np.abs(h[:3, 3]).max()
    return (
        np.abs(g[:3, :3] - h[:3, :3]).max() <= k * EPS
        and np.abs(g[:3, 3] - h[:3, 3]).max() <= k * EPS * L
        and np.array_equal(g[3], [0, 0, 0, 1])
    )


# --- dual numbers ---------------------------------------------------------


def test_dual_arithmetic():
    e = Dual(0.0, 1.0)
    z = e * e
    assert z.a == 0 and z.b == 0  # eps^2 = 0
    x = Dual([1.0, 2.0], [3.0, -1.0])
    y = Dual([0.5, -4.0], [2.0, 5.0])
    for r in (x + y - y, (x * y) / y, 2 * x / 2, x - 0, 1 + x - 1):
        np.testing.assert_allclose(r.a, x.a, rtol=1e-15)
        np.testing.assert_allclose(r.b, x.b, rtol=1e-15)
    np.testing.assert_allclose((x * y).b, x.a * y.b + x.b * y.a)
    np.testing.assert_allclose((1 / x).b, -x.b / x.a**2)
    r = np.ones(2) + x  # ndarray on the left defers to Dual
    assert isinstance(r, Dual) and np.array_equal(r.a, x.a + 1) and np.array_equal(r.b, x.b)
    with pytest.raises(ZeroDivisionError):
        x / Dual([0.0, 1.0], [1.0, 1.0])
    with pytest.raises(ValueError):
        dual_sqrt(Dual(0.0, 1.0))
    with pytest.raises(ValueError):
        dual_atan2(Dual(0.0, 1.0), Dual(0.0, 2.0))
    assert (x[1].a, x[1].b) == (2.0, -1.0)


def _f(x, sin, cos, sqrt, atan2):
    return sqrt(sin(x) * sin(x) + 1) * cos(x) / (x + 2) - atan2(x * x, 1 - x)


@settings(max_examples=50, deadline=None)
@given(st.floats(-1.5, 1.5).filter(lambda t: abs(t - 1) > 1e-3))
def test_dual_numbers_differentiate_at_50_digits(t):
    """The dual part of f(t + eps) is f'(t): checked against mpmath.diff."""
    with MP50.context():
        x = Dual(MP50.asarray(t), MP50.asarray(1))
        fx = _f(x, dual_sin, dual_cos, dual_sqrt, dual_atan2)
        tt = mpmath.mpf(t)
        ref = mpmath.diff(lambda s: _f(s, mpmath.sin, mpmath.cos, mpmath.sqrt, mpmath.atan2), tt)
        assert abs(fx.b[()] - ref) <= mpmath.mpf(10) ** -45 * (1 + abs(ref))
        assert abs(fx.a[()] - _f(tt, mpmath.sin, mpmath.cos, mpmath.sqrt, mpmath.atan2)) <= (
            mpmath.mpf(10) ** -48
        )


def test_dual_numbers_exact():
    x = Dual(np.array(sympy.Rational(1, 3), dtype=object), np.array(sympy.Integer(2), dtype=object))
    y = x * x / (1 + x)
    # d/dt (t^2/(1+t)) = (t^2 + 2t)/(1+t)^2 at 1/3, times 2
    assert y.a[()] == sympy.Rational(1, 12)
    assert y.b[()] == 2 * (sympy.Rational(1, 9) + sympy.Rational(2, 3)) / sympy.Rational(16, 9)
    s = dual_sqrt(
        Dual(np.array(sympy.Integer(4), dtype=object), np.array(sympy.Integer(1), dtype=object))
    )
    assert (s.a[()], s.b[()]) == (2, sympy.Rational(1, 4))
    a = dual_atan2(
        Dual(np.array(sympy.Integer(1), dtype=object), 0),
        Dual(np.array(sympy.Integer(1), dtype=object), 1),
    )
    assert (a.a[()], a.b[()]) == (sympy.pi / 4, sympy.Rational(-1, 2))


# --- dual vectors: bracket and Klein form ----------------------------------


@settings(max_examples=100, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_dual_vector_operations_are_bracket_and_klein(seed):
    rng = np.random.default_rng(seed)
    x, y = rng.normal(size=(2, 4, 6))
    X, Y = screw_to_dual(x), screw_to_dual(y)
    np.testing.assert_array_equal(dual_to_screw(X), x)
    w1, v1, w2, v2 = x[:, :3], x[:, 3:], y[:, :3], y[:, 3:]
    br = dual_to_screw(dual_cross(X, Y))
    np.testing.assert_allclose(br[:, :3], np.cross(w1, w2), atol=1e-14)
    np.testing.assert_allclose(br[:, 3:], np.cross(w1, v2) - np.cross(w2, v1), atol=1e-14)
    # the bracket is the commutator of the 4x4 hats
    for k in range(4):
        H1, H2 = hat(x[k]), hat(y[k])
        C = H1 @ H2 - H2 @ H1
        np.testing.assert_allclose(hat(br[k]), C, atol=1e-14)
    dd = dual_dot(X, Y)
    np.testing.assert_allclose(dd.a, np.sum(w1 * w2, axis=1), atol=1e-14)
    np.testing.assert_allclose(dd.b, np.sum(w1 * v2 + w2 * v1, axis=1), atol=1e-14)


# --- dual quaternions ------------------------------------------------------


@SETTINGS
@given(screw_displacements())
def test_dual_quaternion_round_trip(g):
    Q = dual_quat_from_displacement(g)
    assert abs(Q.a @ Q.a - 1) <= 4 * EPS
    assert abs(Q.a @ Q.b) <= 8 * EPS * (1 + np.abs(g[:3, 3]).max())  # Study condition
    assert close_disp(dual_quat_to_displacement(Q), g)
    Q2 = dual_quat_from_displacement(dual_quat_to_displacement(Q))
    L = 1 + np.abs(g[:3, 3]).max()
    sign = 1 if np.abs(Q2.a - Q.a).max() <= np.abs(Q2.a + Q.a).max() else -1
    assert np.abs(Q2.a - sign * Q.a).max() <= 8 * EPS
    assert np.abs(Q2.b - sign * Q.b).max() <= 8 * EPS * L


@SETTINGS
@given(screw_displacements(), screw_displacements())
def test_dual_quaternion_product_is_composition(g, h):
    P, Q = dual_quat_from_displacement(g), dual_quat_from_displacement(h)
    L = 1 + np.abs(g[:3, 3]).max() + np.abs(h[:3, 3]).max()
    gh = dual_quat_to_displacement(dual_quat_multiply(P, Q))
    ref = g @ h
    assert np.abs(gh[:3, :3] - ref[:3, :3]).max() <= 16 * EPS
    assert np.abs(gh[:3, 3] - ref[:3, 3]).max() <= 16 * EPS * L
    gi = dual_quat_to_displacement(dual_quat_conjugate(P))
    assert close_disp(gi, np.linalg.inv(g))
    one = dual_quat_multiply(P, dual_quat_conjugate(P))
    assert np.abs(one.a - [1, 0, 0, 0]).max() <= 4 * EPS
    assert np.abs(one.b).max() <= 8 * EPS * L


def test_dual_quaternion_exact_and_batched():
    # a rational displacement: rotation from a rational unit quaternion
    q = [sympy.Rational(1, 3), sympy.Rational(2, 3), sympy.Rational(2, 3), 0]
    w, x, y, z = q
    R = sympy.Matrix(
        [
            [1 - 2 * (y**2 + z**2), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x**2 + z**2), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x**2 + y**2)],
        ]
    )
    g = sympy.eye(4)
    g[:3, :3] = R
    g[:3, 3] = sympy.Matrix([sympy.Rational(5, 2), -7, sympy.Rational(1, 9)])
    G = np.array(g.tolist(), dtype=object)
    Q = dual_quat_from_displacement(G)
    assert [sympy.simplify(c) for c in Q.a] == q
    assert sympy.Matrix(dual_quat_to_displacement(Q).tolist()).applyfunc(sympy.simplify) == g
    PQ = dual_quat_multiply(Q, Q)
    assert sympy.Matrix(dual_quat_to_displacement(PQ).tolist()).applyfunc(sympy.simplify) == g * g
    # batch shape (3, 1, 2)
    rng = np.random.default_rng(4)
    gs = np.stack([screw_reference(*_random_screw(rng)) for _ in range(6)]).reshape(3, 1, 2, 4, 4)
    Qb = dual_quat_from_displacement(gs)
    assert Qb.shape == (3, 1, 2, 4)
    np.testing.assert_allclose(dual_quat_to_displacement(Qb), gs, atol=1e-14)


def _random_screw(rng):
    u = rng.normal(size=3)
    return u / np.linalg.norm(u), rng.normal(size=3), rng.uniform(0, math.pi), rng.normal()


# --- dual Rodrigues and the screw motion -----------------------------------


@SETTINGS
@given(unit_axes(fixed=False), points(), angles, lengths, st.floats(-1, 1), st.floats(0.1, 10))
def test_dual_rodrigues_is_the_screw_motion(u, N, theta, scale, dfrac, ulen):
    d = scale * dfrac
    line = np.concatenate([ulen * u, np.cross(N, ulen * u)])  # non-unit Plücker coordinates
    ref = screw_reference(u, N, theta, d)
    M = dual_rodrigues(line, Dual(theta, d))
    L = 1 + np.abs(N).max() + abs(d)
    # scipy's expm of the 4x4 hat: accurate to eps times the norm of the hat
    E = expm_screw(u, N, theta, d)
    nx = 1 + theta * (1 + np.abs(N).max()) + abs(d)
    assert np.abs(M.a - E[:3, :3]).max() <= 16 * EPS * nx
    assert np.abs(displacement_from_dual_matrix(M)[:3, 3] - E[:3, 3]).max() <= 16 * EPS * nx * L
    assert np.abs(M.a - ref[:3, :3]).max() <= 16 * EPS
    # dual part p^ R (the lower-left block of Ad)
    assert np.abs(M.b - skew(ref[:3, 3]) @ ref[:3, :3]).max() <= 32 * EPS * L
    g = screw_displacement(line, Dual(theta, d))
    assert np.abs(g[:3, 3] - ref[:3, 3]).max() <= 32 * EPS * L
    assert np.abs(g[:3, :3] - ref[:3, :3]).max() <= 16 * EPS
    # a pitch added to the line does not change its axis
    h = screw_displacement(line + np.concatenate([np.zeros(3), 0.7 * line[:3]]), Dual(theta, d))
    assert np.abs(h[:3, 3] - g[:3, 3]).max() <= 32 * EPS * L
    # the dual matrix moves lines: M (u + eps m) is the image line
    Mg = dual_matrix_from_displacement(ref)
    img = dual_matmul(Mg, Dual(u[:, None], np.cross(N, u)[:, None]))
    np.testing.assert_allclose(img.a[:, 0], ref[:3, :3] @ u, atol=8 * EPS)
    NN = ref[:3, :3] @ N + ref[:3, 3]
    assert np.abs(img.b[:, 0] - np.cross(NN, ref[:3, :3] @ u)).max() <= 64 * EPS * L


@settings(max_examples=60, deadline=None)
@given(unit_axes(fixed=False), points(), angles, st.floats(-10, 10))
def test_dual_quaternion_of_a_screw_motion(u, N, theta, d):
    """cos(t^/2) + sin(t^/2) (u + eps m) is the dual quaternion of the screw motion."""
    half = Dual(theta / 2, d / 2)
    c, s = dual_cos(half), dual_sin(half)
    m = np.cross(N, u)
    Q = Dual(np.concatenate([[c.a[()]], s.a * u]), np.concatenate([[c.b[()]], s.a * m + s.b * u]))
    g = screw_displacement(np.concatenate([u, m]), Dual(theta, d))
    ref = dual_quat_from_displacement(g)
    L = 1 + np.abs(N).max() + abs(d)
    sign = 1.0 if np.abs(ref.a - Q.a).max() <= np.abs(ref.a + Q.a).max() else -1.0
    assert np.abs(ref.a - sign * Q.a).max() <= 8 * EPS
    assert np.abs(ref.b - sign * Q.b).max() <= 32 * EPS * L


def test_dual_rodrigues_exact():
    u = np.array([sympy.Rational(2, 7), sympy.Rational(3, 7), sympy.Rational(6, 7)], dtype=object)
    N = np.array([1, sympy.Rational(-1, 2), 3], dtype=object)
    m = np.array(
        sympy.Matrix(N.tolist()).cross(sympy.Matrix(u.tolist())).T.tolist()[0], dtype=object
    )
    theta = np.array(sympy.pi / 2, dtype=object)
    d = np.array(sympy.Rational(5, 4), dtype=object)
    g = screw_displacement(np.concatenate([u, m]), Dual(theta, d))
    G = sympy.Matrix(g.tolist())
    X = sympy.Matrix(hat(np.concatenate([u, m + d[()] / theta[()] * u])).tolist()) * theta[()]
    ref = X.exp()
    assert (G - ref).applyfunc(lambda e: sympy.simplify(sympy.expand_complex(e))) == sympy.zeros(4)


# --- dual angle ------------------------------------------------------------


def closest_points(p1, u1, p2, u2):
    A = np.stack([u1, -u2], axis=1)
    st_, *_ = np.linalg.lstsq(A, p2 - p1, rcond=None)
    return p1 + st_[0] * u1, p2 + st_[1] * u2


@SETTINGS
@given(unit_axes(fixed=False), unit_axes(fixed=False), points(), points())
def test_dual_angle_against_closest_points(u1, u2, p1, p2):
    s = np.linalg.norm(np.cross(u1, u2))
    if s < 1e-3:  # near-parallel lines have an ill-conditioned common normal
        u2 = np.cross(u1, np.eye(3)[np.argmin(np.abs(u1))])
        u2 /= np.linalg.norm(u2)
        s = np.linalg.norm(np.cross(u1, u2))
    L1 = np.concatenate([u1, np.cross(p1, u1)])
    L2 = np.concatenate([3 * u2, np.cross(p2, 3 * u2)])
    ang = dual_angle(L1, L2)
    theta = math.atan2(s, u1 @ u2)
    n = np.cross(u1, u2) / s
    c1, c2 = closest_points(p1, u1, p2, u2)
    scale = 1 + np.abs(p1).max() + np.abs(p2).max()
    assert abs(ang.a - theta) <= 8 * EPS
    assert abs(ang.b - (p2 - p1) @ n) <= 64 * EPS * scale / s
    # lstsq reference (condition number 1/s)
    assert abs(abs(ang.b) - np.linalg.norm(c2 - c1)) <= 64 * EPS * scale / s**2
    # symmetric; invariant under a common displacement; dual cosine = dual dot
    sym = dual_angle(L2, L1)
    assert abs(sym.a - ang.a) <= 4 * EPS and abs(sym.b - ang.b) <= 64 * EPS * scale / s
    U1 = Dual(u1, np.cross(p1, u1))
    U2 = Dual(u2, np.cross(p2, u2))
    cos = dual_cos(ang)
    dd = dual_dot(U1, U2)
    assert abs(cos.a - dd.a) <= 4 * EPS
    assert abs(cos.b - dd.b) <= 64 * EPS * scale / s  # Klein form = -d sin(theta)


def test_dual_angle_special_cases():
    z = np.array([0.0, 0, 1])
    origin = np.zeros(3)

    def line(p, u):
        return np.concatenate([u, np.cross(p, u)])

    # skew lines at right angles: sign of d along n = u1 x u2
    ang = dual_angle(line(origin, z), line(np.array([2.0, 0, 0]), np.array([0.0, 1, 0])))
    assert (ang.a[()], ang.b[()]) == (math.pi / 2, -2.0)
    # intersecting lines: d = 0
    p = np.array([1e9, -3.0, 2.0])
    ang = dual_angle(line(p, z), line(p, np.array([0.6, 0.0, 0.8])))
    assert ang.b == 0 or abs(ang.b) <= 8 * EPS * 1e9
    np.testing.assert_allclose(ang.a, math.acos(0.8), rtol=4 * EPS)
    # parallel and antiparallel lines: theta = 0, pi and d = distance >= 0
    for sgn, th in ((1.0, 0.0), (-1.0, math.pi)):
        ang = dual_angle(line(origin, z), line(np.array([3.0, 4.0, 7.0]), sgn * z))
        assert (ang.a[()], ang.b[()]) == (th, 5.0)
    # the same line: 0 + eps 0
    ang = dual_angle(line(p, z), line(p + 5 * z, 2 * z))
    assert ang.a == 0 and abs(ang.b) <= 8 * EPS * 1e9
    # exact: rational lines give the exact dual angle
    q = sympy.Rational
    L1 = np.array([0, 0, 1, 0, 0, 0], dtype=object)
    L2 = np.array(
        [1, 1, 0] + list(sympy.Matrix([q(1, 2), 0, 0]).cross(sympy.Matrix([1, 1, 0]))), dtype=object
    )
    ang = dual_angle(L1, L2)
    # n = z x (1,1,0)/sqrt2 = (-1, 1, 0)/sqrt2, d = (1/2, 0, 0).n
    assert sympy.simplify(ang.a[()] - sympy.pi / 2) == 0
    assert sympy.simplify(ang.b[()] + 1 / (2 * sympy.sqrt(2))) == 0
    with pytest.raises(ValueError, match="non-zero direction"):
        dual_angle(np.array([0.0, 0, 0, 1, 0, 0]), line(origin, z))


# --- dual rank ------------------------------------------------------------


def R_(p, u):
    return [*u, *np.cross(p, u)]


def P_(u):
    return [0.0, 0.0, 0.0, *u]


X, Y, Z = np.eye(3)
O3 = np.zeros(3)
CASES = {
    # name: (screws, (primal, dual, total, real))
    "R": ([R_([1, 2, 3], Z)], (1, 0, 1, 1)),
    "C = R + P on one line": ([R_([1, 2, 3], Z), P_(Z)], (1, 0, 1, 2)),
    "two parallel R": ([R_(O3, Z), R_(X, Z)], (1, 1, 2, 2)),
    "R + P normal to it": ([R_(O3, Z), P_(X)], (1, 1, 2, 2)),
    "G: three parallel R": ([R_(O3, Z), R_(X, Z), R_(Y, Z)], (1, 2, 3, 3)),
    "S: three R through a point": (
        [R_([1, 1, 2], X), R_([1, 1, 2], Y), R_([1, 1, 2], Z)],
        (3, 0, 3, 3),
    ),
    "four concurrent lines": (
        [R_([1, 1, 2], X), R_([1, 1, 2], Y), R_([1, 1, 2], Z), R_([1, 1, 2], [1, 2, 3])],
        (3, 0, 3, 3),
    ),
    "T3": ([P_(X), P_(Y), P_(Z)], (0, 3, 3, 3)),
    "two skew R": ([R_(O3, Z), R_(X, Y)], (2, 0, 2, 2)),
    "D: six screws": ([R_(O3, X), R_(O3, Y), R_(O3, Z), P_(X), P_(Y), P_(Z)], (3, 0, 3, 6)),
    "empty": (np.zeros((0, 6)), (0, 0, 0, 0)),
}


@pytest.mark.parametrize("precision", ["float", "mp:50", "exact"])
@pytest.mark.parametrize("name", list(CASES))
def test_dual_rank_known_cases(name, precision):
    screws, expected = CASES[name]
    S = np.asarray(screws, dtype=float).reshape(-1, 6)
    r = dual_rank(S, precision)
    assert (r.primal, r.dual, r.total, r.real) == expected
    assert r.precision == precision
    if precision != "exact" and expected[1] == 0:
        assert r.dual_margin is None or r.dual_margin.kept is None


@pytest.mark.parametrize("k", [-6, 6])
def test_dual_rank_is_unit_free(k):
    """Scaling all lengths by 10^k changes no verdict and no margin."""
    rng = np.random.default_rng(7)
    for screws, _ in CASES.values():
        S = np.asarray(screws, dtype=float).reshape(-1, 6)
        # move the whole set by a random displacement first (no special axes)
        g = screw_reference(*_random_screw(rng))
        Ad = adjoint(g)
        S = S @ Ad.T
        T = S.copy()
        T[:, 3:] *= 10.0**k
        a, b = dual_rank(S), dual_rank(T)
        assert (a.primal, a.dual, a.total, a.real) == (b.primal, b.dual, b.total, b.real)
        for ma, mb in (
            (a.primal_margin, b.primal_margin),
            (a.dual_margin, b.dual_margin),
            (a.real_margin, b.real_margin),
        ):
            if ma is None or mb is None:
                assert ma is mb
                continue
            # margins give singular values with the sigma_max the thresholds are relative
            # to; unit-free means the relative values (the decision) do not change
            for x, y in ((ma.kept, mb.kept), (ma.dropped, mb.dropped)):
                assert (x is None) == (y is None)
                if x is not None:
                    x = x / ma.sigma_max if ma.sigma_max else x
                    y = y / mb.sigma_max if mb.sigma_max else y
                    assert abs(x - y) <= 1e-9 * max(abs(x), 1e-9) + 1e-12


def test_dual_rank_survives_where_a_mixed_unit_svd_does_not():
    # two parallel revolute axes 1 mm apart, written in units of 1e-6 m ... 1e-9
    for scale in (1e-3, 1e-9, 1e-12):
        S = np.array([R_(O3, Z), R_([scale, 0, 0], Z)])
        r = dual_rank(S)
        assert (r.primal, r.dual, r.total, r.real) == (1, 1, 2, 2)
    naive = decide_rank(np.array([R_(O3, Z), R_([1e-12, 0, 0], Z)]).T, "float")
    assert naive.rank != 2  # the one-SVD verdict changed with the unit


def _exact_reference(S):
    """(primal, dual, total, real) from exact ranks of real matrices."""
    M = sympy.Matrix(S)
    A, B = M[:, :3], M[:, 3:]
    r0 = A.rank()
    real = M.rank()
    # the D-span as a real vector space is spanned by (A, B) and eps (A, B) = (0, A)
    big = sympy.Matrix(sympy.BlockMatrix([[A, B], [sympy.zeros(*A.shape), A]]))
    r1 = big.rank() - 2 * r0
    return r0, r1, r0 + r1, real


@settings(max_examples=40, deadline=None)
@given(
    st.integers(1, 5),
    st.integers(1, 5),
    st.lists(st.integers(-3, 3), min_size=60, max_size=60),
    st.booleans(),
)
def test_dual_rank_matches_exact_module_invariants(n, k, ints, planar_omegas):
    """Random integer screw sets of deficient rank (n screws from k generators),
    decided in float and exactly, against sympy ranks of real matrices."""
    G = np.array(ints[: 6 * k], dtype=float).reshape(k, 6)
    if planar_omegas:
        G[:, :2] = 0  # omega parts along z only: primal rank <= 1
    C = np.array(ints[30 : 30 + n * k], dtype=float).reshape(n, k)
    S = C @ G
    expected = _exact_reference(S.astype(int).tolist())
    got_exact = dual_rank(S, "exact")
    got_float = dual_rank(S, "float")
    assert (got_exact.primal, got_exact.dual, got_exact.total, got_exact.real) == expected
    assert (got_float.primal, got_float.dual, got_float.total, got_float.real) == expected


def test_dual_rank_mp50_resolves_what_float_cannot():
    # two revolute axes parallel up to 1e-20 rad: float sees one direction
    # (primal 1, dual 1), 50 digits sees two directions (primal 2)
    with MP50.context():
        t = mpmath.mpf("1e-20")
        # the z axis, and the axis (0, t, 1) through (0, 1, 0): moment (1, 0, 0)
        S = MP50.asarray([[0, 0, 1, 0, 0, 0], [0, t, 1, 1, 0, 0]])
    r50 = dual_rank(S, "mp:50")
    assert (r50.primal, r50.dual, r50.total, r50.real) == (2, 0, 2, 2)
    rf = dual_rank(np.array(S.tolist(), dtype=float), "float")
    assert (rf.primal, rf.dual, rf.total, rf.real) == (1, 1, 2, 2)
    with pytest.raises(ValueError, match=r"\(n, 6\)"):
        dual_rank(np.zeros((2, 5)))
