"""``mechsing modes`` by the registry of formulations: the family decided once from the
subgroup the joints generate (a four-bar drawn in the xz plane has the modes of the one in
the xy plane), and the general formulation (joint displacements in Study coordinates,
each loop in its subgroup's) on spatial and spherical loops and on arms of fewer than six
joints at a target.

The modes are checked against closed forms and against the independent solver of
``tests/reference/loop_modes_independent.py`` (damped Newton from random starts on 4x4
closure matrices; it imports nothing from mechsing).
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

FOURBAR = ROOT / "examples" / "fourbar.yaml"


def _modes(argv: list[str]) -> dict:
    rc, out, err = run_cli(["modes", *argv, "--format", "json"])
    assert rc == 0, err
    return json.loads(out)


def _joint_vectors(doc: dict, names: list[str]) -> list[np.ndarray]:
    return [np.array([m["joints"][n][0] for n in names]) for m in doc["modes"]]


def _every_value(doc: dict, names: list[str]) -> list[np.ndarray]:
    """Each mode's every coordinate of the joints ``names``, in order."""
    return [np.array([x for n in names for x in m["joints"][n]]) for m in doc["modes"]]


def _same(found: list[np.ndarray], expected: list[np.ndarray], kinds: list[str]) -> None:
    assert len(found) == len(expected), (found, expected)
    for e in expected:
        assert min(np.linalg.norm(wrap_angles(kinds, e - f)) for f in found) < 1e-9, (e, found)


def _vec(*xs: str | int) -> np.ndarray:
    return np.array([float(Fraction(x)) for x in xs])


def test_a_fourbar_in_the_xz_plane_has_the_modes_of_the_xy_one(tmp_path: Path) -> None:
    # the four-bar turned by +90 deg about x: (x, y, z) -> (x, -z, y)
    text = FOURBAR.read_text()
    for old, new in (
        ("axis: [0, 0, 1]", "axis: [0, -1, 0]"),
        ("point: [1, 0, 0]", "point: [1, 0, 0]"),
        ("point: [3, 2, 0]", "point: [3, 0, 2]"),
    ):
        text = text.replace(old, new)
    turned = tmp_path / "fourbar_xz.yaml"
    turned.write_text(text)
    flat, upright = (_modes([str(f), "--config", "crank-30"]) for f in (FOURBAR, turned))
    assert upright["formulation"]["name"] == flat["formulation"]["name"] == "planar platform pose"
    assert upright["count"] == flat["count"] == 2 and upright["complete"] == "proven"
    names = ["A", "B", "C", "D"]
    _same(_joint_vectors(upright, names), _joint_vectors(flat, names), ["R"] * 4)


BENNETT = [
    ("R", _vec(0, 0, 1), _vec(0, 0, 0)),
    ("R", _vec("12/25", "-9/25", "4/5"), _vec("3/5", "4/5", 0)),
    ("R", _vec("-156/701", "429/701", "532/701"), _vec("-2353/3505", "-364/3505", "1248/3505")),
    ("R", _vec(0, "24/25", "7/25"), _vec("-8/5", 0, 0)),
]


def test_bennett_with_its_input_has_the_modes_damped_newton_finds() -> None:
    doc = _modes([str(ROOT / "examples" / "bennett.yaml"), "--config", "q1-1rad"])
    loop = [[(i, 1) for i in range(4)]]
    expected = solve_all(BENNETT, loop, {0: 1.0}, starts=600)
    assert doc["count"] == len(expected) == 1
    _same(_joint_vectors(doc, ["J1", "J2", "J3", "J4"]), expected, ["R"] * 4)
    # Bennett's relations: theta3 = -theta1, theta4 = -theta2 (q relative to the reference)
    (q,) = _joint_vectors(doc, ["J1", "J2", "J3", "J4"])
    assert abs(q[0] + q[2]) < 1e-12 and abs(q[1] + q[3]) < 1e-12
    assert doc["formulation"]["closures"][0]["subgroup"] == "D"
    assert all(m["certified"] for m in doc["modes"])


BRICARD = [
    ("R", _vec("2/7", "3/7", "6/7"), _vec(1, 0, 0)),
    ("R", _vec("1/9", "-4/9", "8/9"), _vec(0, 2, 1)),
    ("R", _vec("-4/9", "4/9", "7/9"), _vec(-1, 1, 2)),
    ("R", _vec("-2/7", "-3/7", "6/7"), _vec(-1, 0, 0)),
    ("R", _vec("-1/9", "4/9", "8/9"), _vec(0, -2, 1)),
    ("R", _vec("4/9", "-4/9", "7/9"), _vec(1, -1, 2)),
]


