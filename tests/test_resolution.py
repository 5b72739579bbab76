"""Verdicts below the resolution of their data (issue 27, item 8).

An offset slider-crank (crank r = 1, rod l = 4, slider pin on the line y = e = 1) is drawn
at its outer dead centre, where crank and rod are collinear: the crank then points at
the slider pin, at angle asin(e / (l + r)) above the slide, so from its reference
direction (straight down, B = (0, -1)) the crank has turned A* = pi/2 + asin(1/5).  The
dead centre is an input singularity (the slider's rate vanishes for any crank rate).

Written as a degree value rounded to 15 significant digits, A is within half a unit of
its 15th digit of A* (a 15-digit value: 101.536959032815 deg): float finds it singular,
while mp:50 finds the written decimals regular by about 1e-15 -- below what the value's
resolution can move the tests by.  auto re-decides float's drop (above float's own
rounding) at mp:50, finds that, and keeps float's singular verdict: the data cannot tell
the drawn dead centre from the written decimals.  Each says so, in every format; with A*
given exactly no verdict does.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from mechsing.model.expressions import written_digits
from mechsing.numeric import RESOLUTION_MIN_DIGITS, data_resolution
from tests.cli import ROOT, cli_json, run_cli
from tests.mechanisms import NON_GRASHOF_ROCKER, PARALLELOGRAM_JOINTS

GEOMETRY = """\
mechanism: offset-slider-crank
{units}bodies: [ground, crank, rod, slider]
joints:
  - {{name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}}
  - {{name: B, type: R, between: [crank, rod], axis: [0, 0, 1], point: [0, -1, 0]}}
  - {{name: C, type: R, between: [rod, slider], axis: [0, 0, 1], point: ["2*sqrt(3)", 1, 0]}}
  - {{name: P, type: P, between: [ground, slider], axis: [1, 0, 0]}}
inputs: [A]
output: {{body: slider}}
configurations:
  dead-centre: {{A: {value}}}
