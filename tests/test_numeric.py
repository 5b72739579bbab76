"""The numeric leaf: precision modes, rank decisions with margins, scaling."""

from __future__ import annotations

import numpy as np
import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st

from mechsing import numeric
from mechsing.numeric import Precision, decide_definiteness, decide_rank, linalg, parse_precision


def test_parse_precision() -> None:
    assert parse_precision("float") == Precision("float")
    assert parse_precision("mp:50") == Precision("mp", 50)
    assert parse_precision("EXACT").mode == "exact"
    assert str(parse_precision("mp:30")) == "mp:30"
    for bad in ("mp:", "mp:3", "double", "mp:x"):
        with pytest.raises(ValueError, match="auto, float, mp:N"):
            parse_precision(bad)


def test_thresholds_follow_design() -> None:
    assert Precision("float").tolerances == numeric.Tolerances(1e-12, 1e-9)
    t = Precision("mp", 50).tolerances
    assert t.tau_lo == pytest.approx(1e-40) and t.tau_hi == pytest.approx(1e-25)
    assert Precision("exact").tolerances == numeric.Tolerances(0.0, 0.0)


def _with_singular_values(sig: list[float], seed: int = 0) -> np.ndarray:
    rng = np.random.default_rng(seed)
    U, _ = np.linalg.qr(rng.normal(size=(6, 6)))
    V, _ = np.linalg.qr(rng.normal(size=(5, 5)))
    S = np.zeros((6, 5))
    S[: len(sig), : len(sig)] = np.diag(sig)
    return U @ S @ V.T


def test_rank_decision_and_margin() -> None:
    d = decide_rank(_with_singular_values([2.0, 1.0, 0.5, 1e-3, 1e-15]), "float", 1.7)
    assert d.rank == 4
    # kept and dropped are singular values; the thresholds are relative to sigma_max
    assert d.margin.kept == pytest.approx(1e-3, rel=1e-9)
    assert d.margin.sigma_max == pytest.approx(2.0)
    assert d.margin.dropped < 1e-12 * d.margin.sigma_max
    assert d.margin.length_scale == 1.7
    assert d.sigma[0] == pytest.approx(2.0)


def test_rank_undecided_between_thresholds() -> None:
    d = decide_rank(_with_singular_values([1.0, 1.0, 1.0, 1.0, 1e-10]), "float")
    assert d.rank is None and not d.decided
    assert d.rank_bounds == (4, 5)
    # mp:50 decides the same matrix (its tau_lo is 1e-40 ... but 1e-10 is data: rank 5)
    m = decide_rank(_with_singular_values([1.0, 1.0, 1.0, 1.0, 1e-10]), "mp:50")
    assert m.rank == 5


def test_rank_full_and_zero() -> None:
    d = decide_rank(np.eye(3), "float")
    assert d.rank == 3 and d.margin.dropped is None and d.margin.kept == 1.0
    # a wide matrix of full row rank drops nothing either (examples/fourbar.yaml: "dropped": null)
    w = decide_rank(np.hstack([np.eye(3), np.ones((3, 1))]), "float")
    assert w.rank == 3 and w.margin.dropped is None
    z = decide_rank(np.zeros((3, 2)), "float", want_spaces=True)
    assert z.rank == 0 and z.null_space.shape == (2, 2)


def test_exact_rank_and_pivot_margin() -> None:
    M = np.array([[1, 2, 3], [2, 4, 6], [1, 0, sympy.Rational(1, 3)]], dtype=object)
    d = decide_rank(M, "exact", want_spaces=True)
    assert d.rank == 2 and d.sigma is None
    assert d.margin.tau_lo == 0 and d.margin.tau_hi == 0
    assert d.margin.kept > 0
    assert d.null_space.shape == (3, 1)
    ns = d.null_space[:, 0]
    assert np.allclose(np.array(M, dtype=float) @ ns, 0)


def test_mp_rank_thresholds() -> None:
    # at mp:50 a singular value of 1e-30 lies between tau_lo = 1e-40 and tau_hi = 1e-25
    P = Precision("mp", 50)
    with P.context():
        a = P.asarray([["1", "0"], ["0", "1e-30"]])
    d = decide_rank(a, P)
    assert d.rank is None  # 1e-30 lies between 1e-40 and 1e-25
    d60 = decide_rank(P.asarray([["1", "0"], ["0", "1e-45"]]), P)
    assert d60.rank == 1


