"""Sweeps per assembly mode, loops and aspects (issue 42), checked against answers not
computed by mechsing: the cusps and the loops around them of the Innocenti &
Parenti-Castelli 3-RPR from the independent code of ``tests/reference/rpr_cusp_loops.py``
(Zein, Wenger & Chablat 2008: a loop around a cusp changes assembly mode without a
singularity), and the aspects of a planar 2R arm in closed form (its elbow is singular at
J2 = 0 and only there on the grid: two regions, J2 < 0 and J2 > 0)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import mechsing
from tests.cli import cli_json, run_cli
from tests.reference import rpr_cusp_loops as ref
from tests.sweep_cusp_design import design_yaml

RHO1 = 14.98  # the section of Zein, Wenger & Chablat (2008)
#: the loop's corner in (rho2, rho3), inside the cusp's wedge (three nearby poses)
CORNER = (13.80, 7.20)
#: around the cusp: P2 from 0 to 0.5, P3 from 0 to -1.4 (rho2 13.8 to 14.3, rho3 7.2 to 5.8)
AROUND = ["P2=0:0.5:0.01", "P3=0:-1.4:0.01"]
#: inside the wedge, around no cusp
BESIDE = ["P2=0:0.08:0.01", "P3=0:0.1:0.01"]


def _rect(vary: list[str]) -> list[tuple[float, float]]:
    (a0, a1), (b0, b1) = (
        (float(v.split("=")[1].split(":")[0]), float(v.split(":")[1])) for v in vary
    )
    c = np.array(CORNER)
    return [tuple(c + d) for d in ((a0, b0), (a1, b0), (a1, b1), (a0, b1))]


@pytest.fixture(scope="module")
def design(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, np.ndarray]:
    """The design's file, its reference the pose of mode 'corner' at phi near 2.79, and
    that pose (phi, theta)."""
    poses = ref.poses_over(RHO1, *CORNER, samples=50_000)
    x = min(poses, key=lambda p: abs(p[0] - 2.793))
    text, lengths = design_yaml(RHO1, x)
    assert np.allclose(lengths, [RHO1, *CORNER], atol=1e-9)
    path = tmp_path_factory.mktemp("cusp") / "cuspidal_3rpr.yaml"
    path.write_text(text)
    return path, x


def _loops(path: Path, vary: list[str]) -> dict:
    """The JSON of the loops of every mode of 'corner' around the rectangle ``vary``."""
    argv = ["sweep", path, "--from", "corner", "--modes", "all", "--loop", "--format", "json"]
    d = cli_json([*argv, *(f"--vary={v}" for v in vary)])
    jsonschema = pytest.importorskip("jsonschema")
    from mechsing.sweeps.schema import sweep_schema

    jsonschema.Draft202012Validator(sweep_schema()).validate(d)
    # the points: every loop's samples, labelled with its mode, reached where it closed
    for loop in d["loops"]:
        mine = [p for p in d["points"] if p["mode"] == loop["mode"]]
        assert mine[0]["values"] == [0.0, 0.0]
        assert all(p["reached"] for p in mine) == loop["closed"]
    return d


def _pose(x_ref: np.ndarray, joints: dict) -> np.ndarray:
    """(phi, theta) of the section from mechsing's joint values (leg 1: Rb1 turns the leg,
    Rb1 + Rp1 the platform)."""
    phi = x_ref[0] + joints["Rb1"][0]
    theta = x_ref[1] + joints["Rb1"][0] + joints["Rp1"][0]
    return np.array([phi, theta])


def _wrapped(d: np.ndarray) -> float:
    return float(np.linalg.norm((d + math.pi) % (2 * math.pi) - math.pi))


def test_reference_cusp_inside_the_loop_only() -> None:
    """The independent computation: one cusp of the section lies inside the rectangle
    AROUND, none inside BESIDE."""
    found = ref.cusps(RHO1, starts=16)
    images = [r for _, r in found]

    def inside(rect: list[tuple[float, float]], p: np.ndarray) -> bool:
        xs, ys = sorted({a for a, _ in rect}), sorted({b for _, b in rect})
        return xs[0] < p[0] < xs[-1] and ys[0] < p[1] < ys[-1]

    assert sum(inside(_rect(AROUND), p) for p in images) == 1
    assert not any(inside(_rect(BESIDE), p) for p in images)


def test_loop_around_a_cusp_changes_mode(design: tuple[Path, np.ndarray]) -> None:
    """mechsing's loops from every mode against the reference's: where the reference
    comes back on another pose, mechsing reports a mode change without a singularity and
    comes back at the reference's pose; where the reference meets a fold, mechsing's loop
    does not close (or locates the singularity); the others come back on their own mode."""
    path, x_ref = design
    d = _loops(path, AROUND)
    assert d["modes"] == [1, 2, 3, 4, 5, 6]
    changes = d["mode_changes"]
    assert len(changes) >= 1
    for loop in d["loops"]:
        start = _pose(x_ref, loop["joints_start"])
        back = ref.follow_rectangle(RHO1, start, _rect(AROUND), step=2e-3)
        if back is None:  # the reference meets a fold of the section
            assert not loop["mode_change_without_singularity"]
            continue
        assert loop["closed"], loop["notes"]
        assert _wrapped(_pose(x_ref, loop["joints_end"]) - back) < 1e-6
        changed = _wrapped(back - start) > 1e-3
        assert loop["mode_change_without_singularity"] == changed
        assert (loop["end_mode"] != loop["mode"]) == changed
    for c in changes:
        assert c["start_mode"] != c["end_mode"] and c["end_mode"] in d["modes"]
        assert c["path"][0] == c["path"][-1] == [0.0, 0.0]


def test_loop_around_no_cusp_keeps_modes(design: tuple[Path, np.ndarray]) -> None:
    path, x_ref = design
    d = _loops(path, BESIDE)
    assert d["mode_changes"] == []
    for loop in d["loops"]:
        back = ref.follow_rectangle(
            RHO1, _pose(x_ref, loop["joints_start"]), _rect(BESIDE), step=2e-3
        )
        assert back is not None
        assert loop["closed"] and loop["end_mode"] == loop["mode"]
        assert _wrapped(_pose(x_ref, loop["joints_end"]) - back) < 1e-6


def test_sweep_from_a_mode(design: tuple[Path, np.ndarray]) -> None:
    """sweep(start=...) by index and by the Mode item agree; every sample carries the mode
    and the first sample is that mode's pose (its legs' lengths from the reference)."""
    path, x_ref = design
    found = mechsing.modes(str(path), "corner", "float")
    by_index = mechsing.sweep(str(path), "P2=0:0.05:0.01", "corner", "float", start=1)
    by_item = mechsing.sweep(str(path), "P2=0:0.05:0.01", "corner", "float", start=found.modes[1])
    assert by_index.mode == by_item.mode == 2
    d = by_index.to_json()
    assert d["mode"] == 2 and all(p["mode"] == 2 for p in d["points"])
    np.testing.assert_allclose(by_index.ratio["output"], by_item.ratio["output"])
    poses = ref.poses_over(RHO1, *CORNER, samples=50_000)
    mode_pose = _pose(x_ref, found.modes[1].joints)
    assert min(_wrapped(p - mode_pose) for p in poses) < 1e-8
    # the default sweep has no mode key (its JSON unchanged)
    plain = mechsing.sweep(str(path), "P2=0:0.05:0.01", "corner", "float").to_json()
    assert "mode" not in plain and "mode" not in plain["points"][0]
    rc, _, err = run_cli(
        ["sweep", path, "--from", "corner", "--vary", "P2=0:0.05:0.01", "--mode", "9"]
    )
    assert rc == 2 and "--mode 1 to 6" in err


ARM = """mechanism: arm-2r
bodies: [ground, upper, fore]
joints:
  - {name: J1, type: R, between: [ground, upper], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J2, type: R, between: [upper, fore], axis: [0, 0, 1], point: [1, 0, 0]}
