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


def _modes(path: Path, config: str = "target") -> dict:
    rc, out, err = run_cli(["modes", str(path), "--config", config, "--format", "json"])
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
    path = _posed(ROOT / "examples" / "planar_3rpr.yaml", tmp_path, _pose(position))
    doc = _modes(path)
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
    # what the modes are, in the JSON and in the heading
    assert doc["formulation"]["working_modes"] is True
    rc, text, _ = run_cli(["modes", str(path), "--config", "target"])
    assert rc == 0 and ": 8 working modes (complete: proven;" in text.splitlines()[0]
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


def _rps_pose() -> tuple[str, list[np.ndarray], list[np.ndarray], list[np.ndarray]]:
    """A pose the 3-RPS of ``tests/data/three_rps.yaml`` reaches, found here with scipy
    alone: its slides at (0.3, -0.2, 0.1), each leg turned about its R axis until the
    ball centres are as far apart as the platform's (fsolve from the reference), the
    platform's pose then fitted to those centres (Kabsch).  Returned: the pose as the
    file writes it (its reference point, the centroid of the ball centres, and its
    rotation vector), and per leg its R point, R axis and ball centre there."""
    from scipy.optimize import fsolve
    from scipy.spatial.transform import Rotation

    s3 = math.sqrt(3)
    bases = [np.array(b) for b in ([2, 0, 0], [-1, s3, 0], [-1, -s3, 0])]
    axes = [np.array(a) for a in ([0, 1, 0], [-s3 / 2, -1 / 2, 0], [s3 / 2, -1 / 2, 0])]
    balls0 = [np.array(c) for c in ([1, 0, 2], [-1 / 2, s3 / 2, 2], [-1 / 2, -s3 / 2, 2])]
    slides = (0.3, -0.2, 0.1)

    def ball(i: int, angle: float) -> np.ndarray:
        d = balls0[i] - bases[i]
        d = d + slides[i] * d / np.linalg.norm(d)
        return bases[i] + Rotation.from_rotvec(angle * axes[i]).apply(d)

    sides = [np.linalg.norm(balls0[i] - balls0[j]) for i, j in ((0, 1), (1, 2), (2, 0))]

    def gaps(angles: np.ndarray) -> list[float]:
        c = [ball(i, a) for i, a in enumerate(angles)]
        return [
            float(np.linalg.norm(c[i] - c[j]) - L)
            for (i, j), L in zip(((0, 1), (1, 2), (2, 0)), sides, strict=True)
        ]

    angles = fsolve(gaps, np.zeros(3), xtol=1e-12)
    assert max(map(abs, gaps(angles))) < 1e-13
    balls = [ball(i, a) for i, a in enumerate(angles)]
    c0, c1 = np.mean(balls0, axis=0), np.mean(balls, axis=0)
    H = sum(np.outer(b0 - c0, b1 - c1) for b0, b1 in zip(balls0, balls, strict=True))
    U, _, Vt = np.linalg.svd(H)
    R = Vt.T @ np.diag([1, 1, np.linalg.det(Vt.T @ U.T)]) @ U.T
    rv = Rotation.from_matrix(R).as_rotvec()
    pose = f"{{position: [{', '.join(map(repr, map(float, c1)))}], rotation_vector: [{', '.join(map(repr, map(float, rv)))}]}}"
    return pose, bases, axes, balls


def test_3rps_at_a_pose_has_two_postures_a_leg(tmp_path: Path) -> None:
    """A 3-RPS at a pose it reaches: each leg's line passes through its R point and its
    ball centre, turned about the R axis to point at the ball (slide |p - b| - |d|) or
    away from it (-|p - b| - |d|): 2 postures a leg, 8 working modes (each leg's start
    system has 20 paths: their product, 8,000, was refused before the legs were
    solved)."""
    pose, bases, axes, balls = _rps_pose()
    path = _posed(ROOT / "tests" / "data" / "three_rps.yaml", tmp_path, pose)
    doc = _modes(path)
    assert doc["count"] == 8
    assert [p["count"] for p in doc["formulation"]["parts"]] == [2, 2, 2]
    s3 = math.sqrt(3)
    balls0 = [np.array(c) for c in ([1, 0, 2], [-1 / 2, s3 / 2, 2], [-1 / 2, -s3 / 2, 2])]
    legs = []
    for b, a, p, p0 in zip(bases, axes, balls, balls0, strict=True):
        d0, d = p0 - b, p - b
        reach = float(np.linalg.norm(d0))
        # the turn about a that takes d0's direction to d's (both normal to a)
        turn = math.atan2(float(a @ np.cross(d0, d)), float(d0 @ d))
        legs.append(
            [
                [turn, float(np.linalg.norm(d)) - reach],
                [_wrap(turn + math.pi), -float(np.linalg.norm(d)) - reach],
            ]
        )
    expected = [[x for leg in choice for x in leg] for choice in itertools.product(*legs)]
    names = ["R1", "P1", "R2", "P2", "R3", "P3"]
    found = [[m["joints"][n][0] for n in names] for m in doc["modes"]]
    _same_sets(found, expected, "RPRPRP")


