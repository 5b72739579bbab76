"""Exact mode's output motion and test spaces in the number field of the data (issue 17).

Exact mode decides the output twist space ``T K`` exactly: K the closure matrix's exact
kernel, the product in the number field, its rank by an exact echelon form, the span's
exact twists identified by a Lie closure of exact echelon forms; the closure-expansion
tests (at mp:50) take their kernel and left kernel from the exact kernel by QR instead of
an SVD.  What is checked, and where the expected answers come from:

* the linear algebra: :func:`field_product` against sympy's matrix product,
  :func:`field_float` against sympy's 50-digit evaluation (a value that cancels to 1e-40
  included), the degree bound of quadratic radicals against the degree of the field
  sympy's primitive element generates;
* :func:`decide_from_exact` on a matrix built with a known kernel and left kernel (a
  random mixing of rows of a matrix of known rank): the spaces it gives annihilate the
  matrix to 50 digits, are orthonormal, and span what they must; a matrix that is not
  the one of the exact decision is refused;
* the output motion of bundled examples against their published facts (the headers):
  Sarrus's top translates along the vertical (P, direction z exactly), Tsai's 3-UPU at its
  flat constraint singularity gains the rotation about the vertical (X, axis z exactly),
  the 3-RPR moves in its plane (G, normal z), the UR5 at its wrist, elbow and shoulder
  singularities has five twists that generate D and at its regular pose all of D, the
  five-bar's output point at an input singularity moves along one line only;
* the same verdicts (dimension, type, subgroup or not, generated subgroup, point
  dimension) as the mp:50 path on every configuration of these examples.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
import sympy

import mechsing
from mechsing.numeric import Precision, decide_from_exact, decide_rank
from mechsing.numeric.field import (
    _degree_bound,
    field_float,
    field_product,
    number_field,
)
from tests.mechanisms import EXAMPLES

S2, S3, S5 = sympy.sqrt(2), sympy.sqrt(3), sympy.sqrt(5)


# ============================================================================ field algebra


def test_field_product_is_the_matrix_product() -> None:
    A = np.array([[1 + S2, S3, 0], [sympy.Rational(2, 7), -S2 * S3, 5]], dtype=object)
    B = np.array([[S2, 1], [1 - S3, sympy.Rational(1, 3)], [S5, 0]], dtype=object)
    got = field_product(A, B)
    want = sympy.Matrix(A.tolist()) * sympy.Matrix(B.tolist())
    assert got.shape == (2, 2)
    for i in range(2):
        for j in range(2):
            assert sympy.simplify(got[i, j] - want[i, j]) == 0


@pytest.mark.parametrize("radical", [S2 * S3 + S5, sympy.Rational(1, 3)])
def test_field_product_sums_before_reducing(radical) -> None:
    """Products summed before one reduction (and zero factors skipped) give sympy's
    matrix product: a zero row, a zero column, sums that cancel to zero and to a
    rational, in a degree-8 field and in QQ."""
    r = radical
    A = np.array(
        [[0, 0, 0], [r, r, 1], [r**2, 2, r], [sympy.Rational(-5, 7), r**3, 0]], dtype=object
    )
    B = np.array([[1, 0, r], [-1, 0, -r], [0, 0, 3]], dtype=object)
    got = field_product(A, B)
    want = sympy.Matrix(A.tolist()) * sympy.Matrix(B.tolist())
    assert got.shape == (4, 3)
    for i in range(4):
        for j in range(3):
            assert sympy.expand(got[i, j] - want[i, j]) == 0
    assert all(x == 0 for x in got[0]) and all(x == 0 for x in got[:, 1])
    # r - r and r^2 - r^2 + 3: sums that cancel, to zero and to a rational
    assert got[1, 0] == 0
    assert got[1, 2] == 3


def test_field_float_is_the_value_to_the_last_digit() -> None:
    vals = [
        S2 + S3 / 7,
        1 - S2 * S3,
        (S5 - S2) ** 3,
        sympy.Rational(-22, 7),
        # cancels to 1e-40: the adaptive evaluation serves
        S2 * S3 * S5 - sympy.sqrt(30) + sympy.Rational(1, 10**40),
    ]
    K, els = number_field(vals)
    for v, e in zip(vals, els, strict=True):
        assert field_float(K, e) == pytest.approx(float(sympy.N(v, 50)), rel=1e-15, abs=0)


@pytest.mark.parametrize(
    ("radicands", "degree"),
    [((3, 11, 33), 4), ((57, 209, 19, 3, 11, 33), 8), ((2, 3, 5), 8), ((2, 8), 2), ((12, 3), 2)],
)
def test_quadratic_radicals_count_by_the_degree_they_generate(radicands, degree) -> None:
    gens = {sympy.Pow(k, sympy.S.Half, evaluate=False) for k in radicands}
    assert _degree_bound(gens) == degree
    K, _ = number_field([sympy.sqrt(k) for k in radicands])
    assert (1 if K.is_QQ else K.mod.degree()) == degree


def test_dependent_square_roots_are_products_of_independent_ones() -> None:
    # ten square roots of five independent classes: QQ(sqrt 2, sqrt 3, sqrt 5, sqrt 7,
    # sqrt 11) of degree 32, each root (sqrt 6 = sqrt 2 sqrt 3, sqrt 21 = sqrt 3 sqrt 7 ...)
    # its element there; a sum with a product of two roots as well
    ks = (2, 3, 5, 7, 11, 6, 10, 14, 15, 21)
    vals = [sympy.sqrt(k) for k in ks] + [sympy.sqrt(6) * sympy.sqrt(21) - sympy.sqrt(14) / 3]
    K, els = number_field(vals)
    assert K.mod.degree() == 32
    for v, e in zip(vals, els, strict=True):
        assert field_float(K, e) == pytest.approx(float(sympy.N(v, 30)), rel=1e-15)
    # sqrt 6 sqrt 21 = 3 sqrt 14: zero in K
    (zero,) = number_field([sympy.sqrt(6) * sympy.sqrt(21) - 3 * sympy.sqrt(14)])[1]
    assert zero == 0


def test_other_radicals_keep_the_product_bound() -> None:
    assert _degree_bound({sympy.sqrt(2), sympy.cbrt(2)}) == 6
    assert _degree_bound({sympy.sqrt(1 + sympy.sqrt(2))}) == 4


# ============================================================================ decide_from_exact


def _mixed(seed: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A 5 x 7 exact matrix C of rank 3 (rows 4, 5 combinations of rows 1-3) with its
    exact kernel basis, and M = G C for a random invertible 5 x 5 G (float entries)."""
    rng = np.random.default_rng(seed)
    top = [
        [sympy.Rational(int(rng.integers(-9, 10)), int(rng.integers(1, 5))) for _ in range(7)]
        for _ in range(3)
    ]
    rows = top + [
        [a + 2 * b for a, b in zip(top[0], top[1], strict=True)],
        [a - b for a, b in zip(top[1], top[2], strict=True)],
    ]
    C = np.array(rows, dtype=object)
    G = rng.normal(size=(5, 5))
    M = (G @ np.array(C, dtype=float)).astype(object)
    return C, M, G


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_decide_from_exact_gives_the_spaces_of_the_matrix(seed: int) -> None:
    C, M, G = _mixed(seed)
    exact = decide_rank(C, "exact", 1.0, want_spaces=True)
    assert exact.rank == 3 and exact.exact_null_space.shape == (7, 4)
    prec = Precision("mp", 50)
    with prec.context():
        # M's entries to 50 digits: G (float) times C (exact rationals)
        Mmp = np.array(
            [
                [
                    mpmath.fsum(
                        mpmath.mpf(G[i, k]) * mpmath.mpf(sympy.N(C[k, j], 60)) for k in range(5)
                    )
                    for j in range(7)
                ]
                for i in range(5)
            ],
            dtype=object,
        )
        dec = decide_from_exact(Mmp, prec, exact)
        assert dec is not None and dec.rank == 3 and dec.precision == "exact"
        N, R, P = (
            mpmath.matrix(x.tolist())
            for x in (dec.null_space, dec.range_space, dec.left_null_space)
        )
        A = mpmath.matrix(Mmp.tolist())
        assert (N.cols, R.cols, P.cols) == (4, 3, 2)
        tiny = mpmath.mpf(10) ** -45 * mpmath.mnorm(A, "F")
        assert mpmath.mnorm(A * N, "F") < tiny
        assert mpmath.mnorm(P.T * A, "F") < tiny
        for Q in (N, R, P):
            assert mpmath.mnorm(Q.T * Q - mpmath.eye(Q.cols), "F") < mpmath.mpf(10) ** -45
        # the range is orthogonal to the left kernel and, with it, fills R^5
        assert mpmath.mnorm(R.T * P, "F") < mpmath.mpf(10) ** -45


