"""The figures of a design review, drawn with matplotlib as deterministic SVG text.

Owns :func:`svg` (a figure as SVG text: the Agg-free SVG writer, text as paths, a fixed
hash salt and no date, so the same input gives the same bytes), :func:`graph_figure` (the
mechanism's graph: bodies as nodes, joints as labelled edges, each loop shaded in its
colour, the ground grey), :func:`path_figure` (a path sweep: the smallest relative singular
value of each test on a log scale against the swept value, float's thresholds shaded,
located singularities marked and labelled) and :func:`grid_figure` (a grid sweep: the
singularity loci over the two swept variables coloured by class, each singularity-free
region tinted in its own colour, the samples not reached greyed, the start marked); and
:func:`swept_axes`, the two axes the kinetostatics' and the dynamics' figures draw their
efforts on along a path.  Swept values are shown in the file's units (the axis labels
say which); everything else is SI.  Figures are made with :class:`matplotlib.figure.Figure`
(no pyplot, no display, no global state).
"""

from __future__ import annotations

import io
import math
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import Any

import matplotlib
import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import FancyArrowPatch, Polygon

__all__ = [
    "CLASS_COLOURS",
    "LOOP_COLOURS",
    "graph_figure",
    "grid_figure",
    "path_figure",
    "svg",
    "swept_axes",
]

#: the style every figure is drawn in (fixed fonts and sizes: reproducible output)
RC = {
    "svg.hashsalt": "mechsing",
    "svg.fonttype": "path",
    "font.family": "DejaVu Sans",
    "font.size": 9.0,
    "axes.titlesize": 10.0,
    "axes.labelsize": 9.0,
    "legend.fontsize": 8.0,
    "path.simplify": True,
    "hatch.linewidth": 0.8,
}

LOOP_COLOURS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b")
TEST_COLOURS = {
    "closure": "#1f77b4",
    "input": "#d62728",
    "output": "#2ca02c",
    "constraint": "#9467bd",
}
#: the singularity-free regions (aspects) of a grid, one colour each, in turn
REGION_COLOURS = (
    "#a6cee3",
    "#b2df8a",
    "#fdbf6f",
    "#cab2d6",
    "#fb9a99",
    "#ffff99",
    "#80cdc1",
    "#d9d9d9",
)
#: the regions named in a grid figure's legend (the others are tinted, not listed)
_REGIONS_IN_LEGEND = 8
CLASS_COLOURS = {
    "input": "#d62728",
    "output": "#2ca02c",
    "serial": "#ff7f0e",
    "constraint": "#9467bd",
    "bifurcation": "#8c564b",
    "passive-motion": "#17becf",
    "undecided": "#7f7f7f",
}


def new_figure(width: float = 6.4, height: float = 4.2) -> Figure:
    """A figure of the given size in inches (drawn at 100 px per inch)."""
    with matplotlib.rc_context(RC):
        return Figure(figsize=(width, height), dpi=100)


def svg(fig: Figure) -> str:
    """The figure as SVG text, byte for byte the same for the same figure."""
    buf = io.BytesIO()
    with matplotlib.rc_context(RC):
        fig.savefig(buf, format="svg", metadata={"Date": None}, bbox_inches="tight")
    text = buf.getvalue().decode("utf-8")
    # the XML prologue and DOCTYPE are not needed in a data URI or an .svg beside a page
    start = text.find("<svg")
    return text[start:]


# --------------------------------------------------------------------------- the graph


