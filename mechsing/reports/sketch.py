"""The 3-D sketch of a mechanism at a configuration, projected on a chosen view.

Owns :class:`View` (an orthographic view: the direction looked along and the screen axes),
:func:`choose_view` (planar mechanisms are seen along their plane's normal; the others
from a fixed oblique direction, z up), :func:`joint_places` (where each joint is at a
configuration, from the bodies' poses) and :func:`sketch_figure` (links as segments between
their joint points, filled when a link carries three joints or more; revolute, helical and
cylindrical axes drawn as short lines, or as a circle when seen end on; prismatic joints as
a slider along their direction; spherical and universal joints as open circles; ground
joints hatched; each screw of a finding drawn as its axis with its pitch).

Conventions: a joint's ``point`` is its place at the reference configuration in the ground
frame, so at a configuration it is ``g_a . point`` with ``g_a`` the pose of ``between[0]``;
a joint without a point (prismatic, planar, translational...) is placed where its first
body carries the place halfway between the reference points of its two bodies' other
joints, or, on the ground, at its other body's joints on a rail.  A twist ``(omega, v)`` (v: the velocity of the body point
at the ground origin) has its axis through ``omega x v / |omega|^2``, direction ``omega``,
pitch ``omega . v / |omega|^2`` (m/rad); with ``omega = 0`` it is a translation along v
(infinite pitch).  A wrench ``(f, m)`` (m about the origin) has its axis through
``f x m / |f|^2``, direction f, pitch ``f . m / |f|^2``; with ``f = 0`` it is a couple.
Lengths in metres.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import matplotlib
import numpy as np
from matplotlib.patches import Circle, Polygon, Rectangle

from mechsing.kinematics import KinematicModel
from mechsing.model import Mechanism
from mechsing.numeric import to_float
from mechsing.numeric.numbers import unit_vector
from mechsing.reports.figures import RC, new_figure

__all__ = [
    "Screw",
    "body_poses",
    "View",
    "choose_view",
    "motion_axis",
    "joint_places",
    "screw_axis",
    "sketch_figure",
]

#: joint types drawn with an axis line (direction parameter ``axis``)
AXIAL = ("R", "H", "C")
#: a tolerance of the drawing only (is a mechanism planar, is an axis seen end on):
#: nothing is decided from it
DRAWING_TOLERANCE = 1e-6


@dataclass(frozen=True)
class View:
    """An orthographic view: ``toward`` the direction looked along (from the viewer into
    the page), ``right`` and ``up`` the screen axes (unit vectors, ground frame); ``name``
    says it in words."""

    toward: np.ndarray
    right: np.ndarray
    up: np.ndarray
    name: str
    #: why this view was chosen (empty for the default oblique view)
    why: str = ""

    def project(self, p: np.ndarray) -> np.ndarray:
        p = np.asarray(p, dtype=float)
        return np.stack([p @ self.right, p @ self.up], axis=-1)


@dataclass(frozen=True)
class Screw:
    """A screw to draw: a twist (``kind`` ``twist``) or a wrench (``wrench``), 6 floats
    in the mechanism's convention, and its label (what it is)."""

    kind: str
    vector: tuple[float, ...]
    label: str
    #: where a translation is drawn: a point of ``body`` at the reference configuration
    #: (SI, ground frame); None: the mechanism's centre
    at: tuple[float, float, float] | None = None
    body: str | None = None


def _f(x: object) -> np.ndarray:
    return np.asarray(to_float(np.asarray(x, dtype=object)), dtype=float)


def _unit(v: np.ndarray) -> np.ndarray:
    return unit_vector(v) if np.any(v) else v


def planar_normal(mech: Mechanism) -> np.ndarray | None:
    """The normal of a planar mechanism (every revolute, helical or cylindrical axis along
    it, every prismatic direction and joint point in a plane across it), else None."""
    axes = [_unit(_f(j.params["axis"])) for j in mech.joints if j.type in AXIAL]
    if not axes or any(j.type not in (*AXIAL, "P") for j in mech.joints):
        return None
    n = axes[0]
    if any(np.linalg.norm(np.cross(n, a)) > DRAWING_TOLERANCE for a in axes):
        return None
    for j in mech.joints:
        if j.type == "P" and abs(float(_unit(_f(j.params["axis"])) @ n)) > DRAWING_TOLERANCE:
            return None
    heights = [float(_f(j.params["point"]) @ n) for j in mech.joints if "point" in j.params]
    if heights and max(heights) - min(heights) > DRAWING_TOLERANCE * max(
        1.0, max(map(abs, heights))
    ):
        return None
    return n if n[np.argmax(np.abs(n))] > 0 else -n


