"""mechsing modes on planar mechanisms with the inputs users type (issue 41): decimal
angles (0.3 rad, whose cosine is not algebraic) and linkages of two loops solved in
stages (a Watt II and a Stephenson III six-bar with a decimal crank).

Every count and mode is checked against closed forms written from the files' geometry
(tests/reference/planar_dyads.py and modes_independent.circle_points: circle
intersections), never against mechsing.
"""

from __future__ import annotations

import json

import numpy as np

from tests.cli import run_cli
from tests.mechanisms import ROOT
from tests.reference.modes_independent import circle_points
from tests.reference.planar_dyads import place, turn, wrap

P2 = np.array


def _modes(path: str, *argv: str) -> dict:
    rc, out, err = run_cli(["modes", str(ROOT / "examples" / path), *argv, "--format", "json"])
    assert rc == 0, err
    return json.loads(out)


def _matches(expected: list[tuple[float, ...]], found: list[tuple[float, ...]]) -> None:
    """Each expected mode (angles) is exactly one found mode, and nothing else is found."""
    assert len(found) == len(expected)
    for e in expected:
        hits = [f for f in found if max(abs(wrap(a - b)) for a, b in zip(e, f, strict=True)) < 1e-9]
        assert len(hits) == 1, (e, found)


def test_five_bar_with_decimal_inputs_has_two_proven_modes() -> None:
    """five_bar.yaml at A1 = 0.3 rad, A2 = -0.2 rad: P is where the circles of radius
    5/2 about B1 and B2 meet (two points); dist1 turns by A1 + B1, dist2 by A2 + B2."""
    doc = _modes("five_bar.yaml", "--config", "inputs")
    assert doc["count"] == 2 and doc["complete"] == "proven"
    assert all(m["certified"] for m in doc["modes"])
    a1, a2 = 0.3, -0.2
    A1, A2, B1r, B2r, Pr = P2([-1.5, 0]), P2([1.5, 0]), P2([-1.5, 2]), P2([1.5, 2]), P2([0, 4])
    B1, B2 = place(A1, A1, a1, B1r), place(A2, A2, a2, B2r)
    expected = [
        (a1, a2, turn(Pr - B1r, p - B1), turn(Pr - B2r, p - B2))
        for p in circle_points(B1, 2.5, B2, 2.5)
    ]
    found = [
        (
            m["joints"]["A1"][0],
            m["joints"]["A2"][0],
            m["joints"]["A1"][0] + m["joints"]["B1"][0],
            m["joints"]["A2"][0] + m["joints"]["B2"][0],
        )
        for m in doc["modes"]
    ]
    _matches(expected, found)


def _six_bar(doc: dict, crank: float, coupler_pts: tuple, rocker: tuple, dyad: tuple) -> None:
    """A four-bar (crank B about A = 0, coupler B-C, rocker C about D) with a dyad (link
    from the point E to G on the output, which turns about F): C and G by circle
    intersections; the modes' coupler angle (A + B) and output angle (-F: F joins the
    output to ground) must be the closed form's, one mode per real assembly."""
    B_ref, C_ref = coupler_pts
    D, _ = rocker
    E_ref, G_ref, F, on_coupler = dyad
    B = place(P2([0, 0]), P2([0, 0]), crank, B_ref)
    expected = []
    for C in circle_points(B, np.linalg.norm(C_ref - B_ref), D, np.linalg.norm(C_ref - D)):
        coupler = turn(C_ref - B_ref, C - B)
        rocker_turn = turn(C_ref - D, C - D)
        E = place(B_ref, B, coupler, E_ref) if on_coupler else place(D, D, rocker_turn, E_ref)
        for G in circle_points(E, np.linalg.norm(G_ref - E_ref), F, np.linalg.norm(G_ref - F)):
            expected.append((coupler, turn(G_ref - F, G - F)))
    found = [
        (m["joints"]["A"][0] + m["joints"]["B"][0], -m["joints"]["F"][0]) for m in doc["modes"]
    ]
    _matches(expected, found)
    assert doc["count"] == len(expected) and doc["complete"] == "proven"
    assert all(m["certified"] for m in doc["modes"])


def test_watt_ii_with_a_decimal_crank_is_solved_in_two_stages() -> None:
    """watt_ii.yaml at A = 0.35 rad: the four-bar A-B-C-D, then the dyad E-G-F on its
    rocker."""
    doc = _modes("watt_ii.yaml", "--config", "crank-20")
    assert len(doc["formulation"]["stages"]) == 2
    _six_bar(
        doc,
        0.35,
        (P2([1, 0]), P2([3, 2])),
        (P2([4, 0]), None),
        (P2([5, 1]), P2([7, 1]), P2([7, -1]), False),
    )


