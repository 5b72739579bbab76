"""A sweep of the output's pose on a 6-UPS platform: the closure split leg by leg, the
samples closed in two passes, the closure measured without its full SVD.

The answers come from outside the code under test: each leg's length from the moved
platform's attachment points (a distance), its U joint's angles from the leg's direction
(Rodrigues' formula written here), the platform's pose from the independent forward
kinematics of tests/reference (:class:`MechanismFile`), the Type II turns of the
octahedral platform at +-pi/2 (Fichter), and numpy's SVD of the same matrices for the
measures.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from mechsing.kinematics.batch_newton import _damped_step
from mechsing.sweeps import SweepRun, sweep
from tests.reference.files import MechanismFile

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
STEWART = EXAMPLES / "stewart_octahedral.yaml"
#: the platform's reference point: the centroid of its S joints' points (the file)
CENTRE = np.array([0.0, 0.0, 1.0])


def rodrigues(axis: np.ndarray, angle: float) -> np.ndarray:
    u = np.asarray(axis, dtype=float)
    u = u / np.linalg.norm(u)
    K = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * (K @ K)


def _geometry() -> tuple[MechanismFile, np.ndarray, np.ndarray, np.ndarray]:
    """The file read by the reference reader: base points, platform points, U axes."""
    f = MechanismFile(STEWART)
    base = np.array([f.joints[f.jidx[f"U{k}"]].prm["point"] for k in range(1, 7)], dtype=float)
    top = np.array([f.joints[f.jidx[f"S{k}"]].prm["point"] for k in range(1, 7)], dtype=float)
    axes = np.array([f.joints[f.jidx[f"U{k}"]].prm["axes"] for k in range(1, 7)], dtype=float)
    return f, base, top, axes


def _path(spec: str) -> tuple[SweepRun, np.ndarray]:
    """The sweep's closed configurations (joints, then the pose coordinates), every sample."""
    run = SweepRun(STEWART, [spec])
    rows = list(run.engine.rows([v.values for v in run.vars], None))
    assert len(rows) == 1 and rows[0].Z is not None
    return run, rows[0].Z


def test_a_dense_platform_turn_closes_every_leg_at_its_inverse_kinematics():
    """Each sample of a dense turn about the vertical through the platform's centre, closed
    by the legs' split Newton in two passes: the P joint is the leg's length at the pose
    minus its length at the reference, the U joint turns the leg onto its direction, and
    the reference forward kinematics puts the platform at the pose."""
    f, base, top, axes = _geometry()
    run, Z = _path("pose.rz=-1.2:1.2:0.0015")
    model = run.engine.model
    col = {j.name: model.joint(j.name).columns for j in model.mech.joints}
    assert not np.isnan(Z[:, 0]).any()
    rz = Z[:, model.n + 2]
    np.testing.assert_allclose(rz, run.vars[0].values, rtol=0, atol=1e-15)
    for z, angle in zip(Z[::37], rz[::37], strict=False):
        R = rodrigues([0, 0, 1], float(angle))
        moved = (R @ (top - CENTRE).T).T + CENTRE
        for k in range(6):
            leg = moved[k] - base[k]
            ref = top[k] - base[k]
            p = z[col[f"P{k + 1}"]][0]
            assert p == pytest.approx(np.linalg.norm(leg) - np.linalg.norm(ref), abs=1e-12)
            a, b = z[col[f"U{k + 1}"]]
            # U: exp(a e1) exp(b e2), both axes through the base point, at the reference
            turn = rodrigues(axes[k][0], a) @ rodrigues(axes[k][1], b)
            d = turn @ (ref / np.linalg.norm(ref))
            np.testing.assert_allclose(d, leg / np.linalg.norm(leg), rtol=0, atol=1e-12)
        g = f.poses(z[: model.n])["platform"]
        np.testing.assert_allclose(g[:3, :3], R, rtol=0, atol=1e-12)
        np.testing.assert_allclose(g[:3, :3] @ CENTRE + g[:3, 3], CENTRE, rtol=0, atol=1e-12)


