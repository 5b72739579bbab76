"""The design review's kinetostatics section: the efforts under the load and the
transmission indices at each configuration that has a load, and along a path sweep the
efforts and the local transmission index against the swept value, with the located
singularities and the effort limits marked (docs/kinetostatics.md)."""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing.reports import document as doc
from mechsing.reports.figures import svg, swept_axes

__all__ = ["kinetostatics_blocks"]


def _num(x: Any, unit: str = "") -> str:
    return "-" if x is None else f"{float(x):.4g}{(' ' + unit) if unit else ''}"


def _configuration_rows(r: Any) -> list[tuple[str, ...]]:
    rows = []
    for c in r.analysis.configurations:
        ks = c.kinetostatics
        if ks is None:
            continue
        unit = {
            n: ("N" if ln else "N m") for n, ln in zip(ks.inputs, ks.input_lengths, strict=True)
        }
        eq = ks.equilibrium
        if eq is None:
            efforts = "no load"
        elif eq.efforts is None:
            efforts = "unbounded (Type II)"
        else:
            efforts = ", ".join(f"{n} {v:.4g} {unit[n]}" for n, v in eq.efforts.items())
        ue = ks.units
        per_f = ", ".join(
            "unbounded" if v is None else f"{v[0]:.4g} {u}/N ({v[1]})" for u, v in ue.force.items()
        )
        per_m = ", ".join(
            "unbounded" if v is None else f"{v[0]:.4g} {u}/(N m) ({v[1]})"
            for u, v in ue.couple.items()
        )
        tr = ks.transmission
        trs = (
            f"input {', '.join(f'{x:.3g}' for x in tr.input or ())}; output "
            f"{', '.join(f'{x:.3g}' for x in tr.output or ())}; local {tr.local:.3g}"
            if tr.local is not None
            else f"none: {tr.reason}"
        )
        rows.append((c.name, efforts, per_f, per_m, trs))
    return rows


def _path_figure(sw: Any) -> Any:
    st = sw.statics
    v = sw.variables[0]
    with swept_axes(sw, 4.6) as (fig, ax, ax2, x):
        for i, n in enumerate(st.inputs):
            ax.plot(x, np.abs(st.efforts[:, i]), lw=1.4, label=f"|{n}| ({st.units[n]})")
        for n, lim in st.limits.items():
            ax.axhline(lim, color="#d62728", lw=0.8, ls="--")
            ax.annotate(f"limit {n}", (x[0], lim), fontsize=7, color="#d62728")
        for p in st.located:
            ax.axvline(p.values[0] / v.factor, color="#d62728", lw=0.8)
        ax.set_yscale("log")
        ax.set_ylabel("|effort|")
        ax.legend(loc="best")
        ax2.plot(x, st.local, color="#2ca02c", lw=1.4, label="local transmission index")
        ax2.set_ylim(0, 1.05)
        ax2.legend(loc="best")
    return fig


def kinetostatics_blocks(r: Any) -> list[doc.Block]:
    """The section (empty when no configuration has a load and the sweep has none)."""
    rows = _configuration_rows(r)
    sw = r.sweep
    along = sw is not None and getattr(sw, "statics", None) is not None and not sw.grid
    if not rows and not along:
        return []
    out: list[doc.Block] = [
        doc.Heading(2, "Kinetostatics"),
        doc.Paragraph(
            "The actuator efforts that hold the load on the output (N for a prismatic input, "
            "N m for a rotation; unbounded at a Type II configuration when the load does "
            "power on the output twist the inputs do not control), the largest effort over "
            "unit pure forces and unit pure couples on the output, and the motion/force "
            "transmission indices of Wang, Wu and Liu (2010; 1 is best, 0 a singularity)."
        ),
    ]
    if rows:
        out.append(
            doc.Table(
                ("configuration", "efforts", "per unit force", "per unit couple", "transmission"),
                tuple(rows),
                caption="Efforts and transmission at each configuration",
            )
        )
    if along:
        st = sw.statics
        out.append(
            doc.Figure(
                "kinetostatics-sweep",
                svg(_path_figure(sw)),
                "efforts and local transmission index along the path",
                "Top: each input's |effort| under the load along the path (log scale); dashed "
                "red: the --max-effort limits; red lines: where an effort crosses its limit; "
                "dotted grey: the located singularities. Bottom: the local transmission index.",
            )
        )
        if st.located:
            v = sw.variables[0]
            out.append(
                doc.Table(
                    ("input", "limit", f"{v.name} ({v.file_unit})", "crossing"),
                    tuple(
                        (
                            p.input,
                            f"{p.limit:g} {st.units[p.input]}",
                            f"{p.values[0] / v.factor:.8g}",
                            "exceeds" if p.exceeds else "falls back below",
                        )
                        for p in st.located
                    ),
                    caption="Effort limits (not singularities)",
                )
            )
    return out
