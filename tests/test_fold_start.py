"""Continuation from a start drawn at a fold of the given values.

A centred slider-crank (crank 1, rod 3) drawn at its outer dead centre: crank and rod
along +x, the slider pin at x = 4.  The slider's displacement P is at its maximum there
(P = 0): P < 0 is reachable on two assembly modes (the crank above or below the slide),
P > 0 on none.  With the pin at x = 4 + P, the law of cosines in the triangle
(origin, crank pin, slider pin) gives the crank angle: cos A = (1 + x^2 - 9) / (2 x).
Continuation must leave the start (where no predictor step moves: the unknown joints'
Jacobian is one rank short) along one of the two modes, and still refuse P > 0.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from tests.cli import run_cli

DEAD_CENTRE = """\
mechanism: dead-centre-start
bodies: [ground, crank, rod, slider]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, rod], axis: [0, 0, 1], point: [1, 0, 0]}
  - {name: C, type: R, between: [rod, slider], axis: [0, 0, 1], point: [4, 0, 0]}
  - {name: P, type: P, between: [ground, slider], axis: [1, 0, 0]}
inputs: [P]
output: {body: crank}
configurations:
  reference: {}
  back: {P: -0.5}
  beyond: {P: 0.1}
"""


def test_continuation_leaves_a_start_drawn_at_a_dead_centre(tmp_path: Path) -> None:
    path = tmp_path / "dead.yaml"
    path.write_text(DEAD_CENTRE)
    rc, out, err = run_cli(["analyze", path, "--config", "back", "--format", "json"])
    assert rc == 0, err
    (c,) = json.loads(out)["configurations"]
    x = 4 - 0.5
    crank = math.acos((1 + x**2 - 9) / (2 * x))  # either mode: A = +-crank
    A = c["joints"]["A"][0]
    assert abs(abs(A) - crank) < 1e-12
    # the rod's angle from +x: the crank pin at (cos A, sin A), the slider pin at (x, 0)
    rod = math.atan2(-math.sin(A), x - math.cos(A))
    assert abs((A + c["joints"]["B"][0]) - rod) < 1e-12
    assert c["closure_residual"] < 1e-12
    assert any("is a fold of the given values" in n for n in c["notes"])


def test_a_target_beyond_the_dead_centre_start_is_still_refused(tmp_path: Path) -> None:
    path = tmp_path / "dead.yaml"
    path.write_text(DEAD_CENTRE)
    rc, _, err = run_cli(["analyze", path, "--config", "beyond"])
    assert rc == 3
    assert "is a fold of the given values" in err and "the target lies beyond it" in err


def test_a_sweep_leaves_a_start_at_a_dead_centre_along_the_curve(tmp_path: Path) -> None:
    """A sweep of P over [-2.5, 0.5] from the start drawn at P = 0 (the outer dead centre,
    a sample of the sweep): both ways along the curve lead to P < 0, so the sweep steps
    off the start onto one mode and reaches every P in [-2, 0] (the pin at x = 4 + P meets
    the crank circle for 2 <= x <= 4), with the limits of travel at P = 0 (x = 1 + 3) and
    P = -2 (x = 3 - 1)."""
    import numpy as np

    from mechsing.sweeps import sweep

    path = tmp_path / "dead.yaml"
    path.write_text(DEAD_CENTRE)
    r = sweep(path, ["P=-2.5:0.5:0.01"])
    P = r.variables[0].values
    inside = (P >= -2 - 1e-9) & (P <= 1e-9)
    assert np.array_equal(r.reached, inside), P[r.reached != inside]
    folds = sorted(p.values[0] for p in r.located if p.kind == "fold")
    assert len(folds) == 2 and abs(folds[0] + 2) < 1e-10 and abs(folds[1]) < 1e-10