def motion_axis(mech: Mechanism) -> tuple[np.ndarray, str] | None:
    """The axis to look along and why, from the geometry at the reference configuration:
    the normal of a planar mechanism; else the common direction of every revolute,
    helical and cylindrical axis when the other joints are sliders (across it or along it)
    and ball joints (a planar linkage whose loop a ball joint closes, as an MJCF
    ``connect`` does, with its joints in one plane across that direction; or a
    Schoenflies (X) mechanism such as a SCARA: rotations about that direction and
    translations); else None."""
    n = planar_normal(mech)
    if n is not None:
        return n, "planar: it moves in the plane across this direction"
    axes = [_unit(_f(j.params["axis"])) for j in mech.joints if j.type in AXIAL]
    if not axes or any(j.type not in (*AXIAL, "P", "S") for j in mech.joints):
        return None
    n = axes[0] if axes[0][np.argmax(np.abs(axes[0]))] > 0 else -axes[0]
    if any(np.linalg.norm(np.cross(n, a)) > DRAWING_TOLERANCE for a in axes):
        return None
    along = False
    for j in mech.joints:
        if j.type == "P":
            c = abs(float(_unit(_f(j.params["axis"])) @ n))
            if DRAWING_TOLERANCE < c < 1 - DRAWING_TOLERANCE:
                return None  # a slider neither across nor along: no one good direction
            along = along or c > 0.5
    heights = [float(_f(j.params["point"]) @ n) for j in mech.joints if "point" in j.params]
    flat = not heights or max(heights) - min(heights) <= DRAWING_TOLERANCE * max(
        1.0, max(map(abs, heights))
    )
    if flat and not along:
        return n, (
            "planar: its revolute axes are parallel and its joints in one plane across "
            "them (the ball joint closes the loop), so it moves in that plane"
        )
    return n, (
        "a Schoenflies mechanism (X): its revolute axes are parallel, so its links turn "
        "about this direction and translate"
    )


def choose_view(mech: Mechanism) -> View:
    """Along the direction :func:`motion_axis` gives (seen from its positive side; the
    view's name says why); else, z up, the oblique view (elevation 30 degrees, azimuth a
    multiple of 45) in which the joints at the reference configuration stand farthest
    apart: the smallest projected distance between two distinct joint points, largest
    (the first such azimuth on a tie)."""
    found = motion_axis(mech)
    if found is not None:
        n, why = found
        toward = -n
        ref = np.array([1.0, 0.0, 0.0]) if abs(n[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
        right = _unit(ref - (ref @ n) * n)
        up = np.cross(n, right)
        axis = "xyz"[int(np.argmax(np.abs(n)))]
        where = f" ({axis})" if np.max(np.abs(n)) > 0.999 else ""
        what = "the plane's normal" if why.startswith("planar") else "the common revolute axis"
        return View(toward, right, up, f"seen along {what}{where}", why)
    places = joint_places(mech, [0.0] * mech.dof)
    pts = np.array(
        [p for e in places.values() for k, p in e.items() if k not in ("axis", "ends", "rail")]
    )
    best: tuple[float, View] | None = None
    for k in range(8):
        az = np.radians(-60.0 + 45.0 * k)
        el = np.radians(30.0)
        eye = np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])
        toward = -eye
        right = _unit(np.cross(toward, np.array([0.0, 0.0, 1.0])))
        up = np.cross(right, toward)
        view = View(toward, right, up, "oblique view, z up")
        score = _spread(view, pts)
        if best is None or score > best[0] + 1e-9:
            best = (score, view)
    assert best is not None
    return best[1]


def _spread(view: View, pts: np.ndarray) -> float:
    """The smallest projected distance between two joint points that are apart in space,
    relative to the projected extent."""
    if len(pts) < 2:
        return 0.0
    xy = view.project(pts)
    extent = float(np.max(np.ptp(xy, axis=0))) or 1.0
    d3 = np.linalg.norm(pts[:, None, :] - pts[None, :, :], axis=-1)
    d2 = np.linalg.norm(xy[:, None, :] - xy[None, :, :], axis=-1)
    apart = d3 > DRAWING_TOLERANCE * max(float(np.max(d3)), 1.0)
    return float(np.min(d2[apart])) / extent if np.any(apart) else 0.0


