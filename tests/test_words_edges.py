"""The words of ``analyze`` and ``sweep`` at their edges, through the command line: the
efforts' unit read as a kind of input, a slider's dead centre named as a crank's, and a
point output swept along x with y held (it has no rotation to hold).

Expected values are closed forms: the slider-crank's outer dead centre (the crank pin B =
(24/25, 7/25) and the slider's pin C = (24/5, 7/5) in line with the crank's pivot A at the
origin) and the five-bar's reach (the left leg's pivots A1 = (-3/2, 0), proximal 2 and distal
5/2 m long, the output point at y = 4: x = sqrt(17)/2 - 3/2 where the leg stretches).
"""

from __future__ import annotations

import json
import math

from tests.cli import run_cli
from tests.mechanisms import ROOT

EXAMPLES = ROOT / "examples"


def test_unbounded_efforts_name_the_kind_of_input() -> None:
    run = run_cli(
        [
            "analyze",
            EXAMPLES / "planar_3rpr.yaml",
            "--config",
            "concurrent",
            "--precision",
            "float",
            "--load",
            "moment=0,0,1",
        ]
    )
    assert run.status == 0, run.err
    assert "unbounded for the prismatic inputs (N)" in run.out
    assert "unbounded for N inputs" not in run.out


def _findings(argv: list) -> list[dict]:
    run = run_cli([*argv, "--format", "json"])
    assert run.status == 0, run.err
    (config,) = json.loads(run.out)["configurations"]
    return config["singularities"]


def test_a_sliders_dead_centre_is_named_as_a_cranks() -> None:
    # the dead centre of the file: A = 2 atan(4/3) turns B = (0, -1) to (sin A, -cos A)
    a = 2 * math.atan(4 / 3)
    b = (math.sin(a), -math.cos(a))
    c = (24 / 5, 7 / 5)
    assert abs(b[0] * c[1] - b[1] * c[0]) < 1e-12  # A, B and C in line
    name = "leg fully stretched or folded"
    slider = _findings(
        ["analyze", EXAMPLES / "slider_crank_slider_input.yaml", "--config", "dead-centre"]
    )
    (output,) = [f for f in slider if f["class"] == "output"]
    assert output["name"] == name and output["joints"] == ["A", "B", "C"]
    crank = _findings(
        ["analyze", EXAMPLES / "slider_crank_crank_input.yaml", "--config", "dead-centre"]
    )
    assert name in {f.get("name") for f in crank}
    run = run_cli(
        ["analyze", EXAMPLES / "slider_crank_slider_input.yaml", "--config", "dead-centre"]
    )
    assert f"output: {name} (its pivots in line): with the inputs locked" in run.out
    # a regular configuration has no name to give
    assert (
        _findings(["analyze", EXAMPLES / "slider_crank_slider_input.yaml", "--config", "slider-4"])
        == []
    )


def test_a_point_output_swept_along_x_holds_y() -> None:
    run = run_cli(
        ["sweep", EXAMPLES / "five_bar.yaml", "--vary", "pose.x=0:2:0.1", "--format", "json"]
    )
    assert run.status == 0, run.err
    doc = json.loads(run.out)
    assert doc["held"] == ["pose.y", "pose.z"]
    (located,) = doc["located"]
    assert abs(located["values"][0] - (math.sqrt(17) / 2 - 1.5)) < 1e-6
    assert "input" in located["classes"]
