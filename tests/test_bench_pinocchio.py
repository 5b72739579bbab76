"""The Pinocchio anchor of the sweep benchmark (benchmarks/_pinocchio_sweep.py) is a fair
anchor: on the benchmark's paths it finds the joint values mechsing's closure finds for the
same held values or output poses (to 1e-9), every point it reports is closed to 1e-12 L, and
its distances to singularity vanish where the published answers say they do (a four-bar's
rocker limits from the law of cosines, the octahedral hexapod's rotation singularity at
+-90 deg, a 3-RPR with concurrent legs).

Skipped when ``pinocchio`` (the ``bench`` extra) is not installed.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

pin = pytest.importorskip("pinocchio")

from mechsing.model import load, loads  # noqa: E402
from tests.reference.benchmarks import benchmark_module  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"

ps = benchmark_module("_pinocchio_sweep")

#: an R-U-P-S loop whose U and S joints the spanning tree crosses from between[1] to
#: between[0] and whose chord is the P joint (the benchmark's examples have neither)
RUPS_REVERSED = """
mechanism: rups-reversed
bodies: [ground, crank, link, piston]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: U, between: [link, crank], axes: [[1, 0, 0], [0, 0, 1]], point: [1, 0, 0]}
  - {name: C, type: P, between: [link, piston], axis: [0, 4, 3]}
  - {name: D, type: S, between: [piston, ground], point: [1, 2, 1.5]}
inputs: [A]
output: {body: link}
"""


def _closed(anchor, path) -> None:
    assert np.all(path.residual <= ps.CLOSURE_RTOL * anchor.length_scale)


@pytest.mark.parametrize(
    ("source", "held", "values", "start", "checked"),
    [
        ("fourbar.yaml", "A", np.deg2rad(np.arange(0, 360, 5.0)), None, [6, 40, 71]),
        # the slider from the reference to 1e-3 of each dead centre (x = 24/5 and 4 sqrt(11)/5)
        (
            "slider_crank_slider_input.yaml",
            "P",
            np.linspace(4 * math.sqrt(11) / 5 - 16 / 5 + 1e-3, 8 / 5 - 1e-3, 200),
            "approach",
            [0, 120, 199],
        ),
        (RUPS_REVERSED, "A", np.deg2rad(np.linspace(0, 60, 31)), None, [10, 30]),
    ],
    ids=["fourbar", "slider-crank", "rups-reversed-tree"],
)
def test_the_anchor_finds_mechsings_joint_values_along_a_held_path(
    source: str, held: str, values: np.ndarray, start: str | None, checked: list[int]
) -> None:
    mech = loads(source) if "\n" in source else load(EXAMPLES / source)
    anchor = ps.PinocchioAnchor(mech)
    q0 = None
    if start == "approach":
        q0 = anchor.approach(pin.neutral(anchor.model), [held], [values[0]])
    path = anchor.path(held, values, q0)
    _closed(anchor, path)
    assert np.all(path.iterations <= 6)
    assert ps.check_against_mechsing(anchor, path, checked, held=held) <= 1e-9


def test_the_anchor_finds_mechsings_joint_values_along_a_pose_path() -> None:
    """The hexapod's platform turned about the vertical through its centre and raised."""
    anchor = ps.PinocchioAnchor(load(EXAMPLES / "stewart_octahedral.yaml"), pose=True)
    n = 41
    rotations = np.zeros((n, 3))
    rotations[:, 2] = np.deg2rad(np.linspace(0, 80, n))
    positions = np.zeros((n, 3))
    positions[:, 2] = np.linspace(0, 0.2, n)
    path = anchor.pose_path(positions, rotations, np.arange(n))
    _closed(anchor, path)
    assert ps.check_against_mechsing(anchor, path, [20, 40], poses=(positions, rotations)) <= 1e-9


def test_the_four_bar_output_map_vanishes_at_the_rocker_limits() -> None:
    """Crank 1, coupler 2 sqrt(2), rocker sqrt(5), ground 4: the rocker stops (Type I) when
    crank and coupler are collinear, |AC| = 2 sqrt(2) +- 1, at the crank angles the law of
    cosines gives in triangle A C D (C above the ground line, as at the reference)."""
    a, c, r, g = 1.0, 2 * math.sqrt(2), math.sqrt(5), 4.0

    def angle_at_a(ac: float) -> float:
        return math.acos((ac * ac + g * g - r * r) / (2 * ac * g))

    limits = [angle_at_a(a + c), angle_at_a(c - a) + math.pi]
    values = np.sort(np.concatenate([np.deg2rad(np.arange(0, 360, 2.0)), limits]))
    anchor = ps.PinocchioAnchor(load(EXAMPLES / "fourbar.yaml"))
    path = anchor.path("A", values)
    _closed(anchor, path)
    at = np.isin(values, limits)
    assert np.all(path.output_sigma[at] < 1e-9)
    far = np.min(np.abs(values[:, None] - np.array(limits)[None, :]), axis=1) > np.deg2rad(5)
    assert np.all(path.output_sigma[far] > 1e-3)
    # a crank-rocker never reaches the toggle (Type II) nor a c-space singularity
    assert np.all(path.input_sigma > 1e-3) and np.all(path.closure_sigma > 1e-2)


