"""The sketch's view follows the geometry: a planar linkage closed by an MJCF ``connect`` (a
ball joint to the loader) is seen along its plane's normal, a SCARA (a Schoenflies motion X)
along its common revolute axis, so a stretched arm is drawn straight; an arm whose axes are
not parallel keeps the oblique view."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mechsing import load
from mechsing.reports.sketch import choose_view, joint_places

ROOT = Path(__file__).resolve().parents[1]
Z = np.array([0.0, 0.0, 1.0])


def test_mjcf_connected_planar_linkage_is_seen_along_its_normal() -> None:
    mech = load(str(ROOT / "examples/fourbar_mjcf.xml"))
    assert {j.type for j in mech.joints} == {"R", "S"}  # the connect is a ball joint
    view = choose_view(mech)
    assert abs(float(view.toward @ Z)) == 1.0
    assert "planar" in view.why


def test_scara_is_seen_along_its_axis_and_its_stretched_arm_is_straight() -> None:
    mech = load(str(ROOT / "docs/images/reports/scara.yaml"))
    view = choose_view(mech)
    assert abs(float(view.toward @ Z)) == 1.0
    assert "Schoenflies" in view.why
    # at the reference the arm is stretched: the pivots of J1, J2 and J4 are in line on the
    # page (an oblique view would show the quill's offset in height as a bend)
    places = joint_places(mech, [0.0] * len(mech.coordinates()))
    a, b, c = (view.project(places[j][next(iter(places[j]))]) for j in ("J1", "J2", "J4"))
    u, v = b - a, c - a
    assert abs(float(u[0] * v[1] - u[1] * v[0])) < 1e-12 * float(np.linalg.norm(v)) ** 2


def test_an_arm_with_crossed_axes_keeps_the_oblique_view() -> None:
    view = choose_view(load(str(ROOT / "examples/puma560.yaml")))
    assert view.why == "" and "oblique" in view.name


def test_a_slider_keeps_its_place_on_its_cylinder() -> None:
    """A 3-RPR leg's slider is drawn where its cylinder carries its reference place
    (halfway between the leg's pivots at the reference): turned back past its base pivot
    (a working mode with the slide negative), it is drawn behind that pivot, not halfway
    to the platform as an unturned leg would be."""
    mech = load(str(ROOT / "examples/planar_3rpr.yaml"))
    a, b = np.array([0.0, 0.0, 0.0]), np.array([0.9, 0.3, 0.0])  # Rb1, Rp1 at the reference
    # leg 1 turned back by pi with the slide -2 |b - a|: Rp1 at b again (a working mode)
    coords = [c for c, _ in mech.coordinates()]
    at_rest = joint_places(mech, [0.0] * len(coords))["P1"]
    assert np.allclose(at_rest["cyl1"], (a + b) / 2)
    q = [np.pi if c == "Rb1" else 0.0 for c in coords]
    q[coords.index("P1")] = -2 * float(np.linalg.norm(b - a))
    turned = joint_places(mech, q)
    assert np.allclose(turned["P1"]["cyl1"], a - (b - a) / 2)
    # the same platform pivot reached the other way: the piston through the base pivot
    assert np.allclose(turned["Rp1"]["platform"], b)