inputs: [J1, J2]
output: {body: fore, point: [2, 0, 0]}
configurations:
  reference: {}
  bent: {J1: 0.3, J2: 1}
"""


@pytest.mark.parametrize(
    ("j2", "below", "above"),
    [
        ("J2=-3:3:0.25", (-3.0, -0.25), (0.25, 3.0)),  # J2 = 0 a sample
        ("J2=-2.9:3:0.2", (-2.9, -0.1), (0.1, 2.9)),  # J2 = 0 between two samples
    ],
)
def test_aspects_of_a_2r_arm(tmp_path: Path, j2: str, below: tuple, above: tuple) -> None:
    """The 2R arm's singularity-free regions on a grid of J1 in [0, 1] and J2 around 0:
    the elbow's line J2 = 0 (det J = sin J2, closed form) splits it into two."""
    path = tmp_path / "arm.yaml"
    path.write_text(ARM)
    d = cli_json(
        ["sweep", path, "--from", "bent", "--vary", "J1=0:1:0.25", "--vary", j2, "--format", "json"]
    )
    ys = np.asarray([p["values"][1] for p in d["points"]])
    per_side = len(set(ys[ys < 0].tolist()))
    assert len(d["aspects"]) == 2
    boxes = sorted(a["box"][1][0] for a in d["aspects"])
    got = sorted((tuple(a["box"][1]), a["cells"], tuple(a["box"][0])) for a in d["aspects"])
    assert boxes[0] < 0 < boxes[1]
    np.testing.assert_allclose(got[0][0], below, atol=1e-12)
    np.testing.assert_allclose(got[1][0], above, atol=1e-12)
    assert got[0][1] == 5 * per_side and got[0][2] == (0.0, 1.0)