def test_the_hexapod_input_map_vanishes_at_plus_minus_90_degrees() -> None:
    """The octahedral hexapod's leg lines become dependent (Type II) when the platform turns
    by +-90 deg about the vertical through its centre, at any height (Fichter 1986)."""
    anchor = ps.PinocchioAnchor(load(EXAMPLES / "stewart_octahedral.yaml"), pose=True)
    degrees = np.arange(-100.0, 101.0, 5.0)
    rotations = np.zeros((len(degrees), 3))
    rotations[:, 2] = np.deg2rad(degrees)
    positions = np.zeros((len(degrees), 3))
    positions[:, 2] = 0.1
    q0 = anchor.approach_pose(pin.neutral(anchor.model), positions[0], rotations[0])
    path = anchor.pose_path(positions, rotations, degrees, q0)
    _closed(anchor, path)
    singular = np.abs(np.abs(degrees) - 90) < 1e-9
    assert np.all(path.input_sigma[singular] < 1e-9)
    assert np.all(path.input_sigma[np.abs(np.abs(degrees) - 90) > 10] > 1e-3)
    assert path.closure_rank == 15


def _concurrency(base: np.ndarray, platform: np.ndarray) -> float:
    """Determinant of the three leg lines through base[i] and platform[i] (homogeneous line
    coordinates, each normalised): zero iff the lines are concurrent or all parallel."""
    lines = []
    for a, b in zip(base, platform, strict=True):
        line = np.cross(np.r_[a, 1.0], np.r_[b, 1.0])
        lines.append(line / np.linalg.norm(line[:2]))
    return float(np.linalg.det(np.array(lines)))


@pytest.mark.parametrize("homothetic", [True, False], ids=["homothetic", "reference-orientation"])
def test_a_pose_grid_of_the_3rpr_meets_its_type_ii_set(homothetic: bool) -> None:
    """3-RPR (base pivots A_i, platform pivots B_i at the reference, from the file): a grid of
    the platform's reference point over a square of side 0.6 at a fixed orientation, as rows
    of paths.  Turned back by 2 atan(1/3), the platform is the base triangle halved about
    (1, 1) (homothetic), so the three leg lines pass through the homothety's centre at every
    position: the whole grid is Type II.  At the reference orientation the concurrency
    determinant stays away from zero over the square, and so does the anchor's test."""
    mech = load(EXAMPLES / "planar_3rpr.yaml")
    anchor = ps.PinocchioAnchor(mech, pose=True)
    base = np.array([[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]])
    pivots = np.array([[0.9, 0.3], [2.5, 1.5], [-0.3, 1.9]])
    centre = pivots.mean(axis=0)  # the output's reference point
    assert np.allclose(anchor.output_origin[:2], centre, atol=1e-15)
    phi = -2 * math.atan(1 / 3) if homothetic else 0.0
    steps = np.linspace(-0.3, 0.3, 5)
    X, Y = np.meshgrid(centre[0] + steps, centre[1] + steps, indexing="ij")
    positions = np.stack([X - centre[0], Y - centre[1], np.zeros_like(X)], axis=-1)
    rotations = np.zeros_like(positions)
    rotations[..., 2] = phi
    q0 = anchor.approach_pose(pin.neutral(anchor.model), positions[0, 0], rotations[0, 0])
    grid = anchor.pose_grid(positions, rotations, np.stack([X, Y], axis=-1), q0)
    _closed(anchor, grid)
    assert grid.values.shape == (25, 2)
    turn = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
    det = np.array([_concurrency(base, (pivots - centre) @ turn.T + xy) for xy in grid.values])
    if homothetic:
        assert np.all(np.abs(det) < 1e-12)
        assert np.all(grid.input_sigma < 1e-9)
    else:
        assert np.all(np.abs(det) > 1.0)
        assert np.all(grid.input_sigma > 0.1)
        flat = positions.reshape(-1, 3), rotations.reshape(-1, 3)
        assert ps.check_against_mechsing(anchor, grid, [0, 12, 24], poses=flat) <= 1e-9