def test_stephenson_iii_with_a_decimal_crank_is_solved_in_two_stages() -> None:
    """stephenson_iii.yaml at A = 0.35 rad: the four-bar A-B-C-D, then the dyad E-G-F on
    its coupler."""
    doc = _modes("stephenson_iii.yaml", "--config", "crank-20")
    _six_bar(
        doc,
        0.35,
        (P2([1, 0]), P2([3, 2])),
        (P2([4, 0]), None),
        (P2([2, 3]), P2([5, 3]), P2([5, 1]), True),
    )


def test_modes_at_mp_n_are_classified() -> None:
    """At mp:50 and mp:60 the modes' digits are carried to the analysis: each mode of the
    four-bar is classified (it was "not classified", the values rounded to 15 digits
    before the closure check)."""
    for prec in ("mp:50", "mp:60"):
        doc = _modes("fourbar.yaml", "--config", "crank-30", "--precision", prec)
        assert doc["count"] == 2
        assert all(m["singular"] is False for m in doc["modes"]), prec


def test_mode_numbers_do_not_depend_on_noise_far_below_the_match_distance() -> None:
    """The PUMA 560's postures at its regular configuration: two have J1 = J2 = J3 = 0 up
    to noise of 1e-51 (of either sign) and differ in J4 (0 and pi): the modes are listed
    in the order of their values rounded to 1e-8 rad, so J4 decides, not the noise."""
    doc = _modes("puma560.yaml", "--config", "regular")
    keys = []
    for m in doc["modes"]:
        q = [wrap(v[0]) for v in m["joints"].values()]
        keys.append(tuple(round((-np.pi if x > np.pi - 5e-9 else x) / 1e-8) for x in q))
    assert len(keys) == 8 and keys == sorted(keys)


