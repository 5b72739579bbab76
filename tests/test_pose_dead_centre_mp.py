"""A pose given at a dead centre is decided at every mp:N (issue 44).

The bundled slider-crank driven by its crank reaches its outer dead centre when crank and rod
line up: the slider at P = 8/5, the pin C at (16/5 + 8/5, 7/5) = (24/5, 7/5), the crank at
A = 2 atan(4/3) (the file's comment, law of cosines).  Given as the slider's pose (its
reference point, the pin C, at (24/5, 7/5, 0)), the configuration is a double root of the
closure: N digits of residual place it only to 10^(-N/2), where the input test's rank lies
between mp:N's thresholds.  Polished again at 2N + 10 digits, as given joint values are, it
is decided: a type I (input) singularity, the leg stretched (serial)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from tests.cli import run_cli

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


@pytest.mark.parametrize("precision", ["mp:30", "mp:50"])
def test_a_slider_dead_centre_given_by_its_pose_is_decided_at_mp(tmp_path, precision):
    text = (EXAMPLES / "slider_crank_crank_input.yaml").read_text()
    path = tmp_path / "pose_dead_centre.yaml"
    path.write_text(
        text[: text.index("configurations:")]
        + 'configurations:\n  reference: {}\n  dc: {pose: {position: ["24/5", "7/5", 0]}}\n'
    )
    run = run_cli(["analyze", path, "--precision", precision, "--config", "dc", "--format", "json"])
    assert run.status in (0, 1), run.err
    (conf,) = json.loads(run.out)["configurations"]
    assert conf.get("undecided", []) == [] and not any(
        d["rank"] is None for d in conf["decisions"]
    ), conf["decisions"]
    assert math.isclose(conf["joints"]["A"][0], 2 * math.atan(4 / 3), abs_tol=1e-14)
    assert math.isclose(conf["joints"]["P"][0], 8 / 5, abs_tol=1e-14)
    assert {s["class"] for s in conf["singularities"]} == {"input", "impossible-output", "serial"}
