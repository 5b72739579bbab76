"""The display floor: text and reports show as 0 every length below the closure tolerance of
the configuration's precision (1e-12 L in float, min(10^(15-N), 10^-12) L at mp:N) and
every angle below that divided by L; the JSON keeps the numbers.  The bundled examples are
analysed and reported as a user runs them."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from mechsing.numeric import display_floor, floored
from tests.cli import run_cli_subprocess

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted(
    p.name for p in (ROOT / "examples").iterdir() if p.suffix in (".yaml", ".xml", ".urdf")
)
NUMBER = re.compile(r"-?\d+(?:\.\d*)?(?:e[-+]?\d+)?")
#: the lines that show lengths and angles (singular values and margins are the rank
#: decisions' evidence, dimensionless, compared with the thresholds printed beside them)
VALUE_LINES = ("joint values", "closure residual", "given pose")


def _run(*args: str) -> str:
    run = run_cli_subprocess(list(args))
    assert run.status in (0, 3), run.err
    return run.out


def test_floor_follows_the_closure_tolerance() -> None:
    assert display_floor("float", 2.0) == pytest.approx(2e-12)
    assert display_floor("mp:50", 2.0) == pytest.approx(2e-35)
    # mp:20 would allow 10^-5 L: never looser than float's 1e-12 L
    assert display_floor("mp:20", 2.0) == pytest.approx(2e-12)
    assert display_floor("exact", 2.0) == 0.0
    assert floored(-7.6e-17, 1e-12) == 0.0
    assert str(floored(-1e-30, 1e-12)) == "0.0"  # never -0
    assert floored(3e-12, 1e-12) == 3e-12


def _tiny(text: str, L: float) -> list[str]:
    """The numbers shown below the floor of their configuration's precision, in the
    lines that show lengths and angles."""
    bad, floor = [], display_floor("float", L)
    for line in text.splitlines():
        head = re.match(r"\s*(?:#+ )?Configuration \S+ \((\S+)\)", line)
        if head:
            floor = display_floor(head.group(1), L)
            continue
        if not any(k in line for k in VALUE_LINES):
            continue
        values = line.split(":", 1)[1] if ":" in line else line
        for tok in NUMBER.findall(values):
            x = float(tok)
            if x != 0 and abs(x) < min(floor, floor / L):
                bad.append(f"{tok} in {line.strip()}")
    return bad


@pytest.mark.parametrize("example", EXAMPLES)
def test_analysis_text_shows_no_round_off(example: str) -> None:
    path = f"examples/{example}"
    doc = json.loads(_run("analyze", path, "--format", "json"))
    L = doc["precision"]["length_scale"]
    assert _tiny(_run("analyze", path), L) == []


@pytest.mark.parametrize("example", ["stewart_octahedral.yaml", "puma560.yaml"])
def test_report_shows_no_round_off(example: str, tmp_path: Path) -> None:
    path = f"examples/{example}"
    doc = json.loads(_run("analyze", path, "--format", "json"))
    L = doc["precision"]["length_scale"]
    out = tmp_path / "review.md"
    _run("report", path, "-o", str(out))
    text = out.read_text(encoding="utf-8")
    # the report's configuration headings carry no precision: each says it in its findings
    assert "joint values" in text
    assert _tiny(text, L) == []
