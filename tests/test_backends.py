"""The backends answer the questions formulas ask: is_zero, null_space, row_space, solve.

Known answers in each arithmetic (an exact rational kernel, an mp matrix with a singular
value of 1e-40, float), the law ``A @ null_space(A) = 0`` in the backend's own sense, and
the internal order of the modules of :mod:`mechsing.numeric`.
"""

from __future__ import annotations

import ast
from pathlib import Path

import mpmath
import numpy as np
import pytest
import sympy

from mechsing.numeric import (
    EXACT,
    FLOAT,
    Precision,
    backend_of,
    coarser_backend,
    decide_rank,
    to_float,
)

MP50 = Precision("mp", 50)


def _mp_near_singular() -> np.ndarray:
    """[[1, 1], [1, 1 + 1e-40]] at 50 digits: singular values about 2 and 5e-41."""
    with MP50.context():
        return MP50.asarray([[1, 1], [1, mpmath.mpf(1) + mpmath.mpf("1e-40")]])


# -- is_zero ------------------------------------------------------------------------


def test_exact_is_zero_proves_and_refuses() -> None:
    assert EXACT.is_zero(sympy.sqrt(2) * sympy.sqrt(3) - sympy.sqrt(6))
    assert EXACT.is_zero(sympy.sin(sympy.pi / 6) - sympy.Rational(1, 2))
    assert not EXACT.is_zero(sympy.Rational(1, 10**70))
    assert not EXACT.is_zero(sympy.sqrt(2) - sympy.Rational(14142135623730951, 10**16))


def test_mp_is_zero_is_relative_to_half_the_digits() -> None:
    with MP50.context():
        bk = MP50.backend
        assert bk.is_zero(mpmath.mpf("1e-40"))
        assert not bk.is_zero(mpmath.mpf("1e-20"))
        assert bk.is_zero(mpmath.mpf("1e-20"), scale=mpmath.mpf("1e10"))
        assert not bk.is_zero(mpmath.mpf("1e-60"), scale=0)  # scale 0: exactly zero
        assert bk.is_zero(mpmath.mpf(0), scale=0)


def test_float_is_zero() -> None:
    assert FLOAT.is_zero(1e-10) and not FLOAT.is_zero(1e-8)
    assert FLOAT.is_zero(1e-8, scale=100.0)
    assert not FLOAT.is_zero(1e-300, scale=0) and FLOAT.is_zero(0.0, scale=0)


# -- null spaces ---------------------------------------------------------------------


def test_exact_rational_null_space() -> None:
    A = EXACT.asarray([[1, 2, 3], [2, 4, 6]])
    N = EXACT.null_space(A)
    assert N.shape == (2, 3)
    assert all(isinstance(x, sympy.Rational) for x in N.flat)
    assert all(x == 0 for x in (A @ N.T).flat)
    # the kernel of [1 2 3] is spanned by (-2, 1, 0) and (-3, 0, 1)
    assert sympy.Matrix(N.tolist()).rref()[0] == sympy.Matrix(
        [[1, 0, sympy.Rational(-1, 3)], [0, 1, sympy.Rational(-2, 3)]]
    )
    R = EXACT.row_space(A)
    assert R.tolist() == [[1, 2, 3]]


def test_mp_sees_a_singular_value_of_1e_40_and_the_decision_drops_it() -> None:
    A = _mp_near_singular()
    with MP50.context():
        bk = backend_of(A)
        assert bk.name == "mp"
        # the backend's own rounding (1e-50) resolves the 1e-40 singular value: full rank
        assert bk.null_space(A).shape == (0, 2)
        # mp:50's two thresholds (tau_lo = 1e-40 relative) decide rank 1
        dec = decide_rank(A, MP50)
        assert dec.rank == 1
        N = bk.null_space(A, dec.rank)
        assert N.shape == (1, 2)
        assert all(isinstance(x, mpmath.mpf) for x in N.flat)
        r = A @ N[0]
        assert all(abs(x) < mpmath.mpf("1e-40") for x in r)
        n = N[0] / mpmath.sqrt(N[0] @ N[0])
        assert abs(abs(n[0]) - 1 / mpmath.sqrt(2)) < mpmath.mpf("1e-39")
    # float never sees it: the matrix rounds to a rank-1 one
    assert FLOAT.null_space(to_float(A)).shape == (1, 2)


def test_float_null_space() -> None:
    A = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    N = FLOAT.null_space(A)
    assert N.shape == (1, 3)
    assert np.allclose(np.abs(N[0]), [0.0, 0.0, 1.0], atol=1e-15)
    assert FLOAT.row_space(A).shape == (2, 3)


@pytest.mark.parametrize("mode", ["float", "mp:30", "exact"])
@pytest.mark.parametrize("seed", range(4))
def test_law_a_times_its_null_space_is_zero(mode: str, seed: int) -> None:
    """A @ null_space(A)^T is zero in the backend's sense, for integer matrices of rank
    below their size (the rank decided by decide_rank)."""
    rng = np.random.default_rng(seed)
    m, n, r = 5, 6, 1 + seed
    A0 = rng.integers(-3, 4, size=(m, r)) @ rng.integers(-3, 4, size=(r, n))
    prec = Precision("mp", 30) if mode.startswith("mp") else Precision(mode)
    with prec.context():
        bk = prec.backend
        A = bk.asarray(A0.tolist())
        dec = decide_rank(A, prec)
        N = bk.null_space(A, dec.rank)
        assert N.shape == (n - dec.rank, n)
        assert dec.rank == np.linalg.matrix_rank(A0.astype(float))
        scale = float(np.linalg.norm(A0.astype(float)))
        assert all(bk.is_zero(x, scale) for x in (A @ N.T).flat)


