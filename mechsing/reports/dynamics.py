"""The design review's section on a timed sweep (``report --vary ... --duration T``): the
efforts the motion needs along the path against time, the located singularities marked,
and the Type II crossing condition at each located Type II point
(:mod:`mechsing.kinetics.timed`, docs/dynamics.md)."""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing.reports import document as doc
from mechsing.reports.figures import svg, swept_axes

__all__ = ["dynamics_blocks"]


def _figure(sw: Any) -> Any:
    dy = sw.dynamics
    v = sw.variables[0]
    with swept_axes(sw, 5.2) as (fig, ax, ax2, x):
        for i, n in enumerate(dy.names):
            ax.plot(x, dy.efforts[:, i], lw=1.4, label=f"{n} ({dy.units[n]})")
        # linear, unless a few samples (a Type II) dwarf the rest: then linear up to the
        # 90th percentile of |effort| and logarithmic beyond, so the rest stays readable
        size = np.abs(dy.efforts[np.isfinite(dy.efforts)])
        if size.size and np.max(size) > 10 * np.percentile(size, 90) > 0:
            ax.set_yscale("symlog", linthresh=float(np.percentile(size, 90)), linscale=2.0)
        for c in dy.crossings:
            ax.axvline(c.values[0] / v.factor, color="#2ca02c" if c.possible else "#d62728", lw=1.0)
        ax.set_ylabel("effort")
        ax.legend(loc="best")
        top = ax.secondary_xaxis(
            "top",
            functions=(
                lambda s: dy.law.time(np.asarray(s) * v.factor),
                lambda t: dy.law.position(t) / v.factor,
            ),
        )
        # ticks away from the ends, where the law is slow and times crowd together
        top.set_xticks(dy.law.duration * np.array([0.1, 0.3, 0.5, 0.7, 0.9]))
        top.set_xlabel("time (s)")
        _, sd, sdd = dy.law.rates(np.asarray(v.values, dtype=float))
        ax2.plot(x, sd / v.factor, color="#1f77b4", lw=1.4, label=f"rate ({v.file_unit}/s)")
        ax2.plot(
            x, sdd / v.factor, color="#ff7f0e", lw=1.4, label=f"acceleration ({v.file_unit}/s^2)"
        )
        ax2.axhline(0, color="#7f7f7f", lw=0.6)
        for c in dy.crossings:
            ax2.axvline(
                c.values[0] / v.factor, color="#2ca02c" if c.possible else "#d62728", lw=1.0
            )
        ax2.legend(loc="best")
    return fig


def dynamics_blocks(r: Any) -> list[doc.Block]:
    """The section (empty without a timed sweep)."""
    sw = r.sweep
    dy = None if sw is None else getattr(sw, "dynamics", None)
    if dy is None:
        return []
    what = "every joint's" if not dy.loops else "the inputs'"
    out: list[doc.Block] = [
        doc.Heading(2, "Dynamics along the sweep"),
        doc.Paragraph(
            f"The swept value follows a quintic rest-to-rest law over {dy.law.duration:g} s "
            f"(at rest at both ends); {what} efforts for that motion (N for a prismatic "
            "joint, N m for a rotation) from the file's masses"
            + (" and gravity" if dy.gravity else ", without gravity")
            + ". At a Type II singularity the efforts stay bounded only when the motion's "
            "dynamic wrench does no power on the twist the inputs leave free (the crossing "
            "condition); otherwise they grow as one over the distance to it."
        ),
        doc.Figure(
            "dynamics-sweep",
            svg(_figure(sw)),
            "efforts along the timed sweep",
            "Top: each effort along the path (time on the top axis; logarithmic beyond the "
            "typical |effort| when a few samples dwarf the rest); dotted grey: the located "
            "singularities; green / red lines: Type II points the motion crosses with "
            "bounded / unbounded efforts. Bottom: the swept value's rate and acceleration.",
        ),
    ]
    if dy.crossings:
        v = sw.variables[0]
        out.append(
            doc.Table(
                (f"{v.name} ({v.file_unit})", "time (s)", "crossing", "residual"),
                tuple(
                    (
                        f"{c.values[0] / v.factor:.8g}",
                        f"{c.time:.6g}",
                        "possible" if c.possible else "not possible",
                        f"{c.residual:.2g}",
                    )
                    for c in dy.crossings
                ),
                caption="The crossing condition at the located Type II points",
            )
        )
    return out