def test_the_split_step_is_the_newton_step_of_the_whole_closure():
    """Leg by leg (six 6 x 6 solves) the step is the one of the whole 36-coordinate system
    (its damped normal equations: they agree to their own rounding, cond^2 eps)."""
    run, Z = _path("pose.rz=-1:1:0.05")
    pb = run.engine.problem
    bc = pb.batch
    cols = np.flatnonzero(~pb.given[: bc.nb])
    split = bc.split(cols)
    assert split is not None
    assert [len(c) for _, c, _ in split.legs] == [6] * 6
    rng = np.random.default_rng(7)
    Q = Z.copy()
    Q[:, : bc.nb] += 1e-3 * rng.standard_normal((len(Z), bc.nb))
    r = bc.residual_twists(bc.deltas(Q))
    whole = _damped_step(bc.jacobian(Q)[:, :, cols], r)
    legs = split.step(bc.screws(Q), r)
    assert np.max(np.abs(legs - whole)) <= 1e-9 * np.max(np.abs(whole))


@pytest.mark.parametrize(
    ("name", "spec"),
    [("planar_3rpr.yaml", "pose.x=0.9:1.1:0.05"), ("stewart_octahedral.yaml", "P1=0:0.01:0.005")],
)
def test_no_split_where_the_legs_are_not_square_or_the_pose_is_not_given(name, spec):
    """A planar platform's legs have three coordinates for six rows each; a sweep of a
    joint does not give the output's pose: both close the whole system."""
    run = SweepRun(EXAMPLES / name, [spec])
    pb = run.engine.problem
    assert pb.batch.split(np.flatnonzero(~pb.given[: pb.batch.nb])) is None


def test_a_dense_turn_locates_the_type_two_turns_to_rounding_with_one_newton_step_a_sample():
    """Fichter's rotation singularity at +-pi/2, on a turn dense enough for the samples to
    be closed between knots (one Newton step each), located to rounding."""
    r = sweep(STEWART, ["pose.rz=-1.8:1.8:0.0018"])
    got = sorted(p.values[0] for p in r.located if "output" in r.tests and "output" in p.tests)
    assert len(got) == 2
    assert abs(got[0] + math.pi / 2) <= 1e-14
    assert abs(got[1] - math.pi / 2) <= 1e-14
    assert all(p.classes and "output" in p.classes for p in r.located)
    # knots every fifth sample (SWEEP_KNOT_STEP / 0.0018): one Newton step for the four
    # samples between two knots, two or three for a knot (from the nodes' cubic, as every
    # sample took before the knots)
    assert r.newton_iterations / r.points() <= 1.5


def test_the_closure_measured_without_its_svd_is_the_svd_s():
    """The closure of full row rank (30 x 36) measured by a QR: its smallest relative
    singular value is numpy's SVD's, its kernel is orthonormal and annihilated, the input
    and output tests on that kernel are those on the SVD's kernel; and the screened sign
    test between any two samples has the sign of the product it stands for."""
    run, Z = _path("pose.rz=-1.7:1.7:0.02")
    meas = run.engine.measures
    Q = Z[:, : run.engine.model.n]
    pm = meas(Q)
    assert "closure" in pm.deferred and "closure" not in pm.bases
    C = pm.matrices["closure"]
    U, s, Vt = np.linalg.svd(C)
    g = meas.generic["closure"]
    assert g == C.shape[1] == 30
    np.testing.assert_allclose(pm.ratio["closure"], s[:, g - 1] / s[:, 0], rtol=1e-12)
    K = pm.kernel
    assert np.max(np.abs(C @ K)) <= 1e-13 * np.max(s[:, 0])
    np.testing.assert_allclose(
        np.swapaxes(K, 1, 2) @ K, np.broadcast_to(np.eye(6), (len(K), 6, 6)), atol=1e-14
    )
    N = np.swapaxes(Vt[:, g:, :], 1, 2)
    E = meas.E
    sE = np.linalg.svd(E @ N, compute_uv=False)
    np.testing.assert_allclose(pm.ratio["output"], sE[:, -1], rtol=1e-9, atol=1e-15)
    # neighbours (screened: the bound) and samples far apart (the product itself)
    n = len(Q)
    ia = np.concatenate([np.arange(n - 1), np.arange(0, n - 40, 7)])
    ib = np.concatenate([np.arange(1, n), np.arange(40, n, 7)])
    d = meas.compressed_pairs(pm, ia, ib)["closure"]
    u, v = U[ia][:, :, g - 1], Vt[ia][:, g - 1, :]
    direct = np.einsum("ni,nij,nj->n", u, C[ib], v)
    assert np.array_equal(np.sign(d), np.sign(direct))
    # the screened pairs' bound is below the product it stands for
    assert np.all(d <= direct + 1e-12 * s[ia, 0])


