"""Numbers of absurd size, hidden divisions by zero and non-ASCII digits, run as a user runs
them: exit status 2 with a message naming the place, never a numpy warning, a traceback or
a file written; and the helpers that make directions unit without overflow."""

from __future__ import annotations

import json
import math
import time
from pathlib import Path

import numpy as np
import pytest
import sympy

from mechsing.model.expressions import ExpressionError, parse_number
from mechsing.numeric import MAX_NUMBER
from mechsing.numeric.numbers import decimal_float, is_decimal_text, safe_norm, unit_vector
from tests.cli import ROOT, run_cli, run_cli_subprocess, runtime_warnings

FOURBAR = ROOT / "examples" / "fourbar.yaml"

#: the bundled four-bar with the point of D and the parameters a case gives
TEMPLATE = """\
{parameters}bodies: [ground, crank, coupler, rocker]
joints:
  - {{name: A, type: R, between: [ground, crank],   axis: [0, 0, 1], point: [0, 0, 0]}}
  - {{name: B, type: R, between: [crank, coupler],  axis: [0, 0, 1], point: [1, 0, 0]}}
  - {{name: C, type: R, between: [coupler, rocker], axis: [0, 0, 1], point: [3, 2, 0]}}
  - {{name: D, type: R, between: [rocker, ground],  axis: [0, 0, 1], point: [{d}, 0, 0]}}
configurations:
  crank-30: {{A: 30}}
"""

ABSURD = {
    # the point of D at 1e300: squares overflowed (exit 4 after numpy warnings)
    "point_1e300": ("", "1e300", "'1e300' is too large", 6),
    # a parameter of 1e400 (not even a float)
    "parameter_1e400": ("parameters: {d: 1e400}\n", "d", "'1e400' is too large", 1),
    # a value beyond the bound made of allowed literals
    "product_1e400": ("", '"1e200*1e200"', "(= 1.0e+400) is too large", 6),
    # an exactly zero divisor, not written as 0: accepted as -5.8e135 before
    "hidden_zero": (
        "",
        '"1/(sin(pi/7)**2 + cos(pi/7)**2 - 1)"',
        "division by zero (the divisor 'sin(pi/7)**2 + cos(pi/7)**2 - 1' is zero",
        6,
    ),
}


def _files(path: Path) -> list[str]:
    return sorted(p.name for p in path.iterdir())


