"""The sketch of a spherical mechanism: every joint axis through one centre, drawn on a sphere.

A spherical chain drawn as :mod:`mechsing.reports.sketch` draws others would be a star: every
joint point is the centre, so every link has zero length.  Here it is drawn as what it is
(Chiang, *Kinematics of Spherical Mechanisms*): each revolute axis as the unit vector from the
centre along its current direction, each link as the great-circle arc between its joints'
unit vectors on the unit sphere (drawn as a faint wireframe), the ground's arcs dashed, and
each screw of a finding as its axis (a lost rotation's axis passes through the centre),
labelled.  Points on the far half of the sphere are drawn fainter.  The drawing is in units
of the sphere's radius (1): directions, not lengths.

Owns :func:`spherical_centre` (is a mechanism spherical, and where is its centre),
:func:`choose_sphere_view` and :func:`sphere_figure`.  Each drawn link carries the ``gid``
``link:<body>`` and each screw ``screw:<k>``, so a test can measure what was drawn.
"""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib
import numpy as np

from mechsing.model import Mechanism
from mechsing.reports.figures import RC, new_figure
from mechsing.reports.sketch import (
    DRAWING_TOLERANCE,
    Screw,
    View,
    _f,
    _unit,
    joint_places,
    screw_axis,
    sketch_axes,
)

__all__ = ["choose_sphere_view", "sphere_figure", "spherical_centre"]

#: points of a drawn great-circle arc
ARC_POINTS = 48
#: how far a screw's axis is drawn past the sphere (radii)
SCREW_REACH = 1.35
#: joint tips closer than this on the page (radii) share one label
LABEL_APART = 0.15


def spherical_centre(mech: Mechanism) -> np.ndarray | None:
    """The common point of every joint axis of a mechanism of revolute joints only (at
    least three, not all parallel) at the reference configuration, else None."""
    if len(mech.joints) < 3 or any(j.type != "R" for j in mech.joints):
        return None
    pts = [_f(j.params["point"]) for j in mech.joints]
    dirs = [_unit(_f(j.params["axis"])) for j in mech.joints]
    if all(np.linalg.norm(np.cross(dirs[0], u)) < DRAWING_TOLERANCE for u in dirs):
        return None
    # the point nearest every axis: sum (I - u u^T)(x - p) = 0
    A = sum(np.eye(3) - np.outer(u, u) for u in dirs)
    b = sum((np.eye(3) - np.outer(u, u)) @ p for p, u in zip(pts, dirs, strict=True))
    c = np.linalg.lstsq(A, b, rcond=None)[0]
    size = max(1.0, *(float(np.linalg.norm(p - c)) for p in pts))
    for p, u in zip(pts, dirs, strict=True):
        if np.linalg.norm(np.cross(c - p, u)) > DRAWING_TOLERANCE * size:
            return None
    return c


def _tips(mech: Mechanism, q: Sequence[float]) -> dict[str, np.ndarray]:
    """Each joint's current unit axis (from the centre)."""
    places = joint_places(mech, q)
    return {j.name: _unit(places[j.name]["axis"]) for j in mech.joints}


def choose_sphere_view(mech: Mechanism) -> View:
    """From outside the sphere, z up as far as it can be: of the view from the middle of the
    joint axes' unit vectors at the reference configuration and the oblique views (elevation
    30 or 60 degrees, azimuth a multiple of 45), the one that sees every link's arc most
    open (the least |normal of its plane . view|: an arc seen edge on is a segment), the
    joints on the near half preferred."""
    tips = _tips(mech, [0.0] * mech.dof)
    normals = []
    for body in mech.bodies:
        js = [j.name for j in mech.joints if body in j.between]
        for a, b in zip(js, js[1:], strict=False):
            n = np.cross(tips[a], tips[b])
            if float(np.linalg.norm(n)) > DRAWING_TOLERANCE:
                normals.append(_unit(n))
    U = np.array(list(tips.values()))
    eyes = [_unit(U.mean(axis=0))] if float(np.linalg.norm(U.mean(axis=0))) > 0.2 else []
    for el in (30.0, 60.0):
        for k in range(8):
            az, e = np.radians(-60.0 + 45.0 * k), np.radians(el)
            eyes.append(np.array([np.cos(e) * np.cos(az), np.cos(e) * np.sin(az), np.sin(e)]))

    def score(eye: np.ndarray) -> float:
        seen = min((abs(float(n @ eye)) for n in normals), default=1.0)
        return seen + 0.25 * float(np.mean(U @ eye))

    eye = max(eyes, key=score)  # the first of equal scores
    toward = -eye
    up0 = np.array([0.0, 0.0, 1.0]) if abs(eye[2]) < 0.95 else np.array([0.0, 1.0, 0.0])
    right = _unit(np.cross(toward, up0))
    return View(toward, right, np.cross(right, toward), "the sphere seen from outside, z up")


