"""A spherical mechanism is drawn on its sphere: every link (the great-circle arc between its
joints' unit axes) has a length on the page, and a finding's screw (a spherical wrist's lost
rotation, whose axis passes through the centre) is drawn through the centre."""

from __future__ import annotations

from pathlib import Path

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

from mechsing import analyze  # noqa: E402
from mechsing.model.loader import load  # noqa: E402
from mechsing.reports.sketch import Screw  # noqa: E402
from mechsing.reports.sphere import (  # noqa: E402
    choose_sphere_view,
    great_arc,
    sphere_figure,
    spherical_centre,
)
from mechsing.singularity.findings import SerialFinding  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SPHERICAL = [
    "examples/spherical_4r.yaml",
    "examples/exercises/08-spherical-four-bar/mechanism.yaml",
    "examples/exercises/05-wrist-singularity/mechanism.yaml",
]


def _q(mech, c) -> list[float]:
    values = dict(c.joints)
    return [float(values[j][i]) for j, i in mech.coordinates()]


def _page_length(ax, line) -> float:
    xy = np.column_stack(line.get_data())
    xy = xy[~np.isnan(xy).any(axis=1)]
    px = ax.transData.transform(xy)
    return float(np.sum(np.linalg.norm(np.diff(px, axis=0), axis=1)))


def test_the_planar_examples_are_not_spherical() -> None:
    assert spherical_centre(load(str(ROOT / "examples/fourbar.yaml"))) is None
    assert spherical_centre(load(str(ROOT / "examples/puma560.yaml"))) is None
    centre = spherical_centre(load(str(ROOT / "examples/spherical_4r.yaml")))
    assert centre is not None and np.allclose(centre, 0.0)


def test_great_arc_is_on_the_sphere_between_its_ends() -> None:
    a, b = np.array([1.0, 0, 0]), np.array([0.0, 0.6, 0.8])
    arc = great_arc(a, b)
    assert np.allclose(np.linalg.norm(arc, axis=1), 1.0)
    assert np.allclose(arc[0], a) and np.allclose(arc[-1], b)
    # in the plane of a and b
    assert np.allclose(arc @ np.cross(a, b), 0.0)


@pytest.mark.parametrize("path", SPHERICAL)
def test_every_link_has_a_length_on_the_page(path: str) -> None:
    mech = load(str(ROOT / path))
    view = choose_sphere_view(mech)
    result = analyze(mech)
    for c in result.configurations:
        fig = sphere_figure(mech, _q(mech, c), view)
        ax = fig.axes[0]
        fig.canvas.draw()
        for body in mech.bodies:
            joints = [j for j in mech.joints if body in j.between]
            if len(joints) < 2:
                continue
            lines = [ln for ln in ax.lines if ln.get_gid() == f"link:{body}"]
            assert lines, f"{c.name}: link {body} not drawn"
            # two joints of a link are never on one axis here: the arc has a length
            assert sum(_page_length(ax, ln) for ln in lines) > 5.0, (c.name, body)


def test_a_lost_rotation_is_drawn_through_the_centre() -> None:
    path = "examples/exercises/05-wrist-singularity/mechanism.yaml"
    mech = load(str(ROOT / path))
    (c,) = analyze(mech, configs=["reference"]).configurations
    (f,) = [f for f in c.singularities if isinstance(f, SerialFinding)]
    fig = sphere_figure(
        mech, _q(mech, c), choose_sphere_view(mech), [Screw("twist", f.twist, "lost twist")]
    )
    (line,) = [ln for ln in fig.axes[0].lines if ln.get_gid() == "screw:0"]
    a, b = np.column_stack(line.get_data())
    assert np.linalg.norm(b - a) > 1.0  # drawn, across the sphere
    # the centre (drawn at the origin of the page) is on it
    d = b - a
    t = float(-a @ d / (d @ d))
    assert 0.0 < t < 1.0
    assert np.linalg.norm(a + t * d) < 1e-9
