"""The design review's configuration and sweep sections: each configuration's sketch
(on its sphere for a spherical mechanism) with the screws of its findings, its numbers
and its findings in sentences (:func:`configuration_sections`); the sweep's curves or
loci and its located points (:func:`sweep_section`)."""

from __future__ import annotations

import numpy as np

from mechsing.analysis import AnalysisResult, ConfigurationResult
from mechsing.analysis.display import floor_for
from mechsing.analysis.html import VERDICT_HEADERS
from mechsing.analysis.words import explain, margin_text
from mechsing.model import Mechanism
from mechsing.numeric import Precision, floored, to_float
from mechsing.reports import document as doc
from mechsing.reports.figures import grid_figure, path_figure, svg
from mechsing.reports.render import joint_values_text
from mechsing.reports.sketch import Screw, View, choose_view, sketch_figure
from mechsing.reports.sphere import choose_sphere_view, sphere_figure, spherical_centre
from mechsing.singularity.findings import ConstraintFinding, MotionFinding, SerialFinding
from mechsing.sweeps import SweepResult
from mechsing.sweeps.results import located_rows

__all__ = ["MAX_SCREWS", "configuration_sections", "sweep_section"]

#: the most screws drawn on one sketch
MAX_SCREWS = 4


def _configuration_q(mech: Mechanism, c: ConfigurationResult) -> list[float]:
    values = dict(c.joints)
    return [float(values[j][i]) for j, i in mech.coordinates()]


def _screws(mech: Mechanism, c: ConfigurationResult) -> list[Screw]:
    out: list[Screw] = []
    for f in c.singularities:
        if isinstance(f, SerialFinding):
            what = "the output chain" if f.chain == "output" else f"leg {f.leg}"
            out.append(Screw("twist", tuple(f.twist), f"lost twist of {what}"))
        elif isinstance(f, MotionFinding) and f.output_twist is not None:
            t = tuple(f.output_twist)
            if len(t) == 3:  # the velocity of the output's point: a translation there
                at = tuple(float(to_float(x)) for x in mech.output_reference_point())
                body = mech.output.body if mech.output else None
                out.append(
                    Screw(
                        "twist",
                        (0.0, 0.0, 0.0, *t),
                        "output point velocity (inputs locked)",
                        at,  # type: ignore[arg-type]
                        body,
                    )
                )
            else:
                out.append(Screw("twist", t, "output twist (inputs locked)"))
        elif isinstance(f, ConstraintFinding):
            for w in f.wrenches[: f.corank or 1]:
                out.append(Screw("wrench", tuple(w), "constraint wrench"))
    unique: list[Screw] = []
    for s in out:
        if not any(np.allclose(s.vector, u.vector) and s.kind == u.kind for u in unique):
            unique.append(s)
    return unique[:MAX_SCREWS]


def _sketch(
    analysis: AnalysisResult, c: ConfigurationResult, view: View, screws: list[Screw]
) -> tuple[object, str]:
    """A configuration's sketch and its caption: on a sphere for a spherical mechanism."""
    mech, q = analysis.mechanism, _configuration_q(analysis.mechanism, c)
    if spherical_centre(mech) is not None:
        fig = sphere_figure(mech, q, view, screws, f"{c.name}: {view.name}")
        caption = (
            "A spherical mechanism (every joint axis through one centre) on its unit sphere: "
            "each joint axis as the unit vector from the centre, each link as the great-circle "
            "arc between its joints (the ground's dashed), the far half of the sphere fainter"
        )
        lost = (
            "; the screws of the findings as coloured axes (a lost rotation's through the centre)."
        )
        return fig, caption + (lost if screws else ".")
    fig = sketch_figure(mech, q, view, screws, analysis.length_scale, f"{c.name}: {view.name}")
    caption = (
        "Links as segments between their joints (filled: a link with three joints or "
        "more), ground hatched, revolute axes as dash-dot lines or circles seen end "
        "on, sliders as boxes"
    )
    caption += "; the screws of the findings as coloured axes with their pitch." if screws else "."
    if view.why:
        caption += f" {view.name[:1].upper()}{view.name[1:]} because the mechanism is {view.why}."
    return fig, caption


