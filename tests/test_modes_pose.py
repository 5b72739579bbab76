"""``mechsing modes`` of a parallel mechanism whose configuration gives the output's pose:
its working modes, every posture of the legs that reaches the pose.

Each serial leg reaches the pose alone, so the general formulation solves the legs one
by one (their closure equations share no unknown) and a mode is one posture per leg.
Checked against closed forms derived here: a planar R-P-R leg reaches its platform
pivot along the line from its base pivot, pointing there or away (the slide then
negative), and an R-R-R leg with its elbow on either side.
"""

from __future__ import annotations

import itertools
import json
import math
from pathlib import Path

import numpy as np
import pytest
import sympy
import yaml

from tests.cli import run_cli
from tests.mechanisms import ROOT

pytest.importorskip("bertini")

#: the platforms' turn about z at the pose asked for
TURN = 0.1


def _posed(src: Path, tmp_path: Path, pose: str) -> Path:
    """The file ``src`` with its configurations replaced by the reference and ``target``."""
    text = src.read_text()
    head = text[: text.index("configurations:")]
    out = tmp_path / src.name
    out.write_text(head + f"configurations:\n  reference: {{}}\n  target: {{pose: {pose}}}\n")
    return out


def _modes(path: Path) -> dict:
    rc, out, err = run_cli(["modes", str(path), "--config", "target", "--format", "json"])
    assert rc == 0, err
    return json.loads(out)


def _wrap(a: float) -> float:
    return (a + math.pi) % (2 * math.pi) - math.pi


def _platform_points(
    pivots: list[tuple[float, float]], position: tuple[float, float]
) -> list[np.ndarray]:
    """Where the pose puts the platform's pivots: turned by TURN about the reference point
    (the centroid of the platform's joint points) and moved to ``position``."""
    c0 = np.mean(np.array(pivots), axis=0)
    R = np.array([[math.cos(TURN), -math.sin(TURN)], [math.sin(TURN), math.cos(TURN)]])
    return [np.array(position) + R @ (np.array(b) - c0) for b in pivots]


def _pose(position: tuple[float, float]) -> str:
    return f"{{position: [{position[0]}, {position[1]}, 0], rotation_vector: [0, 0, {TURN}]}}"


def _same_sets(found: list[list[float]], expected: list[list[float]], kinds: str) -> None:
    def key(v: list[float]) -> list[float]:
        return [_wrap(x) if k == "R" else x for x, k in zip(v, kinds, strict=True)]

    assert len(found) == len(expected)
    left = [key(v) for v in expected]
    for v in map(key, found):
        d = [
            max(
                abs(_wrap(a - b)) if k == "R" else abs(a - b)
                for a, b, k in zip(v, w, kinds, strict=True)
            )
            for w in left
        ]
        k = int(np.argmin(d))
        assert d[k] < 1e-9, (v, left)
        left.pop(k)


def test_3rpr_at_a_pose_has_eight_working_modes(tmp_path: Path) -> None:
    """The 3-RPR example at a pose: each leg points at its platform pivot or away from
    it, 2^3 modes, the count proven leg by leg."""
    position = (1.1, 0.9)
    doc = _modes(_posed(ROOT / "examples" / "planar_3rpr.yaml", tmp_path, _pose(position)))
    base = [(0.0, 0.0), (4.0, 0.0), (0.0, 4.0)]
    pivots = [(0.9, 0.3), (2.5, 1.5), (-0.3, 1.9)]
    legs = []
    for a, b_ref, b in zip(base, pivots, _platform_points(pivots, position), strict=True):
        d = np.array(b_ref) - np.array(a)  # the slide's axis, and the leg at the reference
        reach = np.array(b) - np.array(a)
        turn = math.atan2(reach[1], reach[0]) - math.atan2(d[1], d[0])
        length, rest = float(np.linalg.norm(reach)), float(np.linalg.norm(d))
        # (base turn, slide, platform turn relative to the leg): towards or away
        legs.append(
            [
                (turn, length - rest, TURN - turn),
                (turn + math.pi, -length - rest, TURN - turn - math.pi),
            ]
        )
    expected = [[x for leg in choice for x in leg] for choice in itertools.product(*legs)]
    names = ["Rb1", "P1", "Rp1", "Rb2", "P2", "Rp2", "Rb3", "P3", "Rp3"]
    found = [[m["joints"][n][0] for n in names] for m in doc["modes"]]
    assert doc["count"] == 8
    assert doc["complete"] == "proven"
    assert all(m["certified"] for m in doc["modes"])
    _same_sets(found, expected, "RPR" * 3)
    # the legs solved apart: 6 paths each, not the 216 of the whole system
    assert doc["formulation"]["bezout"] == 18
    assert [p["count"] for p in doc["formulation"]["parts"]] == [2, 2, 2]
    assert sum(m["reached_by_continuation"] for m in doc["modes"]) == 1
    jsonschema = pytest.importorskip("jsonschema")
    rc, out, _ = run_cli(["schema", "--modes"])
    assert rc == 0
    jsonschema.validate(doc, json.loads(out))


