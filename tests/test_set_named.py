"""``--set [NAME:]JOINT=VALUE``: the values with one NAME form one configuration of that name
(the others ``cli``, as before), so one run checks an arm's wrist and elbow; a command that
starts from one configuration refuses several; a joint given twice in one configuration is
refused, the same joint in two configurations is not.  Run as a user runs it."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _run(*args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1"}
    return subprocess.run(
        [sys.executable, "-m", "mechsing", *args],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env=env,
        check=False,
    )


def test_named_sets_make_one_configuration_each() -> None:
    # examples/ur5.yaml's wrist (J5 = 0) and elbow (J3 = 0) poses, given on the command line
    arm = ["--set", "w:J2=-pi/4", "--set", "w:J3=pi/2", "--set", "w:J4=-pi/4", "--set", "w:J5=0"]
    arm += ["--set", "e:J2=-pi/4", "--set", "e:J3=0", "--set", "e:J4=-pi/4", "--set", "e:J5=pi/2"]
    arm += ["--set", "J1=0.5"]
    out = _run(
        "analyze",
        "examples/ur5.yaml",
        *arm,
        "--config",
        "w",
        "--config",
        "e",
        "--config",
        "cli",
        "--format",
        "json",
    )
    assert out.returncode == 0, out.stderr
    confs = {c["name"]: c for c in json.loads(out.stdout)["configurations"]}
    assert list(confs) == ["w", "e", "cli"]
    assert confs["w"]["joints"]["J3"] == [math.pi / 2] and confs["w"]["joints"]["J5"] == [0.0]
    assert confs["e"]["joints"]["J3"] == [0.0] and confs["e"]["joints"]["J5"] == [math.pi / 2]
    assert confs["cli"]["joints"]["J1"] == [0.5]
    names = {k: [f.get("name") for f in c["singularities"]] for k, c in confs.items()}
    assert names["w"] == ["wrist"] and names["e"] == ["elbow"]


def test_a_sweep_starts_from_one_named_configuration() -> None:
    two = _run(
        "sweep", "examples/fourbar.yaml", "--vary", "A=0:10:5", "--set", "a:A=1", "--set", "b:A=2"
    )
    assert two.returncode == 2 and "starts from one configuration" in two.stderr
    one = _run("sweep", "examples/fourbar.yaml", "--vary", "A=0:10:5", "--set", "a:A=1")
    assert one.returncode == 0, one.stderr
    assert "from 'a'" in one.stdout


def test_a_joint_twice_in_one_configuration_is_refused() -> None:
    twice = _run("analyze", "examples/fourbar.yaml", "--set", "a:A=1", "--set", "a:A=2")
    assert twice.returncode == 2 and "given twice for a" in twice.stderr
    apart = _run(
        "analyze",
        "examples/fourbar.yaml",
        "--set",
        "a:A=1",
        "--set",
        "b:A=2",
        "--config",
        "a",
        "--config",
        "b",
    )
    assert apart.returncode == 0, apart.stderr
    taken = _run("analyze", "examples/fourbar.yaml", "--set", "reference:A=1")
    assert taken.returncode == 2 and "already has a configuration named 'reference'" in taken.stderr


def test_condition_is_evaluated_at_the_named_configuration() -> None:
    """`condition --set wrist:B=0` evaluates the factors at the configuration `wrist` the
    values make (it looked for `cli`, which no named value makes). At B = 0 from the drawn
    pose the slider-crank's input condition 4 cos B - 3 sin B (its crank and rod in line, by
    the file's geometry) is 4, and no other factor vanishes there either."""
    r = _run("condition", "examples/slider_crank_crank_input.yaml", "--set", "wrist:B=0")
    assert r.returncode == 0, r.stderr
    assert "at wrist:" in r.stdout and "at cli" not in r.stdout
    assert "(vanishes)" not in r.stdout
