"""``mechsing condition`` at its edges, through the command line.

Expected formulas are worked by hand from each file's geometry (named in each test), never
taken from mechsing.
"""

from __future__ import annotations

import json
from pathlib import Path

from tests.cli import run_cli

#: a four-bar whose rocker pivots lie at x = sqrt(a + 4), a radical of the symbolic a:
#: A at the origin, B = (0, 1), C = (sqrt(a + 4), 2), D = (sqrt(a + 4), 0)
FOURBAR_RADICAL = """\
mechanism: fourbar-radical
parameters: {a: 1}
bodies: [ground, crank, coupler, rocker]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, coupler], axis: [0, 0, 1], point: [0, 1, 0]}
  - {name: C, type: R, between: [coupler, rocker], axis: [0, 0, 1], point: ["sqrt(a + 4)", 2, 0]}
  - {name: D, type: R, between: [rocker, ground], axis: [0, 0, 1], point: ["sqrt(a + 4)", 0, 0]}
inputs: [A]
output: {body: rocker}
"""


def test_a_radical_in_a_joints_point_shows_the_parameters_name(tmp_path: Path) -> None:
    path = tmp_path / "fourbar.yaml"
    path.write_text(FOURBAR_RADICAL, encoding="utf-8")
    for fmt in ("text", "json", "md"):
        run = run_cli(["condition", path, "--symbolic", "a", "--format", fmt])
        assert run.status == 0, run.err
        assert "_a" not in run.out, run.out  # a sympy Dummy prints as _a
        assert "sqrt(a + 4)" in run.out or "\\sqrt{a + 4}" in run.out
    doc = json.loads(run_cli(["condition", path, "--symbolic", "a", "--format", "json"]).out)
    # the input condition: B - A = (0, 1) and C - B = (sqrt(a + 4), 1) rotated by the
    # crank's angle B about B: in line when cross((0, 1), (sqrt(a+4) cos B - sin B, ...)) = 0
    first = doc["conditions"][0]["factors"][0]["expression"]
    assert first.replace(" ", "") in ("sqrt(a+4)*cos(B)-sin(B)", "-sin(B)+sqrt(a+4)*cos(B)")