@pytest.mark.parametrize(
    ("file", "spec", "crossings"),
    [
        # the closure kernel from a QR (a basis continuous along the path)
        (STEWART, "pose.rz=-1.7:1.7:0.002", 2),
        # from an SVD (a basis of the plane of motions picked afresh at each sample)
        (EXAMPLES / "five_bar.yaml", "A1=-1.2:1.2:0.002", None),
    ],
)
def test_the_input_and_output_sign_tests_screened_by_the_kernel_step_keep_their_sign(
    file, spec, crossings
):
    """The input and output tests read the closure kernel's basis: between two samples their
    sign test is ``u^T X N_b R v`` (R turning b's basis to a's).  Where the kernel moved
    less than sigma_g (with the roundings) the bound stands for the product: its sign is
    the product's, it is below the product, and the pairs it does not clear (every sign
    change) are the product itself, bit for bit.  Checked against the product computed at
    every pair with the turn written out here (the orthogonal Procrustes factor): on the
    hexapod's turn through both Type II poses, and along a five-bar's input."""
    run = SweepRun(file, [spec])
    rows = list(run.engine.rows([v.values for v in run.vars], None))
    Z = rows[0].Z[rows[0].reached]
    meas = run.engine.measures
    Q = Z[:, : run.engine.model.n]
    pm = meas(Q)
    assert pm.kernel is not None
    n = len(Q)
    ia = np.concatenate([np.arange(n - 1), np.arange(0, n - 40, 7)])
    ib = np.concatenate([np.arange(1, n), np.arange(40, n, 7)])
    got = meas.compressed_pairs(pm, ia, ib)
    Na, Nb = pm.kernel[ia], pm.kernel[ib]
    u, _, vt = np.linalg.svd(np.swapaxes(Nb, 1, 2) @ Na)
    turn = u @ vt
    # the turn is the nearest: N_b R is closer to N_a than N_b is
    near = np.linalg.norm(Nb @ turn - Na, axis=(1, 2))
    assert np.all(near <= np.linalg.norm(Nb - Na, axis=(1, 2)) + 1e-14)
    screened = {}
    for t in ("input", "output"):
        U, V = pm.basis(t, ia)  # the leading singular vectors, kept or computed now
        M = pm.matrices[t]
        direct = np.einsum("ni,nij,nj->n", U[:, :, -1], M[ib] @ turn, V[:, :, -1])
        d = got[t]
        assert np.array_equal(np.sign(d), np.sign(direct)), t
        assert np.all(d <= direct + 1e-14), t
        exact = d == direct
        screened[t] = int(np.sum(~exact))
        # every sign change is the product itself
        assert np.all(exact[direct < 0]), t
    if crossings is not None:  # both Type II turns cross the output test's zero
        assert np.sum(got["output"][: n - 1] < 0) == crossings
    # most neighbours are screened
    assert min(screened.values()) >= 0.9 * (n - 1)


def test_the_closure_singular_values_from_the_gram_matrix_where_it_is_far_from_singular():
    """The closure's triangular factor's singular values, from R^T R's eigenvalues where the
    smallest relative one is at least SWEEP_GRAM_RATIO, numpy's SVD elsewhere: on matrices
    built with known singular values (random orthogonal factors), the first within their
    bound (30 eps / (2 rho^2) relative, rho the smallest relative one), the others the
    SVD's exactly."""
    from mechsing.sweeps.factors import singular_values as _singular_values
    from mechsing.sweeps.settings import SWEEP_GRAM_RATIO

    rng = np.random.default_rng(7)
    k = 30
    smallest = [1.0, 0.5, 0.2, 1.2 * SWEEP_GRAM_RATIO, 0.8 * SWEEP_GRAM_RATIO, 1e-3, 1e-9]
    want, mats = [], []
    for lo in smallest:
        s = np.sort(np.concatenate([[1.0, lo], rng.uniform(lo, 1.0, k - 2)]))[::-1] * 3.7
        U, _ = np.linalg.qr(rng.standard_normal((k, k)))
        V, _ = np.linalg.qr(rng.standard_normal((k, k)))
        want.append(s)
        mats.append(np.linalg.qr(U @ np.diag(s) @ V.T, mode="r"))  # a triangular factor
    R = np.array(mats)
    got = _singular_values(R)
    svd = np.linalg.svd(R, compute_uv=False)
    for lo, g, w, sv in zip(smallest, got, want, svd, strict=True):
        if lo >= SWEEP_GRAM_RATIO:
            bound = 30 * np.finfo(float).eps / (2 * lo**2)
            np.testing.assert_allclose(g, w, rtol=bound, atol=0)
            np.testing.assert_allclose(g[-1] / g[0], sv[-1] / sv[0], rtol=bound, atol=0)
        else:
            assert np.array_equal(g, sv)
            # the SVD's rounding: a few eps sigma_1 on every singular value
            np.testing.assert_allclose(g, w, rtol=0, atol=1e-14 * w[0])