def graph_figure(
    bodies: Sequence[str],
    ground: str,
    joints: Sequence[tuple[str, str, str, str]],
    loops: Sequence[Sequence[str]],
    loop_bodies: Sequence[Sequence[str]] = (),
) -> Figure:
    """The mechanism's graph.  ``joints``: (name, type, body a, body b); ``loops``: the
    joint names of each loop, ``loop_bodies`` its bodies in order (shaded).  Layout: the
    bodies in rows by their distance from the ground (file order within a row)."""
    import networkx as nx

    g = nx.Graph()
    g.add_nodes_from(bodies)
    for _name, _t, a, b in joints:
        g.add_edge(a, b)
    # layers by distance from the ground, the ground at the bottom: the legs of a
    # parallel robot stand side by side between the ground and the output
    depth = nx.single_source_shortest_path_length(g, ground)
    far = max(depth.values(), default=0) + 1
    layers: dict[int, list[str]] = {}
    for body in bodies:
        layers.setdefault(depth.get(body, far), []).append(body)
    xy = {}
    for level, members in layers.items():
        for i, body in enumerate(members):
            xy[body] = np.array([i - (len(members) - 1) / 2, 0.9 * level], dtype=float)
    columns = max(len(m) for m in layers.values())
    width = min(9.0, max(4.5, 1.4 * columns + (2.8 if loops else 0.5)))
    fig = new_figure(width, min(7.0, max(2.4, 0.9 * len(layers) + 0.8)))
    with matplotlib.rc_context(RC):
        ax = fig.add_subplot()
        ax.set_aspect("equal")
        ax.axis("off")
        loop_of: dict[str, int] = {}
        for k, lp in enumerate(loops):
            colour = LOOP_COLOURS[k % len(LOOP_COLOURS)]
            order = list(dict.fromkeys(loop_bodies[k])) if loop_bodies else []
            if len(order) >= 3:
                ax.add_patch(
                    Polygon([xy[b] for b in order], closed=True, facecolor=colour, alpha=0.10, lw=0)
                )
            for jn in lp:
                loop_of.setdefault(jn, k)
        # parallel joints between the same two bodies are drawn as arcs
        seen: dict[frozenset[str], int] = {}
        for name, t, a, b in joints:
            key = frozenset((a, b))
            i = seen.get(key, 0)
            seen[key] = i + 1
            rad = 0.0 if i == 0 else 0.25 * ((i + 1) // 2) * (1 if i % 2 else -1)
            k = loop_of.get(name)
            colour = "#555555" if k is None else LOOP_COLOURS[k % len(LOOP_COLOURS)]
            lw = 1.2 if k is None else 2.4
            pa, pb = xy[a], xy[b]
            ax.add_patch(
                FancyArrowPatch(
                    pa,
                    pb,
                    arrowstyle="-",
                    connectionstyle=f"arc3,rad={rad}",
                    color=colour,
                    lw=lw,
                    shrinkA=14,
                    shrinkB=14,
                )
            )
            d = pb - pa
            perp = np.array([d[1], -d[0]])
            mid = (pa + pb) / 2 + rad * perp / 2
            ax.text(
                mid[0],
                mid[1],
                f"{name} ({t})",
                ha="center",
                va="center",
                fontsize=8,
                color=colour,
                bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.9},
            )
        for body in bodies:
            x, y = xy[body]
            is_ground = body == ground
            ax.text(
                x,
                y,
                body,
                ha="center",
                va="center",
                fontsize=9,
                fontweight="bold" if is_ground else "normal",
                bbox={
                    "boxstyle": "square,pad=0.35" if is_ground else "round,pad=0.3",
                    "fc": "#d9d9d9" if is_ground else "white",
                    "ec": "#333333",
                    "lw": 2.0 if is_ground else 1.0,
                },
            )
        pts = np.array(list(xy.values()))
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        pad = 0.25 * max(float(np.max(hi - lo)), 1.0)
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad * 0.6, hi[1] + pad * 0.6)
        if loops:
            handles = [
                Polygon(
                    [[0, 0]], closed=True, facecolor=LOOP_COLOURS[k % len(LOOP_COLOURS)], alpha=0.5
                )
                for k in range(len(loops))
            ]
            labels = [f"loop {k + 1}: {'-'.join(lp)}" for k, lp in enumerate(loops)]
            ax.legend(handles, labels, loc="upper left", bbox_to_anchor=(1.0, 1.0), frameon=False)
    return fig


# --------------------------------------------------------------------------- sweeps

#: the floor of the log scale (a measure of exactly zero is drawn there)
FLOOR = 1e-18