# -- solve --------------------------------------------------------------------------


def test_solve_exact_mp_float() -> None:
    A = [[1, 0], [0, 2], [0, 0]]
    b = [1, 1, 0]
    x = EXACT.solve(EXACT.asarray(A), EXACT.asarray(b))
    assert list(x) == [1, sympy.Rational(1, 2)]
    H = [[sympy.Rational(1, i + j + 1) for j in range(3)] for i in range(3)]  # Hilbert
    xe = EXACT.solve(EXACT.asarray(H), EXACT.asarray([1, 1, 1]))
    assert list(xe) == [3, -24, 30]
    with MP50.context():
        xm = MP50.backend.solve(MP50.asarray(H), MP50.asarray([1, 1, 1]))
        assert all(abs(a - b) < mpmath.mpf("1e-45") for a, b in zip(xm, [3, -24, 30], strict=True))
    xf = FLOAT.solve(np.asarray(to_float(H)), np.ones(3))
    assert np.allclose(xf, [3, -24, 30], rtol=1e-12)
    assert FLOAT.solve(np.zeros((3, 0)), np.ones(3)).shape == (0,)


# -- the smaller questions ------------------------------------------------------------


def test_series_switch_and_simplify() -> None:
    assert FLOAT.series_switch(1) == 1 and EXACT.series_switch(1) == 0
    assert EXACT.threshold(4) == 0 and 0 < FLOAT.threshold(4) < 1e-2
    assert EXACT.digits == 0 and 15 < FLOAT.digits < 16
    assert EXACT.simplify(1 / (sympy.sqrt(2) + 1)) == sympy.sqrt(2) - 1
    assert FLOAT.simplify(0.5) == 0.5
    assert EXACT.rational(1, 3) == sympy.Rational(1, 3) and FLOAT.rational(1, 4) == 0.25
    with MP50.context():
        bk = MP50.backend
        assert bk.key == ("mp", 50) and 49 < bk.digits < 51
        assert coarser_backend(bk, EXACT).name == "mp"
        assert coarser_backend(EXACT, FLOAT) is FLOAT
    assert EXACT.frame_centre([1.5, 2.0, 0.0]).tolist() == [0, 0, 0]
    assert FLOAT.frame_centre([1.5, 2.0, 0.0]).tolist() == [1.5, 2.0, 0.0]
    assert Precision.of(EXACT) == Precision("exact") and Precision.of(FLOAT) == Precision("float")


# -- the package's internal layers --------------------------------------------------------

#: mechsing.numeric's modules from the bottom up: each imports only modules before it
NUMERIC_ORDER = [
    "tolerances",
    "dispatch",
    "numbers",
    "lazy",
    "pirational",
    "_mp",
    "_field_arithmetic",
    "field",
    "backend",
    "precision",
    "blocks",
    "linalg",
    "scaling",
    "decisions",
    "inertia",
]


def test_numeric_modules_import_only_downwards() -> None:
    pkg = Path(__file__).resolve().parents[1] / "mechsing" / "numeric"
    assert sorted(p.stem for p in pkg.glob("*.py")) == sorted([*NUMERIC_ORDER, "__init__"])
    upward = []
    for i, name in enumerate(NUMERIC_ORDER):
        tree = ast.parse((pkg / f"{name}.py").read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            mods = []
            if isinstance(node, ast.ImportFrom) and node.module:
                mods = [node.module]
            elif isinstance(node, ast.Import):
                mods = [a.name for a in node.names]
            for mod in mods:
                if mod == "mechsing.numeric" or (
                    mod.startswith("mechsing.") and not mod.startswith("mechsing.numeric.")
                ):
                    upward.append(f"{name} imports {mod}")
                elif mod.startswith("mechsing.numeric."):
                    target = mod.split(".")[2]
                    if NUMERIC_ORDER.index(target) >= i:
                        upward.append(f"{name} imports {target}")
    assert upward == []


def test_exact_numbers_kept_in_float_are_their_nearest_doubles() -> None:
    """A file's exact numbers are converted to float once and kept (a sweep builds its
    model three times): the kept value is the fresh 20-digit evaluation's double, and
    the normal form the fresh one, however often asked; sympy Floats of the same value at
    two precisions are two numbers (kept apart)."""
    from mechsing.numeric import backend

    values = [
        sympy.sqrt(3) / 10,
        -7 * sympy.sqrt(3) / 10,
        sympy.atan(sympy.Rational(1, 5)) * 2,
        sympy.Rational(-3, 2),
        sympy.pi / 6,
        sympy.Float("0.1", 15),
        sympy.Float("0.1", 30),
    ]
    for _ in range(2):
        for v in values:
            assert to_float(v) == float(sympy.N(v, 20))
            fresh = v if v.is_Rational else backend._normal_form.__wrapped__(v)
            assert backend.exact_normal_form(v) == fresh
    assert backend.exact_normal_form(sympy.Float("0.1", 15)) != backend.exact_normal_form(
        sympy.Float("0.1", 30)
    )