def _with_singular_values(rng: np.random.Generator, n: int, s: np.ndarray) -> np.ndarray:
    """An n x len(s) matrix with the singular values s (random orthonormal factors)."""
    U, _ = np.linalg.qr(rng.standard_normal((n, n)))
    V, _ = np.linalg.qr(rng.standard_normal((len(s), len(s))))
    return U[:, : len(s)] @ np.diag(s) @ V.T


def test_the_closure_kernel_from_the_householder_vectors_is_the_complete_q_s_last_columns():
    """The closure kernel formed from a QR's Householder vectors alone (:func:`_complement`,
    the reflectors in blocks, chunk by chunk) is the complete orthogonal factor's last
    columns that numpy forms (LAPACK's dorgqr), to rounding, and it is orthonormal and
    orthogonal to the column space by numpy's SVD of the same matrices: on random matrices,
    on matrices nearly or exactly losing rank (smallest singular values 1e-9, 1e-15, 0), on
    columns already triangular (reflectors that are the identity, tau = 0), with a number
    of reflectors that is not a multiple of the block, more configurations than a chunk,
    one reflector, and no complement at all."""
    from mechsing.numeric.linalg import KERNEL_BLOCK as _KERNEL_BLOCK
    from mechsing.numeric.linalg import KERNEL_CHUNK as _KERNEL_CHUNK
    from mechsing.numeric.linalg import complement as _complement

    rng = np.random.default_rng(11)
    eps = np.finfo(float).eps
    cases = []
    for n, k in ((36, 30), (6, 5), (13, 2 * _KERNEL_BLOCK + 1), (7, 1), (5, 5)):
        mats = [rng.standard_normal((n, k)) * 10.0 ** rng.uniform(-3, 3)]
        for lo in (1e-9, 1e-15, 0.0):
            s = np.sort(np.concatenate([[1.0, lo], rng.uniform(lo, 1.0, max(k - 2, 0))]))[::-1]
            mats.append(_with_singular_values(rng, n, s[:k]) * 3.1)
        upper = np.zeros((n, k))  # already triangular: every tau is 0
        upper[np.triu_indices(n, 0, k)] = rng.standard_normal(len(np.triu_indices(n, 0, k)[0]))
        mats.append(upper)
        cases.append(np.array(mats))
    many = rng.standard_normal((_KERNEL_CHUNK + 37, 36, 30))
    cases.append(many)
    for A in cases:
        N, n, k = A.shape
        h, tau = np.linalg.qr(A, mode="raw")
        K = _complement(h, tau)
        assert K.shape == (N, n, n - k)
        full = np.linalg.qr(A, mode="complete")[0][:, :, k:]
        np.testing.assert_allclose(K, full, rtol=0, atol=50 * eps)
        np.testing.assert_allclose(
            np.swapaxes(K, 1, 2) @ K,
            np.broadcast_to(np.eye(n - k), (N, n - k, n - k)),
            rtol=0,
            atol=50 * eps,
        )
        # orthogonal to the column space: to A itself (relative to its norm), and to the
        # left singular vectors of A's nonzero singular values
        U, s, _ = np.linalg.svd(A, full_matrices=True)
        AK = np.swapaxes(A, 1, 2) @ K
        assert np.all(np.abs(AK) <= 100 * eps * s[:, :1, None])
        for i in range(N):
            kept = s[i] > 1e-6 * s[i, 0]  # directions the matrix clearly has
            assert np.all(np.abs(U[i][:, : len(s[i])][:, kept].T @ K[i]) <= 1e-9)


