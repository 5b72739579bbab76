"""Cayley transforms (mechsing.lie.cayley).  Independent references: the
defining products (I + X)(I - X)^-1 with numpy / mpmath matrix inverses,
scipy's Rotation for the rotation angle 2 atan|a|, and exact sympy algebra."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from mechsing.lie.cayley import (
    cayley_se3,
    cayley_se3_inverse,
    cayley_skew,
    cayley_skew_inverse,
    cayley_so3,
    cayley_so3_inverse,
)
from mechsing.lie.quaternion import quat_to_rotation_matrix
from mechsing.numeric import Precision
from tests.reference.se3 import adjoint, hat, skew
from tests.strategies import gibbs, rationals
from tests.strategies import gibbs_twists as twists

EPS = float(np.finfo(float).eps)
SETTINGS = settings(max_examples=150, deadline=None)


# --- SO(3) -----------------------------------------------------------------


@SETTINGS
@given(gibbs())
def test_cayley_so3_is_rotation_by_twice_atan(a):
    R = cayley_so3(a)
    n = np.linalg.norm(a)
    np.testing.assert_allclose(R.T @ R, np.eye(3), rtol=0, atol=8 * EPS)
    assert abs(np.linalg.det(R) - 1) <= 8 * EPS
    ref = Rotation.from_rotvec(2 * math.atan(n) * (a / n if n > 0 else a)).as_matrix()
    np.testing.assert_allclose(R, ref, rtol=0, atol=8 * EPS)
    # the same rotation as the quaternion (1, a)
    np.testing.assert_allclose(R, quat_to_rotation_matrix(np.concatenate([[1.0], a])), atol=4 * EPS)


@SETTINGS
@given(gibbs().filter(lambda a: np.linalg.norm(a) <= 1e3))
def test_cayley_so3_matches_defining_product(a):
    A = skew(a)
    ref = (np.eye(3) + A) @ np.linalg.inv(np.eye(3) - A)
    n2 = float(a @ a)
    # conditioning of I - A is 1 + |a|^2
    np.testing.assert_allclose(cayley_so3(a), ref, rtol=0, atol=8 * EPS * (1 + n2))
    np.testing.assert_allclose(cayley_skew(A), cayley_so3(a), rtol=0, atol=0)


@SETTINGS
@given(gibbs().filter(lambda a: np.linalg.norm(a) <= 1e4))
def test_cayley_so3_round_trip(a):
    R = cayley_so3(a)
    back = cayley_so3_inverse(R)
    n = np.linalg.norm(a)
    # 1 + tr R = 4/(1 + |a|^2) carries an absolute rounding error ~ eps, so the
    # relative accuracy of a is ~ eps (1 + |a|^2)
    assert np.linalg.norm(back - a) <= 8 * EPS * n * (1 + n * n)
    np.testing.assert_allclose(cayley_skew_inverse(R), skew(back), rtol=0, atol=0)


@settings(max_examples=100, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_rotation_round_trip_for_random_rotations(seed):
    R = Rotation.random(6, random_state=seed).as_matrix()
    R = R[np.trace(R, axis1=-2, axis2=-1) > -0.9]  # keep away from half-turns
    a = cayley_so3_inverse(R)
    np.testing.assert_allclose(cayley_so3(a), R, rtol=0, atol=64 * EPS)
    ang = Rotation.from_matrix(R).magnitude()
    np.testing.assert_allclose(np.linalg.norm(a, axis=-1), np.tan(ang / 2), rtol=64 * EPS)


def test_half_turns_raise():
    for i in range(3):
        R = -np.eye(3)
        R[i, i] = 1.0
        with pytest.raises(ValueError, match="half-turn"):
            cayley_so3_inverse(R)
        g = np.eye(4)
        g[:3, :3] = R
        with pytest.raises(ValueError, match="half-turn"):
            cayley_se3_inverse(g)
    # exactly pi about a non-coordinate axis, exact arithmetic
    u = sympy.Matrix([2, 3, 6]) / 7
    R = np.array((2 * u * u.T - sympy.eye(3)).tolist(), dtype=object)
    with pytest.raises(ValueError, match="half-turn"):
        cayley_so3_inverse(R)
    with pytest.raises(ValueError, match="half-turn"):
        cayley_skew_inverse(np.stack([np.eye(3), np.diag([1.0, -1, -1])]))


def test_batch_shapes():
    rng = np.random.default_rng(3)
    for shape in [(), (1,), (3, 1, 2)]:
        a = rng.normal(size=shape + (3,))
        R = cayley_so3(a)
        assert R.shape == shape + (3, 3)
        assert cayley_so3_inverse(R).shape == shape + (3,)
        xi = rng.normal(size=shape + (6,))
        g = cayley_se3(xi)
        assert g.shape == shape + (4, 4)
        np.testing.assert_allclose(cayley_se3_inverse(g), xi, atol=1e-13)


# --- exact -----------------------------------------------------------------


@settings(max_examples=60, deadline=None)
@given(st.lists(rationals, min_size=3, max_size=3))
def test_exact_rational_gibbs_vector(vals):
    a = np.array(vals, dtype=object)
    R = cayley_so3(a)
    M = sympy.Matrix(R.tolist())
    assert all(x.is_Rational for x in M)
    assert M.T * M == sympy.eye(3)
    assert M.det() == 1
    A = sympy.Matrix(skew(a).tolist())
    assert M == (sympy.eye(3) + A) * (sympy.eye(3) - A).inv()
    assert list(cayley_so3_inverse(R)) == vals
    # tan of half the rotation angle is |a|: 1 + tr R = 4/(1 + |a|^2)
    assert 1 + M.trace() == 4 / (1 + sum(x**2 for x in vals))


@settings(max_examples=40, deadline=None)
@given(st.lists(rationals, min_size=6, max_size=6))
def test_exact_se3_cayley(vals):
    xi = np.array(vals, dtype=object)
    g = cayley_se3(xi)
    G = sympy.Matrix(g.tolist())
    X = sympy.Matrix(hat(xi).tolist())
    assert G == (sympy.eye(4) + X) * (sympy.eye(4) - X).inv()
    assert all(x.is_Rational for x in G)
    assert list(cayley_se3_inverse(g)) == vals


# --- SE(3) -----------------------------------------------------------------


@SETTINGS
@given(twists().filter(lambda x: np.linalg.norm(x[:3]) <= 1e3))
def test_cayley_se3_matches_defining_product(xi):
    # reference: (I + X)(I - X)^-1 with mpmath's matrix inverse at 40 digits
    with mpmath.workdps(40):
        X = mpmath.matrix(hat(xi).tolist())
        ref = (mpmath.eye(4) + X) * mpmath.inverse(mpmath.eye(4) - X)
        ref = np.array(ref.tolist(), dtype=float)
    g = cayley_se3(xi)
    scale = 1 + np.abs(xi[3:]).max()
    np.testing.assert_allclose(g[:3, :3], ref[:3, :3], rtol=0, atol=8 * EPS)
    np.testing.assert_allclose(g[:3, 3], ref[:3, 3], rtol=0, atol=16 * EPS * scale)
    assert np.array_equal(g[3], [0, 0, 0, 1])


@SETTINGS
@given(twists().filter(lambda x: np.linalg.norm(x[:3]) <= 1e3))
def test_cayley_se3_round_trip(xi):
    back = cayley_se3_inverse(cayley_se3(xi))
    n2 = float(xi[:3] @ xi[:3])
    np.testing.assert_allclose(back[:3], xi[:3], rtol=0, atol=8 * EPS * np.sqrt(n2) * (1 + n2))
    # below the normal range rounding is absolute: one subnormal ulp
    np.testing.assert_allclose(
        back[3:],
        xi[3:],
        rtol=0,
        atol=16 * EPS * (1 + n2) * np.abs(xi[3:]).max() + np.finfo(float).smallest_subnormal,
    )


@SETTINGS
@given(twists(), twists())
def test_cayley_se3_is_equivariant(xi, eta):
    # cay(Ad(g) xi) = g cay(xi) g^-1, with g any displacement (here a Cayley image)
    g = cayley_se3(eta)
    lhs = cayley_se3(adjoint(g) @ xi)
    rhs = g @ cayley_se3(xi) @ np.linalg.inv(g)
    R = cayley_so3(xi[:3])
    # conditioning: |omega'| = |omega| but the moved v carries |p| |omega|
    w = 1 + np.abs(xi[:3]).max()
    L = np.abs(g[:3, 3]).max() + np.abs(xi[3:]).max() + 1
    np.testing.assert_allclose(lhs[:3, :3], rhs[:3, :3], rtol=0, atol=64 * EPS * w)
    np.testing.assert_allclose(lhs[:3, 3], rhs[:3, 3], rtol=0, atol=64 * EPS * w * L)
    assert np.allclose(R.T @ R, np.eye(3), rtol=0, atol=8 * EPS)


def test_translation_and_zero_pitch():
    v = np.array([1e9, -2e-9, 3.0])
    g = cayley_se3(np.concatenate([np.zeros(3), v]))
    assert np.array_equal(g[:3, :3], np.eye(3))
    assert np.array_equal(g[:3, 3], 2 * v)
    # a zero-pitch twist about a line through N gives a rotation fixing N
    u = np.array([2.0, 3.0, 6.0]) / 7
    N = np.array([1.0, -2.0, 0.5])
    g = cayley_se3(np.concatenate([0.3 * u, np.cross(N, 0.3 * u)]))
    np.testing.assert_allclose(g[:3, :3] @ N + g[:3, 3], N, atol=8 * EPS)


MP50 = Precision("mp", 50)


@settings(max_examples=25, deadline=None)
@given(twists().filter(lambda x: np.linalg.norm(x[:3]) <= 1e6))
def test_mp50_against_mpmath_inverse(xi):
    with MP50.context():
        x = MP50.asarray(xi)
        g = cayley_se3(x)
        X = mpmath.matrix(hat(x).tolist())
        ref = (mpmath.eye(4) + X) * mpmath.inverse(mpmath.eye(4) - X)
        n2 = 1 + sum(c * c for c in x[:3])
        scale = 1 + max(abs(c) for c in x[3:])
        tol = mpmath.mpf(10) ** -48 * n2 * scale
        assert all(abs(g[i, j] - ref[i, j]) <= tol for i in range(4) for j in range(4))
        back = cayley_se3_inverse(g)
        assert all(abs(b - c) <= tol * n2 for b, c in zip(back, x, strict=True))
