"""--set (an ad-hoc configuration cli on any input format) and the limits key (reported by
analyze, the range of `sweep --vary J` given without one)."""

from __future__ import annotations

import json
import math

from tests.cli import run_cli

LIMITED = """\
mechanism: slider
units: {length: mm, angle: deg}
bodies: [ground, crank, rod, slider]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, between: [crank, rod], axis: [0, 0, 1], point: [10, 0, 0]}
  - {name: C, type: R, between: [rod, slider], axis: [0, 0, 1], point: [40, 0, 0]}
  - {name: S, type: P, between: [slider, ground], axis: [1, 0, 0]}
inputs: [A]
limits:
  A: [-90, 90]
  S: [-5, 5]
configurations:
  reference: {}
"""


def test_set_adds_a_configuration_in_the_files_units(tmp_path) -> None:
    f = tmp_path / "s.yaml"
    f.write_text(LIMITED)
    r = run_cli(["solve", str(f), "--set", "A=90", "--format", "json"])  # --config cli implied
    assert r.status == 0, r.err
    out = json.loads(r.out)
    assert out["configuration"] == "cli"
    assert abs(out["joints"]["A"][0] - math.pi / 2) < 1e-12
    # crank 10 mm at 90 deg, rod 30 mm: the slider is at sqrt(30^2 - 10^2) = 28.28 mm,
    # 40 - 28.28 = 11.72 mm back (the prismatic S moves the ground relative to the slider)
    assert abs(abs(out["joints"]["S"][0]) - (0.040 - math.sqrt(0.030**2 - 0.010**2))) < 1e-9


def test_set_errors(tmp_path) -> None:
    f = tmp_path / "s.yaml"
    f.write_text(LIMITED)
    for argv, words in [
        (["--set", "Z=1"], "no joint 'Z'"),
        (["--set", "A"], "expected JOINT=VALUE"),
        (["--set", "A=1,2"], "has 1 coordinate"),
        (["--set", "A=1", "--set", "A=2"], "given twice"),
        (["--set", "A=1", "--from", "nowhere"], "no such configuration"),
        (["--from", "reference"], "give --set JOINT=VALUE too"),
    ]:
        r = run_cli(["analyze", str(f), *argv])
        assert r.status == 2 and words in r.err, (argv, r.err)
    g = tmp_path / "c.yaml"
    g.write_text(LIMITED.replace("reference: {}", "reference: {}\n  cli: {A: 10}"))
    r = run_cli(["analyze", str(g), "--set", "A=1"])
    assert r.status == 2 and "already has a configuration named 'cli'" in r.err


def test_set_multi_dof_joint(tmp_path) -> None:
    f = tmp_path / "s.yaml"
    f.write_text(
        "bodies: [g, b]\njoints: [{name: S1, type: S, between: [g, b], point: [0, 0, 0]}]\n"
        "configurations: {reference: {}}\n"
    )
    r = run_cli(["solve", str(f), "--set", "S1=0.1,0,pi/10", "--format", "json"])
    assert r.status == 0, r.err
    assert json.loads(r.out)["joints"]["S1"] == [0.1, 0.0, math.pi / 10]


def test_analyze_reports_limits(tmp_path) -> None:
    f = tmp_path / "s.yaml"
    f.write_text(LIMITED)
    r = run_cli(["analyze", str(f), "--format", "json", "--set", "A=120"])
    assert r.status == 0, r.err
    lim = json.loads(r.out)["limits"]
    assert lim["A"] == [[-math.pi / 2, math.pi / 2]] and lim["S"] == [[-0.005, 0.005]]
    text = run_cli(["analyze", str(f), "--set", "A=120"]).out
    assert "Joint limits (m, rad): A [-1.5708, 1.5708], S [-0.005, 0.005]." in text
    assert "outside the joint limits: A" in text


def test_sweep_over_limits(tmp_path) -> None:
    f = tmp_path / "s.yaml"
    f.write_text(LIMITED)
    r = run_cli(["sweep", str(f), "--vary", "A", "--format", "json"])
    assert r.status == 0, r.err
    (var,) = json.loads(r.out)["variables"]
    assert (var["start"], var["stop"], var["samples"]) == (-90.0, 90.0, 201)
    assert abs(var["step"] - 0.9) < 1e-12
    r = run_cli(["sweep", str(f), "--vary", "B"])
    assert r.status == 2 and "has no limits" in r.err


def test_urdf_limits_and_set(tmp_path) -> None:
    r = run_cli(
        [
            "analyze",
            "examples/ur5.urdf",
            "--set",
            "joint5=0",
            "--set",
            "joint3=1",
            "--config",
            "cli",
            "--format",
            "json",
        ]
    )
    assert r.status == 0, r.err
    doc = json.loads(r.out)
    assert doc["limits"]["joint1"] == [[-2 * math.pi, 2 * math.pi]]
    (conf,) = doc["configurations"]
    assert [s["class"] for s in conf["singularities"]] == ["serial"]  # the wrist, theta5 = 0


def test_sweep_from_set(tmp_path) -> None:
    """With --set the sweep starts from cli; without, --from is the sweep's own start."""
    f = tmp_path / "s.yaml"
    f.write_text(LIMITED.replace("reference: {}", "reference: {}\n  tilted: {A: 45}"))
    r = run_cli(["sweep", str(f), "--vary", "A=45:60:5", "--set", "A=45", "--format", "json"])
    assert r.status == 0, r.err
    assert json.loads(r.out)["from"] == "cli"
    r = run_cli(["sweep", str(f), "--vary", "A=45:60:5", "--from", "tilted", "--format", "json"])
    assert r.status == 0, r.err
    assert json.loads(r.out)["from"] == "tilted"
