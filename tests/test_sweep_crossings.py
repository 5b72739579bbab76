"""Never miss a crossing: every singular value that falls is followed, samples that are
themselves singular are listed, a point is located once and a locus through the grid's
samples is one curve.  Checked against closed forms of each geometry."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from mechsing.sweeps import sweep

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"

#: how well a located value must match its closed form
LOCATED = 1e-9

#: a planar 2R arm, links 1 and 0.5: singular where sin(theta2) = 0
ARM_2R = """mechanism: arm2r
dh:
  convention: standard
  rows:
    - {theta: 0, d: 0, a: 1, alpha: 0}
    - {theta: 0, d: 0, a: 0.5, alpha: 0}
output: {body: L2, point: [1.5, 0, 0]}
configurations:
  bent: {J1: 0.3, J2: 1.0}
"""

#: a 3-RPR whose platform triangle is the base's halved about c = (1, 1) (a homothety):
#: at the reference orientation (pose.rz = 0) every leg line passes through the
#: homothety's centre, wherever the platform is: a type II line rz = 0 across the grid
RPR_HOMOTHETIC = """mechanism: rpr-homothetic
bodies: [ground, cyl1, pis1, cyl2, pis2, cyl3, pis3, platform]
joints:
  - {name: Rb1, type: R, between: [ground, cyl1],   axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: P1, type: P, between: [cyl1, pis1],     axis: ["1/2", "1/2", 0]}
  - {name: Rp1, type: R, between: [pis1, platform], axis: [0, 0, 1], point: ["1/2", "1/2", 0]}
  - {name: Rb2, type: R, between: [ground, cyl2],   axis: [0, 0, 1], point: [4, 0, 0]}
  - {name: P2, type: P, between: [cyl2, pis2],     axis: ["-3/2", "1/2", 0]}
  - {name: Rp2, type: R, between: [pis2, platform], axis: [0, 0, 1], point: ["5/2", "1/2", 0]}
  - {name: Rb3, type: R, between: [ground, cyl3],   axis: [0, 0, 1], point: [0, 4, 0]}
  - {name: P3, type: P, between: [cyl3, pis3],     axis: ["1/2", "-3/2", 0]}
  - {name: Rp3, type: R, between: [pis3, platform], axis: [0, 0, 1], point: ["1/2", "5/2", 0]}
inputs: [P1, P2, P3]
output: {body: platform}
configurations:
  turned: {pose: {rotation_vector: [0, 0, "3/10"]}}
"""


def _ur5_singular_j3(theta2: float, theta4: float, lo: float, hi: float) -> list[float]:
    """The UR5's elbow (sin theta3 = 0) and shoulder (a2 cos t2 + a3 cos(t2 + t3) +
    d5 sin(t2 + t3 + t4) = 0) values of theta3 in [lo, hi] with theta2, theta4 (and a
    regular wrist) held: Universal Robots' DH table, solved in closed form."""
    a2, a3, d5 = -0.425, -0.39225, 0.09465
    out = [k * math.pi for k in range(-3, 4) if lo <= k * math.pi <= hi]
    # A cos(phi) + B sin(phi) = C with phi = theta2 + theta3
    A, B, C = a3 + d5 * math.sin(theta4), d5 * math.cos(theta4), -a2 * math.cos(theta2)
    R, delta = math.hypot(A, B), math.atan2(B, A)
    for s in (1, -1):
        phi = delta + s * math.acos(C / R)
        for k in range(-3, 4):
            t3 = phi - theta2 + 2 * k * math.pi
            if lo <= t3 <= hi:
                out.append(t3)
    return sorted(out)


def test_ur5_elbow_after_its_shoulder_is_located():
    """From 'regular' the path over J3 meets the shoulder just before the elbow at pi: the
    elbow's singular value falls while the weakest one (the shoulder's) rises again.
    Every elbow and shoulder value in [0, 6] is located, J3 = 0 (a sample) included."""
    r = sweep(EXAMPLES / "ur5.yaml", ["J3=0:6:0.3"], from_config="regular")
    want = _ur5_singular_j3(-math.pi / 4, -math.pi / 4, 0.0, 6.0)
    got = sorted(p.values[0] for p in r.located if "input" in p.tests)
    assert len(want) == 4
    assert len(got) == len(want)
    np.testing.assert_allclose(got, want, atol=LOCATED)
    elbows = [p for p in r.located if min(abs(p.values[0]), abs(p.values[0] - math.pi)) < 1e-6]
    assert len(elbows) == 2 and all("serial" in (p.classes or ()) for p in elbows)