def test_modes_all_grid_document(design: tuple[Path, np.ndarray]) -> None:
    """--modes all on a grid: one document valid against the sweep schema, every point and
    every aspect labelled with its mode, each mode's samples all there."""
    jsonschema = pytest.importorskip("jsonschema")
    from mechsing.sweeps.schema import sweep_schema

    path, _ = design
    d = cli_json(
        [
            "sweep",
            path,
            "--from",
            "corner",
            "--modes",
            "all",
            "--vary",
            "P2=0:0.04:0.02",
            "--vary",
            "P3=0:0.04:0.02",
            "--format",
            "json",
        ]
    )
    jsonschema.Draft202012Validator(sweep_schema()).validate(d)
    assert d["modes"] == [1, 2, 3, 4, 5, 6]
    assert [p["mode"] for p in d["points"]] == [m for m in d["modes"] for _ in range(9)]
    # a small grid inside the cusp's wedge: every mode regular throughout, one region each
    assert sorted(a["mode"] for a in d["aspects"]) == d["modes"]
    assert all(a["cells"] == 9 for a in d["aspects"])


def test_the_docs_design_is_the_tested_one(design: tuple[Path, np.ndarray]) -> None:
    """docs/sweeps.md carries the file its loop example runs: the design tested here."""
    page = (Path(__file__).resolve().parents[1] / "docs" / "sweeps.md").read_text()
    head = "```yaml\n# file: cuspidal_3rpr.yaml\n"
    start = page.index(head) + len(head)
    assert page[start : page.index("```", start)] == design[0].read_text()


def test_loops_in_markdown_and_bad_options(design: tuple[Path, np.ndarray]) -> None:
    path, _ = design
    vary = [f"--vary={v}" for v in AROUND]
    rc, out, _ = run_cli(
        ["sweep", path, "--from", "corner", "--modes", "all", "--loop", "--format", "md", *vary]
    )
    assert rc == 0 and "| 3 | yes | mode 5 | 0 | **yes** |" in out
    assert "- mode 3 → mode 5" in out
    for argv, words in (
        (["--loop", "--vary", "P2=0:1:0.1"], "give two --vary"),
        (["--loop", "--format", "csv", *vary], "not csv"),
        (["--format", "md", "--vary", "P2=0:1:0.1"], "mechsing report"),
    ):
        rc, _, err = run_cli(["sweep", path, "--from", "corner", *argv])
        assert rc == 2 and words in err, (argv, err)


