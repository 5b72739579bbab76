"""High precision (mp:N) on every valid file: the right answer or a clear message, never a traceback.

Every expected answer is derived here from the mathematics, not read from the program:

1. Newton at N digits closes loops with every joint type that can sit in a loop (R, P, H, C, S,
   U, and G, Y, X, T2, T3, D): at mp:30 and mp:50 the closed configuration satisfies the loop
   equation (the product of the joints' exponentials around the loop is the identity, recomputed
   here with ``mpmath.expm`` at N + 20 digits from the bases written in DESIGN.md) to
   10^(5-N) L, and the residual reported in the JSON of ``mechsing solve`` / ``analyze`` is below
   that too.  The RSSR is also taken 1e-10 rad from its input (rocker dead-centre) singularity,
   where ``auto`` re-decides at mp:50 and must still close.
2. The high-precision SVD never fails: a matrix with repeated rows and a zero column (the
   constraint wrenches of a screw jack), whose singular values follow from its Gram matrix, and
   the screw jack itself (R ground-screw, H screw-nut of pitch 1 mm/rad, P nut-ground) in every
   mode: mobility 1, the nut slides by the pitch times the screw's turn.
3. A serial T3-S chain with the S joint turned by pi/2 about its middle axis (where Euler angles
   would lock) is regular at mp:50: its output screws have rank 6 at every pose.
"""

from __future__ import annotations

import json
from pathlib import Path

import mpmath
import numpy as np
import pytest

from mechsing.numeric import (
    decide_definiteness,
    decide_rank,
    eigh,
    parse_precision,
    spectral_norm,
    svd,
)
from tests.mechanisms import by_name, classes, run_cli, write

# ============================================================================ helpers


def _json(argv: list[str]) -> dict:
    rc, out, err = run_cli(argv)
    assert rc == 0, (argv, rc, err)
    return json.loads(out)


# ============================================================================ 2. robust SVD

#: the constraint wrenches of the screw jack, as stacked at mp:50 (9 x 6): every row has one
#: non-zero entry, so the columns are orthogonal and the Gram matrix is diag(2, 2, 1, 2, 2, 0)
JACK_WRENCHES = [
    [-1, 0, 0, 0, 0, 0],
    [0, 0, 0, 1, 0, 0],
    [0, 0, 0, 0, 1, 0],
    [0, 1, 0, 0, 0, 0],
    [0, 1, 0, 0, 0, 0],
    [0, 0, 1, 0, 0, 0],
    [0, 0, 0, 1, 0, 0],
    [0, 0, 0, 0, 1, 0],
    [1, 0, 0, 0, 0, 0],
]


def _max_abs(M: np.ndarray) -> mpmath.mpf:
    return max((abs(x) for x in np.asarray(M).flat), default=mpmath.mpf(0))


@pytest.mark.parametrize("digits", [20, 30, 50, 80])
@pytest.mark.parametrize("transpose", [False, True])
def test_mp_svd_of_repeated_rows_and_a_zero_column(digits: int, transpose: bool) -> None:
    """Singular values sqrt(2) (four times), 1 and 0, from A^T A = diag(2, 2, 1, 2, 2, 0); U and V
    orthogonal and U S V^T = A at the working precision; the spectral norm is sqrt(2), the rank 5,
    the Gram matrix's eigenvalues 0, 1, 2, 2, 2, 2 (positive semidefinite)."""
    prec = parse_precision(f"mp:{digits}")
    with prec.context():
        A = prec.asarray(JACK_WRENCHES)
        if transpose:
            A = A.T.copy()
        m, n = A.shape
        U, s, Vt = svd(A)
        tol = mpmath.mpf(10) ** (5 - digits)
        expected = [mpmath.sqrt(2)] * 4 + [mpmath.mpf(1), mpmath.mpf(0)]
        assert len(s) == 6
        assert max(abs(a - b) for a, b in zip(s, expected, strict=True)) <= tol
        assert _max_abs(U.T @ U - prec.backend.eye(m)) <= tol
        assert _max_abs(Vt @ Vt.T - prec.backend.eye(n)) <= tol
        S = prec.backend.zeros((m, n))
        for i in range(6):
            S[i, i] = s[i]
        assert _max_abs(U @ S @ Vt - A) <= tol
        assert abs(spectral_norm(A) - mpmath.sqrt(2)) <= tol
        w, Q = eigh(A.T @ A if not transpose else A @ A.T)
        assert max(abs(a - b) for a, b in zip(w, [0, 1, 2, 2, 2, 2], strict=True)) <= tol
    dec = decide_rank(A, prec, want_spaces=True, native_spaces=True)
    assert dec.rank == 5
    assert decide_definiteness(A.T @ A if not transpose else A @ A.T, prec).kind == "semidefinite"


