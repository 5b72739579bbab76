"""The design-review report: :func:`report` and :class:`Report` (HTML, Markdown, notebook).

A report holds the analysis of a mechanism's configurations (:func:`mechsing.analyze`) and
at most one sweep (:func:`mechsing.sweep`: a path or a grid), and reads them in the order a
reviewer does: the verdict table first (a row per configuration and per located singularity
of a path; a row per locus of a grid), then the mechanism (joints table, graph drawing, each
loop's subgroup in words, the mobility numbers with why they differ), each configuration
(a sketch with the screws of its findings, the findings in sentences with their numbers),
the sweep (curves or loci) and how it was computed.  Everything is in SI units and radians
except the swept values of a sweep, which are also shown in the file's units.

The document is deterministic: the same inputs give the same bytes, except the one line
that says how long it took (``Report.seconds``).
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mechsing import __version__
from mechsing.analysis import AnalysisResult, ConfigurationResult, analyze
from mechsing.analysis.contract import subgroup_params
from mechsing.analysis.describe import OutputMotion
from mechsing.analysis.html import VERDICT_HEADERS, class_words, largest_drop, verdict_row
from mechsing.analysis.results import Mobility
from mechsing.model import Mechanism
from mechsing.model.couplings import coupling_source, describe_coupling
from mechsing.numeric import Precision, display_floor, floored, parse_precision, to_float
from mechsing.reader import read_mechanism
from mechsing.report import document as doc
from mechsing.report.figures import graph_figure, grid_figure, path_figure, svg
from mechsing.report.render import _margin, explain, joint_values_text, scene_line
from mechsing.report.sketch import Screw, View, choose_view, sketch_figure
from mechsing.report.sphere import choose_sphere_view, sphere_figure, spherical_centre
from mechsing.report.words import twist_words
from mechsing.singularity.findings import (
    ConstraintFinding,
    MotionFinding,
    SerialFinding,
)
from mechsing.singularity.zfb import not_run_sentences
from mechsing.subgroups import Subgroup, load_catalog
from mechsing.sweeps import SweepResult, sweep
from mechsing.sweeps.results import located_rows
from mechsing.sweeps.spec import Vary

__all__ = ["Report", "report"]

#: the most screws drawn on one sketch
MAX_SCREWS = 4


@dataclass(frozen=True)
class Report:
    """A design review of a mechanism: ``analysis``, an optional ``sweep``, the
    ``command`` that made it and the ``seconds`` it took.

    ``to_html()``: one self-contained HTML file; ``to_markdown(folder)``: Markdown with
    the figures written into ``folder``; in a notebook the report shows itself."""

    analysis: AnalysisResult
    sweep: SweepResult | None = None
    command: str = ""
    seconds: float = field(default=0.0, compare=False)
    modes: object | None = None  # a ModesResult: the section "Assembly modes"

    @property
    def mechanism(self) -> Mechanism:
        """The mechanism reviewed."""
        return self.analysis.mechanism

    def blocks(self) -> list[doc.Block]:
        """The document as blocks (:mod:`mechsing.report.document`)."""
        return _blocks(self)

    def to_html(self) -> str:
        """The report as one self-contained HTML document (inline CSS and figures, no script)."""
        return doc.to_html(self.blocks(), f"Design review: {self.mechanism.name}")

    def to_markdown(
        self,
        folder: str | Path,
        relative_to: str | Path | None = None,
        inputs: Sequence[str | Path] = (),
    ) -> str:
        """The Markdown text; its figures are written into ``folder`` (created; its parent
        must exist) and linked relative to ``relative_to`` (default: the folder's parent,
        where the Markdown goes); no figure may be one of the files ``inputs``."""
        folder = Path(folder)
        return doc.to_markdown(self.blocks(), folder, relative_to or folder.parent, inputs)

    def write(self, path: str | Path, inputs: Sequence[str | Path] = ()) -> Path:
        """Write the report to ``path``: HTML, or Markdown for a ``.md`` path (its figures
        in the folder of the path's stem + ``_files`` beside it), atomically and never
        over one of the files ``inputs`` (:mod:`mechsing.files`); the file written."""
        from mechsing.files import check_output, write_output

        path = check_output(path, inputs)  # a link resolved: the figures go beside its file
        if path.suffix.lower() != ".md":
            return write_output(path, self.to_html(), inputs)
        folder = path.with_name(path.stem + "_files")
        return write_output(path, self.to_markdown(folder, path.parent, inputs), inputs)

    def _repr_html_(self) -> str:
        return doc.html_fragment(self.blocks())


def report(
    mechanism_or_path: Mechanism | str | Path,
    configs: Sequence[str] | None = None,
    vary: Sequence[str | Vary] | str | Vary | None = None,
    precision: Precision | str = "auto",
    from_config: str | None = None,
    *,
    command: str | None = None,
    time_limit: float | None = None,
    modes_of: str | None = None,
) -> Report:
    """A design review of a mechanism (or a file), ready to write as HTML or Markdown.

    Parameters
    ----------
    mechanism_or_path : Mechanism, str or Path
        The mechanism, or the path of its file (any format mechsing reads).
    configs : sequence of str, optional
        The configurations analysed (as ``mechsing.analyze`` does); default: all.
    vary : sequence of str, or str, optional
        One ``"NAME=START:STOP:STEP"`` for a path, two for a grid (in the file's units):
        the report then sweeps the mechanism too.
    precision : Precision or str
        The analysis's precision mode (``auto``, ``float``, ``mp:N``).
    from_config : str, optional
        The configuration the sweep starts from (default ``reference``).
    command : str, optional
        How the report was asked for, shown at its end (default: this call).
    time_limit : float or None
        The most seconds one configuration (or located point) may take, as for
        ``mechsing.analyze``.
    modes_of : str, optional
        A configuration whose every assembly mode (``mechsing.modes``) the report shows
        in a section "Assembly modes", each with a sketch.

    Returns
    -------
    Report
        ``to_html()``, ``to_markdown(folder)``, ``write(path)``, and ``_repr_html_`` for
        a notebook.
    """
    t0 = time.perf_counter()
    mech = (
        mechanism_or_path
        if isinstance(mechanism_or_path, Mechanism)
        else read_mechanism(mechanism_or_path)
    )
    prec = parse_precision(precision) if isinstance(precision, str) else precision
    result = analyze(mech, list(configs) if configs else None, prec, time_limit=time_limit)
    swept = None
    if vary:
        varies = [vary] if isinstance(vary, str | Vary) else list(vary)
        swept = sweep(mech, varies, from_config, prec, time_limit=time_limit)
    if command is None:
        args = [repr(mech.path or mech.name)]
        if configs:
            args.append(f"configs={list(configs)!r}")
        if vary:
            args.append(f"vary={vary!r}")
        args.append(f"precision={str(prec)!r}")
        if from_config:
            args.append(f"from_config={from_config!r}")
        command = f"mechsing.report({', '.join(args)})"
    found = None
    if modes_of is not None:
        from mechsing.assembly import modes

        found = modes(mech, modes_of, prec, time_limit=time_limit)
    return Report(result, swept, command, time.perf_counter() - t0, found)


# --------------------------------------------------------------------------- words


#: display only: a component below this fraction of a vector's largest is shown as 0
#: (rounding noise of a computed direction, e.g. 1e-17 beside 1); nothing is decided by it
DISPLAY_ZERO = 1e-12


def _vec(v: Sequence[float]) -> str:
    big = max((abs(x) for x in v), default=0.0)
    return "(" + ", ".join(f"{x if abs(x) > DISPLAY_ZERO * big else 0.0:.4g}" for x in v) + ")"


def subgroup_words(sg: Subgroup | None) -> str:
    """A subgroup in words: its symbol, catalog name, dimension and parameters (SI)."""
    if sg is None:
        return "not identified"
    name = load_catalog()[sg.symbol].name
    ps = ", ".join(
        f"{k} {_vec(v)}" if isinstance(v, list) else f"{k} {v:.4g}"
        for k, v in subgroup_params(sg).items()
    )
    return f"{sg.symbol}, {name} (dimension {sg.dim}{'; ' + ps if ps else ''})"


def _joint_params(params: dict) -> str:
    parts = []
    for k, v in params.items():
        if k == "axes":
            parts.append("axes " + " and ".join(_vec(_floats(a)) for a in v))
        elif isinstance(v, tuple | list):
            unit = " m" if k == "point" else ""
            parts.append(f"{k} {_vec(_floats(v))}{unit}")
        else:
            parts.append(f"{k} {float(to_float(v)):.4g}")
    return ", ".join(parts) or "-"


def _floats(v: Sequence[object]) -> list[float]:
    return [float(to_float(x)) for x in v]


#: what a loop's subgroup means, for the common ones
LOOP_MEANING = {
    "G": "this loop moves in a plane (planar subgroup G, normal {normal}): it imposes 3 "
    "constraints, not 6",
    "S": "this loop turns about a point (spherical subgroup S, centre {point}): it imposes 3 "
    "constraints, not 6",
    "X": "this loop moves with Schoenflies motion (translations and turns about {axis}): it "
    "imposes 2 constraints",
    "T3": "this loop only translates: it imposes 3 constraints",
    "Y": "this loop moves inside a pseudo-planar subgroup Y: it imposes 3 constraints",
    "D": "this loop's joints generate every displacement: a general spatial loop, 6 constraints",
}


def loop_meaning(sg: Subgroup | None) -> str:
    if sg is None:
        return "its subgroup was not identified: it is counted as a general spatial loop"
    p = {k: _vec(v) if isinstance(v, list) else f"{v:.4g}" for k, v in subgroup_params(sg).items()}
    text = LOOP_MEANING.get(sg.symbol)
    if text is None:
        return f"this loop moves inside {subgroup_words(sg)}: it imposes {sg.dim} constraints"
    try:
        return text.format(**p)
    except KeyError:  # a catalog whose parameters are named otherwise
        return text


def mobility_sentences(m: Mobility) -> list[tuple[str, str, str]]:
    """(name, value, why) of the five mobility numbers of a configuration."""

    def v(x: int | None) -> str:
        return "-" if x is None else str(x)

    out = [
        (
            "Grübler-Kutzbach (spatial)",
            v(m.grubler),
            "6 per moving body minus the constraints of every joint, as if every loop "
            "imposed 6 constraints",
        )
    ]
    if m.group is not None and m.grubler is not None and m.group != m.grubler:
        why = (
            f"counts each loop's constraints in the subgroup its joints generate; it differs "
            f"from the spatial count by {m.group - m.grubler} because the loops move inside "
            "smaller subgroups (planar, spherical...)"
        )
    else:
        why = "counts each loop's constraints in the subgroup its joints generate; here it "
        why += "agrees with the spatial count (general spatial loops)"
    out.append(("group (loop subgroups)", v(m.group), why))
    if m.instantaneous is not None and m.finite is not None and m.instantaneous > m.finite:
        why = (
            "the closure system's nullity here; above the finite mobility: first-order motions "
            "that do not extend (a singularity of the configuration space, or shakiness)"
        )
    else:
        why = (
            "the closure system's nullity here (first-order motions); it equals the finite mobility"
        )
    out.append(("instantaneous", v(m.instantaneous), why))
    out.append(
        (
            "generic",
            v(m.generic),
            "the mobility at the regular configurations of this motion branch (what the "
            "classification compares against)",
        )
    )
    if m.finite == 0 and m.group is not None and m.group < 0:
        why = (
            "the dimension of the motion through this configuration: none, a structure; "
            "above the group count: some constraints are redundant"
        )
    elif m.finite is not None and m.group is not None and m.finite > m.group:
        why = (
            "the dimension of the motion through this configuration; above the group count: "
            "the mobility comes from special geometry (an overconstrained mechanism)"
        )
    else:
        why = "the dimension of the motion through this configuration"
    out.append(("finite", v(m.finite), why))
    return out


# --------------------------------------------------------------------------- sections


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


def _verdict(r: Report) -> list[doc.Block]:
    rows = [verdict_row(c) for c in r.analysis.configurations]
    if r.sweep is not None and not r.sweep.grid:
        rows += located_rows(r.sweep)
    elif r.sweep is not None:
        for k, lo in enumerate(r.sweep.loci):
            on = [
                p
                for p in r.sweep.located
                if p.configuration is not None
                and lo.test in p.tests
                and any(np.allclose(p.values, v) for v in lo.vertices)
            ]
            decided = sorted({p.precision or "-" for p in on}) or ["-"]
            drops = [d for p in on if (d := largest_drop(p.configuration)) is not None]
            if drops:
                d, m = max(drops, key=lambda t: t[0])
                margin = f"largest dropped {d:.3g} <= tau_lo {m.tau_lo:.3g} over its points"
            else:
                margin = "-"
            singular = "yes" if any(p.singular for p in on) else ("undecided" if on else "-")
            rows.append(
                (
                    f"sweep: locus {k + 1} of {lo.test} ({len(lo.vertices)} points)",
                    singular,
                    class_words(lo.classes) if lo.classes else "not classified",
                    margin,
                    ", ".join(decided),
                )
            )
    marked = frozenset(i for i, row in enumerate(rows) if row[1] != "no")
    singular = sum(1 for row in rows if row[1] == "yes")
    if singular:
        lead = f"{singular} of {len(rows)} rows are singular (highlighted)."
    elif marked:
        lead = "No singularity found, but some rows are not decided (highlighted)."
    else:
        lead = f"No singularity: all {len(rows)} rows are regular."
    # what was not looked for is said with what was found
    for sentence in not_run_sentences(r.analysis.mechanism):
        lead += f" Tests not run: {sentence}."
    return [
        doc.Heading(2, "Verdict"),
        doc.Paragraph(lead),
        doc.Table(VERDICT_HEADERS, tuple(rows), marked=marked),
        doc.Paragraph(
            "Margin: the relative singular value that decided the verdict (dropped: at or "
            "below tau_lo, counted as zero; kept: at or above tau_hi, counted as non-zero), "
            "relative to the largest singular value of the same test."
        ),
    ]


def _mechanism(r: Report) -> list[doc.Block]:
    mech = r.mechanism
    inputs = {ref.joint for ref in mech.inputs}
    out: list[doc.Block] = [doc.Heading(2, "The mechanism")]
    output = (
        f"output: {mech.output.body} relative to {mech.output.relative_to}"
        if mech.output
        else "no output"
    )
    out.append(
        doc.Paragraph(
            f"{len(mech.bodies)} bodies (ground: {mech.ground}), {len(mech.joints)} joints "
            f"with {mech.dof} joint coordinates, {len(mech.loops)} independent loop(s); "
            f"inputs: {', '.join(str(i) for i in mech.inputs) or 'none'}; {output}."
        )
    )
    if mech.scene is not None and mech.scene.notes:
        out.append(doc.Paragraph(" ".join(scene_line(n) for n in mech.scene.notes)))
    catalog = load_catalog()
    rows = []
    for j in mech.joints:
        kind = (
            "universal joint (two revolutes)"
            if j.type == "U"
            else catalog[j.type].name
            if j.type in catalog
            else j.type
        )
        rows.append(
            (
                j.name,
                f"{j.between[0]} - {j.between[1]}",
                f"{j.type}: {kind}",
                _joint_params(dict(j.params)),
                ", ".join(j.units),
                "yes" if j.name in inputs else "",
            )
        )
    out.append(
        doc.Table(
            (
                "joint",
                "between",
                "subgroup type",
                "parameters (SI, reference configuration)",
                "coordinates",
                "input",
            ),
            tuple(rows),
            caption="Joints",
        )
    )
    loops = [lp.joints for lp in mech.loops]
    fig = graph_figure(
        mech.bodies,
        mech.ground,
        [(j.name, j.type, j.between[0], j.between[1]) for j in mech.joints],
        loops,
        [lp.bodies for lp in mech.loops],
    )
    out.append(
        doc.Figure(
            "graph",
            svg(fig),
            f"graph of {mech.name}: bodies as nodes, joints as edges",
            "Bodies as nodes (the ground grey, in bold), joints as labelled edges (type in "
            "brackets); each loop shaded in its colour.",
        )
    )
    first = next((c for c in r.analysis.configurations if c.error is None), None)
    if first is not None and first.loops:
        out.append(doc.Heading(3, "Loops"))
        out.append(
            doc.Bullets(
                tuple(
                    f"loop {k + 1} ({'-'.join(lp.joints)}): {loop_meaning(lp.subgroup)}; "
                    f"generated subgroup {subgroup_words(lp.subgroup)}"
                    for k, lp in enumerate(first.loops)
                )
            )
        )
    if mech.couplings:
        out.append(doc.Heading(3, "Couplings"))
        out.append(
            doc.Bullets(
                tuple(
                    f"{describe_coupling(c)} ({coupling_source(c)}; SI, radians): one row of "
                    "the closure system, one degree of freedom less"
                    for c in mech.couplings
                )
            )
        )
    out += _legs_and_motion(r)
    if first is not None and first.mobility is not None:
        out.append(doc.Heading(3, "Mobility"))
        out.append(
            doc.Table(
                ("number", "value", "what it counts and why it differs"),
                tuple(mobility_sentences(first.mobility)),
                caption=f"At configuration {first.name}",
            )
        )
    if r.analysis.properties:
        out.append(doc.Bullets(tuple(f"{p.kind}: {p.explanation}" for p in r.analysis.properties)))
    return out


def motion_words(m: OutputMotion) -> str:
    """The output's twist space in words: its subgroup (type, name, parameters), its
    instantaneous screw when it is one twist, or what its twists span when they span no
    subgroup."""
    if m.dim is None:
        return f"undecided at {m.precision}"
    if m.instantaneous_screw and m.subgroup is not None:
        return f"instantaneous screw {subgroup_words(m.subgroup)}"
    if m.is_subgroup and m.subgroup is not None:
        return subgroup_words(m.subgroup)
    if m.is_subgroup is False:
        return f"not a subgroup: {m.dim} independent twists whose brackets leave their span"
    return f"dimension {m.dim} ({m.note or 'type not identified'})"


def _legs_and_motion(r: Report) -> list[doc.Block]:
    out: list[doc.Block] = []
    a = r.analysis
    if a.legs:
        out.append(doc.Heading(3, "Legs"))
        rows = tuple(
            (
                str(leg.number),
                " - ".join(leg.joints),
                ", ".join(leg.other_joints) or "-",
                ", ".join(leg.bodies) or "-",
            )
            for leg in a.legs
        )
        out.append(
            doc.Table(
                (
                    "leg",
                    f"joints from {a.legs[0].base} to {a.legs[0].body}",
                    "other joints",
                    "bodies",
                ),
                rows,
            )
        )
    m = a.output_motion
    if m is not None and m.instantaneous_screw and m.subgroup is not None:
        # one twist: the screw the output turns about at that instant, not a motion type
        screw = twist_words(m.twists[0], a.length_scale)
        out.append(doc.Heading(3, "Output motion"))
        out.append(
            doc.Paragraph(
                f"{m.body} relative to {m.relative_to} has one degree of freedom: at the "
                f"regular configuration {m.configuration} it moves by {screw}, its "
                f"instantaneous screw {subgroup_words(m.subgroup)} (decided in {m.precision}; "
                f"margin: {_margin(m.margin)}). An instantaneous screw is not a motion type "
                "(a subgroup the output's motions stay in): it can change as the mechanism moves."
            )
        )
    elif m is not None:
        out.append(doc.Heading(3, "Output motion type"))
        out.append(
            doc.Paragraph(
                f"The twists of {m.body} relative to {m.relative_to} span "
                f"{motion_words(m)}: its motion type at the regular configuration "
                f"{m.configuration} (decided in {m.precision}; margin: {_margin(m.margin)})."
            )
        )
    if m is not None:
        # a type the precision left undecided is not a difference
        differ = [
            (c.name, c.output_motion)
            for c in a.configurations
            if c.output_motion is not None
            and not c.output_motion.undecided
            and c.output_motion.summary != m.summary
        ]
        if differ:
            out.append(
                doc.Paragraph("Where it differs (a singularity changes what the output can do):")
            )
            out.append(doc.Bullets(tuple(f"at {name}: {motion_words(cm)}" for name, cm in differ)))
    return out


def _sketch(
    r: Report, c: ConfigurationResult, view: View, screws: list[Screw]
) -> tuple[object, str]:
    """A configuration's sketch and its caption: on a sphere for a spherical mechanism."""
    mech, q = r.mechanism, _configuration_q(r.mechanism, c)
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
    fig = sketch_figure(mech, q, view, screws, r.analysis.length_scale, f"{c.name}: {view.name}")
    caption = (
        "Links as segments between their joints (filled: a link with three joints or "
        "more), ground hatched, revolute axes as dash-dot lines or circles seen end "
        "on, sliders as boxes"
    )
    caption += "; the screws of the findings as coloured axes with their pitch." if screws else "."
    if view.why:
        caption += f" {view.name[:1].upper()}{view.name[1:]} because the mechanism is {view.why}."
    return fig, caption


def _configurations(r: Report) -> list[doc.Block]:
    mech = r.mechanism
    view = choose_sphere_view(mech) if spherical_centre(mech) is not None else choose_view(mech)
    out: list[doc.Block] = [doc.Heading(2, "Configurations")]
    for c in r.analysis.configurations:
        out.append(doc.Heading(3, f"Configuration {c.name}"))
        if c.error is not None:
            out.append(doc.Paragraph(f"not analysed: {c.error}"))
            continue
        screws = _screws(mech, c)
        fig, caption = _sketch(r, c, view, screws)
        out.append(
            doc.Figure(
                f"config-{doc.slug(c.name)}",
                svg(fig),
                f"sketch of {mech.name} at {c.name}",
                caption,
            )
        )
        L = r.analysis.length_scale
        items = [f"joint values (m, rad): {joint_values_text(c, L)}"]
        if c.closure_residual is not None:
            res = floored(c.closure_residual, display_floor(c.precision, L))
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
                    f"{explain(s)}. {verb.capitalize()} in {s.precision}; margin: {_margin(s.margin)}.",
                    f"{s.cls}:",
                )
            )
    return out