def configuration_sections(analysis: AnalysisResult) -> list[doc.Block]:
    """Each configuration: its sketch with the screws of its findings, its numbers, its
    findings in sentences."""
    mech = analysis.mechanism
    view = choose_sphere_view(mech) if spherical_centre(mech) is not None else choose_view(mech)
    out: list[doc.Block] = [doc.Heading(2, "Configurations")]
    for c in analysis.configurations:
        out.append(doc.Heading(3, f"Configuration {c.name}"))
        if c.error is not None:
            out.append(doc.Paragraph(f"not analysed: {c.error}"))
            continue
        screws = _screws(mech, c)
        fig, caption = _sketch(analysis, c, view, screws)
        out.append(
            doc.Figure(
                f"config-{doc.slug(c.name)}",
                svg(fig),
                f"sketch of {mech.name} at {c.name}",
                caption,
            )
        )
        L = analysis.length_scale
        items = [f"joint values (m, rad): {joint_values_text(c, L)}"]
        if c.closure_residual is not None:
            res = floored(c.closure_residual, floor_for(c.precision, L))
            items.append(f"closure residual {res:.3g} m")
        if c.mobility is not None:
            m = c.mobility
            items.append(
                f"mobility: finite {m.finite}, generic {m.generic}, instantaneous "
                f"{m.instantaneous}, group {m.group}, Grübler-Kutzbach {m.grubler}"
            )
        if c.output_motion is not None:
            om = c.output_motion
            shown = f"instantaneous screw {om.summary}" if om.instantaneous_screw else om.summary
            items.append(f"output motion: {shown}")
        below = c.data_resolution  # said in a paragraph of its own, below
        items += [f"note: {n}" for n in c.notes if below is None or n != below.note]
        out.append(doc.Bullets(tuple(items)))
        if c.data_resolution is not None:
            out.append(doc.Paragraph(f"{c.data_resolution.note}.", "Below the data's resolution:"))
        if not c.singularities:
            out.append(
                doc.Paragraph("No singularity: every test kept its generic rank.", "Regular.")
            )
        for s in c.singularities:
            verb = "tested" if s.cls == "undecided" else "decided"
            out.append(
                doc.Paragraph(
                    f"{explain(s)}. {verb.capitalize()} in {s.precision}; margin: {margin_text(s.margin)}.",
                    f"{s.cls}:",
                )
            )
    return out


def _start(analysis: AnalysisResult, sw: SweepResult) -> tuple[float, float] | None:
    """The start of a grid sweep in the file's units (None when it is not known here)."""
    start = next((c for c in analysis.configurations if c.name == sw.from_config), None)
    if start is None or start.error is not None:
        return None
    values = dict(start.joints)
    out = []
    for v in sw.variables:
        name, _, index = v.name.partition("[")
        if name.startswith("pose."):
            if start.pose is None:
                return None
            key = name[5:]
            vec = start.pose.position if len(key) == 1 else start.pose.rotation_vector
            out.append(vec["xyz".index(key[-1])] / v.factor)
        elif name in values:
            i = int(index.rstrip("]")) if index else 0
            out.append(values[name][i] / v.factor)
        else:
            return None
    return (out[0], out[1])


