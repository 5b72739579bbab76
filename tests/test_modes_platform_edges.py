"""mechsing modes on a six-leg platform at extreme slides (issue 44): out of reach is 0
modes, proven by the triangle inequality computed here from the file's own data; slides
that put the system beyond double-precision tracking are refused with exit 3, not a
defect's exit 4."""

from __future__ import annotations

import json

import numpy as np
import pytest
import yaml

from tests.cli import run_cli
from tests.mechanisms import ROOT

DIETMAIER = ROOT / "examples" / "stewart_dietmaier.yaml"


def test_a_leg_out_of_the_others_reach_gives_no_mode() -> None:
    """P1 = 1000 m, the others 0: leg 1 is then ~1000 m long and leg 2 about 1 m, but
    |l1 - l2| <= |a1 - a2| + |b1 - b2| at every pose: no mode, proven without tracking."""
    joints = {j["name"]: j for j in yaml.safe_load(DIETMAIER.read_text())["joints"]}

    def length(i: int, slide: float) -> float:
        a, b = (np.array(joints[f"{k}{i}"]["point"], float) for k in ("U", "S"))
        u = np.array(joints[f"P{i}"]["axis"], float)
        return float(np.linalg.norm(b - a + slide * u / np.linalg.norm(u)))

    a1, a2 = (np.array(joints[f"U{i}"]["point"], float) for i in (1, 2))
    b1, b2 = (np.array(joints[f"S{i}"]["point"], float) for i in (1, 2))
    assert abs(length(1, 1000) - length(2, 0)) > np.linalg.norm(a1 - a2) + np.linalg.norm(b1 - b2)
    argv = ["modes", str(DIETMAIER), "--set", "P1=1000"]
    argv += [f"--set=P{i}=0" for i in range(2, 7)]
    rc, out, err = run_cli([*argv, "--format", "json"])
    assert rc == 0, err
    doc = json.loads(out)
    assert doc["count"] == 0 and doc["complete"] == "proven" and doc["modes"] == []
    assert doc["paths"] is None  # nothing tracked


def test_slides_beyond_double_precision_are_refused_not_a_defect() -> None:
    pytest.importorskip("bertini")
    argv = ["modes", str(DIETMAIER)] + [f"--set=P{i}=1e5" for i in range(1, 7)]
    rc, _, err = run_cli(argv)
    assert rc == 3, err
    assert "stewart_dietmaier.yaml" in err and "homotopy continuation" in err
    assert "defect" not in err