def _gave_up(*args: object, **kwargs: object) -> None:
    raise RuntimeError("svd: no convergence to an eigenvalue after 150 iterations")


@pytest.mark.parametrize("shape", [(6, 6), (9, 6), (6, 9), (1, 4), (4, 1), (36, 30)])
@pytest.mark.parametrize("rank_deficit", [0, 2])
def test_svd_when_mpmath_gives_up(
    monkeypatch: pytest.MonkeyPatch, shape: tuple[int, int], rank_deficit: int
) -> None:
    """Where mpmath's iteration gives up, the SVD still holds: singular values are the square
    roots of the eigenvalues of the Gram matrix (computed here by mpmath's eigsy at 70 digits, an
    independent route), U and V are orthogonal, U S V^T = A, in full and thin form."""
    m, n = shape
    rng = np.random.default_rng(m * 100 + n + rank_deficit)
    r = max(0, min(m, n) - rank_deficit)
    with mpmath.workdps(50):
        A = mpmath.zeros(m, n)
        if r:  # a product of m x r and r x n integer matrices (over 7 and 5): rank r
            X = mpmath.matrix([[int(v) for v in rng.integers(-9, 10, r)] for _ in range(m)]) / 7
            Y = mpmath.matrix([[int(v) for v in rng.integers(-9, 10, n)] for _ in range(r)]) / 5
            A = X * Y
    with mpmath.workdps(70):
        G = A.T * A if m >= n else A * A.T
        ev = sorted(mpmath.eigsy(G, eigvals_only=True), reverse=True)
        # rank r: the other singular values are exactly 0
        expected = [mpmath.sqrt(e) for e in ev[:r]] + [mpmath.mpf(0)] * (min(m, n) - r)
    monkeypatch.setattr(mpmath, "svd_r", _gave_up)
    prec = parse_precision("mp:50")
    tol = mpmath.mpf(10) ** -45 * max(1, max(expected))
    with prec.context():
        Aa = np.array(A.tolist(), dtype=object)
        for full in (True, False):
            U, s, Vt = svd(Aa, full_matrices=full)
            k = min(m, n)
            assert U.shape == ((m, m) if full else (m, k)) and Vt.shape == (
                (n, n) if full else (k, n)
            )
            assert max(abs(a - b) for a, b in zip(s, expected, strict=True)) <= tol
            assert _max_abs(U.T @ U - prec.backend.eye(U.shape[1])) <= tol
            assert _max_abs(Vt @ Vt.T - prec.backend.eye(Vt.shape[0])) <= tol
            S = prec.backend.zeros((U.shape[1], Vt.shape[0]))
            for i in range(k):
                S[i, i] = s[i]
            assert _max_abs(U @ S @ Vt - Aa) <= tol
        assert abs(spectral_norm(Aa) - expected[0]) <= tol
    assert decide_rank(Aa, prec).rank == r