@pytest.mark.skipif(
    __import__("importlib").util.find_spec("distributed") is None,
    reason="Dask distributed is not installed (pip install 'mechsing[dask]')",
)
def test_per_mode_grids_distributed_give_the_serial_result(
    design: tuple[Path, np.ndarray],
) -> None:
    """Each mode's grid on a local Dask cluster is its serial grid (the whole document,
    aspects included); the grid crosses the cusp's singular curves."""
    from mechsing.sweeps import sweep_modes
    from mechsing.sweeps.distributed import usable_cpus

    path, _ = design
    grid = ["P2=0:0.2:0.05", "P3=-1:0:0.25"]
    serial = sweep_modes(str(path), grid, "corner", "float", modes=[3, 4])
    assert any(r.located for r in serial.sweeps)
    spread = sweep_modes(
        str(path), grid, "corner", "float", modes=[3, 4], workers=min(2, usable_cpus())
    )
    assert spread.to_json() == serial.to_json()
    assert [r.mode for r in spread.sweeps] == [3, 4]


def test_a_2r_arm_has_one_mode_and_its_loop_keeps_it(tmp_path: Path) -> None:
    """Both joints of a 2R arm are inputs: the joints are the inputs, one configuration
    per input value (one mode), so --mode 2 is an error naming the fix, and a loop of
    (J1, J2) around [0, 1] x [-0.5, 0.5] comes back on its start, crossing the elbow's
    singular line J2 = 0 (det J = sin J2) on the sides J1 = 1 and J1 = 0 and nowhere else."""
    path = tmp_path / "arm.yaml"
    path.write_text(ARM)
    rc, _, err = run_cli(["sweep", path, "--from", "bent", "--vary", "J2=0:1:0.1", "--mode", "2"])
    assert rc == 2 and "has 1 assembly mode " in err and "give --mode 1 or leave" in err
    assert "Traceback" not in err
    vary = ["--vary", "J1=0:1:0.1", "--vary", "J2=-0.5:0.5:0.1"]
    d = cli_json(["sweep", path, "--from", "bent", *vary, "--loop", "--format", "json"])
    assert d["mode_changes"] == []
    (loop,) = d["loops"]
    assert loop["closed"] and not loop["changed_mode"]
    assert loop["joints_end"]["J2"] == pytest.approx(loop["joints_start"]["J2"], abs=1e-12)
    got = sorted(tuple(p["values"]) for p in loop["located"])
    assert len(got) == 2
    np.testing.assert_allclose(got, [(0.0, 0.0), (1.0, 0.0)], atol=1e-9)
    # det J = sin J2 changes sign there on both sides (J2 = 0 a sample of each edge, where
    # the sign test between neighbours reads a zero singular pair's arbitrary sign): one
    # kind for both, a crossing (it was a minimum on one side)
    assert [p["kind"] for p in loop["located"]] == ["crossing", "crossing"]


def test_aspects_of_a_2r_arm_across_its_stretched_elbow(tmp_path: Path) -> None:
    """J2 over [-3.5, 3.5]: the elbow is singular at J2 = -pi, 0 and pi (sin J2 = 0), so
    the grid has four aspects, bounded by the samples either side of those three lines."""
    path = tmp_path / "arm.yaml"
    path.write_text(ARM)
    d = cli_json(
        ["sweep", path, "--from", "bent", "--vary", "J1=0:1:0.25", "--vary", "J2=-3.5:3.5:0.25"]
        + ["--format", "json"]
    )
    got = sorted(tuple(a["box"][1]) for a in d["aspects"])
    # the samples' runs between the lines sin J2 = 0 (a sample on a line belongs to none)
    samples = np.linspace(-3.5, 3.5, 29)
    lines = (-math.pi, 0.0, math.pi)
    runs: list[list[float]] = [[]]
    for y in samples:
        if any(abs(y - c) < 1e-12 for c in lines):
            runs.append([])
            continue
        if runs[-1] and any(runs[-1][-1] < c < y for c in lines):
            runs.append([])
        runs[-1].append(float(y))
    want = [(r[0], r[-1]) for r in runs if r]
    assert len(want) == 4
    np.testing.assert_allclose(got, want, atol=1e-12)