def test_bricard_with_its_input_has_the_modes_damped_newton_finds() -> None:
    """Bricard's line-symmetric 6R at J1 = 0.4: the two modes damped Newton finds from
    400 random starts on the 4x4 closure, each line-symmetric (J4 = J1, J5 = J2, J6 =
    J3).  The count is proven by the axis formulation (mechsing/assembly/axis.py): J4
    eliminated, 24 paths, every root certified (the general formulation tracks the six
    equations as five random combinations, 72 of whose 120 paths fail: docs/modes.md)."""
    doc = _modes([str(ROOT / "examples" / "bricard.yaml"), "--config", "q1-0.4"])
    names = ["J1", "J2", "J3", "J4", "J5", "J6"]
    expected = solve_all(BRICARD, [[(i, 1) for i in range(6)]], {0: 0.4}, starts=400)
    assert doc["count"] == len(expected) == 2
    _same(_joint_vectors(doc, names), expected, ["R"] * 6)
    for q in expected:
        assert np.allclose(q[3:], q[:3], atol=1e-9)
    assert doc["formulation"]["eliminated"] == "J4" and doc["complete"] == "proven"
    assert doc["paths"]["tracked"] == doc["paths"]["finite"] == 24
    assert all(m["certified"] for m in doc["modes"])


def test_spherical_fourbar_has_two_modes_in_the_rotations_about_its_centre() -> None:
    doc = _modes([str(ROOT / "examples" / "spherical_4r.yaml"), "--config", "crank-60"])
    o = _vec(0, 0, 0)
    joints = [
        ("R", _vec(0, 0, 1), o),
        ("R", _vec(0, "5/13", "12/13"), o),
        ("R", _vec("4/9", "8/9", "1/9"), o),
        ("R", _vec("15/17", 0, "8/17"), o),
    ]
    expected = solve_all(joints, [[(i, 1) for i in range(4)]], {0: np.pi / 3}, starts=600)
    assert doc["count"] == len(expected) == 2
    _same(_joint_vectors(doc, ["A", "B", "C", "D"]), expected, ["R"] * 4)
    closure = doc["formulation"]["closures"][0]
    assert closure["subgroup"] == "S" and closure["equations"] == 3
    assert doc["paths"]["tracked"] == 6  # 3! paths: three pairs, three equations
    assert sum(m["reached_by_continuation"] for m in doc["modes"]) == 1
    # every one of the 6 paths (the multihomogeneous Bezout number) ends at its own
    # certified solution: no mode can be missing
    assert doc["paths"]["finite"] == 6
    assert doc["complete"] == "proven"


PLANAR_3R = """
mechanism: planar-3r
bodies: [ground, l1, l2, l3]
joints:
  - {name: J1, type: R, between: [ground, l1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J2, type: R, between: [l1, l2], axis: [0, 0, 1], point: [1, 0, 0]}
  - {name: J3, type: R, between: [l2, l3], axis: [0, 0, 1], point: [2, 0, 0]}
output: {body: l3, point: [3, 0, 0]}
configurations:
  reference: {}
  target: {pose: {position: [1.5, 1.2, 0], rotation_vector: [0, 0, 0.7]}}
  tilted: {pose: {position: [1.5, 1.2, 0], rotation_vector: [0.1, 0, 0.7]}}
  lifted: {pose: {position: [1.5, 1.2, 0.3], rotation_vector: [0, 0, 0.7]}}
"""


def _two_link(x: float, y: float, a: float, b: float) -> list[tuple[float, float]]:
    """The elbow-up and elbow-down angles of a planar two-link arm reaching (x, y)."""
    c2 = (x * x + y * y - a * a - b * b) / (2 * a * b)
    out = []
    for s2 in (np.sqrt(1 - c2 * c2), -np.sqrt(1 - c2 * c2)):
        q2 = np.arctan2(s2, c2)
        q1 = np.arctan2(y, x) - np.arctan2(b * s2, a + b * c2)
        out.append((q1, q2))
    return out


