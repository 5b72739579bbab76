"""PiRational, the exact number of a file's plain numbers (a rational times a power of pi),
against sympy and mpmath: its sympy value is sympy's number, its arithmetic and order
sympy's, its float the correctly rounded one (mpmath at 400 bits), and ``evalf_float`` the
float sympy's ``N`` gives, so that a float analysis reads the same floats as before."""

from __future__ import annotations

import random
from fractions import Fraction

import mpmath
import pytest
import sympy

from mechsing.model.expressions import parse_number
from mechsing.numeric.pirational import PI, PiRational, evalf_float


def _samples(n: int, seed: int) -> list[tuple[Fraction, int]]:
    rng = random.Random(seed)
    out = []
    for _ in range(n):
        p = rng.randint(-(10 ** rng.randint(1, 14)), 10 ** rng.randint(1, 14))
        q = 10 ** rng.randint(0, 9) * rng.choice([1, 3, 7, 180, 6, 11])
        out.append((Fraction(p, q), rng.choice([0, 0, 1, -1, 2, 3])))
    return out


def _sympy(q: Fraction, k: int) -> sympy.Expr:
    return sympy.Rational(q.numerator, q.denominator) * sympy.pi**k


def test_sympy_value_is_sympys_number() -> None:
    for q, k in _samples(300, 1):
        assert sympy.sympify(PiRational(q, k)) == _sympy(q, k)
    assert sympy.sympify(PiRational(30) * PI / 180) == sympy.pi / 6
    assert isinstance(sympy.sympify(PiRational(Fraction(1, 10))), sympy.Rational)


def test_float_is_correctly_rounded() -> None:
    with mpmath.workprec(400):
        for q, k in _samples(2000, 2):
            want = float(mpmath.mpf(q.numerator) / q.denominator * mpmath.pi**k)
            assert float(PiRational(q, k)) == want, (q, k)


@pytest.mark.parametrize("digits", [17, 20, 30])
def test_evalf_float_is_sympys_float(digits: int) -> None:
    # the float path converts the file's numbers at 20 digits (to_float), the reader at 17
    for q, k in _samples(1500, digits):
        if digits != 20 and k:
            continue  # sympy's own rounding of a product with pi at 17 digits is not exact
        want = float(sympy.N(_sympy(q, k), digits))
        assert evalf_float(PiRational(q, k), digits) == want, (q, k, digits)


def test_arithmetic_and_order_are_sympys() -> None:
    pairs = _samples(400, 3)
    for (qa, ka), (qb, kb) in zip(pairs[::2], pairs[1::2], strict=True):
        a, b = PiRational(qa, ka), PiRational(qb, kb)
        sa, sb = _sympy(qa, ka), _sympy(qb, kb)
        assert sympy.sympify(a + b) == sa + sb
        assert sympy.sympify(a - b) == sa - sb
        assert sympy.sympify(a * b) == sa * sb
        assert sympy.sympify(a / b) == sa / sb
        assert sympy.sympify(a**3) == sa**3
        assert (a < b) == bool(sa < sb) and (a >= b) == bool(sa >= sb)
        assert (a == b) == (sa == sb)
        assert (a < 0.5) == bool(sa < 0.5) and (a > -2.25) == bool(sa > -2.25)
    # with a float: float arithmetic on the correctly rounded float
    assert PI / 6 * 0.5 == float(PI / 6) * 0.5 and 2.0 - PiRational(Fraction(1, 10)) == 1.9
    # a sum of two powers of pi and a root are sympy's
    assert PiRational(1) + PI == 1 + sympy.pi
    assert sympy.sqrt(PiRational(Fraction(9, 4))) == sympy.Rational(3, 2)
    assert PiRational(2) * sympy.sqrt(2) == 2 * sympy.sqrt(2)


@pytest.mark.parametrize(
    "text",
    ["30", "-1.5e-3", "0.1", "pi/6", "-pi", "2*pi/3", "pi**2/4", "1/pi", "(1+2)**2/7", "2**-3"],
)
def test_parse_plain_is_sympys_value(text: str) -> None:
    # sympy's own parser of the same text is the reference (decimals as exact rationals)
    want = sympy.nsimplify(sympy.sympify(text, rational=True))
    got = parse_number(text, plain=True)
    assert isinstance(got, PiRational)
    assert sympy.sympify(got) == want


@pytest.mark.parametrize("text", ["sqrt(3)/2", "pi + 1", "2*atan(1/2)", "cos(pi/12)", "2**(1/2)"])
def test_parse_plain_leaves_the_rest_to_sympy(text: str) -> None:
    got = parse_number(text, plain=True)
    assert isinstance(got, sympy.Basic)
    assert got == sympy.sympify(text, rational=True)


def test_a_subgroup_of_plain_numbers_stays_exact() -> None:
    # a joint's subgroup read from the file's plain numbers: its axis is made unit exactly
    # and an mp:50 basis (auto's second pass) has the exact values to 50 digits, not the
    # floats of 1/10 or 2/7; reference: the row (u, p x u) in fractions
    from mechsing.subgroups import Subgroup

    u = (Fraction(2, 7), Fraction(3, 7), Fraction(6, 7))
    p = (Fraction(1, 10), Fraction(-3, 10), Fraction(7, 3))
    sg = Subgroup("R", axis=[PiRational(2 * x) for x in u], point=[PiRational(x) for x in p])
    cross = (
        p[1] * u[2] - p[2] * u[1],
        p[2] * u[0] - p[0] * u[2],
        p[0] * u[1] - p[1] * u[0],
    )
    (row,) = sg.basis("mp:50")
    for got, want in zip(row, (*u, *cross), strict=True):
        with mpmath.workdps(60):
            assert abs(mpmath.mpf(got) - mpmath.mpf(want.numerator) / want.denominator) < 1e-48
