"""No output, no silence (issue 27, item 7): a closed chain with inputs and no output runs
every test whose ingredients it has (the inputs' rank on the motion space: where an input
loses its independent rate) and says in every format which tests were not run, and why.

The four-bar of tests/data/fourbar_rocker_input.yaml is driven by its rocker and names no
output.  The rocker's toggles come from the file's joint points (the reference reader)
and the law of cosines alone: crank and coupler are in line there, |AC| = |BC| +- |AB|;
turning the rocker by D about its pivot P moves C to P + R(D)(C0 - P), so
|AC|^2 = |d|^2 + |r|^2 + 2 rho cos(D + phi) (d = P - A, r = C0 - P,
rho cos phi = d.r, rho sin phi = (d x r)_z).  At a toggle the
rocker's rate is zero along the mechanism's only motion: the input's rank on the motion
space is 0 instead of 1 (impossible-input).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from tests.cli import run_cli
from tests.reference.files import MechanismFile

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data" / "fourbar_rocker_input.yaml"
MJCF = ROOT / "examples" / "fourbar_mjcf.xml"
NOT_RUN = "no output: the output tests were not run"


def rocker_toggles() -> list[float]:
    """The rocker turns (rad, within half a turn of the drawing) where crank and coupler
    are in line."""
    f = MechanismFile(DATA)
    pt = {j.name: np.asarray(j.prm["point"], dtype=float)[:2] for j in f.joints}
    A, B, C, P = pt["A"], pt["B"], pt["C"], pt["D"]
    ab, bc = np.linalg.norm(B - A), np.linalg.norm(C - B)
    d, r = P - A, C - P
    rho = math.hypot(d @ r, d[0] * r[1] - d[1] * r[0])
    phi = math.atan2(d[0] * r[1] - d[1] * r[0], d @ r)
    out = []
    for reach in (bc + ab, bc - ab):
        c = (reach**2 - d @ d - r @ r) / (2 * rho)
        for s in (1, -1):
            v = math.remainder(-phi + s * math.acos(c), 2 * math.pi)
            out.append(v)
    # the two toggles of the swing through the drawing (D = 0 lies between them)
    below = max(v for v in out if v < 0)
    above = min(v for v in out if v > 0)
    return [below, above]


def test_the_rocker_toggles_are_input_singularities_without_an_output():
    toggles = rocker_toggles()
    r = run_cli(["sweep", DATA, "--vary", "D=-0.5:1.2:0.01", "--format", "json", "--quiet"])
    assert r.status == 0, r.err
    d = json.loads(r.out)
    folds = sorted((p for p in d["located"] if p["kind"] == "fold"), key=lambda p: p["values"])
    np.testing.assert_allclose([p["values"][0] for p in folds], toggles, atol=1e-10)
    assert [p["classes"] for p in folds] == [["impossible-input"], ["impossible-input"]]
    assert any(NOT_RUN in n for n in d["notes"]), d["notes"]


def test_analyze_says_which_tests_were_not_run_in_text_and_json():
    r = run_cli(["analyze", DATA, "--format", "json"])
    assert r.status == 0, r.err
    d = json.loads(r.out)
    (entry,) = d["tests_not_run"]
    assert entry["reason"] == NOT_RUN
    assert set(entry["tests"]) == {
        "input",
        "output",
        "passive-motion",
        "impossible-output",
        "constraint",
        "serial",
    }
    # the test that needs only the inputs ran
    assert any(x["test"] == "impossible-input" for x in d["configurations"][0]["decisions"])
    text = run_cli(["analyze", DATA]).out
    assert f"Tests not run: {NOT_RUN}" in text


def test_an_mjcf_model_names_no_output_and_says_so():
    d = json.loads(run_cli(["analyze", MJCF, "--format", "json"]).out)
    assert [e["reason"] for e in d["tests_not_run"]] == [NOT_RUN]


def test_a_file_with_inputs_and_an_output_ran_every_test():
    d = json.loads(run_cli(["analyze", ROOT / "examples" / "fourbar.yaml", "--format", "json"]).out)
    assert d["tests_not_run"] == []


@pytest.mark.parametrize("suffix", [".md", ".html"])
def test_the_report_verdict_says_which_tests_were_not_run(tmp_path, suffix):
    out = tmp_path / f"review{suffix}"
    r = run_cli(["report", DATA, "--vary", "D=-0.5:1.2:0.05", "-o", out])
    assert r.status == 0, r.err
    text = out.read_text()
    assert f"Tests not run: {NOT_RUN}" in text
    assert "rows are regular" not in text