def test_planar_3r_at_a_target_has_the_two_postures_of_its_closed_form(tmp_path: Path) -> None:
    f = tmp_path / "planar_3r.yaml"
    f.write_text(PLANAR_3R)
    doc = _modes([str(f), "--config", "target"])
    phi = 0.7
    wx, wy = 1.5 - np.cos(phi), 1.2 - np.sin(phi)  # the wrist: the target less the last link
    expected = [np.array([q1, q2, phi - q1 - q2]) for q1, q2 in _two_link(wx, wy, 1, 1)]
    assert doc["count"] == 2
    _same(_joint_vectors(doc, ["J1", "J2", "J3"]), expected, ["R"] * 3)
    assert doc["formulation"]["closures"][0]["subgroup"] == "G"
    assert doc["formulation"]["closures"][0]["equations"] == 3


def test_a_target_outside_the_arms_subgroup_is_refused_naming_it(tmp_path: Path) -> None:
    f = tmp_path / "planar_3r.yaml"
    f.write_text(PLANAR_3R)
    for config in ("tilted", "lifted"):
        rc, _, err = run_cli(["modes", str(f), "--config", config])
        assert rc == 2, err
        assert "outside the subgroup the arm's end moves in" in err
        assert "planar motions G across the normal [0.0, 0.0, 1.0]" in err
        assert "angle about the normal" in err


#: a SCARA at a target pose (the file benchmarks/modes.py times too)
SCARA = ROOT / "tests" / "data" / "scara_at_a_pose.yaml"


def test_scara_at_a_target_has_the_two_postures_of_its_closed_form() -> None:
    doc = _modes([str(SCARA), "--config", "target"])
    expected = [
        np.array([q1, q2, -0.1, 1.1 - q1 - q2]) for q1, q2 in _two_link(0.3, 0.5, 0.4, 0.25)
    ]
    assert doc["count"] == 2
    _same(_joint_vectors(doc, ["J1", "J2", "J3", "J4"]), expected, ["R", "R", "P", "R"])
    closure = doc["formulation"]["closures"][0]
    assert closure["subgroup"] == "X" and closure["equations"] == 4
    assert all(m["certified"] for m in doc["modes"])


def test_sarrus_with_its_input_is_a_curve_as_damped_newton_finds() -> None:
    """Sarrus's linkage with J1 given: besides its two isolated modes, the closed
    configurations with J2 = J5 = pi/2 (J1 + J2 + J3 = 0) form a curve along which J4 and
    J6 turn: damped Newton from random starts lands on many points of it.  modes says
    infinite, with dimension 1, and counts nothing."""
    doc = _modes([str(ROOT / "examples" / "sarrus.yaml"), "--config", "lowered"])
    x, y = _vec(1, 0, 0), _vec(0, 1, 0)
    joints = [
        ("R", x, _vec(0, 0, 0)),
        ("R", x, _vec(0, 1, 1)),
        ("R", x, _vec(0, 0, 2)),
        ("R", y, _vec(1, 0, 2)),
        ("R", y, _vec(2, 0, 1)),
        ("R", y, _vec(1, 0, 0)),
    ]
    found = solve_all(joints, [[(i, 1) for i in range(6)]], {0: -np.pi / 12}, starts=150)
    curve = [q for q in found if abs(q[1] - np.pi / 2) < 1e-6 and abs(q[4] - np.pi / 2) < 1e-6]
    assert len({round(q[3], 3) for q in curve}) > 5  # J4 takes many values on it
    assert doc["count"] is None and doc["complete"] == "infinite" and doc["modes"] == []
    assert doc["formulation"]["dimension"] == 1 and doc["formulation"]["randomized"]
    assert doc["paths"]["tracked"] == 120  # 5!: five pairs


def test_a_redundant_planar_arm_at_a_target_is_a_curve_of_dimension_one(tmp_path: Path) -> None:
    text = PLANAR_3R.replace(
        "output: {body: l3, point: [3, 0, 0]}",
        "  - {name: J4, type: R, between: [l3, l4], axis: [0, 0, 1], point: [3, 0, 0]}\n"
        "output: {body: l4, point: [4, 0, 0]}",
    ).replace("bodies: [ground, l1, l2, l3]", "bodies: [ground, l1, l2, l3, l4]")
    f = tmp_path / "planar_4r.yaml"
    f.write_text(text)
    doc = _modes([str(f), "--config", "target"])
    assert doc["count"] is None and doc["complete"] == "infinite" and doc["modes"] == []
    # four pairs, three closure equations in G: a curve, by the local dimension test
    assert doc["formulation"]["dimension"] == 1
    assert any("local dimension test" in n for n in doc["notes"])