@pytest.mark.parametrize("case", ABSURD)
def test_an_absurd_number_is_bad_input_in_every_command(
    case: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    parameters, d, words, line = ABSURD[case]
    f = tmp_path / "m.yaml"
    f.write_text(TEMPLATE.format(parameters=parameters, d=d))
    for argv in (
        ["analyze", f.name],
        ["sweep", f.name, "--vary", "A=0:10:5", "--quiet"],
        ["condition", f.name],
    ):
        r = run_cli(argv)
        assert r.status == 2, (argv, r.status, r.err)
        assert r.err.startswith("mechsing: error: ") and f"{f.name}:{line}:" in r.err, r.err
        assert words in r.err, r.err
        assert "Warning" not in r.err and "Traceback" not in r.err
        assert r.out == ""
    assert _files(tmp_path) == ["m.yaml"]


def test_absurd_numbers_as_a_subprocess_leave_the_directory_alone(tmp_path: Path) -> None:
    f = tmp_path / "m.yaml"
    f.write_text(TEMPLATE.format(parameters="", d="1e300"))
    before = _files(tmp_path)
    r = run_cli_subprocess(["analyze", f.name, "--format", "json"], cwd=tmp_path, timeout=120)
    assert r.status == 2, r.err
    assert r.err.count("\n") == 1 and "RuntimeWarning" not in r.err, r.err
    assert "m.yaml:6: joint 'D': point[0]: the number '1e300' is too large" in r.err
    assert _files(tmp_path) == before


def test_a_doubling_chain_of_parameters_is_refused_in_linear_time(tmp_path: Path) -> None:
    # a_k = sin(a_{k-1}) + cos(a_{k-1}): the exact value doubles at each step; 40 steps
    # never finished before (each parse evaluated the whole tree)
    chain = "".join(f'  a{k}: "sin(a{k - 1}) + cos(a{k - 1})"\n' for k in range(1, 41))
    f = tmp_path / "chain.yaml"
    f.write_text(TEMPLATE.format(parameters="parameters:\n  a0: 0.5\n" + chain, d="a40"))
    t0 = time.monotonic()
    r = run_cli_subprocess(["analyze", f.name], cwd=tmp_path, timeout=60)
    assert time.monotonic() - t0 < 30
    assert r.status == 2, r.err
    assert "chain.yaml:11: parameter 'a9'" in r.err
    assert "too large for exact evaluation" in r.err and "has 2045 parts (at most 2000)" in r.err


def test_a_deep_chain_of_parameters_is_refused_in_bounded_time(tmp_path: Path) -> None:
    # a_k = sin(a_{k-1}) 600 times: each step cost sympy time growing with the depth (265 s
    # in all before, then a RecursionError read as "nested too deeply" at a325)
    chain = "".join(f'  a{k}: "sin(a{k - 1})"\n' for k in range(1, 601))
    f = tmp_path / "deep.yaml"
    f.write_text(TEMPLATE.format(parameters="parameters:\n  a0: 0.5\n" + chain, d="a600"))
    t0 = time.monotonic()
    r = run_cli_subprocess(["analyze", f.name], cwd=tmp_path, timeout=60)
    assert time.monotonic() - t0 < 30
    assert r.status == 2, r.err
    assert "deep.yaml:66: parameter 'a64'" in r.err
    assert "is nested 65 deep (at most 64)" in r.err


def test_a_short_chain_is_evaluated_once_per_parameter(tmp_path: Path) -> None:
    chain = "".join(f'  a{k}: "sin(a{k - 1}) + cos(a{k - 1})"\n' for k in range(1, 9))
    f = tmp_path / "chain.yaml"
    f.write_text(TEMPLATE.format(parameters="parameters:\n  a0: 0.5\n" + chain, d="3 + a8"))
    r = run_cli(["analyze", str(f), "--config", "reference", "--format", "json"])
    assert r.status == 0, r.err
    assert "Warning" not in r.err


@pytest.mark.parametrize(
    ("text", "zero"),
    [
        ("1/(sin(pi/7)**2 + cos(pi/7)**2 - 1)", True),
        ("1/(atan(1/2) + atan(1/3) - pi/4)", True),  # Euler's arctangent identity
        ("(sqrt(2)*sqrt(3) - sqrt(6) + 0*pi)**(-1)", True),
        ("atan2(sin(pi/5)**2 + cos(pi/5)**2 - 1, 0)", True),
        ("1/(sqrt(2) - 1.4142)", False),  # small, not zero: 1/1.36e-5
        ("1/(pi - 3.14159265)", False),
    ],
)
def test_a_divisor_is_zero_however_it_is_written(text: str, zero: bool) -> None:
    if zero:
        with pytest.raises(ExpressionError, match="division by zero|undefined"):
            parse_number(text)
    else:
        value = parse_number(text)
        expected = {"1/(sqrt(2) - 1.4142)": 1 / (math.sqrt(2) - 1.4142)}.get(
            text, 1 / (math.pi - 3.14159265)
        )
        assert float(value) == pytest.approx(expected, rel=1e-6)


@pytest.mark.parametrize(
    ("option", "words"),
    [
        ("A=\uff13\uff10", "invalid character"),  # fullwidth 30
        ("A=1_0", "write plain decimal digits"),
        ("A=1e13", "'1e13' is too large"),
    ],
)
def test_set_accepts_ascii_decimal_numbers_only(option: str, words: str) -> None:
    r = run_cli(["analyze", FOURBAR, "--set", option])
    assert r.status == 2, r.err
    assert words in r.err and "Traceback" not in r.err


def test_set_takes_an_ascii_number() -> None:
    r = run_cli(["analyze", FOURBAR, "--set", "A=30", "--config", "cli", "--format", "json"])
    assert r.status == 0, r.err


@pytest.mark.parametrize(
    ("varies", "words"),
    [
        (["A=0:1e12:1e-300"], "more than 10,000,000 samples"),  # the count overflowed: exit 4
        (["A=0:1e300:1e-300", "B=0:1:1"], "'1e300' is too large"),
        (["A=0:1:1e-6", "B=0:1:1e-6"], "more than a sweep takes"),
        (["A=0:1_0:1"], "ASCII decimal digits"),
        (["A=0:\uff11:1"], "ASCII decimal digits"),
    ],
)
def test_vary_counts_and_numbers(varies: list[str], words: str) -> None:
    argv = ["sweep", FOURBAR, "--quiet"]
    for v in varies:
        argv += ["--vary", v]
    r = run_cli(argv)
    assert r.status == 2, r.err
    assert words in r.err and "Traceback" not in r.err


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["--", "0,0,1,0,0,1e300"], "'1e300' is too large"),
        (["--length-scale", "1_0", "--", "0,0,1,0,0,0"], "not a decimal number"),
        (["--length-scale", "1e-300", "--", "0,0,1,0,0,0"], "sensible size"),
    ],
)
def test_identify_numbers(argv: list[str], words: str, tmp_path: Path) -> None:
    r = run_cli_subprocess(["identify", *argv], cwd=tmp_path, timeout=60)
    assert r.status == 2, r.err
    assert words in r.err


def test_characteristic_length_of_absurd_size(tmp_path: Path) -> None:
    f = tmp_path / "m.yaml"
    f.write_text(TEMPLATE.format(parameters="characteristic_length: 1e-300\n", d=4))
    r = run_cli(["analyze", str(f)])
    assert r.status == 2 and "too small a length" in r.err, r.err


