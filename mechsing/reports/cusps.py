"""The figure of a section (``mechsing cusps --plot``, and the report's section with
cusps): the number of modes on the grid coloured, the located points of the singular
curves, the cusps marked (filled: certified).

Owns :func:`cusps_figure`, :func:`write_figure` and :func:`cusps_blocks` (the report's
section).
"""

from __future__ import annotations

from typing import Any

import matplotlib
import numpy as np
from matplotlib.colors import BoundaryNorm, ListedColormap
from matplotlib.figure import Figure

from mechsing.reports.figures import RC, new_figure, svg

__all__ = ["cusps_blocks", "cusps_figure", "write_figure"]


def cusps_figure(doc: dict[str, Any]) -> Figure:
    """The figure of a ``cusps`` document (its JSON, :meth:`CuspsResult.to_json`)."""
    (a_name, a_rng), (b_name, b_rng) = doc["section"]["vary"].items()
    grid = doc["modes_grid"]
    fig = new_figure(6.4, 5.4)
    with matplotlib.rc_context(RC):
        ax = fig.add_subplot()
        if grid:
            A, B = np.asarray(grid[a_name]), np.asarray(grid[b_name])
            counts = np.asarray(grid["modes"], dtype=float)
            da, db = (A[1] - A[0]) / 2, (B[1] - B[0]) / 2
            # one band of the colour bar per count seen (the counts are whole numbers:
            # a continuous scale would suggest values between them)
            levels = sorted({int(v) for v in counts.ravel()})
            shades = matplotlib.colormaps["Blues"](np.linspace(0.08, 0.85, len(levels)))
            index = np.searchsorted(levels, counts.astype(int))
            image = ax.imshow(
                index.T,
                extent=(A[0] - da, A[-1] + da, B[0] - db, B[-1] + db),
                origin="lower",
                cmap=ListedColormap(shades),
                norm=BoundaryNorm(np.arange(len(levels) + 1) - 0.5, len(levels)),
                aspect="auto",
                interpolation="nearest",
            )
            bar = fig.colorbar(image, ax=ax, ticks=range(len(levels)), shrink=0.8)
            bar.ax.set_yticklabels([str(v) for v in levels])
            bar.set_label("real modes")
        pts = np.asarray(doc["singular_curves"]["points"], dtype=float).reshape(-1, 2)
        if len(pts):
            ax.plot(pts[:, 0], pts[:, 1], ".", color="#d62728", ms=2.0, label="singular curves")
        for k, c in enumerate(doc["cusps"]):
            x, y = c["inputs"][a_name], c["inputs"][b_name]
            ax.plot(
                [x],
                [y],
                marker="o",
                ms=8,
                ls="",
                mec="black",
                mfc="gold" if c["certified"] else "white",
                label=None if k else "cusp (filled: certified)",
            )
            ax.annotate(f"{k + 1}", (x, y), xytext=(5, 5), textcoords="offset points")
        ax.set_xlim(*a_rng)
        ax.set_ylim(*b_rng)
        if not grid:  # decoupled: proved without a grid; say so rather than draw nothing
            ax.text(
                0.5,
                0.5,
                "no grid computed: no cusp anywhere\n(the modes meet in pairs only; "
                "see the evidence)",
                ha="center",
                va="center",
                transform=ax.transAxes,
            )
        # an arm's section is the workspace half-plane: lengths (the document is in SI)
        unit = " (m)" if doc.get("problem") == "inverse kinematics" else ""
        ax.set_xlabel(a_name + unit)
        ax.set_ylabel(b_name + unit)
        fixed = ", ".join(f"{n} = {v:.6g}" for n, v in doc["section"]["fixed"].items())
        verdict = "cuspidal" if doc["cuspidal"] else "not cuspidal"
        ax.set_title(f"{doc['mechanism']}: {verdict}" + (f" ({fixed})" if fixed else ""))
        if len(pts) or doc["cusps"]:  # below the axes: it hides no cusp
            ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=2)
    return fig


def write_figure(doc: dict[str, Any], path: str) -> None:
    """The figure to ``path`` (PNG, or SVG when the name ends in .svg)."""
    import io

    from mechsing.files import write_output

    fig = cusps_figure(doc)
    if path.lower().endswith(".svg"):
        write_output(path, svg(fig), [], option="--plot")
        return
    buf = io.BytesIO()
    with matplotlib.rc_context(RC):
        fig.savefig(buf, format="png", bbox_inches="tight", metadata={"Software": None})
    write_output(path, buf.getvalue(), [], option="--plot")


def cusps_blocks(res: Any) -> list[Any]:
    """The report's section "Cusps" of a :class:`~mechsing.assembly.cusps.CuspsResult`:
    the verdict with its evidence, the figure, each cusp."""
    from mechsing.assembly.cusps_render import render_cusps
    from mechsing.reports import document as doc

    data = res.to_json()
    lines = render_cusps(data, "text").splitlines()
    out: list[Any] = [
        doc.Heading(2, "Cusps"),
        doc.Paragraph(lines[0] + "."),
        doc.Paragraph("Evidence: " + data["evidence"]["reason"] + "."),
        doc.Figure(
            "cusps-section",
            svg(cusps_figure(data)),
            f"the section of {data['mechanism']}: real modes, singular curves, cusps",
            "The number of real modes on the grid coloured, the singular curves' located "
            "points in red, the cusps circled (filled: certified).",
        ),
    ]
    cusp_lines = [ln for ln in lines if ln[:1].isdigit()]
    if cusp_lines:
        out.append(doc.Bullets(tuple(cusp_lines)))
    return out