@pytest.mark.parametrize("vary", ["J1=0:0:0.1", "J1=0:0.05:0.1"])
def test_a_loop_needs_a_rectangle(tmp_path: Path, vary: str) -> None:
    """A --vary of one sample makes the rectangle a segment: nothing inside to go round."""
    path = tmp_path / "arm.yaml"
    path.write_text(ARM)
    rc, _, err = run_cli(
        ["sweep", path, "--from", "bent", "--vary", vary, "--vary", "J2=0:1:0.1", "--loop"]
    )
    assert rc == 2 and "--vary J1 has one sample (0 rad)" in err and "STEP apart" in err


def test_a_fold_where_two_modes_meet_is_named_so_not_a_limit_of_travel(
    design: tuple[Path, np.ndarray],
) -> None:
    """Mode 4 of the corner followed along P2 (P1, P3 held) stops at a fold where it
    meets another mode: the independent count of real poses (tests/reference) drops by
    two across the located value while P2 goes on (other modes stay real past it), so
    the sweep names it a fold of the direct kinematics, in the located line and in the
    stop note, and not a limit of travel (which reads as the joint's stroke)."""
    path, _ = design
    run = run_cli(["sweep", path, "--from", "corner", "--vary", "P2=0:0.5:0.01", "--mode", "4"])
    assert run.status in (0, 1), run.err
    (line,) = [ln for ln in run.out.splitlines() if ": fold of the direct kinematics" in ln]
    assert "limit of travel" not in run.out and "output" in line
    p2 = float(line.split("P2 = ")[1].split(" m")[0])
    before = len(ref.poses_over(RHO1, CORNER[0] + p2 - 0.005, CORNER[1], samples=50_000))
    after = len(ref.poses_over(RHO1, CORNER[0] + p2 + 0.005, CORNER[1], samples=50_000))
    assert before - after == 2 and after > 0
    (note,) = [ln for ln in run.out.splitlines() if "note: towards" in ln]
    assert "past a fold of the direct kinematics" in note


def test_every_modes_grid_shares_one_local_cluster(
    design: tuple[Path, np.ndarray], monkeypatch: pytest.MonkeyPatch
) -> None:
    """--modes all --workers N: one Dask local cluster for all the modes' grids (it was
    one per mode), through the API and the command line, with the serial documents."""
    from mechsing.sweeps import distributed, sweep_modes

    real = distributed._dask
    started: list[int] = []

    def counting() -> tuple:
        client_cls, cluster_cls, as_completed = real()

        def cluster(*args, **kwargs):
            started.append(1)
            return cluster_cls(*args, **kwargs)

        return client_cls, cluster, as_completed

    monkeypatch.setattr(distributed, "_dask", counting)
    path, _ = design
    grid = ["P2=0:0.1:0.05", "P3=-0.5:0:0.25"]
    serial = sweep_modes(str(path), grid, "corner", "float", modes=[3, 4])
    spread = sweep_modes(str(path), grid, "corner", "float", modes=[3, 4], workers=1)
    assert started == [1]
    assert spread.to_json() == serial.to_json()
    started.clear()
    argv = ["sweep", path, "--from", "corner", "--vary", grid[0], "--vary", grid[1]]
    run = run_cli([*argv, "--modes", "all", "--workers", "1", "--format", "json", "--quiet"])
    assert run.status in (0, 1), run.err
    assert started == [1]
    assert json.loads(run.out)["modes"] == list(range(1, 7))
