"""The design review's mechanism section (:func:`mechanism_section`): the joints table,
the graph drawing, each loop's subgroup in words, the mobility numbers with why they
differ, the legs and the output's motion; and the words it shows them in
(:func:`subgroup_summary`, :func:`loop_meaning`, :func:`mobility_sentences`,
:func:`motion_words`)."""

from __future__ import annotations

from collections.abc import Sequence

from mechsing.analysis import AnalysisResult
from mechsing.analysis.contract import subgroup_params
from mechsing.analysis.describe import OutputMotion
from mechsing.analysis.results import Mobility
from mechsing.analysis.words import margin_text, twist_words
from mechsing.model.couplings import coupling_source, describe_coupling
from mechsing.numeric import to_float
from mechsing.reports import document as doc
from mechsing.reports.figures import graph_figure, svg
from mechsing.reports.render import scene_line
from mechsing.subgroups import Subgroup, load_catalog

__all__ = [
    "loop_meaning",
    "mechanism_section",
    "mobility_sentences",
    "motion_words",
    "subgroup_summary",
]


#: display only: a component below this fraction of a vector's largest is shown as 0
#: (rounding noise of a computed direction, e.g. 1e-17 beside 1); nothing is decided by it
DISPLAY_ZERO = 1e-12


def _vec(v: Sequence[float]) -> str:
    big = max((abs(x) for x in v), default=0.0)
    return "(" + ", ".join(f"{x if abs(x) > DISPLAY_ZERO * big else 0.0:.4g}" for x in v) + ")"


def subgroup_summary(sg: Subgroup | None) -> str:
    """A subgroup in one line: its symbol, catalog name, dimension and parameters (SI
    numbers; the phrase with named directions is :func:`mechsing.analysis.words.subgroup_words`)."""
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
        return f"this loop moves inside {subgroup_summary(sg)}: it imposes {sg.dim} constraints"
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


def mechanism_section(analysis: AnalysisResult) -> list[doc.Block]:
    """The mechanism: joints, graph, loops in words, mobility, legs and output motion."""
    mech = analysis.mechanism
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
    first = next((c for c in analysis.configurations if c.error is None), None)
    if first is not None and first.loops:
        out.append(doc.Heading(3, "Loops"))
        out.append(
            doc.Bullets(
                tuple(
                    f"loop {k + 1} ({'-'.join(lp.joints)}): {loop_meaning(lp.subgroup)}; "
                    f"generated subgroup {subgroup_summary(lp.subgroup)}"
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
    out += _legs_and_motion(analysis)
    if first is not None and first.mobility is not None:
        out.append(doc.Heading(3, "Mobility"))
        out.append(
            doc.Table(
                ("number", "value", "what it counts and why it differs"),
                tuple(mobility_sentences(first.mobility)),
                caption=f"At configuration {first.name}",
            )
        )
    if analysis.properties:
        out.append(doc.Bullets(tuple(f"{p.kind}: {p.explanation}" for p in analysis.properties)))
    return out


def motion_words(m: OutputMotion) -> str:
    """The output's twist space in words: its subgroup (type, name, parameters), its
    instantaneous screw when it is one twist, or what its twists span when they span no
    subgroup."""
    if m.dim is None:
        return f"undecided at {m.precision}"
    if m.instantaneous_screw and m.subgroup is not None:
        return f"instantaneous screw {subgroup_summary(m.subgroup)}"
    if m.is_subgroup and m.subgroup is not None:
        return subgroup_summary(m.subgroup)
    if m.is_subgroup is False:
        return f"not a subgroup: {m.dim} independent twists whose brackets leave their span"
    return f"dimension {m.dim} ({m.note or 'type not identified'})"


def _legs_and_motion(analysis: AnalysisResult) -> list[doc.Block]:
    out: list[doc.Block] = []
    a = analysis
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
                f"instantaneous screw {subgroup_summary(m.subgroup)} (decided in {m.precision}; "
                f"margin: {margin_text(m.margin)}). An instantaneous screw is not a motion type "
                "(a subgroup the output's motions stay in): it can change as the mechanism moves."
            )
        )
    elif m is not None:
        out.append(doc.Heading(3, "Output motion type"))
        out.append(
            doc.Paragraph(
                f"The twists of {m.body} relative to {m.relative_to} span "
                f"{motion_words(m)}: its motion type at the regular configuration "
                f"{m.configuration} (decided in {m.precision}; margin: {margin_text(m.margin)})."
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
