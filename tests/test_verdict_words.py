"""Verdicts in words that do not mislead (issue 27, items 9, 10 and 16)."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.cli import cli_json, run_cli

#: an in-line slider-crank drawn at its outer dead centre: A, B and C on the x axis
#: (crank 1, rod 4), the slider as input and the crank as output.  With crank and rod
#: collinear the slider's rate is zero whatever the crank's rate: with the slider locked
#: the crank can still turn (an output singularity, type II), and the dropped singular
#: value is exactly zero (every screw is exact: points on the axes, axes along z and x)
INLINE = """\
mechanism: inline-slider-crank
bodies: [ground, crank, rod, slider]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, rod], axis: [0, 0, 1], point: [1, 0, 0]}
  - {name: C, type: R, between: [rod, slider], axis: [0, 0, 1], point: [5, 0, 0]}
  - {name: P, type: P, between: [ground, slider], axis: [1, 0, 0]}
inputs: [P]
output: {body: crank}
configurations:
  reference: {}
"""


@pytest.mark.parametrize("precision", ["float", "exact"])
def test_an_exactly_singular_output_finding_shows_its_dropped_zero(
    tmp_path: Path, precision: str
) -> None:
    path = tmp_path / "inline.yaml"
    path.write_text(INLINE)
    c = cli_json(["analyze", path, "--precision", precision, "--format", "json"])["configurations"][
        0
    ]
    (out,) = [s for s in c["singularities"] if s["class"] == "output"]
    assert out["margin"]["dropped"] == 0.0
    rc, text, _ = run_cli(["analyze", path, "--precision", precision])
    assert rc == 0
    block = text[text.index("  output: with the inputs locked") :]
    margin_line = next(line for line in block.splitlines() if "margin:" in line)
    assert "dropped 0 " in margin_line and "dropped -" not in margin_line


def test_exact_report_says_which_tests_ran_at_mp50(tmp_path: Path) -> None:
    """Exact mode runs the input/output tests at mp:50 from the exact data: the verdict
    table says so rather than "exact" for them."""
    path = tmp_path / "inline.yaml"
    path.write_text(INLINE)
    out = tmp_path / "review.md"
    rc, _, err = run_cli(["report", path, "--precision", "exact", "-o", out])
    assert rc == 0, err
    row = next(line for line in out.read_text().splitlines() if line.startswith("| **reference**"))
    assert "exact (the " in row and "tests at mp:50)" in row
    assert "output" in row.split("exact (the ")[1]
