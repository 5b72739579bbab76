"""``mechsing modes`` where the file's numbers are rounded and the closure equations
outnumber the unknowns (an overconstrained loop, an arm at a pose with fewer joints than
the pose has coordinates): the general formulation tracks random combinations of the
equations, and a real root of the combinations is a mode only where the loops close (or
the arm reaches its target) to the tolerance its analysis accepts.  A Bennett linkage
whose axes are rounded to 6 digits is a rigid structure: it has no mode away from its
drawn pose, and modes says so (it used to list the combinations' root as a mode, then
fail when analysing it).

The counts are checked against the independent solver of
``tests/reference/loop_modes_independent.py`` (damped Newton from random starts on 4x4
closure matrices, keeping residuals below 1e-10; it imports nothing from mechsing).
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

from tests.cli import run_cli
from tests.reference.loop_modes_independent import closure_residual, solve_all

pytest.importorskip("bertini")

#: examples/bennett.yaml's third axis and point (exact rationals) as decimals
J3_AXIS = (-156 / 701, 429 / 701, 532 / 701)
J3_POINT = (-2353 / 3505, -364 / 3505, 1248 / 3505)


def _bennett(tmp_path: Path, digits: int) -> tuple[Path, list]:
    """examples/bennett.yaml with its third joint's axis and point written as decimals of
    ``digits`` significant digits; the file and the joints for the independent solver."""
    axis = [float(f"{x:.{digits}g}") for x in J3_AXIS]
    point = [float(f"{x:.{digits}g}") for x in J3_POINT]
    text = f"""mechanism: bennett-{digits}-digits
bodies: [ground, link1, link2, link3]
joints:
  - {{name: J1, type: R, between: [ground, link1], axis: [0, 0, 1], point: [0, 0, 0]}}
  - {{name: J2, type: R, between: [link1, link2], axis: [0.48, -0.36, 0.8], point: [0.6, 0.8, 0]}}
  - {{name: J3, type: R, between: [link2, link3], axis: {axis!r}, point: {point!r}}}
  - {{name: J4, type: R, between: [link3, ground], axis: [0, 0.96, 0.28], point: [-1.6, 0, 0]}}
inputs: [J1]
output: {{body: link2}}
configurations:
  q1-1rad: {{J1: 1}}
"""
    path = tmp_path / f"bennett{digits}.yaml"
    path.write_text(text)
    joints = [
        ("R", np.array([0, 0, 1.0]), np.zeros(3)),
        ("R", np.array([0.48, -0.36, 0.8]), np.array([0.6, 0.8, 0])),
        ("R", np.array(axis), np.array(point)),
        ("R", np.array([0, 0.96, 0.28]), np.array([-1.6, 0, 0])),
    ]
    return path, joints


def _modes(path: Path, config: str) -> dict:
    rc, out, err = run_cli(["modes", str(path), "--config", config, "--format", "json"])
    assert rc == 0, err
    return json.loads(out)


LOOP = [[(i, 1) for i in range(4)]]


def test_a_bennett_rounded_to_six_digits_has_no_mode_away_from_its_drawn_pose(
    tmp_path: Path,
) -> None:
    path, joints = _bennett(tmp_path, 6)
    assert solve_all(joints, LOOP, {0: 1.0}, starts=300) == []
    doc = _modes(path, "q1-1rad")
    assert doc["count"] == 0 and doc["complete"] == "proven"
    assert doc["paths"]["solutions"] == 0 and doc["paths"]["real"] == 0
    (note,) = [n for n in doc["notes"] if "real root(s) of the random combinations" in n]
    assert "the loops left open" in note
    gap = float(re.search(r"by ([0-9.e+-]+) m \(the least\)", note).group(1))
    # the gap is the loop's residual at the combinations' root: of the order of the
    # data's rounding (5e-7), and no closer configuration exists (least squares from the
    # exact linkage's mode, on the independent closure matrices)
    from scipy.optimize import least_squares

    best = least_squares(
        lambda x: closure_residual(joints, LOOP, np.r_[1.0, x]),
        [-0.6313, -1.0, 0.6313],
        xtol=1e-15,
        ftol=1e-15,
        gtol=1e-15,
    )
    least = float(np.linalg.norm(best.fun))
    assert 1e-8 < least < 1e-5
    assert least / 10 < gap < least * 10


def test_a_bennett_written_to_seventeen_digits_keeps_its_mode(tmp_path: Path) -> None:
    path, joints = _bennett(tmp_path, 17)
    expected = solve_all(joints, LOOP, {0: 1.0}, starts=300)
    doc = _modes(path, "q1-1rad")
    assert doc["count"] == len(expected) == 1 and doc["complete"] == "proven"
    q = np.array([doc["modes"][0]["joints"][n][0] for n in ("J1", "J2", "J3", "J4")])
    assert np.linalg.norm(q - expected[0]) < 1e-9
    assert not any("real root(s) of the random combinations" in n for n in doc["notes"])


ARM = """mechanism: planar-2r-arm
bodies: [ground, upper, fore]
joints:
  - {name: J1, type: R, between: [ground, upper], axis: [1, 0, 0], point: [0, 0, 0]}
  - {name: J2, type: R, between: [upper, fore], axis: [1, 0, 0], point: [0, 1, 0]}