def great_arc(a: np.ndarray, b: np.ndarray, n: int = ARC_POINTS) -> np.ndarray:
    """Points of the shorter great-circle arc from unit vector ``a`` to ``b`` (n, 3)."""
    cos = float(np.clip(a @ b, -1.0, 1.0))
    angle = float(np.arccos(cos))
    if angle < DRAWING_TOLERANCE:
        return np.array([a, b])
    t = np.linspace(0.0, 1.0, n)[:, None]
    return (np.sin((1 - t) * angle) * a + np.sin(t * angle) * b) / np.sin(angle)


def _draw_path(
    ax: object, view: View, pts: np.ndarray, gid: str | None = None, **kw: object
) -> None:
    """A 3-D path on the sphere: solid on the near half, faint on the far half."""
    xy = view.project(pts)
    far = pts @ view.toward > 0
    for half, fade in ((False, 1.0), (True, 0.3)):
        mask = far == half
        if not np.any(mask):
            continue
        shown = np.where(mask[:, None], xy, np.nan)
        (line,) = ax.plot(shown[:, 0], shown[:, 1], alpha=fade, **kw)  # type: ignore[attr-defined]
        if gid is not None:
            line.set_gid(gid)


def _wireframe(ax: object, view: View) -> None:
    """The unit sphere: its outline and, faintly, parallels and meridians."""
    t = np.linspace(0, 2 * np.pi, 121)
    ax.plot(np.cos(t), np.sin(t), color="#999999", lw=0.8, zorder=0)  # type: ignore[attr-defined]
    for lat in np.radians([-60, -30, 0, 30, 60]):
        ring = np.stack(
            [np.cos(lat) * np.cos(t), np.cos(lat) * np.sin(t), np.full_like(t, np.sin(lat))], 1
        )
        _draw_path(ax, view, ring, color="#cccccc", lw=0.5, zorder=0)
    for lon in np.radians(np.arange(0, 180, 30)):
        ring = np.stack([np.cos(t) * np.cos(lon), np.cos(t) * np.sin(lon), np.sin(t)], 1)
        _draw_path(ax, view, ring, color="#cccccc", lw=0.5, zorder=0)


