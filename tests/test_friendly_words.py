"""Screws in words, and the text report's legs, output motion and singular twists/wrenches.

Each screw is built by hand from its axis, point and pitch (v = p x omega + h omega for a
twist, m = p x f + h f for a wrench), independently of the code under test.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mechsing.analysis import analyze
from mechsing.analysis.words import twist_words, velocity_words, wrench_words
from mechsing.reports.render import render_text
from tests.mechanisms import CENTRED_SLIDER_CRANK_MM

EX = Path(__file__).resolve().parents[1] / "examples"


def _twist(axis, point, pitch):
    w = np.asarray(axis, float)
    return np.concatenate([w, np.cross(point, w) + pitch * w])


def _wrench(direction, point, pitch):
    f = np.asarray(direction, float)
    return np.concatenate([f, np.cross(point, f) + pitch * f])


def test_pure_rotation_names_its_axis_and_a_point_on_it():
    t = _twist([0, 0, 1], [1, 2, 0], 0.0)
    assert list(t) == [0, 0, 1, 2, -1, 0]  # v = p x omega, by hand
    assert twist_words(t) == "a rotation about the axis through (1, 2, 0) m along z"


def test_pure_translation_is_the_infinite_pitch():
    assert twist_words([0, 0, 0, 1, 0, 0]) == "a translation along x"
    assert twist_words([0, 0, 0, 0, 0, -3]) == "a translation along -z"
    assert twist_words([0, 0, 0, 0.6, 0.8, 0]) == "a translation along (0.6, 0.8, 0)"


def test_screw_gives_its_pitch_in_m_per_rad():
    t = _twist([1, 0, 0], [0, 0.1, 0], 0.02)
    assert np.allclose(t, [1, 0, 0, 0.02, 0, -0.1])
    assert twist_words(t) == (
        "a screw motion of pitch 0.02 m/rad about the axis through (0, 0.1, 0) m along x"
    )


def test_oblique_rotation_axis_and_the_closest_point_to_the_origin():
    s = 1 / np.sqrt(2)
    # the axis through (1, 0, 0) along (1, 1, 0)/sqrt2: its point closest to the origin
    # is (1/2, -1/2, 0)
    t = _twist([s, s, 0], [1, 0, 0], 0.0)
    assert twist_words(t) == (
        "a rotation about the axis through (0.5, -0.5, 0) m along (0.7071, 0.7071, 0)"
    )


def test_force_couple_and_wrench_with_pitch():
    w = _wrench([0, 1, 0], [0, 0, -0.5], 0.0)
    assert np.allclose(w, [0, 1, 0, 0.5, 0, 0])
    assert wrench_words(w) == "a force along y through (0, 0, -0.5) m"
    assert wrench_words([0, 0, 0, 0, 0, 2]) == "a couple about z"
    w = _wrench([0, 0, 1], [1, 0, 0], 0.1)
    assert wrench_words(w) == (
        "a force along z through (1, 0, 0) m with a couple along it (a wrench of pitch 0.1 m)"
    )


@pytest.mark.parametrize("unit", [1.0, 1000.0])
def test_the_decisions_do_not_depend_on_the_unit_of_length(unit):
    # the same rotation in m and in mm (lengths times 1000, L too); a rounding-level pitch
    # and a rounding-level rotation rate stay a rotation and a translation
    t = _twist([0, 0, 1], np.array([0.3, 0.0, 0.0]) * unit, 1e-17 * unit)
    assert twist_words(t, length_scale=unit).startswith("a rotation about the axis")
    assert twist_words([1e-19, 0, 0, 0, 0.5 * unit, 0], length_scale=unit) == (
        "a translation along y"
    )
    f = _wrench([1, 0, 0], np.array([0, 0.2, 0]) * unit, 0.0)
    assert wrench_words(f, length_scale=unit).startswith("a force along x")


def test_point_velocity():
    assert velocity_words([0, 2, 0]) == "the point moves along y"


def test_text_lists_legs_and_the_output_motion_in_words():
    text = render_text(analyze(EX / "tsai_3upu.yaml", precision="float"))
    assert "Legs (joints from ground to platform):" in text
    for i in (1, 2, 3):
        assert f"  leg {i}: U{i}a - P{i} - U{i}b\n" in text
    assert "platform's twists span T3 (spatial translation, dimension 3)" in text
    # at the flat constraint singularity the couples n_i lie along the horizontal legs:
    # the platform gains the rotation about the vertical through its centre, the origin
    assert "platform's twists span X (Schoenflies motion, dimension 4): axis z" in text
    assert "output motion: a rotation about the axis through (0, 0, 0) m along z" in text
    assert "constraint wrench: a couple about x" in text
    assert "constraint wrench: a couple about y" in text


def test_text_of_a_rocker_and_of_a_lost_twist():
    text = render_text(analyze(EX / "fourbar.yaml", precision="float"))
    # one twist: the rocker's instantaneous screw, the rotation about D's axis
    assert (
        "rocker's instantaneous screw: a rotation about the axis through (4, 0, 0) m along z "
        "(R (rotation about an axis (revolute), dimension 1): axis z, point (4, 0, 0) m)"
    ) in text
    # a serial arm at a singularity: each lost twist and resisted wrench in words
    text = render_text(analyze(EX / "ur5.yaml", configs=["wrist"], precision="float"))
    assert "    lost twist: a " in text and "    resisted wrench: a " in text


def test_3rpr_type_ii_turns_about_the_common_point_of_its_legs():
    # examples/planar_3rpr.yaml, configuration concurrent: the three leg lines pass through
    # c = (1, 1) (Bonev, Zlatanov, Gosselin 2003): with the actuators locked the platform
    # turns about the vertical through c
    text = render_text(analyze(EX / "planar_3rpr.yaml", configs=["concurrent"], precision="float"))
    lines = text.splitlines()
    at = lines.index(next(x for x in lines if x.startswith("  output: ")))
    assert lines[at + 1] in (
        "    output motion: a rotation about the axis through (1, 1, 0) m along z",
        "    output motion: a rotation about the axis through (1, 1, 0) m along -z",
    )


def test_point_velocity_spaces():
    from mechsing.analysis.words import velocity_space_words

    assert velocity_space_words([]) == "stays still"
    assert velocity_space_words([[0, 0, -1]]) == "moves along -z only"
    # two velocities in the plane x + y = 0 ... its normal (1, 1, 0)/sqrt2, shown with a
    # positive first component whatever the order of the basis
    s = 1 / np.sqrt(2)
    for basis in ([[s, -s, 0], [0, 0, 1]], [[0, 0, 1], [s, -s, 0]]):
        assert velocity_space_words(basis) == "moves in the plane normal to (0.7071, 0.7071, 0)"
    assert velocity_space_words([[1, 0, 0], [0, 1, 0], [0, 0, 1]]) == "moves in every direction"


def test_five_bar_text_says_where_its_point_moves():
    text = render_text(analyze(EX / "five_bar.yaml", configs=["reference"], precision="float"))
    assert "its point at (0, 4, 0) m moves in the plane normal to z" in text


PLANAR_3R_STRETCHED = """\
mechanism: planar-3r
units: {length: mm}
bodies: [ground, l1, l2, l3]
joints:
  - {name: A, type: R, between: [ground, l1], axis: [0, 0, 1], point: [0, 5, 0]}
  - {name: B, type: R, between: [l1, l2], axis: [0, 0, 1], point: [40, 5, 0]}
  - {name: C, type: R, between: [l2, l3], axis: [0, 0, 1], point: [70, 5, 0]}
