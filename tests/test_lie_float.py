"""The float64 fast paths of the Lie layer (mechsing.lie._float) give the generic code's
numbers bit for bit, row by row, at the branch points (angles 0, tiny, at the series
switch, near and at pi, beyond pi), and agree with references independent of mechsing
(scipy's expm, mpmath at 50 digits)."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import scipy.linalg

from mechsing import lie
from mechsing.lie import _float, _so3
from mechsing.lie._series import SWITCH_T2


def _generic(f, *args):
    """f(*args) with the float fast paths off (every float array takes the generic code)."""
    saved = _float.F64
    _float.F64 = np.dtype("V1")  # a dtype no array of the tests has
    try:
        return f(*args)
    finally:
        _float.F64 = saved


def _angles(n: int, rng: np.random.Generator) -> np.ndarray:
    """Angles at the branch points: 0, tiny, around the series switch, generic, near pi,
    exactly pi, beyond pi."""
    s = math.sqrt(SWITCH_T2)
    fixed = [0.0, 1e-300, 1e-160, 1e-12, 1e-8, s, np.nextafter(s, 0), np.nextafter(s, 2)]
    fixed += [math.pi, np.nextafter(math.pi, 0), math.pi - 1e-9, math.pi - 1e-5, 4.0, 7.5]
    rest = np.concatenate(
        [
            10.0 ** rng.uniform(-17, 0, n),
            rng.uniform(0.5, 1.5, n),
            rng.uniform(0, math.pi, n),
            math.pi - 10.0 ** rng.uniform(-16, -1, n),
        ]
    )
    return np.concatenate([fixed, rest])


def _rotation_vectors(rng: np.random.Generator, n: int = 60) -> np.ndarray:
    th = _angles(n, rng)
    u = rng.normal(size=(len(th), 3))
    u /= np.linalg.norm(u, axis=1)[:, None]
    u[:3] = [[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]]  # on the axes
    return u * th[:, None]


def _twists(rng: np.random.Generator) -> np.ndarray:
    w = _rotation_vectors(rng)
    v = rng.normal(size=w.shape) * 3.0
    v[::7] = 0.0
    return np.concatenate([w, v], axis=1)


def _same(a: np.ndarray, b: np.ndarray) -> None:
    """Equal bit for bit (zeros' signs included)."""
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape
    assert np.array_equal(a, b, equal_nan=True)
    assert np.array_equal(np.signbit(a), np.signbit(b))


FUNCTIONS = {
    "exp_so3": (lambda x: lie.exp_so3(x[..., :3]), "twist"),
    "hat3": (lambda x: _so3.hat3(x[..., :3]), "twist"),
    "cross": (lambda x: _so3.cross(x[..., :3], x[..., 3:]), "twist"),
    "exp": (lie.exp, "twist"),
    "log": (lie.log, "displacement"),
    "log_so3": (lambda g: lie.log_so3(g[..., :3, :3]), "displacement"),
    "quaternion": (
        lambda g: np.concatenate(
            [
                lie.quaternion_parts(g[..., :3, :3])[0][..., None],
                lie.quaternion_parts(g[..., :3, :3])[1],
            ],
            axis=-1,
        ),
        "displacement",
    ),
    "inverse": (lie.inverse, "displacement"),
    "pose": (lambda g: lie.pose(g[..., :3, :3], g[..., :3, 3]), "displacement"),
    "act_screw": (
        lambda g: lie.act_screw(g, np.array([0.3, -0.2, 0.9, 1.5, -2.0, 0.25])),
        "displacement",
    ),
}


def _inputs(kind: str, rng: np.random.Generator) -> np.ndarray:
    xi = _twists(rng)
    if kind == "twist":
        return xi
    g = _generic(lie.exp, xi)
    # exact half-turns and the identity, which the principal log treats apart
    g[0] = np.eye(4)
    g[1, :3, :3] = np.diag([1.0, -1.0, -1.0])
    g[2, :3, :3] = np.diag([-1.0, -1.0, 1.0])
    return g


@pytest.mark.parametrize("name", sorted(FUNCTIONS))
def test_float_fast_path_is_the_generic_code_bit_for_bit(name: str) -> None:
    f, kind = FUNCTIONS[name]
    x = _inputs(kind, np.random.default_rng(11))
    _same(f(x), _generic(f, x))


@pytest.mark.parametrize("name", sorted(FUNCTIONS))
def test_float_fast_path_row_by_row(name: str) -> None:
    """Each row of a batch gets the numbers it gets alone (and as a 0-d batch), and the
    fast path keeps the generic shapes for one element and for stacks of stacks."""
    f, kind = FUNCTIONS[name]
    x = _inputs(kind, np.random.default_rng(12))
    whole = f(x)
    for i in range(0, len(x), 5):
        _same(f(x[i]), whole[i])
        _same(f(x[i]), _generic(f, x[i]))
    k = len(x) // 2 * 2
    _same(
        f(x[:k].reshape((2, k // 2) + x.shape[1:])),
        whole[:k].reshape((2, k // 2) + whole.shape[1:]),
    )


def test_act_screw_broadcasts_as_the_generic_code() -> None:
    rng = np.random.default_rng(13)
    g = _generic(lie.exp, _twists(rng))[:, None]  # (N, 1, 4, 4)
    basis = rng.normal(size=(3, 6))
    _same(lie.act_screw(g, basis), _generic(lie.act_screw, g, basis))


def test_float_exp_and_log_against_independent_references() -> None:
    """exp against scipy's expm of the 4x4 hat; log as the inverse of mpmath's expm at
    50 digits (angles below pi, where log inverts exp)."""
    rng = np.random.default_rng(14)
    xi = _twists(rng)
    g = lie.exp(xi)
    for x, gx in zip(xi, g, strict=True):
        ref = scipy.linalg.expm(lie.hat(x))
        scale = max(1.0, np.abs(ref).max())
        assert np.abs(gx - ref).max() <= 5e-14 * scale * max(1.0, np.linalg.norm(x[:3]))
    inside = np.linalg.norm(xi[:, :3], axis=1) < math.pi - 1e-6
    with mpmath.workdps(50):
        for x in xi[inside][::3]:
            H = mpmath.matrix(lie.hat(x).tolist())
            E = mpmath.expm(H)
            g50 = np.array([[float(E[i, j]) for j in range(4)] for i in range(4)])
            back = lie.log(g50)
            assert np.abs(back - x).max() <= 1e-13 * max(1.0, np.abs(x).max())


def test_mp_and_exact_arrays_keep_the_generic_code() -> None:
    """Object arrays (mp, exact) never take the float path: their results stay objects
    and agree with float to float's rounding."""
    x = np.array([0.3, -0.2, 0.5, 1.0, 2.0, -0.5])
    with mpmath.workdps(30):
        xm = np.array([mpmath.mpf(float(c)) for c in x], dtype=object)
        gm = lie.exp(xm)
        assert gm.dtype == object
        assert np.abs(np.array(gm, dtype=float) - lie.exp(x)).max() < 1e-15 * 4
        back = lie.log(gm)
        assert back.dtype == object
        assert max(abs(back[i] - xm[i]) for i in range(6)) < mpmath.mpf(10) ** -25
