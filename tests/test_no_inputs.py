"""No inputs, still a sweep: an open chain that names an output and no inputs (the 3R
wrist of exercise 05) has one test whose ingredients it has, the rank of its output
chain, and a sweep measures it and locates where it drops, as `analyze` finds it at one
configuration.

The wrist's three axes pass through one point: J4 and J6 along the same direction a and
J5 along b, perpendicular to it (read from the file by the reference reader).  With J4
and J6 held, turning J5 by t carries J6's axis to R_b(t) a = cos(t) a + sin(t) (b x a)
(Rodrigues, a . b = 0), which is parallel to J4's axis a exactly where sin(t) = 0: the
three rotation axes are then coplanar and the chain's rank is 2 instead of 3, at
t = 0 and t = pi on the range 0..6 rad, and nowhere else.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from tests.cli import run_cli
from tests.reference.files import MechanismFile

ROOT = Path(__file__).resolve().parents[1]
WRIST = ROOT / "examples" / "exercises" / "05-wrist-singularity" / "mechanism.yaml"


def wrist_axes() -> dict[str, np.ndarray]:
    f = MechanismFile(WRIST)
    return {j.name: np.asarray(j.prm["axis"], dtype=float) for j in f.joints}


def test_the_wrist_is_as_the_closed_form_assumes():
    ax = wrist_axes()
    np.testing.assert_allclose(np.cross(ax["J4"], ax["J6"]), 0, atol=1e-15)
    assert abs(ax["J4"] @ ax["J5"]) < 1e-15


def test_a_sweep_without_inputs_locates_the_wrist_singularities():
    r = run_cli(
        [
            "sweep",
            WRIST,
            "--vary",
            "J5=0:6:0.3",
            "--format",
            "json",
            "--quiet",
            "--precision",
            "float",
        ]
    )
    assert r.status == 0, r.err
    d = json.loads(r.out)
    located = sorted(d["located"], key=lambda p: p["values"][0])
    # sin(t) = 0 on [0, 6]: t = 0 and t = pi
    np.testing.assert_allclose([p["values"][0] for p in located], [0.0, math.pi], atol=1e-9)
    assert all("serial" in p["classes"] for p in located), located


def test_the_report_of_that_sweep_is_written(tmp_path):
    out = tmp_path / "wrist.md"
    r = run_cli(["report", WRIST, "--vary", "J5=0:6:0.3", "--precision", "float", "-o", out])
    assert r.status == 0, r.err
    assert "No singularity located" not in out.read_text()
