"""The margin of a combined test does not depend on the precision (issue 44).

A test decided from two rank decisions (the input test: dim E(K cap ker T) = rank [TN; EN]
- rank TN) shows the margin of the decision nearer to flipping.  A dropped singular value
within the rounding of the precision (5e-17 in float, 5e-52 at mp:50) cannot flip: which of
the two margins is shown must not depend on it.  At the flat parallelogram with the rocker as
output (the crank along the ground line, a change point) the input test is decided the same
way in float, mp:30 and mp:50, and shows the same kept singular value."""

from __future__ import annotations

import json
import math
from pathlib import Path

from tests.cli import run_cli

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _input_margin(path: Path, precision: str) -> dict:
    run = run_cli(["analyze", path, "--precision", precision, "--format", "json"])
    assert run.status in (0, 1), run.err
    (conf,) = json.loads(run.out)["configurations"]
    assert conf["precision"] == precision
    return next(d for d in conf["decisions"] if d["test"] == "input")


def test_the_input_tests_margin_is_the_same_in_float_and_at_mp(tmp_path: Path) -> None:
    text = (EXAMPLES / "parallelogram.yaml").read_text()
    text = text[: text.index("configurations:")].replace("{body: coupler}", "{body: rocker}")
    path = tmp_path / "parallelogram_rocker.yaml"
    path.write_text(
        text + 'configurations:\n  flat: {A: "-pi/2", B: "pi/2", C: "-pi/2", D: "pi/2"}\n'
    )
    found = {p: _input_margin(path, p) for p in ("float", "mp:30", "mp:50")}
    ranks = {p: d["rank"] for p, d in found.items()}
    assert len(set(ranks.values())) == 1, ranks
    kept = {p: d["margin"]["kept"] for p, d in found.items()}
    assert all(math.isclose(k, kept["float"], rel_tol=1e-12) for k in kept.values()), kept