def sweep_section(analysis: AnalysisResult, sw: SweepResult) -> list[doc.Block]:
    """The sweep: its path's curves or its grid's loci, and what was located."""
    out: list[doc.Block] = [doc.Heading(2, "Sweep")]
    first = sw.to_text().splitlines()[0]
    out.append(
        doc.Paragraph(
            f"{first}; {sw.points()} samples, {int(sw.reached.sum())} reached on the start's "
            f"assembly mode; held at the start's values: {', '.join(sw.held) or 'nothing'}."
        )
    )
    tol = Precision("float").tolerances
    if not sw.grid:
        v = sw.variables[0]
        x = np.asarray(v.values, dtype=float) / v.factor
        curves = []
        for t in sw.tests:  # the located points join the samples of the tests that vanish there
            extra = [(p.values[0] / v.factor, p.ratio) for p in sw.located if t in p.tests]
            xs = np.concatenate([x, [e[0] for e in extra]])
            ys = np.concatenate([np.asarray(sw.ratio[t], dtype=float), [e[1] for e in extra]])
            order = np.argsort(xs, kind="stable")
            curves.append((t, xs[order], ys[order]))
        marks = []
        for p in sw.located:
            label = ", ".join(p.classes or ()) if p.classes is not None else "not classified"
            if p.kind == "fold":
                label = "limit of travel" + (f": {label}" if label else "")
            marks.append((p.values[0] / v.factor, p.ratio, label or "no singularity"))
        fig = path_figure(f"{v.name} ({v.file_unit})", curves, (tol.tau_lo, tol.tau_hi), marks)
        out.append(
            doc.Figure(
                "sweep",
                svg(fig),
                f"smallest relative singular value of each test along {v.name}",
                "Each test's smallest relative singular value along the path (log scale). "
                f"Grey band: float's undecided band from tau_lo = {tol.tau_lo:g} to tau_hi = "
                f"{tol.tau_hi:g}; below it (red tint) a value counts as zero. Triangles: the "
                "located singularities, numbered as in the table below.",
            )
        )
        rows = [(str(k + 1), *row) for k, row in enumerate(located_rows(sw))]
        if rows:
            out.append(
                doc.Table(("#", *VERDICT_HEADERS), tuple(rows), caption="Located singularities")
            )
        else:
            out.append(doc.Paragraph("No singularity located on the path."))
    else:
        vx, vy = sw.variables
        x = np.asarray(vx.values, dtype=float) / vx.factor
        y = np.asarray(vy.values, dtype=float) / vy.factor
        loci = []
        for lo in sw.loci:
            verts = np.asarray(lo.vertices, dtype=float) / np.array([vx.factor, vy.factor])
            loci.append((", ".join(lo.classes) or "unclassified", verts))
        points = [
            (p.values[0] / vx.factor, p.values[1] / vy.factor, ", ".join(p.classes or ()) or "-")
            for p in sw.located
        ]
        fig = grid_figure(
            x,
            y,
            (f"{vx.name} ({vx.file_unit})", f"{vy.name} ({vy.file_unit})"),
            np.asarray(sw.reached, dtype=bool),
            loci,
            points,
            _start(analysis, sw),
            [a.mask for a in sw.aspects],
        )
        on = "the start's assembly mode" if sw.mode is None else f"assembly mode {sw.mode}"
        out.append(
            doc.Figure(
                "sweep",
                svg(fig),
                f"singularity loci over {vx.name} and {vy.name}",
                "The singularity loci over the two swept variables, coloured by the class "
                "found at their points (dots: the located points); tinted, each "
                f"singularity-free region (aspect) of {on}, one colour each; grey: samples "
                "not reached on the start's assembly mode; star: the start.",
            )
        )
        if sw.aspects:
            out.append(
                doc.Table(
                    (
                        "region",
                        "samples",
                        f"{vx.name} ({vx.file_unit})",
                        f"{vy.name} ({vy.file_unit})",
                    ),
                    tuple(
                        (
                            str(k + 1),
                            str(a.cells),
                            f"{a.box[0][0] / vx.factor:.6g} to {a.box[0][1] / vx.factor:.6g}",
                            f"{a.box[1][0] / vy.factor:.6g} to {a.box[1][1] / vy.factor:.6g}",
                        )
                        for k, a in enumerate(sw.aspects)
                    ),
                    caption=f"The {len(sw.aspects)} singularity-free regions (aspects) of {on}",
                )
            )
        rows = located_rows(sw)
        if rows:
            out.append(
                doc.Details(
                    f"The {len(rows)} located singularities",
                    (doc.Table(VERDICT_HEADERS, tuple(rows)),),
                )
            )
    if sw.notes:
        notes = doc.Bullets(tuple(sw.notes))
        out.append(
            notes
            if len(sw.notes) <= 3
            else doc.Details(f"The sweep's {len(sw.notes)} notes", (notes,))
        )
    return out