output: {body: fore, point: [0, "17/10", 0]}
configurations:
  exact: {pose: {position: [0, "cos(3/10) + 7/10*cos(4/5)", "sin(3/10) + 7/10*sin(4/5)"],
                 rotation_vector: ["4/5", 0, 0]}}
  rounded: {pose: {position: [0, 1.443031186, 0.79766947], rotation_vector: [0.8, 0, 0]}}
  five-decimals: {pose: {position: [0, 1.44303, 0.79767], rotation_vector: [0.8, 0, 0]}}
"""


def test_a_planar_arm_at_a_full_pose_reaches_it_exactly_or_not_at_all(tmp_path: Path) -> None:
    """Two joints, a pose of three coordinates in the plane: J1 = 0.3, J2 = 0.5 reach the
    exact pose; a position rounded to 9 decimals (3e-10 off) or 5 (3e-6 off) is out of
    reach (the first is a root of the random combinations that misses the target by more
    than float's 5e-13 m, the second is screened in double precision)."""
    path = tmp_path / "arm.yaml"
    path.write_text(ARM)
    joints = [
        ("R", np.array([1.0, 0, 0]), np.zeros(3)),
        ("R", np.array([1.0, 0, 0]), np.array([0, 1.0, 0])),
    ]

    def target(y: float, z: float) -> np.ndarray:
        # the output frame's displacement from the reference: R_x(0.8) about (0, 1.7, 0)
        # carried to (0, y, z)
        c, s = np.cos(0.8), np.sin(0.8)
        T = np.eye(4)
        T[1:3, 1:3] = [[c, -s], [s, c]]
        T[:3, 3] = np.array([0, y, z]) - T[:3, :3] @ np.array([0, 1.7, 0])
        return T

    exact = (np.cos(0.3) + 0.7 * np.cos(0.8), np.sin(0.3) + 0.7 * np.sin(0.8))
    chain = [[(0, 1), (1, 1)]]
    expected = solve_all(joints, chain, {}, targets=[target(*exact)], starts=200)
    assert len(expected) == 1 and np.allclose(expected[0], [0.3, 0.5], atol=1e-9)
    doc = _modes(path, "exact")
    assert doc["count"] == 1 and doc["complete"] == "proven"
    q = [doc["modes"][0]["joints"][n][0] for n in ("J1", "J2")]
    assert np.allclose(q, [0.3, 0.5], atol=1e-12)

    for config, y, z in (("rounded", 1.443031186, 0.79766947), ("five-decimals", 1.44303, 0.79767)):
        off = np.hypot(y - exact[0], z - exact[1])
        # the independent solver's acceptance (1e-10) is looser than the analysis' float
        # tolerance: it finds the 9-decimal target reached, to its own rounding
        assert (solve_all(joints, chain, {}, targets=[target(y, z)], starts=200) == []) == (
            off > 1e-10
        )
        doc = _modes(path, config)
        assert doc["count"] == 0 and doc["complete"] == "proven"
        notes = [n for n in doc["notes"] if "real root(s) of the random combinations" in n]
        if config == "rounded":
            (note,) = notes
            assert "the arm's end off its target" in note
            gap = float(re.search(r"by ([0-9.e+-]+) m \(the least\)", note).group(1))
            # the residual at the combinations' root: at least the target's distance from
            # the arm's reach, of its order
            assert off / 3 < gap < off * 10