def body_poses(mech: Mechanism, q: Sequence[float]) -> dict[str, np.ndarray]:
    """The 4x4 pose of every body at the joint values ``q`` (SI), ground the identity."""
    model = KinematicModel(mech, "float")
    return {k: np.asarray(v, dtype=float) for k, v in model.poses(np.asarray(q, float)).items()}


def joint_places(mech: Mechanism, q: Sequence[float]) -> dict[str, dict[str, np.ndarray]]:
    """Where each joint is at the joint values ``q`` (SI, the mechanism's coordinate
    order): ``{joint: {body: point}}`` for each of its two bodies (the same point for a
    joint with a point), plus ``"axis"`` (the joint's current direction, if any), in the
    ground frame."""
    poses = body_poses(mech, q)

    def carry(body: str, p: np.ndarray) -> np.ndarray:
        g = poses.get(body, np.eye(4))
        return g[:3, :3] @ p + g[:3, 3]

    out: dict[str, dict[str, np.ndarray]] = {}
    for j in mech.joints:
        a, b = j.between
        if "point" in j.params:
            p = carry(a, _f(j.params["point"]))
            out[j.name] = {a: p, b: p}
        if "axis" in j.params:
            direction = _unit(_f(j.params["axis"]))
            g = poses.get(a, np.eye(4))
            out.setdefault(j.name, {})["axis"] = g[:3, :3] @ direction
    for j in mech.joints:  # joints without a point: halfway between their bodies' joints
        a, b = j.between
        if "point" in j.params:
            continue
        ends, rest = [], []  # each body's other joints: where they are, where they were
        for body in (a, b):
            others = [
                k
                for k in mech.joints
                if k.name != j.name and body in k.between and "point" in k.params
            ]
            ends.append(np.mean([out[k.name][body] for k in others], axis=0) if others else None)
            if others:
                rest.append(np.mean([_f(k.params["point"]) for k in others], axis=0))
        entry = out.setdefault(j.name, {})
        moving = 1 if a == mech.ground else 0 if b == mech.ground else None
        if moving is not None and ends[moving] is not None:
            # a slider on the ground: at its body's joints, on a rail fixed to the ground
            mid = ends[moving]
            entry["rail"] = mid
        else:
            # where its first body carries the place it had at the reference (halfway
            # between the reference points of its bodies' other joints): a slider keeps
            # its place on its cylinder, so a leg turned back past its base pivot (the
            # slide negative) shows it, where halfway would draw the same as unturned
            mid = carry(a, np.mean(rest, axis=0) if rest else np.zeros(3))
            entry["ends"] = np.array([e if e is not None else mid for e in ends])
        entry[a] = mid
        entry[b] = mid
    return out


def screw_axis(s: Screw) -> tuple[np.ndarray | None, np.ndarray, float | None]:
    """(a point on the axis or None for a pure translation or couple, the direction, the
    pitch or None when infinite) of a twist or a wrench (module docstring)."""
    v = np.asarray(s.vector, dtype=float)
    if s.kind == "twist":
        w, lin = v[:3], v[3:]
    else:
        w, lin = v[:3], v[3:]
    nw = float(w @ w)
    if nw <= DRAWING_TOLERANCE**2 * max(float(lin @ lin), 1e-300):
        return None, _unit(lin), None
    return np.cross(w, lin) / nw, w / np.sqrt(nw), float(w @ lin) / nw


def _ground_hatch(ax: object, xy: np.ndarray, size: float) -> None:
    x, y = xy
    ax.add_patch(  # type: ignore[attr-defined]
        Rectangle(
            (x - size, y - 1.6 * size),
            2 * size,
            0.7 * size,
            facecolor="white",
            edgecolor="#333333",
            hatch="////",
            lw=0.8,
            zorder=2,
        )
    )
    ax.plot([x, x], [y - 0.9 * size, y], color="#333333", lw=1.0, zorder=2)  # type: ignore[attr-defined]


def sketch_axes(fig: object) -> object:
    """The axes of a sketch (a mechanism's or a sphere's): equal scales, no ticks, a light
    frame.  Called inside the figures' ``rc_context``."""
    ax = fig.add_subplot()  # type: ignore[attr-defined]
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    for side in ax.spines.values():
        side.set_color("#bbbbbb")
    return ax


