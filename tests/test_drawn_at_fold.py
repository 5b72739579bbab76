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