def test_definiteness() -> None:
    assert decide_definiteness(np.diag([1.0, 2.0])).kind == "definite"
    assert decide_definiteness(np.diag([-1.0, -2.0])).kind == "definite"
    ind = decide_definiteness(np.array([[0.0, 1.0], [1.0, 0.0]]))
    assert ind.kind == "indefinite" and ind.eig_margin == pytest.approx(1.0)
    assert decide_definiteness(np.diag([1.0, 1e-10])).kind is None
    assert decide_definiteness(np.diag([1.0, 0.0])).kind == "semidefinite"
    ex = decide_definiteness(np.array([[1, 2], [2, 1]], dtype=object) * sympy.Integer(1), "exact")
    assert ex.kind == "indefinite" and ex.n_pos == 1 and ex.n_neg == 1


def test_characteristic_length() -> None:
    L, c = numeric.characteristic_length([[0, 0, 0], [1, 0, 0], [3, 2, 0], [4, 0, 0]])
    assert L == pytest.approx(np.sqrt(3.25))
    np.testing.assert_allclose(c, [2, 0.5, 0])
    L, c = numeric.characteristic_length([[2, 0, 0]])
    assert L == 2.0
    assert numeric.characteristic_length(np.zeros((0, 3)))[0] == 1.0
    assert numeric.characteristic_length([[1, 1, 1]], override=0.5)[0] == 0.5
    # points that coincide up to their coordinates' rounding (a spread of 1e-136 at 3.37 m
    # from the origin) have no spread: L is |c| (dividing by 1e-136 blew rounding up to
    # 1e119 in the commensurate rows), at every scale
    for k in (1e-6, 1.0, 1e6):
        pts = k * np.array([[0.0, 1e-136, 3.37], [0.0, -1e-136, 3.37], [1e-182, 0.0, 3.37]])
        assert numeric.characteristic_length(pts)[0] == pytest.approx(3.37 * k, rel=1e-15)
        # a small mechanism far from the origin keeps its own size
        pts = k * np.array([[1.0, 0.0, 0.0], [1.0 + 2e-6, 0.0, 0.0]])
        assert numeric.characteristic_length(pts)[0] == pytest.approx(1e-6 * k, rel=1e-9)


@pytest.mark.parametrize("k", [1e-6, 1.0, 1e6])
def test_scaling_makes_rank_unit_free(k: float) -> None:
    # four parallel revolute screws of a planar four-bar, lengths scaled by k
    pts = np.array([[0, 0, 0], [1, 0, 0], [3, 2, 0], [4, 0, 0]], float) * k
    u = np.array([0, 0, 1.0])
    S = np.array([np.concatenate([u, np.cross(p, u)]) for p in pts]).T
    L, c = numeric.characteristic_length(pts)
    Ss = numeric.scale_screws(S, L, c)
    d = decide_rank(Ss, "float", L)
    ref = decide_rank(
        numeric.scale_screws(S / np.array([[1], [1], [1], [k], [k], [k]]), L / k, c / k)
    )
    assert d.rank == 3 == ref.rank
    # the kept singular values agree; the dropped one is rounding noise in both
    np.testing.assert_allclose(d.sigma[:3], ref.sigma[:3], rtol=1e-10)
    assert d.margin.dropped < 1e-12 and ref.margin.dropped < 1e-12


def test_backends_convert_text_exactly() -> None:
    assert Precision("exact").asarray(["0.1"])[0] == sympy.Rational(1, 10)
    P = Precision("mp", 40)
    with P.context():
        x = P.asarray(["0.1"])[0]
        import mpmath

        assert abs(x - mpmath.mpf(1) / 10) < mpmath.mpf(10) ** -39
    assert numeric.backend_of(np.zeros(3)).name == "float"
    assert numeric.backend_of(Precision("exact").asarray([1, 2])).name == "exact"