def sphere_figure(
    mech: Mechanism,
    q: Sequence[float],
    view: View,
    screws: Sequence[Screw] = (),
    title: str = "",
) -> object:
    """The sketch of a spherical ``mech`` at joint values ``q`` (SI) seen in ``view``, with
    the axes of ``screws`` drawn and labelled (module docstring)."""
    centre = spherical_centre(mech)
    c0 = np.zeros(3) if centre is None else centre
    tips = _tips(mech, q)
    fig = new_figure(6.4, 4.6)
    with matplotlib.rc_context(RC):
        ax = sketch_axes(fig)
        _wireframe(ax, view)
        o = view.project(np.zeros(3))
        ax.plot([o[0]], [o[1]], "o", color="black", ms=4, zorder=4)
        ax.annotate(
            "centre",
            o,
            xytext=(-8, -12),
            textcoords="offset points",
            fontsize=7,
            ha="right",
            color="#555555",
        )
        # links: arcs between their joints' unit vectors
        colours = ("#4a6fa5", "#5b8c5a")
        for k, body in enumerate(b for b in mech.bodies if b != mech.ground):
            js = [j.name for j in mech.joints if body in j.between]
            for a, b in zip(js, js[1:], strict=False):
                _draw_path(
                    ax,
                    view,
                    great_arc(tips[a], tips[b]),
                    f"link:{body}",
                    color=colours[k % 2],
                    lw=3.0,
                    solid_capstyle="round",
                    zorder=2,
                )
        gj = [j.name for j in mech.joints if mech.ground in j.between]
        for a, b in zip(gj, gj[1:], strict=False):
            _draw_path(
                ax,
                view,
                great_arc(tips[a], tips[b]),
                f"link:{mech.ground}",
                color="#777777",
                lw=1.2,
                ls="--",
                zorder=1,
            )
        # joints: unit vectors from the centre, labelled at their tips
        for j in mech.joints:
            u = tips[j.name]
            xy = view.project(np.array([np.zeros(3), u]))
            near = float(u @ view.toward) <= 0
            ax.plot(xy[:, 0], xy[:, 1], color="black", lw=1.0, alpha=1.0 if near else 0.4, zorder=3)
            ax.plot(
                [xy[1, 0]],
                [xy[1, 1]],
                "o",
                mfc="white",
                mec="black",
                ms=6,
                zorder=4,
                alpha=1.0 if near else 0.5,
            )
        # labels: one per place on the page (joints whose tips meet share it), outward
        groups: list[tuple[np.ndarray, list[str]]] = []
        for j in mech.joints:
            xy = view.project(tips[j.name])
            name = j.name + (" (ground)" if mech.ground in j.between else "")
            for at, names in groups:
                if float(np.linalg.norm(at - xy)) < LABEL_APART:
                    names.append(name)
                    break
            else:
                groups.append((xy, [name]))
        for xy, names in groups:
            out = xy - o
            n = float(np.linalg.norm(out))
            out = out / n if n > LABEL_APART else np.array([0.7, 0.7])
            ax.annotate(
                ", ".join(names),
                xy,
                xytext=tuple(10 * out),
                textcoords="offset points",
                ha="left" if out[0] >= -0.3 else "right",
                va="bottom" if out[1] >= -0.3 else "top",
                fontsize=8,
                zorder=5,
                bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none", "alpha": 0.75},
            )
        # screws: the axis through (or nearest) the centre, labelled at its end
        scol = ("#d62728", "#9467bd", "#ff7f0e", "#17becf")
        for k, s in enumerate(screws):
            colour = scol[k % len(scol)]
            point, direction, pitch = screw_axis(s)
            if point is None:  # a translation or a couple: an arrow from the centre
                end = view.project(direction)
                ax.annotate(
                    "",
                    xy=end,
                    xytext=o,
                    arrowprops={"arrowstyle": "-|>", "color": colour, "lw": 1.8},
                    zorder=6,
                )
                ax.plot([o[0], end[0]], [o[1], end[1]], alpha=0, gid=f"screw:{k}")
                words = "a translation" if s.kind == "twist" else "a couple"
                text, at = f"{s.label}: {words}", end
            else:
                foot = point - c0 + ((c0 - point) @ direction) * direction
                ends = view.project(
                    np.array([foot - SCREW_REACH * direction, foot + SCREW_REACH * direction])
                )
                ax.plot(
                    ends[:, 0],
                    ends[:, 1],
                    color=colour,
                    lw=1.8,
                    ls=(0, (6, 2, 1, 2)),
                    zorder=6,
                    gid=f"screw:{k}",
                )
                if np.linalg.norm(foot) < 10 * DRAWING_TOLERANCE:
                    text = f"{s.label}: axis through the centre"
                    if abs(pitch or 0.0) > DRAWING_TOLERANCE:
                        text += f", pitch {pitch:.3g} m/rad"
                else:
                    text = f"{s.label}: pitch {pitch:.3g} m/rad"
                at = ends[int(np.argmax(ends[:, 0]))]
            # the label in the corner, in the screw's colour, clear of the links
            ax.text(
                0.02,
                0.03 + 0.07 * k,
                text,
                transform=ax.transAxes,
                fontsize=8,
                color=colour,
                zorder=7,
                bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": colour, "alpha": 0.9},
            )
            ax.plot([at[0]], [at[1]], marker=">", color=colour, ms=5, zorder=6)
        lim = SCREW_REACH + 0.1
        ax.set_xlim(-lim, lim)
        ax.set_ylim(-lim - 0.15 * len(screws), lim)
        ax.set_title(title or view.name, fontsize=9, loc="left")
    return fig