def _scaled_fourbar(tmp_path: Path, k: str) -> Path:
    f = tmp_path / f"fourbar{k}.yaml"
    f.write_text(
        FOURBAR.read_text()
        .replace("[1, 0, 0]}", f"[1{k}, 0, 0]}}")
        .replace("[3, 2, 0]}", f"[3{k}, 2{k}, 0]}}")
        .replace("[4, 0, 0]}", f"[4{k}, 0, 0]}}")
    )
    return f


def test_a_small_mechanism_is_the_same_mechanism(tmp_path: Path) -> None:
    # every length times 1e-11: L and the residuals are computed without underflow
    small = run_cli(["analyze", _scaled_fourbar(tmp_path, "e-11"), "--format", "json"])
    unit = run_cli(["analyze", FOURBAR, "--format", "json"])
    assert small.status == unit.status == 0, small.err
    assert "Warning" not in small.err
    a, b = json.loads(small.out), json.loads(unit.out)
    assert [(c["name"], c["singular"], c["mobility"]) for c in a["configurations"]] == [
        (c["name"], c["singular"], c["mobility"]) for c in b["configurations"]
    ]
    # the joint angles are those of the unit four-bar (they do not depend on the scale)
    for ca, cb in zip(a["configurations"], b["configurations"], strict=True):
        for name in ("A", "B", "C", "D"):
            assert ca["joints"][name][0] == pytest.approx(cb["joints"][name][0], abs=1e-9)


def test_a_mechanism_of_absurdly_small_size_is_refused(tmp_path: Path) -> None:
    # at 1e-200 the residuals' squares underflow to 0: every configuration "closed" at once
    f = _scaled_fourbar(tmp_path, "e-200")
    r = run_cli(["analyze", f])
    assert r.status == 2, r.err
    assert f"{f}:19: joints: every joint point lies within 4e-200 m of the origin" in r.err


# -- the helpers -------------------------------------------------------------------------


@pytest.mark.parametrize("scale", [1e-300, 1e-200, 1.0, 1e200, 1e308])
def test_unit_vector_without_overflow(scale: float) -> None:
    u = unit_vector([scale, scale, 0.0])
    assert u == pytest.approx([math.sqrt(0.5), math.sqrt(0.5), 0.0], rel=1e-15)
    q = unit_vector([scale, 0, scale, 0])
    assert q == pytest.approx([math.sqrt(0.5), 0, math.sqrt(0.5), 0], rel=1e-15)
    assert safe_norm([0.3 * scale, 0.4 * scale]) == pytest.approx(0.5 * scale, rel=1e-15)


@pytest.mark.parametrize("bad", [[0.0, 0.0, 0.0], [math.inf, 0, 0], [math.nan, 1, 0]])
def test_unit_vector_refuses(bad: list[float]) -> None:
    with pytest.raises(ValueError):
        unit_vector(bad)


@pytest.mark.parametrize(
    "text", ["1_000", "\uff13\uff10", "nan", "inf", "-Infinity", "0x10", "1e", "", "1 2", "\u0661"]
)
def test_decimal_text_is_ascii_decimal_syntax(text: str) -> None:
    assert not is_decimal_text(text)
    with pytest.raises(ValueError):
        decimal_float(text)


@pytest.mark.parametrize(
    ("text", "value"), [("30", 30.0), ("-1.5e3", -1500.0), ("+ .5", 0.5), ("1e12", 1e12)]
)
def test_decimal_float(text: str, value: float) -> None:
    assert decimal_float(text) == value


def test_the_size_bound_is_exact_at_its_edge() -> None:
    assert parse_number(f"{MAX_NUMBER:.0f}") == sympy.Integer(int(MAX_NUMBER))
    with pytest.raises(ExpressionError, match="too large"):
        parse_number(f"{MAX_NUMBER:.0f}.0000001")
    with pytest.raises(ValueError, match="too large"):
        decimal_float("1.0000001e12")
    assert np.isfinite(decimal_float("-1e12"))


# -- no numpy warning reaches standard error ---------------------------------------------

HOSTILE_FILES = sorted((ROOT / "tests" / "bad_files").glob("*.yaml"))


@pytest.mark.parametrize("path", HOSTILE_FILES, ids=[p.stem for p in HOSTILE_FILES])
def test_no_runtime_warning_on_a_hostile_file(path: Path) -> None:
    assert runtime_warnings(["analyze", path]) == []


@pytest.mark.parametrize("case", ABSURD)
def test_no_runtime_warning_on_absurd_numbers(case: str, tmp_path: Path) -> None:
    parameters, d, _, _ = ABSURD[case]
    f = tmp_path / "m.yaml"
    f.write_text(TEMPLATE.format(parameters=parameters, d=d))
    for argv in (["analyze", f], ["sweep", f, "--vary", "A=0:10:5", "--quiet"], ["condition", f]):
        assert runtime_warnings(argv) == []
