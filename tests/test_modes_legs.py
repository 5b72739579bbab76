"""``mechsing modes`` on spatial parallel mechanisms with legs (the leg formulation: each
leg's constraint on the platform's pose in Study coordinates): a 3-RPS, a Delta robot and
Tsai's 3-UPU, through the CLI and its JSON.

Every set of platform poses is checked against the independent solver of
``tests/reference/platform_poses_independent.py`` (damped Newton from random starts on the
legs' own closures, written here from each file's geometry; it imports nothing from
mechsing), and the translating modes of the Delta and the 3-UPU against the published
closed form: the platform's centre on three spheres, two mirror points (R. L. Williams
II, "The Delta parallel robot: kinematics solutions", 2015; L.-W. Tsai, ARK 1996).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from tests.cli import run_cli
from tests.mechanisms import ROOT
from tests.reference.platform_poses_independent import platform_poses, rotation

pytest.importorskip("bertini")

DATA = ROOT / "tests" / "data"
AZIMUTHS = (0.0, 2 * np.pi / 3, 4 * np.pi / 3)


def _modes(path: Path, config: str) -> dict:
    rc, out, err = run_cli(["modes", str(path), "--config", config, "--format", "json"])
    assert rc == 0, err
    return json.loads(out)


def _poses(doc: dict) -> list[tuple[np.ndarray, np.ndarray]]:
    return [
        (np.array(m["output_pose"])[:3, :3], np.array(m["output_pose"])[:3, 3])
        for m in doc["modes"]
    ]


def _same_poses(found: list, expected: list) -> None:
    assert len(found) == len(expected), (len(found), len(expected))
    for R, t in expected:
        assert min(np.linalg.norm(R - R2) + np.linalg.norm(t - t2) for R2, t2 in found) < 1e-8


def _three_spheres(centres: list[np.ndarray], radii: list[float]) -> list[np.ndarray]:
    """The two points on three spheres (the radical line met with the first sphere)."""
    c1, c2, c3 = centres
    r1, r2, r3 = radii
    A = np.array([2 * (c2 - c1), 2 * (c3 - c1)])
    rhs = np.array([r1**2 - r2**2 + c2 @ c2 - c1 @ c1, r1**2 - r3**2 + c3 @ c3 - c1 @ c1])
    d = np.cross(A[0], A[1])
    x0 = np.linalg.lstsq(A, rhs, rcond=None)[0]
    # |x0 + s d - c1|^2 = r1^2
    a, b, c = d @ d, 2 * d @ (x0 - c1), (x0 - c1) @ (x0 - c1) - r1**2
    disc = b * b - 4 * a * c
    return [x0 + (-b + sg * np.sqrt(disc)) / (2 * a) * d for sg in (1, -1)]


def _translating(poses: list) -> list[np.ndarray]:
    return [t for R, t in poses if np.linalg.norm(R - np.eye(3)) < 1e-9]


def test_three_rps_has_the_real_poses_of_its_sixteen() -> None:
    """A 3-RPS (tests/data/three_rps.yaml): the platform's poses for three slides; the
    complex solutions off Study's exceptional quadric number 16, the published maximum
    (C. Innocenti and V. Parenti-Castelli, ASME J. Mech. Des. 1990)."""
    slides = (0.3, -0.2, 0.1)
    doc = _modes(DATA / "three_rps.yaml", "tilted")
    assert doc["formulation"]["name"].startswith("leg constraints")
    assert [leg["kind"] for leg in doc["formulation"]["legs"]] == ["R-S"] * 3
    assert doc["paths"]["solutions"] == 16
    # all 16 found and certified, each in its own box: none missing
    assert doc["complete"] == "proven"
    legs = []
    for k, phi in enumerate(AZIMUTHS):
        c, s = np.cos(phi), np.sin(phi)
        a, b, n = np.array([2 * c, 2 * s, 0]), np.array([c, s, 2.0]), np.array([-s, c, 0])
        u = (b - a) / np.linalg.norm(b - a)
        legs.append((a, b, n, b + u * slides[k]))

    def closure(R: np.ndarray, t: np.ndarray, th: np.ndarray) -> np.ndarray:
        # the ball joint where the platform carries it and where its leg carries it
        return np.concatenate(
            [
                R @ b + t - (a + rotation(n, th[i]) @ (bq - a))
                for i, (a, b, n, bq) in enumerate(legs)
            ]
        )

    expected = platform_poses(closure, extra=3, starts=300)
    _same_poses(_poses(doc), expected)
    assert all(m["certified"] for m in doc["modes"])
    assert all(m["equivalent_solutions"] == 1 for m in doc["modes"])


def test_delta_has_the_two_mirror_translations_among_its_rod_assemblies() -> None:
    """A Delta robot (tests/data/delta.yaml: parallelograms of ball-jointed rods): every
    real assembly of the six rods for three arm angles, two of them translating the
    platform, at the two mirror points of the three spheres."""
    angles = (0.3, -0.2, 0.1)
    doc = _modes(DATA / "delta.yaml", "driven")
    assert [leg["kind"] for leg in doc["formulation"]["legs"]] == ["S-S"] * 6
    rods, centres = [], []
    for k, phi in enumerate(AZIMUTHS):
        c, s = np.cos(phi), np.sin(phi)
        n, pivot = np.array([-s, c, 0.0]), np.array([c, s, 0.0])
        elbow = pivot + rotation(n, angles[k]) @ (np.array([2 * c, 2 * s, 0]) - pivot)
        for w in (0.25, -0.25):
            e0, b = np.array([2 * c, 2 * s, 0]) + w * n, np.array([c / 2, s / 2, -2.0]) + w * n
            rods.append((pivot + rotation(n, angles[k]) @ (e0 - pivot), b, np.linalg.norm(b - e0)))
        centres.append(elbow - np.array([c / 2, s / 2, -2.0]))

    E, B, L = (np.array([rod[k] for rod in rods]) for k in range(3))

    def closure(R: np.ndarray, t: np.ndarray, _x: np.ndarray) -> np.ndarray:
        # the six rods at once (row i: |R b_i + t - e_i| - length_i)
        return np.linalg.norm(B @ R.T + t - E, axis=1) - L

    found = _poses(doc)
    _same_poses(found, platform_poses(closure, starts=300))
    moving = _translating(found)
    mirror = _three_spheres(centres, [2.5] * 3)
    assert len(moving) == 2
    for p in mirror:
        assert min(np.linalg.norm(p - t) for t in moving) < 1e-9
    assert any("spins idly" in n for n in doc["notes"])
    # six distances: at most 40 poses (Raghavan 1993), all found and certified
    assert doc["paths"]["solutions"] == 40
    assert doc["complete"] == "proven"
    # the linear-product start: one sphere (two forms in X and Y), five differences of
    # spheres (one form in X, one in X and Y), the Study quadric (X, Y), the patch (X);
    # a choice is regular when at most four forms are in X alone: 2 * (sum over d
    # differences and q = 0, 1 quadric forms in X with 1 + d + q <= 4 of C(5, d)) =
    # 2 * (26 + 16) = 84 paths (total degree 128)
    assert doc["paths"]["tracked"] == 84


def test_tsai_3upu_has_its_two_translations_and_the_rest_of_its_modes() -> None:
    """Tsai's 3-UPU (examples/tsai_3upu.yaml, configuration lateral): every real platform
    pose for the three slides; two translate the platform, at the three spheres' two
    points (Tsai's forward kinematics), the others turn it (another operation mode)."""
    slides = (0.1, -0.05, 0.0)
    doc = _modes(ROOT / "examples" / "tsai_3upu.yaml", "lateral")
    assert [leg["kind"] for leg in doc["formulation"]["legs"]] == ["U-U"] * 3
    legs, centres = [], []
    for k, phi in enumerate(AZIMUTHS):
        c, s = np.cos(phi), np.sin(phi)
        a, b = np.array([2 * c, 2 * s, 0.0]), np.array([c, s, 1.0])
        s1 = np.array([-s, c, 0.0])
        s2 = np.array([c, s, 1.0]) / np.sqrt(2)
        u = np.array([-c, -s, 1.0]) / np.sqrt(2)
        legs.append((a, b, b + u * slides[k], s1, s2))
        centres.append(a - b)

    def closure(R: np.ndarray, t: np.ndarray, q: np.ndarray) -> np.ndarray:
        out = []
        for i, (a, b, bq, s1, s2) in enumerate(legs):
            Rc = rotation(s1, q[2 * i]) @ rotation(s2, q[2 * i + 1])  # the leg, by its base U
            out.extend(a + Rc @ (bq - a) - (R @ b + t))
            # the platform U: its cross axis (s2, fixed in the leg) stays normal to the
            # platform's axis (s1 at the reference)
            out.append((Rc @ s2) @ (R @ s1))
        return np.array(out)

    found = _poses(doc)
    _same_poses(found, platform_poses(closure, extra=6, starts=300))
    moving = _translating(found)
    lengths = [np.linalg.norm(bq - a) for a, _b, bq, _s1, _s2 in legs]
    assert len(moving) == 2
    for p in _three_spheres(centres, lengths):
        assert min(np.linalg.norm(p - t) for t in moving) < 1e-9
    assert all(m["equivalent_solutions"] == 8 for m in doc["modes"])
    # the linear-product start: one sphere (two forms in X and Y), two differences of
    # spheres (X; X and Y), three quartics (three forms in X, one in X and Y), the Study
    # quadric (X; Y), the patch (X); regular when at most four forms are in X alone:
    # 2 * (sum over d differences, k quartics, q quadric forms in X with 1 + d + k + q
    # <= 4 of C(2, d) C(3, k) 3^k) = 2 * (148 + 58) = 412 paths (total degree 1024)
    assert doc["paths"]["tracked"] == 412