AGILE_EYE = """
mechanism: agile-eye
bodies: [ground, a1, b1, a2, b2, a3, b3, platform]
joints:
  - {name: A1, type: R, between: [ground, a1], axis: [1, 0, 0], point: [0, 0, 0]}
  - {name: B1, type: R, between: [a1, b1], axis: [0, 1, 0], point: [0, 0, 0]}
  - {name: C1, type: R, between: [b1, platform], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: A2, type: R, between: [ground, a2], axis: [0, 1, 0], point: [0, 0, 0]}
  - {name: B2, type: R, between: [a2, b2], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: C2, type: R, between: [b2, platform], axis: [1, 0, 0], point: [0, 0, 0]}
  - {name: A3, type: R, between: [ground, a3], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B3, type: R, between: [a3, b3], axis: [1, 0, 0], point: [0, 0, 0]}
  - {name: C3, type: R, between: [b3, platform], axis: [0, 1, 0], point: [0, 0, 0]}
inputs: [A1, A2, A3]
output: {body: platform}
configurations:
  reference: {}
  turned: {A1: 0.3, A2: -0.2, A3: 0.5}
"""


def test_agile_eye_has_eight_modes_in_two_spherical_loops(tmp_path: Path) -> None:
    """Gosselin's agile eye (a spherical 3-RRR, every axis through the origin, each leg's
    three axes orthogonal at the reference) with decimal inputs: at most 8 modes; here all
    8 are real, as damped Newton on the two loops' 4x4 closures finds."""
    f = tmp_path / "agile_eye.yaml"
    f.write_text(AGILE_EYE)
    doc = _modes([str(f), "--config", "turned"])
    o = _vec(0, 0, 0)
    x, y, z = _vec(1, 0, 0), _vec(0, 1, 0), _vec(0, 0, 1)
    joints = [("R", u, o) for u in (x, y, z, y, z, x, z, x, y)]
    loops = [
        [(0, 1), (1, 1), (2, 1), (5, -1), (4, -1), (3, -1)],
        [(0, 1), (1, 1), (2, 1), (8, -1), (7, -1), (6, -1)],
    ]
    expected = solve_all(joints, loops, {0: 0.3, 3: -0.2, 6: 0.5}, starts=400)
    assert doc["count"] == len(expected) == 8
    names = ["A1", "B1", "C1", "A2", "B2", "C2", "A3", "B3", "C3"]
    _same(_joint_vectors(doc, names), expected, ["R"] * 9)
    assert [c["subgroup"] for c in doc["formulation"]["closures"]] == ["S", "S"]
    assert [c["equations"] for c in doc["formulation"]["closures"]] == [3, 3]
    assert all(m["certified"] for m in doc["modes"])


RSSR = ROOT / "tests" / "data" / "rssr.yaml"


def test_rssr_with_its_input_has_two_modes_the_coupler_listed_without_spin() -> None:
    """An RSSR's coupler turns idly about the line through its two ball joints: the
    modes are the rocker's two positions (the coupler free of spin about that line), not a
    curve.  Closed form: the crank's ball at B = (cos a, sin a, 0), the rocker's at C =
    (3, 1 - 2 sin f, 2 cos f) (f its angle about x from the reference, the joint D's value
    being -f: D is written from the rocker to ground), |C - B|^2 = 9 as at the reference,
    so sin f = (u^2 + v^2 - 5) / (4 v) with u = 3 - cos a, v = 1 - sin a."""
    doc = _modes([str(RSSR), "--config", "crank-30"])
    a = np.pi / 6
    u, v = 3 - np.cos(a), 1 - np.sin(a)
    s = (u * u + v * v - 5) / (4 * v)
    expected = sorted(wrap_angles(["R"] * 2, np.array([-np.arcsin(s), -(np.pi - np.arcsin(s))])))
    assert doc["count"] == 2
    # the rocker's half-angle pair solves a quadratic: two certified modes prove the count
    assert doc["complete"] == "proven"
    got = sorted(m["joints"]["D"][0] for m in doc["modes"])
    assert np.allclose(got, expected, atol=1e-12), (got, expected)
    assert doc["formulation"]["idle_spins"] == [["coupler", "B", "C"]]
    B0, C0 = np.array([1.0, 0, 0]), np.array([3.0, 1, 2])
    for m in doc["modes"]:
        assert m["certified"]
        # B's rotation vector has no component along the coupler's line at the reference
        assert abs(np.dot(m["joints"]["B"], C0 - B0)) < 1e-12


