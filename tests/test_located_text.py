"""At mp:N a sweep's located points, found again at N digits before their analysis, carry
those digits as text (``values_text``, ``joints_text``), as ``solve`` gives ``joints_text``;
in float they are null.  Checked against the four-bar's dead centre in closed form."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import mpmath

ROOT = Path(__file__).resolve().parents[1]


def _sweep(*extra: str) -> dict:
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1"}
    out = subprocess.run(
        [sys.executable, "-m", "mechsing", "sweep", "examples/fourbar.yaml", "--vary", "A=20:50:2"]
        + list(extra)
        + ["--format", "json"],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env=env,
        check=False,
    )
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def _dead_centre() -> mpmath.mpf:
    """The crank angle (rad) where crank AB = 1 and coupler BC = 2 sqrt 2 are in line and C is
    on the rocker's circle about D = (4, 0) of radius sqrt 5: |AC| = 1 + 2 sqrt 2 and
    |AC|^2 + 16 - 8 |AC| cos A = 5 (examples/fourbar.yaml's geometry)."""
    with mpmath.workdps(60):
        ac = 1 + 2 * mpmath.sqrt(2)
        return mpmath.acos((ac**2 + 11) / (8 * ac))


def test_mp_located_point_has_its_digits_as_text() -> None:
    doc = _sweep("--precision", "mp:30")
    (p,) = doc["located"]
    (text,) = p["values_text"]
    assert len(text.replace("-", "").replace(".", "").lstrip("0")) == 30  # N significant digits
    with mpmath.workdps(60):
        assert abs(mpmath.mpf(text) - _dead_centre()) < mpmath.mpf(10) ** -26
        # the float field is float64's rounding of the same value
        assert abs(mpmath.mpf(p["values"][0]) - mpmath.mpf(text)) < mpmath.mpf(10) ** -15
    assert set(p["joints_text"]) == {"A", "B", "C", "D"}
    assert p["joints_text"]["A"] == [text]


def test_float_located_point_has_no_text() -> None:
    (p,) = _sweep("--precision", "float")["located"]
    assert p["values_text"] is None and p["joints_text"] is None