def test_eigh_when_mpmath_gives_up(monkeypatch: pytest.MonkeyPatch) -> None:
    """Where mpmath's QL iteration gives up, the Jacobi eigenvalue method gives the spectrum of a
    symmetric matrix built with known eigenvalues (Q diag(d) Q^T, Q a Householder reflection) and
    orthonormal eigenvectors, and the definiteness decision still stands."""
    d = [-2, 0, 0, 1, 1, 3]
    prec = parse_precision("mp:50")
    with prec.context():
        v = [mpmath.mpf(x) for x in (1, 2, -1, 3, 0, 1)]
        nv2 = mpmath.fsum(x * x for x in v)
        Q = np.array(
            [[(1 if i == j else 0) - 2 * v[i] * v[j] / nv2 for j in range(6)] for i in range(6)]
        )
        D = prec.backend.zeros((6, 6))
        for i, x in enumerate(d):
            D[i, i] = mpmath.mpf(x)
        M = Q @ D @ Q.T
        monkeypatch.setattr(mpmath, "eigsy", _gave_up)
        w, V = eigh(M)
        tol = mpmath.mpf(10) ** -45
        assert max(abs(a - b) for a, b in zip(w, d, strict=True)) <= tol
        assert _max_abs(V.T @ V - prec.backend.eye(6)) <= tol
        assert _max_abs(M @ V - V * w[None, :]) <= tol
    assert decide_definiteness(M, prec).kind == "indefinite"


#: a screw jack: the screw turns in the ground (R), the nut rides on it (H, pitch 1 mm per radian)
#: and slides in the ground without turning (P); the screw's turn is the input, the nut the output
SCREW_JACK = """mechanism: screw-jack
units: {length: mm}
bodies: [ground, screw, nut]
joints:
  - {name: R1, type: R, between: [ground, screw], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: H1, type: H, between: [screw, nut], axis: [0, 0, 1], point: [0, 0, 0], pitch: 1}
  - {name: P1, type: P, between: [nut, ground], axis: [0, 0, 1]}
inputs: [R1]
output: {body: nut}
configurations:
  reference: {}
  turned: {R1: 0.7}
  turned-back: {R1: "-3/2"}
"""
#: pitch of the jack (m per radian)
JACK_PITCH = 1e-3


@pytest.mark.parametrize("mode", ["float", "mp:30", "mp:50", "auto"])
def test_screw_jack_in_every_mode(tmp_path: Path, mode: str) -> None:
    """All three joints lie on one axis, so their screws (z, 0), (z, h z), (0, z) span the
    cylindrical subgroup C (dim 2): closure rank 2, one degree of freedom (3 - 2) everywhere,
    no singularity.  Turning the screw by theta with the nut kept from turning (H1 = -theta)
    moves the nut by h theta along the axis: P1 = h R1 (g_nut = exp(-P1 (0, z)) and
    exp(theta (z, 0)) exp(-theta (z, h z)) = exp(-h theta (0, z))), so the nut's slide rate is the
    pitch times the input rate."""
    path = write(tmp_path, "screw_jack", SCREW_JACK)
    res = _json(["analyze", str(path), "--precision", mode, "--format", "json"])
    assert set(by_name(res)) == {"reference", "turned", "turned-back"}
    for c in res["configurations"]:
        where = (mode, c["name"])
        assert "error" not in c, where
        assert (c["closure_rank"]["rank"], c["closure_rank"]["nullity"]) == (2, 1), where
        assert c["mobility"]["instantaneous"] == c["mobility"]["generic"] == 1, where
        assert c["mobility"]["finite"] == 1, where
        (lp,) = c["loops"]
        assert (lp["subgroup"]["type"], lp["subgroup"]["dim"]) == ("C", 2), where
        assert c["singular"] is False and classes(c) == [], where
        (r1,), (h1,), (p1,) = c["joints"]["R1"], c["joints"]["H1"], c["joints"]["P1"]
        assert h1 == pytest.approx(-r1, abs=1e-15), where
        assert p1 == pytest.approx(JACK_PITCH * r1, rel=1e-14, abs=1e-18), where
