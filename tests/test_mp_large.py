"""mp:N beyond the float range, up to the documented maximum (10000 digits).

The two rank thresholds of mp:N are 10^(10-N) and 10^(-N/2): as floats they underflow to 0
beyond N = 333 and N = 646, where every value then counted as non-zero (``x >= 0``) and
``mechsing analyze examples/fourbar.yaml --precision mp:700`` exited 4 ("subgroup H: pitch must
not be zero").  Expected answers come from the rule itself and from the four-bar's geometry: a
singular value is kept at or above tau_hi and dropped at or below tau_lo (relative to the
largest); the four-bar (ground pivots A at the origin and D at (4, 0, 0), axes z) has mobility 1
at its reference configuration and its rocker turns about the axis z through D.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from mechsing.numeric import decide_definiteness, decide_nonzero, decide_rank, parse_precision
from tests.cli import ROOT, cli_json, run_cli

FOURBAR = ROOT / "examples" / "fourbar.yaml"


def _diag(digits: int, exponent: float) -> np.ndarray:
    with mpmath.workdps(digits):
        small = mpmath.mpf(10) ** exponent
        return np.array([[mpmath.mpf(1), 0], [0, small]], dtype=object)


@pytest.mark.parametrize("digits", [334, 700, 2000, 10000])
def test_the_thresholds_stay_positive_and_decide(digits: int) -> None:
    prec = parse_precision(f"mp:{digits}")
    t = prec.tolerances
    assert 0 < t.tau_lo < t.tau_hi < 1
    # kept: 10^5 above tau_hi = 10^(-N/2); dropped: 10^5 below tau_lo = 10^(10-N)
    kept = decide_rank(_diag(digits, -digits / 2 + 5), prec)
    dropped = decide_rank(_diag(digits, 10 - digits - 5), prec)
    between = decide_rank(_diag(digits, (10 - digits - digits / 2) / 2), prec)
    assert (kept.rank, dropped.rank, between.rank) == (2, 1, None)
    with mpmath.workdps(digits):
        assert decide_nonzero(mpmath.mpf(10) ** (-digits / 2 + 5), prec) is True
        assert decide_nonzero(mpmath.mpf(10) ** (5 - digits), prec) is False
        q = _diag(digits, -digits / 2 + 5)
    assert decide_definiteness(q, prec).kind == "definite"
    assert decide_definiteness(_diag(digits, 5 - digits), prec).kind == "semidefinite"


@pytest.mark.parametrize("digits", [700, 2000])
def test_the_four_bar_at_high_precision(digits: int) -> None:
    data = cli_json(
        [
            "analyze",
            FOURBAR,
            "--precision",
            f"mp:{digits}",
            "--config",
            "reference",
            "--format",
            "json",
        ]
    )
    (conf,) = data["configurations"]
    assert conf["precision"] == f"mp:{digits}"
    assert conf["singular"] is False and conf["mobility"]["finite"] == 1
    motion = data["output_motion"]
    assert motion["type"] == "R"
    assert motion["params"]["axis"] == pytest.approx([0, 0, 1], abs=1e-15)
    assert motion["params"]["point"] == pytest.approx([4, 0, 0], abs=1e-12)


def test_the_text_shows_thresholds_below_the_float_range() -> None:
    r = run_cli(["analyze", FOURBAR, "--precision", "mp:700", "--config", "reference"])
    assert r.status == 0, r.err
    assert "rank thresholds 1e-690 and 1e-350 of the largest singular value" in r.out
    assert "(thresholds 1e-690/1e-350 of the largest, " in r.out  # each margin's too
    assert "; L = 1.803 m)" in r.out


def test_identify_at_the_documented_maximum() -> None:
    # a rotation about z at the origin and one about z through (1, 0, 0) generate the planar
    # group G with normal z
    r = run_cli(["identify", "--precision", "mp:10000", "--", "0,0,1,0,0,0", "0,0,1,0,-1,0"])
    assert r.status == 0, r.err
    assert r.out.startswith("G (dimension 3)\n  normal: 0, 0, 1\n")
