"""Regressions found by an independent review, through the command line."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from mechsing.cli import main

WRIST = """mechanism: zyz-wrist
bodies: [g, a, b, c]
joints:
  - {{name: W1, type: R, between: [g, a], axis: [0, 0, 1], point: [0, 0, 1]}}
  - {{name: W2, type: R, between: [a, b], axis: [0, 1, 0], point: [0, 0, 1]}}
  - {{name: W3, type: R, between: [b, c], axis: [0, 0, 1], point: [0, 0, 1]}}
configurations:
{configs}
"""

FOURBAR = """mechanism: four-bar
bodies: [ground, crank, coupler, rocker]
joints:
  - {{name: A, type: R, between: [ground, crank],   axis: [0, 0, 1], point: [0, 0, 0]}}
  - {{name: B, type: R, between: [crank, coupler],  axis: [0, 0, 1], point: [1, 0, 0]}}
  - {{name: C, type: R, between: [coupler, rocker], axis: [0, 0, 1], point: [3, 2, 0]}}
  - {{name: D, type: R, between: [rocker, ground],  axis: [0, 0, 1], point: [4, 0, 0]}}
configurations:
{configs}
"""


def _run(
    tmp_path: Path, text: str, *args: str, capsys: pytest.CaptureFixture[str]
) -> tuple[int, str, str]:
    p = tmp_path / "m.yaml"
    p.write_text(text)
    status = main(["analyze", str(p), *args])
    out, err = capsys.readouterr()
    return status, out, err


@pytest.mark.parametrize("value", ["1.0e+300", "1e400", '"10**400"'])
def test_absurd_joint_values_are_bad_input_not_a_hang_or_traceback(
    tmp_path, capsys, value: str
) -> None:
    text = WRIST.format(configs=f"  huge: {{W1: {value}}}")
    status, _out, err = _run(tmp_path, text, "--format", "json", capsys=capsys)
    assert status == 2
    assert "Traceback" not in err and "'huge'" in err and "'W1'" in err


def test_a_loop_driven_too_far_is_refused_with_the_way_out(tmp_path, capsys) -> None:
    text = FOURBAR.format(configs="  far: {A: 5000}")  # 800 turns of the crank
    status, _out, err = _run(tmp_path, text, capsys=capsys)
    assert status == 2
    assert "intermediate configurations" in err


def test_a_tree_is_not_continued_and_works_in_exact_mode(tmp_path, capsys) -> None:
    # only W2 given: W1 and W3 keep their start values (exactly 0); nothing is solved
    text = WRIST.format(configs='  bent: {W2: "pi/3"}\n  flat: {W2: 0}')
    status, out, err = _run(
        tmp_path, text, "--precision", "exact", "--format", "json", capsys=capsys
    )
    assert status == 0, err
    conf = {c["name"]: c for c in json.loads(out)["configurations"]}
    assert conf["bent"]["singular"] is False
    # W2 = 0: axes 1 and 3 collinear, decided exactly
    (f,) = conf["flat"]["singularities"]
    assert f["class"] == "serial" and f["precision"] == "exact" and f["joints"] == ["W1", "W3"]
    assert f["margin"]["tau_lo"] == f["margin"]["tau_hi"] == 0


def test_serial_rank_is_decided_at_the_requested_precision(tmp_path, capsys) -> None:
    # W2 = 1e-14 rad: axes 1 and 3 are not collinear, so the wrist is regular; float
    # cannot see it (sigma ~ 1e-14 < tau_lo), mp:50 can (tau_hi = 1e-25)
    configs = '  e11: {W2: "1e-11"}\n  e14: {W2: "1e-14"}'
    status, out, _ = _run(
        tmp_path,
        WRIST.format(configs=configs),
        "--precision",
        "mp:50",
        "--format",
        "json",
        capsys=capsys,
    )
    assert status == 0
    for c in json.loads(out)["configurations"]:
        assert c["singular"] is False and c["precision"] == "mp:50", c["name"]
    # auto: float cannot decide 1e-11 (between the thresholds) and re-decides it at mp:50
    status, out, _ = _run(
        tmp_path, WRIST.format(configs=configs), "--format", "json", capsys=capsys
    )
    e11 = next(c for c in json.loads(out)["configurations"] if c["name"] == "e11")
    assert e11["precision"] == "mp:50" and e11["singular"] is False


def test_a_failed_start_is_named_with_its_loop(tmp_path, capsys) -> None:
    configs = "  bad: {A: 30, B: 0, C: 0, D: 0}\n  next: {A: 40, start: bad}"
    status, out, err = _run(
        tmp_path, FOURBAR.format(configs=configs), "--format", "json", capsys=capsys
    )
    assert status == 3
    errors = {c["name"]: c.get("error", "") for c in json.loads(out)["configurations"]}
    assert "loop A-B-C-D" in errors["bad"]
    assert errors["next"].startswith(
        "configuration 'next' starts from 'bad', which could not be closed"
    )
    assert "Traceback" not in err


def test_reported_vectors_have_no_rounding_signs(tmp_path, capsys) -> None:
    text = """mechanism: planar-3R
bodies: [g, a, b, c]
joints:
  - {name: J1, type: R, between: [g, a], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J2, type: R, between: [a, b], axis: [0, 0, 1], point: [1, 0, 0]}
  - {name: J3, type: R, between: [b, c], axis: [0, 0, 1], point: [2, 0, 0]}
configurations:
  reference: {}
"""
    status, out, _ = _run(tmp_path, text, "--format", "json", capsys=capsys)
    assert status == 0
    (f,) = json.loads(out)["configurations"][0]["singularities"]
    for vec in [*f["wrenches"], f["twist"]]:
        nz = [x for x in vec if x != 0]
        assert nz and nz[0] > 0  # first non-zero component positive, noise reported as 0
        assert all(x == 0 or abs(x) > 1e-9 * max(map(abs, vec)) for x in vec)
    # three collinear joints: the null rates are (1, -2, 1) / 2, up to normalisation
    rates = f["null_joint_rates"]
    assert rates == pytest.approx([0.5, -1.0, 0.5], abs=1e-12)