def test_decide_from_exact_refuses_another_matrix() -> None:
    C, _M, _G = _mixed(0)
    exact = decide_rank(C, "exact", 1.0, want_spaces=True)
    other = np.random.default_rng(5).normal(size=(5, 7)).astype(object)
    assert decide_from_exact(other, Precision("mp", 50), exact) is None
    assert decide_from_exact(other, Precision("float"), exact) is None


# ============================================================================ output motion


def _motions(name: str, precision: str) -> dict:
    res = mechsing.analyze(str(EXAMPLES / f"{name}.yaml"), precision=precision)
    return {c.name: c.output_motion for c in res.configurations if c.error is None}


def test_sarrus_top_translates_vertically_exactly() -> None:
    m = _motions("sarrus", "exact")
    for name in ("reference", "raised"):
        assert (m[name].type, m[name].dim, m[name].precision) == ("P", 1, "exact")
        d = [sympy.sympify(x) for x in m[name].subgroup.params["axis"]]
        assert d[0] == 0 and d[1] == 0 and abs(d[2]) == 1
    assert m["stretched"].dim == 0


def test_tsai_flat_gains_the_rotation_about_the_vertical_exactly() -> None:
    m = _motions("tsai_3upu", "exact")
    assert (m["reference"].type, m["reference"].dim) == ("T3", 3)
    flat = m["flat"]
    assert (flat.type, flat.dim, flat.precision) == ("X", 4, "exact")
    assert [sympy.sympify(x) for x in flat.subgroup.params["axis"]] in ([0, 0, 1], [0, 0, -1])