def sketch_figure(
    mech: Mechanism,
    q: Sequence[float],
    view: View,
    screws: Sequence[Screw] = (),
    length_scale: float = 1.0,
    title: str = "",
) -> object:
    """The sketch of ``mech`` at joint values ``q`` (SI) seen in ``view``, with the axes
    of ``screws`` drawn and labelled (module docstring)."""
    places = joint_places(mech, q)
    fig = new_figure(6.4, 4.6)
    with matplotlib.rc_context(RC):
        ax = sketch_axes(fig)
        pts3 = [
            p for e in places.values() for k, p in e.items() if k not in ("axis", "ends", "rail")
        ]
        allp = view.project(np.array(pts3)) if pts3 else np.zeros((1, 2))
        lo, hi = allp.min(axis=0), allp.max(axis=0)
        span = float(max(np.max(hi - lo), length_scale * 0.5, 1e-9))
        for e in places.values():  # the rails of sliders on the ground are drawn whole
            if "rail" in e and "axis" in e:
                ends = view.project(
                    np.array([e["rail"] + t * 0.3 * span * e["axis"] for t in (-1, 1)])
                )
                lo, hi = np.minimum(lo, ends.min(axis=0)), np.maximum(hi, ends.max(axis=0))
        mark = 0.035 * span
        # links
        bodies = [b for b in mech.bodies if b != mech.ground]
        for k, body in enumerate(bodies):
            pts = [
                places[j.name][body]
                for j in mech.joints
                if body in j.between and j.name in places and body in places[j.name]
            ]
            if len(pts) < 2:
                continue
            xy = view.project(np.array(pts))
            colour = "#4a6fa5" if k % 2 == 0 else "#5b8c5a"
            if len(pts) >= 3:
                hull = _hull(xy)
                ax.add_patch(Polygon(hull, closed=True, facecolor=colour, alpha=0.18, lw=0))
                ax.add_patch(Polygon(hull, closed=True, fill=False, edgecolor=colour, lw=2.5))
            else:
                ax.plot(xy[:, 0], xy[:, 1], color=colour, lw=3.0, solid_capstyle="round", zorder=1)
        # the ground: dashed between its joints, hatched under each
        gpts = [
            places[j.name][mech.ground]
            for j in mech.joints
            if mech.ground in j.between and j.name in places
        ]
        if len(gpts) >= 2:
            gxy = view.project(np.array(gpts))
            ax.plot(gxy[:, 0], gxy[:, 1], color="#777777", lw=1.0, ls="--", zorder=0)
        for p in gpts:
            _ground_hatch(ax, view.project(p), mark)
        # joints
        labels: list[tuple[np.ndarray, list[str], bool]] = []
        for j in mech.joints:
            e = places.get(j.name)
            if not e:
                continue
            p = e[j.between[0]]
            xy = view.project(p)
            if j.type == "P" or "ends" in e or "rail" in e:
                if "rail" in e and "axis" in e:
                    r0 = view.project(p - 0.3 * span * e["axis"])
                    r1 = view.project(p + 0.3 * span * e["axis"])
                    ax.plot([r0[0], r1[0]], [r0[1], r1[1]], color="#777777", lw=2.5, zorder=1)
                ends = view.project(e["ends"]) if "ends" in e else np.array([xy, xy])
                ax.plot(ends[:, 0], ends[:, 1], color="#444444", lw=1.0, ls="-", zorder=1)
                d = view.project(e.get("axis", np.zeros(3)))
                nd = float(np.linalg.norm(d))
                ang = float(np.degrees(np.arctan2(d[1], d[0]))) if nd > 0 else 0.0
                ax.add_patch(
                    Rectangle(
                        (xy[0] - 1.4 * mark, xy[1] - 0.6 * mark),
                        2.8 * mark,
                        1.2 * mark,
                        angle=ang,
                        rotation_point="center",
                        facecolor="white",
                        edgecolor="black",
                        lw=1.2,
                        zorder=3,
                    )
                )
            elif j.type in AXIAL:
                axis = e["axis"]
                d = view.project(axis)
                if float(np.linalg.norm(d)) < 0.2:  # seen end on: a circle with a dot
                    ax.add_patch(
                        Circle(
                            xy, 0.7 * mark, facecolor="white", edgecolor="black", lw=1.2, zorder=3
                        )
                    )
                    ax.plot([xy[0]], [xy[1]], ".", color="black", ms=2.5, zorder=4)
                else:
                    a0 = view.project(p - 0.12 * span * axis)
                    a1 = view.project(p + 0.12 * span * axis)
                    ax.plot(
                        [a0[0], a1[0]], [a0[1], a1[1]], color="black", lw=1.0, ls="-.", zorder=2
                    )
                    ax.add_patch(
                        Circle(
                            xy, 0.45 * mark, facecolor="white", edgecolor="black", lw=1.2, zorder=3
                        )
                    )
            else:  # S, U and the others: an open circle
                ax.add_patch(
                    Circle(xy, 0.6 * mark, facecolor="white", edgecolor="black", lw=1.5, zorder=3)
                )
            # joints that meet on the page (a wrist centre, a shoulder) share one label; a
            # slider's label goes below (it may sit on a pin)
            for at, names, slider in labels:
                if slider == (j.type == "P") and float(np.linalg.norm(at - xy)) < 0.03 * span:
                    names.append(j.name)
                    break
            else:
                labels.append((xy, [j.name], j.type == "P"))
        for xy, names, slider in labels:
            ax.annotate(
                ", ".join(names),
                xy,
                xytext=(6, -14) if slider else (6, 5),
                textcoords="offset points",
                fontsize=8,
                zorder=5,
                bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none", "alpha": 0.75},
            )
        # screws
        centre = np.mean(np.array(pts3), axis=0) if pts3 else np.zeros(3)
        extra: list[np.ndarray] = []  # what the screws add to the drawing's extent
        colours = ("#d62728", "#9467bd", "#ff7f0e", "#17becf")
        for k, s in enumerate(screws):
            colour = colours[k % len(colours)]
            point, direction, pitch = screw_axis(s)
            if point is None:
                base = centre
                if s.at is not None:
                    g = body_poses(mech, q).get(s.body or mech.ground, np.eye(4))
                    base = g[:3, :3] @ np.asarray(s.at, dtype=float) + g[:3, 3]
                c = view.project(base)
                d = view.project(direction)
                extra += [c, c + 0.25 * span * d]
                ax.annotate(
                    "",
                    xy=c + 0.25 * span * d,
                    xytext=c,
                    arrowprops={"arrowstyle": "-|>", "color": colour, "lw": 1.8},
                    zorder=6,
                )
                words = "translation" if s.kind == "twist" else "couple"
                text = f"{s.label}: a {words}"
                at = c + 0.25 * span * d
            else:
                # the axis's point nearest the mechanism's centre
                foot = point + ((centre - point) @ direction) * direction
                d = view.project(direction)
                at = view.project(foot)
                extra.append(at)
                if float(np.linalg.norm(d)) < 0.2:
                    ax.plot([at[0]], [at[1]], marker="o", mfc="none", mec=colour, ms=10, mew=1.8)
                    ax.plot([at[0]], [at[1]], marker=".", color=colour, ms=4)
                else:
                    a0 = view.project(foot - 0.7 * span * direction)
                    a1 = view.project(foot + 0.7 * span * direction)
                    ax.plot(
                        [a0[0], a1[0]], [a0[1], a1[1]], color=colour, lw=1.8, ls=(0, (6, 2, 1, 2))
                    )
                text = f"{s.label}: pitch {pitch:.3g} m/rad"
            # the label below the drawing, in the screw's colour: never over a link
            ax.text(
                0.02,
                0.03 + 0.07 * (len(screws) - 1 - k),
                text,
                transform=ax.transAxes,
                fontsize=8,
                color=colour,
                zorder=7,
                bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": colour, "alpha": 0.9},
            )
        mid = (lo + hi) / 2
        extra = [e for e in extra if float(np.max(np.abs(e - mid))) < span]  # not far away
        if extra:
            lo = np.minimum(lo, np.min(extra, axis=0))
            hi = np.maximum(hi, np.max(extra, axis=0))
        pad = 0.12 * span
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        # room below for the screws' labels (each about 0.07 of the height)
        below = 0.1 * len(screws) * (hi[1] - lo[1] + 2 * pad + 2 * mark)
        ax.set_ylim(lo[1] - pad - 2 * mark - below, hi[1] + pad)
        ax.set_title(title or view.name, fontsize=9, loc="left")
    return fig


def _hull(xy: np.ndarray) -> np.ndarray:
    """The convex hull of projected points (all of them when they are on a line)."""
    from scipy.spatial import ConvexHull, QhullError

    try:
        return xy[ConvexHull(xy).vertices]
    except (QhullError, ValueError):
        return xy