@contextmanager
def swept_axes(sw: Any, height: float) -> Iterator[tuple[Figure, Any, Any, np.ndarray]]:
    """The two axes of efforts along a path sweep ``sw`` (the kinetostatics' and the
    dynamics' figures): yields the figure, the top axes (the efforts), the bottom ones
    (sharing the swept value) and the swept values in the file's unit, the located
    singularities marked on the top axes (dotted grey, under what is drawn next) and the
    swept value named under the bottom ones.  Drawn inside the house style (``RC``)."""
    v = sw.variables[0]
    x = np.asarray(v.values, dtype=float) / v.factor
    fig = new_figure(7.0, height)
    with matplotlib.rc_context(RC):
        ax = fig.add_subplot(2, 1, 1)
        for p in sw.located:
            ax.axvline(p.values[0] / v.factor, color="#7f7f7f", lw=0.8, ls=":")
        below = fig.add_subplot(2, 1, 2, sharex=ax)
        below.set_xlabel(f"{v.name} ({v.file_unit})")
        yield fig, ax, below, x


def path_figure(
    xlabel: str,
    curves: Sequence[tuple[str, np.ndarray, np.ndarray]],
    thresholds: tuple[float, float],
    marks: Sequence[tuple[float, float, str]],
) -> Figure:
    """A path sweep: ``curves`` (test, swept values, smallest relative singular value at
    each; NaN where not reached); float's ``thresholds`` (tau_lo, tau_hi) shaded;
    ``marks``: (x, measure, label) of each located singularity."""
    fig = new_figure(7.0, 4.2)
    with matplotlib.rc_context(RC):
        ax = fig.add_subplot()
        tau_lo, tau_hi = thresholds
        ax.axhspan(FLOOR, tau_lo, color="#d62728", alpha=0.08, lw=0)
        ax.axhspan(tau_lo, tau_hi, color="#7f7f7f", alpha=0.22, lw=0)
        lowest = 1.0
        xmin, xmax = math.inf, -math.inf
        reached = [float(xm) for xm, _, _ in marks]  # the swept values reached, and marked
        for test, x, y in curves:
            xmin, xmax = min(xmin, float(np.min(x))), max(xmax, float(np.max(x)))
            ok = np.isfinite(y)
            if np.any(ok):
                reached += [float(np.min(x[ok])), float(np.max(x[ok]))]
            yy = np.where(np.isfinite(y), np.maximum(y, FLOOR), np.nan)
            if np.any(np.isfinite(yy)):
                lowest = min(lowest, float(np.nanmin(yy)))
            ax.semilogy(x, yy, color=TEST_COLOURS.get(test, "#333333"), lw=1.4, label=test)
        bottom = max(FLOOR, min(lowest, tau_lo) / 30)
        ax.set_ylim(bottom, 2.0)
        # zoom to what was reached when it is a small part of the requested range; the rest
        # is said, not drawn empty
        full = (xmin, xmax)
        if reached and max(reached) - min(reached) < 0.8 * (xmax - xmin):
            pad = 0.05 * max(max(reached) - min(reached), 1e-9 * max(1.0, abs(xmax - xmin)))
            xmin, xmax = max(full[0], min(reached) - pad), min(full[1], max(reached) + pad)
            gone = [f"{a:.4g} to {b:.4g}" for a, b in ((full[0], xmin), (xmax, full[1])) if b > a]
            ax.text(
                0.005,
                0.02,
                "not reached: " + " and ".join(gone),
                transform=ax.transAxes,
                fontsize=7,
                color="#444444",
                bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "#bbbbbb", "alpha": 0.9},
            )
        last = -math.inf
        numbered = sorted((xm, k, ym, label) for k, (xm, ym, label) in enumerate(marks))
        for xm, k, ym, label in numbered:
            ax.axvline(xm, color="#333333", lw=0.7, ls=":")
            ax.plot([xm], [max(ym, bottom * 1.5)], marker="v", color="black", ms=6)
            # a mark too close to the one before it is labelled by its number only
            crowded = xm - last < 0.04 * (xmax - xmin)
            last = xm
            ax.annotate(
                f"{k + 1}" if crowded else f"{k + 1}: {label}",
                xy=(xm, 1.0),
                xycoords=("data", "axes fraction"),
                xytext=(2, -4),
                textcoords="offset points",
                rotation=90,
                ha="left",
                va="top",
                fontsize=7.5,
                bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.85},
            )
        ax.text(
            0.995,
            math.sqrt(tau_lo * tau_hi),
            "float: undecided band",
            transform=ax.get_yaxis_transform(),
            ha="right",
            va="center",
            fontsize=7,
            color="#444444",
        )
        ax.set_xlabel(xlabel)
        ax.set_ylabel("smallest relative singular value")
        ax.set_xlim(xmin, xmax)
        ax.grid(True, which="major", lw=0.4, alpha=0.5)
        ax.legend(
            loc="upper center",
            bbox_to_anchor=(0.5, -0.13),
            ncols=max(1, len(curves)),
            frameon=False,
        )
    return fig