"""

#: the outer dead centre: the crank turned from straight down to point at the pin
DEAD_CENTRE = math.pi / 2 + math.asin(1 / 5)


def _rounded(tmp_path: Path) -> Path:
    value = float(f"{math.degrees(DEAD_CENTRE):.15g}")
    path = tmp_path / "rounded.yaml"
    path.write_text(GEOMETRY.format(units="units: {angle: deg}\n", value=repr(value)))
    return path


def _exact(tmp_path: Path) -> Path:
    """Every value exact (exact mode needs them all): the rod then points along the
    crank, asin(1/5) above the slide, having turned from its reference direction (B0 to
    the pin, 30 degrees) by asin(1/5) - pi/6; the pin is at 5 (2 sqrt(6) / 5, 1/5)."""
    path = tmp_path / "exact.yaml"
    value = '"pi/2 + asin(1/5)", B: "-2*pi/3", C: "pi/6 - asin(1/5)", P: "2*sqrt(6) - 2*sqrt(3)"'
    path.write_text(GEOMETRY.format(units="", value=value))
    return path


def test_written_digits_and_resolution() -> None:
    """Half a unit in the last written digit, from the text; none for an expression or
    a short decimal (a drawing's dimension, taken as exact)."""
    assert written_digits("1.85459043600322") == (15, -14)
    assert written_digits("-0.0025") == (2, -4)
    assert written_digits("1.5e-3") == (2, -4)
    assert written_digits("pi/3") is None
    assert data_resolution(15, -14) == pytest.approx(5e-15, rel=1e-12)
    assert data_resolution(15, -12, math.pi / 180) == pytest.approx(5e-13 * math.pi / 180)
    assert data_resolution(RESOLUTION_MIN_DIGITS - 1, -3) == 0.0


def test_auto_keeps_the_dead_centre_drawn_to_15_digits_singular(tmp_path: Path) -> None:
    """The dead centre drawn to 15 digits is a dead centre to auto (what the data can
    tell), decided in float by float's margins, with the written decimals' verdict at
    mp:50 said beside it."""
    path = _rounded(tmp_path)
    c = cli_json(["analyze", path, "--format", "json"])["configurations"][0]
    assert c["precision"] == "float"
    assert c["singular"] is True
    assert "input" in {s["class"] for s in c["singularities"]}
    assert all(s["precision"] == "float" for s in c["singularities"])
    below = c["data_resolution"]
    assert below["verdict_from"] == "float"
    assert below["written_decimals"] == "regular"
    assert below["digits"] == 15
    assert below["value"] < below["spread"]
    for fmt in ("text", "md"):
        rc, out, _ = run_cli(["analyze", path, "--format", fmt])
        assert rc == 0
        assert "singular in float, within the resolution of its 15-digit data" in out
        assert "give more digits or exact values to decide the written decimals" in out


def test_a_value_given_with_set_has_the_resolution_it_has_in_a_file(tmp_path: Path) -> None:
    """The same 15-digit dead centre given on the command line (``--set``) is judged as
    the file's value is: auto keeps float's singular verdict, within the resolution of
    the 15 digits written; the exact value given with --set gets no such note."""
    path = tmp_path / "set.yaml"
    path.write_text(GEOMETRY.format(units="units: {angle: deg}\n", value="0"))
    value = repr(float(f"{math.degrees(DEAD_CENTRE):.15g}"))
    doc = cli_json(["analyze", path, "--set", f"A={value}", "--format", "json"])
    (c,) = [c for c in doc["configurations"] if c["name"] == "cli"]
    assert c["singular"] is True
    below = c["data_resolution"]
    assert below["digits"] == 15 and below["verdict_from"] == "float"
    assert below["resolution"] == pytest.approx(0.5e-12 * math.pi / 180, rel=1e-9)
    exact = cli_json(["analyze", path, "--set", "A=90 + asin(1/5)*180/pi", "--format", "json"])
    (e,) = [c for c in exact["configurations"] if c["name"] == "cli"]
    assert e["singular"] is True and e.get("data_resolution") is None


def test_regular_below_the_resolution_of_15_digits(tmp_path: Path) -> None:
    precision = "mp:50"
    path = _rounded(tmp_path)
    c = cli_json(["analyze", path, "--precision", precision, "--format", "json"])["configurations"][
        0
    ]
    assert c["precision"] == "mp:50"
    assert c["singular"] is False  # the written decimals are regular ...
    below = c["data_resolution"]  # ... by less than their resolution can move them
    assert below["below_resolution"] is True
    assert below["digits"] == 15
    # the resolution: half a unit in the 15th digit of a value of about 101.5 degrees
    assert below["resolution"] == pytest.approx(0.5e-12 * math.pi / 180, rel=1e-9)
    assert below["value"] < below["spread"]
    assert any("below the resolution of its 15-digit data" in n for n in c["notes"])
    for fmt in ("text", "md"):
        rc, out, _ = run_cli(["analyze", path, "--precision", precision, "--format", fmt])
        assert rc == 0
        assert "regular at the written decimals, below the resolution of its 15-digit" in out
        assert "give more digits, exact values, or let mechsing solve it" in out


def test_float_singular_verdict_is_above_the_resolution(tmp_path: Path) -> None:
    """Float's singular verdict (a dropped value at float's rounding, far below tau_lo)
    cannot flip within the data's resolution: nothing to say."""
    c = cli_json(["analyze", _rounded(tmp_path), "--precision", "float", "--format", "json"])[
        "configurations"
    ][0]
    assert c["singular"] is True
    assert "input" in {s["class"] for s in c["singularities"]}
    assert "data_resolution" not in c


@pytest.mark.parametrize("precision", ["auto", "mp:50", "exact"])
def test_exact_dead_centre_is_singular_and_not_below_resolution(
    tmp_path: Path, precision: str
) -> None:
    c = cli_json(["analyze", _exact(tmp_path), "--precision", precision, "--format", "json"])[
        "configurations"
    ][0]
    assert c["singular"] is True
    assert "input" in {s["class"] for s in c["singularities"]}
    assert "data_resolution" not in c
    assert not any("resolution" in n for n in c.get("notes", []))


def test_report_says_the_verdict_is_below_the_resolution(tmp_path: Path) -> None:
    out = tmp_path / "review.html"
    rc, _, err = run_cli(["report", _rounded(tmp_path), "-o", out])
    assert rc == 0, err
    html = out.read_text()
    assert "below the resolution of its 15-digit data" in html


def test_geometry_written_to_16_digits_has_a_resolution_too(tmp_path: Path) -> None:
    """The pin's x = 2 sqrt(3) written to 16 digits, the crank at the exact dead-centre
    angle: mp:50 finds the written decimals off the dead centre, by less than the pin's
    resolution (half a unit in its 16th digit) can move the tests."""
    path = tmp_path / "pin.yaml"
    text = GEOMETRY.format(units="", value='"pi/2 + asin(1/5)"')
    path.write_text(text.replace('"2*sqrt(3)"', repr(float(f"{2 * math.sqrt(3):.16g}"))))
    c = cli_json(["analyze", path, "--precision", "mp:50", "--format", "json"])["configurations"][0]
    below = c["data_resolution"]
    assert below["digits"] == 16
    assert below["resolution"] == pytest.approx(0.5e-15, rel=1e-12)
    assert below["value"] < below["spread"]


@pytest.mark.parametrize(
    ("precision", "target", "beyond"),
    [
        ("auto", '"8/5 + 1e-16"', "1e-16"),
        ("mp:50", '"8/5 + 1e-16"', "1e-16"),
        ("float", "1.61", "0.01"),
    ],
)
def test_a_target_beyond_a_limit_of_travel_names_it(
    tmp_path: Path, precision: str, target: str, beyond: str
) -> None:
    """The bundled slider-crank driven by its slider: the pin on y = 7/5 reaches at most
    x = sqrt((l + r)^2 - e^2) = sqrt(25 - 49/25) = 24/5, from 16/5 at the reference, so
    the slide P stops at its outer dead centre P = 8/5.  A target beyond it has no closed
    configuration: the message names P, how far beyond and where the limit is (1e-16 m
    beyond is closed in float, to its tolerance: it fails at 50 digits, at about 1.6 m;
    0.01 m beyond stops float's continuation short of the limit, which then lies past the
    value it reached, within 1e-4 m of 1.6 m)."""
    import re

    text = (ROOT / "examples" / "slider_crank_slider_input.yaml").read_text()
    path = tmp_path / "beyond.yaml"
    path.write_text(text + f"  beyond: {{P: {target}}}\n")
    rc, out, err = run_cli(["analyze", path, "--config", "beyond", "--precision", precision])
    assert rc == 3
    assert "beyond a limit of travel" in err
    if precision != "float":
        assert f"P is {beyond} m beyond its limit at about P = 1.6 m" in err
        return
    past = re.search(
        r"P is at most ([0-9.]+) m beyond its limit, which lies past P = ([0-9.]+)", err
    )
    assert past is not None, err
    assert past.group(1) == beyond and 1.6 - 1e-4 < float(past.group(2)) < 1.6, err


ROCKER = NON_GRASHOF_ROCKER + "configurations:\n  near: {A: 27.6149}\n"


def test_an_input_beyond_its_limit_is_named_in_the_file_units(tmp_path: Path) -> None:
    """A non-Grashof four-bar (2 + 4 > 3 + sqrt 5): the crank AB stops where B, C and D
    line up, |BD| = 3 + sqrt 5, at the angle acos((4 + 16 - |BD|^2) / 16) from AD (law of
    cosines), 90 deg less from AB's reference direction; a target just beyond it is named
    with the distance and the limit in degrees, the file's unit."""
    bd = 3 + math.sqrt(5)
    limit = math.degrees(math.acos((4 + 16 - bd**2) / 16)) - 90
    path = tmp_path / "rocker.yaml"
    path.write_text(ROCKER)
    rc, _, err = run_cli(["analyze", path, "--precision", "float"])
    assert rc == 3
    assert f"A is {27.6149 - limit:.3g} deg beyond its limit at about A = {limit:.3f} deg" in err


PARALLELOGRAM = (
    "mechanism: parallelogram\n"
    + PARALLELOGRAM_JOINTS
    + """\
inputs: [A]
output: {body: rocker}
configurations:
  flat: {A: -1.57079632679490}
"""
)


def test_auto_keeps_float_when_the_written_decimals_do_not_close_at_50_digits(
    tmp_path: Path,
) -> None:
    """A parallelogram four-bar (crank and rocker 1, ground and coupler 2) with its crank
    turned to -pi/2 written to 15 digits: the crank lies along the ground line, the
    linkage flat, the change point where the parallelogram and the antiparallelogram
    branches cross (a bifurcation).  Float closes it; at 50 digits the polish from float's
    landing, at a double root, does not reach 50 digits' tolerance (the refusal reads
    1.7e-15 rad beyond a limit, less than the value's resolution).  auto keeps float's
    analysis (a bifurcation) and says what 50 digits found, instead of refusing the
    configuration."""
    path = tmp_path / "parallelogram.yaml"
    path.write_text(PARALLELOGRAM)
    c = cli_json(["analyze", path, "--format", "json"])["configurations"][0]
    assert c["precision"] == "float"
    assert "error" not in c
    assert "bifurcation" in {s["class"] for s in c["singularities"]}
    assert any("at 50 digits the written decimals did not close" in n for n in c["notes"])


@pytest.mark.parametrize("digits", [13, 15])
def test_flat_parallelogram_rounding_does_not_reach_floats_threshold(
    tmp_path: Path, digits: int
) -> None:
    """The flat parallelogram with its crank at -pi/2 written to 13 or 15 digits: the
    rounding (at most 5e-13 or 5e-15 rad) moves every test's singular values by at most
    the change of its matrix (Weyl), a unit-order rate per radian for a linkage of unit
    lengths: a few times the resolution, far from carrying the closure's dropped value
    (about 3e-13 of the largest, float's rounding) past float's lower threshold 1e-12.
    The singular verdict (a bifurcation) stands with no note of the data's resolution.
    The spread used to be 4e-9 at 15 digits (4e-7 at 13): its finite differences
    compared the input/output tests of a kernel of dimension 2 at the bifurcation with
    those of a kernel of dimension 1 beside it, which do not move continuously."""
    path = tmp_path / "parallelogram.yaml"
    path.write_text(PARALLELOGRAM.replace("-1.57079632679490", f"{-math.pi / 2:.{digits}g}"))
    c = cli_json(["analyze", path, "--precision", "float", "--format", "json"])["configurations"][0]
    assert c["singular"] is True
    assert "bifurcation" in {s["class"] for s in c["singularities"]}
    assert "data_resolution" not in c
    assert not any("resolution" in n for n in c.get("notes", []))