def _start(r: Report) -> tuple[float, float] | None:
    """The start of a grid sweep in the file's units (None when it is not known here)."""
    sw = r.sweep
    assert sw is not None
    start = next((c for c in r.analysis.configurations if c.name == sw.from_config), None)
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


def _sweep(r: Report) -> list[doc.Block]:
    sw = r.sweep
    assert sw is not None
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
            _start(r),
        )
        out.append(
            doc.Figure(
                "sweep",
                svg(fig),
                f"singularity loci over {vx.name} and {vy.name}",
                "The singularity loci over the two swept variables, coloured by the class "
                "found at their points (dots: the located points); grey: samples not reached "
                "on the start's assembly mode; star: the start.",
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


def _how(r: Report) -> list[doc.Block]:
    t = r.analysis.precision.tolerances
    mode = str(r.analysis.precision)
    thresholds = (
        "exact ranks"
        if mode == "exact"
        else "rank thresholds tau_lo = {} and tau_hi = {} of the largest singular value".format(
            *t.shown()
        )
    )
    items = [
        f"mechsing {__version__}",
        f"command: {r.command}",
        f"precision: {mode} ({thresholds}); auto re-decides at mp:50 what float leaves open",
        f"characteristic length L = {r.analysis.length_scale:.6g} m (lengths are divided by it "
        "before ranks are decided)",
        f"file: {r.mechanism.path or r.mechanism.name}",
        f"time taken: {r.seconds:.2f} s",
    ]
    return [doc.Heading(2, "How it was computed"), doc.Bullets(tuple(items))]


def _blocks(r: Report) -> list[doc.Block]:
    mech = r.mechanism
    out: list[doc.Block] = [
        doc.Heading(1, f"Design review: {mech.name}"),
        doc.Paragraph(
            f"Singularities of {mech.name} ({mech.path or 'built in Python'}) at "
            f"{len(r.analysis.configurations)} configuration(s)"
            + (", with a sweep." if r.sweep is not None else ".")
        ),
    ]
    out += _verdict(r)
    out += _mechanism(r)
    out += _configurations(r)
    if r.sweep is not None:
        out += _sweep(r)
    if r.modes is not None:
        from mechsing.report.modes_section import modes_blocks

        out += modes_blocks(mech, r.modes, r.analysis.length_scale)
    out += _how(r)
    return out