def grid_figure(
    x: np.ndarray,
    y: np.ndarray,
    labels: tuple[str, str],
    reached: np.ndarray,
    loci: Sequence[tuple[str, np.ndarray]],
    points: Sequence[tuple[float, float, str]],
    start: tuple[float, float] | None,
    regions: Sequence[np.ndarray] = (),
) -> Figure:
    """A grid sweep over ``x`` (columns) and ``y`` (rows), in the file's units: the
    samples not reached greyed, each singularity-free region (``regions``: a mask of the
    grid's shape each, the aspects) tinted in its own colour, each locus (class label,
    (k, 2) vertices) in its class's colour, each located point (x, y, class label), and
    the ``start`` as a star."""
    fig = new_figure(6.4, 5.2)
    with matplotlib.rc_context(RC):
        ax = fig.add_subplot()
        if len(regions):
            dx = (x[-1] - x[0]) / max(len(x) - 1, 1) / 2
            dy = (y[-1] - y[0]) / max(len(y) - 1, 1) / 2
            tint = np.zeros((*reached.shape, 4))
            for k, mask in enumerate(regions):
                colour = matplotlib.colors.to_rgb(REGION_COLOURS[k % len(REGION_COLOURS)])
                tint[np.asarray(mask, dtype=bool)] = (*colour, 0.45)
                if k < _REGIONS_IN_LEGEND:
                    ax.plot(
                        [],
                        [],
                        "s",
                        color=colour,
                        alpha=0.45,
                        ms=8,
                        label=f"region {k + 1} ({int(np.sum(mask))} samples)",
                    )
            ax.imshow(
                tint,
                extent=(x[0] - dx, x[-1] + dx, y[0] - dy, y[-1] + dy),
                origin="lower",
                aspect="auto",
                interpolation="nearest",
            )
        if not np.all(reached):
            dx = (x[-1] - x[0]) / max(len(x) - 1, 1) / 2
            dy = (y[-1] - y[0]) / max(len(y) - 1, 1) / 2
            ax.imshow(
                np.where(reached, np.nan, 1.0),
                extent=(x[0] - dx, x[-1] + dx, y[0] - dy, y[-1] + dy),
                origin="lower",
                cmap="Greys",
                vmin=0,
                vmax=4,
                aspect="auto",
                interpolation="nearest",
            )
        shown: set[str] = set()
        for label, v in loci:
            colour = CLASS_COLOURS.get(label.split(",")[0], "#333333")
            ax.plot(
                v[:, 0],
                v[:, 1],
                color=colour,
                lw=2.0,
                label=None if label in shown else f"locus: {label}",
            )
            shown.add(label)
        for px, py, label in points:
            ax.plot([px], [py], ".", color=CLASS_COLOURS.get(label.split(",")[0], "#333333"), ms=4)
        if start is not None:
            ax.plot([start[0]], [start[1]], marker="*", color="black", ms=12, ls="", label="start")
        ax.set_xlim(float(x[0]), float(x[-1]))
        ax.set_ylim(float(y[0]), float(y[-1]))
        ax.set_xlabel(labels[0])
        ax.set_ylabel(labels[1])
        ax.grid(True, lw=0.4, alpha=0.5)
        if not np.all(reached):
            ax.plot([], [], "s", color="#cfcfcf", label="not reached from the start")
        ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), frameon=False)
    return fig
