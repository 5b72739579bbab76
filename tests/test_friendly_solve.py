"""``mechsing solve``: the typed SolveResult, ``joints_text`` at the precision solved to,
and the text that prints every digit.

The four-bar of examples/fourbar.yaml (A (0,0), B (1,0), C (3,2), D (4,0)) is closed here
independently at 60 digits with mpmath: the crank pin turns to B' = (cos t, sin t), C' is
the intersection of the circles about B' (radius |BC|) and D (radius |CD|) on the
reference's side of B'D, and the joint values follow from the link angles.
"""

from __future__ import annotations

import json
from pathlib import Path

import mpmath
import pytest
import sympy

from mechsing.analysis.solve import SolveResult, solve
from mechsing.kinematics import solve_configuration
from mechsing.model import load
from tests.cli import run_cli

EX = Path(__file__).resolve().parents[1] / "examples"
FOURBAR = EX / "fourbar.yaml"
OLD_KEYS = [
    "mechanism",
    "configuration",
    "precision",
    "joints",
    "closure_residual",
    "underdetermined",
    "steps",
]


def fourbar_60_digits(degrees: int) -> dict[str, mpmath.mpf]:
    """The four-bar's joint values at a crank angle in degrees, at 60 digits."""
    with mpmath.workdps(60):
        theta = mpmath.mpf(degrees) * mpmath.pi / 180
        A, B, C, D = (mpmath.matrix(p) for p in ([0, 0], [1, 0], [3, 2], [4, 0]))
        r1, r2 = mpmath.norm(C - B), mpmath.norm(C - D)

        def cross(u, v):
            return u[0] * v[1] - u[1] * v[0]

        def angle(u, v):  # from u to v
            return mpmath.atan2(cross(u, v), u[0] * v[0] + u[1] * v[1])

        side = mpmath.sign(cross(D - B, C - B))
        Bt = mpmath.matrix([mpmath.cos(theta), mpmath.sin(theta)])
        d = mpmath.norm(D - Bt)
        a = (r1**2 - r2**2 + d**2) / (2 * d)
        h = mpmath.sqrt(r1**2 - a**2)
        u = (D - Bt) / d
        Ct = Bt + a * u + side * h * mpmath.matrix([-u[1], u[0]])
        psi = angle(C - B, Ct - Bt)  # coupler turn
        phi = angle(C - D, Ct - D)  # rocker turn
        return {"A": theta, "B": psi - theta, "C": phi - psi, "D": -phi}


def _half_unit_in_last_place(x: mpmath.mpf, digits: int) -> mpmath.mpf:
    """Half a unit in the last of ``digits`` significant digits of ``x``."""
    e = int(mpmath.floor(mpmath.log10(abs(x)))) if x else 0
    return mpmath.mpf(10) ** (e + 1 - digits) / 2


@pytest.mark.parametrize("digits", [25, 40])
def test_mp_joints_text_has_n_digits_and_reads_back_to_the_mp_solution(digits):
    res = solve(load(str(FOURBAR)), "crank-30", f"mp:{digits}")
    assert isinstance(res, SolveResult) and res.precision == f"mp:{digits}"
    _model, closed = solve_configuration(load(str(FOURBAR)), "crank-30", f"mp:{digits}")
    truth = fourbar_60_digits(30)
    with mpmath.workdps(60):
        for (name, (text,)), q in zip(res.joints_text, closed.q, strict=True):
            mantissa = text.lstrip("-").replace(".", "").lstrip("0")
            assert len(mantissa) == digits, text
            x = mpmath.mpf(text)
            # correctly rounded: within half a unit of the N-th digit of the mp solution
            # (so within 5 * 10^-N relative)
            assert abs(x - q) <= _half_unit_in_last_place(q, digits)
            # and the mp solution is the four-bar's to about N digits
            assert abs(x - truth[name]) <= 10 * _half_unit_in_last_place(truth[name], digits)
    # joints stays numeric: the floats of the same values
    for (_name, (value,)), (_n, (text,)) in zip(res.joints, res.joints_text, strict=True):
        assert isinstance(value, float) and value == pytest.approx(float(text), rel=1e-15)


def test_mp_text_prints_every_digit():
    run = run_cli(["solve", str(FOURBAR), "--config", "crank-30", "--precision", "mp:30"])
    assert run.status == 0
    truth = fourbar_60_digits(30)
    with mpmath.workdps(30):
        d = mpmath.nstr(truth["D"], 30, strip_zeros=False)
    assert f"  D: {d} rad" in run.out.splitlines()
    assert len(d.replace("0.", "", 1).lstrip("0")) == 30


def test_float_json_keeps_its_keys_and_adds_joints_text():
    run = run_cli(["solve", str(FOURBAR), "--config", "crank-30", "--format", "json"])
    doc = json.loads(run.out)
    assert list(doc) == [*OLD_KEYS, "joints_text", "notes"]
    for name, values in doc["joints"].items():
        # the shortest decimal that reads back to the float itself
        assert [float(t) for t in doc["joints_text"][name]] == values
    truth = fourbar_60_digits(30)
    assert doc["joints"]["B"][0] == pytest.approx(float(truth["B"]), abs=1e-14)


def test_exact_json_gives_the_exact_values_as_text():
    f = EX / "parallelogram.yaml"
    run = run_cli(
        [
            "solve",
            str(f),
            "--config",
            "anti-parallelogram",
            "--precision",
            "exact",
            "--format",
            "json",
        ]
    )
    doc = json.loads(run.out)
    assert list(doc) == [*OLD_KEYS, "joints_text", "notes"] and doc["precision"] == "exact"
    # B = (3/5, 4/5) on the unit circle about A: the crank turned from +y by -2 atan(1/3)
    assert (
        sympy.simplify(
            sympy.sympify(doc["joints_text"]["A"][0]) + 2 * sympy.atan(sympy.Rational(1, 3))
        )
        == 0
    )
    for name, (text,) in doc["joints_text"].items():
        assert float(sympy.sympify(text)) == pytest.approx(doc["joints"][name][0], rel=1e-15)