def test_3prs_at_a_pose_has_two_postures_a_leg() -> None:
    """A 3-PRS with generic inclined sliders (``tests/data/three_prs.yaml``) at a pose it
    reaches: a leg's R axis is normal to its slide, so the ball centre p stays at the
    link's distance from the R axis: with d = p - r0 (r0 the R point at slide 0) and u
    the slide's direction, t^2 - 2 t u.d + |d|^2 - |c0 - r0|^2 = 0 gives the slide's two
    values, the turn about the R axis the angle from c0 - r0 to d - t u (their parts normal
    to the axis).  The file's
    numbers and the pose are read with yaml alone.  (In double precision a path of the
    second leg failed and its long slide, 4.06 m, was missed: 4 modes of 8.)"""
    from scipy.spatial.transform import Rotation

    path = ROOT / "tests" / "data" / "three_prs.yaml"
    data = yaml.safe_load(path.read_text())
    joints = {j["name"]: j for j in data["joints"]}
    pose = data["configurations"]["at-pose"]["pose"]
    turn = Rotation.from_rotvec(pose["rotation_vector"])
    o = np.array(data["output"]["point"], dtype=float)
    legs = []
    for i in (1, 2, 3):
        u = np.array(joints[f"P{i}"]["axis"], dtype=float)
        u /= np.linalg.norm(u)
        a = np.array(joints[f"R{i}"]["axis"], dtype=float)
        a /= np.linalg.norm(a)
        r0 = np.array(joints[f"R{i}"]["point"], dtype=float)
        c0 = np.array(joints[f"S{i}"]["point"], dtype=float)
        assert abs(a @ u) < 1e-12  # the R axis normal to the slide
        p = np.array(pose["position"]) + turn.apply(c0 - o)
        d, v0 = p - r0, c0 - r0
        assert abs(a @ d - a @ v0) < 1e-9  # the pose is reached: p in the R's plane
        disc = (u @ d) ** 2 - d @ d + v0 @ v0
        assert disc > 0.05
        postures = []
        for t in (u @ d + math.sqrt(disc), u @ d - math.sqrt(disc)):
            # the turn about a: between the parts of c0 - r0 and d - t u normal to a
            w, v = d - t * u - (a @ d) * a, v0 - (a @ v0) * a
            postures.append([float(t), math.atan2(float(a @ np.cross(v, w)), float(v @ w))])
        legs.append(postures)
    doc = _modes(path, "at-pose")
    assert [p["count"] for p in doc["formulation"]["parts"]] == [2, 2, 2]
    expected = [[x for leg in choice for x in leg] for choice in itertools.product(*legs)]
    found = [
        [m["joints"][n][0] for n in ("P1", "R1", "P2", "R2", "P3", "R3")] for m in doc["modes"]
    ]
    assert doc["count"] == 8
    _same_sets(found, expected, "PRPRPR")
    assert all(m["certified"] for m in doc["modes"])


def test_parts_whose_solutions_combine_beyond_the_limit_are_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The modes the parts' solutions combine into are counted once the parts are solved:
    beyond the most analysed, refused (exit 2) with each part's count (a Gough-Stewart
    platform at a pose, four postures a leg: 4,096; here the limit lowered to 4 on the
    3-RPS's 2 x 2 x 2)."""
    from mechsing.assembly import parts

    monkeypatch.setattr(parts, "MAX_MODES", 4)
    pose, *_ = _rps_pose()
    path = _posed(ROOT / "tests" / "data" / "three_rps.yaml", tmp_path, pose)
    rc, _out, err = run_cli(["modes", str(path), "--config", "target"])
    assert rc == 2
    assert "no method applies" not in err
    assert "2 x 2 x 2 real solutions (R1, P1, S1: 2; R2, P2, S2: 2; R3, P3, S3: 2)" in err
    assert "combine into 8 modes, more than the 4 analysed at most" in err
    assert "configuration 'target'" in err and "give some of these joints' values" in err


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