@pytest.mark.parametrize("reaches", [True, False])
def test_a_leg_given_whole_is_checked_not_solved(reaches: bool, tmp_path: Path) -> None:
    """The 3-RPR at the pose with leg 1's three joints given too: where they put its
    pivot on the platform's, the other two legs' 4 postures are the modes; where they do
    not, there is none, proven at once (no span refusal, no system tracked whole)."""
    position = (1.1, 0.9)
    a, b_ref = np.array([0.0, 0.0]), np.array([0.9, 0.3])
    b = _platform_points([(0.9, 0.3), (2.5, 1.5), (-0.3, 1.9)], position)[0]
    turn = math.atan2(b[1] - a[1], b[0] - a[0]) - math.atan2(b_ref[1], b_ref[0])
    slide = float(np.linalg.norm(b - a) - np.linalg.norm(b_ref))
    if not reaches:
        slide += 0.1
    values = f"Rb1: {turn!r}, P1: {slide!r}, Rp1: {TURN - turn!r}, "
    text = (ROOT / "examples" / "planar_3rpr.yaml").read_text()
    path = tmp_path / "leg_given.yaml"
    path.write_text(
        text[: text.index("configurations:")]
        + "configurations:\n  reference: {}\n"
        + f"  target: {{{values}pose: {_pose(position)}}}\n"
    )
    doc = _modes(path)
    if reaches:
        assert doc["count"] == 4
        assert all(abs(m["joints"]["P1"][0] - slide) < 1e-12 for m in doc["modes"])
    else:
        assert doc["count"] == 0 and doc["complete"] == "proven"
        assert doc["paths"] is None
        assert "leave it off the output's pose by 0.1 m" in doc["notes"][0]


def test_3rrr_at_a_pose_has_eight_working_modes(tmp_path: Path) -> None:
    """A 3-RRR at a pose: each leg's elbow on either side of the line from its base pivot
    to its platform pivot (two-link inverse kinematics), 2^3 modes."""
    src = ROOT / "tests" / "data" / "planar_3rrr.yaml"
    data = yaml.safe_load(src.read_text())
    points = {j["name"]: [float(sympy.sympify(x)) for x in j["point"][:2]] for j in data["joints"]}
    legs_joints = [j for j in data["joints"] if j["between"][0] == "ground"]
    position = (0.1, 0.05)
    doc = _modes(_posed(src, tmp_path, _pose(position)))
    # each leg: ground -> (base R) -> link -> (elbow R) -> link -> (platform R) -> platform
    chains = []
    for first in legs_joints:
        chain = [first]
        while chain[-1]["between"][1] != data["output"]["body"]:
            chain.append(
                next(j for j in data["joints"] if j["between"][0] == chain[-1]["between"][1])
            )
        chains.append([j["name"] for j in chain])
    pivots = [tuple(points[c[2]]) for c in chains]
    legs = []
    for chain, b in zip(chains, _platform_points(pivots, position), strict=True):
        a, m, p = (np.array(points[n]) for n in chain)
        l1, l2 = float(np.linalg.norm(m - a)), float(np.linalg.norm(p - m))
        reach = b - a
        r = float(np.linalg.norm(reach))
        alpha = math.atan2(reach[1], reach[0])
        # the elbow's angle off the line a-b (law of cosines), on either side
        off = math.acos((l1 * l1 + r * r - l2 * l2) / (2 * l1 * r))
        sols = []
        for side in (1, -1):
            e = a + l1 * np.array([math.cos(alpha + side * off), math.sin(alpha + side * off)])
            first = math.atan2(e[1] - a[1], e[0] - a[0]) - math.atan2(m[1] - a[1], m[0] - a[0])
            link2 = math.atan2(b[1] - e[1], b[0] - e[0]) - math.atan2(p[1] - m[1], p[0] - m[0])
            sols.append((first, link2 - first, TURN - link2))
        legs.append(sols)
    names = [n for c in chains for n in c]
    expected = [[x for leg in choice for x in leg] for choice in itertools.product(*legs)]
    found = [[m["joints"][n][0] for n in names] for m in doc["modes"]]
    assert doc["count"] == 8
    assert doc["complete"] == "proven"
    _same_sets(found, expected, "R" * 9)


@pytest.mark.parametrize("example", ["stewart_octahedral.yaml", "tsai_3upu.yaml"])
def test_legs_whose_postures_multiply_beyond_the_limit_are_refused(
    example: str, tmp_path: Path
) -> None:
    """Six U-P-S legs, or three U-P-U legs, at a pose: each leg's start system has 120
    paths, and their postures could combine into more modes than are analysed: refused at
    once, with the counts, not left running."""
    path = _posed(ROOT / "examples" / example, tmp_path, "{position: [0.05, -0.03, 1.1]}")
    rc, _out, err = run_cli(["modes", str(path), "--config", "target"])
    assert rc == 2
    assert "working modes" in err and "120, 120, 120" in err


def test_a_leg_with_a_loop_of_its_own_is_refused_naming_it(tmp_path: Path) -> None:
    """A Delta at a pose: its legs hold parallelograms, so no leg is one chain to the
    platform; refused at once, naming the leg, not left to a system closed whole."""
    path = _posed(
        ROOT / "tests" / "data" / "delta.yaml", tmp_path, "{position: [0.01, 0.02, -0.05]}"
    )
    rc, _out, err = run_cli(["modes", str(path), "--config", "target"])
    assert rc == 2
    assert "leg 1 (R1, S1a, S1c, S1b, S1d) is not one chain of joints" in err
    assert "holds a loop of its own" in err
