"""``mechsing modes`` on single loops of six joints with one given, squared by one unknown
revolute's axis (mechsing/assembly/axis.py): the modes against the independent solver of
``tests/reference/loop_modes_independent.py`` (damped Newton from random starts on 4x4
closure matrices; it imports nothing from mechsing), and ``complete`` proven only where
every one of the square system's 24 roots is certified.
"""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
import yaml

from tests.cli import run_cli
from tests.mechanisms import ROOT
from tests.reference.loop_modes_independent import solve_all, wrap_angles

pytest.importorskip("bertini")

BRICARD = ROOT / "examples" / "bricard.yaml"
PLANE = ROOT / "tests" / "data" / "bricard_plane.yaml"
NAME = "a six-joint loop squared by one revolute's axis"


def _modes(path: Path, config: str) -> dict:
    rc, out, err = run_cli(["modes", str(path), "--config", config, "--format", "json"])
    assert rc == 0, err
    return json.loads(out)


def _loop(path: Path) -> tuple[list, list, list[str]]:
    """The file's joints for the independent solver, its one loop (each joint's sign: -1
    where the joint is written from the far body back) and the joint names."""
    doc = yaml.safe_load(path.read_text())

    def vec(xs: list) -> np.ndarray:
        return np.array([float(Fraction(str(x))) for x in xs])

    joints = [(j["type"], vec(j["axis"]), vec(j.get("point", [0, 0, 0]))) for j in doc["joints"]]
    bodies = doc["bodies"]
    loop = []
    for i, j in enumerate(doc["joints"]):
        a, b = j["between"]
        ahead = (bodies[(i + 1) % len(bodies)] if i + 1 < len(bodies) else "ground") == b
        loop.append((i, 1 if ahead else -1))
    return joints, [loop], [j["name"] for j in doc["joints"]]


def _check(doc: dict, path: Path, given: dict[int, float], count: int) -> None:
    joints, loops, names = _loop(path)
    kinds = [j[0] for j in joints]
    expected = solve_all(joints, loops, given, starts=400)
    assert doc["count"] == len(expected) == count, (doc["count"], expected)
    found = [np.array([m["joints"][n][0] for n in names]) for m in doc["modes"]]
    for e in expected:
        assert min(np.linalg.norm(wrap_angles(kinds, e - f)) for f in found) < 1e-9, (e, found)
    assert all(m["certified"] for m in doc["modes"])


def test_a_plane_symmetric_bricard_has_its_two_modes_proven() -> None:
    doc = _modes(PLANE, "q1")
    assert doc["formulation"]["name"] == NAME and doc["complete"] == "proven"
    assert doc["paths"]["tracked"] == doc["paths"]["finite"] == 24
    _check(doc, PLANE, {0: 0.3}, 2)
    for m in doc["modes"]:  # mirror images: J2 = J6, J3 = J5
        q = m["joints"]
        assert abs(q["J2"][0] - q["J6"][0]) < 1e-12 and abs(q["J3"][0] - q["J5"][0]) < 1e-12


def test_reversed_joints_and_another_given_joint(tmp_path: Path) -> None:
    """Bricard's line-symmetric 6R with J4 and J5 written backwards (crossed against the
    loop) and J3 given: the same two modes, J4 and J5 negated."""
    text = BRICARD.read_text()
    text = text.replace("between: [link3, link4]", "between: [link4, link3]")
    text = text.replace("between: [link4, link5]", "between: [link5, link4]")
    text = text.replace("inputs: [J1]", "inputs: [J3]")
    text = text.replace("  q1-0.4: {J1: 0.4}", "  q3: {J3: -0.7292412338193741}")
    f = tmp_path / "bricard_reversed.yaml"
    f.write_text(text)
    doc = _modes(f, "q3")
    assert doc["formulation"]["name"] == NAME and doc["complete"] == "proven"
    _check(doc, f, {2: -0.7292412338193741}, 2)
    assert any(abs(m["joints"]["J4"][0] + 0.4) < 1e-12 for m in doc["modes"])


RIGID = """
mechanism: rigid-loop-with-a-slide
bodies: [ground, l1, l2, l3, l4, l5]
joints:
  - {name: J1, type: R, between: [ground, l1], axis: ["2/7", "3/7", "6/7"], point: [1, 0, 0]}
  - {name: J2, type: P, between: [l1, l2], axis: ["1/9", "-4/9", "8/9"]}
  - {name: J3, type: R, between: [l2, l3], axis: ["-4/9", "4/9", "7/9"], point: [-1, 1, 2]}
  - {name: J4, type: R, between: [l3, l4], axis: ["3/5", "0", "4/5"], point: [-1, 0, 1]}
  - {name: J5, type: R, between: [l4, l5], axis: [0, 1, 0], point: [0, -2, 1]}
  - {name: J6, type: R, between: [l5, ground], axis: ["4/9", "-4/9", "7/9"], point: [1, -1, 2]}
inputs: [J2]
output: {body: l3}
configurations:
  reference: {}
  at-reference: {J2: 0}
"""


def test_a_rigid_loop_with_its_given_slide_has_only_its_reference(tmp_path: Path) -> None:
    """A generic loop of five revolutes and a slide is rigid: with the slide at its
    reference value, the reference is the one closed configuration (the square system's
    other real roots slide along the eliminated axis)."""
    f = tmp_path / "rigid.yaml"
    f.write_text(RIGID)
    doc = _modes(f, "at-reference")
    assert doc["formulation"]["name"] == NAME and doc["complete"] == "proven"
    _check(doc, f, {1: 0.0}, 1)
    assert all(abs(v[0]) < 1e-40 for v in doc["modes"][0]["joints"].values())


def test_a_loop_whose_paths_mostly_fail_in_double_is_not_tracked_again() -> None:
    """Sarrus's linkage with J1 given: its closed configurations hold a curve (J2 = J5 =
    pi/2), on which most of the axis system's paths end, and no precision makes a count
    of them; each elimination tried loses most of its 24 paths in double precision and is
    given up at once, not tracked again in adaptive precision (which crawled along the
    curve for over ten minutes): the loop goes to the general formulation."""
    import mpmath

    from mechsing import load
    from mechsing.assembly import axis
    from mechsing.assembly.engine import RETRY_FAILED
    from mechsing.assembly.given import read_given
    from mechsing.numeric import parse_precision

    mech = load(ROOT / "examples" / "sarrus.yaml")
    given = read_given(mech, "raised", parse_precision("float"), 50, 1e-9)
    with mpmath.workdps(50):
        prob, names, signs, order = axis._layout(given)
        for joint in order[: axis.ELIMINATIONS]:
            got = axis._attempt(given, prob, axis._system(given, prob, names, signs, joint))
            assert isinstance(got, str) and got.endswith("in double precision")
            lost = int(got.split(" of ")[0])
            assert lost > RETRY_FAILED * 24