def test_the_largest_singular_value_from_the_smaller_gram_matrix():
    """The output rows' norm (:func:`_largest_singular_value`, the largest eigenvalue of
    the smaller Gram matrix) is the largest singular value the matrices were built with,
    within a few eps times their smaller side, and numpy's SVD's, whichever side is
    smaller, for matrices of any rank (0 for the zero matrix)."""
    from mechsing.sweeps.factors import largest_singular_value as _largest_singular_value

    rng = np.random.default_rng(5)
    eps = np.finfo(float).eps
    for r, c in ((6, 36), (3, 36), (36, 6), (6, 6)):
        k = min(r, c)
        want, mats = [], []
        for lo in (1.0, 0.3, 1e-8, 0.0):
            s = np.sort(np.concatenate([[1.0, lo], rng.uniform(lo, 1.0, k - 2)]))[::-1]
            s = s * 10.0 ** rng.uniform(-4, 4)
            A = _with_singular_values(rng, max(r, c), s)
            mats.append(A if r >= c else A.T)
            want.append(s[0])
        mats.append(np.zeros((r, c)))
        want.append(0.0)
        got = _largest_singular_value(np.array(mats))
        np.testing.assert_allclose(got, want, rtol=4 * k * eps, atol=0)
        svd = np.linalg.svd(np.array(mats), compute_uv=False)[:, 0]
        np.testing.assert_allclose(got, svd, rtol=4 * k * eps, atol=0)


def test_the_closure_matrices_not_kept_are_computed_again_the_same():
    """A closure of full row rank is measured without keeping its matrices (nor the bordered
    tests' rows): read at any rows, they are the numbers the measures computed (bit for
    bit), also after batches are gathered (by slices or index arrays) and after a batch
    travelled to another process (pickled); the neighbours' screen, from the norms the
    measures kept, gives what it gives from the matrices themselves."""
    import pickle

    from mechsing.sweeps.measures import PointMeasures

    run, Z = _path("pose.rz=-1.6:1.6:0.004")
    meas = run.engine.measures
    Q = Z[:, : run.engine.model.n]
    parts = [meas(Q[:300]), meas(Q[300:])]
    pm = PointMeasures.gather([(p, slice(None)) for p in parts])
    assert "closure" in pm.deferred and not isinstance(pm.matrices["closure"], np.ndarray)
    whole, _ = meas.matrices(Q)
    idx = np.array([0, 5, 299, 300, 301, len(Q) - 1])
    for t in ("closure", "input_rows"):
        assert np.array_equal(pm.matrices[t][idx], whole[t][idx])
        again = pickle.loads(pickle.dumps(pm))
        assert np.array_equal(again.matrices[t][idx], whole[t][idx])
        # a gather of a pickled batch (whole) and of a computed one
        mixed = PointMeasures.gather([(again, slice(0, 10)), (pm, np.array([400, 401, 7]))])
        want = np.concatenate([whole[t][:10], whole[t][[400, 401, 7]]])
        assert np.array_equal(mixed.matrices[t][:], want)
    # the screen from the kept norms and from the matrices themselves
    kept = PointMeasures(
        pm.rank,
        pm.ratio,
        pm.bases,
        pm.kernel,
        {t: whole[t] for t in pm.matrices},
        pm.deferred,
        pm.top,
    )
    ia = np.arange(len(Q) - 1)
    ib = ia + 1
    a = meas.compressed_pairs(pm, ia, ib)
    b = meas.compressed_pairs(kept, ia, ib)
    for t in a:
        assert np.array_equal(a[t], b[t]), t
    # every Weyl bound screened positive, and the closure never crosses zero on this turn
    assert np.all(a["closure"] > 0)
    # the norms gathered by an index array: kept where the next point follows, and the
    # screen of those points' pairs is the one of the whole batch
    pick = np.array([3, 4, 5, 9, 10, 298, 299, 300, 301, 600])
    sub = PointMeasures.gather([(pm, pick)])
    size, ahead = sub.steps["closure"]
    assert np.array_equal(size, pm.steps["closure"][0][pick])
    follows = np.append(pick[1:] == pick[:-1] + 1, False)
    assert np.array_equal(np.isnan(ahead), ~follows | (pick == 299))
    ja = np.arange(len(pick) - 1)
    c = meas.compressed_pairs(sub, ja, ja + 1)
    d = meas.compressed_pairs(kept, pick[:-1], pick[1:])
    for t in c:
        assert np.array_equal(c[t], d[t]), t
    # its singular values: numpy's SVD of the same matrices
    s = np.linalg.svd(whole["closure"], compute_uv=False)
    assert np.allclose(pm.ratio["closure"], s[:, -1] / s[:, 0], rtol=1e-12, atol=0)