def test_rssr_whose_crank_cannot_be_reached_has_no_mode_proven() -> None:
    """The RSSR's crank at pi: by the closed form sin f = (u^2 + v^2 - 5) / (4 v) = 3 (u
    = 4, v = 1), no real rocker angle; the rod's quadratic has two complex roots, each
    certified not real, so no mode is proven (continuation's 60 paths proved nothing)."""
    u, v = 3 - np.cos(np.pi), 1 - np.sin(np.pi)
    assert abs((u * u + v * v - 5) / (4 * v)) > 1
    doc = _modes([str(RSSR), "--config", "crank-180"])
    assert doc["count"] == 0 and doc["complete"] == "proven" and doc["modes"] == []


RSSP = """
mechanism: rssp
bodies: [ground, crank, coupler, slider]
joints:
  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: S, between: [crank, coupler], point: [1, 0, 0]}
  - {name: C, type: S, between: [coupler, slider], point: [3, 1, 2]}
  - {name: D, type: P, between: [ground, slider], axis: [1, 0, 0]}
inputs: [A]
output: {body: slider}
configurations:
  reference: {}
  crank-30: {A: "pi/6"}
"""


def test_rssp_with_its_input_has_two_modes_proven_by_the_rods_length(tmp_path: Path) -> None:
    """An RSSP (the RSSR's rocker a slider along x): closed form, the crank's ball at B =
    (cos a, sin a, 0), the slider's at C = (3 + x, 1, 2), |C - B|^2 = 9 as at the
    reference, so x = cos a - 3 +- sqrt(5 - (1 - sin a)^2): two modes, the count proven
    (a quadratic in the slide has at most two roots)."""
    f = tmp_path / "rssp.yaml"
    f.write_text(RSSP)
    doc = _modes([str(f), "--config", "crank-30"])
    a = np.pi / 6
    r = np.sqrt(5 - (1 - np.sin(a)) ** 2)
    assert doc["count"] == 2 and doc["complete"] == "proven"
    got = sorted(m["joints"]["D"][0] for m in doc["modes"])
    assert np.allclose(got, [np.cos(a) - 3 - r, np.cos(a) - 3 + r], atol=1e-12), got
    assert all(m["certified"] for m in doc["modes"])
    B0, C0 = np.array([1.0, 0, 0]), np.array([3.0, 1, 2])
    for m in doc["modes"]:
        assert abs(np.dot(m["joints"]["B"], C0 - B0)) < 1e-12


