"""Unit quaternions (mechsing.lie.quaternion): references are scipy's Rotation
(scalar-LAST layout, converted here) and direct mpmath / sympy evaluation."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from mechsing.lie.quaternion import (
    quat_conjugate,
    quat_exp,
    quat_from_rotation_matrix,
    quat_inverse,
    quat_log,
    quat_multiply,
    quat_rotate,
    quat_to_rotation_matrix,
)
from mechsing.numeric import Precision
from tests.strategies import rotvecs

EPS = float(np.finfo(float).eps)
SETTINGS = settings(max_examples=150, deadline=None)


def to_scipy(q):
    return np.asarray(q)[..., [1, 2, 3, 0]]


def from_scipy(q):
    return np.asarray(q)[..., [3, 0, 1, 2]]


def same_up_to_sign(a, b, tol):
    return min(np.max(np.abs(a - b)), np.max(np.abs(a + b))) <= tol


# --- float: comparisons with scipy ----------------------------------------


@SETTINGS
@given(rotvecs())
def test_exp_matches_scipy_and_log_inverts_it(phi):
    q = quat_exp(phi)
    ref = from_scipy(Rotation.from_rotvec(phi).as_quat())
    assert same_up_to_sign(q, ref, 2 * EPS)
    assert abs(np.dot(q, q) - 1) <= 4 * EPS
    theta = np.linalg.norm(phi)
    # |phi| may round to just above pi (w < 0): log then returns the other
    # representative, of angle 2 pi - |phi| <= pi
    assert q[0] >= -2 * EPS
    expected = phi if q[0] >= 0 else phi * (1 - 2 * math.pi / theta)
    back = quat_log(q)
    # the log is accurate relative to the angle at both ends of [0, pi]
    assert np.linalg.norm(back - expected) <= 4 * EPS * max(theta, 1e-300)


@SETTINGS
@given(rotvecs())
def test_matrix_round_trip_and_scipy_matrix(phi):
    q = quat_exp(phi)
    R = quat_to_rotation_matrix(q)
    np.testing.assert_allclose(R, Rotation.from_rotvec(phi).as_matrix(), rtol=0, atol=4 * EPS)
    np.testing.assert_allclose(R.T @ R, np.eye(3), rtol=0, atol=8 * EPS)
    q2 = quat_from_rotation_matrix(R)
    assert q2[0] >= 0
    assert same_up_to_sign(q2, q, 4 * EPS)
    np.testing.assert_allclose(quat_to_rotation_matrix(q2), R, rtol=0, atol=8 * EPS)


@settings(max_examples=100, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_from_rotation_matrix_matches_scipy(seed):
    rot = Rotation.random(8, random_state=seed)
    q = quat_from_rotation_matrix(rot.as_matrix())
    ref = from_scipy(rot.as_quat())
    ref = np.where(ref[:, :1] < 0, -ref, ref)  # scipy's sign is not w >= 0
    np.testing.assert_allclose(q, ref, rtol=0, atol=4 * EPS)


@SETTINGS
@given(rotvecs(), rotvecs(), st.lists(st.floats(-1e3, 1e3), min_size=3, max_size=3))
def test_group_laws(phi1, phi2, v):
    p, q = quat_exp(phi1), quat_exp(phi2)
    v = np.array(v)
    # homomorphism to SO(3): R(p q) = R(p) R(q); rotate = matrix product
    np.testing.assert_allclose(
        quat_to_rotation_matrix(quat_multiply(p, q)),
        quat_to_rotation_matrix(p) @ quat_to_rotation_matrix(q),
        rtol=0,
        atol=16 * EPS,
    )
    np.testing.assert_allclose(
        quat_rotate(p, v),
        quat_to_rotation_matrix(p) @ v,
        rtol=0,
        atol=16 * EPS * (1 + np.abs(v).max()),
    )
    ref = Rotation.from_quat(to_scipy(p)) * Rotation.from_quat(to_scipy(q))
    assert same_up_to_sign(quat_multiply(p, q), from_scipy(ref.as_quat()), 8 * EPS)
    # inverse and conjugate
    np.testing.assert_allclose(quat_multiply(p, quat_conjugate(p)), [1, 0, 0, 0], atol=4 * EPS)
    np.testing.assert_allclose(quat_inverse(p), quat_conjugate(p), atol=4 * EPS)


def test_associativity_and_non_unit_inverse():
    rng = np.random.default_rng(1)
    a, b, c = rng.normal(size=(3, 5, 4))
    np.testing.assert_allclose(
        quat_multiply(quat_multiply(a, b), c), quat_multiply(a, quat_multiply(b, c)), atol=1e-14
    )
    np.testing.assert_allclose(
        quat_multiply(a, quat_inverse(a)), np.tile([1, 0, 0, 0], (5, 1)), atol=1e-15
    )
    # the rational (homogeneous) rotation formulas accept non-unit quaternions
    un = a / np.linalg.norm(a, axis=-1, keepdims=True)
    np.testing.assert_allclose(quat_to_rotation_matrix(a), quat_to_rotation_matrix(un), atol=1e-15)
    np.testing.assert_allclose(quat_rotate(a, b[:, 1:]), quat_rotate(un, b[:, 1:]), atol=1e-14)
    np.testing.assert_allclose(quat_log(3 * un), quat_log(un), atol=1e-15)


@pytest.mark.parametrize("shape", [(), (1,), (3, 1, 2)])
def test_batch_shapes(shape):
    rng = np.random.default_rng(2)
    phi = rng.normal(size=shape + (3,))
    q = quat_exp(phi)
    assert q.shape == shape + (4,)
    R = quat_to_rotation_matrix(q)
    assert R.shape == shape + (3, 3)
    assert quat_from_rotation_matrix(R).shape == shape + (4,)
    assert quat_log(q).shape == shape + (3,)
    assert quat_multiply(q, q).shape == shape + (4,)
    assert quat_rotate(q, phi).shape == shape + (3,)
    flat = phi.reshape(-1, 3)
    np.testing.assert_allclose(
        R.reshape(-1, 3, 3), Rotation.from_rotvec(flat).as_matrix(), rtol=0, atol=8 * EPS
    )


# --- half-turns: the documented sign at w == 0 ----------------------------


def half_turn(u):
    u = sympy.Matrix(u) / sympy.sqrt(sum(x**2 for x in u))
    return np.array((2 * u * u.T - sympy.eye(3)).tolist(), dtype=object)


@pytest.mark.parametrize(
    ("axis", "expected"),
    [
        ((2, 3, 6), (0, sympy.Rational(2, 7), sympy.Rational(3, 7), sympy.Rational(6, 7))),
        ((-2, 3, -6), (0, sympy.Rational(2, 7), sympy.Rational(-3, 7), sympy.Rational(6, 7))),
        ((1, -1, 0), (0, 1 / sympy.sqrt(2), -1 / sympy.sqrt(2), 0)),  # tie: x wins
        ((0, 0, -1), (0, 0, 0, 1)),
    ],
)
def test_half_turn_sign_exact_and_float(axis, expected):
    R = half_turn(axis)
    q = quat_from_rotation_matrix(R)
    assert all(sympy.simplify(a - b) == 0 for a, b in zip(q, expected, strict=True))
    # log of a half-turn has angle exactly pi along the (signed) axis
    w = quat_log(q)
    assert sympy.simplify(sum(x**2 for x in w) - sympy.pi**2) == 0
    # float: same rule (these matrices are exact or within rounding of a half-turn)
    qf = quat_from_rotation_matrix(np.array(R.tolist(), dtype=float))
    np.testing.assert_allclose(qf, np.array(expected, dtype=float), atol=4e-8)


def test_half_turn_exact_float_diagonals():
    for i in range(3):
        R = -np.eye(3)
        R[i, i] = 1.0
        q = quat_from_rotation_matrix(R)
        expected = np.zeros(4)
        expected[i + 1] = 1.0
        assert np.array_equal(q, expected)
        assert np.array_equal(quat_log(q), math.pi * expected[1:])
    # q and -q at w == 0 give the two valid logs +-pi u
    assert np.array_equal(quat_log(np.array([0.0, -1, 0, 0])), [-math.pi, 0, 0])


# --- exact (sympy) and 50 digits (mpmath) ----------------------------------


@settings(max_examples=40, deadline=None)
@given(st.lists(st.integers(-9, 9), min_size=4, max_size=4).filter(any))
def test_exact_rational_quaternion_gives_exact_rotation(ints):
    q = np.array([sympy.Integer(i) / 3 for i in ints], dtype=object)
    R = quat_to_rotation_matrix(q)
    M = sympy.Matrix(R.tolist())
    assert all(x.is_Rational for x in M)
    assert M.T * M == sympy.eye(3)
    assert M.det() == 1
    # back to the unit quaternion: the same rotation, exactly, with w >= 0
    qb = quat_from_rotation_matrix(R)
    Mb = sympy.Matrix(quat_to_rotation_matrix(qb).tolist()).applyfunc(sympy.nsimplify)
    assert (Mb - M).applyfunc(sympy.simplify) == sympy.zeros(3)
    assert sympy.simplify(sum(x**2 for x in qb) - 1) == 0
    assert bool(qb[0] >= 0)
    # rotate agrees with the matrix exactly
    v = np.array([sympy.Rational(1, 2), sympy.Integer(-3), sympy.Rational(5, 7)], dtype=object)
    assert sympy.Matrix(quat_rotate(q, v).tolist()) == M * sympy.Matrix(v.tolist())


def test_exact_exp_log_at_zero_and_right_angle():
    z = np.array([sympy.Integer(0)] * 3, dtype=object)
    q = quat_exp(z)
    assert list(q) == [1, 0, 0, 0]
    assert list(quat_log(q)) == [0, 0, 0]
    half = np.array([sympy.Integer(1), sympy.Integer(1), 0, 0], dtype=object)
    assert [sympy.simplify(x) for x in quat_log(half)] == [sympy.pi / 2, 0, 0]
    qe = quat_exp(np.array([sympy.pi / 3, 0, 0], dtype=object))
    assert [sympy.simplify(x) for x in qe] == [sympy.sqrt(3) / 2, sympy.Rational(1, 2), 0, 0]


MP50 = Precision("mp", 50)


@settings(max_examples=60, deadline=None)
@given(rotvecs())
def test_mp50_exp_log_against_direct_mpmath(phi):
    with MP50.context():
        x = MP50.asarray(phi)
        q = quat_exp(x)
        assert all(isinstance(c, mpmath.mpf) for c in q)
        t = mpmath.sqrt(sum(c * c for c in x))
        if t == 0:
            ref = [mpmath.mpf(1), 0, 0, 0]
        else:
            ref = [mpmath.cos(t / 2)] + [mpmath.sin(t / 2) / t * c for c in x]
        assert max(abs(a - b) for a, b in zip(q, ref, strict=True)) <= mpmath.mpf(10) ** -49
        back = quat_log(q)
        # |x| may exceed pi (a float near pi): then the log is the other representative
        expected = x if q[0] >= 0 else x * (1 - 2 * mpmath.pi / t)
        err = mpmath.sqrt(sum((a - b) ** 2 for a, b in zip(back, expected, strict=True)))
        assert err <= mpmath.mpf(10) ** -48 * max(t, mpmath.mpf(10) ** -300)
        R = quat_to_rotation_matrix(q)
        q2 = quat_from_rotation_matrix(R)
        d = min(
            max(abs(a - b) for a, b in zip(q2, q, strict=True)),
            max(abs(a + b) for a, b in zip(q2, q, strict=True)),
        )
        assert d <= mpmath.mpf(10) ** -48


def test_mp50_series_branch_is_accurate():
    # below the switch point the series must still give 50 correct digits
    with MP50.context():
        for t in ["1e-30", "1e-12", "3e-9", "1e-6"]:
            x = MP50.asarray([t, "0", "0"])
            q = quat_exp(x)
            tt = mpmath.mpf(t)
            assert abs(q[1] - mpmath.sin(tt / 2)) <= mpmath.mpf(10) ** -50 * tt
            back = quat_log(q)
            assert abs(back[0] - tt) <= mpmath.mpf(10) ** -49 * tt


def test_bad_input():
    with pytest.raises(ValueError, match="zero quaternion"):
        quat_log(np.zeros(4))
    with pytest.raises(ValueError, match="zero quaternion"):
        quat_inverse(np.zeros((2, 4)))
    with pytest.raises(ValueError, match=r"\(\.\.\., 4\)"):
        quat_multiply(np.zeros(3), np.zeros(4))
    with pytest.raises(ValueError, match=r"\(\.\.\., 3, 3\)"):
        quat_from_rotation_matrix(np.eye(4))