def test_ur5_output_twists_exactly() -> None:
    m = _motions("ur5", "exact")
    assert (m["regular"].type, m["regular"].dim) == ("D", 6)
    for name in ("wrist", "elbow", "shoulder"):
        assert m[name].dim == 5 and m[name].is_subgroup is False
        assert m[name].generated.symbol == "D"
        # the twists are orthonormal in the commensurate metric: five independent rows
        assert np.linalg.matrix_rank(np.array(m[name].twists)) == 5


def test_five_bar_point_at_an_input_singularity_exactly() -> None:
    m = _motions("five_bar", "exact")["type1"]
    assert m.point is not None and m.point.dim == 1
    a1p = np.array(m.point.position) - [-1.5, 0, 0]
    assert abs(np.dot(m.point.velocities[0], a1p)) < 1e-12


@pytest.mark.parametrize(
    "name",
    [
        "fourbar",
        "five_bar",
        "parallelogram",
        "planar_3rpr",
        "bennett",
        "sarrus",
        "tsai_3upu",
        "ur5",
        "spherical_4r",
    ],
)
def test_exact_output_motion_has_the_mp50_verdicts(name: str) -> None:
    def key(m):
        gen = m.generated.symbol if m.generated is not None else None
        return (m.dim, m.type, m.is_subgroup, gen, None if m.point is None else m.point.dim)

    exact, mp = _motions(name, "exact"), _motions(name, "mp:50")
    assert exact
    for config, m in exact.items():
        assert m.precision == "exact"
        assert key(m) == key(mp[config]), config