def test_span_is_mpmath_svd_bit_for_bit() -> None:
    """The closure's span skips only mpmath.svd_r's right singular vectors: its basis is
    svd_r's U to the bit (wide, square and tall coefficient matrices, rank deficient)."""
    import mpmath
    import sympy

    from mechsing.assembly.certify import poly_terms
    from mechsing.assembly.general import _span

    rng = np.random.default_rng(5)
    xs = sympy.symbols("x0:3")
    with mpmath.workdps(50):
        for k, rank in ((3, 8), (8, 4), (17, 6)):
            dirs = rng.integers(-9, 10, (rank, 8))
            monos = [xs[i % 3] ** (1 + i // 3) for i in range(k)]
            product = [
                sum(
                    sympy.Rational(int(c @ dirs[:, n]), 7) * m
                    for c, m in zip(rng.integers(-5, 6, (k, rank)), monos, strict=True)
                )
                for n in range(8)
            ]
            V = _span(product, list(xs))
            cols: dict = {}
            for n, comp in enumerate(product):
                for mono, c in poly_terms(comp, list(xs)):
                    cols.setdefault(mono, [0] * 8)[n] = mpmath.mpf(sympy.N(c, 50))
            M = mpmath.matrix([[int(n == 0)] + [c[n] for c in cols.values()] for n in range(8)])
            U, S, _ = mpmath.svd_r(M)
            r = sum(1 for x in S if x > 1e-20 * S[0])
            assert V == (U[:, :r] if r < U.cols else U)


def test_translation_joints_are_written_as_slides(tmp_path: Path) -> None:
    """A T2 joint (two slides in a plane) closes a loop: a crank A turning a plate that
    only translates, pinned to the crank at B (2, 1): the plate moves by B's displacement
    Rot(A) B - B, so T (plate to ground) is its opposite and B = -A; one mode.  And a T3
    joint with a ball joint after it, at a pose: T moves the ball's centre, the ball turns
    the rest: one mode, the given values."""
    f = tmp_path / "crank_t2.yaml"
    f.write_text(
        "mechanism: crank-on-a-translating-plate\n"
        "bodies: [ground, crank, plate]\n"
        "joints:\n"
        "  - {name: A, type: R, between: [ground, crank], axis: [0, 0, 1], point: [0, 0, 0]}\n"
        "  - {name: B, type: R, between: [crank, plate], axis: [0, 0, 1], point: [2, 1, 0]}\n"
        "  - {name: T, type: T2, between: [plate, ground], normal: [0, 0, 1]}\n"
        "inputs: [A]\n"
        "configurations:\n  reference: {}\n  turned: {A: 0.7}\n"
    )
    doc = _modes([str(f), "--config", "turned"])
    a, b0 = 0.7, np.array([2.0, 1.0])
    rot = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
    moved = rot @ b0 - b0
    assert doc["count"] == 1
    _same(_every_value(doc, ["A", "B", "T"]), [np.array([a, -a, *(-moved)])], list("RRPP"))
    assert all(m["certified"] for m in doc["modes"])
    chain = ROOT / "tests" / "data" / "t3_s_chain.yaml"
    given = yaml.safe_load(chain.read_text())["configurations"]["middle-axis"]
    doc = _modes([str(chain), "--config", "middle-axis"])
    assert doc["count"] == 1
    _same(
        _every_value(doc, ["T", "S"]),
        [np.array([*given["T"], 0.0, np.pi / 2, 0.0])],
        list("PPPPPP"),
    )


@pytest.mark.parametrize("config", ["moved", "posed"])
def test_an_arm_joint_given_as_a_displacement_is_refused_by_name(
    config: str, tmp_path: Path
) -> None:
    """A serial arm whose configuration (or its start) gives a ball joint as a rotation
    matrix: modes takes joint values, and says so naming the joint, exit 2 (both cases
    were an internal error, exit 4)."""
    f = tmp_path / "rcs_arm.yaml"
    rot = "{rotation: [[1, 0, 0], [0, 0, -1], [0, 1, 0]]}"
    f.write_text(
        "mechanism: rcs-arm\n"
        "bodies: [ground, a, b, c]\n"
        "joints:\n"
        "  - {name: J1, type: R, between: [ground, a], axis: [0, 0, 1], point: [0, 0, 0]}\n"
        "  - {name: C1, type: C, between: [a, b], axis: [1, 0, 0], point: [0, 0, 1]}\n"
        "  - {name: S1, type: S, between: [b, c], point: [1, 0, 1]}\n"
        "output: {body: c}\n"
        "configurations:\n"
        "  reference: {}\n"
        "  bent: {J1: 0.3, C1: [0.2, 0.1], S1: [0.1, 0.2, 0.3]}\n"
        f"  moved: {{start: bent, S1: {rot}}}\n"
        f"  posed: {{pose: {{position: [0.5, 0.2, 1.1]}}, S1: {rot}}}\n"
    )
    rc, _out, err = run_cli(["modes", str(f), "--config", config])
    assert rc == 2, err
    assert "joint S1 is given as a displacement; modes takes joint values" in err


class _Meta:
    """A path's metadata as Bertini 2 gives it: its endgame's success code."""

    def __init__(self, c: object) -> None:
        self.endgame_success_code = c


class _Solver:
    """A solver whose paths ended with ``codes`` (without ``metadata``: one that does not
    say how its paths ended)."""

    def __init__(self, codes: list[object], metadata: bool = True) -> None:
        self.codes = codes
        if metadata:
            self.solution_metadata = lambda: [_Meta(c) for c in self.codes]

    def num_paths(self) -> int:
        return len(self.codes)


@pytest.mark.parametrize(
    "failed, again, metadata",
    # of 8 paths (RETRY_FAILED is 1/4); a solver without the paths' metadata: no retry
    [(0, False, True), (1, True, True), (2, True, True), (3, False, True), (1, False, False)],
)
def test_a_double_tracking_that_failed_a_few_paths_runs_again_in_adaptive_precision(
    monkeypatch: pytest.MonkeyPatch, failed: int, again: bool, metadata: bool
) -> None:
    """A failed path may hide a mode: where double precision failed some paths (neither
    converged nor went to infinity), at most a quarter of them, the system is tracked again
    in adaptive precision and its endpoints are those of the second run; where none failed,
    or more than a quarter (paths ending on a set that is not finite), not; nor where the
    caller asks for no retry.  The success codes of the double run (Bertini's own
    ``SuccessCode`` members) are set by a wrapper around Bertini's solve of a system of
    two conics (four finite solutions, no path lost)."""
    import bertini
    import sympy

    from mechsing.assembly import engine

    x, y = sympy.symbols("x y")
    eqs = [x**2 + y**2 - 4, x * y - 1]
    real_solve = bertini.solve
    runs: list[str] = []
    code = bertini.SuccessCode

    class Result:
        def __init__(self, solutions: object, solver: _Solver) -> None:
            self.solutions, self.solver = solutions, solver

    def solve(system: object, **kw: object) -> object:
        result = real_solve(system, **kw)
        runs.append(str(kw["mptype"]))
        if kw["mptype"] == "double":
            codes = [code.FailedToConverge] * failed + [code.GoingToInfinity] * 2
            codes += [code.SecurityMaxNormReached] * 2
            codes += [code.Success] * (8 - len(codes))
            return Result(result.solutions, _Solver(codes, metadata))
        return result

    monkeypatch.setattr(bertini, "solve", solve)
    raw, _ = engine.track(eqs, [[x, y]], mptype="double")
    assert runs == (["double", "adaptive"] if again else ["double"])
    assert len(raw) == 4
    for z in raw:
        assert abs(z[0] ** 2 + z[1] ** 2 - 4) < 1e-9 and abs(z[0] * z[1] - 1) < 1e-9
    runs.clear()
    engine.track(eqs, [[x, y]], mptype="double", retry=False)
    assert runs == ["double"]


def test_where_bertini_refuses_the_adaptive_run_the_double_run_s_endpoints_stand(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The retry in adaptive precision is a second chance, not a new way to fail: should
    Bertini refuse it, the endpoints double precision found are returned."""
    from mechsing.assembly import engine

    calls: list[str] = []

    def run(model: str) -> tuple[str, str]:
        calls.append(model)
        if model == "adaptive":
            raise RuntimeError("refused")
        return "double result", "solver"

    monkeypatch.setattr(engine, "_failed_a_few", lambda solver, tight: True)
    assert engine._with_retry(run, "double", True) == ("double result", "solver")
    assert calls == ["double", "adaptive"]


def test_a_linear_product_tracking_is_run_again_in_adaptive_precision_too(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The linear-product start system's tracking takes the same rule: with its double
    run's failures counted a few, it is tracked again in adaptive precision (the same two
    conics, every solution found)."""
    import sympy

    from mechsing.assembly import engine

    x, y = sympy.symbols("x y")
    eqs = [x**2 + y**2 - 4, x * y - 1]
    factors = [[[0, 1], [0, 1]], [[0], [1]]]
    choices = engine.linear_product_paths(factors, 2)
    asked: list[bool] = []
    real = engine._failed_a_few

    def failed_a_few(solver: object, tight: bool) -> bool:
        asked.append(real(solver, tight))  # the real solver's metadata is read
        return True

    monkeypatch.setattr(engine, "_failed_a_few", failed_a_few)
    raw, tracked = engine.track_linear_product(eqs, [x, y], factors, choices, mptype="double")
    assert asked == [False]  # asked once, of the double run only
    assert tracked == len(choices) == 4
    assert len(raw) == 4
    for z in raw:
        assert abs(z[0] ** 2 + z[1] ** 2 - 4) < 1e-9 and abs(z[0] * z[1] - 1) < 1e-9


def test_a_tight_tracking_counts_a_path_to_infinity_as_lost() -> None:
    """Where every path is to end at a finite root (the axis formulation's 24), a path
    that went to infinity is lost as a failed one is: one of eight is a few (tracked
    again), three of eight too many; without ``tight`` neither is a failure."""
    import bertini

    from mechsing.assembly import engine

    code = bertini.SuccessCode
    one = _Solver([code.GoingToInfinity] + [code.Success] * 7)
    three = _Solver([code.SecurityMaxNormReached] * 3 + [code.Success] * 5)
    assert engine._failed_a_few(one, tight=True)
    assert not engine._failed_a_few(three, tight=True)
    assert not engine._failed_a_few(one) and not engine._failed_a_few(three)