output: {body: l3}
configurations:
  stretched: {}
"""

CENTRED_SLIDER_CRANK_DEAD_CENTRE = (
    CENTRED_SLIDER_CRANK_MM + "configurations:\n  dead-centre: {A: 90}\n"
)


def _serial(path: Path, chain: str) -> dict:
    conf = analyze(path).to_json()["configurations"][0]
    return next(s for s in conf["singularities"] if s["class"] == "serial" and s["chain"] == chain)


def _plane_wrenches_by_hand() -> list[np.ndarray]:
    # what every planar chain with axes along z resists: the force along z and the couples
    # about x and y (unit force through the origin, unit moments)
    return [_wrench([0, 0, 1], [0, 0, 0], 0.0), np.eye(6)[3], np.eye(6)[4]]


@pytest.mark.parametrize(
    ("text", "chain", "line_y"),
    [(PLANAR_3R_STRETCHED, "output", 0.005), (CENTRED_SLIDER_CRANK_DEAD_CENTRE, "leg", 0.0)],
)
def test_a_planar_chain_in_line_loses_the_translation_along_its_line(tmp_path, text, chain, line_y):
    # A planar 3R arm stretched along the line y = 5 mm, and the slider-crank's crank-rod
    # leg at its dead centre (A, B, C on the x axis): the chain's twists are the rotations
    # about z through points of its line, which span the rotation about z and the
    # translation along y.  Inside the plane's motions it has lost the translation along
    # x, and it newly resists the force along its line; what every configuration resists
    # comes after: the force along z and the couples about x and y.
    path = tmp_path / "m.yaml"
    path.write_text(text)
    f = _serial(path, chain)
    assert f["corank"] == 1
    assert np.allclose(f["twist"], [0, 0, 0, 1, 0, 0], atol=1e-12)
    W = np.array(f["wrenches"])
    assert W.shape == (4, 6)
    assert np.allclose(W[0], _wrench([1, 0, 0], [0, line_y, 0], 0.0), atol=1e-12)
    usual = _plane_wrenches_by_hand()
    for w, want in zip(W[1:], usual, strict=True):
        assert np.allclose(w, want, atol=1e-12), (w, want)
    text_out = render_text(analyze(path))
    assert "lost twist: a translation along x" in text_out
    assert f"resisted wrench: a force along x through (0, {line_y:g}, 0) m" in text_out


def test_text_says_when_the_values_given_leave_the_configuration_free(tmp_path):
    # the five-bar has two degrees of freedom: giving A1 alone leaves one, which
    # continuation fills with minimum-norm steps (JSON: underdetermined); the text says
    # so and names what was given, where a fully given input pair says nothing of it
    text = (EX / "five_bar.yaml").read_text() + "  one-input: {A1: 0.3}\n"
    path = tmp_path / "five_bar.yaml"
    path.write_text(text)
    res = analyze(path, configs=["one-input", "inputs"])
    by_name = {c["name"]: c for c in res.to_json()["configurations"]}
    assert by_name["one-input"].get("underdetermined") is True
    assert "underdetermined" not in by_name["inputs"]
    out = render_text(res)
    blocks = {b.split(" ", 1)[0]: b for b in out.split("\nConfiguration ")[1:]}
    one, both = blocks["one-input"], blocks["inputs"]
    assert "underdetermined: the values given (A1) leave the mechanism free to move" in one
    assert "from reference; give more joint values to fix them" in one
    assert "underdetermined" not in both


def test_an_output_motion_basis_reads_as_a_rotation_and_a_translation(tmp_path):
    # A plate gliding on the plane z = 0 (G) whose point (1, 0, 0) is held by a rod to
    # the ground point (1, 1, 1) (two S joints): the point moves normal to the rod, along
    # x, so the plate's twists span the translation along x and the rotation about z
    # through (1, 0, 0) (by hand), and the text shows exactly those two.
    path = tmp_path / "gss.yaml"
    path.write_text(
        "mechanism: plate-on-plane-with-rod\n"
        "bodies: [ground, plate, rod]\n"
        "joints:\n"
        "  - {name: G1, type: G, between: [ground, plate], normal: [0, 0, 1]}\n"
        "  - {name: S1, type: S, between: [plate, rod], point: [1, 0, 0]}\n"
        "  - {name: S2, type: S, between: [rod, ground], point: [1, 1, 1]}\n"
        "output: {body: plate}\n"
    )
    res = analyze(path)
    twists = np.array(res.to_json()["configurations"][0]["output_motion"]["twists"])
    assert np.allclose(twists, [_twist([0, 0, 1], [1, 0, 0], 0.0), [0, 0, 0, 1, 0, 0]])
    assert (
        "e.g. a rotation about the axis through (1, 0, 0) m along z; a translation along x"
        in render_text(res)
    )