def _rrr_pivots(angles: list[float]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """tests/data/planar_3rrr.yaml at its input angles: the elbows B_i (placed), the
    platform pivots C_i (platform frame) and the distal links' lengths."""
    s3, s7, s21 = np.sqrt(3), np.sqrt(7), np.sqrt(21)
    A = P2([[0, 2], [-s3, -1], [s3, -1]])
    B = P2(
        [
            [s7 / 4, 5 / 4],
            [-s7 / 8 - 5 * s3 / 8, s21 / 8 - 5 / 8],
            [-s7 / 8 + 5 * s3 / 8, -s21 / 8 - 5 / 8],
        ]
    )
    C = P2([[0, 0.5], [-s3 / 4, -1 / 4], [s3 / 4, -1 / 4]])
    now = P2([place(A[i], A[i], angles[i], B[i]) for i in range(3)])
    return now, C, np.linalg.norm(B - C, axis=1)


def test_a_3rrr_whose_eliminant_has_radicals_in_a_denominator_gets_its_modes() -> None:
    """The planar 3-RRR (tests/data) with A1 = pi/6 and A2 = A3 = 0 ended in a sympy
    PolynomialError (exit 4): its count is now the closed form's (none: the elbows are
    then out of the distal links' reach), and with decimal inputs two modes, as
    Gosselin's elimination (the reference's 3-RPR scan, legs from the elbows) finds."""
    from tests.reference.modes_independent import rpr_poses

    path = ROOT / "tests" / "data" / "planar_3rrr.yaml"
    cases = (
        ((np.pi / 6, 0, 0), ("pi/6", "0", "0")),
        ((0.1, 0, 0), ("0.1", "0", "0")),
        ((0.2, -0.1, 0.05), ("0.2", "-0.1", "0.05")),  # three decimals: minutes in sympy
    )
    for angles, texts in cases:
        sets = [f"--set=A{i + 1}={t}" for i, t in enumerate(texts)]
        rc, out, err = run_cli(["modes", str(path), *sets, "--format", "json"])
        assert rc == 0, err
        doc = json.loads(out)
        expected = rpr_poses(*_rrr_pivots(list(angles)), samples=100_000)
        assert doc["count"] == len(expected) and doc["complete"] == "proven"
        for theta, _p in expected:  # the platform turns by C1's and the dist1's turns
            hits = [
                m
                for m in doc["modes"]
                if abs(wrap(sum(m["joints"][n][0] for n in ("A1", "B1", "C1")) - theta)) < 1e-7
            ]
            assert len(hits) == 1


def test_the_double_rocker_at_pi_over_5_gets_its_two_modes() -> None:
    """examples/double_rocker.yaml at A = pi/5 (cos(pi/5) has nested radicals, with
    sqrt(15) from the file's geometry: the norm over Q ran past a probe's limit): B at the
    input's end, C where the circles about B (the coupler) and about D (the output)
    meet; the coupler turns by A + B."""
    doc = _modes("double_rocker.yaml", "--set", "A=pi/5")
    assert doc["count"] == 2 and doc["complete"] == "proven"
    a = np.pi / 5
    B_ref, C_ref, D = P2([3, 0]), P2([23 / 4, 3 * np.sqrt(15) / 4]), P2([5, 0])
    B = place(P2([0, 0]), P2([0, 0]), a, B_ref)
    expected = [
        (turn(C_ref - B_ref, C - B), turn(C_ref - D, C - D))
        for C in circle_points(B, np.linalg.norm(C_ref - B_ref), D, np.linalg.norm(C_ref - D))
    ]
    found = [
        (m["joints"]["A"][0] + m["joints"]["B"][0], -m["joints"]["D"][0]) for m in doc["modes"]
    ]
    _matches(expected, found)


def test_an_absurd_input_is_refused_before_solving() -> None:
    """--set A=1e12 (degrees) on the four-bar: refused as bad input naming the joint (it
    was found, then refused in the classification under an internal name)."""
    rc, _, err = run_cli(["modes", str(ROOT / "examples" / "fourbar.yaml"), "--set", "A=1e12"])
    assert rc == 2
    assert "fourbar.yaml" in err and "joint 'A'" in err and "#mode" not in err


POINT = """\
mechanism: 3rpr-point
bodies: [ground, cyl1, pis1, cyl2, pis2, cyl3, pis3, platform]
joints:
  - {name: Rb1, type: R, between: [ground, cyl1],   axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: P1, type: P, between: [cyl1, pis1],     axis: [3, 4, 0]}
  - {name: Rp1, type: R, between: [pis1, platform], axis: [0, 0, 1], point: [3, 4, 0]}
  - {name: Rb2, type: R, between: [ground, cyl2],   axis: [0, 0, 1], point: [8, 0, 0]}
  - {name: P2, type: P, between: [cyl2, pis2],     axis: [-5, 4, 0]}
  - {name: Rp2, type: R, between: [pis2, platform], axis: [0, 0, 1], point: [3, 4, 0]}
  - {name: Rb3, type: R, between: [ground, cyl3],   axis: [0, 0, 1], point: [-4, 11, 0]}
  - {name: P3, type: P, between: [cyl3, pis3],     axis: [7, -7, 0]}
  - {name: Rp3, type: R, between: [pis3, platform], axis: [0, 0, 1], point: [3, 4, 0]}
inputs: [P1, P2, P3]
output: {body: platform}
configurations:
  reference: {}
"""


def test_a_3rpr_whose_platform_is_a_point(tmp_path) -> None:
    """Three legs to one platform point (3, 4): at the reference slides the point is
    placed and the platform turns freely about it (a curve: no count); with P1 = 1/2
    leg 1 reaches 5.5 from (0, 0) while legs 2 and 3 keep the point at (3, 4), 5 away:
    no closed configuration (0 modes, proven)."""
    path = tmp_path / "point.yaml"
    path.write_text(POINT)
    rc, out, err = run_cli(
        ["modes", str(path), "--set", "P1=0", "--set", "P2=0", "--set", "P3=0", "--format", "json"]
    )
    assert rc == 0, err
    doc = json.loads(out)
    assert doc["complete"] == "infinite" and doc["count"] is None
    rc, out, err = run_cli(
        [
            "modes",
            str(path),
            "--set",
            "P1=1/2",
            "--set",
            "P2=0",
            "--set",
            "P3=0",
            "--format",
            "json",
        ]
    )
    assert rc == 0, err
    doc = json.loads(out)
    assert doc["count"] == 0 and doc["complete"] == "proven"


def test_time_limit_stops_the_planar_elimination_and_classification() -> None:
    """--time-limit covers the exact method and the classification too (they ran outside
    it): the 3-RRR with three decimal inputs stops with exit 3 and the reason."""
    path = ROOT / "tests" / "data" / "planar_3rrr.yaml"
    argv = ["modes", str(path), "--set", "A1=0.2", "--set", "A2=-0.1", "--set", "A3=0.05"]
    rc, _, err = run_cli([*argv, "--time-limit", "1"])
    assert rc == 3 and "within --time-limit 1 s" in err and "Traceback" not in err


def test_a_slider_crank_with_its_crank_given_is_planar_exactly() -> None:
    """slider_crank_crank_input.yaml at A = pi/3: its plane's normal is taken from the
    file's exact axes (the float one carried 1e-15 of rounding, which turned the
    mechanism off the xy plane and sent it to the general formulation, not proven).
    Closed form: B = (sin A, -cos A), C = (16/5 + P, 7/5) on the slide, |C - B| = 4 as at
    the reference, so P = sin A - 16/5 +- sqrt(16 - (7/5 + cos A)^2)."""
    doc = _modes("slider_crank_crank_input.yaml", "--config", "crank-60")
    assert doc["formulation"]["name"] == "planar platform pose"
    assert doc["count"] == 2 and doc["complete"] == "proven"
    a = np.pi / 3
    root = np.sqrt(16 - (7 / 5 + np.cos(a)) ** 2)
    expected = sorted(np.sin(a) - 16 / 5 + k * root for k in (-1, 1))
    found = sorted(m["joints"]["P"][0] for m in doc["modes"])
    assert np.allclose(found, expected, atol=1e-12), (found, expected)
