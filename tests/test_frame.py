"""The commensurate frame (mechsing.numeric.CommensurateFrame): its forward and inverse maps
are inverse to each other, a wrench's pairing with a twist survives the way back to SI, and
scaling and moving a mechanism changes no commensurate quantity."""

from __future__ import annotations

import numpy as np
import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st

from mechsing.kinematics import KinematicModel
from mechsing.model import loads
from mechsing.numeric import EXACT, CommensurateFrame, parse_precision
from tests.mechanisms import EXAMPLES, scaled_text
from tests.strategies import frame_data


def frames() -> st.SearchStrategy[CommensurateFrame]:
    return frame_data().map(lambda data: CommensurateFrame.of(*data))


def _matrix(rng: np.random.Generator, L: float, rows: int, cols: int) -> np.ndarray:
    """Random SI screws: angular parts of order 1, linear parts of order L."""
    M = rng.normal(size=(rows, cols))
    for b in range(rows // 6):
        M[6 * b + 3 : 6 * b + 6] *= L
    return M


def _rotation(rng: np.random.Generator) -> np.ndarray:
    Q, R = np.linalg.qr(rng.normal(size=(3, 3)))
    Q = Q * np.sign(np.diag(R))
    return Q if np.linalg.det(Q) > 0 else -Q


@settings(max_examples=60, deadline=None)
@given(frames(), st.integers(0, 2**32 - 1))
def test_forward_then_inverse_is_the_identity(fr: CommensurateFrame, seed: int) -> None:
    rng = np.random.default_rng(seed)
    L, lc = fr.L, fr.length_columns
    tol = 1e-12
    # twists (no column factor)
    t = _matrix(rng, L, 6, 1)[:, 0]
    back = fr.twist_back(fr.twists(t[:, None])[:, 0])
    assert np.allclose(back, t, rtol=tol, atol=tol * max(1.0, np.abs(t).max()))
    # joint screws: each commensurate column back to SI, its length factor removed
    S = _matrix(rng, L, 6, 5)
    Ss = fr.screws(S)
    for j in range(5):
        col = fr.twist_back(Ss[:, j]) / (L if lc[j] else 1.0)
        assert np.allclose(col, S[:, j], rtol=tol, atol=tol * np.abs(S[:, j]).max())
    # stacked blocks: each block is the screws map of its rows
    M = _matrix(rng, L, 18, 5)
    Ms = fr.blocks(M)
    for b in range(3):
        assert np.array_equal(Ms[6 * b : 6 * b + 6], fr.screws(M[6 * b : 6 * b + 6]))
    assert np.array_equal(fr.blocks(M, columns=False)[6:12], fr.twists(M[6:12]))
    r = M[:, 0]
    assert np.array_equal(fr.stacked(r), fr.blocks(r[:, None], columns=False)[:, 0])
    # basis rows are twists
    assert np.array_equal(fr.rows(S.T), fr.twists(S).T)
    # rates both ways, also on a subset of columns
    d = rng.normal(size=5) * np.where(lc, L, 1.0)
    assert np.allclose(fr.rates_back(fr.rates(d)), d, rtol=tol, atol=0)
    assert np.array_equal(
        fr.rates_back(fr.rates(d)[[1, 3]], [1, 3]), fr.rates_back(fr.rates(d))[[1, 3]]
    )
    # points
    x = rng.normal(size=3) * L
    assert np.allclose(fr.point_back(fr.point(x)), x, rtol=tol, atol=tol * L * 10)


@settings(max_examples=60, deadline=None)
@given(frames(), st.integers(0, 2**32 - 1))
def test_pairing_of_wrench_and_twist_survives_the_way_back(
    fr: CommensurateFrame, seed: int
) -> None:
    """wrench_back(y) = (f, m) with f . v + m . omega = y . twists(t) for every SI twist t (the
    factor is 1: the commensurate pairing is the SI virtual power)."""
    rng = np.random.default_rng(seed)
    y = rng.normal(size=6)
    t = _matrix(rng, fr.L, 6, 1)[:, 0]
    f, m = np.split(fr.wrench_back(y), 2)
    si = f @ t[3:] + m @ t[:3]
    comm = y @ fr.twists(t[:, None])[:, 0]
    assert si == pytest.approx(
        comm, rel=1e-9, abs=1e-9 * (np.abs(y).max() * np.abs(fr.twists(t[:, None])).max())
    )


@settings(max_examples=60, deadline=None)
@given(frames(), st.sampled_from([1e-6, 1e-3, 7.0, 1e6]), st.integers(0, 2**32 - 1))
def test_scaling_and_moving_changes_no_commensurate_quantity(
    fr: CommensurateFrame, k: float, seed: int
) -> None:
    """The mechanism scaled by k and moved by a rigid motion (R, p): the frame is (kL, R k c + p);
    the SI screws are Ad of the motion of the scaled screws; their commensurate screws are the
    unscaled ones rotated by R (equal Gram matrices, equal singular values), and the joint
    rates and the wrenches' pairing are unchanged."""
    rng = np.random.default_rng(seed)
    R, p = _rotation(rng), rng.normal(size=3) * fr.L * k
    moved = CommensurateFrame.of(k * fr.L, R @ (k * fr.c) + p, fr.length_columns)
    S = _matrix(rng, fr.L, 6, 5)
    S[:3, fr.length_columns] = 0.0  # a length coordinate moves along a pure translation
    S[3:, fr.length_columns] /= fr.L
    # scaled: linear parts times k; a translation's screw (0, u) is a direction, unchanged
    Sk = S.copy()
    Sk[3:, ~fr.length_columns] *= k
    # moved by (R, p): Ad = [[R, 0], [hat(p) R, R]]
    W, V = R @ Sk[:3], R @ Sk[3:]
    S1 = np.concatenate([W, V + np.cross(p, W.T).T])
    A0, A1 = fr.screws(S), moved.screws(S1)
    Rb = np.kron(np.eye(2), R)
    assert np.allclose(A1, Rb @ A0, rtol=1e-9, atol=1e-9 * np.abs(A0).max())
    assert np.allclose(
        np.linalg.svd(A1, compute_uv=False),
        np.linalg.svd(A0, compute_uv=False),
        rtol=1e-9,
        atol=1e-9,
    )
    # rates: a commensurate rate is the same number in both mechanisms
    x = rng.normal(size=5)
    xs0, xs1 = fr.rates_back(x), moved.rates_back(x)
    assert np.allclose(xs1, np.where(fr.length_columns, k * xs0, xs0), rtol=1e-12)


@pytest.mark.parametrize("precision", ["float", "mp:30", "exact"])
def test_model_frame_is_the_files_scale_and_is_scale_free(precision: str) -> None:
    """A model builds its frame once (its numbers are the model's); the example scaled by
    10^3 has the same commensurate screws at the reference configuration."""
    path = EXAMPLES / "slider_crank_slider_input.yaml"
    m0 = KinematicModel(loads(path.read_text()), precision)
    m1 = KinematicModel(loads(scaled_text(path, "*1000")), precision)
    assert m0.frame.length_columns is m0.length_columns
    assert m0.float_frame.L == m0.length_scale == m0.frame.L_float
    if precision == "exact":
        assert isinstance(m0.frame.L, sympy.Rational)
        assert m0.backend is EXACT
    with parse_precision(precision).context():
        q0, q1 = m0.zeros(), m1.zeros()
        A0 = m0.frame.screws(m0.current_screws(q0))
        A1 = m1.frame.screws(m1.current_screws(q1))
    assert m1.length_scale == pytest.approx(1000 * m0.length_scale, rel=1e-12)
    assert np.allclose(
        np.asarray(A1, dtype=float), np.asarray(A0, dtype=float), rtol=1e-12, atol=1e-12
    )
