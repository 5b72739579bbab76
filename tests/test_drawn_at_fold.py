"""A configuration drawn at a fold to its data's digits, at an explicit mp:N (issue 44).

The double rocker of examples/double_rocker.yaml has its input's limits at A = +-2 pi/3
(law of cosines in the file's comment: B, C, D aligned, |BD| = 7): there the output can
move with the input locked (Gosselin-Angeles type II).  Written to 15 digits, 2 pi/3 rounds
up to 2.09439510239320, 4.5e-15 rad beyond the limit and within the value's resolution
(5e-15): mp:50 analyses the limit itself, placed at 50 digits, and says so, instead of
refusing "beyond a limit of travel".  The flat parallelogram given by its input at 15 digits
(-1.57079632679490, 3.2e-15 from -pi/2, where the parallelogram and anti-parallelogram
branches cross) is analysed at the nearest closed configuration, not refused."""

from __future__ import annotations

import json
import math
from pathlib import Path

from tests.cli import run_cli

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _with_configuration(tmp_path: Path, example: str, line: str) -> Path:
    text = (EXAMPLES / example).read_text()
    head = text[: text.index("configurations:")]
    out = tmp_path / example
    out.write_text(head + "configurations:\n  reference: {}\n" + line + "\n")
    return out


def test_double_rocker_drawn_at_its_limit_is_analysed_at_the_limit_at_mp50(tmp_path):
    path = _with_configuration(tmp_path, "double_rocker.yaml", "  limit: {A: 2.09439510239320}")
    run = run_cli(
        ["analyze", path, "--precision", "mp:50", "--config", "limit", "--format", "json"]
    )
    assert run.status in (0, 1), run.err
    assert "beyond a limit of travel" not in run.err
    (conf,) = json.loads(run.out)["configurations"]
    assert "error" not in conf
    # the limit in closed form: A = 2 pi/3
    assert math.isclose(conf["joints"]["A"][0], 2 * math.pi / 3, abs_tol=1e-15)
    classes = {s["class"] for s in conf["singularities"]}
    assert "output" in classes  # type II at a limit of the input (Gosselin-Angeles 1990)
    out = next(d for d in conf["decisions"] if d["test"] == "output")
    assert out["margin"]["dropped"] is not None and out["margin"]["dropped"] < 1e-40
    assert any("within the resolution of its 15-digit data" in n for n in conf["notes"])
    assert not any("float places them only" in n for n in conf["notes"])


def test_flat_parallelogram_given_by_its_input_to_15_digits_is_not_refused_at_mp50(tmp_path):
    path = _with_configuration(tmp_path, "parallelogram.yaml", "  flat: {A: -1.57079632679490}")
    run = run_cli(["analyze", path, "--precision", "mp:50", "--config", "flat", "--format", "json"])
    assert run.status in (0, 1), run.err
    assert "beyond" not in run.err
    (conf,) = json.loads(run.out)["configurations"]
    assert "error" not in conf
    assert abs(conf["joints"]["A"][0] + math.pi / 2) < 5e-15  # within the data's resolution
    assert any("nearest closed configuration" in n for n in conf["notes"])


WRIST_AT_A_POSE = """\
mechanism: zyz-wrist
bodies: [g, a, b, c]
joints:
  - {name: W1, type: R, between: [g, a], axis: [0, 0, 1], point: [0, 0, 1]}
  - {name: W2, type: R, between: [a, b], axis: [0, 1, 0], point: [0, 0, 1]}
  - {name: W3, type: R, between: [b, c], axis: [0, 0, 1], point: [0, 0, 1]}
output: {body: c}
configurations:
  reference: {}
  drawn: {pose: {rotation_vector: [5.8e-18, 0, 0.500000000000000]}}
"""


def test_a_wrist_given_by_a_pose_drawn_at_its_singularity_is_analysed_there_at_mp50(tmp_path):
    """A Z-Y-Z spherical wrist given the output's rotation vector (5.8e-18, 0, 0.5), its
    rotation written to 15 digits (known to 5e-16 rad): within that, the rotation is the
    turn by 0.5 rad about z, where the Z-Y-Z angles are W2 = 0, W1 + W3 = 0.5 (the wrist's
    singularity: axes W1 and W3 aligned, the chain of rank 2).  Continuation at 50 digits
    from the reference (W2 = 0 already) stops there, the lost direction being the one the
    5.8e-18 asks for; the analysis is of the nearest closed configuration, with a note, not
    a refusal "beyond a limit of travel"."""
    path = tmp_path / "wrist.yaml"
    path.write_text(WRIST_AT_A_POSE)
    run = run_cli(
        ["analyze", path, "--precision", "mp:50", "--config", "drawn", "--format", "json"]
    )
    assert run.status in (0, 1), run.err
    assert "beyond a limit of travel" not in run.err
    (conf,) = json.loads(run.out)["configurations"]
    assert "error" not in conf
    joints = conf["joints"]
    assert abs(joints["W2"][0]) < 1e-40  # the Z-Y-Z middle angle of a turn about z
    assert math.isclose(joints["W1"][0] + joints["W3"][0], 0.5, abs_tol=1e-15)
    assert conf["singular"] is True
    assert {s["class"] for s in conf["singularities"]} == {"serial"}
    (serial,) = conf["singularities"]
    assert serial["corank"] == 1 and serial["margin"]["dropped"] < 1e-40
    (note,) = [n for n in conf["notes"] if "written pose" in n]
    assert "within the resolution of its 15-digit data (its rotation to 5e-16 rad)" in note
    assert "pose.rx moved by 5.8e-18 rad" in note
