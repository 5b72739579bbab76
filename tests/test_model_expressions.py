"""Exact numbers and the expression whitelist (mechsing.model.expressions)."""

from __future__ import annotations

import pytest
import sympy
from hypothesis import given
from hypothesis import strategies as st

from mechsing.cli import UserError, exit_status
from mechsing.model.expressions import ExpressionError, parse_number


@pytest.mark.parametrize(
    "text, value",
    [
        ("0.1", sympy.Rational(1, 10)),
        ("-3", sympy.Integer(-3)),
        ("+2.5", sympy.Rational(5, 2)),
        (".5", sympy.Rational(1, 2)),
        ("1e3", sympy.Integer(1000)),
        ("1.5E-3", sympy.Rational(3, 2000)),
        ("1/3", sympy.Rational(1, 3)),
        ("pi/2", sympy.pi / 2),
        ("sqrt(3)/2", sympy.sqrt(3) / 2),
        ("cos(pi/12)/2", sympy.cos(sympy.pi / 12) / 2),
        ("2*atan(1/2)", 2 * sympy.atan(sympy.Rational(1, 2))),
        ("atan2(1, 2)", sympy.atan2(1, 2)),
        ("asin(1/2)", sympy.pi / 6),
        ("acos(0)", sympy.pi / 2),
        ("tan(pi/4)", sympy.Integer(1)),
        ("2**-1", sympy.Rational(1, 2)),
        ("2**(1/2)", sympy.sqrt(2)),
        ("(-(1 - 3)) * 0.25", sympy.Rational(1, 2)),
        ("sin(pi/6) + 0.1", sympy.Rational(3, 5)),
    ],
)
def test_accepted_values_are_exact(text, value):
    got = parse_number(text)
    assert sympy.simplify(got - value) == 0
    assert isinstance(got, sympy.Basic)


def test_decimal_text_is_exact_not_float():
    v = parse_number("0.1")
    assert v == sympy.Rational(1, 10)
    assert v != sympy.Rational(0.1)  # the float64 rounding of 0.1


@given(st.decimals(allow_nan=False, allow_infinity=False, places=8, min_value=-1e6, max_value=1e6))
def test_decimal_round_trip(d):
    text = format(d, "f")
    assert parse_number(text) == sympy.Rational(text)


@pytest.mark.parametrize(
    "text, word",
    [
        ("__import__('os').system('true')", "not allowed"),
        ("().__class__", "attribute"),
        ("x + 1", "'x'"),
        ("exp(1)", "'exp'"),
        ("e", "'e'"),
        ("sqrt", "without parentheses"),
        ("sqrt(1, 2)", "takes 1 argument"),
        ("atan2(1)", "takes 2 arguments"),
        ("sin(x=1)", "keyword"),
        ("2 ^ 3", "**"),
        ("7 % 2", "%"),
        ("7 // 2", "//"),
        ("1 < 2", "comparisons"),
        ("[1, 2]", "lists"),
        ("'abc'", "constant"),
        ("1j", "complex"),
        ("0x10", "decimal"),
        ("1_000", "decimal"),
        ("lambda: 0", "lambda"),
        ("1 if 1 else 0", "if/else"),
        ("1/0", "division by zero"),
        ("0**-1", "division by zero"),
        ("atan2(0, 0)", "undefined"),
        ("sqrt(-1)", "not a finite real"),
        ("asin(2)", "not a finite real"),
        ("2**pi", "rational"),
        ("2**1000", "too large"),
        ("(10**100)**100", "too large"),
        ("1e500", "exponent"),
        ("1" * 500, "too many digits"),
        ("1+" * 600 + "1", "too long"),
        ("(" * 300 + "1" + ")" * 300, "not valid"),
        ("1 +", "not valid"),
        ("", "empty"),
        ("+".join(["1"] * 150), "too many"),
    ],
)
def test_rejected(text, word):
    with pytest.raises(ExpressionError) as exc:
        parse_number(text)
    assert word.lower() in str(exc.value).lower()
    assert isinstance(exc.value, UserError) and exit_status(exc.value) == 2


def test_no_code_runs(tmp_path):
    marker = tmp_path / "pwned"
    with pytest.raises(ExpressionError):
        parse_number(f"__import__('pathlib').Path('{marker}').touch()")
    assert not marker.exists()