def test_2r_grid_locates_each_point_once_and_joins_its_lines(tmp_path):
    """A 2R grid whose samples include theta2 = 0: the elbow lines theta2 = -pi, 0, pi
    cross each of the three rows once (nine points, none twice) and each line is one
    locus through the three rows."""
    arm = tmp_path / "arm2r.yaml"
    arm.write_text(ARM_2R)
    r = sweep(arm, ["J2=-4:4:0.5", "J1=0:1:0.5"], from_config="bent")
    pts = sorted((p.values[1], p.values[0]) for p in r.located if "input" in p.tests)
    want = sorted((j1, t2) for j1 in (0.0, 0.5, 1.0) for t2 in (-math.pi, 0.0, math.pi))
    assert len(pts) == len(want)
    np.testing.assert_allclose(pts, want, atol=LOCATED)
    loci = [lc for lc in r.loci if lc.test == "input"]
    assert len(loci) == 3
    for lc in loci:
        v = np.asarray(lc.vertices)
        assert len(v) == 3
        assert np.ptp(v[:, 0]) < 1e-9 and np.ptp(v[:, 1]) == 1.0


def test_3rpr_type_ii_line_on_a_sampled_row_is_one_locus(tmp_path):
    """The homothetic 3-RPR's type II line rz = 0 is a row of the grid: every sample on
    it is singular (listed), and the line is one locus from end to end."""
    f = tmp_path / "rpr.yaml"
    f.write_text(RPR_HOMOTHETIC)
    r = sweep(f, ["pose.x=0.7:1.31:0.1", "pose.rz=-0.3:0.31:0.1"], from_config="turned")
    out = [p for p in r.located if "output" in p.tests]
    xs = sorted(p.values[0] for p in out)
    np.testing.assert_allclose(xs, np.arange(0.7, 1.31, 0.1), atol=LOCATED)
    assert all(abs(p.values[1]) < LOCATED for p in out)
    loci = [lc for lc in r.loci if lc.test == "output"]
    assert len(loci) == 1 and len(loci[0].vertices) == 7


def _tau_a(a: float, b: float) -> float:
    """The planar 2R's (links 1 and 0.5) shoulder torque holding the tip force (1, -2):
    -(J^T f)[0], its Jacobian in closed form."""
    col = np.array([-np.sin(a) - 0.5 * np.sin(a + b), np.cos(a) + 0.5 * np.cos(a + b)])
    return -float(col @ np.array([1.0, -2.0]))


def test_max_effort_on_a_grid_locates_the_limit_along_every_row(tmp_path):
    """--max-effort on a grid (refused before): along each row (B held at its sample) the
    shoulder's |torque| falls to 2.5 where the closed form's root is."""
    import json

    from scipy.optimize import brentq

    from tests.cli import run_cli
    from tests.mechanisms import PLANAR_2R_LOADED as PLANAR_2R

    f = tmp_path / "r2.yaml"
    f.write_text(PLANAR_2R)
    argv = ["sweep", f, "--vary", "A=0:1.5:0.1", "--vary", "B=0.7:1.11:0.2", "--from", "bent"]
    r = run_cli([*argv, "--precision", "float", "--format", "json", "--max-effort", "A=2.5"])
    assert r.status == 0, r.err
    limits = json.loads(r.out)["effort_limits"]
    assert len(limits) == 3
    for lim, b in zip(sorted(limits, key=lambda p: p["values"][1]), (0.7, 0.9, 1.1), strict=True):
        root = brentq(lambda a, b=b: abs(_tau_a(a, b)) - 2.5, 0.0, 1.5, xtol=1e-14)
        assert lim["values"][1] == pytest.approx(b, abs=1e-12)
        assert lim["values"][0] == pytest.approx(root, abs=1e-9)
        assert abs(lim["efforts"]["A"]) == pytest.approx(2.5, rel=1e-8)


def test_the_second_weakest_singular_value_kept_by_the_measures_is_numpy_s():
    """A path's tests are measured without their vectors; the screen of the other falling
    values reads sigma_(g-1) from the measures' own factorisation (kept per signed test,
    also through a gather) instead of a second SVD: numpy's singular values of the same
    matrices, to rounding, on the UR5's path over J3 (input and output of rank 6)."""
    from mechsing.sweeps import SweepRun
    from mechsing.sweeps.measures import PointMeasures

    run = SweepRun(EXAMPLES / "ur5.yaml", ["J3=0:6:0.01"], from_config="regular")
    rows = list(run.engine.rows([v.values for v in run.vars], None))
    Z = rows[0].Z
    assert Z is not None
    meas = run.engine.measures
    Q = Z[:, : run.engine.model.n]
    pm = PointMeasures.gather([(meas(Q[:200]), slice(None)), (meas(Q[200:]), slice(None))])
    eps = float(np.finfo(float).eps)
    checked = 0
    for t in ("input", "output"):
        g = meas.generic.get(t)
        if g is None or g < 2 or t in pm.bases:
            continue
        M = np.asarray(pm.matrices[t])
        want = np.linalg.svd(M, compute_uv=False)[:, g - 2]
        size = np.linalg.norm(M, axis=(1, 2))
        assert pm.second[t].shape == want.shape
        assert np.all(np.abs(pm.second[t] - want) <= 16 * eps * size), t
        checked += 1
    assert checked == 2