def test_decide_nonzero_is_the_two_threshold_rule_on_one_value():
    """One relative value decided like a singular value: above tau_hi non-zero, below tau_lo
    zero, between undecided (float 1e-12 / 1e-9; mp:30 1e-20 / 1e-15); exact mode proves."""
    import sympy

    from mechsing.numeric import Precision, decide_nonzero

    f, mp = Precision("float"), Precision("mp", 30)
    assert [decide_nonzero(x, f) for x in (1e-13, -1e-10, 1e-8)] == [False, None, True]
    assert [decide_nonzero(x, mp) for x in (1e-21, 1e-16, -1e-14)] == [False, None, True]
    ex = Precision("exact")
    assert decide_nonzero(sympy.sqrt(2) * sympy.sqrt(3) - sympy.sqrt(6), ex) is False
    assert decide_nonzero(sympy.Rational(1, 10**40), ex) is True


def test_mechsing_starts_without_scipy_sparse_and_loads_it_for_a_big_mechanism() -> None:
    # scipy.sparse and matplotlib cost a fifth and a third of a second at every start:
    # only a big mechanism's sparse closure needs the one, only the review's figures the
    # other (checked in a fresh interpreter)
    import subprocess
    import sys

    code = (
        "import sys, mechsing.analysis, mechsing.cli, mechsing.cli.analyze\n"
        "from mechsing.numeric.blocks import issparse\n"
        "import numpy as np\n"
        "assert 'scipy.sparse' not in sys.modules, 'imported at start'\n"
        "assert 'matplotlib' not in sys.modules, 'the review loaded for the text'\n"
        "assert not issparse(np.eye(3))\n"
        "from scipy.sparse import csr_matrix\n"
        "assert issparse(csr_matrix(np.eye(3))) and not issparse(np.eye(3))\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


@settings(max_examples=200, deadline=None)
@given(
    st.lists(st.sampled_from([0.0, 1.0]), min_size=2, max_size=7).filter(any),
    st.integers(0, 2**32 - 1),
)
def test_first_nonzero_sign_is_not_decided_by_noise(pattern: list[float], seed: int) -> None:
    # DESIGN: directions have their first non-zero component positive.  A vector with
    # exact zeros and the same vector with 1e-15 noise of either sign in those zeros (a
    # direction (0, 0, -1) computed as (1e-17, -2e-17, -1)) are the same direction
    rng = np.random.default_rng(seed)
    v = (
        np.array(pattern)
        * rng.uniform(0.1, 2.0, len(pattern))
        * rng.choice([-1.0, 1.0], len(pattern))
    )
    noisy = v + np.where(v == 0, rng.uniform(-1e-15, 1e-15, len(v)), 0.0)
    first = v[np.flatnonzero(v)[0]]
    for x in (v, noisy, 1e-6 * noisy, 1e6 * noisy):  # relative to the vector's size
        assert linalg.first_nonzero_sign(x) == np.sign(first)
        u = linalg.first_nonzero_positive(x)
        assert u[np.flatnonzero(v)[0]] > 0
        assert np.array_equal(u, np.sign(first) * np.asarray(x) + 0.0)
    assert linalg.first_nonzero_sign(np.zeros(3)) == 1.0


@settings(max_examples=100, deadline=None)
@given(st.floats(0.0, 1.0), st.floats(1e-3, 1e3))
def test_rank_difference_margin_is_not_decided_by_a_rounding_level_drop(
    noise: float, scale: float
) -> None:
    # rank [TN; EN] - rank TN as at fourbar_changepoint.yaml's flat configuration: TN of
    # full rank (smallest kept 0.62), [TN; EN] dropping one singular value that is zero
    # up to rounding.  Whether float computes that value as 0 or as a few 1e-17 (at another
    # length scale, on another BLAS) must not change which decision the margin shows
    from mechsing.numeric import FLOAT_ROUNDING_FACTOR, Margin, RankDecision, rank_difference

    rounding = 2.5e-16 * scale
    full = Margin(0.62 * scale, None, 1e-12, 1e-9, 1.0, None, 1.0 * scale, rounding)
    seen = set()
    for dropped in (0.0, noise * FLOAT_ROUNDING_FACTOR * rounding):
        m = Margin(0.93 * scale, dropped, 1e-12, 1e-9, 1.0, None, 1.13 * scale, rounding)
        big = RankDecision(2, None, m, "float", (2, 2))
        small = RankDecision(2, None, full, "float", (2, 2))
        for a, b in ((big, small), (small, big)):
            d = rank_difference(a, b)
            assert d.rank == 0
            seen.add(d.margin.kept)
    assert seen == {0.62 * scale}
